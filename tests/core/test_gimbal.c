/*
 * Orientation paths and gimbal joint angles (qorient/gimbal.h), against double references:
 * the requested orientation is built in double from known yaw/pitch/roll curves, and the
 * commanded angles are recomposed in double.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <cmocka.h>

#include "common/ref.h"
#include "qorient/gimbal.h"

#define DEG (REF_PI / 180.0)

/* Intrinsic Z-Y'-X'' (yaw, pitch, roll) in double: q = qz(a1) qy(a2) qx(a3). */
static ref_quat ref_zyx(double a1, double a2, double a3)
{
    ref_vec3 z = { 0, 0, 1 }, y = { 0, 1, 0 }, x = { 1, 0, 0 };
    return ref_quat_mul(ref_quat_mul(ref_quat_from_axis_angle(z, a1), ref_quat_from_axis_angle(y, a2)),
                        ref_quat_from_axis_angle(x, a3));
}

static double recompose_err(qo_euler_f32 e, ref_quat want)
{
    return ref_quat_angle_between(ref_zyx(e.a1, e.a2, e.a3), want);
}

static void test_path_init_errors(void **state)
{
    float t[3] = { 0.0f, 1.0f, 2.0f };
    qo_quat_f32 k[3] = { { 1, 0, 0, 0 }, { 0, 1, 0, 0 }, { 0, 0, 1, 0 } };
    qo_quat_f32 ks[3], a[3], b[3];
    qo_gimbal_path_f32 p;
    qo_quat_f32 q;
    (void)state;
    assert_int_equal(qo_gimbal_path_init_f32(NULL, t, k, 3, QO_GIMBAL_PATH_SLERP, ks, NULL, NULL), QO_E_NULL);
    assert_int_equal(qo_gimbal_path_init_f32(&p, NULL, k, 3, QO_GIMBAL_PATH_SLERP, ks, NULL, NULL), QO_E_NULL);
    assert_int_equal(qo_gimbal_path_init_f32(&p, t, k, 3, QO_GIMBAL_PATH_SPLINE, ks, NULL, b), QO_E_NULL);
    assert_int_equal(qo_gimbal_path_init_f32(&p, t, k, 1, QO_GIMBAL_PATH_SLERP, ks, NULL, NULL), QO_E_TOO_FEW);
    assert_int_equal(qo_gimbal_path_init_f32(&p, t, k, 3, (qo_gimbal_path_interp)7, ks, a, b), QO_E_ARG);
    t[1] = 0.0f;
    assert_int_equal(qo_gimbal_path_init_f32(&p, t, k, 3, QO_GIMBAL_PATH_SLERP, ks, NULL, NULL), QO_E_ORDER);
    t[1] = NAN;
    assert_int_equal(qo_gimbal_path_init_f32(&p, t, k, 3, QO_GIMBAL_PATH_SLERP, ks, NULL, NULL), QO_E_NONFINITE);
    t[1] = 1.0f;
    k[2].w = 0.0f; k[2].x = 0.0f; k[2].y = 0.0f; k[2].z = 0.0f;
    assert_int_equal(qo_gimbal_path_init_f32(&p, t, k, 3, QO_GIMBAL_PATH_SLERP, ks, NULL, NULL), QO_E_DEGENERATE);
    /* a failed init leaves a path that sampling rejects */
    assert_int_equal(qo_gimbal_path_sample_f32(&p, 0.5f, &q), QO_E_STATE);
    assert_true(q.w == 1.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f);
}

/* Both interpolations pass through every key, hold the ends, and slerp between keys matches a
 * double slerp of the sign-aligned keys. */
