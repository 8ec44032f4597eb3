/* qorient/interp.h: lerp, nlerp, slerp (short, long, rate), key alignment, Bezier, Shoemake
 * spline and Squad, float32, checked against double-precision references written here from the
 * textbook formulas (not from the code under test), with fixed-seed random inputs and edge
 * tables. Every failure names the case and its inputs. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "qorient/interp.h"
#include "qorient/quat.h"

#define PI 3.14159265358979323846

/* ---- double reference quaternion algebra ------------------------------------------------ */
#include "common/dq_interp.h"

static dq dq_from(qo_quat_f32 q) { dq r = { q.w, q.x, q.y, q.z }; return r; }
static double norm_dev(qo_quat_f32 q) { return fabs(dq_norm(dq_from(q)) - 1.0); }

/* Shortest-way slerp of (normalised) a, b. */
static dq d_slerp(dq a, dq b, double t)
{
    a = dq_unit(a); b = dq_unit(b);
    if (dq_dot(a, b) < 0) b = dq_neg(b);
    return d_slerp_raw(a, b, t);
}

/* ---- check helper ----------------------------------------------------------------------- */
#define CHECK(cond, ...) do { if (!(cond)) { fail_msg(__VA_ARGS__); } } while (0)
#define QF(q) (double)(q).w, (double)(q).x, (double)(q).y, (double)(q).z
#define QFMT "(%.9g %.9g %.9g %.9g)"

static int q_bits_equal(qo_quat_f32 a, qo_quat_f32 b) { return memcmp(&a, &b, sizeof a) == 0; }
static qo_quat_f32 unit_f(qo_quat_f32 q)
{
    qo_quat_f32 u;
    assert_int_equal(qo_quat_normalize_f32(q, &u), QO_OK);
    return u;
}
static qo_quat_f32 neg_f(qo_quat_f32 q) { qo_quat_f32 r = { -q.w, -q.x, -q.y, -q.z }; return r; }
static const qo_quat_f32 ZERO_Q = { 0.0f, 0.0f, 0.0f, 0.0f };

#define TOL_ROT 1e-6  /* rad, slerp / Bezier result vs double reference */
#define TOL_NORM 1e-6 /* | |q| - 1 | */

/* ---- slerp ------------------------------------------------------------------------------ */

/* One slerp case against the double reference: rotation error, 4-D error (the sign is
 * specified: nearest a), unit norm. */
static void check_slerp_case(const char *name, qo_quat_f32 a, qo_quat_f32 b, float t)
{
    qo_quat_f32 out;
    qo_status st = qo_quat_slerp_f32(a, b, t, &out);
    dq ref = d_slerp(dq_from(a), dq_from(b), (double)t);
    double re = rot_err(ref, dq_from(out)), d4 = dist4(dq_unit(ref), dq_from(out));
    CHECK(st == QO_OK, "%s: status %d a=" QFMT " b=" QFMT " t=%.9g", name, (int)st, QF(a),
          QF(b), (double)t);
    CHECK(re <= TOL_ROT && d4 <= TOL_ROT, "%s: rotation error %.3g, 4-D error %.3g a=" QFMT
          " b=" QFMT " t=%.9g out=" QFMT, name, re, d4, QF(a), QF(b), (double)t, QF(out));
    CHECK(norm_dev(out) <= TOL_NORM, "%s: norm deviation %.3g a=" QFMT " b=" QFMT " t=%.9g",
          name, norm_dev(out), QF(a), QF(b), (double)t);
}

static void test_slerp_random_vs_double(void **state)
{
    int i;
    (void)state;
    rng_seed(0x51E4F00Dull);
    for (i = 0; i < 3000; i++) {
        qo_quat_f32 a = f_from(rand_unit()), b = f_from(rand_unit());
        float t = (float)rng_u();
        if (i % 3 == 1) { /* non-unit inputs, scaled by 1e-3 .. 1e3 */
            double ka = pow(10.0, rng_range(-3, 3)), kb = pow(10.0, rng_range(-3, 3));
            a = f_from(dq_scale(dq_from(a), ka));
            b = f_from(dq_scale(dq_from(b), kb));
        }
        check_slerp_case("random", a, b, t);
    }
}

/* Edge table: b at rotation angle delta from a (random axis), with both signs of b, at a grid
 * of t including the exact ends. delta covers identical, nearly identical (1e-7..1e-3 rad),
 * around the series threshold, and nearly 180 deg (dot from 5e-6 up). */
static void test_slerp_edge_table(void **state)
{
    static const double deltas[] = { 0.0, 1e-7, 3e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1.9e-3, 2e-3,
                                      2.1e-3, 1e-2, 0.5, 2.0, PI - 1e-2, PI - 1e-3, PI - 1e-4,
                                      PI - 1e-5 };
    static const float ts[] = { 0.0f, 1e-7f, 1e-3f, 0.25f, 0.5f, 0.75f, 0.999f, 0.9999999f,
                                1.0f };
    size_t di, ti;
    int k, sgn;
    (void)state;
    rng_seed(0xED6Eull);
    for (k = 0; k < 8; k++) {
        dq a = rand_unit();
        for (di = 0; di < sizeof deltas / sizeof deltas[0]; di++) {
            dq b = dq_mul(a, rand_axis_rot(deltas[di]));
            for (sgn = 0; sgn < 2; sgn++) {
                qo_quat_f32 fa = f_from(a), fb = f_from(sgn ? dq_neg(b) : b);
                for (ti = 0; ti < sizeof ts / sizeof ts[0]; ti++) {
                    char name[96];
                    snprintf(name, sizeof name, "edge delta=%.3g sign=%s", deltas[di],
                             sgn ? "-b" : "+b");
                    check_slerp_case(name, fa, fb, ts[ti]);
                }
            }
        }
    }
}

/* q vs -q and q vs q: the result is the rotation q for every t, unit length (the cglm /
 * filament bug averages q and -q to near zero). */
static void test_slerp_same_rotation_opposite_sign(void **state)
{
    int i, k;
    (void)state;
    rng_seed(0x0990ull);
    for (i = 0; i < 200; i++) {
        qo_quat_f32 q = f_from(rand_unit());
        for (k = 0; k <= 16; k++) {
            float t = (float)k / 16.0f;
            qo_quat_f32 o1, o2;
            assert_int_equal(qo_quat_slerp_f32(q, neg_f(q), t, &o1), QO_OK);
            assert_int_equal(qo_quat_slerp_f32(q, q, t, &o2), QO_OK);
            CHECK(rot_err(dq_from(q), dq_from(o1)) <= TOL_ROT && norm_dev(o1) <= TOL_NORM,
                  "q vs -q: q=" QFMT " t=%g out=" QFMT, QF(q), (double)t, QF(o1));
            CHECK(dist4(dq_from(q), dq_from(o1)) <= TOL_ROT,
                  "q vs -q: sign must stay that of a: q=" QFMT " t=%g out=" QFMT, QF(q),
                  (double)t, QF(o1));
            CHECK(dist4(dq_from(q), dq_from(o2)) <= TOL_ROT && norm_dev(o2) <= TOL_NORM,
                  "q vs q: q=" QFMT " t=%g out=" QFMT, QF(q), (double)t, QF(o2));
        }
    }
}

