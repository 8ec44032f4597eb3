/* `qorient plan --profile trapezoid|scurve`: stream targets in, limit-respecting motion out. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/motion.h"
#include "qorient/motion_fx.h"

#define PM_MAX QO_MOTION_MAX_JOINTS

static const char plan_usage[] =
    "usage: qorient plan --profile trapezoid|scurve --vmax V[,V...] --amax A[,A...]\n"
    "                    [--jmax J[,J...]] [--rate HZ] [--sync time|phase|none]\n"
    "                    [--min P[,P...]] [--max P[,P...]] [--wrap J[,J...]] [--degrees]\n"
    "                    [--fixed] [FILE|-]\n"
    "\n"
    "Plans velocity-, acceleration- (and jerk-) limited motion of N joints toward targets that\n"
    "arrive over time, re-planning from the current position, velocity and acceleration at\n"
    "each new target (no jump, no stop at each point), and samples it at a fixed rate.\n"
    "\n"
    "input (FILE, or standard input for '-' or none): one line per target, numbers separated\n"
    "by commas and/or blanks:  t,p1,...,pN\n"
    "  t is the time (s) the target is ISSUED: the motion re-plans from its state at t.\n"
    "  The first line is the start: the joints are at rest at p1..pN at time t.\n"
    "  Times must not decrease (an equal time replaces the previous target).\n"
    "  Blank lines and lines starting with '#' are skipped.\n"
    "output: t,p1..pN,v1..vN,a1..aN every 1/HZ s from the first time until every joint is at\n"
    "  rest at its last target (positions in the input unit, v in unit/s, a in unit/s^2).\n"
    "\n"
    "options:\n"
    "  --profile P   trapezoid (acceleration-limited, jerk unlimited) or scurve (jerk-limited,\n"
    "                acceleration continuous). Required.\n"
    "  --vmax V,...  maximum |velocity| per joint (unit/s), > 0; one value = every joint.\n"
    "  --amax A,...  maximum |acceleration| per joint (unit/s^2), > 0. Required.\n"
    "  --jmax J,...  maximum |jerk| per joint (unit/s^3), > 0. Required for scurve, unused\n"
    "                by trapezoid.\n"
    "  --rate HZ     output sample rate, > 0 (default 100).\n"
    "  --sync S      time (default): all joints arrive together; phase: straight line in\n"
    "                joint space when the state allows it (all at rest, or moving along the\n"
    "                new line), else time, with a note on standard error; none: each joint\n"
    "                as fast as it can.\n"
    "  --min P,...   lowest allowed target per joint; --max P,... highest. Targets outside\n"
    "                are clamped to the range and reported on standard error.\n"
    "  --wrap J,...  1-based joint numbers of continuous joints: they take the short way\n"
    "                round, period 2*pi (or 360 with --degrees). Output stays unwrapped.\n"
    "  --degrees     positions are degrees (sets the wrap period to 360). Limits are always\n"
    "                in the positions' unit.\n"
    "  --fixed       sample with the fixed-point core (Q16.16, |values| < 32768).\n"
    "  -h, --help    this text.\n"
    "\n"
    "A line with the wrong number of columns, a field that is not a finite number or a\n"
    "decreasing time is skipped with a message naming the line on standard error; the exit\n"
    "status is then 1. Usage errors exit 2.\n";

/* Comma/blank separated list of numbers from an option argument. */
static int parse_list(const char *arg, const char *opt, double *out, size_t *n)
{
    char *copy = strdup(arg);
    int rc;
    size_t i;
    if (copy == NULL) return -1;
    rc = qo_cli_parse_numbers(copy, out, PM_MAX, n);
    free(copy);
    if (rc != 0 || *n == 0) {
        fprintf(stderr, "qorient plan: %s: expected up to %d numbers separated by commas, got '%s'\n", opt,
                PM_MAX, arg);
        return -1;
    }
    for (i = 0; i < *n; i++) {
        if (!isfinite(out[i])) {
            fprintf(stderr, "qorient plan: %s: value %zu is not finite\n", opt, i + 1);
            return -1;
        }
    }
    return 0;
}

/* Spreads a 1- or N-element list to N joints (N comes from the first line, `ln`). */
static int spread(const char *opt, const double *in, size_t nin, size_t n, double *out, long ln)
{
    size_t i;
    if (nin != 1 && nin != n) {
        fprintf(stderr, "qorient plan: line %ld has %zu joints but %s has %zu values (give 1 or %zu)\n", ln, n, opt,
                nin, n);
        return -1;
    }
    for (i = 0; i < n; i++) out[i] = in[nin == 1 ? 0 : i];
    return 0;
}

