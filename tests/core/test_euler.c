/* Euler angles, float32: all 24 conventions against a double-precision reference written here
 * (products of elementary rotations), scipy's documented examples, hand-derived values, exactly
 * singular and just-off-singular inputs, bad inputs and the nearest-solution decomposition. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "common/dq.h"
#include "qorient/euler.h"
#include "qorient/quat.h"

#define PI_D 3.14159265358979323846

/* The enum order is ABI: the test keeps its own copy of the names and derives the axes from
 * the letters, so the reference shares nothing with the code under test. */
static const char *const k_names[24] = {
    "xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx", "yxy", "yzy", "zxz", "zyz",
    "XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX", "XYX", "XZX", "YXY", "YZY", "ZXZ", "ZYZ",
};

/* The double-precision reference (elementary rotations composed in double) and the fixed-seed
 * PRNG are tests/common/ref.c, shared with bench/accuracy_euler*.c. */
static ref_rng rng;

/* How far the float angles, composed in double, are from the rotation q. */
static double recompose_err(int seq, qo_euler_f32 e, dq q)
{
    return dq_angle(ref_quat_from_euler(k_names[seq], e.a1, e.a2, e.a3), q);
}

static int is_proper_name(int seq) { return k_names[seq][0] == k_names[seq][2]; }

static double wrap_d(double a) { return a - 2 * PI_D * floor((a + PI_D) / (2 * PI_D)); }
static double ang_diff(double a, double b) { return fabs(wrap_d(a - b)); }

static void check_ranges(int seq, qo_euler_f32 e, const char *what)
{
    const float pi = 3.14159265358979f, hpi = 1.57079632679490f;
    int ok = e.a1 >= -pi && e.a1 <= pi && e.a3 >= -pi && e.a3 <= pi;
    if (is_proper_name(seq)) ok = ok && e.a2 >= 0.0f && e.a2 <= pi;
    else ok = ok && e.a2 >= -hpi && e.a2 <= hpi;
    if (!ok) fail_msg("%s %s: angles (%.9g %.9g %.9g) outside scipy's ranges", what,
                      k_names[seq], e.a1, e.a2, e.a3);
}

/* ---- sequence names ------------------------------------------------------------------ */
static void test_seq_parse_and_name(void **state)
{
    int i;
    qo_euler_seq s;
    (void)state;
    for (i = 0; i < 24; i++) {
        qo_status st = qo_euler_seq_parse(k_names[i], &s);
        if (st != QO_OK || (int)s != i)
            fail_msg("parse(\"%s\") gave status %d seq %d, want %d", k_names[i], (int)st, (int)s, i);
        assert_string_equal(qo_euler_seq_name((qo_euler_seq)i), k_names[i]);
        assert_int_equal(qo_euler_seq_is_intrinsic((qo_euler_seq)i), i >= 12);
        assert_int_equal(qo_euler_seq_is_proper((qo_euler_seq)i), is_proper_name(i));
    }
    assert_string_equal(qo_euler_seq_name(QO_EULER_SEQ_COUNT_), "invalid");
    assert_string_equal(qo_euler_seq_name((qo_euler_seq)-1), "invalid");
    assert_int_equal(qo_euler_seq_is_intrinsic(QO_EULER_SEQ_COUNT_), 0);
    assert_int_equal(qo_euler_seq_is_proper((qo_euler_seq)99), 0);
    assert_int_equal(QO_EULER_XYZ, 12);
    assert_int_equal(QO_EULER_zyz, 11);
}

static void test_seq_parse_rejects(void **state)
{
    static const char *const bad[] = {
        "", "x", "xy", "xyzx", "xyz ", " xyz", "xxy", "xyy", "XXZ", "zzz", "xYz", "XyZ", "xyZ",
        "abc", "xy1", "XY", "uvw", "x-y", "XYZXYZ", "wxy", "{yz",
    };
    size_t i;
    qo_euler_seq s;
    (void)state;
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        s = QO_EULER_ZYX;
        if (qo_euler_seq_parse(bad[i], &s) != QO_E_ARG || s != QO_EULER_SEQ_COUNT_)
            fail_msg("parse(\"%s\") accepted or left out unset (%d)", bad[i], (int)s);
    }
    s = QO_EULER_ZYX;
    assert_int_equal(qo_euler_seq_parse(NULL, &s), QO_E_NULL);
    assert_int_equal(s, QO_EULER_SEQ_COUNT_);
    assert_int_equal(qo_euler_seq_parse("xyz", NULL), QO_E_NULL);
}

/* ---- from_euler ------------------------------------------------------------------------ */
static void test_from_euler_random_all24(void **state)
{
    int seq, n;
    (void)state;
    rng.s = 0x1234567ull;
    for (seq = 0; seq < 24; seq++) {
        for (n = 0; n < 500; n++) {
            /* Most in one turn; some wider, as the angles are periodic. */
            double span = (n % 5 == 0) ? 10.0 : PI_D;
            qo_euler_f32 e;
            qo_quat_f32 q;
            dq r;
            double err;
            e.a1 = (float)ref_rng_range(&rng, -span, span);
            e.a2 = (float)ref_rng_range(&rng, -span, span);
            e.a3 = (float)ref_rng_range(&rng, -span, span);
            assert_int_equal(qo_quat_from_euler_f32((qo_euler_seq)seq, e, &q), QO_OK);
            r = ref_quat_from_euler(k_names[seq], e.a1, e.a2, e.a3);
            /* Same sign as the product, not only the same rotation (scipy's as_quat). */
            err = fabs(q.w - r.w) + fabs(q.x - r.x) + fabs(q.y - r.y) + fabs(q.z - r.z);
            if (err > 1e-6 || dq_angle(dq_unit_from_f(q), r) > 1e-6)
                fail_msg("from_euler %s (%.9g %.9g %.9g): component error %.3g", k_names[seq],
                         e.a1, e.a2, e.a3, err);
        }
    }
}

