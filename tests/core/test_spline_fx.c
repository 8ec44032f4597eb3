/* Keyframe splines, fixed-point sampler: Q16.16 against the float32 sampler of the same plan
 * (worst difference in LSB, bound from spline_fx.h), against closed forms in double, and the
 * edges (ends, wrap, limits, overflow, order after rounding, storage, NULL, failed table). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <math.h>
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <cmocka.h>

#include "qorient/spline.h"
#include "qorient/spline_fx.h"
#include "common/ref.h"

#define MAXK 12
#define MAXN 4
#define CAP 1024

static uint64_t rng_state;
static uint64_t splitmix64(void) { return ref_splitmix64(&rng_state); } /* tests/common/ref.c */
static double urand(double lo, double hi)
{
    return lo + (hi - lo) * (double)(splitmix64() >> 11) * (1.0 / 9007199254740992.0);
}

static float coef[CAP];
static int32_t table[CAP];

static const qo_spline_profile all_profiles[] = {
    QO_SPLINE_LINEAR, QO_SPLINE_CUBIC_HERMITE, QO_SPLINE_CATMULL_ROM, QO_SPLINE_CUBIC_C2,
    QO_SPLINE_QUINTIC
};
#define NPROF 5

static double lsb(double x) { return x * 65536.0; }

static double coef_sum(const qo_spline_f32 *sp, size_t k, size_t j)
{
    const float *b = sp->coef + sp->n_keys + 3 * sp->n_joints + 6 * (k * sp->n_joints + j);
    double s = 0.0;
    int n;
    for (n = 0; n < 6; n++) s += fabs(b[n]);
    return s;
}

/* Fixed against float for every profile over random plans. exact_times: key times are
 * multiples of 2^-10 s (exact in Q16.16), else arbitrary floats (the key-time rounding term
 * of the bound applies, and samples within 2 LSB of a key skip the derivative orders the
 * profile does not keep continuous). Prints the worst differences in LSB. */