/* Exactly 180 deg of rotation apart: dot == 0 exactly in float. No flip; the path is the great
 * circle through a and b (the double reference makes the same choice). */
static void test_slerp_exact_180(void **state)
{
    static const qo_quat_f32 pairs[][2] = {
        { { 1.0f, 0.0f, 0.0f, 0.0f }, { 0.0f, 1.0f, 0.0f, 0.0f } },
        { { 1.0f, 0.0f, 0.0f, 0.0f }, { 0.0f, 0.0f, 0.0f, -1.0f } },
        { { 0.5f, 0.5f, 0.5f, 0.5f }, { 0.5f, -0.5f, 0.5f, -0.5f } },
        { { 0.0f, 0.6f, 0.8f, 0.0f }, { 0.0f, -0.8f, 0.6f, 0.0f } },
    };
    size_t i;
    int k;
    (void)state;
    for (i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        assert_true(qo_quat_dot_f32(pairs[i][0], pairs[i][1]) == 0.0f);
        for (k = 0; k <= 8; k++) {
            char name[64];
            snprintf(name, sizeof name, "exact 180 pair %u", (unsigned)i);
            check_slerp_case(name, pairs[i][0], pairs[i][1], (float)k / 8.0f);
        }
    }
}

/* Nearly 180 deg where |dot| is below float rounding: which of the two (almost equally short)
 * ways is taken is decided by rounding, so either reference is accepted; the result must still
 * be one of them to 1e-6 and unit length. */
static void test_slerp_nearly_180_ambiguous(void **state)
{
    int i, k;
    (void)state;
    rng_seed(0x180180ull);
    for (i = 0; i < 100; i++) {
        dq a = rand_unit(), b = dq_mul(a, rand_axis_rot(PI - 1e-7 * rng_u()));
        qo_quat_f32 fa = f_from(a), fb = f_from(b);
        for (k = 0; k <= 8; k++) {
            float t = (float)k / 8.0f;
            qo_quat_f32 out;
            dq ua = dq_unit(dq_from(fa)), ub = dq_unit(dq_from(fb));
            double e1, e2;
            assert_int_equal(qo_quat_slerp_f32(fa, fb, t, &out), QO_OK);
            e1 = rot_err(d_slerp_raw(ua, ub, t), dq_from(out));
            e2 = rot_err(d_slerp_raw(ua, dq_neg(ub), t), dq_from(out));
            CHECK((e1 <= TOL_ROT || e2 <= TOL_ROT) && norm_dev(out) <= TOL_NORM,
                  "nearly 180: errors %.3g / %.3g a=" QFMT " b=" QFMT " t=%g", e1, e2, QF(fa),
                  QF(fb), (double)t);
        }
    }
}

/* t == 0 and t == 1 give the normalised inputs bit-exactly; t == 1 with dot < 0 gives -b. */
static void test_slerp_exact_endpoints(void **state)
{
    int i;
    (void)state;
    rng_seed(0xE4D5ull);
    for (i = 0; i < 500; i++) {
        qo_quat_f32 a = f_from(dq_scale(rand_unit(), rng_range(0.5, 2))),
                    b = f_from(dq_scale(rand_unit(), rng_range(0.5, 2)));
        qo_quat_f32 o0, o1, ua = unit_f(a), ub = unit_f(b);
        if (qo_quat_dot_f32(ua, ub) < 0.0f) ub = neg_f(ub);
        assert_int_equal(qo_quat_slerp_f32(a, b, 0.0f, &o0), QO_OK);
        assert_int_equal(qo_quat_slerp_f32(a, b, 1.0f, &o1), QO_OK);
        CHECK(q_bits_equal(o0, ua), "t=0: a=" QFMT " b=" QFMT " out=" QFMT, QF(a), QF(b),
              QF(o0));
        CHECK(q_bits_equal(o1, ub), "t=1: a=" QFMT " b=" QFMT " out=" QFMT " want " QFMT,
              QF(a), QF(b), QF(o1), QF(ub));
    }
}

/* Constant angular rate: angle(a, slerp(a, b, t)) == t * angle(a, b). */
static void test_slerp_constant_rate(void **state)
{
    int i, k;
    (void)state;
    rng_seed(0xC0457ull);
    for (i = 0; i < 300; i++) {
        dq a = rand_unit(), b = dq_mul(a, rand_axis_rot(rng_range(0, PI)));
        qo_quat_f32 fa = f_from(a), fb = f_from(b);
        double phi = rot_err(dq_from(fa), dq_from(fb));
        for (k = 0; k <= 20; k++) {
            float t = (float)k / 20.0f;
            qo_quat_f32 out;
            double ang;
            assert_int_equal(qo_quat_slerp_f32(fa, fb, t, &out), QO_OK);
            ang = rot_err(dq_from(fa), dq_from(out));
            CHECK(fabs(ang - (double)t * phi) <= 2 * TOL_ROT,
                  "rate: angle %.9g want %.9g (phi %.9g) a=" QFMT " b=" QFMT " t=%g", ang,
                  (double)t * phi, phi, QF(fa), QF(fb), (double)t);
        }
    }
}

/* Every error: status and the documented output value. */
static void test_slerp_errors(void **state)
{
    const qo_quat_f32 a = { 0.0f, 0.0f, 0.0f, 2.0f }, b = { 1.0f, 0.0f, 0.0f, 0.0f };
    const qo_quat_f32 ua = { 0.0f, 0.0f, 0.0f, 1.0f }, id = { 1.0f, 0.0f, 0.0f, 0.0f };
    const qo_quat_f32 nanq = { NAN, 0.0f, 0.0f, 1.0f }, infq = { 1.0f, INFINITY, 0.0f, 0.0f };
    static const float bad_t[] = { -1e-7f, -1.0f, 1.0000001f, 2.0f };
    qo_quat_f32 out;
    size_t i;
    int which;
    (void)state;
    for (which = 0; which < 2; which++) {
        qo_status (*f)(qo_quat_f32, qo_quat_f32, float, qo_quat_f32 *) =
            which ? qo_quat_slerp_long_f32 : qo_quat_slerp_f32;
        assert_int_equal(f(a, b, 0.5f, NULL), QO_E_NULL);
        for (i = 0; i < sizeof bad_t / sizeof bad_t[0]; i++) {
            CHECK(f(a, b, bad_t[i], &out) == QO_E_RANGE && q_bits_equal(out, ua),
                  "slerp%s t=%.9g: want QO_E_RANGE and unit a", which ? "_long" : "",
                  (double)bad_t[i]);
        }
        CHECK(f(a, b, NAN, &out) == QO_E_NONFINITE && q_bits_equal(out, ua), "t=NaN %d", which);
        CHECK(f(a, b, INFINITY, &out) == QO_E_NONFINITE && q_bits_equal(out, ua), "t=Inf %d",
              which);
        CHECK(f(ZERO_Q, b, 0.5f, &out) == QO_E_DEGENERATE && q_bits_equal(out, id), "a=0 %d",
              which);
        CHECK(f(a, ZERO_Q, 0.5f, &out) == QO_E_DEGENERATE && q_bits_equal(out, id), "b=0 %d",
              which);
        CHECK(f(nanq, b, 0.5f, &out) == QO_E_NONFINITE && q_bits_equal(out, id), "a=NaN %d",
              which);
        CHECK(f(a, infq, 0.5f, &out) == QO_E_NONFINITE && q_bits_equal(out, id), "b=Inf %d",
              which);
        /* NaN wins over zero, whichever argument holds it */
        CHECK(f(ZERO_Q, nanq, 0.5f, &out) == QO_E_NONFINITE, "a=0 b=NaN %d", which);
        /* bad t with bad quaternion: the quaternion is reported */
        CHECK(f(nanq, b, 3.0f, &out) == QO_E_NONFINITE && q_bits_equal(out, id),
              "a=NaN t=3 %d", which);
    }
}