/* scipy's documented examples and hand-derived values. */
static void test_from_euler_known_values(void **state)
{
    const float d90 = 1.57079632679490f;
    qo_euler_f32 e;
    qo_quat_f32 q, q2;
    qo_vec3_f32 v, vz = { 0.0f, 0.0f, 1.0f }, vx = { 1.0f, 0.0f, 0.0f };
    const float h = 0.70710678118655f;
    (void)state;
    /* scipy as_rotvec docs: from_euler('YX', (-90, -90)) is 120 deg about -(1,1,1)/sqrt3, i.e.
     * q = (0.5, -0.5, -0.5, -0.5). A 3-letter intrinsic "YXZ" with a3 = 0 is the same. */
    e.a1 = -d90; e.a2 = -d90; e.a3 = 0.0f;
    assert_int_equal(qo_quat_from_euler_f32(QO_EULER_YXZ, e, &q), QO_OK);
    assert_float_equal(q.w, 0.5f, 1e-6f); assert_float_equal(q.x, -0.5f, 1e-6f);
    assert_float_equal(q.y, -0.5f, 1e-6f); assert_float_equal(q.z, -0.5f, 1e-6f);
    /* scipy: from_euler('z', 90).as_quat() = [0, 0, 0.7071, 0.7071] (x, y, z, w). Here as the
     * yaw of intrinsic ZYX (aerospace yaw-pitch-roll): it turns x into y. */
    e.a1 = d90; e.a2 = 0.0f; e.a3 = 0.0f;
    assert_int_equal(qo_quat_from_euler_f32(QO_EULER_ZYX, e, &q), QO_OK);
    assert_float_equal(q.w, h, 1e-6f); assert_float_equal(q.z, h, 1e-6f);
    assert_float_equal(q.x, 0.0f, 1e-7f); assert_float_equal(q.y, 0.0f, 1e-7f);
    v = qo_quat_rotate_f32(q, vx);
    assert_float_equal(v.x, 0.0f, 1e-6f); assert_float_equal(v.y, 1.0f, 1e-6f);
    /* Intrinsic vs extrinsic differ: XYZ (90, 90, 0) = Rx(90) Ry(90) sends z to x;
     * xyz (90, 90, 0) = Ry(90) Rx(90) sends z to -y. */
    e.a1 = d90; e.a2 = d90; e.a3 = 0.0f;
    assert_int_equal(qo_quat_from_euler_f32(QO_EULER_XYZ, e, &q), QO_OK);
    v = qo_quat_rotate_f32(q, vz);
    assert_float_equal(v.x, 1.0f, 1e-6f); assert_float_equal(v.y, 0.0f, 1e-6f);
    assert_float_equal(v.z, 0.0f, 1e-6f);
    assert_int_equal(qo_quat_from_euler_f32(QO_EULER_xyz, e, &q), QO_OK);
    v = qo_quat_rotate_f32(q, vz);
    assert_float_equal(v.x, 0.0f, 1e-6f); assert_float_equal(v.y, -1.0f, 1e-6f);
    assert_float_equal(v.z, 0.0f, 1e-6f);
    /* Intrinsic XYZ (a, b, c) is extrinsic zyx (c, b, a): identical quaternions. */
    e.a1 = 0.3f; e.a2 = -1.1f; e.a3 = 2.5f;
    assert_int_equal(qo_quat_from_euler_f32(QO_EULER_XYZ, e, &q), QO_OK);
    e.a1 = 2.5f; e.a3 = 0.3f;
    assert_int_equal(qo_quat_from_euler_f32(QO_EULER_zyx, e, &q2), QO_OK);
    assert_float_equal(q.w, q2.w, 1e-7f); assert_float_equal(q.x, q2.x, 1e-7f);
    assert_float_equal(q.y, q2.y, 1e-7f); assert_float_equal(q.z, q2.z, 1e-7f);
}

static void test_from_euler_bad_inputs(void **state)
{
    qo_euler_f32 e = { 0.1f, 0.2f, 0.3f };
    qo_quat_f32 q;
    int i;
    (void)state;
    assert_int_equal(qo_quat_from_euler_f32(QO_EULER_xyz, e, NULL), QO_E_NULL);
    q.w = 5.0f;
    assert_int_equal(qo_quat_from_euler_f32(QO_EULER_SEQ_COUNT_, e, &q), QO_E_ARG);
    assert_true(q.w == 1.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f);
    assert_int_equal(qo_quat_from_euler_f32((qo_euler_seq)-3, e, &q), QO_E_ARG);
    for (i = 0; i < 6; i++) {
        qo_euler_f32 b = e;
        float bad = (i % 2) ? INFINITY : NAN;
        if (i / 2 == 0) b.a1 = bad; else if (i / 2 == 1) b.a2 = bad; else b.a3 = (i % 2) ? -INFINITY : NAN;
        q.w = 5.0f;
        if (qo_quat_from_euler_f32(QO_EULER_ZXZ, b, &q) != QO_E_NONFINITE)
            fail_msg("from_euler accepted non-finite angle %d", i);
        assert_true(q.w == 1.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f);
    }
}