static void fixed_vs_float(int exact_times, uint64_t seed)
{
    size_t pi;
    int trial, i, j;
    double worst_p = 0, worst_v = 0, worst_a = 0;
    rng_state = seed;
    for (trial = 0; trial < 12; trial++) {
        float t[MAXK], p[MAXK * MAXN], v[MAXK * MAXN];
        int K = 2 + trial % 10, N = 4;
        t[0] = (float)urand(-2.0, 2.0);
        if (exact_times) t[0] = floorf(t[0] * 1024.0f) / 1024.0f;
        for (i = 1; i < K; i++) {
            t[i] = t[i - 1] + (float)urand(0.2, 1.0);
            if (exact_times) t[i] = floorf(t[i] * 1024.0f) / 1024.0f;
        }
        for (i = 0; i < K * N; i++) {
            p[i] = (float)urand(-20.0, 20.0);
            v[i] = (float)urand(-20.0, 20.0);
        }
        for (pi = 0; pi < NPROF; pi++) {
            qo_spline_settings_f32 set = qo_spline_settings_default;
            qo_spline_f32 sp;
            qo_spline_q16 fx;
            int order;
            set.profile = all_profiles[pi];
            set.key_vel = v;
            set.end = (trial & 1) ? QO_SPLINE_END_NATURAL : QO_SPLINE_END_CLAMPED;
            assert_int_equal(qo_spline_init_f32((size_t)N, (size_t)K, t, p, &set, coef, CAP, &sp),
                             QO_OK);
            assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_OK);
            order = set.profile == QO_SPLINE_LINEAR ? 0
                  : (set.profile == QO_SPLINE_CUBIC_C2 || set.profile == QO_SPLINE_QUINTIC) ? 2 : 1;
            for (i = 0; i < 300; i++) {
                qo_q16 tq = (qo_q16)lrint(urand(t[0] - 0.1, t[K - 1] + 0.1) * 65536.0);
                float tf = (float)tq / 65536.0f; /* exact: |tq| < 2^24 */
                float pf[MAXN], vf[MAXN], af[MAXN];
                qo_q16 pq[MAXN], vq[MAXN], aq[MAXN];
                size_t seg = 0;
                double h, near = 1e30;
                int k;
                assert_int_equal(qo_spline_sample_f32(&sp, tf, pf, vf, af, NULL), QO_OK);
                assert_int_equal(qo_spline_sample_q16(&fx, tq, pq, vq, aq, NULL), QO_OK);
                for (k = 0; k < K; k++) {
                    if (fabs((double)tf - t[k]) < near) near = fabs((double)tf - t[k]);
                    if (k + 1 < K && tf >= t[k]) seg = (size_t)k;
                }
                h = (double)t[seg + 1] - t[seg];
                for (j = 0; j < N; j++) {
                    double S = coef_sum(&sp, seg, (size_t)j);
                    double fb = 8 * FLT_EPSILON * S; /* float32's own rounding, units */
                    double dp = fabs((double)pq[j] - lsb(pf[j]));
                    double dv = fabs((double)vq[j] - lsb(vf[j]));
                    double da = fabs((double)aq[j] - lsb(af[j]));
                    double shift = exact_times ? 0.0 : 1.0 / 131072.0; /* key-time rounding, s */
                    /* the row's extra fractional bits f, from the documented table layout */
                    int32_t f = table[5 * K + 3 * N + 7 * ((int)seg * N + j) + 6];
                    double g = ldexp(1.0, -f);
                    /* bound of spline_fx.h + float32's own rounding + 1 LSB for the
                     * float-to-LSB comparison itself */
                    double tol_p = 0.5 + 5.5 * g + lsb(fb) + lsb(fabs(vf[j]) * shift) + 1;
                    /* key-time rounding moves the sample by <= shift and changes h by
                     * <= 2 shift (relative 2 shift / h, once for v, twice for a) */
                    double tol_v = 10 * g / h + 0.5 + fabs(lsb(vf[j])) * 0x1p-22 + lsb(5 * fb / h) +
                                   lsb(fabs(af[j]) * shift + fabs(vf[j]) * 2 * shift / h) + 1;
                    double tol_a = 23 * g / (h * h) + 0.5 + fabs(lsb(af[j])) * 0x1p-22 +
                                   lsb(20 * fb / (h * h)) + lsb(4 * 60 * S / (h * h * h) * shift +
                                   fabs(af[j]) * 4 * shift / h) + 1;
                    int skip_v = !exact_times && order < 1 && near < 2.0 / 65536.0;
                    int skip_a = !exact_times && order < 2 && near < 2.0 / 65536.0;
                    if (dp > worst_p) worst_p = dp;
                    if (!skip_v && dv > worst_v) worst_v = dv;
                    if (!skip_a && da > worst_a) worst_a = da;
                    if (dp > tol_p)
                        fail_msg("profile %d trial %d t=%.9g joint %d: pos fixed %.9g float %.9g, "
                                 "%.1f LSB > %.1f", (int)set.profile, trial, (double)tf, j,
                                 pq[j] / 65536.0, (double)pf[j], dp, tol_p);
                    if (!skip_v && dv > tol_v)
                        fail_msg("profile %d trial %d t=%.9g joint %d: vel fixed %.9g float %.9g, "
                                 "%.1f LSB > %.1f", (int)set.profile, trial, (double)tf, j,
                                 vq[j] / 65536.0, (double)vf[j], dv, tol_v);
                    if (!skip_a && da > tol_a)
                        fail_msg("profile %d trial %d t=%.9g joint %d: acc fixed %.9g float %.9g, "
                                 "%.1f LSB > %.1f", (int)set.profile, trial, (double)tf, j,
                                 aq[j] / 65536.0, (double)af[j], da, tol_a);
                }
            }
        }
    }
    print_message("fixed vs float (%s key times): worst |diff| pos %.1f, vel %.1f, acc %.1f LSB\n",
                  exact_times ? "Q16-exact" : "arbitrary", worst_p, worst_v, worst_a);
}

static void test_fixed_vs_float_exact_times(void **state)
{
    (void)state;
    fixed_vs_float(1, 1001);
}

static void test_fixed_vs_float_arbitrary_times(void **state)
{
    (void)state;
    fixed_vs_float(0, 2002);
}

/* Closed forms in double: linear interpolation, and the rest-to-rest quintic
 * p0 + d (10 s^3 - 15 s^4 + 6 s^5) with its derivatives. */