/* ---- slerp long ------------------------------------------------------------------------- */

static void test_slerp_long(void **state)
{
    int i, k;
    double worst_k = 0;
    (void)state;
    rng_seed(0x1046ull);
    for (i = 0; i < 300; i++) {
        dq a = rand_unit(), b = dq_mul(a, rand_axis_rot(rng_range(0.01, PI)));
        qo_quat_f32 fa = f_from(a), fb = f_from(i % 2 ? dq_neg(b) : b);
        dq ua = dq_unit(dq_from(fa)), ub = dq_unit(dq_from(fb));
        double phi = rot_err(ua, ub), psi;
        if (dq_dot(ua, ub) > 0) ub = dq_neg(ub);
        psi = 2 * PI - phi; /* the long rotation angle */
        for (k = 0; k <= 16; k++) {
            float t = (float)k / 16.0f;
            qo_quat_f32 out;
            dq ref = d_slerp_raw(ua, ub, t);
            double ang, want = (double)t * psi, e4;
            assert_int_equal(qo_quat_slerp_long_f32(fa, fb, t, &out), QO_OK);
            /* documented accuracy of the long way: 1e-6/phi (input rounding / |a + b'|) */
            e4 = dist4(dq_unit(ref), dq_from(out));
            if (e4 * phi > worst_k) worst_k = e4 * phi;
            CHECK(e4 <= TOL_ROT + 1e-6 / phi && norm_dev(out) <= TOL_NORM,
                  "long: 4-D error %.3g a=" QFMT " b=" QFMT " t=%g", e4, QF(fa), QF(fb),
                  (double)t);
            if (want > PI) want = 2 * PI - want;
            ang = rot_err(ua, dq_from(out));
            CHECK(fabs(ang - want) <= 2 * TOL_ROT + 2e-6 / phi,
                  "long rate: angle %.9g want %.9g a=" QFMT " b=" QFMT " t=%g", ang, want,
                  QF(fa), QF(fb), (double)t);
        }
    }
    print_message("slerp_long: worst 4-D error * phi = %.3g\n", worst_k);
    {   /* same rotation: no axis, refused */
        qo_quat_f32 q = f_from(rand_unit()), out;
        assert_int_equal(qo_quat_slerp_long_f32(q, q, 0.5f, &out), QO_E_DEGENERATE);
        assert_true(q_bits_equal(out, unit_f(q)));
        assert_int_equal(qo_quat_slerp_long_f32(q, neg_f(q), 0.5f, &out), QO_E_DEGENERATE);
    }
}

/* ---- lerp / nlerp ----------------------------------------------------------------------- */

static void test_lerp(void **state)
{
    int i;
    qo_quat_f32 out;
    const qo_quat_f32 a = { 1.0f, 2.0f, 3.0f, 4.0f }, b = { -1.0f, 0.5f, 0.0f, 8.0f };
    const qo_quat_f32 id = { 1.0f, 0.0f, 0.0f, 0.0f }, nanq = { NAN, 0.0f, 0.0f, 0.0f };
    (void)state;
    rng_seed(0x1E4Bull);
    for (i = 0; i < 500; i++) {
        qo_quat_f32 p = f_from(dq_scale(rand_unit(), 3)), q = f_from(rand_unit());
        float t = (float)rng_u();
        dq ref = dq_add(dq_scale(dq_from(p), 1.0 - (double)t), dq_scale(dq_from(q), (double)t));
        assert_int_equal(qo_quat_lerp_f32(p, q, t, &out), QO_OK);
        CHECK(dist4(ref, dq_from(out)) <= 1e-6, "lerp p=" QFMT " q=" QFMT " t=%g", QF(p), QF(q),
              (double)t);
    }
    assert_int_equal(qo_quat_lerp_f32(a, b, 0.0f, &out), QO_OK);
    assert_true(q_bits_equal(out, a));
    assert_int_equal(qo_quat_lerp_f32(a, b, 1.0f, &out), QO_OK);
    assert_true(q_bits_equal(out, b));
    /* no normalisation, no flip: the midpoint of q and -q is zero */
    assert_int_equal(qo_quat_lerp_f32(a, neg_f(a), 0.5f, &out), QO_OK);
    assert_true(out.w == 0.0f && out.x == 0.0f && out.y == 0.0f && out.z == 0.0f);
    assert_int_equal(qo_quat_lerp_f32(ZERO_Q, b, 0.5f, &out), QO_OK);
    assert_int_equal(qo_quat_lerp_f32(a, b, 1.5f, &out), QO_E_RANGE);
    assert_true(q_bits_equal(out, a));
    assert_int_equal(qo_quat_lerp_f32(a, b, NAN, &out), QO_E_NONFINITE);
    assert_true(q_bits_equal(out, a));
    assert_int_equal(qo_quat_lerp_f32(nanq, b, 0.5f, &out), QO_E_NONFINITE);
    assert_true(q_bits_equal(out, id));
    assert_int_equal(qo_quat_lerp_f32(a, b, 0.5f, NULL), QO_E_NULL);
}

