/*
 * qorient convert FROM TO [--degrees] [--fixed]
 * qorient slerp [--fixed]
 *
 * One rotation per input line, one per output line (text contract in DESIGN.md):
 *   quat       w x y z              (normalised on input; output canonical, w >= 0)
 *   matrix     m00 m01 m02 m10 ... m22  (row-major; must be a rotation within tolerance)
 *   rotvec     x y z                (axis * angle)
 *   axisangle  ax ay az angle       (axis need not be unit; output axis is unit, angle in [0,pi])
 *   euler:SEQ  a1 a2 a3             (scipy naming: xyz extrinsic, XYZ intrinsic); output adds
 *                                   a 4th column: 1 in the gimbal-lock band, else 0
 * Numbers are separated by blanks or commas. Empty lines and '#' comments are copied through
 * unchanged so output line N always answers input line N.
 */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/convert.h"
#include "qorient/euler.h"
#include "qorient/interp.h"
#include "qorient/quat.h"
#include "qorient/status.h"

static const double DEG = 3.14159265358979323846 / 180.0;

static int parse_rep(const char *s, struct rep_spec *r)
{
    r->seq = QO_EULER_xyz;
    if (strcmp(s, "quat") == 0) r->kind = REP_QUAT;
    else if (strcmp(s, "matrix") == 0) r->kind = REP_MATRIX;
    else if (strcmp(s, "rotvec") == 0) r->kind = REP_ROTVEC;
    else if (strcmp(s, "axisangle") == 0) r->kind = REP_AXISANGLE;
    else if (strncmp(s, "euler:", 6) == 0) {
        r->kind = REP_EULER;
        return qo_euler_seq_parse(s + 6, &r->seq) == QO_OK ? 0 : -1;
    } else return -1;
    return 0;
}

static size_t rep_count(enum rep k)
{
    switch (k) {
    case REP_QUAT: return 4;
    case REP_MATRIX: return 9;
    case REP_ROTVEC: return 3;
    case REP_AXISANGLE: return 4;
    case REP_EULER: return 3;
    }
    return 0;
}

/* Input numbers -> unit quaternion with the float32 core. */
static qo_status to_quat_f32(const struct rep_spec *r, const double *v, int degrees, qo_quat_f32 *q)
{
    float ang = degrees ? (float)DEG : 1.0f;
    switch (r->kind) {
    case REP_QUAT: {
        qo_quat_f32 in = { (float)v[0], (float)v[1], (float)v[2], (float)v[3] };
        return qo_quat_normalize_f32(in, q);
    }
    case REP_MATRIX: {
        qo_mat3_f32 m;
        int i;
        for (i = 0; i < 9; i++) m.m[i / 3][i % 3] = (float)v[i];
        return qo_mat3_to_quat_f32(&m, q);
    }
    case REP_ROTVEC: {
        qo_vec3_f32 rv = { (float)v[0] * ang, (float)v[1] * ang, (float)v[2] * ang };
        return qo_rotvec_to_quat_f32(rv, q);
    }
    case REP_AXISANGLE: {
        qo_vec3_f32 ax = { (float)v[0], (float)v[1], (float)v[2] };
        return qo_axis_angle_to_quat_f32(ax, (float)v[3] * ang, q);
    }
    case REP_EULER: {
        qo_euler_f32 e;
        e.a1 = (float)v[0] * ang; e.a2 = (float)v[1] * ang; e.a3 = (float)v[2] * ang;
        return qo_euler_to_quat_f32(r->seq, e, q);
    }
    }
    *q = qo_quat_identity_f32();
    return QO_E_ARG;
}

/* Unit quaternion -> output numbers with the float32 core; *n is the count written. */
static qo_status from_quat_f32(const struct rep_spec *r, qo_quat_f32 q, int degrees, double *o, size_t *n)
{
    double s = degrees ? 1.0 / DEG : 1.0;
    qo_status st = QO_OK;
    *n = 0;
    switch (r->kind) {
    case REP_QUAT:
        q = qo_quat_canonical_f32(q);
        o[0] = q.w; o[1] = q.x; o[2] = q.y; o[3] = q.z; *n = 4;
        break;
    case REP_MATRIX: {
        qo_mat3_f32 m;
        int i;
        st = qo_mat3_from_quat_f32(q, &m);
        for (i = 0; i < 9; i++) o[i] = m.m[i / 3][i % 3];
        *n = 9;
        break;
    }
    case REP_ROTVEC: {
        qo_vec3_f32 rv;
        st = qo_rotvec_from_quat_f32(q, &rv);
        o[0] = rv.x * s; o[1] = rv.y * s; o[2] = rv.z * s; *n = 3;
        break;
    }
    case REP_AXISANGLE: {
        qo_vec3_f32 ax;
        float a;
        st = qo_axis_angle_from_quat_f32(q, &ax, &a);
        o[0] = ax.x; o[1] = ax.y; o[2] = ax.z; o[3] = a * s; *n = 4;
        break;
    }
    case REP_EULER: {
        qo_euler_f32 e;
        qo_euler_info_f32 info;
        st = qo_euler_from_quat_f32(q, r->seq, &e, &info);
        o[0] = e.a1 * s; o[1] = e.a2 * s; o[2] = e.a3 * s; o[3] = info.locked ? 1.0 : 0.0;
        *n = 4;
        break;
    }
    }
    return st;
}