static void test_path_keys_and_between(void **state)
{
    enum { N = 6 };
    float t[N];
    qo_quat_f32 k[N], ks[N], a[N], b[N];
    ref_quat rk[N];
    ref_rng rng = { 0x6172BA11ULL };
    qo_gimbal_path_f32 p;
    int interp, i, j;
    (void)state;
    for (i = 0; i < N; i++) {
        t[i] = 0.5f * (float)i + (float)(0.1 * ref_rng_unit(&rng));
        rk[i] = ref_rng_quat(&rng);
        if (i % 2) { rk[i].w = -rk[i].w; rk[i].x = -rk[i].x; rk[i].y = -rk[i].y; rk[i].z = -rk[i].z; }
        k[i] = ref_quat_to_f32(rk[i]);
    }
    for (interp = 0; interp < 2; interp++) {
        qo_quat_f32 q;
        assert_int_equal(qo_gimbal_path_init_f32(&p, t, k, N, (qo_gimbal_path_interp)interp, ks, a, b), QO_OK);
        for (i = 0; i < N; i++) {
            double e;
            assert_int_equal(qo_gimbal_path_sample_f32(&p, t[i], &q), QO_OK);
            e = ref_quat_angle_between(ref_quat_from_f32(q), rk[i]);
            if (e > 1e-6) print_error("interp %d key %d: error %g rad\n", interp, i, e);
            assert_true(e <= 1e-6);
        }
        assert_int_equal(qo_gimbal_path_sample_f32(&p, t[0] - 5.0f, &q), QO_OK);
        assert_true(ref_quat_angle_between(ref_quat_from_f32(q), rk[0]) <= 1e-6);
        assert_int_equal(qo_gimbal_path_sample_f32(&p, t[N - 1] + 5.0f, &q), QO_OK);
        assert_true(ref_quat_angle_between(ref_quat_from_f32(q), rk[N - 1]) <= 1e-6);
        assert_int_equal(qo_gimbal_path_sample_f32(&p, NAN, &q), QO_E_NONFINITE);
    }
    /* slerp between keys vs double: rotation from key i by fraction u of the short angle */
    assert_int_equal(qo_gimbal_path_init_f32(&p, t, k, N, QO_GIMBAL_PATH_SLERP, ks, NULL, NULL), QO_OK);
    for (i = 0; i + 1 < N; i++) {
        for (j = 1; j < 8; j++) {
            double u = j / 8.0;
            float tt = (float)(t[i] + u * (t[i + 1] - t[i]));
            double uu = ((double)tt - t[i]) / ((double)t[i + 1] - t[i]);
            ref_quat q0 = ref_quat_normalize(rk[i]), q1 = ref_quat_normalize(rk[i + 1]), want;
            double d = q0.w * q1.w + q0.x * q1.x + q0.y * q1.y + q0.z * q1.z, th, s0, s1, e;
            qo_quat_f32 q;
            if (d < 0) { q1.w = -q1.w; q1.x = -q1.x; q1.y = -q1.y; q1.z = -q1.z; d = -d; }
            th = acos(d > 1 ? 1 : d);
            s0 = sin((1 - uu) * th) / sin(th); s1 = sin(uu * th) / sin(th);
            want.w = s0 * q0.w + s1 * q1.w; want.x = s0 * q0.x + s1 * q1.x;
            want.y = s0 * q0.y + s1 * q1.y; want.z = s0 * q0.z + s1 * q1.z;
            assert_int_equal(qo_gimbal_path_sample_f32(&p, tt, &q), QO_OK);
            e = ref_quat_angle_between(ref_quat_from_f32(q), want);
            if (e > 1e-6) print_error("segment %d u %g: error %g rad\n", i, uu, e);
            assert_true(e <= 1e-6);
        }
    }
}

/* A pitch sweep straight through +90 degrees (the ZYX singular configuration) with yaw and
 * roll fixed. The gimbal must stay continuous (the nearest branch carries pitch past 90
 * instead of flipping yaw and roll by 180), report the margin and the lock band, hold the
 * free angle in the band, and recompose to the requested orientation. */
