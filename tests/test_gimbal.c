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
    qo_orient_path_f32 p;
    qo_quat_f32 q;
    (void)state;
    assert_int_equal(qo_orient_path_init_f32(NULL, t, k, 3, QO_PATH_SLERP, ks, NULL, NULL), QO_E_NULL);
    assert_int_equal(qo_orient_path_init_f32(&p, NULL, k, 3, QO_PATH_SLERP, ks, NULL, NULL), QO_E_NULL);
    assert_int_equal(qo_orient_path_init_f32(&p, t, k, 3, QO_PATH_SPLINE, ks, NULL, b), QO_E_NULL);
    assert_int_equal(qo_orient_path_init_f32(&p, t, k, 1, QO_PATH_SLERP, ks, NULL, NULL), QO_E_TOO_FEW);
    assert_int_equal(qo_orient_path_init_f32(&p, t, k, 3, (qo_path_interp)7, ks, a, b), QO_E_ARG);
    t[1] = 0.0f;
    assert_int_equal(qo_orient_path_init_f32(&p, t, k, 3, QO_PATH_SLERP, ks, NULL, NULL), QO_E_ORDER);
    t[1] = NAN;
    assert_int_equal(qo_orient_path_init_f32(&p, t, k, 3, QO_PATH_SLERP, ks, NULL, NULL), QO_E_NONFINITE);
    t[1] = 1.0f;
    k[2].w = 0.0f; k[2].x = 0.0f; k[2].y = 0.0f; k[2].z = 0.0f;
    assert_int_equal(qo_orient_path_init_f32(&p, t, k, 3, QO_PATH_SLERP, ks, NULL, NULL), QO_E_DEGENERATE);
    /* a failed init leaves a path that sampling rejects */
    assert_int_equal(qo_orient_path_sample_f32(&p, 0.5f, &q), QO_E_STATE);
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
    qo_orient_path_f32 p;
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
        assert_int_equal(qo_orient_path_init_f32(&p, t, k, N, (qo_path_interp)interp, ks, a, b), QO_OK);
        for (i = 0; i < N; i++) {
            double e;
            assert_int_equal(qo_orient_path_sample_f32(&p, t[i], &q), QO_OK);
            e = ref_quat_angle_between(ref_quat_from_f32(q), rk[i]);
            if (e > 1e-6) print_error("interp %d key %d: error %g rad\n", interp, i, e);
            assert_true(e <= 1e-6);
        }
        assert_int_equal(qo_orient_path_sample_f32(&p, t[0] - 5.0f, &q), QO_OK);
        assert_true(ref_quat_angle_between(ref_quat_from_f32(q), rk[0]) <= 1e-6);
        assert_int_equal(qo_orient_path_sample_f32(&p, t[N - 1] + 5.0f, &q), QO_OK);
        assert_true(ref_quat_angle_between(ref_quat_from_f32(q), rk[N - 1]) <= 1e-6);
        assert_int_equal(qo_orient_path_sample_f32(&p, NAN, &q), QO_E_NONFINITE);
    }
    /* slerp between keys vs double: rotation from key i by fraction u of the short angle */
    assert_int_equal(qo_orient_path_init_f32(&p, t, k, N, QO_PATH_SLERP, ks, NULL, NULL), QO_OK);
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
            assert_int_equal(qo_orient_path_sample_f32(&p, tt, &q), QO_OK);
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
    qo_gimbal_settings_f32 s = qo_gimbal_settings_default_f32;
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
    /* held split: within 2 * band of the request (qo_quat_to_euler_near_f32's bound) */
    assert_true(worst_locked <= 2.0 * s.band);
    /* pitch continued past 90 degrees on the same branch: the last sample has pitch ~120 */
    assert_true(fabs(o.angles.a2 - 120 * DEG) < 1e-4);
}

/* The rate limit is the last word: a sudden 90-degree request, and a reset outside the
 * position limits, both move at vmax per second and set the clipped bits. */
static void test_gimbal_rate_and_position_limits(void **state)
{
    qo_gimbal_settings_f32 s = qo_gimbal_settings_default_f32;
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
    qo_gimbal_settings_f32 s = qo_gimbal_settings_default_f32;
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
    s = qo_gimbal_settings_default_f32;
    s.band = -0.1f;
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_E_RANGE);
    s = qo_gimbal_settings_default_f32;
    s.min[0] = 1.0f; s.max[0] = -1.0f;
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_E_LIMIT);
    s = qo_gimbal_settings_default_f32;
    s.seq = QO_EULER_SEQ_COUNT_;
    assert_int_equal(qo_gimbal_init_f32(&g, &s), QO_E_ARG);

    assert_int_equal(qo_gimbal_init_f32(&g, &qo_gimbal_settings_default_f32), QO_OK);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_path_init_errors),
        cmocka_unit_test(test_path_keys_and_between),
        cmocka_unit_test(test_gimbal_through_singularity),
        cmocka_unit_test(test_gimbal_rate_and_position_limits),
        cmocka_unit_test(test_gimbal_errors_hold),
    };
    return cmocka_run_group_tests_name("gimbal", tests, NULL, NULL);
}
