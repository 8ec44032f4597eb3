/*
 * qo_traj_*: the trajectory object. Keyframes are checked against double-precision
 * interpolation written here (linear, cubic Hermite); targets against the motion planner
 * driven by hand at small float32 times, and both against themselves shifted to t = 1e7 s
 * (the integer time scheme must make the absolute offset invisible). Fixed seeds; edges:
 * empty, one key, full storage, NaN/Inf, times not increasing, before start / after end,
 * times beyond the documented range, NULL and uninitialised objects. Duration rules
 * (qo_traj_set_timing): whole periods, minimum duration, refused values.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "qorient/traj.h"
#include "common/ref.h"

#define NJ 3
#define CAP 16
#define S (QO_TRAJ_NS_PER_S)
#define BIG ((qo_traj_ns)10000000 * S) /* t = 1e7 s */

static ref_rng rng;
static uint64_t rng_next(void) { return ref_rng_next(&rng); }
static double urand(double lo, double hi) { return ref_rng_range(&rng, lo, hi); }

struct keys_fix {
    qo_traj tr;
    qo_traj_ns t[CAP];
    float store[4096];
};

static void init_keys(struct keys_fix *f, qo_spline_profile prof, unsigned cols)
{
    qo_spline_settings_f32 set = qo_spline_settings_default;
    set.profile = prof;
    assert_int_equal(qo_traj_store_len(QO_TRAJ_KEYS, NJ, CAP, cols) <= 4096, 1);
    assert_int_equal(qo_traj_init_keys(&f->tr, NJ, &set, cols, f->t, CAP, f->store, 4096), QO_OK);
}

/* Random keys: times in ns, positions and velocities in double for the references. */
struct keyset {
    size_t k;
    qo_traj_ns t[CAP];
    double p[CAP][NJ], v[CAP][NJ];
};

static void make_keys(struct keyset *ks, size_t k, qo_traj_ns base)
{
    size_t i, j;
    qo_traj_ns t = base;
    ks->k = k;
    for (i = 0; i < k; i++) {
        ks->t[i] = t;
        t += (qo_traj_ns)(urand(0.05, 3.0) * 1e9);
        for (j = 0; j < NJ; j++) {
            ks->p[i][j] = (float)urand(-10.0, 10.0);
            ks->v[i][j] = (float)urand(-5.0, 5.0);
        }
    }
}

static void push_keys(struct keys_fix *f, const struct keyset *ks, unsigned cols)
{
    size_t i, j;
    for (i = 0; i < ks->k; i++) {
        float p[NJ], v[NJ];
        for (j = 0; j < NJ; j++) { p[j] = (float)ks->p[i][j]; v[j] = (float)ks->v[i][j]; }
        assert_int_equal(qo_traj_push(&f->tr, ks->t[i], p, cols >= 2 ? v : NULL, NULL), QO_OK);
    }
}