static void test_gimbal_through_singularity(void **state)
{
    qo_gimbal_settings_f32 s = qo_gimbal_settings_default;
    qo_gimbal_f32 g;
    qo_gimbal_sample_f32 o;
    const double yaw = 30 * DEG, roll = -20 * DEG, dt = 0.002;
    double max_jump = 0, worst_free = 0, worst_unlocked = 0, worst_locked = 0;
    int i, n_locked = 0;
    float held_a3 = 0;
    int in_band = 0;
    (void)state;
    s.seq = QO_EULER_ZYX;
    s.band = (float)(1.0 * DEG);
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_OK);
    for (i = 0; i <= 1000; i++) {
        double tt = i * dt, pitch = (60.0 + 60.0 * i / 1000.0) * DEG; /* 60 -> 120 degrees */
        ref_quat want = ref_zyx(yaw, pitch, roll);
        double margin = fabs(pitch - 90 * DEG), e;
        qo_euler_f32 prev = g.prev;
        assert_int_equal(qo_gimbal_step_f32(&g, (float)tt, ref_quat_to_f32(want), &o), QO_OK);
        assert_int_equal(o.clipped, 0);
        if (i > 0) {
            double j = fmax(fabs(o.angles.a1 - prev.a1), fmax(fabs(o.angles.a2 - prev.a2), fabs(o.angles.a3 - prev.a3)));
            if (j > max_jump) max_jump = j;
        }
        /* margin: the pitch's distance from 90 degrees, as the double curve says */
        if (fabs(o.margin - margin) > 2e-6) print_error("step %d: margin %g want %g\n", i, o.margin, margin);
        assert_true(fabs(o.margin - margin) <= 2e-6);
        if (margin > s.band + 1e-5) assert_int_equal(o.locked, 0);
        if (margin < s.band - 1e-5) assert_int_equal(o.locked, 1);
        e = recompose_err(o.angles, want);
        if (o.locked) {
            n_locked++;
            if (!in_band) { held_a3 = o.angles.a3; in_band = 1; }
            /* the free angle is held exactly */
            if (fabs(o.angles.a3 - held_a3) > worst_free) worst_free = fabs(o.angles.a3 - held_a3);
            if (e > worst_locked) worst_locked = e;
        } else {
            in_band = 0;
            if (e > worst_unlocked) worst_unlocked = e;
        }
    }
    /* per-step change bounded by the path's own rate (0.06 deg of pitch per step) plus a small
     * allowance: no 180-degree branch flip, no free-angle swing */
    if (max_jump > 0.2 * DEG) print_error("largest per-step change %g deg\n", max_jump / DEG);
    assert_true(max_jump <= 0.2 * DEG);
    assert_true(n_locked >= 30); /* 2 degrees of the sweep at 0.06 deg per step */
    assert_true(worst_free == 0.0);
    if (worst_unlocked > 2e-6) print_error("unlocked recomposition %g rad\n", worst_unlocked);
    assert_true(worst_unlocked <= 2e-6);
    /* held split: within 2 * band of the request (qo_euler_from_quat_near_f32's bound) */
    assert_true(worst_locked <= 2.0 * s.band);
    /* pitch continued past 90 degrees on the same branch: the last sample has pitch ~120 */
    assert_true(fabs(o.angles.a2 - 120 * DEG) < 1e-4);
}

/* The rate limit is the last word: a sudden 90-degree request, and a reset outside the
 * position limits, both move at vmax per second and set the clipped bits. */
static void test_gimbal_rate_and_position_limits(void **state)
{
    qo_gimbal_settings_f32 s = qo_gimbal_settings_default;
    qo_gimbal_f32 g;
    qo_gimbal_sample_f32 o;
    qo_euler_f32 start = { 0.0f, 0.0f, 0.0f };
    const float dt = 0.01f, vmax = 1.0f;
    ref_quat want = ref_zyx(90 * DEG, 0, 0);
    float prev_a1 = 0;
    int i, reached = -1;
    (void)state;
    s.vmax = vmax;
    s.min[1] = (float)(-10 * DEG);
    s.max[1] = (float)(10 * DEG);
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_OK);
    assert_int_equal(qo_gimbal_reset_f32(&g, start, 0.0f), QO_OK);
    for (i = 1; i <= 200; i++) {
        assert_int_equal(qo_gimbal_step_f32(&g, (float)i * dt, ref_quat_to_f32(want), &o), QO_OK);
        /* the step the gimbal saw is the float difference of the two sample times */
        assert_true(fabsf(o.angles.a1 - prev_a1) <= vmax * ((float)i * dt - (float)(i - 1) * dt) * (1 + 1e-5f));
        if (reached < 0) {
            if ((o.clipped & 1u) == 0) reached = i;
        }
        prev_a1 = o.angles.a1;
    }
    /* 90 degrees at 1 rad/s takes 1.571 s = 157 steps */
    assert_true(reached >= 157 && reached <= 159);
    assert_true(fabs(o.angles.a1 - 90 * DEG) < 1e-5);

    /* reset outside the pitch limits: walks back at vmax, clipped reported, never a jump */
    start.a1 = 0.0f; start.a2 = (float)(40 * DEG); start.a3 = 0.0f;
    assert_int_equal(qo_gimbal_reset_f32(&g, start, 10.0f), QO_OK);
    want = ref_zyx(0, 40 * DEG, 0);
    {
        float prev_a2 = start.a2;
        for (i = 1; i <= 100; i++) {
            assert_int_equal(qo_gimbal_step_f32(&g, 10.0f + (float)i * dt, ref_quat_to_f32(want), &o), QO_OK);
            float step = (10.0f + (float)i * dt) - (10.0f + (float)(i - 1) * dt);
            assert_true(fabsf(o.angles.a2 - prev_a2) <= vmax * step * (1 + 1e-5f));
            assert_true(o.clipped & 2u);
            prev_a2 = o.angles.a2;
        }
        assert_true(fabs(o.angles.a2 - 10 * DEG) < 1e-5); /* arrived at the limit and stays */
    }
}