static void print_record(const double *o, size_t n, int last_is_flag)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (i) putchar(' ');
        if (last_is_flag && i + 1 == n) printf("%d", o[i] != 0.0);
        else qo_cli_print_f32(stdout, (float)o[i]);
    }
    putchar('\n');
}

static void line_error(const char *cmd, unsigned long lineno, const char *reason)
{
    printf("error: %s\n", reason);
    fprintf(stderr, "qorient %s: line %lu: %s\n", cmd, lineno, reason);
}

/* Reads lines, calls fn on each record of `want` numbers. Returns the exit status. */
typedef const char *(*record_fn)(const double *v, void *ctx);

static int for_each_record(const char *cmd, size_t want, record_fn fn, void *ctx)
{
    char *buf = NULL;
    size_t cap = 0;
    unsigned long lineno = 0;
    int failed = 0;
    double v[16];
    char msg[QO_CLI_REASON_CAP];
    long len = -1;
    /* A filter: one line in memory at a time (at most QO_CLI_LINE_MAX characters), so the
     * input needs no bound on its length. */
    while ((len = qo_cli_getline(&buf, &cap, stdin, NULL)) >= 0) {
        size_t n;
        int rc;
        struct qo_cli_field bad;
        const char *p = buf;
        lineno++;
        if (strlen(buf) != (size_t)len) {
            /* a NUL would end the record early: "1 0 0 0\0 2 3" is not the quaternion 1 0 0 0 */
            line_error(cmd, lineno, "contains a NUL byte");
            failed = 1;
            continue;
        }
        while (*p == ' ' || *p == '\t') p++;
        if (*p == '\0' || *p == '#') {
            puts(buf); /* keep line N of output answering line N of input */
            continue;
        }
        rc = qo_cli_parse_fields(buf, v, sizeof v / sizeof v[0], &n, &bad);
        if (rc != 0 && rc != QO_CLI_NUM_MANY) {
            line_error(cmd, lineno, qo_cli_field_reason(rc, &bad, "column", msg, sizeof msg));
            failed = 1;
            continue;
        }
        if (rc == QO_CLI_NUM_MANY || n != want) {
            snprintf(msg, sizeof msg, "expected %zu numbers, got %s%zu", want, rc == QO_CLI_NUM_MANY ? "more than " : "", n);
            line_error(cmd, lineno, msg);
            failed = 1;
            continue;
        }
        {
            const char *err = fn(v, ctx);
            if (err) {
                line_error(cmd, lineno, err);
                failed = 1;
            }
        }
    }
    if (len < -1) {
        /* an endless line (/dev/zero): said in its place, and nothing after it is read */
        line_error(cmd, lineno + 1, qo_cli_line_problem(len));
        failed = 1;
    } else if (ferror(stdin)) {
        /* a directory fails with EISDIR: not an empty input */
        fprintf(stderr, "qorient %s: -: read error: %s\n", cmd, strerror(errno));
        failed = 1;
    }
    free(buf);
    return failed;
}

/* The --fixed paths take the inputs the float32 core sees (rounded to float32: what rounds to
 * zero in float32, 1e-320, is zero here too), so both refuse and accept the same records;
 * the parser has refused what float32 cannot hold (1e39). */
static void as_float32(const double *v, size_t m, double *w)
{
    size_t i;
    for (i = 0; i < m; i++) w[i] = (double)(float)v[i];
}

struct convert_ctx {
    struct rep_spec from, to;
    int degrees, fixed;
};

static const char *convert_one(const double *v, void *vctx)
{
    const struct convert_ctx *c = vctx;
    double o[9];
    size_t n;
    qo_status st;
    if (c->fixed) {
        double w[16];
        size_t m = c->from.kind == REP_MATRIX ? 9 : c->from.kind == REP_QUAT || c->from.kind == REP_AXISANGLE ? 4 : 3;
        as_float32(v, m, w);
        st = qo_cli_convert_fixed(&c->from, &c->to, w, c->degrees, o, &n);
    } else {
        qo_quat_f32 q;
        st = to_quat_f32(&c->from, v, c->degrees, &q);
        if (st == QO_OK) st = from_quat_f32(&c->to, q, c->degrees, o, &n);
    }
    if (st != QO_OK) return qo_status_str(st);
    print_record(o, n, c->to.kind == REP_EULER);
    return NULL;
}

