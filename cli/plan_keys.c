/* `qorient plan` for keyframe profiles: reads keyframes, plans with qorient/spline.h and
 * prints samples at a fixed rate. Velocity/acceleration/jerk-limited profiles (trapezoid,
 * scurve) belong to the motion planner; the command dispatcher routes them there. */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/spline.h"

/* Columns of one input line are t plus up to this many numbers: a CLI limit only (the
 * library has no maximum). */
#define PLAN_MAX_FIELDS 3072

static const char plan_usage[] =
    "usage: qorient plan [OPTIONS] [FILE|-]\n"
    "\n"
    "Plans a multi-joint trajectory through keyframes and prints it sampled at a fixed rate.\n"
    "\n"
    "Input (FILE, or standard input when FILE is '-' or absent): one keyframe per line,\n"
    "  t,p1,...,pN      t = time in seconds when the keyframe is reached (strictly increasing),\n"
    "                   p = joint positions in your unit; numbers separated by commas and/or\n"
    "                   blanks; blank lines and lines starting with '#' are ignored. Every line\n"
    "                   must have the same number of columns (see --columns).\n"
    "Output: one line per sample, 't,p1..pN,v1..vN,a1..aN' (position, velocity in units/s,\n"
    "  acceleration in units/s^2), at t = t_first + i/rate up to the last key time, plus a\n"
    "  last sample at exactly the last key time when the rate does not land on it. Before\n"
    "  the first and after the last key a trajectory is at rest; at the last key it reports\n"
    "  the end velocity/acceleration of the last segment.\n"
    "\n"
    "Options:\n"
    "  --profile NAME   linear   straight lines between keys (velocity steps at keys)\n"
    "                   cubic    cubic Hermite through keys with given velocities\n"
    "                            (needs --columns pv)\n"
    "                   catmull  cubic with Catmull-Rom (time-weighted) tangents, C1\n"
    "                   spline   interpolating C2 cubic spline (default)\n"
    "                   quintic  quintic segments, C2; velocities/accelerations from the\n"
    "                            input (--columns pv|pva) or estimated (--derivs)\n"
    "                   trapezoid|scurve are the velocity/acceleration/jerk-limited moves of\n"
    "                   the motion planner and take --vmax/--amax/--jmax/--sync\n"
    "                   (their options: qorient plan --profile scurve --help).\n"
    "  --rate HZ        samples per second, > 0 (default 100)\n"
    "  --end rest|natural\n"
    "                   ends of catmull/spline/quintic: rest = zero velocity (and for quintic\n"
    "                   zero acceleration) at the first and last key (default); natural =\n"
    "                   zero acceleration there\n"
    "  --columns p|pv|pva\n"
    "                   what follows t on each line: positions (default; pv for cubic),\n"
    "                   positions and velocities, or positions, velocities, accelerations\n"
    "                   (pv and pva: quintic and cubic only)\n"
    "  --derivs estimated|zero\n"
    "                   quintic: key velocities/accelerations not in the input are estimated\n"
    "                   (default) or zero (stop at every key)\n"
    "  --min P[,P...]   lower position limits: one value for all joints or one per joint;\n"
    "  --max P[,P...]   upper limits likewise. Samples are clamped (velocity and acceleration\n"
    "                   of a clamped joint are 0) and a note on standard error counts them.\n"
    "  --wrap J[,J...]  continuous joints, 1-based: each step between keys takes the short way\n"
    "                   round (period 2 pi, or 360 with --degrees); output in\n"
    "                   (-period/2, period/2]\n"
    "  --unwrapped      print continuous joints unwrapped (continuing from the first key)\n"
    "  --degrees        positions are degrees: the wrap period is 360\n"
    "  --fixed          sample with the fixed-point (Q16.16) sampler instead of float32\n"
    "                   (times and values must fit in +-32768; each sample is taken at the\n"
    "                   nearest Q16.16 time, within 7.7 us of the printed time)\n"
    "  --vmax V,...  --amax A,...  --jmax J,...  --sync MODE\n"
    "                   limits of the trapezoid|scurve profiles only: given with a keyframe\n"
    "                   profile they are an error (keyframe timing comes from the input).\n"
    "  -h, --help       this text\n"
    "\n"
    "Exit status: 0 ok; 1 bad input (the message on standard error names the line) or the\n"
    "plan failed; 2 usage error.\n";