static void test_gimbal_errors_hold(void **state)
{
    qo_gimbal_settings_f32 s = qo_gimbal_settings_default;
    qo_gimbal_f32 g;
    qo_gimbal_sample_f32 o;
    qo_quat_f32 q = ref_quat_to_f32(ref_zyx(0.3, 0.2, 0.1));
    qo_quat_f32 bad = { NAN, 0, 0, 0 }, zero = { 0, 0, 0, 0 };
    qo_euler_f32 held;
    (void)state;
    assert_int_equal(qo_gimbal_init_f32(NULL, &s), QO_E_NULL);
    s.vmax = 0.0f;
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_E_LIMIT);
    s.vmax = NAN;
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_E_LIMIT);
    s = qo_gimbal_settings_default;
    s.band = -0.1f;
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_E_RANGE);
    s = qo_gimbal_settings_default;
    s.min[0] = 1.0f; s.max[0] = -1.0f;
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_E_LIMIT);
    s = qo_gimbal_settings_default;
    s.seq = QO_EULER_SEQ_COUNT_;
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_E_ARG);

    assert_int_equal(qo_gimbal_init_f32(&g, &qo_gimbal_settings_default), QO_OK);
    assert_int_equal(qo_gimbal_step_f32(&g, 0.0f, q, &o), QO_OK);
    held = o.angles;
    assert_true(recompose_err(held, ref_quat_from_f32(q)) < 1e-6);
    /* NaN, zero quaternion, time going backwards: status, joints hold, state unchanged */
    assert_int_equal(qo_gimbal_step_f32(&g, 0.1f, bad, &o), QO_E_NONFINITE);
    assert_true(o.angles.a1 == held.a1 && o.angles.a2 == held.a2 && o.angles.a3 == held.a3);
    assert_int_equal(qo_gimbal_step_f32(&g, 0.1f, zero, &o), QO_E_DEGENERATE);
    assert_true(o.angles.a1 == held.a1 && o.angles.a2 == held.a2 && o.angles.a3 == held.a3);
    assert_int_equal(qo_gimbal_step_f32(&g, 0.0f, q, &o), QO_E_ORDER);
    assert_true(o.angles.a1 == held.a1 && o.angles.a2 == held.a2 && o.angles.a3 == held.a3);
    assert_int_equal(qo_gimbal_step_f32(&g, NAN, q, &o), QO_E_NONFINITE);
    assert_int_equal(qo_gimbal_step_f32(&g, 0.1f, q, NULL), QO_E_NULL);
    assert_int_equal(qo_gimbal_step_f32(&g, 0.1f, q, &o), QO_OK);
    assert_true(o.angles.a1 == held.a1 && o.angles.a2 == held.a2 && o.angles.a3 == held.a3);
    held.a1 = NAN;
    assert_int_equal(qo_gimbal_reset_f32(&g, held, 1.0f), QO_E_NONFINITE);
}

/* The tracking filter on random paths through and near the ZYX singular configuration (fixed
 * seed): keys every 0.5 s with yaw and roll random, pitch sweeping 60 -> 120 degrees (through
 * lock) or 70 -> 89.x -> 70 (near it), hold band 1..3 degrees, sampled at 100..500 Hz, with
 * and without a rate limit and a jerk limit. Judged only from the output positions, in double,
 * by finite differences over m ticks (the mean of the acceleration over a triangle of 2m ticks,
 * so it can never exceed the largest |acceleration| of a true motion): independent of the
 * planner's coefficients. Float32 rounding of the positions enters each difference as at most
 * (2^k) * ulp(|p|) / (m dt)^k; the tolerance is that plus 1e-5 relative. */
