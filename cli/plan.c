/* `qorient plan`: reads keyframes or targets into a qorient/traj.h trajectory (planopt.c,
 * shared with `qorient stream`) and prints it sampled at a fixed rate. */
#include "cli.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* In parts: C99 only promises string literals of 4095 characters. */
static const char *const plan_usage[] = {
    "usage: qorient plan [OPTIONS] [FILE|-]\n"
    "\n"
    "Plans a multi-joint trajectory and prints it sampled at a fixed rate: through keyframes\n"
    "(linear, cubic, catmull, spline, quintic), or as velocity/acceleration(/jerk)-limited\n"
    "motion toward targets issued over time (trapezoid, scurve).\n"
    "\n"
    "Input (FILE, or standard input when FILE is '-' or absent): one line per keyframe or\n"
    "target, numbers separated by commas and/or blanks; blank lines and lines starting with\n"
    "'#' are ignored; every line has the same number of columns.\n"
    "  keyframes  t,p1,...,pN   t = time (s) the keyframe is reached, strictly increasing\n"
    "                           (with --columns pv|pva: t,p1..pN,v1..vN[,a1..aN])\n"
    "  targets    t,p1,...,pN   t = time (s) the target is ISSUED (not decreasing; an equal time\n"
    "                           replaces the previous target): the motion re-plans from its\n"
    "                           position, velocity and acceleration at t. The first line is\n"
    "                           the start: at rest at p1..pN from t.\n"
    "             t,p1..pN,v1..vN  with --target-velocities: each target is reached moving at\n"
    "                           v1..vN (the joints pass through it and, with no later\n"
    "                           target, move on at that velocity); the start's v must be 0\n"
    "  Times are exact to the ns at any magnitude up to +-4.6e9 s.\n"
    "Output: one line per sample, 't,p1..pN,v1..vN,a1..aN' (position, velocity in unit/s,\n"
    "  acceleration in unit/s^2) at t = t_first + i/rate, i = 0, 1, ...: keyframes up to the\n"
    "  last key time, plus a sample at exactly the last key time when the rate does not land\n"
    "  on it; targets until the first sample with every joint at rest at its last target.\n"
    "  Keyframes: before the first and after the last key the trajectory is at rest; at the\n"
    "  last key it reports the end velocity/acceleration of the last segment.\n"
    "  At most --max-samples lines: a longer plan is refused before anything is printed.\n"
    "\n"
    "Options:\n"
    "  --profile NAME   linear   straight lines between keys (velocity steps at keys)\n"
    "                   cubic    cubic Hermite through keys with given velocities\n"
    "                            (needs --columns pv)\n"
    "                   catmull  cubic with Catmull-Rom (time-weighted) tangents, C1\n"
    "                   spline   interpolating C2 cubic spline (default)\n"
    "                   quintic  quintic segments, C2; velocities/accelerations from the\n"
    "                            input (--columns pv|pva) or estimated (--derivs)\n"
    "                   trapezoid  targets, acceleration-limited (jerk unlimited)\n"
    "                   scurve     targets, jerk-limited (acceleration continuous)\n"
    "  --rate HZ        samples per second, in [0.001, 1e6] (default 100)\n"
    "  --max-samples N  most lines printed, in [1, 1e10] (default 1000000)\n"
    "  --min P[,P...]   lower position limits: one value for all joints or one per joint;\n"
    "  --max P[,P...]   upper limits likewise. Keyframes: samples are clamped (velocity and\n"
    "                   acceleration of a clamped joint are 0) and a note on standard error\n"
    "                   counts them. Targets: a target outside is clamped, with a note.\n"
    "  --wrap J[,J...]  continuous joints, 1-based: each step takes the short way round\n"
    "                   (period 2 pi, or 360 with --degrees); positions of any size are\n"
    "                   reduced to (-period/2, period/2] first. Keyframes: output in\n"
    "                   (-period/2, period/2] unless --unwrapped; targets: output unwrapped.\n"
    "  --degrees        positions are degrees: the wrap period is 360\n",
    "  --fixed          sample with the fixed-point (Q16.16) core instead of float32: times\n"
    "                   after the first line and values must fit in +-32768; the values are\n"
    "                   printed exactly (the Q16.16 value's full decimal)\n"
    "Keyframe profiles only:\n"
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
    "  --unwrapped      print continuous joints unwrapped (continuing from the first key)\n"
    "Target profiles (trapezoid, scurve) only:\n"
    "  --vmax V[,V...]  maximum |velocity| per joint (unit/s), in [1e-3, 1e9]; required\n"
    "  --amax A[,A...]  maximum |acceleration| (unit/s^2), in [1e-3, 1e9]; required\n"
    "  --jmax J[,J...]  maximum |jerk| (unit/s^3), in [1e-3, 1e9]; required for scurve\n"
    "  --vmin V[,V...]  asymmetric limits: most negative velocity per joint (unit/s), in\n"
    "  --amin A[,A...]  [-1e9, -1e-3] and within a factor 20 of -vmax, -amax (default -vmax,\n"
    "                   -amax); every velocity of the motion is in [vmin, vmax], every\n"
    "                   acceleration in [amin, amax]\n"
    "  --sync MODE[,MODE...]\n"
    "                   one mode for all joints, or one per joint: time (default): all\n"
    "                   joints arrive together; phase: straight line in joint space when the\n"
    "                   state allows it, else time, with a note; none: each joint as fast as\n"
    "                   it can; if-necessary: time sync only for joints whose target moves\n"
    "                   (--target-velocities), the others as fast as they can\n"
    "  --target-velocities\n"
    "                   target lines are t,p1..pN,v1..vN (above); a target velocity outside\n"
    "                   [vmin, vmax] is refused naming its line, nothing printed (exit 1)\n"
    "  --min-duration S a move lasts at least S seconds, in [0, 1e4] (default 0)\n"
    "  --discrete       durations rounded up to whole periods of --rate: a move issued on a\n"
    "                   sample ends exactly on a sample (the last one at rest)\n"
    "  -h, --help       this text\n"
    "\n"
    "A bad input line (not a number, NaN or Inf, out of float32 range, a NUL byte, the wrong\n"
    "number of columns, a time out of order) stops the command with a message naming the line\n"
    "before anything is printed, in both modes; so does an input past a bound: more than\n"
    "67108864 bytes, --max-samples lines or 4194304 numbers, or times that already make more\n"
    "than --max-samples samples (the rest is not read).\n"
    "Exit status: 0 ok; 1 bad input, unreadable input or a failed plan; 2 usage error.\n",
    NULL
};