static void convert_usage(FILE *f)
{
    fputs("usage: qorient convert FROM TO [--degrees] [--fixed]\n"
          "\n"
          "Reads one rotation per line from standard input and writes it converted, one per line.\n"
          "FROM and TO are one of:\n"
          "  quat        w x y z             scalar first, Hamilton; normalised on input,\n"
          "                                  written canonical (w >= 0)\n"
          "  matrix      m00 m01 m02 m10 m11 m12 m20 m21 m22   row-major, must be a rotation\n"
          "  rotvec      x y z               rotation vector: unit axis times angle\n"
          "  axisangle   ax ay az angle      axis need not be unit; written unit, angle in [0,pi]\n"
          "  euler:SEQ   a1 a2 a3            SEQ as in scipy: lowercase extrinsic (xyz, zyz...),\n"
          "                                  uppercase intrinsic (XYZ, ZYX...); 12 sequences each.\n"
          "                                  Output adds a 4th column: 1 in the gimbal-lock band.\n"
          "Numbers are separated by blanks or commas; empty and '#' lines are copied through.\n"
          "\n"
          "options:\n"
          "  -d, --degrees   angles (rotvec, axisangle, euler) in degrees instead of radians\n"
          "  -f, --fixed     compute with the fixed-point core (inputs converted at the boundary)\n"
          "  -h, --help      this text\n"
          "\n"
          "A line that cannot be read or converted prints 'error: REASON' in its place and a\n"
          "message naming the line on standard error; the exit status is then 1.\n"
          "\n"
          "example:\n"
          "  echo '0 0 1 90' | qorient convert axisangle euler:ZYX --degrees\n"
          "  90 0 0 0\n", f);
}

int qo_cli_convert(int argc, char **argv)
{
    static const struct option opts[] = {
        { "degrees", no_argument, NULL, 'd' },
        { "fixed", no_argument, NULL, 'f' },
        { "help", no_argument, NULL, 'h' },
        { NULL, 0, NULL, 0 },
    };
    struct convert_ctx c;
    int ch;
    memset(&c, 0, sizeof c);
    while ((ch = getopt_long(argc, argv, "dfh", opts, NULL)) != -1) {
        switch (ch) {
        case 'd': c.degrees = 1; break;
        case 'f': c.fixed = 1; break;
        case 'h': convert_usage(stdout); return 0;
        default: convert_usage(stderr); return 2;
        }
    }
    if (argc - optind != 2) {
        fprintf(stderr, "qorient convert: need FROM and TO\n");
        convert_usage(stderr);
        return 2;
    }
    for (ch = 0; ch < 2; ch++)
        if (parse_rep(argv[optind + ch], ch ? &c.to : &c.from) != 0) {
            fprintf(stderr, "qorient convert: unknown representation %s\n", QO_CLI_QUOTED(argv[optind + ch]));
            return 2;
        }
    return for_each_record("convert", rep_count(c.from.kind), convert_one, &c);
}

static const char *slerp_one(const double *v, void *vctx)
{
    const int *fixed = vctx;
    double o[4];
    qo_status st;
    if (*fixed) {
        double w[9];
        as_float32(v, 9, w);
        st = qo_cli_slerp_fixed(w, o);
    } else {
        qo_quat_f32 a = { (float)v[0], (float)v[1], (float)v[2], (float)v[3] };
        qo_quat_f32 b = { (float)v[4], (float)v[5], (float)v[6], (float)v[7] };
        qo_quat_f32 q;
        st = qo_interp_slerp_f32(a, b, (float)v[8], &q);
        o[0] = q.w; o[1] = q.x; o[2] = q.y; o[3] = q.z;
    }
    if (st != QO_OK) return qo_status_str(st);
    print_record(o, 4, 0);
    return NULL;
}

static void slerp_usage(FILE *f)
{
    fputs("usage: qorient slerp [--fixed]\n"
          "\n"
          "Each input line 'w0 x0 y0 z0 w1 x1 y1 z1 t' gives 'w x y z': the spherical linear\n"
          "interpolation from q0 (t = 0) to q1 (t = 1), the short way round, at constant angular\n"
          "rate. Inputs are normalised; t must be in [0, 1]. The result is not canonicalised: at\n"
          "t = 1 it is q1 or -q1, whichever is nearer q0.\n"
          "\n"
          "options:\n"
          "  -f, --fixed     compute with the fixed-point core\n"
          "  -h, --help      this text\n"
          "\n"
          "A line that cannot be read or interpolated prints 'error: REASON' in its place and a\n"
          "message naming the line on standard error; the exit status is then 1.\n", f);
}

int qo_cli_slerp(int argc, char **argv)
{
    static const struct option opts[] = {
        { "fixed", no_argument, NULL, 'f' },
        { "help", no_argument, NULL, 'h' },
        { NULL, 0, NULL, 0 },
    };
    int ch, fixed = 0;
    while ((ch = getopt_long(argc, argv, "fh", opts, NULL)) != -1) {
        switch (ch) {
        case 'f': fixed = 1; break;
        case 'h': slerp_usage(stdout); return 0;
        default: slerp_usage(stderr); return 2;
        }
    }
    if (optind != argc) {
        fprintf(stderr, "qorient slerp: unexpected argument %s\n", QO_CLI_QUOTED(argv[optind]));
        return 2;
    }
    return for_each_record("slerp", 9, slerp_one, &fixed);
}