#define TRACK_CASES 120
#define TRACK_MAXS 4100

/* k-th derivative by finite differences over the points i-m, i, i+m (, i+2m) at their actual
 * float32 sample times: k! times the Newton divided difference, which is the mean of the k-th
 * derivative over a B-spline kernel, so it never exceeds the largest |derivative|. */
static double fd_k(const double *p, const double *tt, int i, int m, int k)
{
    double x[4], d[4];
    int a, b;
    for (a = 0; a <= k; a++) { x[a] = tt[i + (a - 1) * m]; d[a] = p[i + (a - 1) * m]; }
    if (k == 1) { x[0] = tt[i - m]; d[0] = p[i - m]; x[1] = tt[i]; d[1] = p[i]; }
    for (b = 1; b <= k; b++)
        for (a = k; a >= b; a--) d[a] = (d[a] - d[a - 1]) / (x[a] - x[a - b]);
    return d[k] * (k == 3 ? 6 : k);
}

/* nudge 0: the keys as built; else the seed of 1-ulp nudges to every key component. */
static void track_random_paths(uint64_t nudge)
{
    static double out[3][TRACK_MAXS], path[3][TRACK_MAXS], tt[TRACK_MAXS];
    ref_rng rng = { 0x7EAC4ED5ULL }, nr;
    int c, raw_jumps = 0;
    nr.s = nudge;
    for (c = 0; c < TRACK_CASES; c++) {
        enum { K = 7 };
        float kt[K];
        qo_quat_f32 keys[K], ks[K], ca[K], cb[K];
        qo_gimbal_path_f32 pa;
        qo_gimbal_settings_f32 gs = qo_gimbal_settings_default;
        qo_gimbal_track_settings_f32 ts = qo_gimbal_track_settings_default;
        qo_gimbal_f32 g;
        qo_gimbal_track_f32 tr;
        qo_gimbal_sample_f32 o;
        qo_gimbal_track_sample_f32 to;
        const double rates[3] = { 100, 200, 500 };
        double dt = 1.0 / rates[c % 3], through = c % 2 == 0, peak = 89.0 + ref_rng_unit(&rng);
        double maxp = 0, worst_a = 0, worst_j = 0, worst_v = 0, worst_err = 0, raw_step = 0;
        int i, k, j, n = 0, settled_at = -1, interp = (c / 2) % 2;
        gs.band = (float)(ref_rng_range(&rng, 1, 3) * DEG);
        if (c % 5 == 1) gs.vmax = (float)ref_rng_range(&rng, 1, 4);
        ts.amax = (float)ref_rng_range(&rng, 4, 40);
        ts.vmax = gs.vmax;
        if (c % 3 != 0) {
            ts.jmax = (float)ref_rng_range(&rng, 100, 2000);
            if (ts.gain > ts.jmax / (4 * ts.amax)) ts.gain = ts.jmax / (4 * ts.amax);
        }
        for (k = 0; k < K; k++) {
            double u = (double)k / (K - 1), pitch = through ? 60 + 60 * u : 70 + (peak - 70) * sin(REF_PI * u);
            kt[k] = 0.5f * (float)k;
            keys[k] = ref_quat_to_f32(ref_zyx(ref_rng_range(&rng, -1, 1), pitch * DEG, ref_rng_range(&rng, -0.5, 0.5)));
            if (nudge != 0) {
                /* each component 1 ulp up or down, as another libm's sin/cos may round it */
                keys[k].w = nextafterf(keys[k].w, ref_rng_unit(&nr) < 0.5 ? 2.0f : -2.0f);
                keys[k].x = nextafterf(keys[k].x, ref_rng_unit(&nr) < 0.5 ? 2.0f : -2.0f);
                keys[k].y = nextafterf(keys[k].y, ref_rng_unit(&nr) < 0.5 ? 2.0f : -2.0f);
                keys[k].z = nextafterf(keys[k].z, ref_rng_unit(&nr) < 0.5 ? 2.0f : -2.0f);
            }
        }
        assert_int_equal(qo_gimbal_path_init_f32(&pa, kt, keys, K, (qo_gimbal_path_interp)interp, ks, ca, cb), QO_OK);
        assert_int_equal(qo_gimbal_init_f32(&g, &gs), QO_OK);
        assert_int_equal(qo_gimbal_track_init_f32(&tr, &ts), QO_OK);
        /* the path (3 s), then until settled, at most TRACK_MAXS samples */
        for (i = 0; i < TRACK_MAXS; i++) {
            float t = (float)(i * dt);
            qo_quat_f32 q;
            assert_int_equal(qo_gimbal_path_sample_f32(&pa, t, &q), QO_OK);
            assert_int_equal(qo_gimbal_step_f32(&g, t, q, &o), QO_OK);
            assert_int_equal(qo_gimbal_track_step_f32(&tr, t, o.angles, &to), QO_OK);
            tt[i] = t;
            path[0][i] = o.angles.a1; path[1][i] = o.angles.a2; path[2][i] = o.angles.a3;
            out[0][i] = to.angles.a1; out[1][i] = to.angles.a2; out[2][i] = to.angles.a3;
            for (j = 0; j < 3; j++) {
                double e = fabs(path[j][i] - out[j][i]);
                if (fabs(out[j][i]) > maxp) maxp = fabs(out[j][i]);
                if (e > worst_err) worst_err = e;
                if (fabs(to.err - fmax(fabs(path[0][i] - out[0][i]), fmax(fabs(path[1][i] - out[1][i]),
                    fabs(path[2][i] - out[2][i])))) > 1e-6) fail_msg("case %d step %d: err %g", c, i, (double)to.err);
            }
            n = i + 1;
            if (t > 3.0f && to.settled) { settled_at = i; break; }
        }
        /* tracking error -> 0: the joints end on the path's end, at rest, exactly */
        if (settled_at < 0) fail_msg("nudge %lu case %d: not settled %g s after the path stopped", (unsigned long)nudge, c, (n - 1) * dt - 3);
        for (j = 0; j < 3; j++) assert_true(out[j][n - 1] == path[j][n - 1] && to.rate[j] == 0.0f);
        /* bounded: well under the excursion a rate step at amax can leave (the paths' rates
         * stay below 3 rad/s: 3^2 / (2 * 4) = 1.1 rad) */
        /* bounded: the joints stay within the range the path covers, up to the overshoot of
         * braking onto it when the path stops dead: from rate R (the largest seen) and
         * acceleration amax away from it, the acceleration ramps to -amax in 2 amax/jmax
         * (covering at most 2 R amax/jmax), then stops within R^2/(2 amax); the filter sees
         * the stop one step late (the path's rate is a difference of its last two samples),
         * R dt more: the filter never runs away from the path */
        for (j = 0; j < 3; j++) {
            double lo = path[j][0], hi = lo, r = 0, over;
            for (i = 1; i < n; i++) {
                lo = fmin(lo, path[j][i]); hi = fmax(hi, path[j][i]);
                r = fmax(r, fabs(fd_k(out[j], tt, i, 1, 1)));
            }
            over = r * r / (2 * ts.amax) + (isfinite(ts.jmax) ? 2 * r * ts.amax / ts.jmax : 0) + r * dt + 1e-6;
            for (i = 0; i < n; i++)
                if (out[j][i] < lo - over || out[j][i] > hi + over)
                    fail_msg("case %d joint %d step %d: %g outside the path's [%g, %g] by more than %g", c, j, i,
                             out[j][i], lo, hi, over);
        }
        for (j = 0; j < 3; j++) {
            const double ulp = 1.2e-7 * (maxp + 1);
            for (i = 1; i < n; i++) {
                double v = fd_k(out[j], tt, i, 1, 1), rv = fd_k(path[j], tt, i, 1, 1);
                if (isfinite(gs.vmax) && fabs(v) > gs.vmax * (1 + 1e-5) + 2 * ulp / dt)
                    fail_msg("case %d joint %d step %d: rate %g > vmax %g", c, j, i, v, (double)gs.vmax);
                if (i + 1 < n) {
                    /* rates continuous: each step of the rate within amax*dt, over 1 and 10 ticks */
                    int m;
                    for (m = 1; m <= 10; m += 9) {
                        if (i - m >= 0 && i + m < n) {
                            double a = fabs(fd_k(out[j], tt, i, m, 2)), tol = 4 * ulp / (m * dt * m * dt);
                            if (a > ts.amax * (1 + 1e-5) + tol)
                                fail_msg("case %d joint %d step %d (m %d): |acc| %.9g > amax %g", c, j, i, m, a, (double)ts.amax);
                            if (a - tol > worst_a) worst_a = a - tol;
                        }
                    }
                    if (i + 1 < n && fabs(fd_k(path[j], tt, i + 1, 1, 1) - rv) > raw_step)
                        raw_step = fabs(fd_k(path[j], tt, i + 1, 1, 1) - rv);
                }
                if (isfinite(ts.jmax) && i - 20 >= 0 && i + 40 < n) {
                    double h = 20 * dt, jr = fabs(fd_k(out[j], tt, i, 20, 3)), tol = 8 * ulp / (h * h * h);
                    if (jr > ts.jmax * (1 + 1e-5) + tol)
                        fail_msg("case %d joint %d step %d: |jerk| %.9g > jmax %g", c, j, i, jr, (double)ts.jmax);
                    if (jr > worst_j) worst_j = jr;
                }
                if (fabs(v) > worst_v) worst_v = fabs(v);
            }
        }
        (void)worst_a; (void)worst_j;
        /* the unfiltered gimbal's rate jumps by more than amax*dt here (the filter had work) */
        if (raw_step > ts.amax * dt * 1.5) raw_jumps++;
    }
    /* a check on the test: most paths ask for more than the limits somewhere */
    if (raw_jumps < TRACK_CASES / 2) fail_msg("only %d of %d paths exceeded amax unfiltered", raw_jumps, TRACK_CASES);
}