static void usage(FILE *f)
{
    size_t i;
    for (i = 0; plan_usage[i]; i++) fputs(plan_usage[i], f);
}

static void print_row(qo_traj_ns t, size_t n, const float *pva)
{
    size_t j;
    qo_cli_print_time(stdout, t);
    for (j = 0; j < 3 * n; j++) {
        putchar(',');
        qo_cli_print_f32(stdout, pva[j]);
    }
    putchar('\n');
}

/* A Q16.16 value as its exact decimal (at most 16 fraction digits: 2^-16 = 5^16 / 10^16),
 * trailing zeros dropped: the same text for keyframes and targets. */
static void print_q16(qo_q16 x)
{
    unsigned long a = x < 0 ? 0UL - (unsigned long)(long)x : (unsigned long)x;
    unsigned long long frac = (unsigned long long)(a & 0xffffUL) * 152587890625ULL;
    char digits[24];
    int k = 16;
    printf("%s%lu", x < 0 ? "-" : "", a >> 16);
    if (frac == 0) return;
    snprintf(digits, sizeof digits, "%016llu", frac);
    while (k > 0 && digits[k - 1] == '0') digits[--k] = '\0';
    printf(".%s", digits);
}

static void print_row_q16(qo_traj_ns t, size_t n, const qo_q16 *pva)
{
    size_t j;
    qo_cli_print_time(stdout, t);
    for (j = 0; j < 3 * n; j++) {
        putchar(',');
        print_q16(pva[j]);
    }
    putchar('\n');
}

/* Seconds after `from` as Q16.16 (saturated: the table says what is beyond it). */
static qo_q16 q16_time(qo_traj_ns t, qo_traj_ns from)
{
    double s = (double)(t - from) * 1e-9 * 65536.0;
    if (s >= 2147483647.0) return INT32_MAX;
    if (s <= -2147483648.0) return INT32_MIN;
    return (qo_q16)llround(s);
}

