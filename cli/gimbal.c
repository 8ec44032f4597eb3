/*
 * qorient gimbal [OPTIONS] [FILE|-]
 * Reads quaternion keyframes `t,w,x,y,z`, interpolates them on the sphere and writes the
 * mechanism's joint angles `t,a1,a2,a3,margin,lock,clipped` at a fixed rate.
 */
#include "cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/gimbal.h"

static void gimbal_usage(FILE *f)
{
    fputs("usage: qorient gimbal [OPTIONS] [FILE|-]\n"
          "\n"
          "Reads orientation keyframes, one per line 't,w,x,y,z' (time in s, quaternion scalar\n"
          "first; commas and/or blanks; '#' comments), interpolates them on the quaternion sphere\n"
          "and writes, at a fixed rate from the first key time to the last (and on while a rate\n"
          "limit still holds a joint back), the joint angles of a\n"
          "2- or 3-axis gimbal:\n"
          "  t,a1,a2,a3,margin,lock,clipped\n"
          "a1..a3   joint angles, outer to inner, of the mechanism's axis sequence, nearest the\n"
          "         previous sample (no jumps; continuous joints keep counting turns)\n"
          "margin   angle of the requested orientation from the singular configuration\n"
          "lock     1 inside the hold band (the free angle a3 is held steady), else 0\n"
          "clipped  bit mask of joints a rate or position limit held back (1 = a1, 2 = a2, 4 = a3)\n"
          "\n"
          "With --amax the joint angles are those of a tracking filter (qo_gimbal_track_f32): the\n"
          "joints follow the path with continuous rates, |acceleration| <= A (and |jerk| <= J),\n"
          "lagging it where the path asks for more; after the last key the output goes on until\n"
          "every joint is on the path's end at rest.\n"
          "\n"
          "options:\n"
          "  -s, --seq SEQ       axes outer to inner, scipy naming (default ZYX: yaw, pitch, roll)\n"
          "  -r, --rate HZ       output rate (default 100)\n"
          "  -i, --interp KIND   slerp (piecewise, default) or spline (Shoemake, C1 through keys)\n"
          "  -b, --band DEG      hold band around the singular configuration, degrees (default 1)\n"
          "  -v, --vmax V        joint rate limit, rad/s (deg/s with --degrees); default none\n"
          "  -a, --amax A        smooth the joints: follow the path with acceleration limited to A,\n"
          "                      rad/s^2 (deg/s^2 with --degrees); rates are then continuous\n"
          "  -j, --jmax J        with --amax, also limit jerk to J, rad/s^3 (deg/s^3 with --degrees)\n"
          "  -d, --degrees       write angles and margin in degrees, read --vmax, --amax, --jmax in\n"
          "                      deg/s, deg/s^2, deg/s^3\n"
          "      --max-samples N most rows printed, a whole number in [1, 1e10] (default 1000000):\n"
          "                      a longer output (the path and the catch-up after it) is refused\n"
          "                      before anything is printed\n"
          "  -h, --help          this text\n"
          "\n"
          "Errors (non-monotonic times, wrong column count, non-numbers, NaN or Inf, numbers out of\n"
          "float32 range, a zero quaternion, a line longer than 1048576 characters, more than\n"
          "67108864 bytes or --max-samples keyframes, keyframes spanning more than --max-samples\n"
          "rows, bad options) are reported on standard error naming the line (the rest is not read);\n"
          "the exit status is then 1 (2 for usage errors) and nothing is written. When the\n"
          "joints have not caught up with the path's end after one hour of rows, the rows are\n"
          "written, a message says so and the exit status is 1.\n"
          "\n"
          "example: pitch straight through the ZYX singularity\n"
          "  printf '0 1 0 0 0\\n2 0.7071068 0 0.7071068 0\\n4 0 0 1 0\\n' | qorient gimbal --rate 10\n", f);
}

static int parse_positive(const char *s, double *v)
{
    char *end;
    *v = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*v) && *v > 0;
}