static void test_track_random_paths(void **state)
{
    (void)state;
    track_random_paths(0);
}

/* The same paths with every key component 1 ulp off (fixed seeds): what another target's libm
 * hands the test. Each must still settle exactly: a tracker that re-planned its hold at every
 * step chattered an ulp around the target forever here (CI, M4F/M7/aarch64/armhf, case 14). */
static void test_track_random_paths_nudged(void **state)
{
    uint64_t seed;
    (void)state;
    for (seed = 1; seed <= 3; seed++) track_random_paths(0x9E3779B97F4A7C15ULL * seed);
}

/* A path holding still from the start stays exactly still; a constant-rate ramp is tracked
 * with an error that decays to float32 rounding. */
static void test_track_steady(void **state)
{
    qo_gimbal_track_f32 tr;
    qo_gimbal_track_sample_f32 to;
    qo_euler_f32 e = { 0.5f, -0.25f, 1.0f };
    int i;
    (void)state;
    assert_int_equal(qo_gimbal_track_init_f32(&tr, &qo_gimbal_track_settings_default), QO_OK);
    for (i = 0; i < 50; i++) {
        assert_int_equal(qo_gimbal_track_step_f32(&tr, 0.01f * (float)i, e, &to), QO_OK);
        assert_true(to.angles.a1 == e.a1 && to.angles.a2 == e.a2 && to.angles.a3 == e.a3 && to.settled == 1);
    }
    /* ramp at 0.3 rad/s on a1 from t = 0.5 s: after 3 s the error is small */
    for (i = 50; i < 400; i++) {
        qo_euler_f32 r = e;
        double t = 0.01 * i;
        r.a1 = (float)(0.5 + 0.3 * (t - 0.49));
        assert_int_equal(qo_gimbal_track_step_f32(&tr, (float)t, r, &to), QO_OK);
        assert_int_equal(to.settled, 0);
    }
    if (to.err > 1e-5f || fabsf(to.rate[0] - 0.3f) > 1e-4f) fail_msg("ramp: err %g rate %g", (double)to.err, (double)to.rate[0]);
}

