/*
 * bench/motion/compare.c - planning time of today's planner against the planner of commit
 * 9bf587d (before issue 11), same cases, one run. Built and run by `make bench-motion`
 * (mk/motion.mk), which extracts the old lib/src/motion.c and its header from git and renames
 * their symbols qo_motion_* -> qoold_motion_* (build/motion_old/).
 *
 * Cases (fixed seed): 7 joints, SCURVE, SYNC_TIME, limits as in issue 11 (vmax U[0.5,5],
 * amax U[1,20], jmax U[10,500], displacement U[-3,3]); "rest": every joint at rest; "moving":
 * every joint in a random state with |v0| <= vmax, |a0| <= amax, |v0 + a0|a0|/(2 jmax)| <= vmax.
 * Each case is planned by both planners alternately, each timed as the best of 5 identical
 * re-plans on the wall clock (the machine is shared: a preempted run says nothing about the
 * code). Prints median, p99 and worst per planner and scenario, and the median of the
 * per-case ratio old / new.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "qorient/motion.h"
#include "qoold/motion.h"
#include "common/ref.h"
#include "common/linux/bench_clock.h"

#ifdef QO_BENCH_CALLGRIND
#include <valgrind/callgrind.h>
#else
#define CALLGRIND_ZERO_STATS
#define CALLGRIND_DUMP_STATS
#endif

#define NJ 7
#if defined(__GNUC__)
#define NOINLINE __attribute__((noinline))
#else
#define NOINLINE
#endif
#define REPS 5

typedef struct bcase {
    float vmax[NJ], amax[NJ], jmax[NJ], p0[NJ], v0[NJ], a0[NJ], tg[NJ];
} bcase;

static void make_case(ref_rng *g, int moving, bcase *c)
{
    int i;
    for (i = 0; i < NJ; i++) {
        c->vmax[i] = (float)ref_rng_range(g, 0.5, 5.0);
        c->amax[i] = (float)ref_rng_range(g, 1.0, 20.0);
        c->jmax[i] = (float)ref_rng_range(g, 10.0, 500.0);
        c->p0[i] = (float)ref_rng_range(g, -2.0, 2.0);
        c->v0[i] = c->a0[i] = 0.0f;
        while (moving) {
            double v = ref_rng_range(g, -1.0, 1.0) * c->vmax[i], a = ref_rng_range(g, -1.0, 1.0) * c->amax[i];
            if (fabs(v + a * fabs(a) / (2.0 * c->jmax[i])) <= c->vmax[i]) {
                c->v0[i] = (float)v;
                c->a0[i] = (float)a;
                break;
            }
        }
        c->tg[i] = (float)(c->p0[i] + ref_rng_range(g, -3.0, 3.0));
    }
}

/* The same body for both planners (PFX selects the API): init, put each joint in its state (one
 * long constant-jerk-free phase, as a previous plan would leave it); NAME##_plan plans it with
 * set_target at t = 0 (kept out of line: make bench-motion-ir counts its instructions alone). */