struct out {
    const struct qo_cli_plan_opts *o;
    struct qo_cli_plan *p;
    const struct qo_cli_rows *r;
    size_t n, next_row;         /* targets: first row not yet applied with its notes */
    float *f;                   /* 3n + n */
    qo_q16 *q;                  /* 3n */
    int8_t *cl;
    unsigned long *ncl;
    /* --fixed */
    int32_t *table;
    qo_spline_table_q16 sq;
    qo_motion_table_q16 mq;
    qo_motion_seg_q16 segs[QO_MOTION_MAX_JOINTS * QO_MOTION_Q16_SEGS];
    unsigned long exported;     /* re-plans seen by the last export */
    int overflow;
};

/* Targets: applies each row due by t at its own time, with the notes for its line. */
static int apply_rows(struct out *w, qo_traj_ns t)
{
    int rc = 0;
    size_t j;
    while (w->next_row < w->r->rows && w->r->t[w->next_row] <= t) {
        size_t k = w->next_row++;
        qo_traj *tr = &w->p->tr;
        long ln = w->r->line[k];
        qo_status st;
        if (k == 0) continue; /* the start */
        st = qo_traj_sample(tr, w->r->t[k], w->f, NULL, NULL, NULL);
        if (k + 1 < w->r->rows && w->r->t[k + 1] == w->r->t[k]) continue; /* replaced at once */
        if (st != QO_OK) {
            fprintf(stderr, "qorient plan: line %ld: %s\n", ln, qo_status_str(st));
            rc = 1;
            continue;
        }
        if (w->o->sync == QO_MOTION_SYNC_PHASE && qo_motion_sync_used(&tr->planner) != QO_MOTION_SYNC_PHASE)
            fprintf(stderr, "qorient plan: line %ld: no straight line from the current state, time sync used\n",
                    ln);
        for (j = 0; j < w->n; j++) {
            if (tr->planner.unsynced & ((uint32_t)1 << j))
                fprintf(stderr, "qorient plan: line %ld: joint %zu cannot take the common duration from its "
                        "state; it arrives early\n", ln, j + 1);
            if (tr->clamped & ((uint32_t)1 << j))
                fprintf(stderr, "qorient plan: line %ld: joint %zu target %.9g clamped to %.9g\n", ln, j + 1,
                        w->r->v[k * w->r->width + j], (double)tr->joints[j].goal);
        }
    }
    return rc;
}

static int emit(struct out *w, qo_traj_ns t)
{
    qo_traj *tr = &w->p->tr;
    size_t n = w->n, j;
    qo_status st;
    int rc = 0;
    if (tr->kind == QO_TRAJ_TARGETS) rc = apply_rows(w, t);
    st = qo_traj_sample(tr, t, w->f, w->f + n, w->f + 2 * n, w->cl);
    if (st != QO_OK && tr->kind == QO_TRAJ_KEYS) rc = 1; /* not reachable for a prepared plan */
    for (j = 0; j < n; j++) w->ncl[j] += w->cl[j] != 0;
    if (!w->o->fixed) {
        print_row(t, n, w->f);
        return rc;
    }
    if (tr->kind == QO_TRAJ_KEYS) {
        st = qo_spline_sample_q16(&w->sq, q16_time(t, tr->t_ns[0]), w->q, w->q + n, w->q + 2 * n, NULL);
    } else {
        if (w->exported != tr->replans || w->mq.n == 0) {
            st = qo_motion_export_q16(&tr->planner, &w->mq, w->segs, sizeof w->segs / sizeof w->segs[0]);
            if (st == QO_E_OVERFLOW && !w->overflow)
                fprintf(stderr, "qorient plan: --fixed: the plan exceeds the Q16.16 range (|x| < 32768, t < "
                        "32768 s)\n");
            if (st == QO_E_OVERFLOW) w->overflow++;
            w->exported = tr->replans;
        }
        st = qo_motion_sample_q16(&w->mq, q16_time(t, tr->origin), w->q, w->q + n, w->q + 2 * n);
    }
    if (st == QO_E_OVERFLOW) w->overflow++;
    print_row_q16(t, n, w->q);
    return rc;
}

/* Rows a targets plan prints: a trial run of the same plan (which also refuses, naming the
 * line, a target state the limits cannot reach, before anything is printed). */
