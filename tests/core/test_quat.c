/*
 * qorient/quat.h: every function against the double references of tests/common/ref.c over
 * fixed-seed random inputs, plus the edges (zero, NaN, Inf, FLT_MAX, subnormal, identical,
 * antipodal, tiny angles, canonical ties) and the lecture's worked examples.
 */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "common/ref.h"
#include "common/scalar_inline.h"
#include "qorient/convert.h"
#include "qorient/quat.h"

/* A status check inside a loop over cases: names the call and the case on failure. */
#define EXPECT_OK(call, n) do { \
        qo_status st_ = (call); \
        if (st_ != QO_OK) fail_msg("%s: status %d in case %d", #call, (int)st_, (int)(n)); \
    } while (0)

#define N_RANDOM 2000

static qo_quat_f32 qf(float w, float x, float y, float z)
{
    qo_quat_f32 q;
    q.w = w; q.x = x; q.y = y; q.z = z;
    return q;
}

static qo_vec3_f32 vf(float x, float y, float z)
{
    qo_vec3_f32 v;
    v.x = x; v.y = y; v.z = z;
    return v;
}

static int is_identity_q(qo_quat_f32 q)
{
    return q.w == 1.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f;
}

static int is_zero_v(qo_vec3_f32 v)
{
    return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f;
}

static void print_q(const char *name, qo_quat_f32 q)
{
    print_error("  %s = (%.9g, %.9g, %.9g, %.9g)\n", name, q.w, q.x, q.y, q.z);
}

/* Largest componentwise |a - b| relative to scale. */
static double qdiff(qo_quat_f32 a, ref_quat b)
{
    double d = fabs(a.w - b.w), e;
    e = fabs(a.x - b.x); if (e > d) d = e;
    e = fabs(a.y - b.y); if (e > d) d = e;
    e = fabs(a.z - b.z); if (e > d) d = e;
    return d;
}

static ref_quat rscale(ref_quat q, double s)
{
    q.w *= s; q.x *= s; q.y *= s; q.z *= s;
    return q;
}

/* A random quaternion with a random scale over [1e-3, 1e3] (so products stay in range). */
static ref_quat rand_q_scaled(ref_rng *rng)
{
    return rscale(ref_rng_quat(rng), pow(10.0, ref_rng_range(rng, -3.0, 3.0)));
}

/* ---- algebra ---- */

static void test_identity_conj_dot(void **state)
{
    ref_rng rng = { 1 };
    int n;
    (void)state;
    assert_true(is_identity_q(qo_quat_identity_f32()));
    for (n = 0; n < N_RANDOM; n++) {
        qo_quat_f32 a = ref_quat_to_f32(rand_q_scaled(&rng)), b = ref_quat_to_f32(rand_q_scaled(&rng));
        qo_quat_f32 c = qo_quat_conj_f32(a);
        double d = (double)a.w * b.w + (double)a.x * b.x + (double)a.y * b.y + (double)a.z * b.z;
        double mag = ref_quat_norm(ref_quat_from_f32(a)) * ref_quat_norm(ref_quat_from_f32(b));
        if (c.w != a.w || c.x != -a.x || c.y != -a.y || c.z != -a.z)
            fail_msg("conj case %d wrong%s", n, "");
        if (fabs(qo_quat_dot_f32(a, b) - d) > 1e-6 * mag) {
            print_q("a", a);
            print_q("b", b);
            fail_msg("dot case %d: %.9g vs %.9g", n, qo_quat_dot_f32(a, b), d);
        }
    }
}

static void test_mul_vs_double(void **state)
{
    ref_rng rng = { 2 };
    int n;
    (void)state;
    for (n = 0; n < N_RANDOM; n++) {
        ref_quat ra = rand_q_scaled(&rng), rb = rand_q_scaled(&rng), rc = ref_rng_quat(&rng);
        qo_quat_f32 a = ref_quat_to_f32(ra), b = ref_quat_to_f32(rb), c = ref_quat_to_f32(rc);
        ref_quat ab = ref_quat_mul(ref_quat_from_f32(a), ref_quat_from_f32(b));
        qo_quat_f32 p = qo_quat_mul_f32(a, b);
        double mag = ref_quat_norm(ref_quat_from_f32(a)) * ref_quat_norm(ref_quat_from_f32(b));
        qo_quat_f32 l, r;
        if (qdiff(p, ab) > 5e-7 * mag) {
            print_q("a", a);
            print_q("b", b);
            print_q("a*b", p);
            fail_msg("mul case %d: error %.3g (|a||b| = %.3g)", n, qdiff(p, ab), mag);
        }
        /* Norms multiply. */
        if (fabs(qo_quat_norm_f32(p) - mag) > 1e-6 * mag)
            fail_msg("mul case %d: |a*b| %.9g vs |a||b| %.9g", n, qo_quat_norm_f32(p), mag);
        /* Associativity (unit operands so the tolerance is absolute). */
        a = ref_quat_to_f32(ref_rng_quat(&rng));
        b = ref_quat_to_f32(ref_rng_quat(&rng));
        l = qo_quat_mul_f32(qo_quat_mul_f32(a, b), c);
        r = qo_quat_mul_f32(a, qo_quat_mul_f32(b, c));
        if (qdiff(l, ref_quat_from_f32(r)) > 1e-6)
            fail_msg("mul associativity case %d: error %.3g", n, qdiff(l, ref_quat_from_f32(r)));
        /* Identity is neutral (exactly), q * conj(q) = |q|^2 (vector part ~0). */
        p = qo_quat_mul_f32(qo_quat_identity_f32(), a);
        if (memcmp(&p, &a, sizeof p) != 0 && !(p.w == a.w && p.x == a.x && p.y == a.y && p.z == a.z))
            fail_msg("identity * q != q in case %d%s", n, "");
        p = qo_quat_mul_f32(a, qo_quat_conj_f32(a));
        if (fabs(p.w - 1.0) > 1e-6 || fabs(p.x) > 1e-7 || fabs(p.y) > 1e-7 || fabs(p.z) > 1e-7) {
            print_q("q*conj(q)", p);
            fail_msg("q * conj(q) case %d is not (1,0,0,0)%s", n, "");
        }
    }
    /* Hamilton's rules: i j = k, j k = i, k i = j, i i = -1. */
    {
        qo_quat_f32 i = qf(0, 1, 0, 0), j = qf(0, 0, 1, 0), k = qf(0, 0, 0, 1), p;
        p = qo_quat_mul_f32(i, j);
        assert_true(p.w == 0.0f && p.x == 0.0f && p.y == 0.0f && p.z == 1.0f);
        p = qo_quat_mul_f32(j, k);
        assert_true(p.w == 0.0f && p.x == 1.0f && p.y == 0.0f && p.z == 0.0f);
        p = qo_quat_mul_f32(k, i);
        assert_true(p.w == 0.0f && p.x == 0.0f && p.y == 1.0f && p.z == 0.0f);
        p = qo_quat_mul_f32(i, i);
        assert_true(p.w == -1.0f && p.x == 0.0f && p.y == 0.0f && p.z == 0.0f);
    }
}