struct pm_out {
    qo_motion_planner_f32 *pl;
    double t_first;            /* input time of the first line: the output grid's anchor */
    double t_origin;           /* input time that is the core's time 0 (the last re-plan) */
    double t_next;             /* next output time */
    double period;
    long k;                    /* samples written */
    int fixed;
    qo_motion_table_q16 tab;
    qo_motion_seg_q16 segs[PM_MAX * QO_MOTION_Q16_SEGS];
    int warned_overflow;
};

static void emit_row(struct pm_out *o, double t)
{
    size_t i, n = o->pl->n;
    float p[PM_MAX], v[PM_MAX], a[PM_MAX];
    if (o->fixed) {
        qo_q16 qp[PM_MAX], qv[PM_MAX], qa[PM_MAX];
        double local = t - (o->t_origin + (double)o->pl->t0);
        qo_q16 tq = local >= 32767.0 ? INT32_MAX : (qo_q16)lrint(local * 65536.0);
        qo_status st = qo_motion_sample_q16(&o->tab, tq, qp, qv, qa);
        if (st == QO_E_OVERFLOW && !o->warned_overflow) {
            fprintf(stderr, "qorient plan: warning: fixed-point value saturated near t=%g\n", t);
            o->warned_overflow = 1;
        }
        for (i = 0; i < n; i++) {
            p[i] = (float)(qp[i] / 65536.0);
            v[i] = (float)(qv[i] / 65536.0);
            a[i] = (float)(qa[i] / 65536.0);
        }
    } else {
        qo_motion_sample_f32(o->pl, (float)(t - o->t_origin), p, v, a);
    }
    printf("%.9g", t);
    for (i = 0; i < n; i++) { putchar(','); qo_cli_print_f32(stdout, p[i]); }
    for (i = 0; i < n; i++) { putchar(','); qo_cli_print_f32(stdout, v[i]); }
    for (i = 0; i < n; i++) { putchar(','); qo_cli_print_f32(stdout, a[i]); }
    putchar('\n');
}

/* Writes every sample before time `until` (exclusive). */
static void emit_until(struct pm_out *o, double until)
{
    while (o->t_next < until) {
        emit_row(o, o->t_next);
        o->k++;
        o->t_next = o->t_first + (double)o->k * o->period;
    }
}

static void after_plan(struct pm_out *o)
{
    if (o->fixed) {
        qo_status st = qo_motion_export_q16(o->pl, &o->tab, o->segs, sizeof o->segs / sizeof o->segs[0]);
        if (st == QO_E_OVERFLOW && !o->warned_overflow) {
            fprintf(stderr, "qorient plan: warning: plan exceeds the Q16.16 range (|x| < 32768, t < 32768 s)\n");
            o->warned_overflow = 1;
        }
    }
}