/* Double reference: linear or cubic Hermite through the keys, at rest outside. */
static void ref_keys(const struct keyset *ks, int hermite, qo_traj_ns t, double *p, double *v)
{
    size_t i, j;
    if (t < ks->t[0] || t >= ks->t[ks->k - 1]) {
        size_t e = t < ks->t[0] ? 0 : ks->k - 1;
        for (j = 0; j < NJ; j++) { p[j] = ks->p[e][j]; v[j] = 0.0; }
        if (t == ks->t[ks->k - 1] && ks->k > 1) {
            /* at the last key: the end velocity of the last segment */
            double h = (double)(ks->t[e] - ks->t[e - 1]) * 1e-9;
            for (j = 0; j < NJ; j++) v[j] = hermite ? ks->v[e][j] : (ks->p[e][j] - ks->p[e - 1][j]) / h;
        }
        return;
    }
    for (i = 0; i + 1 < ks->k && ks->t[i + 1] <= t; i++) {}
    {
        double h = (double)(ks->t[i + 1] - ks->t[i]) * 1e-9, s = (double)(t - ks->t[i]) * 1e-9 / h;
        for (j = 0; j < NJ; j++) {
            double p0 = ks->p[i][j], p1 = ks->p[i + 1][j];
            if (!hermite) {
                p[j] = p0 + s * (p1 - p0);
                v[j] = (p1 - p0) / h;
            } else {
                double m0 = ks->v[i][j] * h, m1 = ks->v[i + 1][j] * h, s2 = s * s, s3 = s2 * s;
                p[j] = (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 +
                       (s3 - s2) * m1;
                v[j] = ((6 * s2 - 6 * s) * p0 + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * p1 +
                        (3 * s2 - 2 * s) * m1) / h;
            }
        }
    }
}

static void check_keys_vs_ref(int hermite, qo_traj_ns base, uint64_t seed)
{
    static struct keys_fix f;
    struct keyset ks;
    int c, i;
    rng.s = seed;
    for (c = 0; c < 50; c++) {
        size_t k = 2 + (size_t)(rng_next() % (CAP - 1));
        qo_traj_ns end;
        make_keys(&ks, k, base);
        init_keys(&f, hermite ? QO_SPLINE_CUBIC_HERMITE : QO_SPLINE_LINEAR, hermite ? 2 : 1);
        push_keys(&f, &ks, hermite ? 2 : 1);
        assert_int_equal(qo_traj_prepare(&f.tr), QO_OK);
        assert_int_equal(qo_traj_end_time(&f.tr, &end), QO_OK);
        assert_true(end == ks.t[k - 1]);
        for (i = 0; i < 200; i++) {
            qo_traj_ns t = ks.t[0] - S + (qo_traj_ns)(urand(0.0, 1.0) * (double)(end - ks.t[0] + 2 * S));
            float p[NJ], v[NJ], a[NJ];
            double rp[NJ], rv[NJ];
            size_t j;
            if (i == 0) t = ks.t[0];
            if (i == 1) t = end;
            assert_int_equal(qo_traj_sample(&f.tr, t, p, v, a, NULL), QO_OK);
            ref_keys(&ks, hermite, t, rp, rv);
            for (j = 0; j < NJ; j++) {
                /* float32 time relative to the first key: ulp(45 s) ~ 4e-6 s, times |v| <= ~400 */
                double tol_p = 2e-5 * (1.0 + fabs(rp[j])) + 4e-6 * fabs(rv[j]);
                if (fabs(p[j] - rp[j]) > tol_p || fabs(v[j] - rv[j]) > 1e-3 * (1.0 + fabs(rv[j])) + 1e-2) {
                    fprintf(stderr, "case %d seed %llu base %lld t %lld joint %zu: p %.9g ref %.9g, v %.9g ref %.9g\n",
                            c, (unsigned long long)seed, (long long)base, (long long)t, j, (double)p[j], rp[j],
                            (double)v[j], rv[j]);
                    fail();
                }
            }
            assert_int_equal(qo_traj_done(&f.tr, t), t >= end);
        }
    }
}

static void test_keys_linear_ref(void **state) { (void)state; check_keys_vs_ref(0, 0, 11); }
static void test_keys_hermite_ref(void **state) { (void)state; check_keys_vs_ref(1, 0, 12); }
static void test_keys_linear_ref_1e7(void **state) { (void)state; check_keys_vs_ref(0, BIG, 11); }
static void test_keys_hermite_ref_1e7(void **state) { (void)state; check_keys_vs_ref(1, BIG, 12); }

/* The same keys at base 0 and at 1e7 s give bit-identical samples for every profile (the
 * spline sees only offsets from the first key); the naive float32 absolute time could not. */
static void test_keys_time_invariant(void **state)
{
    static struct keys_fix f0, f1;
    struct keyset k0, k1;
    int prof, i;
    (void)state;
    for (prof = QO_SPLINE_LINEAR; prof <= QO_SPLINE_QUINTIC; prof++) {
        unsigned cols = prof == QO_SPLINE_CUBIC_HERMITE ? 2 : 1;
        rng.s = 21;
        make_keys(&k0, 9, 0);
        rng.s = 21;
        make_keys(&k1, 9, BIG);
        init_keys(&f0, (qo_spline_profile)prof, cols);
        init_keys(&f1, (qo_spline_profile)prof, cols);
        push_keys(&f0, &k0, cols);
        push_keys(&f1, &k1, cols);
        for (i = 0; i < 500; i++) {
            qo_traj_ns dt = (qo_traj_ns)(urand(-1.0, 30.0) * 1e9);
            float p0[NJ], v0[NJ], a0[NJ], p1[NJ], v1[NJ], a1[NJ];
            assert_int_equal(qo_traj_sample(&f0.tr, dt, p0, v0, a0, NULL), QO_OK);
            assert_int_equal(qo_traj_sample(&f1.tr, BIG + dt, p1, v1, a1, NULL), QO_OK);
            assert_memory_equal(p0, p1, sizeof p0);
            assert_memory_equal(v0, v1, sizeof v0);
            assert_memory_equal(a0, a1, sizeof a0);
        }
    }
}

/* Same samples as planning the spline directly with float offsets (the traj adds nothing). */
static void test_keys_vs_spline_direct(void **state)
{
    static struct keys_fix f;
    struct keyset ks;
    float tr_[CAP], pk[CAP * NJ], coef[2048];
    qo_spline_f32 sp;
    size_t i, j;
    (void)state;
    rng.s = 31;
    make_keys(&ks, 7, 5 * S);
    init_keys(&f, QO_SPLINE_CUBIC_C2, 1);
    push_keys(&f, &ks, 1);
    for (i = 0; i < ks.k; i++) {
        tr_[i] = (float)((double)(ks.t[i] - ks.t[0]) * 1e-9);
        for (j = 0; j < NJ; j++) pk[i * NJ + j] = (float)ks.p[i][j];
    }
    assert_int_equal(qo_spline_init_f32(NJ, ks.k, tr_, pk, &qo_spline_settings_default, coef, 2048, &sp), QO_OK);
    for (i = 0; i < 300; i++) {
        qo_traj_ns t = ks.t[0] + (qo_traj_ns)(i * 50000000LL);
        float p[NJ], v[NJ], rp[NJ], rv[NJ];
        assert_int_equal(qo_traj_sample(&f.tr, t, p, v, NULL, NULL), QO_OK);
        qo_spline_sample_f32(&sp, (float)((double)(t - ks.t[0]) * 1e-9), rp, rv, NULL, NULL);
        for (j = 0; j < NJ; j++) {
            assert_float_equal(p[j], rp[j], 1e-5 * (1.0 + fabs(rp[j])));
            assert_float_equal(v[j], rv[j], 1e-4 * (1.0 + fabs(rv[j])));
        }
    }
}

static void test_keys_edges(void **state)
{
    static struct keys_fix f;
    float p[NJ] = { 1, 2, 3 }, o[NJ], v[NJ], a[NJ], nan_p[NJ] = { 0, NAN, 0 }, inf_p[NJ] = { INFINITY, 0, 0 };
    int8_t cl[NJ];
    qo_traj_ns end;
    size_t i;
    (void)state;
    init_keys(&f, QO_SPLINE_CUBIC_C2, 1);
    assert_int_equal(qo_traj_joints(&f.tr), NJ);
    /* empty */
    memset(o, 0x7f, sizeof o);
    assert_int_equal(qo_traj_sample(&f.tr, 0, o, v, a, cl), QO_E_TOO_FEW);
    assert_true(o[0] == 0.0f && v[1] == 0.0f && a[2] == 0.0f && cl[0] == 0);
    assert_int_equal(qo_traj_prepare(&f.tr), QO_E_TOO_FEW);
    assert_int_equal(qo_traj_end_time(&f.tr, &end), QO_E_TOO_FEW);
    assert_true(end == 0);
    assert_int_equal(qo_traj_done(&f.tr, 0), 1);
    /* one key: held at rest before, at and after it */
    assert_int_equal(qo_traj_push(&f.tr, BIG, p, NULL, NULL), QO_OK);
    for (i = 0; i < 3; i++) {
        qo_traj_ns t = BIG + ((qo_traj_ns)i - 1) * S;
        assert_int_equal(qo_traj_sample(&f.tr, t, o, v, a, NULL), QO_OK);
        assert_memory_equal(o, p, sizeof p);
        assert_true(v[0] == 0.0f && a[0] == 0.0f);
    }
    /* NaN / Inf / not increasing / beyond the time range: refused, nothing stored */
    assert_int_equal(qo_traj_push(&f.tr, BIG + S, nan_p, NULL, NULL), QO_E_NONFINITE);
    assert_int_equal(qo_traj_push(&f.tr, BIG + S, inf_p, NULL, NULL), QO_E_NONFINITE);
    assert_int_equal(qo_traj_push(&f.tr, BIG, p, NULL, NULL), QO_E_ORDER);
    assert_int_equal(qo_traj_push(&f.tr, BIG - 1, p, NULL, NULL), QO_E_ORDER);
    assert_int_equal(qo_traj_push(&f.tr, QO_TRAJ_TIME_MAX + 1, p, NULL, NULL), QO_E_RANGE);
    /* 1 ns after the first key at an offset of 0: distinct in float32? 1e-9 s is, so accepted */
    assert_int_equal(qo_traj_push(&f.tr, BIG + 1, p, NULL, NULL), QO_OK);
    assert_int_equal(f.tr.n_keys, 2);
    /* an offset that rounds to the previous one in float32 (1e4 s + 1 ns) is refused */
    assert_int_equal(qo_traj_push(&f.tr, BIG + 10000 * S, p, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, BIG + 10000 * S + 1, p, NULL, NULL), QO_E_ORDER);
    assert_int_equal(qo_traj_push(&f.tr, BIG, NULL, NULL, NULL), QO_E_NULL);
    /* full */
    for (i = f.tr.n_keys; i < CAP; i++)
        assert_int_equal(qo_traj_push(&f.tr, BIG + (qo_traj_ns)(10001 + i) * S, p, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, BIG + 20000 * S, p, NULL, NULL), QO_E_CAPACITY);
    assert_int_equal(f.tr.n_keys, CAP);
    /* t outside the time range: first key at rest, QO_E_RANGE */
    memset(o, 0, sizeof o);
    assert_int_equal(qo_traj_sample(&f.tr, QO_TRAJ_TIME_MAX + 5, o, v, a, NULL), QO_E_RANGE);
    assert_memory_equal(o, p, sizeof p);
    /* NULLs and not initialised */
    assert_int_equal(qo_traj_sample(&f.tr, 0, NULL, v, a, NULL), QO_E_NULL);
    assert_int_equal(qo_traj_sample(NULL, 0, o, v, a, NULL), QO_E_NULL);
    assert_int_equal(qo_traj_end_time(NULL, &end), QO_E_NULL);
    assert_int_equal(qo_traj_end_time(&f.tr, NULL), QO_E_NULL);
    assert_int_equal(qo_traj_joints(NULL), 0);
    assert_int_equal(qo_traj_done(NULL, 0), 1);
    assert_int_equal(qo_traj_init_keys(&f.tr, NJ, NULL, 1, f.t, CAP, f.store, 10), QO_E_CAPACITY);
    assert_int_equal(qo_traj_joints(&f.tr), 0);
    memset(o, 0x7f, sizeof o);
    assert_int_equal(qo_traj_sample(&f.tr, 0, o, NULL, NULL, NULL), QO_E_STATE);
    assert_int_equal(qo_traj_push(&f.tr, 0, p, NULL, NULL), QO_E_STATE);
    assert_int_equal(qo_traj_init_keys(&f.tr, 0, NULL, 1, f.t, CAP, f.store, 4096), QO_E_TOO_FEW);
    assert_int_equal(qo_traj_init_keys(&f.tr, NJ, NULL, 1, f.t, 1, f.store, 4096), QO_E_TOO_FEW);
    assert_int_equal(qo_traj_init_keys(&f.tr, NJ, NULL, 4, f.t, CAP, f.store, 4096), QO_E_ARG);
    assert_int_equal(qo_traj_init_keys(&f.tr, NJ, NULL, 1, NULL, CAP, f.store, 4096), QO_E_NULL);
    {
        qo_spline_settings_f32 set = qo_spline_settings_default;
        set.profile = QO_SPLINE_CUBIC_HERMITE;
        assert_int_equal(qo_traj_init_keys(&f.tr, NJ, &set, 1, f.t, CAP, f.store, 4096), QO_E_ARG);
    }
    /* a plan the spline refuses (a step of 1e30 in 1 s): the error from sample, first key held */
    init_keys(&f, QO_SPLINE_LINEAR, 1);
    {
        float big[NJ] = { 1e30f, 0, 0 };
        assert_int_equal(qo_traj_push(&f.tr, 0, p, NULL, NULL), QO_OK);
        assert_int_equal(qo_traj_push(&f.tr, S / 1000, big, NULL, NULL), QO_OK);
        assert_int_equal(qo_traj_prepare(&f.tr), QO_E_RANGE);
        assert_int_equal(qo_traj_sample(&f.tr, S / 2000, o, v, a, NULL), QO_E_RANGE);
        assert_memory_equal(o, p, sizeof p);
        assert_true(v[0] == 0.0f && a[0] == 0.0f);
    }
    /* seconds to ns */
    assert_int_equal(qo_traj_ns_from_s(10000000.5, &end), QO_OK);
    assert_true(end == BIG + S / 2);
    assert_int_equal(qo_traj_ns_from_s(-0.25, &end), QO_OK);
    assert_true(end == -S / 4);
    assert_int_equal(qo_traj_ns_from_s(NAN, &end), QO_E_NONFINITE);
    assert_true(end == 0);
    assert_int_equal(qo_traj_ns_from_s(1e39, &end), QO_E_RANGE);
    assert_int_equal(qo_traj_ns_from_s(-INFINITY, &end), QO_E_NONFINITE);
    assert_int_equal(qo_traj_ns_from_s(1.0, NULL), QO_E_NULL);
}

/* ---- targets ---- */

struct tgt_fix {
    qo_traj tr;
    qo_traj_ns t[CAP];
    float store[CAP * NJ];
    qo_motion_joint_f32 joints[NJ];
    qo_motion_limits_f32 lim[NJ];
};

static void init_targets(struct tgt_fix *f, qo_motion_profile prof)
{
    qo_motion_settings_f32 set = qo_motion_settings_default;
    size_t j;
    set.profile = prof;
    for (j = 0; j < NJ; j++) {
        f->lim[j] = qo_motion_limits_default;
        f->lim[j].vmax = 2.0f + (float)j;
        f->lim[j].amax = 4.0f;
        f->lim[j].jmax = 20.0f;
    }
    assert_int_equal(qo_traj_init_targets(&f->tr, NJ, f->lim, &set, f->joints, f->t, CAP, f->store,
                                          CAP * NJ), QO_OK);
}

/* The traj against the planner driven by hand (re-plan at each target time, times relative
 * to the last re-plan, exactly what the header promises), at base 0 and 1e7 s; and at the end
 * every joint at rest on its last target. Targets arrive while the motion runs (pushed
 * between samples: the live case). */
static void check_targets(qo_motion_profile prof, qo_traj_ns base, uint64_t seed)
{
    static struct tgt_fix f;
    int c;
    rng.s = seed;
    for (c = 0; c < 30; c++) {
        qo_motion_planner_f32 pl;
        qo_motion_joint_f32 jj[NJ];
        qo_motion_settings_f32 set = qo_motion_settings_default;
        float start[NJ], tg[NJ], p[NJ], v[NJ], a[NJ], rp[NJ], rv[NJ], ra[NJ];
        qo_traj_ns t, next_target, origin = base, dt = 10 * 1000000LL; /* 10 ms ticks */
        int n_targets = 1 + (int)(rng_next() % 6), sent = 0, guard = 0;
        size_t j;
        init_targets(&f, prof);
        set.profile = prof;
        for (j = 0; j < NJ; j++) start[j] = (float)urand(-5, 5);
        assert_int_equal(qo_traj_push(&f.tr, base, start, NULL, NULL), QO_OK);
        assert_int_equal(qo_motion_init_f32(&pl, jj, NJ, f.lim, start, 0.0f, &set), QO_OK);
        next_target = base + (qo_traj_ns)(urand(0.0, 1.0) * 1e9);
        for (t = base; guard < 100000; t += dt, guard++) {
            if (sent < n_targets && t >= next_target) {
                /* every other target arrives late, stamped before the last tick sampled: it
                 * must start from the last sampled state, not rewrite the past */
                qo_traj_ns tp = next_target - (rng_next() % 2 ? 2 * dt : 0), at;
                qo_traj_ns last = t > base ? t - dt : base;
                for (j = 0; j < NJ; j++) tg[j] = (float)urand(-10, 10);
                assert_int_equal(qo_traj_push(&f.tr, tp, tg, NULL, NULL), QO_OK);
                /* the reference: the planner re-planned by hand at max(stamp, last sample) */
                at = tp > last ? tp : last;
                qo_motion_shift_time_f32(&pl, (float)((double)(at - origin) * 1e-9));
                origin = at;
                assert_int_equal(qo_motion_set_target_f32(&pl, 0.0f, tg, NULL), QO_OK);
                sent++;
                next_target = t + (qo_traj_ns)(urand(0.05, 2.0) * 1e9);
            }
            assert_int_equal(qo_traj_sample(&f.tr, t, p, v, a, NULL), QO_OK);
            qo_motion_sample_f32(&pl, (float)((double)(t - origin) * 1e-9), rp, rv, ra);
            for (j = 0; j < NJ; j++) {
                if (fabsf(p[j] - rp[j]) > 1e-5f * (1.0f + fabsf(rp[j])) || fabsf(v[j] - rv[j]) > 1e-4f) {
                    fprintf(stderr, "case %d seed %llu t %lld joint %zu: p %.9g ref %.9g v %.9g ref %.9g\n", c,
                            (unsigned long long)seed, (long long)(t - base), j, (double)p[j], (double)rp[j],
                            (double)v[j], (double)rv[j]);
                    fail();
                }
            }
            if (sent == n_targets && qo_traj_done(&f.tr, t)) break;
        }
        assert_true(guard < 100000);
        assert_int_equal(f.tr.replans, (unsigned long)n_targets);
        for (j = 0; j < NJ; j++) {
            assert_float_equal(p[j], tg[j], 1e-4 * (1.0 + fabs(tg[j])));
            assert_true(v[j] == 0.0f && a[j] == 0.0f);
        }
    }
}

static void test_targets_vs_planner(void **state)
{
    (void)state;
    check_targets(QO_MOTION_SCURVE, 0, 41);
    check_targets(QO_MOTION_TRAPEZOID, 0, 42);
}

static void test_targets_vs_planner_1e7(void **state)
{
    (void)state;
    check_targets(QO_MOTION_SCURVE, BIG, 41);
    check_targets(QO_MOTION_TRAPEZOID, BIG + 123456789, 42);
}

/* Targets queued ahead of time and a target due between samples: continuity (no jump in p or
 * v beyond what the limits allow over one tick), checked by a double finite-difference bound. */
static void test_targets_queue_continuity(void **state)
{
    static struct tgt_fix f;
    float p0[NJ] = { 0, 0, 0 }, p[NJ], v[NJ], a[NJ], pp[NJ], pv[NJ];
    qo_traj_ns t, end, dt = 1000000; /* 1 ms */
    size_t j, i;
    int first = 1;
    (void)state;
    init_targets(&f, QO_MOTION_SCURVE);
    assert_int_equal(qo_traj_push(&f.tr, BIG, p0, NULL, NULL), QO_OK);
    for (i = 1; i <= 5; i++) {
        float tg[NJ];
        for (j = 0; j < NJ; j++) tg[j] = (float)((double)i * (j + 1) * (i % 2 ? 1.0 : -0.5));
        /* 0.3337 s apart: never on a tick */
        assert_int_equal(qo_traj_push(&f.tr, BIG + (qo_traj_ns)i * 333700000LL, tg, NULL, NULL), QO_OK);
    }
    assert_int_equal(qo_traj_done(&f.tr, BIG + 1000 * S), 0); /* queued: not done */
    for (t = BIG; !qo_traj_done(&f.tr, t); t += dt) {
        assert_int_equal(qo_traj_sample(&f.tr, t, p, v, a, NULL), QO_OK);
        for (j = 0; j < NJ; j++) {
            assert_true(fabsf(v[j]) <= f.lim[j].vmax * 1.0001f && fabsf(a[j]) <= f.lim[j].amax * 1.0001f);
            if (!first) {
                double dtp = 1e-3 * f.lim[j].vmax * 1.001 + 1e-5;
                double dtv = 1e-3 * f.lim[j].amax * 1.001 + 1e-5;
                assert_true(fabs((double)p[j] - pp[j]) <= dtp);
                assert_true(fabs((double)v[j] - pv[j]) <= dtv);
            }
            pp[j] = p[j];
            pv[j] = v[j];
        }
        first = 0;
        assert_true(t < BIG + 100 * S);
    }
    assert_int_equal(f.tr.replans, 5);
    assert_int_equal(qo_traj_end_time(&f.tr, &end), QO_OK);
    assert_true(end <= t && end > t - dt - 1);
}

static void test_targets_edges(void **state)
{
    static struct tgt_fix f;
    float p[NJ] = { 1, -2, 3 }, o[NJ], v[NJ], a[NJ], nan_p[NJ] = { NAN, 0, 0 }, huge[NJ] = { 1e19f, 0, 0 };
    int8_t cl[NJ] = { 5, 5, 5 };
    qo_traj_ns end;
    size_t i;
    (void)state;
    init_targets(&f, QO_MOTION_SCURVE);
    /* empty */
    memset(o, 0x7f, sizeof o);
    assert_int_equal(qo_traj_sample(&f.tr, 0, o, v, a, cl), QO_E_TOO_FEW);
    assert_true(o[0] == 0.0f && v[0] == 0.0f && cl[0] == 0);
    assert_int_equal(qo_traj_end_time(&f.tr, &end), QO_E_TOO_FEW);
    assert_int_equal(qo_traj_done(&f.tr, 0), 1);
    assert_int_equal(qo_traj_prepare(&f.tr), QO_E_TOO_FEW);
    /* start only: at rest there, before, at and long after */
    assert_int_equal(qo_traj_push(&f.tr, BIG, p, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_prepare(&f.tr), QO_OK);
    for (i = 0; i < 3; i++) {
        assert_int_equal(qo_traj_sample(&f.tr, BIG + ((qo_traj_ns)i - 1) * 1000 * S, o, v, a, cl), QO_OK);
        assert_memory_equal(o, p, sizeof p);
        assert_true(v[0] == 0.0f && a[0] == 0.0f && cl[0] == 0);
    }
    assert_int_equal(qo_traj_end_time(&f.tr, &end), QO_OK);
    assert_true(end >= BIG && end <= BIG + 1);
    /* refused pushes */
    assert_int_equal(qo_traj_push(&f.tr, BIG + S, nan_p, NULL, NULL), QO_E_NONFINITE);
    assert_int_equal(qo_traj_push(&f.tr, BIG + S, huge, NULL, NULL), QO_E_RANGE);
    assert_int_equal(qo_traj_push(&f.tr, -QO_TRAJ_TIME_MAX - 1, p, NULL, NULL), QO_E_RANGE);
    /* queue up to capacity (times equal allowed), then full */
    for (i = 0; i < CAP; i++) assert_int_equal(qo_traj_push(&f.tr, BIG + 2000 * S, p, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, BIG + 2000 * S, p, NULL, NULL), QO_E_CAPACITY);
    assert_int_equal(qo_traj_push(&f.tr, BIG + 1999 * S, p, NULL, NULL), QO_E_ORDER);
    assert_int_equal(qo_traj_end_time(&f.tr, &end), QO_OK);
    assert_true(end == BIG + 2000 * S);
    assert_int_equal(qo_traj_done(&f.tr, BIG + 3000 * S), 0);
    /* all due: applied, space again */
    assert_int_equal(qo_traj_sample(&f.tr, BIG + 2000 * S, o, v, a, NULL), QO_OK);
    assert_int_equal(f.tr.count, 0);
    assert_int_equal(f.tr.replans, CAP);
    assert_int_equal(qo_traj_done(&f.tr, BIG + 2000 * S), 1);
    /* sampling before the last re-plan: its state, QO_E_ORDER */
    assert_int_equal(qo_traj_sample(&f.tr, BIG + 10 * S, o, v, a, NULL), QO_E_ORDER);
    assert_memory_equal(o, p, sizeof p);
    /* before the start, after re-plans: the state at the last re-plan, QO_E_ORDER */
    assert_int_equal(qo_traj_sample(&f.tr, BIG - S, o, v, a, NULL), QO_E_ORDER);
    assert_memory_equal(o, p, sizeof p);
    /* out of the time range */
    assert_int_equal(qo_traj_sample(&f.tr, QO_TRAJ_TIME_MAX + 1, o, v, a, NULL), QO_E_RANGE);
    assert_memory_equal(o, p, sizeof p);
    /* init errors */
    f.lim[1].vmax = 0.0f;
    assert_int_equal(qo_traj_init_targets(&f.tr, NJ, f.lim, NULL, f.joints, f.t, CAP, f.store, CAP * NJ),
                     QO_E_LIMIT);
    assert_int_equal(qo_traj_joints(&f.tr), 0);
    f.lim[1].vmax = 1.0f;
    assert_int_equal(qo_traj_init_targets(&f.tr, NJ, f.lim, NULL, f.joints, f.t, CAP, f.store, CAP * NJ - 1),
                     QO_E_CAPACITY);
    assert_int_equal(qo_traj_init_targets(&f.tr, QO_MOTION_MAX_JOINTS + 1, f.lim, NULL, f.joints, f.t, CAP,
                                          f.store, CAP * NJ), QO_E_CAPACITY);
    assert_int_equal(qo_traj_init_targets(&f.tr, NJ, f.lim, NULL, f.joints, f.t, 0, f.store, CAP * NJ),
                     QO_E_TOO_FEW);
    assert_int_equal(qo_traj_init_targets(&f.tr, NJ, NULL, NULL, f.joints, f.t, CAP, f.store, CAP * NJ),
                     QO_E_NULL);
    assert_int_equal(qo_traj_store_len(QO_TRAJ_TARGETS, NJ, CAP, 1), CAP * NJ);
    assert_int_equal(qo_traj_store_len(QO_TRAJ_NONE, NJ, CAP, 1), 0);
    assert_int_equal(qo_traj_store_len(QO_TRAJ_KEYS, NJ, 1, 1), 0);
    assert_int_equal(qo_traj_store_len(QO_TRAJ_KEYS, (size_t)-1 / 2, 4, 1), 0);
}

/* Duration (ns) of the plan made by the re-plan just applied: end time minus re-plan time. */
static qo_traj_ns plan_ns(const qo_traj *tr)
{
    qo_traj_ns end;
    assert_int_equal(qo_traj_end_time(tr, &end), QO_OK);
    return end - tr->origin;
}

/* qo_traj_set_timing with a period: every re-planned move lasts a whole number of periods (the
 * end time rounds up by at most 1 ns) and never less than without the rule (same targets from
 * rest); re-plans in mid-motion too. Set before the first push (it must survive the start's
 * planner init) or after it. */
static void check_timing_period(qo_motion_profile prof, float P, int set_before, uint64_t seed)
{
    static struct tgt_fix f, g;
    float start[NJ], tg[NJ], o[NJ];
    qo_traj_ns t = BIG;
    int c;
    size_t j;
    rng.s = seed;
    init_targets(&f, prof);
    init_targets(&g, prof);
    for (j = 0; j < NJ; j++) start[j] = (float)urand(-5, 5);
    if (set_before) assert_int_equal(qo_traj_set_timing(&f.tr, 0.0f, P), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, t, start, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&g.tr, t, start, NULL, NULL), QO_OK);
    if (!set_before) assert_int_equal(qo_traj_set_timing(&f.tr, 0.0f, P), QO_OK);
    for (c = 0; c < 40; c++) {
        qo_traj_ns d, dg, end, mid;
        double k;
        for (j = 0; j < NJ; j++) tg[j] = (float)urand(-10, 10);
        if (c % 4 == 3) tg[c % NJ] = o[c % NJ] + 1e-3f; /* a tiny move of one joint */
        /* from rest: both trajectories start from the same state */
        assert_int_equal(qo_traj_push(&f.tr, t, tg, NULL, NULL), QO_OK);
        assert_int_equal(qo_traj_push(&g.tr, t, tg, NULL, NULL), QO_OK);
        assert_int_equal(qo_traj_sample(&f.tr, t, o, NULL, NULL, NULL), QO_OK);
        assert_int_equal(qo_traj_sample(&g.tr, t, o, NULL, NULL, NULL), QO_OK);
        d = plan_ns(&f.tr);
        dg = plan_ns(&g.tr);
        k = floor((double)d / (P * 1e9) + 0.5);
        if (!(k >= 1.0 && fabs((double)d - k * (double)P * 1e9) <= 1e-6 * (double)d + 2.0 && d >= dg - 1)) {
            fprintf(stderr, "timing case %d seed %llu P %g: duration %lld ns, without the rule %lld ns\n", c,
                    (unsigned long long)seed, (double)P, (long long)d, (long long)dg);
            fail();
        }
        /* a re-plan in mid-motion (a third of the way), from a moving state */
        mid = t + d / 3;
        for (j = 0; j < NJ; j++) tg[j] = (float)urand(-10, 10);
        assert_int_equal(qo_traj_push(&f.tr, mid, tg, NULL, NULL), QO_OK);
        assert_int_equal(qo_traj_sample(&f.tr, mid, o, NULL, NULL, NULL), QO_OK);
        d = plan_ns(&f.tr);
        k = floor((double)d / (P * 1e9) + 0.5);
        if (!(k >= 1.0 && fabs((double)d - k * (double)P * 1e9) <= 1e-6 * (double)d + 2.0)) {
            fprintf(stderr, "timing case %d seed %llu P %g: mid-motion duration %lld ns\n", c,
                    (unsigned long long)seed, (double)P, (long long)d);
            fail();
        }
        /* on to rest at that target, for both (g goes there from rest too) */
        assert_int_equal(qo_traj_end_time(&f.tr, &end), QO_OK);
        t = end + S;
        assert_int_equal(qo_traj_sample(&f.tr, t, o, NULL, NULL, NULL), QO_OK);
        for (j = 0; j < NJ; j++) assert_float_equal(o[j], tg[j], 1e-4 * (1.0 + fabs(tg[j])));
        assert_int_equal(qo_traj_push(&g.tr, t, tg, NULL, NULL), QO_OK);
        assert_int_equal(qo_traj_sample(&g.tr, t, o, NULL, NULL, NULL), QO_OK);
        assert_int_equal(qo_traj_end_time(&g.tr, &end), QO_OK);
        t = (end > t ? end : t) + S;
        assert_int_equal(qo_traj_sample(&g.tr, t, o, NULL, NULL, NULL), QO_OK);
        assert_int_equal(qo_traj_sample(&f.tr, t, o, NULL, NULL, NULL), QO_OK);
    }
}

static void test_targets_timing_period(void **state)
{
    (void)state;
    check_timing_period(QO_MOTION_SCURVE, 0.01f, 1, 51);
    check_timing_period(QO_MOTION_TRAPEZOID, 0.01f, 0, 52);
    check_timing_period(QO_MOTION_SCURVE, 0.001f, 0, 53);
    check_timing_period(QO_MOTION_TRAPEZOID, 1.0f / 30.0f, 1, 54);
}

/* min_duration: a short move lasts exactly min_duration; a long one keeps its own time. Bad
 * values are refused and change nothing; KEYS and uninitialised objects are QO_E_STATE. */
static void test_targets_timing_min_and_edges(void **state)
{
    static struct tgt_fix f;
    static struct keys_fix k;
    float p0[NJ] = { 0, 0, 0 }, small[NJ] = { 1e-3f, 0, -1e-3f }, far[NJ] = { 30, -30, 30 }, o[NJ];
    float bad[][2] = { { -1.0f, 0.0f }, { 0.0f, -0.01f }, { NAN, 0.0f }, { 0.0f, NAN }, { INFINITY, 0.0f },
                       { 0.0f, 1e-7f }, { 2e4f, 0.0f }, { 0.0f, 2e4f } };
    qo_traj_ns d;
    size_t i;
    qo_traj z;
    (void)state;
    init_targets(&f, QO_MOTION_SCURVE);
    assert_int_equal(qo_traj_set_timing(&f.tr, 2.0f, 0.0f), QO_OK);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(qo_traj_set_timing(&f.tr, bad[i][0], bad[i][1]), QO_E_ARG);
        assert_true(f.tr.min_duration == 2.0f && f.tr.period == 0.0f);
        assert_true(f.tr.planner.min_duration == 2.0f && f.tr.planner.period == 0.0f);
    }
    assert_int_equal(qo_traj_push(&f.tr, BIG, p0, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, BIG + S, small, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&f.tr, BIG + S, o, NULL, NULL, NULL), QO_OK);
    d = plan_ns(&f.tr);
    /* exactly 2 s up to the float32 rounding of the planner's phase sums (1e-6 relative) */
    assert_true(d >= 2 * S - 2000 && d <= 2 * S + 2000);
    /* refused after the start too: the rules stay */
    assert_int_equal(qo_traj_set_timing(&f.tr, -0.5f, 0.0f), QO_E_ARG);
    assert_true(f.tr.planner.min_duration == 2.0f);
    /* a long move is not shortened to min_duration */
    assert_int_equal(qo_traj_push(&f.tr, BIG + 10 * S, far, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&f.tr, BIG + 10 * S, o, NULL, NULL, NULL), QO_OK);
    assert_true(plan_ns(&f.tr) > 3 * S);
    /* back to off: the tiny move is fast again */
    assert_int_equal(qo_traj_set_timing(&f.tr, 0.0f, 0.0f), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, BIG + 100 * S, p0, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, BIG + 200 * S, small, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&f.tr, BIG + 200 * S, o, NULL, NULL, NULL), QO_OK);
    assert_true(plan_ns(&f.tr) < S);
    /* state and NULL */
    init_keys(&k, QO_SPLINE_LINEAR, 1);
    assert_int_equal(qo_traj_set_timing(&k.tr, 1.0f, 0.01f), QO_E_STATE);
    memset(&z, 0, sizeof z);
    assert_int_equal(qo_traj_set_timing(&z, 1.0f, 0.01f), QO_E_STATE);
    assert_int_equal(qo_traj_set_timing(NULL, 1.0f, 0.01f), QO_E_NULL);
}