static void test_rotate_vs_double(void **state)
{
    ref_rng rng = { 3 };
    int n;
    (void)state;
    for (n = 0; n < N_RANDOM; n++) {
        qo_quat_f32 a = ref_quat_to_f32(ref_rng_quat(&rng)), b = ref_quat_to_f32(ref_rng_quat(&rng));
        ref_vec3 rv = { ref_rng_range(&rng, -5, 5), ref_rng_range(&rng, -5, 5),
                        ref_rng_range(&rng, -5, 5) };
        qo_vec3_f32 v = ref_vec3_to_f32(rv), r, r2, r3;
        /* The reference normalises the (float) q: rotate is specified for unit q only. */
        ref_vec3 e = ref_quat_rotate(ref_quat_from_f32(a), ref_vec3_from_f32(v));
        double len = sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z);
        r = qo_quat_rotate_f32(a, v);
        if (fabs(r.x - e.x) > 1e-6 * len || fabs(r.y - e.y) > 1e-6 * len ||
            fabs(r.z - e.z) > 1e-6 * len) {
            print_q("q", a);
            fail_msg("rotate case %d: v (%g %g %g) -> (%.9g %.9g %.9g), expected (%.9g %.9g %.9g)",
                     n, v.x, v.y, v.z, r.x, r.y, r.z, e.x, e.y, e.z);
        }
        /* (a*b) v = a (b v), and q, -q rotate alike. */
        r2 = qo_quat_rotate_f32(qo_quat_mul_f32(a, b), v);
        r3 = qo_quat_rotate_f32(a, qo_quat_rotate_f32(b, v));
        if (fabsf(r2.x - r3.x) > 2e-6f * (float)len || fabsf(r2.y - r3.y) > 2e-6f * (float)len ||
            fabsf(r2.z - r3.z) > 2e-6f * (float)len)
            fail_msg("rotate composition case %d: (%g %g %g) vs (%g %g %g)", n, r2.x, r2.y, r2.z,
                     r3.x, r3.y, r3.z);
        r2 = qo_quat_rotate_f32(qf(-a.w, -a.x, -a.y, -a.z), v);
        if (r2.x != r.x || r2.y != r.y || r2.z != r.z)
            fail_msg("rotate case %d: q and -q differ%s", n, "");
    }
}

/* ---- norm, normalise, inverse: overflow / underflow / zero / NaN ---- */

static void test_norm_range(void **state)
{
    ref_rng rng = { 4 };
    int n;
    (void)state;
    /* Random directions at scales from subnormal to near FLT_MAX / 2 (sum of squares would
     * overflow or underflow in naive float). */
    for (n = 0; n < N_RANDOM; n++) {
        double e = ref_rng_range(&rng, -44.0, 37.9);
        ref_quat rq = rscale(ref_rng_quat(&rng), pow(10.0, e));
        qo_quat_f32 q = ref_quat_to_f32(rq);
        double expect = ref_quat_norm(ref_quat_from_f32(q));
        float got = qo_quat_norm_f32(q);
        /* Relative 1e-6 where the input is a normal float; subnormal inputs carry their own
         * rounding (a few ulp of 1.4e-45) so allow that absolute error too. */
        if (fabs(got - expect) > 1e-6 * expect + 4e-45) {
            print_q("q", q);
            fail_msg("norm case %d (scale 1e%.1f): %.9g vs %.9g", n, e, got, expect);
        }
    }
    assert_true(qo_quat_norm_f32(qf(0, 0, 0, 0)) == 0.0f);
    assert_true(qo_quat_norm_f32(qf(-0.0f, 0, 0, -0.0f)) == 0.0f);
    assert_true(qo_quat_norm_f32(qf(FLT_MAX, 0, 0, 0)) == FLT_MAX);
    assert_true(fabs(qo_quat_norm_f32(qf(FLT_MAX / 2, FLT_MAX / 2, 0, 0)) -
                     (double)FLT_MAX / sqrt(2.0)) < 1e-6 * FLT_MAX);
    /* True norm 2 FLT_MAX: not representable -> Inf (not NaN, not a wrap). */
    assert_true(isinf(qo_quat_norm_f32(qf(FLT_MAX, FLT_MAX, FLT_MAX, -FLT_MAX))));
    /* Smallest subnormal: 1.4e-45 * 2 for four equal components. */
    assert_true(qo_quat_norm_f32(qf(0x1p-149f, -0x1p-149f, 0x1p-149f, 0x1p-149f)) == 0x1p-148f);
    assert_true(qo_quat_norm_f32(qf(3e-39f, 4e-39f, 0, 0)) > 4.99e-39f &&
                qo_quat_norm_f32(qf(3e-39f, 4e-39f, 0, 0)) < 5.01e-39f);
    assert_true(isnan(qo_quat_norm_f32(qf(1, NAN, 0, 0))));
    assert_true(isnan(qo_quat_norm_f32(qf(INFINITY, NAN, 0, 0))));
    assert_true(isinf(qo_quat_norm_f32(qf(0, 0, -INFINITY, 1))));
}