#define DEFINE_PLANNER(NAME, PFX)                                                                   \
    typedef struct NAME##_ctx {                                                                     \
        PFX##_planner_f32 pl;                                                                       \
        PFX##_joint_f32 jts[NJ];                                                                    \
        PFX##_limits_f32 l[NJ];                                                                     \
    } NAME##_ctx;                                                                                   \
    static int NAME##_setup(NAME##_ctx *x, const bcase *c)                                          \
    {                                                                                               \
        int i;                                                                                      \
        for (i = 0; i < NJ; i++) {                                                                  \
            x->l[i] = PFX##_limits_default;                                                         \
            x->l[i].vmax = c->vmax[i];                                                              \
            x->l[i].amax = c->amax[i];                                                              \
            x->l[i].jmax = c->jmax[i];                                                              \
        }                                                                                           \
        if (PFX##_init_f32(&x->pl, x->jts, NJ, x->l, c->p0, 0.0f, NULL) != QO_OK) return 0;         \
        for (i = 0; i < NJ; i++) {                                                                  \
            x->jts[i].nph = 1;                                                                      \
            x->jts[i].ph[0].t = 0.0f;                                                               \
            x->jts[i].ph[0].d = x->jts[i].duration = 1e6f;                                          \
            x->jts[i].ph[0].p = x->jts[i].final = c->p0[i];                                         \
            x->jts[i].ph[0].v = c->v0[i];                                                           \
            x->jts[i].ph[0].a = c->a0[i];                                                           \
            x->jts[i].ph[0].j = 0.0f;                                                               \
        }                                                                                           \
        return 1;                                                                                   \
    }                                                                                               \
    int NAME##_plan(NAME##_ctx *x, const bcase *c);                                                 \
    NOINLINE int NAME##_plan(NAME##_ctx *x, const bcase *c)                                         \
    {                                                                                               \
        return PFX##_set_target_f32(&x->pl, 0.0f, c->tg, NULL) == QO_OK;                            \
    }                                                                                               \
    static double NAME(const bcase *c, float *dur)                                                  \
    {                                                                                               \
        NAME##_ctx x;                                                                               \
        double best = INFINITY;                                                                     \
        int r;                                                                                      \
        for (r = 0; r < REPS; r++) {                                                                \
            double t0;                                                                              \
            if (!NAME##_setup(&x, c)) return -1.0;                                                  \
            t0 = bench_now_ns();                                                                    \
            if (!NAME##_plan(&x, c)) return -1.0;                                                   \
            t0 = bench_now_ns() - t0;                                                               \
            if (t0 < best) best = t0;                                                               \
        }                                                                                           \
        *dur = x.pl.duration;                                                                       \
        return best;                                                                                \
    }
DEFINE_PLANNER(time_new, qo_motion)
DEFINE_PLANNER(time_old, qoold_motion)

static void report(const char *name, double *x, int n)
{
    qsort(x, (size_t)n, sizeof *x, bench_cmp_d);
    printf("  %-26s median %6.0f ns  p99 %6.0f ns  worst %7.0f ns\n", name, x[n / 2], x[(int)(0.99 * (n - 1))], x[n - 1]);
}

/* --ir N: each case planned once by each planner (new, then old, per case; rest then moving),
 * the instructions of each plan dumped by callgrind as one part (built with -DQO_BENCH_CALLGRIND
 * as build/bench/motion_ir and run by make bench-motion-ir). */
static int run_ir(int n)
{
    int moving, k;
    for (moving = 0; moving < 2; moving++) {
        ref_rng g;
        g.s = 20261127u + (unsigned)moving;
        for (k = 0; k < n; k++) {
            bcase c;
            time_new_ctx xn;
            time_old_ctx xo;
            make_case(&g, moving, &c);
            if (!time_new_setup(&xn, &c) || !time_old_setup(&xo, &c)) return 1;
            CALLGRIND_ZERO_STATS;
            if (!time_new_plan(&xn, &c)) return 1;
            CALLGRIND_DUMP_STATS;
            CALLGRIND_ZERO_STATS;
            if (!time_old_plan(&xo, &c)) return 1;
            CALLGRIND_DUMP_STATS;
        }
    }
    return 0;
}

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[argc - 1]) : 20000, moving;
    double *tn, *to, *ratio;
    if (argc > 2 && strcmp(argv[1], "--ir") == 0) return run_ir(n);
    tn = malloc(sizeof(double) * (size_t)n);
    to = malloc(sizeof(double) * (size_t)n);
    ratio = malloc(sizeof(double) * (size_t)n);
    if (!tn || !to || !ratio || n < 1) return 1;
    printf("motion planning, 7 joints, SCURVE, SYNC_TIME, %d cases per scenario, best of %d per case\n", n, REPS);
    for (moving = 0; moving < 2; moving++) {
        ref_rng g;
        int k, slower = 0, faster = 0;
        char name[64];
        g.s = 20261127u + (unsigned)moving;
        for (k = 0; k < n; k++) {
            bcase c;
            float dn, dold;
            make_case(&g, moving, &c);
            /* alternate which planner goes first, so neither always gets the warm cache */
            if (k & 1) {
                to[k] = time_old(&c, &dold);
                tn[k] = time_new(&c, &dn);
            } else {
                tn[k] = time_new(&c, &dn);
                to[k] = time_old(&c, &dold);
            }
            if (tn[k] < 0.0 || to[k] < 0.0) {
                printf("case %d refused\n", k);
                return 1;
            }
            ratio[k] = to[k] / tn[k];
            if (dn > dold * 1.001f) slower++;
            if (dn < dold * 0.999f) faster++;
        }
        printf("from %s:\n", moving ? "moving starts" : "rest");
        snprintf(name, sizeof name, "today (this tree)");
        report(name, tn, n);
        snprintf(name, sizeof name, "before (9bf587d)");
        report(name, to, n);
        qsort(ratio, (size_t)n, sizeof *ratio, bench_cmp_d);
        printf("  per-case speed-up old/new: median %.2fx, p1 %.2fx\n", ratio[n / 2], ratio[n / 100]);
        printf("  plan durations: %d shorter than before by > 0.1 %%, %d longer\n", faster, slower);
    }
    free(tn);
    free(to);
    free(ratio);
    return 0;
}