/* Found by fuzz/fuzz_traj.c (each input is also in fuzz/regress/traj/): times at both ends of
 * the range (their difference, 2^63 ns, overflowed int64), a single key with a wrap period
 * far below its ulp (the wrap loop never ended) and a single key with a position limit of
 * -Inf above it (held at -Inf with QO_OK). */
static void test_fuzz_findings(void **state)
{
    static struct keys_fix f;
    static struct tgt_fix g;
    qo_spline_settings_f32 set = qo_spline_settings_default;
    float p0[NJ] = { 0, 1, 2 }, p1[NJ] = { 2, 3, 4 }, pos[NJ], vel[NJ], acc[NJ];
    float lo[NJ] = { -INFINITY, -INFINITY, -INFINITY }, hi[NJ] = { INFINITY, -INFINITY, INFINITY };
    unsigned char wrap[NJ] = { 1, 0, 0 };
    qo_traj_ns end;
    size_t j;
    (void)state;
    set.profile = QO_SPLINE_LINEAR;
    assert_int_equal(qo_traj_init_keys(&f.tr, NJ, &set, 1, f.t, CAP, f.store, 4096), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, -QO_TRAJ_TIME_MAX, p0, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, QO_TRAJ_TIME_MAX, p1, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&f.tr, QO_TRAJ_TIME_MAX, pos, vel, acc, NULL), QO_OK);
    for (j = 0; j < NJ; j++) assert_true(pos[j] == p1[j]);
    /* halfway (t = 0): the mean, to the float32 rounding of 9.2e9 s offsets */
    assert_int_equal(qo_traj_sample(&f.tr, 0, pos, vel, acc, NULL), QO_OK);
    for (j = 0; j < NJ; j++) assert_true(fabs(pos[j] - 0.5 * (p0[j] + p1[j])) < 1e-5);

    init_targets(&g, QO_MOTION_SCURVE);
    assert_int_equal(qo_traj_push(&g.tr, QO_TRAJ_TIME_MAX - S, p0, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&g.tr, QO_TRAJ_TIME_MAX - S, p1, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&g.tr, QO_TRAJ_TIME_MAX - S, pos, vel, acc, NULL), QO_OK);
    assert_int_equal(qo_traj_end_time(&g.tr, &end), QO_OK);
    assert_true(end == QO_TRAJ_TIME_MAX); /* the move's end is beyond the range: saturated */
    init_targets(&g, QO_MOTION_SCURVE);
    assert_int_equal(qo_traj_push(&g.tr, -QO_TRAJ_TIME_MAX, p0, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&g.tr, -QO_TRAJ_TIME_MAX, p1, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&g.tr, QO_TRAJ_TIME_MAX, pos, vel, acc, NULL), QO_OK);
    for (j = 0; j < NJ; j++) assert_true(pos[j] == p1[j]);
    assert_int_equal(qo_traj_end_time(&g.tr, &end), QO_OK);
    assert_true(end > -QO_TRAJ_TIME_MAX && end < -QO_TRAJ_TIME_MAX + 10 * S);

    set.wrap = wrap;
    set.wrap_period = 1e-30f;
    p0[0] = 1e30f;
    assert_int_equal(qo_traj_init_keys(&f.tr, NJ, &set, 1, f.t, CAP, f.store, 4096), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, 0, p0, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&f.tr, S, pos, vel, acc, NULL), QO_OK);
    assert_true(fabsf(pos[0]) <= 0.5e-30f); /* fmodf: wrapped in one step */
    set.wrap = NULL;
    set.pos_min = lo;
    set.pos_max = hi;
    assert_int_equal(qo_traj_init_keys(&f.tr, NJ, &set, 1, f.t, CAP, f.store, 4096), QO_OK);
    assert_int_equal(qo_traj_push(&f.tr, 0, p0, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_prepare(&f.tr), QO_E_LIMIT); /* as the plan of two keys says */
    assert_int_equal(qo_traj_sample(&f.tr, S, pos, vel, acc, NULL), QO_E_LIMIT);
    for (j = 0; j < NJ; j++) assert_true(pos[j] == p0[j] && vel[j] == 0.0f && acc[j] == 0.0f);
}