static void test_normalize(void **state)
{
    ref_rng rng = { 5 };
    int n;
    qo_quat_f32 u;
    (void)state;
    for (n = 0; n < N_RANDOM; n++) {
        double e = ref_rng_range(&rng, -44.0, 38.4);
        qo_quat_f32 q = ref_quat_to_f32(rscale(ref_rng_quat(&rng), pow(10.0, e)));
        ref_quat expect = ref_quat_normalize(ref_quat_from_f32(q));
        /* Subnormal inputs have few significant bits: the reference is of the float input, so
         * only the float32 output rounding (plus scaling steps) counts. */
        if (qo_quat_normalize_f32(q, &u) != QO_OK || qdiff(u, expect) > 4e-7) {
            print_q("q", q);
            print_q("out", u);
            fail_msg("normalize case %d (scale 1e%.1f): error %.3g", n, e, qdiff(u, expect));
        }
    }
    /* Components at FLT_MAX: |q| overflows float but q/|q| does not. */
    assert_int_equal(qo_quat_normalize_f32(qf(FLT_MAX, -FLT_MAX, 0, 0), &u), QO_OK);
    assert_true(fabsf(u.w - 0.70710678f) < 1e-7f && fabsf(u.x + 0.70710678f) < 1e-7f &&
                u.y == 0.0f && u.z == 0.0f);
    assert_int_equal(qo_quat_normalize_f32(qf(FLT_MAX, FLT_MAX, FLT_MAX, FLT_MAX), &u), QO_OK);
    assert_true(u.w == 0.5f && u.x == 0.5f && u.y == 0.5f && u.z == 0.5f);
    /* Smallest subnormal: sign kept. */
    assert_int_equal(qo_quat_normalize_f32(qf(0, 0, -0x1p-149f, 0), &u), QO_OK);
    assert_true(u.w == 0.0f && u.x == 0.0f && u.y == -1.0f && u.z == 0.0f);
    assert_int_equal(qo_quat_normalize_f32(qf(-2, 0, 0, 0), &u), QO_OK);
    assert_true(u.w == -1.0f);
    /* Errors: identity out. */
    u = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_normalize_f32(qf(0, 0, 0, 0), &u), QO_E_DEGENERATE);
    assert_true(is_identity_q(u));
    u = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_normalize_f32(qf(-0.0f, 0, -0.0f, 0), &u), QO_E_DEGENERATE);
    assert_true(is_identity_q(u));
    u = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_normalize_f32(qf(1, NAN, 0, 0), &u), QO_E_NONFINITE);
    assert_true(is_identity_q(u));
    u = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_normalize_f32(qf(0, 0, 0, INFINITY), &u), QO_E_NONFINITE);
    assert_true(is_identity_q(u));
    assert_int_equal(qo_quat_normalize_f32(qf(1, 0, 0, 0), NULL), QO_E_NULL);
}

static void test_inverse(void **state)
{
    ref_rng rng = { 6 };
    int n;
    qo_quat_f32 u;
    (void)state;
    for (n = 0; n < N_RANDOM; n++) {
        /* |q| in [1e-18, 1e18]: 1/|q| is a normal float. */
        double e = ref_rng_range(&rng, -18.0, 18.0);
        qo_quat_f32 q = ref_quat_to_f32(rscale(ref_rng_quat(&rng), pow(10.0, e)));
        ref_quat rq = ref_quat_from_f32(q);
        double n2 = rq.w * rq.w + rq.x * rq.x + rq.y * rq.y + rq.z * rq.z;
        ref_quat expect = { rq.w / n2, -rq.x / n2, -rq.y / n2, -rq.z / n2 };
        double scale = 1.0 / sqrt(n2);
        if (qo_quat_inverse_f32(q, &u) != QO_OK || qdiff(u, expect) > 4e-7 * scale) {
            print_q("q", q);
            print_q("out", u);
            fail_msg("inverse case %d (scale 1e%.1f): error %.3g", n, e, qdiff(u, expect) / scale);
        }
        /* q * q^-1 = identity. */
        {
            qo_quat_f32 p = qo_quat_mul_f32(q, u);
            if (fabs(p.w - 1.0) > 1e-6 || fabs(p.x) > 1e-6 || fabs(p.y) > 1e-6 || fabs(p.z) > 1e-6)
                fail_msg("q * inverse(q) case %d: (%g %g %g %g)", n, p.w, p.x, p.y, p.z);
        }
    }
    /* |q|^2 = 1e60 overflows float, but 1/|q| = 1e-30 is representable: computed. */
    assert_int_equal(qo_quat_inverse_f32(qf(0, 1e30f, 0, 0), &u), QO_OK);
    assert_true(u.w == 0.0f && fabsf(u.x + 1e-30f) < 1e-36f && u.y == 0.0f && u.z == 0.0f);
    /* |q| overflows float (components at FLT_MAX): no finite |q|, status. */
    u = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_inverse_f32(qf(FLT_MAX, FLT_MAX, 0, 0), &u), QO_E_DEGENERATE);
    assert_true(is_identity_q(u));
    /* Subnormal q: 1/|q| overflows. */
    u = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_inverse_f32(qf(1e-42f, 0, 0, 0), &u), QO_E_DEGENERATE);
    assert_true(is_identity_q(u));
    u = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_inverse_f32(qf(0, 0, 0, 0), &u), QO_E_DEGENERATE);
    assert_true(is_identity_q(u));
    u = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_inverse_f32(qf(NAN, 0, 0, 0), &u), QO_E_NONFINITE);
    assert_true(is_identity_q(u));
    u = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_inverse_f32(qf(1, 0, -INFINITY, 0), &u), QO_E_NONFINITE);
    assert_true(is_identity_q(u));
    assert_int_equal(qo_quat_inverse_f32(qf(1, 0, 0, 0), NULL), QO_E_NULL);
    /* Unit quaternion: the conjugate. */
    assert_int_equal(qo_quat_inverse_f32(qf(0, 0.6f, 0, 0.8f), &u), QO_OK);
    assert_true(u.w == 0.0f && fabsf(u.x + 0.6f) < 1e-7f && fabsf(u.z + 0.8f) < 1e-7f);
}