static void test_track_errors(void **state)
{
    qo_gimbal_track_settings_f32 s = qo_gimbal_track_settings_default;
    qo_gimbal_track_f32 tr, before;
    qo_gimbal_track_sample_f32 to;
    qo_euler_f32 e = { 0.1f, 0.2f, 0.3f }, bad = e;
    const float badv[] = { 0.0f, -1.0f, NAN, 1e-7f, 2e12f, (float)1e39 /* +Inf */ };
    size_t i;
    (void)state;
    assert_int_equal(qo_gimbal_track_init_f32(NULL, &s), QO_E_NULL);
    assert_int_equal(qo_gimbal_track_init_f32(&tr, NULL), QO_E_NULL);
    for (i = 0; i < sizeof badv / sizeof badv[0]; i++) {
        s = qo_gimbal_track_settings_default; s.amax = badv[i];
        assert_int_equal(qo_gimbal_track_init_f32(&tr, &s), QO_E_LIMIT);
        assert_int_equal(qo_gimbal_track_step_f32(&tr, 0.0f, e, &to), QO_E_STATE);
        assert_true(to.angles.a1 == 0.0f && to.err == 0.0f && to.settled == 0);
        s = qo_gimbal_track_settings_default; s.gain = badv[i];
        assert_int_equal(qo_gimbal_track_init_f32(&tr, &s), QO_E_LIMIT);
        if (!isinf(badv[i])) { /* jmax and vmax take +INFINITY for "none" */
            s = qo_gimbal_track_settings_default; s.jmax = badv[i];
            assert_int_equal(qo_gimbal_track_init_f32(&tr, &s), QO_E_LIMIT);
            s = qo_gimbal_track_settings_default; s.vmax = badv[i];
            assert_int_equal(qo_gimbal_track_init_f32(&tr, &s), QO_E_LIMIT);
        }
    }
    s = qo_gimbal_track_settings_default; s.vmax = -INFINITY;
    assert_int_equal(qo_gimbal_track_init_f32(&tr, &s), QO_E_LIMIT);
    s = qo_gimbal_track_settings_default; s.jmax = 100.0f;
    assert_int_equal(qo_gimbal_track_init_f32(&tr, &s), QO_OK);
    /* before the first step: errors give zeros and do not start the filter */
    bad.a2 = NAN;
    assert_int_equal(qo_gimbal_track_step_f32(&tr, 0.0f, bad, &to), QO_E_NONFINITE);
    bad.a2 = 1e19f;
    assert_int_equal(qo_gimbal_track_step_f32(&tr, 0.0f, bad, &to), QO_E_RANGE);
    assert_int_equal(tr.started, 0);
    assert_int_equal(qo_gimbal_track_step_f32(&tr, 0.0f, e, NULL), QO_E_NULL);
    assert_int_equal(qo_gimbal_track_step_f32(&tr, 0.0f, e, &to), QO_OK);
    e.a1 = 1.0f;
    assert_int_equal(qo_gimbal_track_step_f32(&tr, 0.1f, e, &to), QO_OK);
    /* errors after start: the state at the last step, state unchanged */
    {
        qo_gimbal_track_sample_f32 last = to;
        const float ts[] = { NAN, 0.1f, 0.05f, 0.2f, 0.2f, (float)1e39 };
        for (i = 0; i < sizeof ts / sizeof ts[0]; i++) {
            qo_euler_f32 x = e;
            qo_status want = i == 0 || i == 5 ? QO_E_NONFINITE : i < 3 ? QO_E_ORDER : QO_E_RANGE;
            if (i == 3) x.a3 = 1e19f;
            if (i == 4) x.a3 = -INFINITY, want = QO_E_NONFINITE;
            before = tr;
            assert_int_equal(qo_gimbal_track_step_f32(&tr, ts[i], x, &to), want);
            assert_memory_equal(&tr, &before, sizeof tr);
            assert_true(to.angles.a1 == last.angles.a1 && to.angles.a2 == last.angles.a2
                        && to.rate[0] == last.rate[0] && to.acc[0] == last.acc[0] && to.err == 0.0f && to.settled == 0);
        }
    }
    /* a step of a huge length (float difference overflows) is refused */
    tr.t_prev = -3e38f;
    assert_int_equal(qo_gimbal_track_step_f32(&tr, 3e38f, e, &to), QO_E_RANGE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_path_init_errors),
        cmocka_unit_test(test_path_keys_and_between),
        cmocka_unit_test(test_gimbal_through_singularity),
        cmocka_unit_test(test_gimbal_rate_and_position_limits),
        cmocka_unit_test(test_gimbal_errors_hold),
        cmocka_unit_test(test_track_random_paths),
        cmocka_unit_test(test_track_random_paths_nudged),
        cmocka_unit_test(test_track_steady),
        cmocka_unit_test(test_track_errors),
    };
    return cmocka_run_group_tests_name("gimbal", tests, NULL, NULL);
}