enum { OPT_PROFILE = 256, OPT_RATE, OPT_END, OPT_COLUMNS, OPT_DERIVS, OPT_MIN, OPT_MAX, OPT_WRAP,
       OPT_UNWRAPPED, OPT_DEGREES, OPT_FIXED, OPT_VMAX, OPT_AMAX, OPT_JMAX, OPT_SYNC };

static const struct option plan_opts[] = {
    { "profile", required_argument, NULL, OPT_PROFILE },
    { "rate", required_argument, NULL, OPT_RATE },
    { "end", required_argument, NULL, OPT_END },
    { "columns", required_argument, NULL, OPT_COLUMNS },
    { "derivs", required_argument, NULL, OPT_DERIVS },
    { "min", required_argument, NULL, OPT_MIN },
    { "max", required_argument, NULL, OPT_MAX },
    { "wrap", required_argument, NULL, OPT_WRAP },
    { "unwrapped", no_argument, NULL, OPT_UNWRAPPED },
    { "degrees", no_argument, NULL, OPT_DEGREES },
    { "fixed", no_argument, NULL, OPT_FIXED },
    { "vmax", required_argument, NULL, OPT_VMAX },
    { "amax", required_argument, NULL, OPT_AMAX },
    { "jmax", required_argument, NULL, OPT_JMAX },
    { "sync", required_argument, NULL, OPT_SYNC },
    { "help", no_argument, NULL, 'h' },
    { NULL, 0, NULL, 0 }
};

/* Parses a comma/blank separated list of numbers into a new array. Returns its count, or
 * -1 when a field is not a finite number. */
static long parse_list(const char *arg, double **out)
{
    size_t n = 0, i;
    char *copy = strdup(arg);
    double *v = malloc(PLAN_MAX_FIELDS * sizeof *v);
    *out = NULL;
    if (copy == NULL || v == NULL || qo_cli_parse_numbers(copy, v, PLAN_MAX_FIELDS, &n) != 0 ||
        n == 0) {
        free(copy);
        free(v);
        return -1;
    }
    for (i = 0; i < n; i++)
        if (!isfinite(v[i])) {
            free(copy);
            free(v);
            return -1;
        }
    free(copy);
    *out = v;
    return (long)n;
}

struct plan_cfg {
    qo_spline_profile profile;
    double rate;
    qo_spline_end end;
    int columns; /* 1 p, 2 pv, 3 pva; 0 = profile default */
    qo_spline_derivs derivs;
    const char *min_arg, *max_arg, *wrap_arg;
    int unwrapped, degrees, fixed;
    const char *motion_opt; /* first of --vmax/--amax/--jmax/--sync given */
};

/* Keyframes as read: K rows of t + cols numbers, float. */
struct plan_keys {
    size_t n_keys, cap, cols;
    float *t, *vals;
    double t_first, t_last; /* as read, for printing the sample times */
};

static int push_key(struct plan_keys *ks, double td, const double *v)
{
    size_t i;
    float t = (float)td;
    if (ks->n_keys == ks->cap) {
        size_t nc = ks->cap ? 2 * ks->cap : 64;
        float *nt = realloc(ks->t, nc * sizeof *nt);
        float *nv;
        if (nt == NULL) return -1;
        ks->t = nt;
        nv = realloc(ks->vals, nc * ks->cols * sizeof *nv);
        if (nv == NULL) return -1;
        ks->vals = nv;
        ks->cap = nc;
    }
    ks->t[ks->n_keys] = t;
    if (ks->n_keys == 0) ks->t_first = td;
    ks->t_last = td;
    for (i = 0; i < ks->cols; i++) ks->vals[ks->n_keys * ks->cols + i] = (float)v[i];
    ks->n_keys++;
    return 0;
}