static void test_canonical(void **state)
{
    static const struct { const char *name; float in[4], out[4]; } t[] = {
        { "w > 0 kept", { 0.5f, -0.5f, 0.5f, -0.5f }, { 0.5f, -0.5f, 0.5f, -0.5f } },
        { "w < 0 flipped", { -0.5f, -0.5f, 0.5f, -0.5f }, { 0.5f, 0.5f, -0.5f, 0.5f } },
        { "tie w = 0, x < 0", { 0.0f, -0.6f, 0.8f, 0.0f }, { 0.0f, 0.6f, -0.8f, 0.0f } },
        { "tie w = -0, x = -0, y < 0", { -0.0f, -0.0f, -1.0f, 0.0f }, { 0.0f, 0.0f, 1.0f, 0.0f } },
        { "tie w = x = y = 0, z < 0", { 0.0f, 0.0f, 0.0f, -1.0f }, { 0.0f, 0.0f, 0.0f, 1.0f } },
        { "tie w = 0, x > 0 kept", { 0.0f, 0.6f, -0.8f, 0.0f }, { 0.0f, 0.6f, -0.8f, 0.0f } },
        { "tiny negative w", { -1e-30f, 1.0f, 0.0f, 0.0f }, { 1e-30f, -1.0f, 0.0f, 0.0f } },
        { "zero stays zero", { -0.0f, -0.0f, -0.0f, -0.0f }, { 0.0f, 0.0f, 0.0f, 0.0f } },
    };
    size_t k;
    ref_rng rng = { 7 };
    int n;
    (void)state;
    for (k = 0; k < sizeof t / sizeof t[0]; k++) {
        qo_quat_f32 c = qo_quat_canonical_f32(qf(t[k].in[0], t[k].in[1], t[k].in[2], t[k].in[3]));
        /* Bitwise: -0.0 must come out as +0.0 so canonical quaternions compare equal. */
        qo_quat_f32 e = qf(t[k].out[0], t[k].out[1], t[k].out[2], t[k].out[3]);
        if (memcmp(&c, &e, sizeof c) != 0) {
            print_q("got", c);
            fail_msg("canonical %s: expected (%g %g %g %g)", t[k].name, e.w, e.x, e.y, e.z);
        }
    }
    for (n = 0; n < N_RANDOM; n++) {
        qo_quat_f32 q = ref_quat_to_f32(ref_rng_quat(&rng)), c = qo_quat_canonical_f32(q);
        qo_quat_f32 cn = qo_quat_canonical_f32(qf(-q.w, -q.x, -q.y, -q.z));
        int same = c.w == q.w && c.x == q.x && c.y == q.y && c.z == q.z;
        int neg = c.w == -q.w && c.x == -q.x && c.y == -q.y && c.z == -q.z;
        if (!(c.w >= 0.0f) || !(same || neg) || memcmp(&c, &cn, sizeof c) != 0)
            fail_msg("canonical case %d: w %g, q and -q must map to one representative", n, c.w);
    }
}

/* ---- angle between ---- */

static void test_angle_between(void **state)
{
    ref_rng rng = { 8 };
    static const double tiny[] = { 1e-2, 1e-3, 1e-4, 1e-5, 1e-6 };
    int n;
    size_t k;
    (void)state;
    for (n = 0; n < N_RANDOM; n++) {
        qo_quat_f32 a = ref_quat_to_f32(ref_rng_quat(&rng)), b = ref_quat_to_f32(ref_rng_quat(&rng));
        double e = ref_quat_angle_between(ref_quat_from_f32(a), ref_quat_from_f32(b));
        float got = qo_quat_angle_between_f32(a, b);
        float gotn = qo_quat_angle_between_f32(a, qf(-b.w, -b.x, -b.y, -b.z));
        if (fabs(got - e) > 1e-6 || got != gotn || !(got >= 0.0f && got <= 3.14159274f))
            fail_msg("angle_between case %d: %.9g (with -b %.9g) vs %.9g", n, got, gotn, e);
    }
    /* Tiny angles: absolute error at the float32 round-off level, no acos plateau (acos would
     * give 0 or 4.9e-4 below ~3e-4 rad). */
    for (k = 0; k < sizeof tiny / sizeof tiny[0]; k++) {
        for (n = 0; n < 200; n++) {
            ref_quat ra = ref_rng_quat(&rng);
            ref_vec3 ax = { ref_rng_range(&rng, -1, 1), ref_rng_range(&rng, -1, 1),
                            ref_rng_range(&rng, -1, 1) };
            ref_quat rb = ref_quat_mul(ra, ref_quat_from_axis_angle(ax, tiny[k]));
            qo_quat_f32 a = ref_quat_to_f32(ra), b = ref_quat_to_f32(rb);
            double e = ref_quat_angle_between(ref_quat_from_f32(a), ref_quat_from_f32(b));
            float got = qo_quat_angle_between_f32(a, b);
            if (fabs(got - e) > 3e-7)
                fail_msg("angle_between tiny %g case %d: %.9g vs %.9g", tiny[k], n, got, e);
        }
    }
    /* Identical, antipodal representative, half turn, axis-aligned exact. */
    {
        qo_quat_f32 a = qf(0.5f, 0.5f, -0.5f, 0.5f);
        assert_true(qo_quat_angle_between_f32(a, a) == 0.0f);
        assert_true(qo_quat_angle_between_f32(a, qf(-0.5f, -0.5f, 0.5f, -0.5f)) == 0.0f);
        assert_true(fabs(qo_quat_angle_between_f32(qf(1, 0, 0, 0), qf(0, 0, 1, 0)) - REF_PI) < 1e-6);
        assert_true(fabs(qo_quat_angle_between_f32(qf(1, 0, 0, 0), qf(0.70710678f, 0, 0, 0.70710678f)) -
                         REF_PI / 2) < 1e-6);
    }
}