/* ---- to_euler: generic ------------------------------------------------------------------ */
static void test_to_euler_random_rotations_all24(void **state)
{
    int seq, n;
    (void)state;
    rng.s = 42;
    for (seq = 0; seq < 24; seq++) {
        for (n = 0; n < 500; n++) {
            /* Uniform random rotation (normalised Gaussian-ish via 4 uniforms + reject). */
            dq r;
            double nn;
            qo_quat_f32 qf;
            qo_euler_f32 e;
            qo_euler_info_f32 info;
            do {
                r.w = ref_rng_range(&rng, -1, 1); r.x = ref_rng_range(&rng, -1, 1);
                r.y = ref_rng_range(&rng, -1, 1); r.z = ref_rng_range(&rng, -1, 1);
                nn = r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z;
            } while (nn > 1.0 || nn < 1e-3);
            nn = sqrt(nn);
            r.w /= nn; r.x /= nn; r.y /= nn; r.z /= nn;
            qf = f_from(r);
            r = dq_unit_from_f(qf); /* the reference is the float input itself */
            assert_int_equal(qo_quat_to_euler_f32(qf, (qo_euler_seq)seq, &e, &info), QO_OK);
            check_ranges(seq, e, "random");
            if (recompose_err(seq, e, r) > 1e-6)
                fail_msg("to_euler %s of q=(%.9g %.9g %.9g %.9g): (%.9g %.9g %.9g) recomposes "
                         "%.3g rad off", k_names[seq], qf.w, qf.x, qf.y, qf.z, e.a1, e.a2, e.a3,
                         recompose_err(seq, e, r));
            if (info.locked != (info.margin <= QO_EULER_LOCK_BAND_F32))
                fail_msg("%s: locked %d with margin %.3g", k_names[seq], info.locked, info.margin);
        }
    }
}

/* Angles in scipy's ranges, away from lock, come back as given (mod 2pi near +-pi). */
static void test_to_euler_recovers_angles_all24(void **state)
{
    int seq, n;
    (void)state;
    rng.s = 7;
    for (seq = 0; seq < 24; seq++) {
        for (n = 0; n < 300; n++) {
            double a1 = ref_rng_range(&rng, -PI_D, PI_D), a3 = ref_rng_range(&rng, -PI_D, PI_D), a2, margin;
            dq r;
            qo_quat_f32 qf;
            qo_euler_f32 e;
            qo_euler_info_f32 info;
            if (is_proper_name(seq)) {
                a2 = ref_rng_range(&rng, 0.05, PI_D - 0.05);
                margin = fmin(a2, PI_D - a2);
            } else {
                a2 = ref_rng_range(&rng, -PI_D / 2 + 0.05, PI_D / 2 - 0.05);
                margin = PI_D / 2 - fabs(a2);
            }
            r = ref_quat_from_euler(k_names[seq], a1, a2, a3);
            if (n % 2) { r.w = -r.w; r.x = -r.x; r.y = -r.y; r.z = -r.z; } /* q and -q */
            qf = f_from(r);
            assert_int_equal(qo_quat_to_euler_f32(qf, (qo_euler_seq)seq, &e, &info), QO_OK);
            /* a1, a3 are conditioned like 1/margin near lock. */
            if (ang_diff(e.a1, a1) > 2e-5 || fabs(e.a2 - a2) > 2e-6 || ang_diff(e.a3, a3) > 2e-5 ||
                info.locked || fabs(info.margin - margin) > 2e-6)
                fail_msg("%s (%.9g %.9g %.9g) came back as (%.9g %.9g %.9g) locked %d margin %.9g",
                         k_names[seq], a1, a2, a3, e.a1, e.a2, e.a3, info.locked, info.margin);
        }
    }
}

/* scipy's as_euler docs: rotvec (0, 0, pi/2) is zxy (90, 0, 0); rotvec (0, -pi/3, 0) is
 * zxy (0, 0, -60). Hand-derived: identity gives zeros for Tait-Bryan. */
static void test_to_euler_known_values(void **state)
{
    const float h = 0.70710678118655f;
    qo_quat_f32 q = { h, 0.0f, 0.0f, h };
    qo_euler_f32 e;
    qo_euler_info_f32 info;
    (void)state;
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_zxy, &e, &info), QO_OK);
    assert_float_equal(e.a1, 1.57079633f, 1e-6f);
    assert_float_equal(e.a2, 0.0f, 1e-6f); assert_float_equal(e.a3, 0.0f, 1e-6f);
    assert_int_equal(info.locked, 0);
    assert_float_equal(info.margin, 1.57079633f, 1e-6f);
    q.w = 0.86602540378444f; q.x = 0.0f; q.y = -0.5f; q.z = 0.0f;
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_zxy, &e, &info), QO_OK);
    assert_float_equal(e.a1, 0.0f, 1e-6f); assert_float_equal(e.a2, 0.0f, 1e-6f);
    assert_float_equal(e.a3, -1.04719755f, 1e-6f);
    q = qo_quat_identity_f32();
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_ZYX, &e, &info), QO_OK);
    assert_true(fabsf(e.a1) < 1e-7f && fabsf(e.a2) < 1e-7f && fabsf(e.a3) < 1e-7f);
    /* The identity is singular for proper sequences: locked, a3 = 0, a1 = 0. */
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_ZXZ, &e, &info), QO_OK);
    assert_int_equal(info.locked, 1);
    assert_true(info.margin == 0.0f && e.a3 == 0.0f && fabsf(e.a1) < 1e-7f && e.a2 == 0.0f);
    /* A non-unit input is normalised: 1e-20 and 1e20 times the yaw quaternion. */
    q.w = h * 1e-20f; q.x = 0.0f; q.y = 0.0f; q.z = h * 1e-20f;
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_ZYX, &e, NULL), QO_OK);
    assert_float_equal(e.a1, 1.57079633f, 1e-6f);
    q.w = h * 1e20f; q.z = h * 1e20f;
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_ZYX, &e, NULL), QO_OK);
    assert_float_equal(e.a1, 1.57079633f, 1e-6f);
    /* Subnormal and near-FLT_MAX components: scaled, not rejected, not overflowing. */
    q.w = 1e-40f; q.x = 0.0f; q.y = 0.0f; q.z = 1e-40f;
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_ZYX, &e, &info), QO_OK);
    assert_float_equal(e.a1, 1.57079633f, 1e-5f);
    q.w = 3e38f; q.x = 3e38f; q.y = 0.0f; q.z = 0.0f; /* 90 deg about x */
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_XYZ, &e, &info), QO_OK);
    assert_float_equal(e.a1, 1.57079633f, 1e-6f);
    assert_float_equal(e.a2, 0.0f, 1e-6f); assert_float_equal(e.a3, 0.0f, 1e-6f);
    /* A tiny but not-yet-subnormal singular input is still flagged (the margin is a ratio). */
    q.w = 0.70710678118655f * 1e-30f; q.x = 0.0f; q.y = 0.70710678118655f * 1e-30f; q.z = 0.0f;
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_ZYX, &e, &info), QO_OK);
    assert_int_equal(info.locked, 1);
    assert_float_equal(e.a2, 1.57079633f, 1e-6f);
}