static void test_nlerp(void **state)
{
    int i;
    qo_quat_f32 out, out2;
    const qo_quat_f32 id = { 1.0f, 0.0f, 0.0f, 0.0f };
    (void)state;
    rng_seed(0x41E4Bull);
    for (i = 0; i < 1000; i++) {
        dq a = rand_unit(), b = rand_unit();
        qo_quat_f32 fa = f_from(dq_scale(a, rng_range(0.1, 10))), fb = f_from(b);
        float t = (float)rng_u();
        dq ua = dq_unit(dq_from(fa)), ub = dq_unit(dq_from(fb)), ref;
        if (dq_dot(ua, ub) < 0) ub = dq_neg(ub); /* shortest way */
        ref = dq_unit(dq_add(dq_scale(ua, 1.0 - (double)t), dq_scale(ub, (double)t)));
        assert_int_equal(qo_quat_nlerp_f32(fa, fb, t, &out), QO_OK);
        CHECK(dist4(ref, dq_from(out)) <= 1e-6 && norm_dev(out) <= TOL_NORM,
              "nlerp a=" QFMT " b=" QFMT " t=%g out=" QFMT, QF(fa), QF(fb), (double)t, QF(out));
        /* -b: same path */
        assert_int_equal(qo_quat_nlerp_f32(fa, neg_f(fb), t, &out2), QO_OK);
        CHECK(dist4(dq_from(out), dq_from(out2)) <= 1e-6, "nlerp -b a=" QFMT " b=" QFMT " t=%g",
              QF(fa), QF(fb), (double)t);
        /* short way: never further from a than b' */
        CHECK(rot_err(ua, dq_from(out)) <= rot_err(ua, ub) + 1e-6,
              "nlerp not on the short arc a=" QFMT " b=" QFMT " t=%g", QF(fa), QF(fb),
              (double)t);
    }
    {   /* q vs -q stays q; ends; errors */
        qo_quat_f32 q = f_from(rand_unit());
        assert_int_equal(qo_quat_nlerp_f32(q, neg_f(q), 0.5f, &out), QO_OK);
        assert_true(dist4(dq_from(q), dq_from(out)) <= 1e-6);
        assert_int_equal(qo_quat_nlerp_f32(q, neg_f(q), 1.0f, &out), QO_OK);
        assert_true(q_bits_equal(out, unit_f(q)));
        assert_int_equal(qo_quat_nlerp_f32(q, id, 2.0f, &out), QO_E_RANGE);
        assert_true(q_bits_equal(out, unit_f(q)));
        assert_int_equal(qo_quat_nlerp_f32(q, ZERO_Q, 0.5f, &out), QO_E_DEGENERATE);
        assert_true(q_bits_equal(out, id));
        assert_int_equal(qo_quat_nlerp_f32(q, id, NAN, &out), QO_E_NONFINITE);
        assert_int_equal(qo_quat_nlerp_f32(q, id, 0.5f, NULL), QO_E_NULL);
    }
}

/* ---- slerp rate ------------------------------------------------------------------------- */

static void test_slerp_rate(void **state)
{
    int i;
    qo_vec3_f32 w;
    (void)state;
    rng_seed(0x4A7Eull);
    for (i = 0; i < 500; i++) {
        dq a = rand_unit(), b = rand_unit();
        qo_quat_f32 fa = f_from(a), fb = f_from(b);
        float T = (float)rng_range(0.01, 10);
        dq ua = dq_unit(dq_from(fa)), ub = dq_unit(dq_from(fb)), lg;
        double ex, ey, ez, tol;
        if (dq_dot(ua, ub) < 0) ub = dq_neg(ub);
        lg = dq_log(dq_mul(dq_conj(ua), ub));
        assert_int_equal(qo_quat_slerp_rate_f32(fa, fb, T, &w), QO_OK);
        ex = (double)w.x - 2 * lg.x / (double)T;
        ey = (double)w.y - 2 * lg.y / (double)T;
        ez = (double)w.z - 2 * lg.z / (double)T;
        tol = 1e-6 / (double)T; /* 1e-6 rad of angle over T */
        CHECK(sqrt(ex * ex + ey * ey + ez * ez) <= tol, "rate a=" QFMT " b=" QFMT " T=%g", QF(fa),
              QF(fb), (double)T);
    }
    {
        qo_quat_f32 q = f_from(rand_unit());
        assert_int_equal(qo_quat_slerp_rate_f32(q, q, 0.0f, &w), QO_E_RANGE);
        assert_true(w.x == 0.0f && w.y == 0.0f && w.z == 0.0f);
        assert_int_equal(qo_quat_slerp_rate_f32(q, q, -1.0f, &w), QO_E_RANGE);
        assert_int_equal(qo_quat_slerp_rate_f32(q, q, NAN, &w), QO_E_NONFINITE);
        assert_int_equal(qo_quat_slerp_rate_f32(q, ZERO_Q, 1.0f, &w), QO_E_DEGENERATE);
        assert_int_equal(qo_quat_slerp_rate_f32(q, q, 1.0f, NULL), QO_E_NULL);
        assert_int_equal(qo_quat_slerp_rate_f32(q, neg_f(q), 1.0f, &w), QO_OK);
        assert_true(fabs((double)w.x) + fabs((double)w.y) + fabs((double)w.z) <= 1e-6);
    }
}

/* ---- key alignment ---------------------------------------------------------------------- */

static void test_align_keys(void **state)
{
    qo_quat_f32 k[6], o[6];
    const qo_quat_f32 id = { 1.0f, 0.0f, 0.0f, 0.0f };
    dq prev;
    int i;
    (void)state;
    rng_seed(0xA11Full);
    prev = rand_unit();
    for (i = 0; i < 6; i++) {
        prev = dq_mul(prev, rand_axis_rot(rng_range(0.1, 3.0)));
        k[i] = f_from(dq_scale(i % 2 ? dq_neg(prev) : prev, 1.0 + i));
    }
    assert_int_equal(qo_quat_align_keys_f32(k, 6, o), QO_OK);
    CHECK(q_bits_equal(o[0], unit_f(k[0])), "aligned key 0 keeps its sign %d", 0);
    for (i = 1; i < 6; i++) {
        CHECK(qo_quat_dot_f32(o[i - 1], o[i]) >= 0.0f && rot_err(dq_from(o[i]), dq_from(k[i]))
              <= 1e-6 && norm_dev(o[i]) <= TOL_NORM, "aligned key %d", i);
    }
    /* in place gives the same */
    assert_int_equal(qo_quat_align_keys_f32(k, 6, k), QO_OK);
    for (i = 0; i < 6; i++) CHECK(q_bits_equal(k[i], o[i]), "in-place key %d", i);
    assert_int_equal(qo_quat_align_keys_f32(k, 0, o), QO_E_TOO_FEW);
    assert_int_equal(qo_quat_align_keys_f32(NULL, 3, o), QO_E_NULL);
    for (i = 0; i < 3; i++) assert_true(q_bits_equal(o[i], id));
    k[2] = ZERO_Q;
    assert_int_equal(qo_quat_align_keys_f32(k, 6, o), QO_E_DEGENERATE);
    for (i = 0; i < 6; i++) assert_true(q_bits_equal(o[i], id));
    k[4].y = NAN;
    assert_int_equal(qo_quat_align_keys_f32(k, 6, o), QO_E_NONFINITE);
}

/* ---- Bezier ----------------------------------------------------------------------------- */

/* de Casteljau in double with textbook slerp over sign-aligned, normalised points. */
static dq d_bezier(const qo_quat_f32 *c, size_t n, double t)
{
    dq p[16];
    size_t i, lev;
    p[0] = dq_unit(dq_from(c[0]));
    for (i = 1; i < n; i++) {
        p[i] = dq_unit(dq_from(c[i]));
        if (dq_dot(p[i - 1], p[i]) < 0) p[i] = dq_neg(p[i]);
    }
    for (lev = n - 1; lev > 0; lev--)
        for (i = 0; i < lev; i++) p[i] = dq_unit(d_slerp_raw(p[i], p[i + 1], t));
    return p[0];
}