/* Reads all keyframes; on a bad line prints the message naming it and returns 1. */
static int read_keys(FILE *in, const char *name, int per_joint, struct plan_keys *ks)
{
    char *line = NULL;
    size_t cap = 0, n;
    long lineno = 0, first_line = 0, prev_line = 0;
    double *v = malloc((PLAN_MAX_FIELDS + 1) * sizeof *v);
    int rc = 0;
    if (v == NULL) {
        fprintf(stderr, "qorient plan: out of memory\n");
        return 1;
    }
    while (qo_cli_getline(&line, &cap, in) >= 0) {
        int pr;
        size_t i;
        float tf;
        lineno++;
        pr = qo_cli_parse_numbers(line, v, PLAN_MAX_FIELDS + 1, &n);
        if (pr == -2) {
            fprintf(stderr, "qorient plan: %s: line %ld: more than %d columns\n", name, lineno,
                    PLAN_MAX_FIELDS + 1);
            rc = 1;
            break;
        }
        if (pr != 0) {
            fprintf(stderr, "qorient plan: %s: line %ld: not a number: '%s'\n", name, lineno, line);
            rc = 1;
            break;
        }
        if (n == 0) continue;
        for (i = 0; i < n; i++)
            if (!isfinite(v[i]) || !isfinite((float)v[i])) break;
        if (i < n) {
            fprintf(stderr, "qorient plan: %s: line %ld: column %zu is not a finite float number\n",
                    name, lineno, i + 1);
            rc = 1;
            break;
        }
        if (first_line == 0) {
            if (n < 2 || (n - 1) % (size_t)per_joint != 0) {
                fprintf(stderr,
                        "qorient plan: %s: line %ld: %zu columns: expected t and %d number(s) "
                        "per joint\n",
                        name, lineno, n, per_joint);
                rc = 1;
                break;
            }
            first_line = lineno;
            ks->cols = n - 1;
        } else if (n - 1 != ks->cols) {
            fprintf(stderr,
                    "qorient plan: %s: line %ld: %zu columns, expected %zu as on line %ld\n", name,
                    lineno, n, ks->cols + 1, first_line);
            rc = 1;
            break;
        }
        tf = (float)v[0];
        if (ks->n_keys > 0 && !(tf > ks->t[ks->n_keys - 1])) {
            fprintf(stderr,
                    "qorient plan: %s: line %ld: time %.9g is not after the previous "
                    "keyframe's %.9g "
                    "(line %ld): times must increase strictly\n",
                    name, lineno, v[0], (double)ks->t[ks->n_keys - 1], prev_line);
            rc = 1;
            break;
        }
        if (push_key(ks, v[0], v + 1) != 0) {
            fprintf(stderr, "qorient plan: out of memory\n");
            rc = 1;
            break;
        }
        prev_line = lineno;
    }
    free(line);
    free(v);
    if (rc == 0 && ks->n_keys < 2) {
        fprintf(stderr, "qorient plan: %s: need at least 2 keyframes, got %zu\n", name, ks->n_keys);
        rc = 1;
    }
    return rc;
}

/* Limits from --min/--max: one value for all joints or one per joint. Returns 0 or 2. */
static int make_limits(const char *arg, const char *opt, size_t nj, float **out)
{
    double *v;
    long n;
    size_t j;
    *out = NULL;
    if (arg == NULL) return 0;
    n = parse_list(arg, &v);
    if (n < 0) {
        fprintf(stderr, "qorient plan: %s: '%s' is not a list of finite numbers\n", opt, arg);
        return 2;
    }
    if ((size_t)n != 1 && (size_t)n != nj) {
        fprintf(stderr, "qorient plan: %s: %ld values for %zu joints (give 1 or %zu)\n", opt, n,
                nj, nj);
        free(v);
        return 2;
    }
    *out = malloc(nj * sizeof **out);
    if (*out == NULL) {
        free(v);
        return 2;
    }
    for (j = 0; j < nj; j++) (*out)[j] = (float)v[n == 1 ? 0 : j];
    free(v);
    return 0;
}

static int make_wrap(const char *arg, size_t nj, unsigned char **out)
{
    double *v;
    long n, i;
    *out = NULL;
    if (arg == NULL) return 0;
    n = parse_list(arg, &v);
    if (n < 0) {
        fprintf(stderr, "qorient plan: --wrap: '%s' is not a list of joint numbers\n", arg);
        return 2;
    }
    *out = calloc(nj, 1);
    if (*out == NULL) {
        free(v);
        return 2;
    }
    for (i = 0; i < n; i++) {
        if (v[i] != floor(v[i]) || v[i] < 1 || v[i] > (double)nj) {
            fprintf(stderr, "qorient plan: --wrap: joint %g is not in 1..%zu\n", v[i], nj);
            free(v);
            return 2;
        }
        (*out)[(size_t)v[i] - 1] = 1;
    }
    free(v);
    return 0;
}

/* The time column is the nominal sample time t_first + i/rate (printed with %.9g, so a
 * 100 Hz stream reads 0.01, not the float32 0.00999999978 it was sampled at). */