/* ---- exp / log ---- */

static double vdiff(qo_vec3_f32 v, ref_vec3 e)
{
    return fmax(fabs(v.x - e.x), fmax(fabs(v.y - e.y), fabs(v.z - e.z)));
}

static void test_exp_vs_double(void **state)
{
    ref_rng rng = { 9 };
    int n;
    qo_quat_f32 o;
    (void)state;
    for (n = 0; n < N_RANDOM; n++) {
        /* |v| from 1e-9 to 10 (Taylor region and the closed form). */
        ref_vec3 d = { ref_rng_range(&rng, -1, 1), ref_rng_range(&rng, -1, 1),
                       ref_rng_range(&rng, -1, 1) };
        double dl = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
        double r = pow(10.0, ref_rng_range(&rng, -9.0, 1.0)) / dl;
        qo_vec3_f32 v = vf((float)(d.x * r), (float)(d.y * r), (float)(d.z * r));
        ref_vec3 rv = ref_vec3_from_f32(v);
        double vn = sqrt(rv.x * rv.x + rv.y * rv.y + rv.z * rv.z);
        ref_quat e = { cos(vn), sin(vn) / vn * rv.x, sin(vn) / vn * rv.y, sin(vn) / vn * rv.z };
        if (qo_quat_exp_f32(v, &o) != QO_OK || qdiff(o, e) > 1e-6) {
            print_q("exp", o);
            print_q("expected", ref_quat_to_f32(e));
            fail_msg("exp case %d: v (%.9g %.9g %.9g) error %.3g", n, v.x, v.y, v.z, qdiff(o, e));
        }
    }
    assert_int_equal(qo_quat_exp_f32(vf(0, 0, 0), &o), QO_OK);
    assert_true(is_identity_q(o));
    /* Tiny vector: exactly (1, v) - the Taylor branch loses nothing. */
    assert_int_equal(qo_quat_exp_f32(vf(1e-20f, -3e-30f, 0), &o), QO_OK);
    assert_true(o.w == 1.0f && o.x == 1e-20f && o.y == -3e-30f && o.z == 0.0f);
    o = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_exp_f32(vf(3e38f, 3e38f, 0), &o), QO_E_NONFINITE); /* |v| overflows */
    assert_true(is_identity_q(o));
    o = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_exp_f32(vf(NAN, 0, 0), &o), QO_E_NONFINITE);
    assert_true(is_identity_q(o));
    o = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_exp_f32(vf(0, 0, -INFINITY), &o), QO_E_NONFINITE);
    assert_true(is_identity_q(o));
    assert_int_equal(qo_quat_exp_f32(vf(0, 0, 0), NULL), QO_E_NULL);
}

static void test_log_vs_double(void **state)
{
    ref_rng rng = { 10 };
    int n;
    qo_vec3_f32 o;
    (void)state;
    for (n = 0; n < N_RANDOM; n++) {
        qo_quat_f32 q = ref_quat_to_f32(rand_q_scaled(&rng));
        ref_quat rq = ref_quat_from_f32(q);
        double vn = sqrt(rq.x * rq.x + rq.y * rq.y + rq.z * rq.z);
        double k = atan2(vn, rq.w) / vn;
        ref_vec3 e = { k * rq.x, k * rq.y, k * rq.z };
        if (qo_quat_log_f32(q, &o) != QO_OK || vdiff(o, e) > 1e-6) {
            print_q("q", q);
            fail_msg("log case %d: got (%.9g %.9g %.9g), error %.3g", n, o.x, o.y, o.z, vdiff(o, e));
        }
    }
    assert_int_equal(qo_quat_log_f32(qf(1, 0, 0, 0), &o), QO_OK);
    assert_true(is_zero_v(o));
    /* -1: angle pi about the documented axis x. */
    assert_int_equal(qo_quat_log_f32(qf(-1, 0, 0, 0), &o), QO_OK);
    assert_true(fabs(o.x - REF_PI) < 1e-6 && o.y == 0.0f && o.z == 0.0f);
    /* Tiny vector part: full relative precision (1e-25^2 underflows in a naive |v|). */
    assert_int_equal(qo_quat_log_f32(qf(1, 0, 1e-25f, 0), &o), QO_OK);
    assert_true(o.x == 0.0f && fabsf(o.y - 1e-25f) < 1e-31f && o.z == 0.0f);
    /* Near -1 with a tiny vector along y: the axis is y, not the fallback x. */
    assert_int_equal(qo_quat_log_f32(qf(-1, 0, 1e-25f, 0), &o), QO_OK);
    if (!(o.x == 0.0f && fabs(o.y - REF_PI) < 1e-6 && o.z == 0.0f))
        fail_msg("log(-1, 0, 1e-25, 0) = (%g %g %g) lost the axis", o.x, o.y, o.z);
    /* Huge components: |q| and |v| overflow a naive float computation. */
    assert_int_equal(qo_quat_log_f32(qf(0, 1e20f, 0, 0), &o), QO_OK);
    if (!(fabs(o.x - REF_PI / 2) < 1e-6 && o.y == 0.0f))
        fail_msg("log(0, 1e20, 0, 0) = (%g %g %g)", o.x, o.y, o.z);
    assert_int_equal(qo_quat_log_f32(qf(FLT_MAX, FLT_MAX, 0, 0), &o), QO_OK);
    if (!(fabs(o.x - REF_PI / 4) < 1e-6))
        fail_msg("log(FLT_MAX, FLT_MAX, 0, 0) = (%g %g %g)", o.x, o.y, o.z);
    o = vf(9, 9, 9);
    assert_int_equal(qo_quat_log_f32(qf(0, 0, 0, 0), &o), QO_E_DEGENERATE);
    assert_true(is_zero_v(o));
    o = vf(9, 9, 9);
    assert_int_equal(qo_quat_log_f32(qf(1, 0, NAN, 0), &o), QO_E_NONFINITE);
    assert_true(is_zero_v(o));
    o = vf(9, 9, 9);
    assert_int_equal(qo_quat_log_f32(qf(INFINITY, 0, 0, 0), &o), QO_E_NONFINITE);
    assert_true(is_zero_v(o));
    assert_int_equal(qo_quat_log_f32(qf(1, 0, 0, 0), NULL), QO_E_NULL);
}

