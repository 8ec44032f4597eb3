/* Keyframe spline sampling: cost per joint per tick (float32 and Q16.16 samplers; median of
 * repeated runs, 7 and 18 joints) and the worst fixed-vs-float difference in LSB.
 *
 *   make build/bench/bench_spline && build/bench/bench_spline
 *
 * The plan: 32 quintic keyframes (every profile samples the same degree-5 Horner, so the
 * cost does not depend on the profile), positions in [-3, 3], key spacing 0.2-1.0 s.
 * Each run samples 20000 ticks at 1 kHz across the whole plan (binary search included). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "qorient/spline.h"
#include "qorient/spline_fx.h"
#include "common/ref.h"
#include "common/linux/bench_clock.h"

#define NK 32
#define MAXJ 18
#define TICKS 20000
#define RUNS 31

static uint64_t rng = 12345;
static double urand(double lo, double hi)
{
    return lo + (hi - lo) * ref_unit_from_bits(ref_splitmix64(&rng)); /* tests/common/ref.c */
}

static float t_keys[NK], p_keys[NK * MAXJ];
static float coef[NK + 3 * MAXJ + 6 * NK * MAXJ];
static int32_t table[5 * NK + 3 * MAXJ + 7 * NK * MAXJ];
static volatile float sink_f;
static volatile int32_t sink_q;

static void make_plan(size_t nj, int exact_times, qo_spline_f32 *sp, qo_spline_table_q16 *fx)
{
    qo_spline_settings_f32 set = qo_spline_settings_default;
    size_t i;
    qo_status st;
    t_keys[0] = 0.0f;
    for (i = 1; i < NK; i++) {
        t_keys[i] = t_keys[i - 1] + (float)urand(0.2, 1.0);
        if (exact_times) t_keys[i] = floorf(t_keys[i] * 1024.0f) / 1024.0f;
    }
    for (i = 0; i < NK * nj; i++) p_keys[i] = (float)urand(-3.0, 3.0);
    set.profile = QO_SPLINE_QUINTIC;
    st = qo_spline_init_f32(nj, NK, t_keys, p_keys, &set, coef, sizeof coef / sizeof coef[0], sp);
    if (st == QO_OK) st = qo_spline_export_q16(sp, fx, table, sizeof table / sizeof table[0]);
    if (st != QO_OK) {
        fprintf(stderr, "bench_spline: plan failed: %s\n", qo_status_str(st));
        exit(1);
    }
}

/* ns per joint per tick of TICKS samples spread over the plan; derivs 0: position only. */
static double time_f32(const qo_spline_f32 *sp, double span, size_t nj, int derivs)
{
    float pos[MAXJ], vel[MAXJ], acc[MAXJ];
    double t0 = bench_now_ns();
    int i;
    for (i = 0; i < TICKS; i++) {
        float t = (float)(span * i / TICKS);
        qo_spline_sample_f32(sp, t, pos, derivs ? vel : NULL, derivs ? acc : NULL, NULL);
        sink_f = pos[nj - 1];
    }
    return (bench_now_ns() - t0) / ((double)TICKS * (double)nj);
}

static double time_q16(const qo_spline_table_q16 *fx, double span, size_t nj, int derivs)
{
    qo_q16 pq[MAXJ], vq[MAXJ], aq[MAXJ];
    double t0 = bench_now_ns();
    int i;
    for (i = 0; i < TICKS; i++) {
        qo_q16 t = (qo_q16)(span * 65536.0 * i / TICKS);
        qo_spline_sample_q16(fx, t, pq, derivs ? vq : NULL, derivs ? aq : NULL, NULL);
        sink_q = pq[nj - 1];
    }
    return (bench_now_ns() - t0) / ((double)TICKS * (double)nj);
}

static void bench(size_t nj)
{
    qo_spline_f32 sp;
    qo_spline_table_q16 fx;
    double tf[RUNS], tq[RUNS], tfp[RUNS], tqp[RUNS], span;
    int r;
    make_plan(nj, 1, &sp, &fx);
    span = t_keys[NK - 1];
    for (r = 0; r < RUNS; r++) {
        tf[r] = time_f32(&sp, span, nj, 1);
        tq[r] = time_q16(&fx, span, nj, 1);
        /* position only (servo setpoints): vel/acc NULL */
        tfp[r] = time_f32(&sp, span, nj, 0);
        tqp[r] = time_q16(&fx, span, nj, 0);
    }
    qsort(tfp, RUNS, sizeof tfp[0], bench_cmp_d);
    qsort(tqp, RUNS, sizeof tqp[0], bench_cmp_d);
    qsort(tf, RUNS, sizeof tf[0], bench_cmp_d);
    qsort(tq, RUNS, sizeof tq[0], bench_cmp_d);
    printf("%2zu joints: float32 %.1f ns/joint/tick (%.0f ns/tick), Q16.16 %.1f ns/joint/tick "
           "(%.0f ns/tick); median of %d runs x %d ticks (min %.1f / %.1f)\n",
           nj, tf[RUNS / 2], tf[RUNS / 2] * (double)nj, tq[RUNS / 2], tq[RUNS / 2] * (double)nj,
           RUNS, TICKS, tf[0], tq[0]);
    printf("%2zu joints, position only: float32 %.1f ns/joint/tick, Q16.16 %.1f ns/joint/tick "
           "(min %.1f / %.1f)\n", nj, tfp[RUNS / 2], tqp[RUNS / 2], tfp[0], tqp[0]);
}

static void accuracy(int exact_times)
{
    qo_spline_f32 sp;
    qo_spline_table_q16 fx;
    double wp = 0, wv = 0, wa = 0;
    int i, trial;
    size_t j;
    for (trial = 0; trial < 20; trial++) {
        make_plan(7, exact_times, &sp, &fx);
        for (i = 0; i < TICKS; i++) {
            qo_q16 t = (qo_q16)((double)t_keys[NK - 1] * 65536.0 * i / TICKS);
            float pf[MAXJ], vf[MAXJ], af[MAXJ];
            qo_q16 pq[MAXJ], vq[MAXJ], aq[MAXJ];
            qo_spline_sample_f32(&sp, (float)t / 65536.0f, pf, vf, af, NULL);
            qo_spline_sample_q16(&fx, t, pq, vq, aq, NULL);
            for (j = 0; j < 7; j++) {
                double dp = fabs((double)pq[j] - (double)pf[j] * 65536.0);
                double dv = fabs((double)vq[j] - (double)vf[j] * 65536.0);
                double da = fabs((double)aq[j] - (double)af[j] * 65536.0);
                if (dp > wp) wp = dp;
                if (dv > wv) wv = dv;
                if (da > wa) wa = da;
            }
        }
    }
    printf("fixed vs float, %s key times (20 plans x 7 joints x %d ticks): worst |diff| "
           "pos %.1f LSB, vel %.1f LSB, acc %.1f LSB (1 LSB = 2^-16 = 1.53e-5 unit)\n",
           exact_times ? "Q16.16-exact" : "arbitrary", TICKS, wp, wv, wa);
}

int main(void)
{
    bench(7);
    bench(18);
    accuracy(1);
    accuracy(0);
    return 0;
}