/* Target states through the queue: storage decides whether targets carry velocities; each is
 * reached at the end of its move (position and velocity, the acceleration 0), checked on the
 * samples against the target, not the planner's coefficients; a refused state leaves the
 * motion planned before going on, bit for bit; per-joint sync survives the start. */
static void test_targets_states(void **state)
{
    enum { C = 4 };
    static float store3[C * NJ * 3];
    qo_traj tr, ref;
    qo_traj_ns t_ns[C], t_ref[C];
    float store_ref[C * NJ];
    qo_motion_joint_f32 joints[NJ], jref[NJ];
    qo_motion_limits_f32 lim[NJ];
    float p0[NJ] = { 0, 0, 0 }, p1[NJ] = { 1.0f, -0.5f, 0.25f }, v1[NJ] = { 0.5f, -0.25f, 0.0f };
    float vbad[NJ] = { 0.5f, 9.0f, 0.0f }, pos[NJ], vel[NJ], acc[NJ], pr[NJ], vr[NJ], ar[NJ];
    qo_traj_ns end, t;
    size_t j;
    (void)state;
    for (j = 0; j < NJ; j++) {
        lim[j] = qo_motion_limits_default;
        lim[j].vmax = 2.0f; lim[j].amax = 4.0f; lim[j].jmax = 20.0f;
        lim[j].vmin = -1.0f; /* asymmetric: the motion's velocities stay in [-1, 2] */
    }
    assert_int_equal(qo_traj_store_len(QO_TRAJ_TARGETS, NJ, C, 2), 2 * C * NJ);
    assert_int_equal(qo_traj_store_len(QO_TRAJ_TARGETS, NJ, C, 3), 3 * C * NJ);
    assert_int_equal(qo_traj_store_len(QO_TRAJ_TARGETS, NJ, C, 4), 0);
    /* positions-only storage: a velocity is refused, nothing stored */
    assert_int_equal(qo_traj_init_targets(&ref, NJ, lim, NULL, jref, t_ref, C, store_ref, C * NJ), QO_OK);
    assert_int_equal(ref.target_cols, 1);
    assert_int_equal(qo_traj_push(&ref, 0, p0, v1, NULL), QO_E_CAPACITY);
    assert_int_equal(qo_traj_init_targets(&tr, NJ, lim, NULL, joints, t_ns, C, store3, C * NJ * 2), QO_OK);
    assert_int_equal(tr.target_cols, 2);
    assert_int_equal(qo_traj_push(&tr, 0, p0, v1, v1), QO_E_CAPACITY); /* no room for accelerations */
    assert_int_equal(qo_traj_push(&tr, 0, p0, v1, NULL), QO_E_ARG);    /* the start is at rest */
    assert_int_equal(qo_traj_set_joint_sync(&tr, NJ, QO_MOTION_SYNC_NONE), QO_E_RANGE);
    assert_int_equal(qo_traj_set_joint_sync(&tr, 0, (qo_motion_sync)9), QO_E_ARG);
    assert_int_equal(qo_traj_set_joint_sync(&tr, 2, QO_MOTION_SYNC_NONE), QO_OK);
    assert_int_equal(qo_traj_push(&tr, 0, p0, NULL, NULL), QO_OK);
    assert_int_equal(joints[2].sync, (int)QO_MOTION_SYNC_NONE); /* kept across the start */
    assert_int_equal(joints[0].sync, -1);
    assert_int_equal(qo_traj_push(&tr, 0, p1, v1, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&tr, 0, pos, vel, acc, NULL), QO_OK);
    assert_int_equal(qo_traj_end_time(&tr, &end), QO_OK);
    assert_true(end > 0 && end < 10 * S);
    /* at the end: on the target state; just after: moving on at the target velocity */
    assert_int_equal(qo_traj_sample(&tr, end, pos, vel, acc, NULL), QO_OK);
    for (j = 0; j < NJ; j++) {
        if (fabsf(pos[j] - p1[j]) > 1e-4f || fabsf(vel[j] - v1[j]) > 1e-4f || fabsf(acc[j]) > 1e-3f)
            fail_msg("joint %zu at the end: %g %g %g, want %g %g 0", j, (double)pos[j], (double)vel[j], (double)acc[j],
                     (double)p1[j], (double)v1[j]);
    }
    assert_int_equal(qo_traj_sample(&tr, end + S, pos, vel, acc, NULL), QO_OK);
    for (j = 0; j < NJ; j++) assert_true(fabsf(pos[j] - (p1[j] + v1[j])) < 1e-3f && fabsf(vel[j] - v1[j]) < 1e-4f);
    /* every sample on the way within [vmin, vmax] */
    for (t = 0; t <= end; t += S / 100) {
        assert_int_equal(qo_traj_sample(&tr, t, pos, vel, acc, NULL), QO_OK);
        for (j = 0; j < NJ; j++) assert_true(vel[j] <= 2.0f * (1 + 1e-5f) && vel[j] >= -1.0f * (1 + 1e-5f));
    }

    /* a refused state (9 > vmax): QO_E_LIMIT, the motion before goes on as if never pushed */
    assert_int_equal(qo_traj_init_targets(&tr, NJ, lim, NULL, joints, t_ns, C, store3, C * NJ * 2), QO_OK);
    assert_int_equal(qo_traj_init_targets(&ref, NJ, lim, NULL, jref, t_ref, C, store_ref, C * NJ), QO_OK);
    assert_int_equal(qo_traj_push(&tr, 0, p0, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&ref, 0, p0, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&tr, 0, p1, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&ref, 0, p1, NULL, NULL), QO_OK);
    assert_int_equal(qo_traj_push(&tr, S / 2, p0, vbad, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&tr, S / 4, pos, vel, acc, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&ref, S / 4, pr, vr, ar, NULL), QO_OK);
    assert_int_equal(qo_traj_sample(&tr, S / 2, pos, vel, acc, NULL), QO_E_LIMIT);
    assert_int_equal(tr.replan_status, QO_E_LIMIT);
    for (t = S / 2; t < 5 * S; t += S / 10) {
        (void)qo_traj_sample(&tr, t, pos, vel, acc, NULL);
        assert_int_equal(qo_traj_sample(&ref, t, pr, vr, ar, NULL), QO_OK);
        for (j = 0; j < NJ; j++) assert_true(fabsf(pos[j] - pr[j]) <= 1e-6f * (1 + fabsf(pr[j])) && fabsf(vel[j] - vr[j]) <= 1e-5f);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_keys_linear_ref),
        cmocka_unit_test(test_keys_hermite_ref),
        cmocka_unit_test(test_keys_linear_ref_1e7),
        cmocka_unit_test(test_keys_hermite_ref_1e7),
        cmocka_unit_test(test_keys_time_invariant),
        cmocka_unit_test(test_keys_vs_spline_direct),
        cmocka_unit_test(test_keys_edges),
        cmocka_unit_test(test_targets_vs_planner),
        cmocka_unit_test(test_targets_vs_planner_1e7),
        cmocka_unit_test(test_targets_queue_continuity),
        cmocka_unit_test(test_targets_edges),
        cmocka_unit_test(test_targets_timing_period),
        cmocka_unit_test(test_targets_timing_min_and_edges),
        cmocka_unit_test(test_fuzz_findings),
        cmocka_unit_test(test_targets_states),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