/* ---- gimbal lock -------------------------------------------------------------------------- */
static double singular_value(int seq, int which)
{
    if (is_proper_name(seq)) return which ? PI_D : 0.0;
    return which ? PI_D / 2 : -PI_D / 2;
}

static void test_exactly_singular_all24(void **state)
{
    int seq, which, n;
    (void)state;
    rng.s = 99;
    for (seq = 0; seq < 24; seq++) {
        for (which = 0; which < 2; which++) {
            for (n = 0; n < 200; n++) {
                double a1 = ref_rng_range(&rng, -PI_D, PI_D), a3 = ref_rng_range(&rng, -PI_D, PI_D);
                double a2 = singular_value(seq, which);
                dq r = ref_quat_from_euler(k_names[seq], a1, a2, a3);
                qo_quat_f32 qf = f_from(r);
                qo_euler_f32 e;
                qo_euler_info_f32 info;
                double err;
                assert_int_equal(qo_quat_to_euler_f32(qf, (qo_euler_seq)seq, &e, &info), QO_OK);
                err = recompose_err(seq, e, dq_unit_from_f(qf));
                if (!info.locked || e.a3 != 0.0f || err > 1e-5 || fabs(e.a2 - a2) > 1e-5)
                    fail_msg("singular %s (%.9g %.9g %.9g): locked %d margin %.3g -> "
                             "(%.9g %.9g %.9g) recomposes %.3g off", k_names[seq], a1, a2, a3,
                             info.locked, info.margin, e.a1, e.a2, e.a3, err);
                check_ranges(seq, e, "singular");

                /* The same, built as a user would: our from_euler with the float nearest the
                 * singular angle; then with each component moved by up to 2 ulp (noise from
                 * an upstream float computation). Both must still be flagged. */
                {
                    qo_euler_f32 se;
                    qo_quat_f32 qs;
                    float *comp[4];
                    int c;
                    se.a1 = (float)a1; se.a2 = (float)a2; se.a3 = (float)a3;
                    assert_int_equal(qo_quat_from_euler_f32((qo_euler_seq)seq, se, &qs), QO_OK);
                    assert_int_equal(qo_quat_to_euler_f32(qs, (qo_euler_seq)seq, &e, &info), QO_OK);
                    err = recompose_err(seq, e, ref_quat_from_euler(k_names[seq], se.a1, a2, se.a3));
                    if (!info.locked || e.a3 != 0.0f || err > 1e-5)
                        fail_msg("singular via from_euler %s (%.9g %.9g %.9g): locked %d margin "
                                 "%.3g err %.3g", k_names[seq], se.a1, se.a2, se.a3, info.locked,
                                 info.margin, err);
                    comp[0] = &qs.w; comp[1] = &qs.x; comp[2] = &qs.y; comp[3] = &qs.z;
                    for (c = 0; c < 4; c++) {
                        int u = (int)(ref_rng_next(&rng) % 5) - 2;
                        for (; u > 0; u--) *comp[c] = nextafterf(*comp[c], INFINITY);
                        for (; u < 0; u++) *comp[c] = nextafterf(*comp[c], -INFINITY);
                    }
                    assert_int_equal(qo_quat_to_euler_f32(qs, (qo_euler_seq)seq, &e, &info), QO_OK);
                    err = recompose_err(seq, e, dq_unit_from_f(qs));
                    if (!info.locked || err > 1e-5)
                        fail_msg("singular + 2 ulp noise %s q=(%.9g %.9g %.9g %.9g): locked %d "
                                 "margin %.3g err %.3g", k_names[seq], qs.w, qs.x, qs.y, qs.z,
                                 info.locked, info.margin, err);
                }
            }
        }
    }
}

/* Hand-derived free-angle choice (a3 = 0, a1 takes the rest):
 *   ZYX (y, +pi/2, r) = Rz(y) Ry(pi/2) Rx(r) = Rz(y - r) Ry(pi/2)  ->  (y - r, pi/2, 0)
 *   ZYX (y, -pi/2, r)                          = Rz(y + r) Ry(-pi/2) -> (y + r, -pi/2, 0)
 *   ZXZ (a, 0, c) -> (a + c, 0, 0);  ZXZ (a, pi, c) = Rz(a - c) Rx(pi) -> (a - c, pi, 0)
 *   zxz (a, pi, c) = Rz(c) Rx(pi) Rz(a) = Rz(c - a) Rx(pi) = Rx(pi) Rz(a - c) -> (a - c, pi, 0) */