static void test_bezier(void **state)
{
    qo_quat_f32 c[QO_BEZIER_MAX_POINTS + 1], out, o2;
    const qo_quat_f32 id = { 1.0f, 0.0f, 0.0f, 0.0f };
    int i, k;
    size_t n;
    (void)state;
    rng_seed(0xBE21E4ull);
    for (i = 0; i < 400; i++) {
        dq p = rand_unit();
        n = 2 + (size_t)(i % (QO_BEZIER_MAX_POINTS - 1));
        for (k = 0; k < (int)n; k++) {
            p = dq_mul(p, rand_axis_rot(rng_range(0, 1.5)));
            c[k] = f_from(dq_scale(rng_u() < 0.3 ? dq_neg(p) : p, rng_range(0.5, 2)));
        }
        for (k = 0; k <= 10; k++) {
            float t = (float)k / 10.0f;
            dq ref = d_bezier(c, n, (double)t);
            assert_int_equal(qo_quat_bezier_f32(c, n, t, &out), QO_OK);
            CHECK(dist4(ref, dq_from(out)) <= 2 * TOL_ROT && norm_dev(out) <= TOL_NORM,
                  "bezier n=%u t=%g error %.3g", (unsigned)n, (double)t,
                  dist4(ref, dq_from(out)));
        }
        /* exact end points */
        assert_int_equal(qo_quat_bezier_f32(c, n, 0.0f, &out), QO_OK);
        CHECK(q_bits_equal(out, unit_f(c[0])), "bezier t=0 n=%u", (unsigned)n);
        assert_int_equal(qo_quat_bezier_f32(c, n, 1.0f, &out), QO_OK);
        CHECK((q_bits_equal(out, unit_f(c[n - 1])) || q_bits_equal(out, neg_f(unit_f(c[n - 1])))),
              "bezier t=1 n=%u", (unsigned)n);
        if (n == 2) { /* a 2-point Bezier is slerp */
            for (k = 0; k <= 10; k++) {
                float t = (float)k / 10.0f;
                assert_int_equal(qo_quat_bezier_f32(c, 2, t, &out), QO_OK);
                assert_int_equal(qo_quat_slerp_f32(c[0], c[1], t, &o2), QO_OK);
                CHECK(dist4(dq_from(out), dq_from(o2)) <= TOL_ROT, "bezier2 vs slerp t=%g",
                      (double)t);
            }
        }
        if (n == 4) { /* the cubic shortcut is the same function */
            assert_int_equal(qo_quat_bezier3_f32(c[0], c[1], c[2], c[3], 0.3f, &o2), QO_OK);
            assert_int_equal(qo_quat_bezier_f32(c, 4, 0.3f, &out), QO_OK);
            assert_true(q_bits_equal(out, o2));
        }
    }
    /* errors */
    for (k = 0; k <= QO_BEZIER_MAX_POINTS; k++) c[k] = f_from(rand_unit());
    assert_int_equal(qo_quat_bezier_f32(c, QO_BEZIER_MAX_POINTS + 1, 0.5f, &out), QO_E_CAPACITY);
    assert_true(q_bits_equal(out, id));
    assert_int_equal(qo_quat_bezier_f32(c, QO_BEZIER_MAX_POINTS, 0.5f, &out), QO_OK);
    assert_int_equal(qo_quat_bezier_f32(c, 1, 0.5f, &out), QO_E_TOO_FEW);
    assert_int_equal(qo_quat_bezier_f32(c, 0, 0.5f, &out), QO_E_TOO_FEW);
    assert_int_equal(qo_quat_bezier_f32(NULL, 3, 0.5f, &out), QO_E_NULL);
    assert_true(q_bits_equal(out, id));
    assert_int_equal(qo_quat_bezier_f32(c, 3, 0.5f, NULL), QO_E_NULL);
    assert_int_equal(qo_quat_bezier_f32(c, 3, -0.5f, &out), QO_E_RANGE);
    assert_true(q_bits_equal(out, unit_f(c[0])));
    assert_int_equal(qo_quat_bezier_f32(c, 3, NAN, &out), QO_E_NONFINITE);
    assert_true(q_bits_equal(out, unit_f(c[0])));
    c[1] = ZERO_Q;
    assert_int_equal(qo_quat_bezier_f32(c, 3, 0.5f, &out), QO_E_DEGENERATE);
    assert_true(q_bits_equal(out, id));
    c[2].z = INFINITY;
    assert_int_equal(qo_quat_bezier3_f32(c[0], c[1], c[2], c[3], 0.5f, &out), QO_E_NONFINITE);
}

/* ---- Shoemake spline -------------------------------------------------------------------- */

#define MAXK 12

static dq d_bezier4(dq p0, dq p1, dq p2, dq p3, double t)
{
    dq p01 = dq_unit(d_slerp_raw(p0, p1, t)), p12 = dq_unit(d_slerp_raw(p1, p2, t));
    dq p23 = dq_unit(d_slerp_raw(p2, p3, t));
    dq p012 = dq_unit(d_slerp_raw(p01, p12, t)), p123 = dq_unit(d_slerp_raw(p12, p23, t));
    return dq_unit(d_slerp_raw(p012, p123, t));
}

static dq d_spline_eval(const dq *q, const dq *a, const dq *b, size_t n, double s)
{
    size_t i = (size_t)s;
    if (i > n - 2) i = n - 2;
    return d_bezier4(q[i], a[i], b[i + 1], q[i + 1], s - (double)i);
}

/* A random key sequence: steps of 0.05..maxstep rad, random signs and scales (unaligned). */
static void rand_keys(qo_quat_f32 *k, size_t n, double maxstep)
{
    dq p = rand_unit();
    size_t i;
    for (i = 0; i < n; i++) {
        if (i) p = dq_mul(p, rand_axis_rot(rng_range(0.05, maxstep)));
        k[i] = f_from(dq_scale(rng_u() < 0.4 ? dq_neg(p) : p, rng_range(0.5, 2)));
    }
}

/* aligned unit double keys from float keys */
static void d_align(const qo_quat_f32 *k, size_t n, dq *q)
{
    size_t i;
    for (i = 0; i < n; i++) {
        q[i] = dq_unit(dq_from(k[i]));
        if (i && dq_dot(q[i - 1], q[i]) < 0) q[i] = dq_neg(q[i]);
    }
}