static void test_exp_log_round_trip(void **state)
{
    ref_rng rng = { 11 };
    int n;
    (void)state;
    for (n = 0; n < N_RANDOM; n++) {
        /* exp(log q) = q/|q| for any non-zero q. */
        qo_quat_f32 q = ref_quat_to_f32(rand_q_scaled(&rng)), back;
        qo_vec3_f32 l, p;
        ref_quat uq = ref_quat_normalize(ref_quat_from_f32(q));
        EXPECT_OK(qo_quat_log_f32(q, &l), n);
        EXPECT_OK(qo_quat_exp_f32(l, &back), n);
        if (qdiff(back, uq) > 2e-6) {
            print_q("q", q);
            print_q("exp(log q)", back);
            fail_msg("exp(log q) case %d: error %.3g", n, qdiff(back, uq));
        }
        /* log(exp v) = v for |v| < pi (the principal branch). */
        {
            ref_vec3 d = { ref_rng_range(&rng, -1, 1), ref_rng_range(&rng, -1, 1),
                           ref_rng_range(&rng, -1, 1) };
            double s = ref_rng_range(&rng, 0, 3.1) / sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
            p = vf((float)(d.x * s), (float)(d.y * s), (float)(d.z * s));
        }
        EXPECT_OK(qo_quat_exp_f32(p, &back), n);
        EXPECT_OK(qo_quat_log_f32(back, &l), n);
        /* d(log)/dq grows like 1/sin|v| towards pi: allow for it. */
        {
            double pn = sqrt((double)p.x * p.x + (double)p.y * p.y + (double)p.z * p.z);
            if (vdiff(l, ref_vec3_from_f32(p)) > 2e-6 / sin(fmax(0.04, pn)))
                fail_msg("log(exp p) case %d: p (%.9g %.9g %.9g) error %.3g", n, p.x, p.y, p.z,
                         vdiff(l, ref_vec3_from_f32(p)));
        }
    }
}

/* ---- integrate ---- */