static void test_singular_free_angle_choice(void **state)
{
    const double y = 0.7, r = 0.2;
    qo_euler_f32 e;
    qo_euler_info_f32 info;
    (void)state;
    assert_int_equal(qo_quat_to_euler_f32(f_from(ref_quat_from_euler(k_names[17], y, PI_D / 2, r)), QO_EULER_ZYX,
                                          &e, &info), QO_OK);
    assert_int_equal(info.locked, 1);
    assert_float_equal(e.a1, (float)(y - r), 2e-6f);
    assert_float_equal(e.a2, 1.57079633f, 1e-6f);
    assert_true(e.a3 == 0.0f);
    assert_int_equal(qo_quat_to_euler_f32(f_from(ref_quat_from_euler(k_names[17], y, -PI_D / 2, r)), QO_EULER_ZYX,
                                          &e, &info), QO_OK);
    assert_int_equal(info.locked, 1);
    assert_float_equal(e.a1, (float)(y + r), 2e-6f);
    assert_true(e.a3 == 0.0f);
    assert_int_equal(qo_quat_to_euler_f32(f_from(ref_quat_from_euler(k_names[22], 0.5, 0.0, 0.4)), QO_EULER_ZXZ,
                                          &e, &info), QO_OK);
    assert_int_equal(info.locked, 1);
    assert_float_equal(e.a1, 0.9f, 2e-6f);
    assert_true(e.a3 == 0.0f);
    assert_int_equal(qo_quat_to_euler_f32(f_from(ref_quat_from_euler(k_names[22], 0.5, PI_D, 0.4)), QO_EULER_ZXZ,
                                          &e, &info), QO_OK);
    assert_int_equal(info.locked, 1);
    assert_float_equal(e.a1, 0.1f, 2e-6f);
    assert_int_equal(qo_quat_to_euler_f32(f_from(ref_quat_from_euler(k_names[10], 0.5, PI_D, 0.4)), QO_EULER_zxz,
                                          &e, &info), QO_OK);
    assert_int_equal(info.locked, 1);
    assert_float_equal(e.a1, 0.1f, 2e-6f);
    /* Exactly representable singular quaternions: ZYX pitch 90 deg alone; margin 0. */
    {
        const float h = 0.70710678118655f;
        qo_quat_f32 q = { h, 0.0f, h, 0.0f };
        assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_ZYX, &e, &info), QO_OK);
        assert_int_equal(info.locked, 1);
        assert_true(info.margin < 1e-6f);
        assert_float_equal(e.a2, 1.57079633f, 1e-6f);
        /* 180 deg about x is ZXZ (0, pi, 0): singular at pi. */
        q.w = 0.0f; q.x = 1.0f; q.y = 0.0f; q.z = 0.0f;
        assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_ZXZ, &e, &info), QO_OK);
        assert_true(info.locked && info.margin == 0.0f);
        assert_float_equal(e.a2, 3.14159265f, 1e-6f);
        assert_true(recompose_err(22, e, dq_unit_from_f(q)) < 1e-6);
    }
}

static void test_just_off_singular_all24(void **state)
{
    static const double offs[] = { 1e-5, 1e-4, 1e-3, 0.01, 0.035 };
    int seq, which, k, n, side;
    (void)state;
    rng.s = 2024;
    for (seq = 0; seq < 24; seq++)
        for (which = 0; which < 2; which++)
            for (k = 0; k < 5; k++)
                for (side = 0; side < 2; side++)
                    for (n = 0; n < 20; n++) {
                        double a1 = ref_rng_range(&rng, -PI_D, PI_D), a3 = ref_rng_range(&rng, -PI_D, PI_D);
                        double s = singular_value(seq, which);
                        /* Toward the inside of the range; past the end (side 1) is the other
                         * branch of a nearby rotation, equally valid input. */
                        double inward = (s > 0.0) ? -1.0 : 1.0;
                        double a2 = s + (side ? -inward : inward) * offs[k];
                        dq r = ref_quat_from_euler(k_names[seq], a1, a2, a3);
                        qo_quat_f32 qf = f_from(r);
                        qo_euler_f32 e;
                        qo_euler_info_f32 info;
                        double err;
                        assert_int_equal(qo_quat_to_euler_f32(qf, (qo_euler_seq)seq, &e, &info), QO_OK);
                        err = recompose_err(seq, e, dq_unit_from_f(qf));
                        if (info.locked || err > 1e-5 ||
                            fabs(info.margin - offs[k]) > 1e-6 + 1e-4 * offs[k])
                            fail_msg("%s (%.9g %.9g %.9g), %.3g off lock: locked %d margin %.6g, "
                                     "recomposes %.3g off", k_names[seq], a1, a2, a3, offs[k],
                                     info.locked, info.margin, err);
                        check_ranges(seq, e, "near-singular");
                        /* A caller band: flagged iff margin <= band; the forced a3 = 0 costs at
                         * most 2*margin. A band of 2 deg never flags the 0.035 rad case. */
                        {
                            const float band = 0.0349f; /* just under 2 deg = 0.034907 */
                            assert_int_equal(qo_quat_to_euler_band_f32(qf, (qo_euler_seq)seq, band,
                                                                       &e, &info), QO_OK);
                            err = recompose_err(seq, e, dq_unit_from_f(qf));
                            if (info.locked != (info.margin <= band) ||
                                (offs[k] > 0.0349 && info.locked) ||
                                err > (info.locked ? 2.0 * info.margin + 1e-5 : 1e-5) ||
                                (info.locked && e.a3 != 0.0f))
                                fail_msg("band %s (%.9g %.9g %.9g): locked %d margin %.6g err %.3g",
                                         k_names[seq], a1, a2, a3, info.locked, info.margin, err);
                        }
                    }
}