static void print_time(double t)
{
    if (t == 0.0) t = 0.0;
    printf("%.9g", t);
}

static void print_row_f32(double t, size_t nj, const float *p, const float *v, const float *a)
{
    size_t j;
    print_time(t);
    for (j = 0; j < nj; j++) { putchar(','); qo_cli_print_f32(stdout, p[j]); }
    for (j = 0; j < nj; j++) { putchar(','); qo_cli_print_f32(stdout, v[j]); }
    for (j = 0; j < nj; j++) { putchar(','); qo_cli_print_f32(stdout, a[j]); }
    putchar('\n');
}

static void print_q16(qo_q16 x)
{
    printf("%.10g", (double)x / 65536.0);
}

static void print_row_q16(double t, size_t nj, const qo_q16 *p, const qo_q16 *v, const qo_q16 *a)
{
    size_t j;
    print_time(t);
    for (j = 0; j < nj; j++) { putchar(','); print_q16(p[j]); }
    for (j = 0; j < nj; j++) { putchar(','); print_q16(v[j]); }
    for (j = 0; j < nj; j++) { putchar(','); print_q16(a[j]); }
    putchar('\n');
}

static int parse_opts(int argc, char **argv, struct plan_cfg *c, int *help)
{
    int o;
    c->profile = QO_SPLINE_CUBIC_C2;
    c->rate = 100.0;
    c->end = QO_SPLINE_END_CLAMPED;
    c->columns = 0;
    c->derivs = QO_SPLINE_DERIVS_ESTIMATED;
    c->min_arg = c->max_arg = c->wrap_arg = NULL;
    c->unwrapped = c->degrees = c->fixed = 0;
    c->motion_opt = NULL;
    *help = 0;
    while ((o = getopt_long(argc, argv, "h", plan_opts, NULL)) != -1) {
        switch (o) {
        case OPT_PROFILE:
            if (strcmp(optarg, "linear") == 0) c->profile = QO_SPLINE_LINEAR;
            else if (strcmp(optarg, "cubic") == 0) c->profile = QO_SPLINE_CUBIC_HERMITE;
            else if (strcmp(optarg, "catmull") == 0) c->profile = QO_SPLINE_CATMULL_ROM;
            else if (strcmp(optarg, "spline") == 0) c->profile = QO_SPLINE_CUBIC_C2;
            else if (strcmp(optarg, "quintic") == 0) c->profile = QO_SPLINE_QUINTIC;
            else if (strcmp(optarg, "trapezoid") == 0 || strcmp(optarg, "scurve") == 0) {
                fprintf(stderr, "qorient plan: --profile %s is a velocity/acceleration-limited "
                        "move of "
                        "the motion planner, not a keyframe profile\n", optarg);
                return 2;
            } else {
                fprintf(stderr, "qorient plan: --profile: unknown profile '%s'\n", optarg);
                return 2;
            }
            break;
        case OPT_RATE: {
            char *end;
            errno = 0;
            c->rate = strtod(optarg, &end);
            if (end == optarg || *end != '\0' || !isfinite(c->rate) || !(c->rate > 0.0)) {
                fprintf(stderr, "qorient plan: --rate: '%s' is not a positive number of Hz\n",
                        optarg);
                return 2;
            }
            break;
        }
        case OPT_END:
            if (strcmp(optarg, "rest") == 0) c->end = QO_SPLINE_END_CLAMPED;
            else if (strcmp(optarg, "natural") == 0) c->end = QO_SPLINE_END_NATURAL;
            else {
                fprintf(stderr, "qorient plan: --end: '%s' is not rest or natural\n", optarg);
                return 2;
            }
            break;
        case OPT_COLUMNS:
            if (strcmp(optarg, "p") == 0) c->columns = 1;
            else if (strcmp(optarg, "pv") == 0) c->columns = 2;
            else if (strcmp(optarg, "pva") == 0) c->columns = 3;
            else {
                fprintf(stderr, "qorient plan: --columns: '%s' is not p, pv or pva\n", optarg);
                return 2;
            }
            break;
        case OPT_DERIVS:
            if (strcmp(optarg, "estimated") == 0) c->derivs = QO_SPLINE_DERIVS_ESTIMATED;
            else if (strcmp(optarg, "zero") == 0) c->derivs = QO_SPLINE_DERIVS_ZERO;
            else {
                fprintf(stderr, "qorient plan: --derivs: '%s' is not estimated or zero\n", optarg);
                return 2;
            }
            break;
        case OPT_MIN: c->min_arg = optarg; break;
        case OPT_MAX: c->max_arg = optarg; break;
        case OPT_WRAP: c->wrap_arg = optarg; break;
        case OPT_UNWRAPPED: c->unwrapped = 1; break;
        case OPT_DEGREES: c->degrees = 1; break;
        case OPT_FIXED: c->fixed = 1; break;
        case OPT_VMAX: if (!c->motion_opt) c->motion_opt = "--vmax"; break;
        case OPT_AMAX: if (!c->motion_opt) c->motion_opt = "--amax"; break;
        case OPT_JMAX: if (!c->motion_opt) c->motion_opt = "--jmax"; break;
        case OPT_SYNC: if (!c->motion_opt) c->motion_opt = "--sync"; break;
        case 'h': *help = 1; return 0;
        default:
            fputs("qorient plan: see 'qorient plan --help'\n", stderr);
            return 2;
        }
    }
    if (c->motion_opt) {
        fprintf(stderr, "qorient plan: %s applies to --profile trapezoid|scurve only; keyframe "
                "profiles take their timing from the keyframes\n", c->motion_opt);
        return 2;
    }
    if (c->columns == 0) c->columns = c->profile == QO_SPLINE_CUBIC_HERMITE ? 2 : 1;
    if (c->profile == QO_SPLINE_CUBIC_HERMITE && c->columns < 2) {
        fputs("qorient plan: --profile cubic needs key velocities: --columns pv\n", stderr);
        return 2;
    }
    if (c->columns > 1 && c->profile != QO_SPLINE_CUBIC_HERMITE &&
        c->profile != QO_SPLINE_QUINTIC) {
        fputs("qorient plan: --columns pv|pva only with --profile cubic or quintic\n", stderr);
        return 2;
    }
    return 0;
}