static void test_integrate(void **state)
{
    ref_rng rng = { 12 };
    int n, s;
    qo_quat_f32 o;
    (void)state;
    for (n = 0; n < 40; n++) {
        ref_quat q0 = ref_rng_quat(&rng);
        ref_vec3 w = { ref_rng_range(&rng, -3, 3), ref_rng_range(&rng, -3, 3),
                       ref_rng_range(&rng, -3, 3) };
        double wn = sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
        const int steps = 1000;
        const float dt = 1e-3f;
        double tt = (double)steps * dt;
        /* Closed form for constant body rate: q(T) = q0 * exp(omega T / 2). */
        ref_quat expect = ref_quat_mul(q0, ref_quat_from_axis_angle(w, wn * tt));
        qo_quat_f32 q = ref_quat_to_f32(q0), one;
        qo_vec3_f32 om = ref_vec3_to_f32(w);
        double err_many, err_one;
        for (s = 0; s < steps; s++) EXPECT_OK(qo_quat_integrate_f32(q, om, dt, &q), n);
        EXPECT_OK(qo_quat_integrate_f32(ref_quat_to_f32(q0), om, (float)tt, &one), n);
        err_many = ref_quat_angle_between(ref_quat_from_f32(q), expect);
        err_one = ref_quat_angle_between(ref_quat_from_f32(one), expect);
        /* One exact step: round-off only. 1000 steps: round-off accumulates (~1e-7 per step
         * as a random walk, bounded linearly), with no first-order drift. */
        if (err_one > 1e-6 || err_many > 1e-4 || fabs(qo_quat_norm_f32(q) - 1.0) > 1e-6) {
            print_q("q0", ref_quat_to_f32(q0));
            fail_msg("integrate case %d: omega (%g %g %g): 1 step %.3g rad, %d steps %.3g rad", n,
                     w.x, w.y, w.z, err_one, steps, err_many);
        }
        /* Backwards over the same time returns to q0. */
        EXPECT_OK(qo_quat_integrate_f32(one, om, -(float)tt, &o), n);
        if (ref_quat_angle_between(ref_quat_from_f32(o), q0) > 1e-6)
            fail_msg("integrate case %d: backwards does not return to q0 (%.3g rad)", n,
                     ref_quat_angle_between(ref_quat_from_f32(o), q0));
    }
    /* Body frame: a rate about body z applied to a 90-degree yaw about x stays about body z:
     * q = (c, s, 0, 0), rate (0, 0, 1) for pi/2 -> q * (c, 0, 0, s). */
    {
        const float c = 0.70710678f;
        ref_quat e = ref_quat_mul(ref_quat_from_f32(qf(c, c, 0, 0)), ref_quat_from_f32(qf(c, 0, 0, c)));
        assert_int_equal(qo_quat_integrate_f32(qf(c, c, 0, 0), vf(0, 0, 1), 1.5707963f, &o), QO_OK);
        if (ref_quat_angle_between(ref_quat_from_f32(o), e) > 1e-6) {
            print_q("got", o);
            fail_msg("integrate is not body-frame%s", "");
        }
    }
    /* Zero rate or dt: the (normalised) input. Non-unit input is normalised. */
    assert_int_equal(qo_quat_integrate_f32(qf(2, 0, 0, 0), vf(1, 2, 3), 0.0f, &o), QO_OK);
    assert_true(is_identity_q(o));
    /* Errors. */
    o = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_integrate_f32(qf(0, 0, 0, 2), vf(NAN, 0, 0), 0.1f, &o), QO_E_NONFINITE);
    assert_true(o.w == 0.0f && o.x == 0.0f && o.y == 0.0f && o.z == 1.0f);
    o = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_integrate_f32(qf(0, 0, 0, 2), vf(0, 0, 1), INFINITY, &o), QO_E_NONFINITE);
    assert_true(o.w == 0.0f && o.z == 1.0f);
    o = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_integrate_f32(qf(0, 0, 0, 0), vf(0, 0, 1), 0.1f, &o), QO_E_DEGENERATE);
    assert_true(is_identity_q(o));
    o = qf(9, 9, 9, 9);
    assert_int_equal(qo_quat_integrate_f32(qf(NAN, 0, 0, 0), vf(0, 0, 1), 0.1f, &o), QO_E_NONFINITE);
    assert_true(is_identity_q(o));
    assert_int_equal(qo_quat_integrate_f32(qf(1, 0, 0, 0), vf(0, 0, 1), 0.1f, NULL), QO_E_NULL);
}

static void test_is_finite(void **state)
{
    (void)state;
    assert_int_equal(qo_quat_is_finite_f32(qf(1, -FLT_MAX, 0x1p-149f, 0)), 1);
    assert_int_equal(qo_quat_is_finite_f32(qf(NAN, 0, 0, 0)), 0);
    assert_int_equal(qo_quat_is_finite_f32(qf(0, INFINITY, 0, 0)), 0);
    assert_int_equal(qo_quat_is_finite_f32(qf(0, 0, -INFINITY, 0)), 0);
    assert_int_equal(qo_quat_is_finite_f32(qf(0, 0, 0, NAN)), 0);
}

/* ---- the lecture's worked examples (numbers from the lecture notes, not from this code) ---- */

static void test_lecture_examples(void **state)
{
    qo_quat_f32 q;
    qo_vec3_f32 r;
    (void)state;
    /* Rotating (1,0,0) by 180 degrees about (1,0,1) gives (0,0,1).
     * q = exp((0, pi/2 * (1,0,1)/sqrt2)). */
    assert_int_equal(qo_quat_exp_f32(vf(1.5707963f * 0.70710678f, 0, 1.5707963f * 0.70710678f), &q),
                     QO_OK);
    r = qo_quat_rotate_f32(q, vf(1, 0, 0));
    if (!(fabsf(r.x) < 1e-6f && fabsf(r.y) < 1e-6f && fabsf(r.z - 1.0f) < 1e-6f))
        fail_msg("180 about (1,0,1) of (1,0,0): got (%g %g %g), expected (0 0 1)", r.x, r.y, r.z);
    /* 30 degrees about (0,3,4) is the quaternion (0.966, 0, 0.155, 0.207) (3 decimals). */
    {
        const float half = 0.5f * 30.0f * 3.14159265f / 180.0f;
        assert_int_equal(qo_quat_exp_f32(vf(0, half * 3.0f / 5.0f, half * 4.0f / 5.0f), &q), QO_OK);
        if (!(fabsf(q.w - 0.966f) < 5e-4f && fabsf(q.x) < 5e-4f && fabsf(q.y - 0.155f) < 5e-4f &&
              fabsf(q.z - 0.207f) < 5e-4f)) {
            print_q("q", q);
            fail_msg("30 degrees about (0,3,4): expected (0.966, 0, 0.155, 0.207)%s", "");
        }
        /* And it rotates by 30 degrees: angle from identity. */
        assert_true(fabs(qo_quat_angle_between_f32(qo_quat_identity_f32(), q) - REF_PI / 6) < 1e-6);
    }
}

/* ---- SIMD bodies against the scalar ones, bit for bit ---------------------------------------- */

/* Equal bits, or both NaN (IEEE 754 leaves a NaN result's sign and payload unspecified, and
 * compilers already pick either operand's NaN for a commutative a*b). */
static int same_f(float a, float b)
{
    uint32_t ua, ub;
    if (isnan(a) || isnan(b)) return isnan(a) && isnan(b);
    memcpy(&ua, &a, sizeof ua);
    memcpy(&ub, &b, sizeof ub);
    return ua == ub;
}