/* Range ends: every combination of a1, a3 in {-pi, -pi/2, 0, pi/2, pi} and a2 at the ends and
 * middle of its range (ends are singular): recomposes, stays in range, flagged iff singular. */
static void test_range_ends_all24(void **state)
{
    static const double e13[] = { -PI_D, -PI_D / 2, 0.0, PI_D / 2, PI_D };
    int seq, i1, i2, i3;
    (void)state;
    for (seq = 0; seq < 24; seq++)
        for (i1 = 0; i1 < 5; i1++)
            for (i2 = 0; i2 < 3; i2++)
                for (i3 = 0; i3 < 5; i3++) {
                    double a2 = is_proper_name(seq) ? (i2 == 0 ? 0.0 : (i2 == 1 ? PI_D / 2 : PI_D))
                                                    : (i2 == 0 ? -PI_D / 2 : (i2 == 1 ? 0.0 : PI_D / 2));
                    dq r = ref_quat_from_euler(k_names[seq], e13[i1], a2, e13[i3]);
                    qo_quat_f32 qf = f_from(r);
                    qo_euler_f32 e;
                    qo_euler_info_f32 info;
                    double err;
                    assert_int_equal(qo_quat_to_euler_f32(qf, (qo_euler_seq)seq, &e, &info), QO_OK);
                    err = recompose_err(seq, e, dq_unit_from_f(qf));
                    check_ranges(seq, e, "range ends");
                    if (err > 1e-5 || info.locked != (i2 != 1))
                        fail_msg("range ends %s (%.9g %.9g %.9g) -> (%.9g %.9g %.9g) locked %d err %.3g",
                                 k_names[seq], e13[i1], a2, e13[i3], e.a1, e.a2, e.a3, info.locked, err);
                }
}

/* ---- bad inputs ------------------------------------------------------------------------- */
static void expect_to_euler_error(qo_quat_f32 q, qo_euler_seq seq, float band, qo_status want,
                                  const char *what)
{
    qo_euler_f32 e = { 9.0f, 9.0f, 9.0f };
    qo_euler_info_f32 info = { 7, 9.0f };
    qo_euler_f32 prev = { 0.5f, 0.25f, -0.5f };
    qo_status st = qo_quat_to_euler_band_f32(q, seq, band, &e, &info);
    if (st != want || e.a1 != 0.0f || e.a2 != 0.0f || e.a3 != 0.0f || info.locked != 0 ||
        info.margin != 0.0f)
        fail_msg("%s: band status %d (want %d), out (%g %g %g) info {%d %g}", what, (int)st,
                 (int)want, e.a1, e.a2, e.a3, info.locked, info.margin);
    e.a1 = 9.0f; info.locked = 7;
    st = qo_quat_to_euler_near_f32(q, seq, prev, band, &e, &info);
    if (st != want || e.a1 != prev.a1 || e.a2 != prev.a2 || e.a3 != prev.a3 || info.locked != 0)
        fail_msg("%s: near status %d (want %d), out (%g %g %g) is not prev", what, (int)st,
                 (int)want, e.a1, e.a2, e.a3);
    if (band == QO_EULER_LOCK_BAND_F32) {
        e.a1 = 9.0f;
        st = qo_quat_to_euler_f32(q, seq, &e, NULL);
        if (st != want || e.a1 != 0.0f) fail_msg("%s: default status %d", what, (int)st);
    }
}