static void test_fixed_vs_closed_form(void **state)
{
    const float t[2] = { 0.5f, 2.5f };
    const float p[2] = { -3.0f, 7.0f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    qo_spline_q16 fx;
    int prof, i;
    (void)state;
    for (prof = 0; prof < 2; prof++) {
        set.profile = prof ? QO_SPLINE_QUINTIC : QO_SPLINE_LINEAR;
        assert_int_equal(qo_spline_init_f32(1, 2, t, p, &set, coef, CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_OK);
        for (i = 0; i <= 2000; i++) {
            qo_q16 tq = (qo_q16)(32768 + i * 65);
            double tt = tq / 65536.0, s = (tt - 0.5) / 2.0, d = 10.0, rp, rv, ra;
            qo_q16 pq, vq, aq;
            if (prof) {
                rp = -3.0 + d * (10 * s * s * s - 15 * s * s * s * s + 6 * pow(s, 5));
                rv = d * (30 * s * s - 60 * s * s * s + 30 * pow(s, 4)) / 2.0;
                ra = d * (60 * s - 180 * s * s + 120 * s * s * s) / 4.0;
            } else {
                rp = -3.0 + d * s;
                rv = d / 2.0;
                ra = 0.0;
            }
            assert_int_equal(qo_spline_sample_q16(&fx, tq, &pq, &vq, &aq, NULL), QO_OK);
            if (fabs(pq - lsb(rp)) > 8 || fabs(vq - lsb(rv)) > 8 || fabs(aq - lsb(ra)) > 8)
                fail_msg("%s t=%.9g: fixed (%.9g %.9g %.9g) vs double (%.9g %.9g %.9g)",
                         prof ? "quintic" : "linear", tt, pq / 65536.0, vq / 65536.0, aq / 65536.0,
                         rp, rv, ra);
        }
    }
}

/* A small move keeps extra fractional bits (f = 12 here: max |b| = 15 * 0.25): the fixed
 * sample is then within 1 LSB of the double closed form in position and velocity. */
static void test_fixed_small_move_precision(void **state)
{
    const float t[2] = { 0.0f, 0.5f };
    const float p[2] = { 0.125f, 0.375f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    qo_spline_q16 fx;
    int i;
    double worst_p = 0, worst_v = 0;
    (void)state;
    set.profile = QO_SPLINE_QUINTIC;
    assert_int_equal(qo_spline_init_f32(1, 2, t, p, &set, coef, CAP, &sp), QO_OK);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_OK);
    assert_int_equal(table[5 * 2 + 3 * 1 + 6], 12); /* f of the only segment */
    for (i = 0; i <= 32768; i += 7) {
        double s = i / 32768.0, d = 0.25, rp, rv;
        qo_q16 pq, vq;
        rp = 0.125 + d * (10 * pow(s, 3) - 15 * pow(s, 4) + 6 * pow(s, 5));
        rv = d * (30 * s * s - 60 * pow(s, 3) + 30 * pow(s, 4)) / 0.5;
        assert_int_equal(qo_spline_sample_q16(&fx, (qo_q16)i, &pq, &vq, NULL, NULL), QO_OK);
        if (fabs(pq - lsb(rp)) > worst_p) worst_p = fabs(pq - lsb(rp));
        if (fabs(vq - lsb(rv)) > worst_v) worst_v = fabs(vq - lsb(rv));
        if (fabs(pq - lsb(rp)) > 1.0 || fabs(vq - lsb(rv)) > 1.0)
            fail_msg("t=%.9g: fixed (%.9g, %.9g) vs double (%.9g, %.9g)", i / 65536.0, pq / 65536.0,
                     vq / 65536.0, rp, rv);
    }
    print_message("small move vs double: worst pos %.2f, vel %.2f LSB\n", worst_p, worst_v);
}

/* Ends, wrap and limits in the fixed sampler. */
static void test_fixed_ends_wrap_limits(void **state)
{
    const float t[3] = { 0.0f, 1.0f, 2.0f };
    const float p[6] = { 3.0f, 0.0f, -3.0f, 5.0f, -2.5f, 1.0f };
    const unsigned char wrap[2] = { 1, 0 };
    const float lo[2] = { -10.0f, -1.0f }, hi[2] = { 10.0f, 4.0f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    qo_spline_q16 fx;
    qo_q16 pos[2], vel[2], acc[2];
    int8_t cl[2];
    int i, seen_clamp = 0;
    (void)state;
    set.wrap = wrap;
    set.pos_min = lo;
    set.pos_max = hi;
    assert_int_equal(qo_spline_init_f32(2, 3, t, p, &set, coef, CAP, &sp), QO_OK);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_OK);
    /* before / after: keys at rest; exact end: last key */
    assert_int_equal(qo_spline_sample_q16(&fx, INT32_MIN, pos, vel, acc, cl), QO_OK);
    assert_int_equal(pos[0], (qo_q16)lrint(3.0 * 65536));
    assert_int_equal(vel[0], 0);
    assert_int_equal(qo_spline_sample_q16(&fx, INT32_MAX, pos, vel, acc, cl), QO_OK);
    assert_int_equal(pos[1], 65536);
    assert_int_equal(vel[1], 0);
    assert_int_equal(acc[1], 0);
    assert_int_equal(qo_spline_sample_q16(&fx, 2 * 65536, pos, vel, acc, cl), QO_OK);
    assert_true(abs(pos[0] - (qo_q16)lrint(-2.5 * 65536)) <= 1);
    for (i = 0; i <= 200; i++) {
        qo_q16 tq = (qo_q16)(i * 65536 / 100);
        float pf[2], vf[2];
        int8_t cf[2];
        assert_int_equal(qo_spline_sample_q16(&fx, tq, pos, vel, acc, cl), QO_OK);
        assert_int_equal(qo_spline_sample_f32(&sp, (float)tq / 65536.0f, pf, vf, NULL, cf), QO_OK);
        /* wrapped joint: in (-pi, pi], near +-pi (the short way), same as float */
        if (!(pos[0] > -205888 && pos[0] <= 205888) || fabs(fabs(pos[0] / 65536.0) - M_PI) > 0.7)
            fail_msg("t=%g: wrapped joint %.9g", tq / 65536.0, pos[0] / 65536.0);
        /* equal, or one period apart when the two land on either side of +-pi */
        if (fabs(pos[0] - lsb(pf[0])) > 16 && fabs(fabs(pos[0] - lsb(pf[0])) - lsb(2 * M_PI)) > 16)
            fail_msg("t=%g: wrapped fixed %.9g float %.9g", tq / 65536.0, pos[0] / 65536.0,
                     (double)pf[0]);
        /* limited joint: the same clamp decision as float (away from the limit itself) */
        if (cl[1] != cf[1] && fabs(pf[1] - hi[1]) > 1e-3 && fabs(pf[1] - lo[1]) > 1e-3)
            fail_msg("t=%g: clamp fixed %d float %d (float pos %.9g)", tq / 65536.0, cl[1], cf[1],
                     (double)pf[1]);
        if (cl[1]) {
            seen_clamp = 1;
            assert_true(pos[1] == (cl[1] > 0 ? 4 * 65536 : -65536));
            assert_int_equal(vel[1], 0);
            assert_int_equal(acc[1], 0);
        }
    }
    assert_true(seen_clamp);
}

/* Conversion and sampling errors. */
static void test_fixed_edges(void **state)
{
    const float t[2] = { 0.0f, 1.0f }, p[2] = { 0.0f, 1.0f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp, empty;
    qo_spline_q16 fx;
    qo_q16 pos = 5, vel = 5, acc = 5;
    int8_t cl = 3;
    size_t need = qo_spline_q16_len(1, 2);
    (void)state;
    set.profile = QO_SPLINE_LINEAR;
    assert_int_equal(need, 10 + 3 + 14);
    assert_int_equal(qo_spline_q16_len(0, 2), 0);
    assert_int_equal(qo_spline_q16_len(1, 1), 0);
    assert_int_equal(qo_spline_q16_len(SIZE_MAX / 4, 4), 0);
    assert_int_equal(qo_spline_init_f32(1, 2, t, p, &set, coef, CAP, &sp), QO_OK);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, need - 1), QO_E_CAPACITY);
    assert_int_equal(fx.n_keys, 0);
    assert_int_equal(qo_spline_sample_q16(&fx, 0, &pos, &vel, &acc, &cl), QO_E_NULL); /* no table */
    assert_true(pos == 0 && vel == 0 && acc == 0 && cl == 0);
    assert_int_equal(qo_spline_export_q16(NULL, &fx, table, CAP), QO_E_NULL);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, NULL, CAP), QO_E_NULL);
    assert_int_equal(qo_spline_export_q16(&sp, NULL, table, CAP), QO_E_NULL);
    assert_int_equal(qo_spline_init_f32(1, 1, t, p, &set, coef, CAP, &empty), QO_E_TOO_FEW);
    assert_int_equal(qo_spline_export_q16(&empty, &fx, table, CAP), QO_E_STATE);
    /* a usable table, then a fake failed one: STATE with zeroed outputs */
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, need), QO_OK);
    assert_int_equal(qo_spline_sample_q16(&fx, 32768, &pos, &vel, &acc, &cl), QO_OK);
    assert_int_equal(pos, 32768);
    assert_int_equal(vel, 65536);
    fx.n_keys = 0;
    assert_int_equal(qo_spline_sample_q16(&fx, 32768, &pos, &vel, &acc, &cl), QO_E_STATE);
    assert_true(pos == 0 && vel == 0 && acc == 0 && cl == 0);
    assert_int_equal(qo_spline_sample_q16(NULL, 0, &pos, &vel, &acc, &cl), QO_E_NULL);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, need), QO_OK);
    vel = 5;
    assert_int_equal(qo_spline_sample_q16(&fx, 0, NULL, &vel, NULL, NULL), QO_E_NULL);
    assert_int_equal(vel, 0);
    /* out of Q16.16: a position, a time; key times that round to the same Q16.16 value */
    {
        const float pbig[2] = { 0.0f, 40000.0f }, tbig[2] = { 0.0f, 40000.0f };
        const float tclose[2] = { 0.0f, 1e-6f };
        assert_int_equal(qo_spline_init_f32(1, 2, t, pbig, &set, coef, CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_E_OVERFLOW);
        assert_int_equal(fx.n_keys, 0);
        assert_int_equal(qo_spline_init_f32(1, 2, tbig, p, &set, coef, CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_E_OVERFLOW);
        assert_int_equal(qo_spline_init_f32(1, 2, tclose, p, &set, coef, CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_E_ORDER);
    }
    /* a velocity beyond Q16.16 (rest-to-rest quintic over 2000 units in 10 ms: peak 3.75e5
     * units/s) saturates and says so; the position is still right */
    {
        const float tf[2] = { 0.0f, 0.01f }, pf[2] = { 0.0f, 2000.0f }, pn[2] = { 0.0f, -2000.0f };
        qo_q16 half = (qo_q16)lrint(0.01 * 65536) / 2; /* s = 0.5 of the rounded segment */
        set.profile = QO_SPLINE_QUINTIC;
        assert_int_equal(qo_spline_init_f32(1, 2, tf, pf, &set, coef, CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_OK);
        assert_int_equal(qo_spline_sample_q16(&fx, half, &pos, &vel, &acc, NULL), QO_E_OVERFLOW);
        assert_int_equal(vel, INT32_MAX);
        {
            double sd = (double)half / (double)lrint(0.01 * 65536);
            double want = 2000.0 * (10 * pow(sd, 3) - 15 * pow(sd, 4) + 6 * pow(sd, 5));
            if (fabs(pos - lsb(want)) > 8)
                fail_msg("saturated-velocity sample: pos %.9g, want %.9g", pos / 65536.0, want);
        }
        assert_int_equal(qo_spline_init_f32(1, 2, tf, pn, &set, coef, CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_OK);
        assert_int_equal(qo_spline_sample_q16(&fx, half, &pos, &vel, NULL, NULL), QO_E_OVERFLOW);
        assert_int_equal(vel, INT32_MIN);
        /* linear: the end state holds the same slope, so the conversion already refuses */
        set.profile = QO_SPLINE_LINEAR;
        assert_int_equal(qo_spline_init_f32(1, 2, tf, pf, &set, coef, CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_E_OVERFLOW);
    }
    /* the shortest segment Q16.16 can hold (1 LSB of time) and a long one (hours) */
    {
        const float ts[3] = { 0.0f, 1.0f / 65536.0f, 20000.0f }, ps[3] = { 0.0f, 0.0f, 1.0f };
        set.profile = QO_SPLINE_CUBIC_C2;
        assert_int_equal(qo_spline_init_f32(1, 3, ts, ps, &set, coef, CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, CAP), QO_OK);
        assert_int_equal(qo_spline_sample_q16(&fx, 10000 * 65536, &pos, &vel, &acc, NULL), QO_OK);
        assert_true(abs(pos - 32768) <= 8);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fixed_vs_float_exact_times),
        cmocka_unit_test(test_fixed_vs_float_arbitrary_times),
        cmocka_unit_test(test_fixed_vs_closed_form),
        cmocka_unit_test(test_fixed_small_move_precision),
        cmocka_unit_test(test_fixed_ends_wrap_limits),
        cmocka_unit_test(test_fixed_edges),
    };
    return cmocka_run_group_tests_name("spline_fx", tests, NULL, NULL);
}