static float bits_f(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* One component: any bit pattern (NaN, Inf, subnormal, -0 included), an edge value, a value
 * of random sign and decade in [1e-45, 1e38], or a component of a random unit quaternion. */
static float rand_component(ref_rng *rng, int mode, float unit)
{
    static const uint32_t edge[] = {
        0x00000000u, 0x80000000u, 0x3f800000u, 0xbf800000u, 0x7f800000u, 0xff800000u,
        0x7fc00000u, 0xffc00000u, 0x7f800001u, 0x00000001u, 0x80000001u, 0x007fffffu,
        0x00800000u, 0x7f7fffffu, 0xff7fffffu, 0x3f000000u, 0x0da24260u, 0x7149f2cau
    };
    uint64_t r = ref_rng_next(rng);
    switch (mode) {
    case 0: return bits_f((uint32_t)r);
    case 1: return bits_f(edge[(r >> 8) % (sizeof edge / sizeof edge[0])]);
    case 2: {
        double m = ref_rng_range(rng, 1.0, 10.0) * pow(10.0, ref_rng_range(rng, -45.0, 38.0));
        return (float)((r & 1u) ? -m : m);
    }
    default: return unit;
    }
}

/* 1e6 cases where there are SIMD bodies; elsewhere both sides are the scalar code and a short
 * run (emulated Cortex-M is slow) only keeps the test itself honest. */
#define SIMD_CASES (QO_SIMD_SSE2 ? 1000000L : 10000L)

static void test_simd_same_bits_as_scalar(void **state)
{
    ref_rng rng = { 15 };
    long i, nan_in = 0;
    (void)state;
    /* the comparison itself catches one ulp */
    assert_false(same_f(1.0f, nextafterf(1.0f, 2.0f)));
    assert_false(same_f(0.0f, -0.0f));
    for (i = 0; i < SIMD_CASES; i++) {
        qo_quat_f32 ua = ref_quat_to_f32(ref_rng_quat(&rng)), ub = ref_quat_to_f32(ref_rng_quat(&rng));
        int ma = (int)(ref_rng_next(&rng) % 5u), mb = (int)(ref_rng_next(&rng) % 5u);
        qo_quat_f32 a = qf(rand_component(&rng, ma, ua.w), rand_component(&rng, ma, ua.x),
                           rand_component(&rng, ma, ua.y), rand_component(&rng, ma, ua.z));
        qo_quat_f32 b = qf(rand_component(&rng, mb, ub.w), rand_component(&rng, mb, ub.x),
                           rand_component(&rng, mb, ub.y), rand_component(&rng, mb, ub.z));
        qo_vec3_f32 v = vf(b.x, b.y, b.z), rv = qo_quat_rotate_f32(a, v), sv = scalar_quat_rotate_f32(a, v);
        qo_quat_f32 rq = qo_quat_mul_f32(a, b), sq = scalar_quat_mul_f32(a, b);
        qo_mat3_f32 rm, sm;
        qo_status rs, ss;
        int k;
        if (!qo_quat_is_finite_f32(a)) nan_in++;
        if (!(same_f(rq.w, sq.w) && same_f(rq.x, sq.x) && same_f(rq.y, sq.y) && same_f(rq.z, sq.z))) {
            print_q("a", a); print_q("b", b); print_q("simd", rq); print_q("scalar", sq);
            fail_msg("case %ld: qo_quat_mul_f32 differs from the scalar body", i);
        }
        if (!(same_f(rv.x, sv.x) && same_f(rv.y, sv.y) && same_f(rv.z, sv.z))) {
            print_q("q", a);
            fail_msg("case %ld: rotate of (%a %a %a): simd (%a %a %a), scalar (%a %a %a)", i, v.x,
                     v.y, v.z, rv.x, rv.y, rv.z, sv.x, sv.y, sv.z);
        }
        rs = qo_quat_normalize_f32(a, &rq);
        ss = scalar_quat_normalize_f32(a, &sq);
        if (rs != ss || !(same_f(rq.w, sq.w) && same_f(rq.x, sq.x) && same_f(rq.y, sq.y) &&
                          same_f(rq.z, sq.z))) {
            print_q("q", a); print_q("simd", rq); print_q("scalar", sq);
            fail_msg("case %ld: normalize differs (status %d, scalar %d)", i, (int)rs, (int)ss);
        }
        rs = qo_quat_to_mat3_f32(a, &rm);
        ss = scalar_quat_to_mat3_f32(a, &sm);
        for (k = 0; k < 9; k++) {
            if (rs != ss || !same_f(rm.m[k / 3][k % 3], sm.m[k / 3][k % 3])) {
                print_q("q", a);
                fail_msg("case %ld: to_mat3 m[%d][%d] simd %a, scalar %a (status %d, %d)", i, k / 3,
                         k % 3, rm.m[k / 3][k % 3], sm.m[k / 3][k % 3], (int)rs, (int)ss);
            }
        }
    }
    /* the edges were exercised: a fifth of the cases or so have a NaN/Inf component */
    assert_true(nan_in > SIMD_CASES / 10);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identity_conj_dot),
        cmocka_unit_test(test_mul_vs_double),
        cmocka_unit_test(test_rotate_vs_double),
        cmocka_unit_test(test_norm_range),
        cmocka_unit_test(test_normalize),
        cmocka_unit_test(test_inverse),
        cmocka_unit_test(test_canonical),
        cmocka_unit_test(test_angle_between),
        cmocka_unit_test(test_exp_vs_double),
        cmocka_unit_test(test_log_vs_double),
        cmocka_unit_test(test_exp_log_round_trip),
        cmocka_unit_test(test_integrate),
        cmocka_unit_test(test_is_finite),
        cmocka_unit_test(test_lecture_examples),
        cmocka_unit_test(test_simd_same_bits_as_scalar),
    };
    return cmocka_run_group_tests_name("quat", tests, NULL, NULL);
}