/* Samples and prints; returns the exit status. */
static int run_plan(const struct plan_cfg *c, const struct plan_keys *ks, size_t nj,
                    const qo_spline_settings_f32 *set, const float *pos_keys)
{
    size_t need = qo_spline_coef_len(nj, ks->n_keys), j;
    float *coef = need ? malloc(need * sizeof *coef) : NULL;
    float *p = malloc(3 * nj * sizeof *p);
    int8_t *cl = malloc(nj);
    unsigned long *ncl = calloc(nj, sizeof *ncl);
    int32_t *table = NULL;
    qo_q16 *pq = malloc(3 * nj * sizeof *pq);
    qo_spline_f32 sp;
    qo_spline_q16 fx;
    qo_status st;
    double t0 = ks->t_first, tl = ks->t_last, span_n, i;
    int rc = 0, overflow = 0;
    if (coef == NULL || p == NULL || cl == NULL || ncl == NULL || pq == NULL) {
        fputs("qorient plan: out of memory\n", stderr);
        rc = 1;
        goto out;
    }
    st = qo_spline_init_f32(nj, ks->n_keys, ks->t, pos_keys, set, coef, need, &sp);
    if (st != QO_OK) {
        fprintf(stderr, "qorient plan: error: %s\n", qo_status_str(st));
        rc = 1;
        goto out;
    }
    if (c->fixed) {
        size_t tn = qo_spline_q16_len(nj, ks->n_keys);
        table = tn ? malloc(tn * sizeof *table) : NULL;
        st = table ? qo_spline_to_q16_f32(&sp, table, tn, &fx) : QO_E_CAPACITY;
        if (st != QO_OK) {
            fprintf(stderr, "qorient plan: --fixed: error: %s\n", qo_status_str(st));
            rc = 1;
            goto out;
        }
    }
    span_n = floor((tl - t0) * c->rate + 1e-9);
    if (span_n > 1e9) {
        fprintf(stderr, "qorient plan: %.0f samples: lower --rate\n", span_n + 1);
        rc = 1;
        goto out;
    }
    for (i = 0; i <= span_n + 1; i++) {
        double t = (i <= span_n) ? t0 + i / c->rate : tl;
        if (i > span_n && (float)(t0 + span_n / c->rate) >= (float)tl) break; /* landed on it */
        if (t > tl) t = tl;
        if (c->fixed) {
            qo_q16 tq = (qo_q16)lrint(t * 65536.0);
            st = qo_spline_sample_q16(&fx, tq, pq, pq + nj, pq + 2 * nj, cl);
            if (st == QO_E_OVERFLOW) overflow++;
            print_row_q16(t, nj, pq, pq + nj, pq + 2 * nj);
        } else {
            qo_spline_sample_f32(&sp, (float)t, p, p + nj, p + 2 * nj, cl);
            print_row_f32(t, nj, p, p + nj, p + 2 * nj);
        }
        for (j = 0; j < nj; j++) ncl[j] += cl[j] != 0;
    }
    for (j = 0; j < nj; j++)
        if (ncl[j])
            fprintf(stderr,
                    "qorient plan: note: joint %zu clamped to its limits in %lu sample(s)\n",
                    j + 1, ncl[j]);
    if (overflow) {
        fprintf(stderr, "qorient plan: --fixed: %d sample(s) saturated Q16.16\n", overflow);
        rc = 1;
    }
out:
    free(coef);
    free(p);
    free(cl);
    free(ncl);
    free(table);
    free(pq);
    return rc;
}