int qo_cli_gimbal(int argc, char **argv)
{
    static const struct option opts[] = {
        { "seq", required_argument, NULL, 's' },
        { "rate", required_argument, NULL, 'r' },
        { "interp", required_argument, NULL, 'i' },
        { "band", required_argument, NULL, 'b' },
        { "vmax", required_argument, NULL, 'v' },
        { "amax", required_argument, NULL, 'a' },
        { "jmax", required_argument, NULL, 'j' },
        { "degrees", no_argument, NULL, 'd' },
        { "max-samples", required_argument, NULL, 'm' },
        { "help", no_argument, NULL, 'h' },
        { NULL, 0, NULL, 0 },
    };
    const double deg = 3.14159265358979323846 / 180.0;
    qo_gimbal_settings_f32 gs = qo_gimbal_settings_default;
    qo_gimbal_path_interp interp = QO_GIMBAL_PATH_SLERP;
    double rate = 100.0, band_deg = 1.0, vmax = INFINITY, amax = 0.0, jmax = INFINITY, v;
    double max_samples = QO_CLI_MAX_SAMPLES_DEFAULT;
    int degrees = 0, ch, rc = 1, unsettled = 0;
    unsigned caught_up_not = 0;
    FILE *in = stdin;
    float *t = NULL;
    qo_quat_f32 *keys = NULL, *ks = NULL, *a = NULL, *b = NULL;
    size_t n = 0, cap = 0, lcap = 0, left = QO_CLI_INPUT_MAX;
    long len = -1;
    qo_traj_ns t0n = 0;
    char *line = NULL;
    unsigned long lineno = 0;
    qo_gimbal_path_f32 path;
    qo_gimbal_f32 g;
    qo_gimbal_track_settings_f32 ts = qo_gimbal_track_settings_default;
    qo_gimbal_track_f32 tr;
    qo_status st;

    while ((ch = getopt_long(argc, argv, "s:r:i:b:v:a:j:dh", opts, NULL)) != -1) {
        switch (ch) {
        case 's':
            if (qo_euler_seq_parse(optarg, &gs.seq) != QO_OK) {
                fprintf(stderr, "qorient gimbal: --seq: %s is not a sequence (e.g. ZYX, zyx, ZXZ)\n",
                        QO_CLI_QUOTED(optarg));
                return 2;
            }
            break;
        case 'r':
            if (qo_cli_number("gimbal", "--rate", optarg, QO_CLI_RATE_MIN, QO_CLI_RATE_MAX, "Hz", &rate)) return 2;
            break;
        case 'm':
            if (qo_cli_count("gimbal", "--max-samples", optarg, 1.0, QO_CLI_MAX_SAMPLES_LIMIT, &max_samples)) return 2;
            break;
        case 'i':
            if (strcmp(optarg, "slerp") == 0) interp = QO_GIMBAL_PATH_SLERP;
            else if (strcmp(optarg, "spline") == 0) interp = QO_GIMBAL_PATH_SPLINE;
            else {
                fprintf(stderr, "qorient gimbal: --interp: %s is not slerp or spline\n", QO_CLI_QUOTED(optarg));
                return 2;
            }
            break;
        case 'b':
            if (qo_cli_number("gimbal", "--band", optarg, 0.0, 90.0, "degrees", &band_deg)) return 2;
            break;
        case 'v':
            if (!parse_positive(optarg, &v)) {
                fprintf(stderr, "qorient gimbal: --vmax: %s is not a positive number\n", QO_CLI_QUOTED(optarg));
                return 2;
            }
            vmax = v;
            break;
        case 'a':
        case 'j':
            if (!parse_positive(optarg, &v)) {
                fprintf(stderr, "qorient gimbal: --%s: %s is not a positive number\n", ch == 'a' ? "amax" : "jmax",
                        QO_CLI_QUOTED(optarg));
                return 2;
            }
            if (ch == 'a') amax = v; else jmax = v;
            break;
        case 'd': degrees = 1; break;
        case 'h': gimbal_usage(stdout); return 0;
        default: gimbal_usage(stderr); return 2;
        }
    }
    if (isfinite(jmax) && amax == 0.0) {
        fprintf(stderr, "qorient gimbal: --jmax needs --amax\n");
        return 2;
    }
    if (argc - optind > 1) {
        fprintf(stderr, "qorient gimbal: at most one input file\n");
        return 2;
    }
    if (argc - optind == 1 && strcmp(argv[optind], "-") != 0) {
        in = fopen(argv[optind], "r");
        if (in == NULL) {
            fprintf(stderr, "qorient gimbal: cannot open '%s'\n", argv[optind]);
            return 1;
        }
    }
    gs.band = (float)(band_deg * deg);
    gs.vmax = (float)(degrees && isfinite(vmax) ? vmax * deg : vmax);
    ts.vmax = gs.vmax;
    ts.amax = (float)(degrees ? amax * deg : amax);
    ts.jmax = (float)(degrees && isfinite(jmax) ? jmax * deg : jmax);
    /* With a jerk limit the error gain stays below jmax/(4 amax) (qorient/gimbal.h: above it
     * the joints ring around the path before settling); the ratio is the same in degrees. */
    if (amax > 0.0 && isfinite(jmax) && ts.gain > (float)(jmax / (4.0 * amax))) ts.gain = (float)(jmax / (4.0 * amax));
    if (amax > 0.0 && qo_gimbal_track_init_f32(&tr, &ts) != QO_OK) {
        fprintf(stderr, "qorient gimbal: --amax, --jmax and --vmax must be in [%g, %g] rad/s^k with --amax\n",
                (double)QO_MOTION_LIMIT_MIN, (double)QO_MOTION_LIMIT_MAX);
        if (in != stdin) fclose(in);
        return 2;
    }

    while ((len = qo_cli_getline(&line, &lcap, in, &left)) >= 0) {
        double f[6];
        size_t m;
        int prc;
        struct qo_cli_field bad;
        char why[QO_CLI_REASON_CAP];
        qo_traj_ns tn;
        float rel;
        lineno++;
        if (strlen(line) != (size_t)len) {
            fprintf(stderr, "qorient gimbal: line %lu: contains a NUL byte\n", lineno);
            goto out;
        }
        /* the parser refuses NaN, Inf and what float32 (the core's quaternion) cannot hold */
        prc = qo_cli_parse_fields(line, f, 6, &m, &bad);
        if (prc == 0 && m == 0) continue;
        if (prc != 0 && prc != QO_CLI_NUM_MANY) {
            fprintf(stderr, "qorient gimbal: line %lu: %s\n", lineno,
                    qo_cli_field_reason(prc, &bad, "column", why, sizeof why));
            goto out;
        }
        if (prc == QO_CLI_NUM_MANY || m != 5) {
            fprintf(stderr, "qorient gimbal: line %lu: expected 5 numbers (t,w,x,y,z), got %s%zu\n",
                    lineno, prc == QO_CLI_NUM_MANY ? "more than " : "", m);
            goto out;
        }
        if (f[1] == 0 && f[2] == 0 && f[3] == 0 && f[4] == 0) {
            fprintf(stderr, "qorient gimbal: line %lu: %s\n", lineno, qo_status_str(QO_E_DEGENERATE));
            goto out;
        }
        /* Key times in ns, handed to the float32 core as offsets from the first key: a path at
         * t = 1e7 s is sampled as finely as one at t = 0. */
        if (qo_traj_ns_from_s(f[0], &tn) != QO_OK) {
            fprintf(stderr, "qorient gimbal: line %lu: time %g s is beyond the +-4.6e9 s supported\n", lineno, f[0]);
            goto out;
        }
        if (n == 0) t0n = tn;
        /* Bounded as it is read: more keys than --max-samples, or keys whose times already
         * span more than --max-samples rows, stop the reading here (the rows are counted
         * exactly, catch-up included, once the path is known). */
        if ((double)n >= max_samples) {
            fprintf(stderr, "qorient gimbal: line %lu: more than --max-samples %.0f keyframes: nothing more is "
                    "read (raise --max-samples)\n", lineno, max_samples);
            goto out;
        }
        rel = (float)((double)(tn - t0n) * 1e-9);
        /* the rows up to this key on the grid sampled below (at least these are printed) */
        if (floor((double)rel * rate + 1e-9) + 1.0 > max_samples) {
            fprintf(stderr, "qorient gimbal: line %lu: the output is at least %.0f rows at %g Hz by this key's time, "
                    "more than --max-samples %.0f: lower --rate or raise --max-samples\n", lineno,
                    floor((double)rel * rate + 1e-9) + 1.0, rate, max_samples);
            goto out;
        }
        if (n > 0 && !(rel > t[n - 1])) {
            fprintf(stderr, "qorient gimbal: line %lu: time %.9g is not after the previous key's (as a float32 "
                    "offset from the first key)\n", lineno, f[0]);
            goto out;
        }
        if (n == cap) {
            size_t nc = cap ? 2 * cap : 64;
            float *nt = realloc(t, nc * sizeof *t);
            qo_quat_f32 *nk;
            if (nt == NULL) goto oom;
            t = nt;
            nk = realloc(keys, nc * sizeof *keys);
            if (nk == NULL) goto oom;
            keys = nk;
            cap = nc;
        }
        t[n] = rel;
        keys[n].w = (float)f[1]; keys[n].x = (float)f[2]; keys[n].y = (float)f[3]; keys[n].z = (float)f[4];
        n++;
    }
    if (len < -1) {
        fprintf(stderr, "qorient gimbal: line %lu: %s\n", lineno + 1, qo_cli_line_problem(len));
        goto out;
    }
    if (ferror(in)) {
        fprintf(stderr, "qorient gimbal: %s: read error: %s\n", in == stdin ? "-" : argv[optind], strerror(errno));
        goto out;
    }
    if (n < 2) {
        fprintf(stderr, "qorient gimbal: need at least 2 keyframes, got %zu\n", n);
        goto out;
    }
    ks = malloc(n * sizeof *ks);
    a = malloc(n * sizeof *a);
    b = malloc(n * sizeof *b);
    if (ks == NULL || a == NULL || b == NULL) goto oom;
    st = qo_gimbal_path_init_f32(&path, t, keys, n, interp, ks, a, b);
    if (st == QO_OK) st = qo_gimbal_init_f32(&g, &gs);
    if (st != QO_OK) {
        fprintf(stderr, "qorient gimbal: %s\n", qo_status_str(st));
        goto out;
    }
    {
        /* Sample times t0 + k/rate computed from k (no accumulated rounding), then the last key
         * time itself if the grid does not land on it. */
        double t0 = t[0], t1 = t[n - 1], s = degrees ? 1.0 / deg : 1.0; /* offsets: t0 == 0 */
        double span_n = floor((t1 - t0) * rate + 1e-9);
        unsigned long k, kmax;
        int extra;
        /* As `qorient plan`: more than 1e9 samples is refused (key times up to 3e38 s would
         * otherwise overflow the conversion to unsigned long, which is undefined). */
        if (!(span_n <= 1e9)) {
            fprintf(stderr, "qorient gimbal: %.0f samples: lower --rate\n", span_n + 1.0);
            goto out;
        }
        kmax = (unsigned long)span_n;
        extra = t0 + (double)kmax / rate < t1 - 1e-9;
        /* After the last key the path holds it; while a rate limit still holds a joint back,
         * or the tracking filter has not settled on the path's end, the samples go on (on the
         * same grid) until every joint has arrived: the motion has ended when the joints are
         * where the path ends, not when the path does. Bounded by one hour of catching up. */
        unsigned long kcatch = kmax + (unsigned long)(3600.0 * rate < 1e9 ? 3600.0 * rate : 1e9);
        qo_gimbal_sample_f32 o;
        qo_gimbal_track_sample_f32 to;
        double rows = 0.0;
        int pass;
        /* Pass 0 counts the rows without printing (the catch-up makes the count unknown in
         * advance), so that more than --max-samples is refused before anything is printed, as
         * `qorient plan` does; pass 1, from the same initial state, prints them. */
        for (pass = 0; pass < 2; pass++) {
            st = qo_gimbal_init_f32(&g, &gs);
            if (st == QO_OK && amax > 0.0) st = qo_gimbal_track_init_f32(&tr, &ts);
            if (st != QO_OK) { /* accepted once above: only a broken invariant lands here */
                fprintf(stderr, "qorient gimbal: %s\n", qo_status_str(st));
                goto out;
            }
            o.clipped = 0;
            to.settled = 1;
            for (k = 0; k <= kmax + (unsigned long)extra || ((o.clipped || !to.settled) && k <= kcatch); k++) {
                double tt = k <= kmax ? t0 + (double)k / rate : k == kmax + 1 && extra ? t1 : t0 + (double)(k - (unsigned long)extra) / rate;
                qo_quat_f32 q;
                st = qo_gimbal_path_sample_f32(&path, (float)tt, &q);
                if (st == QO_OK) st = qo_gimbal_step_f32(&g, (float)tt, q, &o);
                if (st == QO_OK && amax > 0.0) {
                    st = qo_gimbal_track_step_f32(&tr, (float)tt, o.angles, &to);
                    o.angles = to.angles;
                }
                if (st != QO_OK) {
                    fprintf(stderr, "qorient gimbal: t=%g: %s\n", tt, qo_status_str(st));
                    goto out;
                }
                if (pass == 0) {
                    if (++rows > max_samples) break;
                    continue;
                }
                qo_cli_print_time(stdout, t0n + (qo_traj_ns)llround(tt * 1e9)); putchar(',');
                qo_cli_print_f32(stdout, (float)(o.angles.a1 * s)); putchar(',');
                qo_cli_print_f32(stdout, (float)(o.angles.a2 * s)); putchar(',');
                qo_cli_print_f32(stdout, (float)(o.angles.a3 * s)); putchar(',');
                qo_cli_print_f32(stdout, (float)(o.margin * s));
                printf(",%d,%u\n", o.locked, o.clipped);
            }
            if (pass == 0 && rows > max_samples) {
                fprintf(stderr, "qorient gimbal: the output is more than --max-samples %.0f rows at %g Hz: lower "
                        "--rate or raise --max-samples\n", max_samples, rate);
                goto out;
            }
        }
        caught_up_not = o.clipped;
        unsettled = !to.settled;
    }
    rc = 0;
    if (caught_up_not) {
        fprintf(stderr, "qorient gimbal: after one hour of catch-up --vmax still holds joints back (clipped=%u): "
                "the last row is far from the path's end\n", caught_up_not);
        rc = 1;
    } else if (unsettled) {
        fprintf(stderr, "qorient gimbal: after one hour of catch-up the tracking filter has not settled on the "
                "path's end: the last row is not at rest there\n");
        rc = 1;
    }
    goto out;
oom:
    fprintf(stderr, "qorient gimbal: out of memory\n");
out:
    if (in != stdin) fclose(in);
    free(line); free(t); free(keys); free(ks); free(a); free(b);
    return rc;
}