static void test_to_euler_bad_inputs(void **state)
{
    qo_quat_f32 ok = { 0.9f, 0.1f, 0.2f, 0.3f }, q;
    qo_euler_f32 e, prev = { 0.0f, 0.0f, 0.0f };
    qo_euler_info_f32 info;
    int i;
    (void)state;
    for (i = 0; i < 8; i++) {
        q = ok;
        switch (i) {
        case 0: q.w = NAN; break;
        case 1: q.x = INFINITY; break;
        case 2: q.y = -INFINITY; break;
        case 3: q.z = NAN; break;
        case 4: q.w = NAN; q.x = NAN; q.y = NAN; q.z = NAN; break;
        case 5: q.x = 3e38f; q.y = INFINITY; break;
        case 6: q.w = -NAN; break;
        default: q.z = -INFINITY; break;
        }
        expect_to_euler_error(q, QO_EULER_ZYX, QO_EULER_LOCK_BAND_F32, QO_E_NONFINITE, "non-finite q");
    }
    q.w = q.x = q.y = q.z = 0.0f;
    expect_to_euler_error(q, QO_EULER_xyx, QO_EULER_LOCK_BAND_F32, QO_E_DEGENERATE, "zero q");
    q.w = -0.0f;
    expect_to_euler_error(q, QO_EULER_XYZ, QO_EULER_LOCK_BAND_F32, QO_E_DEGENERATE, "-0 q");
    expect_to_euler_error(ok, QO_EULER_SEQ_COUNT_, QO_EULER_LOCK_BAND_F32, QO_E_ARG, "bad seq");
    expect_to_euler_error(ok, (qo_euler_seq)-1, QO_EULER_LOCK_BAND_F32, QO_E_ARG, "negative seq");
    expect_to_euler_error(ok, QO_EULER_XYZ, -1e-3f, QO_E_RANGE, "negative band");
    expect_to_euler_error(ok, QO_EULER_XYZ, 1.6f, QO_E_RANGE, "band > pi/2");
    expect_to_euler_error(ok, QO_EULER_XYZ, NAN, QO_E_NONFINITE, "NaN band");
    expect_to_euler_error(ok, QO_EULER_XYZ, INFINITY, QO_E_NONFINITE, "Inf band");
    assert_int_equal(qo_quat_to_euler_f32(ok, QO_EULER_XYZ, NULL, &info), QO_E_NULL);
    assert_int_equal(qo_quat_to_euler_band_f32(ok, QO_EULER_XYZ, 0.1f, NULL, &info), QO_E_NULL);
    assert_int_equal(qo_quat_to_euler_near_f32(ok, QO_EULER_XYZ, prev, 0.1f, NULL, &info), QO_E_NULL);
    /* A non-finite prev: zeros, not a copy of the NaN. */
    for (i = 0; i < 3; i++) {
        qo_euler_f32 bad = prev;
        if (i == 0) bad.a1 = NAN; else if (i == 1) bad.a2 = INFINITY; else bad.a3 = -INFINITY;
        e.a1 = e.a2 = e.a3 = 9.0f;
        assert_int_equal(qo_quat_to_euler_near_f32(ok, QO_EULER_XYZ, bad, 0.1f, &e, &info),
                         QO_E_NONFINITE);
        assert_true(e.a1 == 0.0f && e.a2 == 0.0f && e.a3 == 0.0f && info.locked == 0);
    }
    /* Band limits themselves are accepted. */
    assert_int_equal(qo_quat_to_euler_band_f32(ok, QO_EULER_XYZ, 0.0f, &e, &info), QO_OK);
    assert_int_equal(qo_quat_to_euler_band_f32(ok, QO_EULER_XYZ, 1.57079632679490f, &e, &info), QO_OK);
    assert_int_equal(info.locked, 1); /* pi/2 flags everything */
    assert_true(recompose_err(12, e, dq_unit_from_f(ok)) <= 2.0 * info.margin + 1e-5);
}

/* ---- nearest solution ------------------------------------------------------------------- */
static double dmax(double a, double b) { return a > b ? a : b; }

/* Follows a path of true joint angles true(t) through a singularity; the nearest decomposition
 * must track it (including outside scipy's ranges) without jumps. */
static void run_path(int seq, double a1_0, double a1_1, double a2_0, double a2_1, double a3_0,
                     double a3_1, int steps, float band, double track_tol, const char *what)
{
    /* A path whose a2 is symmetric about a singular value is exactly singular at its midpoint,
     * which must then be flagged whatever the band. */
    double mid2 = 0.5 * (a2_0 + a2_1);
    int singular_mid = fabs(mid2 - PI_D / 2) < 1e-12 || fabs(mid2 + PI_D / 2) < 1e-12 ||
                       fabs(mid2) < 1e-12 || fabs(mid2 - PI_D) < 1e-12;
    qo_euler_f32 prev, out;
    qo_euler_info_f32 info;
    int k;
    prev.a1 = (float)a1_0; prev.a2 = (float)a2_0; prev.a3 = (float)a3_0;
    for (k = 0; k <= steps; k++) {
        double t = (double)k / steps;
        double a1 = a1_0 + (a1_1 - a1_0) * t, a2 = a2_0 + (a2_1 - a2_0) * t;
        double a3 = a3_0 + (a3_1 - a3_0) * t;
        dq r;
        qo_quat_f32 qf;
        double err, jump, dev;
        if (2 * k == steps) a2 = 0.5 * (a2_0 + a2_1); /* the midpoint exactly */
        r = ref_quat_from_euler(k_names[seq], a1, a2, a3);
        qf = f_from(r);
        assert_int_equal(qo_quat_to_euler_near_f32(qf, (qo_euler_seq)seq, prev, band, &out, &info),
                         QO_OK);
        err = recompose_err(seq, out, dq_unit_from_f(qf));
        jump = dmax(fabs(out.a1 - prev.a1), dmax(fabs(out.a2 - prev.a2), fabs(out.a3 - prev.a3)));
        dev = dmax(fabs(out.a1 - a1), dmax(fabs(out.a2 - a2), fabs(out.a3 - a3)));
        if (err > (info.locked ? 2.0 * info.margin + 1e-5 : 1e-5) || jump > 0.06 ||
            dev > (info.margin > 0.03 ? track_tol : 0.06) || (info.locked && out.a3 != prev.a3) ||
            (2 * k == steps && singular_mid && !info.locked))
            fail_msg("%s %s step %d: true (%.6f %.6f %.6f) got (%.6f %.6f %.6f) prev "
                     "(%.6f %.6f %.6f) locked %d margin %.3g err %.3g", what, k_names[seq], k,
                     a1, a2, a3, out.a1, out.a2, out.a3, prev.a1, prev.a2, prev.a3, info.locked,
                     info.margin, err);
        prev = out;
    }
}

static void test_near_through_singularity_all24(void **state)
{
    int seq;
    (void)state;
    for (seq = 0; seq < 24; seq++) {
        double s = is_proper_name(seq) ? 0.0 : PI_D / 2;
        /* a2 crosses the singular value (leaving scipy's range on the far side), a1 and a3 move
         * meanwhile; 100 steps of 0.004 rad in a2. Default band and a 0.01 rad hold band. */
        run_path(seq, 0.3, 1.1, s - 0.2, s + 0.2, -0.5, 0.1, 100, QO_EULER_LOCK_BAND_F32, 1e-4,
                 "through lock (default band)");
        run_path(seq, 0.3, 1.1, s + 0.2, s - 0.2, -0.5, 0.1, 100, 0.01f, 1e-4,
                 "through lock (0.01 band)");
        if (is_proper_name(seq))
            run_path(seq, -2.0, -1.0, PI_D - 0.2, PI_D + 0.2, 2.0, 2.5, 100, 0.01f, 1e-4,
                     "through pi");
        else
            run_path(seq, -2.0, -1.0, -s + 0.2, -s - 0.2, 2.0, 2.5, 100, 0.01f, 1e-4,
                     "through -pi/2");
    }
}