static void test_spline_vs_double_and_through_keys(void **state)
{
    qo_quat_f32 k[MAXK], a[MAXK], b[MAXK], out;
    dq q[MAXK], da[MAXK], db[MAXK];
    int it, j;
    size_t n, i;
    (void)state;
    rng_seed(0x5B11E5ull);
    for (it = 0; it < 120; it++) {
        n = 2 + (size_t)(it % (MAXK - 1));
        rand_keys(k, n, it % 2 ? 1.5 : 3.0);
        d_align(k, n, q);
        d_spline_controls(q, n, da, db);
        assert_int_equal(qo_quat_spline_controls_f32(k, n, a, b), QO_OK);
        for (i = 0; i < n; i++) { /* control points (a_{n-1}, b_0 unused) */
            if (i + 1 < n)
                CHECK(dist4(da[i], dq_from(a[i])) <= 2e-6, "spline a[%u] n=%u error %.3g",
                      (unsigned)i, (unsigned)n, dist4(da[i], dq_from(a[i])));
            if (i > 0)
                CHECK(dist4(db[i], dq_from(b[i])) <= 2e-6, "spline b[%u] n=%u error %.3g",
                      (unsigned)i, (unsigned)n, dist4(db[i], dq_from(b[i])));
        }
        for (i = 0; i < n; i++) { /* passes through every key, with the aligned sign */
            assert_int_equal(qo_quat_spline_eval_f32(k, a, b, n, (float)i, &out), QO_OK);
            CHECK(dist4(q[i], dq_from(out)) <= TOL_ROT && norm_dev(out) <= TOL_NORM,
                  "spline through key %u of %u: error %.3g", (unsigned)i, (unsigned)n,
                  dist4(q[i], dq_from(out)));
        }
        for (j = 0; j < 40; j++) { /* anywhere vs the double construction */
            float s = (float)(rng_u() * (double)(n - 1));
            dq ref = d_spline_eval(q, da, db, n, (double)s);
            assert_int_equal(qo_quat_spline_eval_f32(k, a, b, n, s, &out), QO_OK);
            CHECK(dist4(ref, dq_from(out)) <= 3e-6 && norm_dev(out) <= TOL_NORM,
                  "spline n=%u s=%.9g error %.3g", (unsigned)n, (double)s,
                  dist4(ref, dq_from(out)));
        }
        if (n == 2) { /* two keys: the spline is slerp */
            for (j = 0; j <= 10; j++) {
                qo_quat_f32 o2;
                float s = (float)j / 10.0f;
                assert_int_equal(qo_quat_spline_eval_f32(k, a, b, n, s, &out), QO_OK);
                assert_int_equal(qo_quat_slerp_f32(k[0], k[1], s, &o2), QO_OK);
                CHECK(dist4(dq_from(out), dq_from(o2)) <= 2 * TOL_ROT,
                      "2-key spline vs slerp s=%g", (double)s);
            }
        }
    }
}

/* Body-frame rotation vector 2 log(conj(p) x) in double. */
static void rotvec(qo_quat_f32 p, qo_quat_f32 x, double v[3])
{
    dq l = dq_log(dq_mul(dq_conj(dq_unit(dq_from(p))), dq_unit(dq_from(x))));
    if (dq_dot(dq_from(p), dq_from(x)) < 0) l = dq_log(dq_mul(dq_conj(dq_unit(dq_from(p))),
                                                              dq_neg(dq_unit(dq_from(x)))));
    v[0] = 2 * l.x; v[1] = 2 * l.y; v[2] = 2 * l.z;
}
static void rotvec_d(dq p, dq x, double v[3])
{
    dq l;
    if (dq_dot(p, x) < 0) x = dq_neg(x);
    l = dq_log(dq_mul(dq_conj(p), x));
    v[0] = 2 * l.x; v[1] = 2 * l.y; v[2] = 2 * l.z;
}

/* One-sided second-order angular velocity at s0 from samples at s0 + sg*h, s0 + sg*2h
 * (sg = +1 right, -1 left): r(x) = w x + c x^2 + e x^3 gives (4 r(h) - r(2h)) / (2h) =
 * w - 2 e h^2 = w - r''' h^2 / 3. */