int qo_cli_plan_moves(int argc, char **argv)
{
    static const struct option opts[] = {
        { "profile", required_argument, NULL, 'p' }, { "rate", required_argument, NULL, 'r' },
        { "vmax", required_argument, NULL, 'v' },    { "amax", required_argument, NULL, 'a' },
        { "jmax", required_argument, NULL, 'j' },    { "sync", required_argument, NULL, 's' },
        { "min", required_argument, NULL, 'm' },     { "max", required_argument, NULL, 'M' },
        { "wrap", required_argument, NULL, 'w' },    { "degrees", no_argument, NULL, 'd' },
        { "fixed", no_argument, NULL, 'f' },         { "help", no_argument, NULL, 'h' },
        { NULL, 0, NULL, 0 }
    };
    double vl[PM_MAX], al[PM_MAX], jl[PM_MAX], mn[PM_MAX], mx[PM_MAX], wr[PM_MAX];
    size_t nv = 0, na = 0, nj = 0, nmn = 0, nmx = 0, nwr = 0;
    double rate = 100.0;
    int degrees = 0, have_profile = 0, fixed = 0, c, status = 0;
    qo_motion_settings_f32 set = qo_motion_settings_default;
    const char *path = "-";
    FILE *in;
    char *line = NULL;
    size_t cap = 0;
    long ln = 0, len;
    int started = 0;
    double t_prev = 0.0;
    qo_motion_planner_f32 pl;
    qo_motion_joint_f32 joints[PM_MAX];
    qo_motion_limits_f32 lim[PM_MAX];
    struct pm_out *o;

    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        switch (c) {
        case 'p':
            if (strcmp(optarg, "trapezoid") == 0) set.profile = QO_MOTION_TRAPEZOID;
            else if (strcmp(optarg, "scurve") == 0) set.profile = QO_MOTION_SCURVE;
            else {
                fprintf(stderr, "qorient plan: --profile must be trapezoid or scurve, not '%s'\n", optarg);
                return 2;
            }
            have_profile = 1;
            break;
        case 'r': {
            char *end;
            rate = strtod(optarg, &end);
            if (end == optarg || *end != '\0' || !isfinite(rate) || rate <= 0.0) {
                fprintf(stderr, "qorient plan: --rate must be a number > 0, not '%s'\n", optarg);
                return 2;
            }
            break;
        }
        case 'v': if (parse_list(optarg, "--vmax", vl, &nv)) return 2; break;
        case 'a': if (parse_list(optarg, "--amax", al, &na)) return 2; break;
        case 'j': if (parse_list(optarg, "--jmax", jl, &nj)) return 2; break;
        case 'm': if (parse_list(optarg, "--min", mn, &nmn)) return 2; break;
        case 'M': if (parse_list(optarg, "--max", mx, &nmx)) return 2; break;
        case 'w': if (parse_list(optarg, "--wrap", wr, &nwr)) return 2; break;
        case 's':
            if (strcmp(optarg, "time") == 0) set.sync = QO_MOTION_SYNC_TIME;
            else if (strcmp(optarg, "phase") == 0) set.sync = QO_MOTION_SYNC_PHASE;
            else if (strcmp(optarg, "none") == 0) set.sync = QO_MOTION_SYNC_NONE;
            else {
                fprintf(stderr, "qorient plan: --sync must be time, phase or none, not '%s'\n", optarg);
                return 2;
            }
            break;
        case 'd': degrees = 1; break;
        case 'f': fixed = 1; break;
        case 'h': fputs(plan_usage, stdout); return 0;
        default: fputs(plan_usage, stderr); return 2;
        }
    }
    if (!have_profile || nv == 0 || na == 0 || (set.profile == QO_MOTION_SCURVE && nj == 0)) {
        fprintf(stderr, "qorient plan: %s is required\n",
                !have_profile ? "--profile" : nv == 0 ? "--vmax" : na == 0 ? "--amax" : "--jmax (for scurve)");
        fputs(plan_usage, stderr);
        return 2;
    }
    {
        /* Limits must be > 0 (finite was checked while parsing): say so before reading input. */
        const struct { const char *name; const double *v; size_t n; } lists[3] = {
            { "--vmax", vl, nv }, { "--amax", al, na }, { "--jmax", jl, nj }
        };
        size_t li, i;
        for (li = 0; li < 3; li++) {
            for (i = 0; i < lists[li].n; i++) {
                if (!(lists[li].v[i] > 0.0)) {
                    fprintf(stderr, "qorient plan: %s value %zu is %g: limits must be > 0\n", lists[li].name, i + 1,
                            lists[li].v[i]);
                    return 2;
                }
            }
        }
    }
    if (optind + 1 < argc) {
        fprintf(stderr, "qorient plan: one input file at most\n");
        return 2;
    }
    if (optind < argc) path = argv[optind];
    o = calloc(1, sizeof *o);
    if (o == NULL) return 2;
    o->fixed = fixed;
    in = strcmp(path, "-") == 0 ? stdin : fopen(path, "r");
    if (in == NULL) {
        fprintf(stderr, "qorient plan: cannot open '%s'\n", path);
        free(o);
        return 2;
    }
    o->pl = &pl;
    o->period = 1.0 / rate;

    while ((len = qo_cli_getline(&line, &cap, in)) >= 0) {
        double num[PM_MAX + 1];
        size_t n = 0, i;
        int rc;
        ln++;
        rc = qo_cli_parse_numbers(line, num, PM_MAX + 1, &n); /* t and at most PM_MAX positions */
        if (rc == 0 && n == 0) continue;
        if (rc == -1) {
            fprintf(stderr, "qorient plan: line %ld: not a number\n", ln);
            status = 1;
            continue;
        }
        if (rc == -2 || n < 2 || (started && n != pl.n + 1)) {
            if (started)
                fprintf(stderr, "qorient plan: line %ld: expected %zu columns (t and %zu positions), got %s\n", ln,
                        pl.n + 1, pl.n, rc == -2 ? "more" : "fewer or more");
            else
                fprintf(stderr, "qorient plan: line %ld: expected t and 1..%d positions\n", ln, PM_MAX);
            status = 1;
            continue;
        }
        for (i = 0; i < n; i++)
            if (!isfinite(num[i])) break;
        if (i < n) {
            fprintf(stderr, "qorient plan: line %ld: column %zu is not finite\n", ln, i + 1);
            status = 1;
            continue;
        }
        if (!started) {
            size_t nn = n - 1;
            double v[PM_MAX], a[PM_MAX], j[PM_MAX], lo[PM_MAX], hi[PM_MAX];
            float start[PM_MAX];
            qo_status st;
            if (spread("--vmax", vl, nv, nn, v, ln) || spread("--amax", al, na, nn, a, ln) ||
                (nj && spread("--jmax", jl, nj, nn, j, ln)) || (nmn && spread("--min", mn, nmn, nn, lo, ln)) ||
                (nmx && spread("--max", mx, nmx, nn, hi, ln))) {
                status = 2;
                break;
            }
            for (i = 0; i < nn; i++) {
                lim[i] = qo_motion_limits_default;
                lim[i].vmax = (float)v[i];
                lim[i].amax = (float)a[i];
                lim[i].jmax = nj ? (float)j[i] : 1.0f;
                if (nmn) lim[i].pmin = (float)lo[i];
                if (nmx) lim[i].pmax = (float)hi[i];
                if (!(v[i] > 0.0) || !(a[i] > 0.0) || (nj && !(j[i] > 0.0))) {
                    fprintf(stderr, "qorient plan: joint %zu: limits must be > 0 (vmax %g, amax %g%s)\n", i + 1,
                            v[i], a[i], nj ? ", jmax > 0" : "");
                    status = 2;
                }
                if (lim[i].pmin > lim[i].pmax) {
                    fprintf(stderr, "qorient plan: line %ld: joint %zu: --min %g > --max %g\n", ln, i + 1,
                            (double)lim[i].pmin, (double)lim[i].pmax);
                    status = 2;
                }
                start[i] = (float)num[i + 1];
            }
            for (i = 0; i < nwr; i++) {
                double w = wr[i];
                if (w != floor(w) || w < 1.0 || w > (double)nn) {
                    fprintf(stderr, "qorient plan: --wrap: '%g' is not a joint number 1..%zu\n", w, nn);
                    status = 2;
                    continue;
                }
                lim[(size_t)w - 1].wrap = degrees ? 360.0f : 6.28318530718f;
            }
            if (status == 2) break;
            st = qo_motion_init_f32(&pl, joints, nn, lim, start, 0.0f, &set);
            if (st != QO_OK) {
                fprintf(stderr, "qorient plan: line %ld: %s\n", ln, qo_status_str(st));
                status = 2;
                break;
            }
            started = 1;
            t_prev = num[0];
            o->t_origin = num[0];
            o->t_first = num[0];
            o->t_next = num[0];
            o->k = 0;
            after_plan(o);
            continue;
        }
        if (num[0] < t_prev) {
            fprintf(stderr, "qorient plan: line %ld: time %g is before the previous line's %g\n", ln, num[0], t_prev);
            status = 1;
            continue;
        }
        emit_until(o, num[0]);
        {
            float tg[PM_MAX];
            uint32_t mask = 0;
            qo_status st;
            for (i = 0; i < pl.n; i++) tg[i] = (float)num[i + 1];
            /* Keep the core's float32 times small in long runs: time 0 = this re-plan. */
            qo_motion_shift_time_f32(&pl, (float)(num[0] - o->t_origin));
            o->t_origin = num[0];
            st = qo_motion_set_target_f32(&pl, 0.0f, tg, &mask);
            if (st != QO_OK) {
                fprintf(stderr, "qorient plan: line %ld: %s\n", ln, qo_status_str(st));
                status = 1;
            }
            if (st == QO_OK && set.sync == QO_MOTION_SYNC_PHASE && qo_motion_sync_used(&pl) != QO_MOTION_SYNC_PHASE)
                fprintf(stderr, "qorient plan: line %ld: no straight line from the current state, time sync used\n",
                        ln);
            for (i = 0; i < pl.n; i++)
                if (pl.unsynced & ((uint32_t)1 << i))
                    fprintf(stderr, "qorient plan: line %ld: joint %zu cannot take the common duration from its "
                            "state; it arrives early\n", ln, i + 1);
            for (i = 0; i < pl.n; i++)
                if (mask & ((uint32_t)1 << i))
                    fprintf(stderr, "qorient plan: line %ld: joint %zu target %g clamped to %g\n", ln, i + 1,
                            num[i + 1], (double)pl.joints[i].goal);
            after_plan(o);
        }
        t_prev = num[0];
    }
    if (started && status != 2) {
        /* Until the motion has ended: the last row is the first one at rest at the targets. */
        double end = o->t_origin + (double)qo_motion_end_time_f32(&pl);
        emit_until(o, end);
        while (!qo_motion_done_f32(&pl, (float)(o->t_next - o->t_origin))) {
            emit_row(o, o->t_next);
            o->k++;
            o->t_next = o->t_first + (double)o->k * o->period;
        }
        emit_row(o, o->t_next);
    } else if (!started && status == 0) {
        fprintf(stderr, "qorient plan: no start line (t,p1,...,pN) in the input\n");
        status = 1;
    }
    free(line);
    if (in != stdin) fclose(in);
    free(o);
    fflush(stdout);
    return status;
}