static int targets_rows(const struct qo_cli_plan_opts *o, const struct qo_cli_rows *r, const char *name,
                        double *rows)
{
    qo_traj_ns end = 0;
    int rc = qo_cli_plan_trial("plan", name, o, r, &end);
    if (rc == 0) *rows = ceil((double)(end - r->t[0]) * 1e-9 * o->rate) + 1.0;
    return rc;
}

int qo_cli_plan(int argc, char **argv)
{
    static const struct option opts[] = { QO_CLI_PLAN_OPTIONS, { "help", no_argument, NULL, 'h' },
                                           { NULL, 0, NULL, 0 } };
    struct qo_cli_plan_opts o;
    struct qo_cli_rows r;
    struct qo_cli_plan p;
    struct out w;
    const char *name = "-";
    qo_traj_ns t0, tl, t;
    double i, rows;
    size_t j;
    int c, rc;

    qo_cli_plan_opts_default(&o);
    o.sampled = 1;
    memset(&r, 0, sizeof r);
    memset(&p, 0, sizeof p);
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        if (c == 'h') {
            usage(stdout);
            return 0;
        }
        if (c == '?' || qo_cli_plan_opt("plan", &o, c, optarg) != 0) {
            fputs("qorient plan: see 'qorient plan --help'\n", stderr);
            return 2;
        }
    }
    if (qo_cli_plan_opts_check("plan", &o) != 0) return 2;
    if (optind + 1 < argc) {
        fputs("qorient plan: at most one input file\n", stderr);
        return 2;
    }
    if (optind < argc) name = argv[optind];
    rc = qo_cli_rows_read("plan", &o, name, &r);
    if (rc) goto done;
    t0 = r.t[0];
    tl = r.t[r.rows - 1];
    if (o.motion) {
        rc = targets_rows(&o, &r, name, &rows);
        if (rc) goto done;
    } else {
        rows = qo_cli_grid_rows(t0, tl, o.rate);
    }
    if (rows > o.max_samples) {
        fprintf(stderr, "qorient plan: the plan is %.0f samples at %g Hz, more than --max-samples %.0f: "
                "lower --rate or raise --max-samples\n", rows, o.rate, o.max_samples);
        rc = 1;
        goto done;
    }
    rc = qo_cli_plan_from_rows("plan", name, &o, &r, &p);
    if (rc) goto done;

    memset(&w, 0, sizeof w);
    w.o = &o;
    w.p = &p;
    w.r = &r;
    w.n = p.n;
    w.f = malloc(3 * p.n * sizeof *w.f);
    w.q = malloc(3 * p.n * sizeof *w.q);
    w.cl = malloc(p.n);
    w.ncl = calloc(p.n, sizeof *w.ncl);
    if (!w.f || !w.q || !w.cl || !w.ncl) {
        fputs("qorient plan: out of memory\n", stderr);
        rc = 1;
        goto out;
    }
    if (o.fixed && !o.motion) {
        size_t tn = qo_spline_q16_len(p.n, p.tr.n_keys);
        qo_status st;
        w.table = tn ? malloc(tn * sizeof *w.table) : NULL;
        st = w.table ? qo_spline_export_q16(&p.tr.spline, &w.sq, w.table, tn) : QO_E_CAPACITY;
        if (st != QO_OK) {
            fprintf(stderr, "qorient plan: --fixed: %s\n", qo_status_str(st));
            rc = 1;
            goto out;
        }
    }
    for (i = 0;; i++) {
        t = qo_cli_grid(t0, o.rate, i);
        if (!o.motion && t >= tl) {
            rc |= emit(&w, tl); /* the last key, exactly */
            break;
        }
        rc |= emit(&w, t);
        if (o.motion && w.next_row >= r.rows && qo_traj_done(&p.tr, t)) break;
    }
    for (j = 0; j < p.n; j++)
        if (w.ncl[j])
            fprintf(stderr, "qorient plan: note: joint %zu clamped to its limits in %lu sample(s)\n", j + 1,
                    w.ncl[j]);
    if (w.overflow) {
        fprintf(stderr, "qorient plan: --fixed: %d sample(s) saturated Q16.16\n", w.overflow);
        rc = 1;
    }
out:
    free(w.f);
    free(w.q);
    free(w.cl);
    free(w.ncl);
    free(w.table);
done:
    qo_cli_plan_free(&p);
    qo_cli_rows_free(&r);
    fflush(stdout);
    return rc;
}