static void test_near_across_wrap_and_turns(void **state)
{
    int seq;
    (void)state;
    for (seq = 0; seq < 24; seq++) {
        double mid = is_proper_name(seq) ? 1.0 : 0.3;
        /* a1 crosses +pi, a3 crosses -pi: no 2pi jumps. */
        run_path(seq, 3.0, 3.4, mid, mid + 0.1, -3.0, -3.4, 40, QO_EULER_LOCK_BAND_F32, 1e-4,
                 "across wrap");
        /* Several turns of the first joint: keeps counting. */
        run_path(seq, 0.0, 20.0, mid, mid, 0.5, -0.5, 400, QO_EULER_LOCK_BAND_F32, 1e-4, "turns");
    }
}

static void test_near_picks_branch_and_locks(void **state)
{
    int seq;
    (void)state;
    rng.s = 555;
    for (seq = 0; seq < 24; seq++) {
        double a1 = ref_rng_range(&rng, -2.5, 2.5), a3 = ref_rng_range(&rng, -2.5, 2.5);
        double a2 = is_proper_name(seq) ? 1.2 : 0.6;
        double alt2 = is_proper_name(seq) ? -a2 : PI_D - a2;
        dq r = ref_quat_from_euler(k_names[seq], a1, a2, a3);
        qo_quat_f32 qf = f_from(r);
        qo_euler_f32 prev, out;
        qo_euler_info_f32 info;
        /* prev near the alternative branch, two turns up on a1. */
        prev.a1 = (float)(a1 + PI_D + 4 * PI_D + 0.05);
        prev.a2 = (float)(alt2 - 0.05);
        prev.a3 = (float)(a3 + PI_D - 0.05);
        assert_int_equal(qo_quat_to_euler_near_f32(qf, (qo_euler_seq)seq, prev, 0.0f, &out, &info),
                         QO_OK);
        if (fabs(out.a1 - (a1 + 5 * PI_D)) > 1e-5 || fabs(out.a2 - alt2) > 1e-5 ||
            fabs(out.a3 - (a3 + PI_D)) > 1e-5 || recompose_err(seq, out, r) > 1e-5)
            fail_msg("near %s alt branch: got (%.7f %.7f %.7f) want (%.7f %.7f %.7f)", k_names[seq],
                     out.a1, out.a2, out.a3, a1 + 5 * PI_D, alt2, a3 + PI_D);
        /* prev near the principal branch. */
        prev.a1 = (float)(a1 - 0.1); prev.a2 = (float)(a2 + 0.1); prev.a3 = (float)(a3 + 0.1);
        assert_int_equal(qo_quat_to_euler_near_f32(qf, (qo_euler_seq)seq, prev, 0.0f, &out, &info),
                         QO_OK);
        if (fabs(out.a1 - a1) > 1e-5 || fabs(out.a2 - a2) > 1e-5 || fabs(out.a3 - a3) > 1e-5)
            fail_msg("near %s principal: got (%.7f %.7f %.7f)", k_names[seq], out.a1, out.a2, out.a3);
        /* Exactly singular: a3 stays at prev.a3 exactly and the result composes to q. */
        r = ref_quat_from_euler(k_names[seq], a1, singular_value(seq, 1), a3);
        qf = f_from(r);
        prev.a1 = 0.25f; prev.a2 = (float)singular_value(seq, 1); prev.a3 = 7.5f;
        assert_int_equal(qo_quat_to_euler_near_f32(qf, (qo_euler_seq)seq, prev,
                                                   QO_EULER_LOCK_BAND_F32, &out, &info), QO_OK);
        if (!info.locked || out.a3 != 7.5f || recompose_err(seq, out, dq_unit_from_f(qf)) > 1e-5 ||
            fabs(out.a1 - prev.a1) > PI_D)
            fail_msg("near %s at lock: locked %d got (%.7f %.7f %.7f) err %.3g", k_names[seq],
                     info.locked, out.a1, out.a2, out.a3, recompose_err(seq, out, dq_unit_from_f(qf)));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_seq_parse_and_name),
        cmocka_unit_test(test_seq_parse_rejects),
        cmocka_unit_test(test_from_euler_random_all24),
        cmocka_unit_test(test_from_euler_known_values),
        cmocka_unit_test(test_from_euler_bad_inputs),
        cmocka_unit_test(test_to_euler_random_rotations_all24),
        cmocka_unit_test(test_to_euler_recovers_angles_all24),
        cmocka_unit_test(test_to_euler_known_values),
        cmocka_unit_test(test_exactly_singular_all24),
        cmocka_unit_test(test_singular_free_angle_choice),
        cmocka_unit_test(test_just_off_singular_all24),
        cmocka_unit_test(test_range_ends_all24),
        cmocka_unit_test(test_to_euler_bad_inputs),
        cmocka_unit_test(test_near_through_singularity_all24),
        cmocka_unit_test(test_near_across_wrap_and_turns),
        cmocka_unit_test(test_near_picks_branch_and_locks),
    };
    return cmocka_run_group_tests_name("euler", tests, NULL, NULL);
}