static void omega_side(const double r1[3], const double r2[3], double h, double sg, double w[3])
{
    int c;
    for (c = 0; c < 3; c++) w[c] = sg * (4 * r1[c] - r2[c]) / (2 * h);
}
static double vdist(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* C1 at every join: the angular velocity just left and just right of each inner key agrees.
 * Tolerance, derived per join:
 *  - rounding: each sample's orientation error is <= e (measured here against the double
 *    construction), so each rotation vector r is off by <= 2e and the stencil (4 r1 - r2)/(2h)
 *    by <= 10e/(2h) = 5e/h per side: 10e/h for the difference of the two sides;
 *  - truncation: -r''' h^2/3 per side; r''' h^2 is estimated on the double construction as
 *    |w(h) - w(2h)| (the stencil at 2h is off by 4 r''' h^2/3), counted twice for safety.
 * The same estimator then must see the kink of piecewise slerp through the same keys (its
 * velocity jumps at each key) - which shows the check can fail. */
static void test_spline_c1(void **state)
{
    qo_quat_f32 k[MAXK], a[MAXK], b[MAXK], f[5];
    dq q[MAXK], da[MAXK], db[MAXK];
    const double h = 1.0 / 64; /* exact in float, so s0 +- h, +- 2h are exact */
    int it;
    size_t n, i;
    double worst_ratio = 0;
    (void)state;
    rng_seed(0xC1C1ull);
    for (it = 0; it < 40; it++) {
        n = 3 + (size_t)(it % (MAXK - 2));
        rand_keys(k, n, 1.5);
        d_align(k, n, q);
        d_spline_controls(q, n, da, db);
        assert_int_equal(qo_quat_spline_controls_f32(k, n, a, b), QO_OK);
        for (i = 1; i + 1 < n; i++) {
            double s0 = (double)i, e = 0, rl1[3], rl2[3], rr1[3], rr2[3], wl[3], wr[3];
            double dr1[3], dr2[3], dl1[3], dl2[3], dwr1[3], dwr2[3], dwl1[3], dwl2[3];
            double trunc, tol, jump;
            int j;
            dq dref[5];
            for (j = 0; j < 5; j++) { /* s0-2h, s0-h, s0, s0+h, s0+2h */
                double s = s0 + (j - 2) * h;
                assert_int_equal(qo_quat_spline_eval_f32(k, a, b, n, (float)s, &f[j]), QO_OK);
                dref[j] = d_spline_eval(q, da, db, n, s);
                if (rot_err(dref[j], dq_from(f[j])) > e) e = rot_err(dref[j], dq_from(f[j]));
            }
            rotvec(f[2], f[1], rl1); rotvec(f[2], f[0], rl2);
            rotvec(f[2], f[3], rr1); rotvec(f[2], f[4], rr2);
            omega_side(rl1, rl2, h, -1, wl);
            omega_side(rr1, rr2, h, 1, wr);
            /* truncation estimate from the double construction at h and 2h */
            {
                dq m2 = d_spline_eval(q, da, db, n, s0 - 4 * h);
                dq m1 = dref[0], p1 = dref[4], p2 = d_spline_eval(q, da, db, n, s0 + 4 * h);
                rotvec_d(dref[2], dref[1], dl1); rotvec_d(dref[2], m1, dl2);
                rotvec_d(dref[2], dref[3], dr1); rotvec_d(dref[2], p1, dr2);
                omega_side(dl1, dl2, h, -1, dwl1); omega_side(dr1, dr2, h, 1, dwr1);
                rotvec_d(dref[2], m1, dl1); rotvec_d(dref[2], m2, dl2);
                rotvec_d(dref[2], p1, dr1); rotvec_d(dref[2], p2, dr2);
                omega_side(dl1, dl2, 2 * h, -1, dwl2); omega_side(dr1, dr2, 2 * h, 1, dwr2);
                trunc = 2 * (vdist(dwl1, dwl2) + vdist(dwr1, dwr2)) / 3;
            }
            tol = 10 * e / h + 2 * trunc + 1e-9;
            jump = vdist(wl, wr);
            if (jump / tol > worst_ratio) worst_ratio = jump / tol;
            CHECK(jump <= tol, "C1 at key %u of %u: |w_left - w_right| = %.3g rad/s > tol %.3g "
                  "(e=%.3g, trunc=%.3g)", (unsigned)i, (unsigned)n, jump, tol, e, trunc);
            /* Sensitivity: piecewise slerp through the same keys has a velocity jump. */
            {
                qo_quat_f32 g[5];
                double gl1[3], gl2[3], gr1[3], gr2[3], gwl[3], gwr[3];
                for (j = 0; j < 5; j++) {
                    double s = s0 + (j - 2) * h;
                    size_t seg = (j < 2) ? i - 1 : i;
                    assert_int_equal(qo_quat_slerp_f32(k[seg], k[seg + 1],
                                                       (float)(s - (double)seg), &g[j]), QO_OK);
                }
                rotvec(g[2], g[1], gl1); rotvec(g[2], g[0], gl2);
                rotvec(g[2], g[3], gr1); rotvec(g[2], g[4], gr2);
                omega_side(gl1, gl2, h, -1, gwl);
                omega_side(gr1, gr2, h, 1, gwr);
                CHECK(vdist(gwl, gwr) > 10 * tol, "C1 check too weak: piecewise slerp jump %.3g "
                      "vs tol %.3g at key %u", vdist(gwl, gwr), tol, (unsigned)i);
            }
        }
    }
    print_message("spline C1: worst |jump| / tolerance = %.3f\n", worst_ratio);
}

/* Flipping the sign of any keys (and scaling them) gives the same rotations everywhere. */
static void test_spline_sign_invariance(void **state)
{
    qo_quat_f32 k[MAXK], k2[MAXK], a[MAXK], b[MAXK], a2[MAXK], b2[MAXK], o1, o2, o3;
    int it, j;
    size_t n, i;
    (void)state;
    rng_seed(0x516Full);
    for (it = 0; it < 60; it++) {
        n = 2 + (size_t)(it % (MAXK - 1));
        rand_keys(k, n, 2.0);
        for (i = 0; i < n; i++) {
            k2[i] = (rng_u() < 0.5) ? neg_f(k[i]) : k[i];
        }
        k2[0] = neg_f(k[0]); /* always flip the first one too */
        assert_int_equal(qo_quat_spline_controls_f32(k, n, a, b), QO_OK);
        assert_int_equal(qo_quat_spline_controls_f32(k2, n, a2, b2), QO_OK);
        for (j = 0; j <= 50; j++) {
            float s = (float)((double)j / 50.0 * (double)(n - 1));
            assert_int_equal(qo_quat_spline_eval_f32(k, a, b, n, s, &o1), QO_OK);
            assert_int_equal(qo_quat_spline_eval_f32(k2, a2, b2, n, s, &o2), QO_OK);
            /* unaligned caller keys with the first controls: same curve */
            assert_int_equal(qo_quat_spline_eval_f32(k2, a, b, n, s, &o3), QO_OK);
            CHECK(rot_err(dq_from(o1), dq_from(o2)) <= TOL_ROT &&
                  rot_err(dq_from(o1), dq_from(o3)) <= TOL_ROT,
                  "sign-flipped keys n=%u s=%g: %.3g / %.3g", (unsigned)n, (double)s,
                  rot_err(dq_from(o1), dq_from(o2)), rot_err(dq_from(o1), dq_from(o3)));
            CHECK(dist4(dq_from(o1), dq_from(o3)) <= TOL_ROT,
                  "output sign must follow the aligned keys n=%u s=%g", (unsigned)n, (double)s);
        }
    }
}

/* The end rule of the notes: keys at a uniform rate about one axis give a_0 = q_0 and
 * b_{N-1} = q_{N-1} (the spline starts and ends at rest; documented). */
static void test_spline_end_rule(void **state)
{
    qo_quat_f32 k[5], a[5], b[5];
    dq base, step;
    int i;
    (void)state;
    rng_seed(0xE2Dull);
    base = rand_unit();
    step = rand_axis_rot(0.4);
    for (i = 0; i < 5; i++) {
        k[i] = f_from(base);
        base = dq_mul(base, step);
    }
    assert_int_equal(qo_quat_spline_controls_f32(k, 5, a, b), QO_OK);
    CHECK(rot_err(dq_from(a[0]), dq_from(k[0])) <= 2e-6, "a_0 = q_0 for uniform keys: %.3g",
          rot_err(dq_from(a[0]), dq_from(k[0])));
    CHECK(rot_err(dq_from(b[4]), dq_from(k[4])) <= 2e-6, "b_N = q_N for uniform keys: %.3g",
          rot_err(dq_from(b[4]), dq_from(k[4])));
    /* and the interior controls sit at 1/3 of the uniform step (Catmull-Rom on the circle) */
    for (i = 1; i < 4; i++) {
        double ang = rot_err(dq_from(k[i]), dq_from(a[i]));
        CHECK(fabs(ang - 0.4 / 3) <= 2e-6, "a_%d at %.9g rad, want %.9g", i, ang, 0.4 / 3);
    }
}

static void test_spline_errors(void **state)
{
    qo_quat_f32 k[4], a[4], b[4], out;
    const qo_quat_f32 id = { 1.0f, 0.0f, 0.0f, 0.0f };
    int i;
    (void)state;
    rng_seed(0xE44ull);
    rand_keys(k, 4, 1.0);
    assert_int_equal(qo_quat_spline_controls_f32(k, 1, a, b), QO_E_TOO_FEW);
    assert_true(q_bits_equal(a[0], id) && q_bits_equal(b[0], id));
    assert_int_equal(qo_quat_spline_controls_f32(NULL, 4, a, b), QO_E_NULL);
    for (i = 0; i < 4; i++) assert_true(q_bits_equal(a[i], id) && q_bits_equal(b[i], id));
    assert_int_equal(qo_quat_spline_controls_f32(k, 4, NULL, b), QO_E_NULL);
    assert_int_equal(qo_quat_spline_controls_f32(k, 4, a, b), QO_OK);
    /* s out of range: nearest end key */
    assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 4, -0.001f, &out), QO_E_RANGE);
    assert_true(q_bits_equal(out, unit_f(k[0])));
    assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 4, 3.001f, &out), QO_E_RANGE);
    assert_true(q_bits_equal(out, unit_f(k[3])));
    assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 4, NAN, &out), QO_E_NONFINITE);
    assert_true(q_bits_equal(out, unit_f(k[0])));
    assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 4, INFINITY, &out), QO_E_NONFINITE);
    assert_true(q_bits_equal(out, unit_f(k[3])));
    assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 4, 3.0f, &out), QO_OK);
    assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 1, 0.0f, &out), QO_E_TOO_FEW);
    assert_true(q_bits_equal(out, id));
    assert_int_equal(qo_quat_spline_eval_f32(k, NULL, b, 4, 1.0f, &out), QO_E_NULL);
    assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 4, 1.0f, NULL), QO_E_NULL);
    k[1] = ZERO_Q;
    assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 4, 0.5f, &out), QO_E_DEGENERATE);
    assert_true(q_bits_equal(out, id));
    assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 4, 2.5f, &out), QO_OK); /* other segment */
    assert_int_equal(qo_quat_spline_controls_f32(k, 4, a, b), QO_E_DEGENERATE);
    for (i = 0; i < 4; i++) assert_true(q_bits_equal(a[i], id) && q_bits_equal(b[i], id));
    k[3].w = NAN;
    assert_int_equal(qo_quat_spline_controls_f32(k, 4, a, b), QO_E_NONFINITE);
}

/* A 180-deg swing out and back (q0 == q2, q1 at 90 deg of 4-D angle): the bisector is undefined
 * and the documented choice is a zero tangent at q1; the curve stays finite, unit and through
 * the keys. */
static void test_spline_swing_back(void **state)
{
    const qo_quat_f32 k[3] = { { 1.0f, 0.0f, 0.0f, 0.0f }, { 0.0f, 0.0f, 1.0f, 0.0f },
                               { 1.0f, 0.0f, 0.0f, 0.0f } };
    qo_quat_f32 a[3], b[3], out;
    int j;
    (void)state;
    assert_int_equal(qo_quat_spline_controls_f32(k, 3, a, b), QO_OK);
    CHECK(rot_err(dq_from(a[1]), dq_from(k[1])) <= 1e-6 && rot_err(dq_from(b[1]), dq_from(k[1]))
          <= 1e-6, "swing back: zero tangent at the middle key %d", 1);
    for (j = 0; j <= 20; j++) {
        float s = (float)j / 10.0f;
        assert_int_equal(qo_quat_spline_eval_f32(k, a, b, 3, s, &out), QO_OK);
        CHECK(qo_quat_is_finite_f32(out) && norm_dev(out) <= TOL_NORM, "swing back s=%g",
              (double)s);
    }
}

/* ---- Squad ------------------------------------------------------------------------------ */

static dq d_squad(dq q0, dq s0, dq s1, dq q1, double t)
{
    dq x = dq_unit(d_slerp_raw(q0, q1, t)), y = dq_unit(d_slerp_raw(s0, s1, t));
    return dq_unit(d_slerp_raw(x, y, 2 * t * (1 - t)));
}

static void test_squad(void **state)
{
    qo_quat_f32 k[MAXK], s[MAXK], out, o2;
    const qo_quat_f32 id = { 1.0f, 0.0f, 0.0f, 0.0f };
    dq q[MAXK], ds[MAXK];
    int it, j;
    size_t n, i;
    (void)state;
    rng_seed(0x50AAull);
    for (it = 0; it < 100; it++) {
        n = 2 + (size_t)(it % (MAXK - 1));
        rand_keys(k, n, 1.5);
        d_align(k, n, q);
        d_squad_controls(q, n, ds);
        assert_int_equal(qo_quat_squad_controls_f32(k, n, s), QO_OK);
        for (i = 0; i < n; i++)
            CHECK(dist4(ds[i], dq_from(s[i])) <= 2e-6, "squad s[%u] of %u: %.3g", (unsigned)i,
                  (unsigned)n, dist4(ds[i], dq_from(s[i])));
        for (i = 0; i + 1 < n; i++) {
            /* through the keys, exactly */
            assert_int_equal(qo_quat_squad_f32(k[i], s[i], s[i + 1], k[i + 1], 0.0f, &out), QO_OK);
            CHECK(q_bits_equal(out, unit_f(k[i])), "squad t=0 segment %u", (unsigned)i);
            assert_int_equal(qo_quat_squad_f32(k[i], s[i], s[i + 1], k[i + 1], 1.0f, &out), QO_OK);
            CHECK(rot_err(dq_from(out), dq_from(k[i + 1])) <= TOL_ROT, "squad t=1 segment %u",
                  (unsigned)i);
            for (j = 1; j < 10; j++) {
                float t = (float)j / 10.0f;
                dq ref = d_squad(q[i], ds[i], ds[i + 1], q[i + 1], (double)t);
                assert_int_equal(qo_quat_squad_f32(k[i], s[i], s[i + 1], k[i + 1], t, &out),
                                 QO_OK);
                CHECK(rot_err(ref, dq_from(out)) <= 3e-6 && norm_dev(out) <= TOL_NORM,
                      "squad segment %u t=%g: %.3g", (unsigned)i, (double)t,
                      rot_err(ref, dq_from(out)));
                /* caller signs do not matter */
                assert_int_equal(qo_quat_squad_f32(neg_f(k[i]), s[i], neg_f(s[i + 1]), k[i + 1],
                                                   t, &o2), QO_OK);
                CHECK(rot_err(dq_from(o2), dq_from(out)) <= TOL_ROT, "squad signs t=%g",
                      (double)t);
            }
        }
    }
    assert_int_equal(qo_quat_squad_f32(k[0], s[0], s[1], k[1], 1.5f, &out), QO_E_RANGE);
    assert_true(q_bits_equal(out, unit_f(k[0])));
    assert_int_equal(qo_quat_squad_f32(k[0], ZERO_Q, s[1], k[1], 0.5f, &out), QO_E_DEGENERATE);
    assert_true(q_bits_equal(out, id));
    assert_int_equal(qo_quat_squad_f32(k[0], s[0], s[1], k[1], NAN, &out), QO_E_NONFINITE);
    assert_int_equal(qo_quat_squad_f32(k[0], s[0], s[1], k[1], 0.5f, NULL), QO_E_NULL);
    assert_int_equal(qo_quat_squad_controls_f32(k, 1, s), QO_E_TOO_FEW);
    assert_int_equal(qo_quat_squad_controls_f32(NULL, 3, s), QO_E_NULL);
    for (i = 0; i < 3; i++) assert_true(q_bits_equal(s[i], id));
    k[1].x = NAN;
    assert_int_equal(qo_quat_squad_controls_f32(k, 3, s), QO_E_NONFINITE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_slerp_random_vs_double),
        cmocka_unit_test(test_slerp_edge_table),
        cmocka_unit_test(test_slerp_same_rotation_opposite_sign),
        cmocka_unit_test(test_slerp_exact_180),
        cmocka_unit_test(test_slerp_nearly_180_ambiguous),
        cmocka_unit_test(test_slerp_exact_endpoints),
        cmocka_unit_test(test_slerp_constant_rate),
        cmocka_unit_test(test_slerp_errors),
        cmocka_unit_test(test_slerp_long),
        cmocka_unit_test(test_lerp),
        cmocka_unit_test(test_nlerp),
        cmocka_unit_test(test_slerp_rate),
        cmocka_unit_test(test_align_keys),
        cmocka_unit_test(test_bezier),
        cmocka_unit_test(test_spline_vs_double_and_through_keys),
        cmocka_unit_test(test_spline_c1),
        cmocka_unit_test(test_spline_sign_invariance),
        cmocka_unit_test(test_spline_end_rule),
        cmocka_unit_test(test_spline_errors),
        cmocka_unit_test(test_spline_swing_back),
        cmocka_unit_test(test_squad),
    };
    return cmocka_run_group_tests_name("interp", tests, NULL, NULL);
}