int qo_cli_plan_keys(int argc, char **argv)
{
    struct plan_cfg c;
    struct plan_keys ks = { 0, 0, 0, NULL, NULL, 0.0, 0.0 };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    float *lo = NULL, *hi = NULL, *pk = NULL, *vk = NULL, *ak = NULL;
    unsigned char *wrap = NULL;
    const char *name = "-";
    FILE *in = stdin;
    size_t nj, k, j;
    int help, rc;

    rc = parse_opts(argc, argv, &c, &help);
    if (rc) return rc;
    if (help) {
        fputs(plan_usage, stdout);
        return 0;
    }
    if (optind + 1 < argc) {
        fputs("qorient plan: at most one input file\n", stderr);
        return 2;
    }
    if (optind < argc && strcmp(argv[optind], "-") != 0) {
        name = argv[optind];
        in = fopen(name, "r");
        if (in == NULL) {
            fprintf(stderr, "qorient plan: %s: %s\n", name, strerror(errno));
            return 1;
        }
    }
    rc = read_keys(in, name, c.columns, &ks);
    if (in != stdin) fclose(in);
    if (rc) goto out;
    nj = ks.cols / (size_t)c.columns;
    rc = make_limits(c.min_arg, "--min", nj, &lo);
    if (rc == 0) rc = make_limits(c.max_arg, "--max", nj, &hi);
    if (rc == 0) rc = make_wrap(c.wrap_arg, nj, &wrap);
    if (rc) goto out;
    if (lo && hi)
        for (j = 0; j < nj; j++)
            if (lo[j] > hi[j]) {
                fprintf(stderr, "qorient plan: --min/--max: joint %zu: min %.9g > max %.9g\n",
                        j + 1, (double)lo[j], (double)hi[j]);
                rc = 2;
                goto out;
            }
    /* split the rows into positions / velocities / accelerations */
    pk = malloc(ks.n_keys * nj * sizeof *pk);
    vk = c.columns >= 2 ? malloc(ks.n_keys * nj * sizeof *vk) : NULL;
    ak = c.columns >= 3 ? malloc(ks.n_keys * nj * sizeof *ak) : NULL;
    if (pk == NULL || (c.columns >= 2 && vk == NULL) || (c.columns >= 3 && ak == NULL)) {
        fputs("qorient plan: out of memory\n", stderr);
        rc = 1;
        goto out;
    }
    for (k = 0; k < ks.n_keys; k++)
        for (j = 0; j < nj; j++) {
            const float *row = ks.vals + k * ks.cols;
            pk[k * nj + j] = row[j];
            if (vk) vk[k * nj + j] = row[nj + j];
            if (ak) ak[k * nj + j] = row[2 * nj + j];
        }
    set.profile = c.profile;
    set.end = c.end;
    set.derivs = c.derivs;
    set.key_vel = vk;
    set.key_acc = ak;
    set.pos_min = lo;
    set.pos_max = hi;
    set.wrap = wrap;
    set.wrap_period = c.degrees ? 360.0f : 6.28318530717958647692f;
    set.wrap_output = !c.unwrapped;
    rc = run_plan(&c, &ks, nj, &set, pk);
out:
    free(ks.t);
    free(ks.vals);
    free(lo);
    free(hi);
    free(wrap);
    free(pk);
    free(vk);
    free(ak);
    return rc;
}
