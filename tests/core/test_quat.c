/*
 * tests/core/test_quat.c - every qo_quat_* of qorient/quat.h (float32) and qorient/quat_fx.h
 * (Q1.30), one test program for the concept (docs/TESTING.md, "One body for both cores").
 *
 * First section: one body per behaviour both cores have (exp/log, mul, conj, normalize,
 * canonical, angle_between, integrate, rotate), registered with BOTH against the adapter
 * table of tests/common/cores.h: inputs rounded as each core receives them, the reference
 * computed in double from those rounded values, each core with its own tolerance; the edges
 * (identity, identical, antipodal, zero, each core's out-of-range value) in the same body.
 * Then the core-only behaviour, each against double / long double references over fixed
 * seeds: float32 (norm over the whole exponent range and subnormals, inverse, is_finite, -0
 * ties, NaN/Inf statuses, the lecture's worked examples, the SIMD bodies bit for bit against
 * the scalar ones) and Q1.30 (results to the LSB, saturation, the fast normalisation tier,
 * NULL outputs).
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "common/cores.h"
#include "common/ref.h"
#include "common/scalar_inline.h"
#include "qorient/convert.h"
#include "qorient/fxconv.h"
#include "qorient/fxmath.h"
#include "qorient/quat.h"
#include "qorient/quat_fx.h"

#define N_RANDOM 1000
#define N_LONG 20000

/* ==== one body, both cores (common/cores.h) ==================================== */

/* log(q) = atan2(|u|, w) u / |u| for any non-zero q (not canonicalised), in double */
static ref_vec3 log_ref(dq q)
{
    double vn = sqrt(q.x * q.x + q.y * q.y + q.z * q.z), k = atan2(vn, q.w) / vn;
    return vn > 0 ? v_make(k * q.x, k * q.y, k * q.z) : v_make(q.w < 0 ? PI : 0, 0, 0);
}

/* exp and log against the closed forms of the ROUNDED inputs, and each other's inverse.
 * exp: |v| from 1e-7 up to pi in every core; then float32 |v| from 1e-9 to 10, Q1.30
 * components up to 3.9 rad with tiny ones mixed in; log: |q| from 0.3 to 1.9 (Q1.30) or 1e-3 to
 * 1e3 (float32), not canonicalised (angles up to 2 pi) */
static void test_exp_log(void **state)
{
    const core *c = *state;
    /* float32: 1e-6; Q1.30: 2 LSB (exp), 1.5 LSB of Q3.28 (log) */
    const double tol_exp = c->fixed ? 2 / Q30 : 1e-6, tol_log = c->fixed ? 1.5 / Q28 : 1e-6;
    const double q_lo = c->fixed ? log10(0.3) : -3, q_hi = c->fixed ? log10(1.9) : 3;
    int n;
    dq o;
    ref_vec3 v, l;
    rng_seed(103);
    for (n = 0; n < N_LONG; n++) {
        ref_vec3 d = v_rand(-1, 1), lw;
        dq p, want, q, back;
        double s, pn;
        if (n % 4 == 0) {
            s = pow(10.0, rng_range(-7, -2)) / v_norm(d);
            d = v_make(d.x * s, d.y * s, d.z * s);
        } else if (n % 4 == 1) {
            s = rng_range(0, PI) / v_norm(d);
            d = v_make(d.x * s, d.y * s, d.z * s);
        } else if (!c->fixed) {
            s = pow(10.0, rng_range(-9, 1)) / v_norm(d);
            d = v_make(d.x * s, d.y * s, d.z * s);
        } else {
            d = v_make(3.9 * d.x / (1 + (double)(n % 8 / 2) * 100), 3.9 * d.y, 3.9 * d.z);
            if (n % 8 >= 4) { d.y /= 1e4; d.z /= 1e5; }
        }
        v = v_in(c, d, 1);
        p.w = 0; p.x = v.x; p.y = v.y; p.z = v.z;
        want = dq_exp(p);
        if (c->exp(v, &o) != QO_OK || q_dist(o, want) > tol_exp)
            fail_msg("%s exp case %d: v (%.10g %.10g %.10g) got " QFMT " error %.3g", c->name,
                     n, v.x, v.y, v.z, QARG(o), q_dist(o, want));
        q = c->q_in(dq_scale(rand_unit(), pow(10.0, rng_range(q_lo, q_hi))));
        lw = log_ref(q);
        if (c->log(q, &l) != QO_OK || v_dist(l, lw) > tol_log)
            fail_msg("%s log case %d: q " QFMT " got (%.10g %.10g %.10g) want (%.10g %.10g %.10g)",
                     c->name, n, QARG(q), l.x, l.y, l.z, lw.x, lw.y, lw.z);
        /* exp(log q) = q / |q| */
        if (c->exp(l, &back) != QO_OK || q_dist(back, dq_unit(q)) > (c->fixed ? 2 * c->tol_abs : 2e-6))
            fail_msg("%s exp(log q) case %d: q " QFMT " error %.3g", c->name, n, QARG(q),
                     q_dist(back, dq_unit(q)));
        /* log(exp p) = p for |p| < pi (the principal branch); d(log)/dq grows like 1/sin|p| */
        s = rng_range(0, 3.1) / v_norm(d = v_rand(-1, 1));
        v = v_in(c, v_make(d.x * s, d.y * s, d.z * s), 1);
        pn = v_norm(v);
        if (c->exp(v, &back) != QO_OK || c->log(back, &l) != QO_OK ||
            v_dist(l, v) > (c->fixed ? 4 / Q30 / sin(fmax(0.04, pn)) + 2 / Q28
                                     : 2e-6 / sin(fmax(0.04, pn))))
            fail_msg("%s log(exp p) case %d: p (%.10g %.10g %.10g) error %.3g", c->name, n, v.x,
                     v.y, v.z, v_dist(l, v));
    }
    assert_int_equal(c->exp(v_make(0, 0, 0), &o), QO_OK);
    assert_true(dq_is(o, ID));
    assert_int_equal(c->log(ID, &l), QO_OK);
    assert_true(v_norm(l) == 0);
    /* -1: 2 pi about the documented axis x */
    assert_int_equal(c->log(dq_neg(ID), &l), QO_OK);
    assert_true(fabs(l.x - PI) <= c->tol_ang && l.y == 0 && l.z == 0);
    /* antipodal inputs give the same rotation: logs pi/2 apart in length, opposite axes */
    o = c->q_in(dq_axis_angle(1, 2, 3, 1.0));
    assert_int_equal(c->log(o, &v), QO_OK);
    assert_int_equal(c->log(dq_neg(o), &l), QO_OK);
    assert_true(fabs(v_norm(v) + v_norm(l) - PI) <= 2 * c->tol_ang);
    l = v_make(9, 9, 9);
    assert_int_equal(c->log(ZERO_Q, &l), QO_E_DEGENERATE);
    assert_true(v_norm(l) == 0);
    /* out of range: Inf (float32) / saturated Q3.28 component (~8 rad, fixed: QO_E_RANGE) */
    assert_int_equal(c->exp(v_make(c->big, 0, 0), &o), ST(c, QO_E_NONFINITE, QO_E_RANGE));
    assert_true(dq_is(o, ID));
}


/* mul, conj, identity, dot and norm: one rounding per result against the double algebra of the
 * ROUNDED operands; non-unit operands over each core's range (float32: |q| from 1e-3 to 1e3;
 * Q1.30: up to 1.4, so that products stay below 2) */
static void test_mul_conj_dot(void **state)
{
    const core *c = *state;
    const double hi = c->fixed ? log10(1.4) : 3.0;
    /* Q1.30: half an LSB (1e-14 for the double reference's own rounding of 62-bit products) */
    const double half_lsb = 0.5 / Q30 + 1e-14;
    int n;
    dq o;
    rng_seed(104);
    for (n = 0; n < N_LONG; n++) {
        dq a = c->q_in(dq_scale(rand_unit(), pow(10.0, rng_range(-3.0, hi))));
        dq b = c->q_in(dq_scale(rand_unit(), pow(10.0, rng_range(-3.0, hi))));
        dq u = c->q_in(rand_unit()), v = c->q_in(rand_unit()), w = c->q_in(rand_unit());
        double mag = dq_norm(a) * dq_norm(b);
        dq want = dq_mul(a, b), l, r;
        o = c->mul(a, b);
        if (q_dist(o, want) > (c->fixed ? half_lsb : 5e-7 * mag))
            fail_msg("%s mul case %d: a " QFMT " b " QFMT " error %.3g (|a||b| = %.3g)", c->name,
                     n, QARG(a), QARG(b), q_dist(o, want), mag);
        /* norms multiply: the product's rounding plus the norm's */
        if (fabs(c->norm(o) - mag) > (c->fixed ? 2 / Q30 : 1e-6 * mag))
            fail_msg("%s mul case %d: |a*b| %.12g vs |a||b| %.12g", c->name, n, c->norm(o), mag);
        if (fabs(c->dot(a, b) - dq_dot(a, b)) > (c->fixed ? half_lsb : 1e-6 * mag))
            fail_msg("%s dot case %d: a " QFMT " b " QFMT " got %.12g want %.12g", c->name, n,
                     QARG(a), QARG(b), c->dot(a, b), dq_dot(a, b));
        if (fabs(c->norm(a) - dq_norm(a)) > (c->fixed ? half_lsb : 1e-6 * dq_norm(a)))
            fail_msg("%s norm case %d: q " QFMT " got %.12g want %.12g", c->name, n, QARG(a),
                     c->norm(a), dq_norm(a));
        if (!dq_is(c->conj(a), dq_conj(a)))
            fail_msg("%s conj case %d: a " QFMT, c->name, n, QARG(a));
        /* unit operands: the product, associativity, identity neutral (exactly), u conj(u) = 1 */
        o = c->mul(u, v);
        if (dist4(o, dq_mul(u, v)) > 2 * c->tol_abs)
            fail_msg("%s mul (unit) case %d: error %.3g", c->name, n, dist4(o, dq_mul(u, v)));
        l = c->mul(o, w);
        r = c->mul(u, c->mul(v, w));
        if (q_dist(l, r) > c->tol_abs)
            fail_msg("%s mul associativity case %d: error %.3g", c->name, n, q_dist(l, r));
        if (!dq_is(c->mul(c->identity(), u), u))
            fail_msg("%s identity * q != q in case %d: q " QFMT, c->name, n, QARG(u));
        o = c->mul(u, c->conj(u));
        if (fabs(o.w - 1) > c->tol_abs || fmax(fabs(o.x), fmax(fabs(o.y), fabs(o.z))) > c->tol_abs / 10)
            fail_msg("%s q * conj(q) case %d: " QFMT, c->name, n, QARG(o));
    }
    assert_true(dq_is(c->identity(), ID));
    /* Hamilton's rules, exactly: i j = k, j k = i, k i = j, i i = -1 */
    {
        const dq i = { 0, 1, 0, 0 }, j = { 0, 0, 1, 0 }, k = { 0, 0, 0, 1 };
        assert_true(dq_is(c->mul(i, j), k));
        assert_true(dq_is(c->mul(j, k), i));
        assert_true(dq_is(c->mul(k, i), j));
        assert_true(dq_is(c->mul(i, i), dq_neg(ID)));
    }
    /* identity is neutral; q (-q) is the identity rotation with w = -1 */
    o = c->q_in(rand_unit());
    assert_true(dist4(c->mul(ID, o), o) <= c->tol_abs);
    assert_true(rot_err(c->mul(o, dq_neg(dq_conj(o))), ID) <= 4 * c->tol_rot);
    /* a product beyond the format saturates in fixed point (float: exact, 4) */
    o.w = o.x = o.y = o.z = c->u_in(1.0);
    o = c->mul(o, dq_conj(o));
    assert_true(fabs(o.w - fmin(4.0, c->u_max)) <= c->tol_abs);
}

static void test_normalize(void **state)
{
    const core *c = *state;
    int n;
    dq o;
    rng_seed(113);
    for (n = 0; n < N_RANDOM; n++) {
        dq s = c->q_in(dq_scale(rand_unit(), pow(10.0, rng_range(-6, 0.2))));
        if (c->normalize(s, &o) != QO_OK || dist4(o, dq_unit(s)) > 2 * c->tol_abs)
            fail_msg("%s normalize case %d: q " QFMT " got " QFMT, c->name, n, QARG(s), QARG(o));
    }
    assert_int_equal(c->normalize(ZERO_Q, &o), QO_E_DEGENERATE);
    assert_true(dq_is(o, ID));
    /* out of range: Inf (float32) / every component saturated (fixed: normalises) */
    o.w = o.x = o.y = o.z = c->big;
    assert_int_equal(c->normalize(o, &o), ST(c, QO_E_NONFINITE, QO_OK));
    if (c->fixed) {
        dq half = { 0.5, 0.5, 0.5, 0.5 };
        assert_true(dist4(o, half) <= 2 * c->tol_abs);
    }
}

/* canonical: the representative with w >= 0 (ties: the first non-zero of x, y, z positive),
 * exactly as the double reference picks it, the same for q and -q */
static void test_canonical(void **state)
{
    const core *c = *state;
    int n;
    dq o;
    rng_seed(111);
    for (n = 0; n < N_RANDOM; n++) {
        dq a = c->q_in(rand_unit());
        o = c->canonical(a);
        if (!dq_is(o, ref_quat_canonical(a)) || !dq_is(c->canonical(dq_neg(a)), o) || !(o.w >= 0))
            fail_msg("%s canonical case %d: " QFMT " got " QFMT ", of -q " QFMT, c->name, n,
                     QARG(a), QARG(o), QARG(c->canonical(dq_neg(a))));
    }
    assert_true(dq_is(c->canonical(dq_neg(ID)), ID));
    /* w == 0: the first non-zero of x, y, z made positive */
    {
        dq h = { 0, 0, -0.5, 0.5 }, hc = { 0, 0, 0.5, -0.5 };
        assert_true(dq_is(c->canonical(h), hc));
    }
}

/* angle_between against the double reference of the ROUNDED inputs: random pairs, pairs 1e-5
 * apart and nearly antipodal, tiny angles (no acos plateau); the same for b and -b exactly */
static void test_angle_between(void **state)
{
    const core *c = *state;
    static const double tiny[] = { 1e-2, 1e-3, 1e-4, 1e-5, 1e-6 };
    /* float32: 1e-6 rad (3e-7 for tiny angles); Q1.30 (a Q3.28 result): 2 LSB */
    const double tol = c->fixed ? 2 / Q28 : 1e-6, tol_tiny = c->fixed ? 2 / Q28 : 3e-7;
    const double pi_max = c->fixed ? QO_Q28_PI / Q28 : (double)3.14159274f;
    int n;
    size_t k;
    dq a;
    rng_seed(114);
    for (n = 0; n < N_LONG; n++) {
        dq b;
        double want, got;
        a = c->q_in(rand_unit());
        if (n % 3 == 0) {
            b = c->q_in(dq_mul(a, rand_axis_rot(1e-5 * rng_u())));
            if (n % 2) b = dq_neg(b);
        } else {
            b = c->q_in(rand_unit());
        }
        want = ref_quat_angle_between(a, b);
        got = c->angle_between(a, b);
        if (fabs(got - want) > tol || !(got >= 0 && got <= pi_max) ||
            c->angle_between(a, dq_neg(b)) != got)
            fail_msg("%s angle_between case %d: a " QFMT " b " QFMT " got %.12g (with -b %.12g)"
                     " want %.12g", c->name, n, QARG(a), QARG(b), got,
                     c->angle_between(a, dq_neg(b)), want);
    }
    for (k = 0; k < sizeof tiny / sizeof tiny[0]; k++) {
        for (n = 0; n < 200; n++) {
            dq b;
            a = c->q_in(rand_unit());
            b = c->q_in(dq_mul(a, rand_axis_rot(tiny[k])));
            if (fabs(c->angle_between(a, b) - ref_quat_angle_between(a, b)) > tol_tiny)
                fail_msg("%s angle_between tiny %g case %d: %.12g vs %.12g", c->name, tiny[k], n,
                         c->angle_between(a, b), ref_quat_angle_between(a, b));
        }
    }
    /* identical and antipodal: 0 exactly; half turn; quarter turn */
    {
        const dq h = { 0.5, 0.5, -0.5, 0.5 }, y180 = { 0, 0, 1, 0 };
        assert_true(c->angle_between(h, h) == 0);
        assert_true(c->angle_between(h, dq_neg(h)) == 0);
        assert_true(fabs(c->angle_between(ID, y180) - PI) <= tol);
        assert_true(fabs(c->angle_between(ID, c->q_in(dq_axis_angle(0, 0, 1, PI / 2))) - PI / 2) <= tol);
    }
    /* random identical: 0 (exactly in fixed point, as quat_fx.h says; float32 to rounding);
     * random antipodal: the same rotation, 0 too */
    a = c->q_in(rand_unit());
    assert_true(c->angle_between(a, a) <= (c->fixed ? 0.0 : c->tol_ang));
    assert_true(c->angle_between(a, dq_neg(a)) <= (c->fixed ? 0.0 : c->tol_ang));
}

/* integrate by a body-frame increment: q/|q| exp(dtheta / 2), normalised; increments of 1e-4,
 * 0.5 and 3 rad per component (Q1.30: to 4 LSB; float32: 4 tol_abs) */
static void test_integrate(void **state)
{
    const core *c = *state;
    static const double scale[] = { 1e-4, 0.5, 3.0 };
    int n;
    dq o;
    rng_seed(115);
    for (n = 0; n < N_LONG; n++) {
        dq a = c->q_in(rand_unit()), want;
        ref_vec3 d = v_in(c, v_rand(-scale[n % 3], scale[n % 3]), 1);
        dq p = { 0, d.x / 2, d.y / 2, d.z / 2 };
        want = dq_unit(dq_mul(dq_unit(a), dq_exp(p)));
        if (c->integrate(a, d, &o) != QO_OK ||
            (c->fixed ? q_dist(o, want) > 4 / Q30 : dist4(o, want) > 4 * c->tol_abs))
            fail_msg("%s integrate case %d: q " QFMT " dtheta (%.10g %.10g %.10g) error %.3g",
                     c->name, n, QARG(a), d.x, d.y, d.z, dist4(o, want));
    }
    assert_int_equal(c->integrate(ID, v_make(0, 0, 0), &o), QO_OK);
    assert_true(dq_is(o, ID));
    /* a zero increment normalises q */
    assert_int_equal(c->integrate(dq_scale(ID, 0.25), v_make(0, 0, 0), &o), QO_OK);
    assert_true(dq_is(o, ID));
    assert_int_equal(c->integrate(ZERO_Q, v_make(0.1, 0, 0), &o), QO_E_DEGENERATE);
    assert_true(dq_is(o, ID));
    /* out of range: Inf (float32) / a saturated Q3.28 increment (fixed: ~8 rad, a valid turn) */
    assert_int_equal(c->integrate(ID, v_make(c->big, 0, 0), &o), ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(fabs(dq_norm(o) - 1) <= 4 * c->tol_abs);
}


/* rotate against the sandwich q (0, v) q* in double (Q1.30: of q as given, |q|^2 - 1 within
 * 2^-29 from the rounding; float32: of q normalised, rotate being specified for unit q):
 * float32 vectors up to 5 long, Q1.30 up to 1 */
static void test_rotate(void **state)
{
    const core *c = *state;
    int n;
    ref_vec3 o;
    rng_seed(105);
    for (n = 0; n < N_LONG; n++) {
        dq q = c->q_in(rand_unit()), b = c->q_in(rand_unit());
        ref_vec3 d = v_rand(-1, 1), v, want, r2, r3;
        double len;
        if (c->fixed && v_norm(d) > 1) d = v_make(d.x / v_norm(d), d.y / v_norm(d), d.z / v_norm(d));
        v = v_in(c, c->fixed ? d : v_make(5 * d.x, 5 * d.y, 5 * d.z), 0);
        len = v_norm(v);
        if (c->fixed) {
            dq p = { 0, v.x, v.y, v.z }, w = dq_mul(dq_mul(q, p), dq_conj(q));
            want = v_make(w.x, w.y, w.z);
        } else {
            want = ref_quat_rotate(q, v);
        }
        o = c->rotate(q, v);
        /* Q1.30: 2 LSB of rounding plus |q|^2 - 1 times |v|; float32: relative to |v| */
        if (v_dist(o, want) > (c->fixed ? 4 / Q30 : 1e-6 * len))
            fail_msg("%s rotate case %d: q " QFMT " v (%.10g %.10g %.10g) error %.3g", c->name,
                     n, QARG(q), v.x, v.y, v.z, v_dist(o, want));
        /* q and -q are the same rotation (float32: the same bits) */
        if (v_dist(c->rotate(dq_neg(q), v), o) > (c->fixed ? 2 * c->tol_abs : 0))
            fail_msg("%s rotate case %d: -q differs", c->name, n);
        /* (a*b) v = a (b v) */
        r2 = c->rotate(c->mul(q, b), v);
        r3 = c->rotate(q, c->rotate(b, v));
        if (v_dist(r2, r3) > (c->fixed ? 4 * c->tol_abs : 2e-6 * len))
            fail_msg("%s rotate composition case %d: (%.10g %.10g %.10g) vs (%.10g %.10g %.10g)",
                     c->name, n, r2.x, r2.y, r2.z, r3.x, r3.y, r3.z);
    }
    o = c->rotate(ID, v_make(0.5, -0.25, 0.125));
    assert_true(o.x == 0.5 && o.y == -0.25 && o.z == 0.125);
    /* 90 deg about z takes x to y (Q1.30: to 2 LSB, z exactly 0) */
    o = c->rotate(c->q_in(dq_axis_angle(0, 0, 1, PI / 2)), v_make(1, 0, 0));
    assert_true(fabs(o.x) <= (c->fixed ? 2 / Q30 : 4 * c->tol_abs));
    assert_true(fabs(o.y - 1) <= (c->fixed ? 2 / Q30 : 4 * c->tol_abs));
    assert_true(fabs(o.z) <= (c->fixed ? 0 : c->tol_abs));
}


/* ==== float32 only: qorient/quat.h ====================================== */

#define N_F32 2000

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

/* ---- norm, normalise, inverse: overflow / underflow / zero / NaN ---- */

static void test_f32_norm_range(void **state)
{
    ref_rng rng = { 4 };
    int n;
    (void)state;
    /* Random directions at scales from subnormal to near FLT_MAX / 2 (sum of squares would
     * overflow or underflow in naive float). */
    for (n = 0; n < N_F32; n++) {
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

static void test_f32_normalize(void **state)
{
    ref_rng rng = { 5 };
    int n;
    qo_quat_f32 u;
    (void)state;
    for (n = 0; n < N_F32; n++) {
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

static void test_f32_inverse(void **state)
{
    ref_rng rng = { 6 };
    int n;
    qo_quat_f32 u;
    (void)state;
    for (n = 0; n < N_F32; n++) {
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

static void test_f32_canonical_ties(void **state)
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
}

/* ---- exp / log ---- */

/* exp at the float32 ends: the Taylor branch exact, overflow, NaN, Inf, NULL (the rounding
 * is test_exp_log, both cores) */
static void test_f32_exp_edges(void **state)
{
    qo_quat_f32 o;
    (void)state;
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

/* log at the float32 ends: tiny and huge components, the axis near -1, NaN, Inf, NULL (the
 * rounding is test_exp_log, both cores) */
static void test_f32_log_edges(void **state)
{
    qo_vec3_f32 o;
    (void)state;
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

/* ---- integrate ---- */

static void test_f32_integrate(void **state)
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

static void test_f32_is_finite(void **state)
{
    (void)state;
    assert_int_equal(qo_quat_is_finite_f32(qf(1, -FLT_MAX, 0x1p-149f, 0)), 1);
    assert_int_equal(qo_quat_is_finite_f32(qf(NAN, 0, 0, 0)), 0);
    assert_int_equal(qo_quat_is_finite_f32(qf(0, INFINITY, 0, 0)), 0);
    assert_int_equal(qo_quat_is_finite_f32(qf(0, 0, -INFINITY, 0)), 0);
    assert_int_equal(qo_quat_is_finite_f32(qf(0, 0, 0, NAN)), 0);
}

/* ---- the lecture's worked examples (numbers from the lecture notes, not from this code) ---- */

static void test_f32_lecture_examples(void **state)
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
#define SIMD_CASES (QO_QUAT_SIMD_SSE2 ? 1000000L : 10000L)

static void test_f32_simd_same_bits_as_scalar(void **state)
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
        rs = qo_mat3_from_quat_f32(a, &rm);
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

/* ==== Q1.30 only: qorient/quat_fx.h ===================================== */

#define TWO30 1073741824.0
#define TWO28 268435456.0

/* The fixed-seed PRNG of this section (tests/common/ref.c). */
static ref_rng xrng;

#define XFMT "(%ld %ld %ld %ld)"
#define XARG(q) (long)(q).w, (long)(q).x, (long)(q).y, (long)(q).z

static void test_q30_identity_conj_inverse_canonical(void **state)
{
    qo_quat_q30 q = { -5, 6, -7, INT32_MIN }, c;
    static const struct { qo_quat_q30 in, want; } canon[] = {
        { { 1, -2, 3, -4 }, { 1, -2, 3, -4 } },
        { { -1, -2, 3, -4 }, { 1, 2, -3, 4 } },
        { { 0, -2, 3, -4 }, { 0, 2, -3, 4 } },
        { { 0, 0, -3, 4 }, { 0, 0, 3, -4 } },
        { { 0, 0, 0, -4 }, { 0, 0, 0, 4 } },
        { { 0, 0, 0, 0 }, { 0, 0, 0, 0 } },
        { { 0, 2, -3, 4 }, { 0, 2, -3, 4 } },
        { { INT32_MIN, 0, 0, 0 }, { INT32_MAX, 0, 0, 0 } },
    };
    size_t i;
    (void)state;
    c = qo_quat_identity_q30();
    assert_int_equal(c.w, QO_Q30_ONE); assert_int_equal(c.x, 0); assert_int_equal(c.y, 0); assert_int_equal(c.z, 0);
    c = qo_quat_conj_q30(q);
    assert_int_equal(c.w, -5); assert_int_equal(c.x, -6); assert_int_equal(c.y, 7);
    assert_int_equal(c.z, INT32_MAX); /* -(-2.0) saturates */
    c = qo_quat_inverse_q30(q);
    assert_int_equal(c.x, -6); assert_int_equal(c.z, INT32_MAX);
    for (i = 0; i < sizeof canon / sizeof canon[0]; i++) {
        c = qo_quat_canonical_q30(canon[i].in);
        if (c.w != canon[i].want.w || c.x != canon[i].want.x || c.y != canon[i].want.y || c.z != canon[i].want.z)
            fail_msg("canonical" XFMT " = " XFMT, XARG(canon[i].in), XARG(c));
    }
}

/* mul, dot and norm beyond the format: saturated, never wrapped; the checked mul says so
 * (the rounding of each to half an LSB is test_mul_conj_dot, both cores) */
static void test_q30_mul_saturation(void **state)
{
    qo_quat_q30 r;
    qo_quat_q30 big = { INT32_MIN, INT32_MIN, 0, 0 };
    (void)state;
    /* Saturation: non-unit inputs whose product leaves [-2, 2). */
    assert_int_equal(qo_quat_mul_checked_q30(big, big, &r), QO_E_OVERFLOW);
    assert_int_equal(r.x, INT32_MAX);   /* 2 * (-2)(-2) = 8 */
    assert_int_equal(r.w, 0);           /* 4 - 4 */
    r = qo_quat_mul_q30(big, big);
    assert_int_equal(r.x, INT32_MAX);
    assert_int_equal(qo_quat_mul_checked_q30(qo_quat_identity_q30(), big, &r), QO_OK);
    assert_int_equal(r.w, INT32_MIN);
    assert_int_equal(qo_quat_mul_checked_q30(big, big, NULL), QO_E_NULL);
    assert_int_equal(qo_quat_dot_q30(big, big), INT32_MAX);
    assert_int_equal(qo_quat_norm_q30(big), INT32_MAX);
    {
        qo_quat_q30 all = { INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN };
        assert_int_equal(qo_quat_norm_q30(all), INT32_MAX);
    }
}

/* The exact normalisation (1 LSB) and its fast tier (16 LSB, never beyond +-1.0) run through
 * the same checks. */
typedef struct norm_impl {
    const char *name;
    qo_status (*fn)(qo_quat_q30, qo_quat_q30 *);
    double bound_lsb;
} norm_impl;
static const norm_impl norm_impls[] = {
    { "normalize", qo_quat_normalize_q30, 1.0 },
    { "normalize_fast", qo_quat_normalize_fast_q30, 16.0 },
};

static void check_normalize(const norm_impl *f, qo_quat_q30 q)
{
    qo_quat_q30 r;
    dq want = ref_quat_normalize(ref_quat_from_q30(q));
    double e;
    assert_int_equal(f->fn(q, &r), QO_OK);
    e = ref_quat_err_lsb_q30(r, want);
    if (e > f->bound_lsb + 1e-6)
        fail_msg("%s " XFMT " = " XFMT ": %.3f LSB", f->name, XARG(q), XARG(r), e);
    if (r.w > QO_Q30_ONE || r.w < -QO_Q30_ONE || r.x > QO_Q30_ONE || r.x < -QO_Q30_ONE ||
        r.y > QO_Q30_ONE || r.y < -QO_Q30_ONE || r.z > QO_Q30_ONE || r.z < -QO_Q30_ONE)
        fail_msg("%s " XFMT " = " XFMT ": beyond 1", f->name, XARG(q), XARG(r));
}

static void test_q30_normalize(void **state)
{
    qo_quat_q30 r, z = { 0, 0, 0, 0 };
    qo_quat_q30 edges[] = {
        { 1, 0, 0, 0 }, { 0, 0, 0, -1 }, { 1, 1, 1, 1 }, { 1, -1, 2, 0 },
        { INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN }, { INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX },
        { INT32_MIN, 0, 0, 0 }, { INT32_MAX, INT32_MIN, 1, -1 }, { QO_Q30_ONE, 0, 0, 0 },
        { 3, 4, 0, 0 }, { 1 << 29, 1 << 29, 1 << 29, 1 << 29 }, { (1 << 29) - 1, 0, 0, 0 },
        { 0x3FFFFFFF, 0x3FFFFFFF, 0x3FFFFFFF, 0x3FFFFFFF }, { 0, 1 << 30, 0, 1 << 30 },
        /* |q|^2 just below 2^60 (normalize_fast's 2^30 boundary of its scaled square) */
        { 717548339, 401245721, 510734886, 464970573 }, { 1 << 29, 1, 1, 1 },
    };
    size_t i, f;
    int k;
    (void)state;
    for (f = 0; f < sizeof norm_impls / sizeof norm_impls[0]; f++) {
        const norm_impl *n = &norm_impls[f];
        r.w = 7;
        assert_int_equal(n->fn(z, &r), QO_E_DEGENERATE);
        assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
        assert_int_equal(n->fn(z, NULL), QO_E_NULL);
        for (i = 0; i < sizeof edges / sizeof edges[0]; i++) check_normalize(n, edges[i]);
        /* Sign kept (-1 exactly for the exact one). */
        assert_int_equal(n->fn(edges[6], &r), QO_OK);
        assert_true(r.w >= -QO_Q30_ONE && r.w <= -QO_Q30_ONE + (int32_t)n->bound_lsb);
        if (n->bound_lsb <= 1.0) assert_int_equal(r.w, -QO_Q30_ONE);
        xrng.s = 12;
        for (k = 0; k < 20000; k++) {
            /* Random directions at random scales, from a few LSB to the end of the range. */
            dq d = ref_rng_quat(&xrng);
            double s = ldexp(1.0, -(int)(ref_rng_next(&xrng) % 28u)) * (1.0 + ref_rng_unit(&xrng));
            qo_quat_q30 q;
            q.w = qo_q30_from_f32((float)(d.w * s)); q.x = qo_q30_from_f32((float)(d.x * s));
            q.y = qo_q30_from_f32((float)(d.y * s)); q.z = qo_q30_from_f32((float)(d.z * s));
            if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) continue;
            check_normalize(n, q);
        }
        /* Raw int32 components of random magnitude (every scaling branch). */
        for (k = 0; k < 200000; k++) {
            unsigned sh = (unsigned)(ref_rng_next(&xrng) % 32u);
            qo_quat_q30 q;
            q.w = (int32_t)(uint32_t)ref_rng_next(&xrng) >> sh; q.x = (int32_t)(uint32_t)ref_rng_next(&xrng) >> sh;
            q.y = (int32_t)(uint32_t)ref_rng_next(&xrng) >> sh; q.z = (int32_t)(uint32_t)ref_rng_next(&xrng) >> sh;
            if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) continue;
            check_normalize(n, q);
        }
    }
}

/* rotate at the ends of the format: defined (no overflow UB), identity exact on any vector, the
 * zero quaternion leaves v unchanged (the rounding is test_rotate, both cores) */
static void test_q30_rotate_edges(void **state)
{
    qo_vec3_q30 r;
    (void)state;
    /* Identity leaves v alone exactly; saturation for absurd inputs stays defined. */
    r = qo_quat_rotate_q30(qo_quat_identity_q30(), (qo_vec3_q30){ 123, INT32_MIN, INT32_MAX });
    assert_int_equal(r.x, 123); assert_int_equal(r.y, INT32_MIN); assert_int_equal(r.z, INT32_MAX);
    r = qo_quat_rotate_q30((qo_quat_q30){ INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN },
                           (qo_vec3_q30){ INT32_MIN, INT32_MAX, INT32_MIN });
    /* (The call above must merely be free of overflow UB: UBSan aborts the test otherwise.)
     * The zero quaternion leaves v unchanged (t = 0). */
    r = qo_quat_rotate_q30((qo_quat_q30){ 0, 0, 0, 0 }, (qo_vec3_q30){ 5, -6, 7 });
    assert_int_equal(r.x, 5); assert_int_equal(r.y, -6); assert_int_equal(r.z, 7);
}

/* exp and log at the ends of the format: 4 rad and INT32_MIN refused, -1 and a 5-LSB w exact,
 * a tiny rotation to the LSB, NULL (the rounding is test_exp_log, both cores) */
static void test_q30_exp_log_edges(void **state)
{
    qo_quat_q30 r;
    qo_vec3_q28 v;
    (void)state;
    /* Edges. */
    assert_int_equal(qo_quat_exp_q30((qo_vec3_q28){ 0, 0, 0 }, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
    assert_int_equal(qo_quat_exp_q30((qo_vec3_q28){ 4 * QO_Q28_ONE, 0, 0 }, &r), QO_E_RANGE);
    assert_int_equal(r.w, QO_Q30_ONE);
    assert_int_equal(qo_quat_exp_q30((qo_vec3_q28){ 0, INT32_MIN, 0 }, &r), QO_E_RANGE);
    assert_int_equal(qo_quat_exp_q30((qo_vec3_q28){ 0, 0, 0 }, NULL), QO_E_NULL);
    assert_int_equal(qo_quat_log_q30((qo_quat_q30){ 0, 0, 0, 0 }, &v), QO_E_DEGENERATE);
    assert_int_equal(v.x, 0); assert_int_equal(v.y, 0); assert_int_equal(v.z, 0);
    assert_int_equal(qo_quat_log_q30((qo_quat_q30){ -QO_Q30_ONE, 0, 0, 0 }, &v), QO_OK);
    assert_int_equal(v.x, QO_Q28_PI); assert_int_equal(v.y, 0);
    assert_int_equal(qo_quat_log_q30((qo_quat_q30){ 5, 0, 0, 0 }, &v), QO_OK);
    assert_int_equal(v.x, 0);
    assert_int_equal(qo_quat_log_q30(qo_quat_identity_q30(), NULL), QO_E_NULL);
    /* A tiny rotation: log (1, e) = (e) to the LSB. */
    assert_int_equal(qo_quat_log_q30((qo_quat_q30){ QO_Q30_ONE, 64, 0, 0 }, &v), QO_OK);
    assert_int_equal(v.x, 16);
}

/* integrate: NULL, a 6-LSB quaternion normalised (the rounding is test_integrate, both cores) */
static void test_q30_integrate_edges(void **state)
{
    qo_quat_q30 r;
    (void)state;
    assert_int_equal(qo_quat_integrate_q30((qo_quat_q30){ 0, 0, 0, 0 }, (qo_vec3_q28){ 1, 2, 3 }, &r), QO_E_DEGENERATE);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
    assert_int_equal(qo_quat_integrate_q30(qo_quat_identity_q30(), (qo_vec3_q28){ 1, 2, 3 }, NULL), QO_E_NULL);
    /* Zero increment: q normalised. */
    assert_int_equal(qo_quat_integrate_q30((qo_quat_q30){ 2 * 3, 0, 0, 0 }, (qo_vec3_q28){ 0, 0, 0 }, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        BOTH(test_exp_log),
        BOTH(test_mul_conj_dot),
        BOTH(test_normalize),
        BOTH(test_canonical),
        BOTH(test_angle_between),
        BOTH(test_integrate),
        BOTH(test_rotate),
        cmocka_unit_test(test_f32_norm_range),
        cmocka_unit_test(test_f32_normalize),
        cmocka_unit_test(test_f32_inverse),
        cmocka_unit_test(test_f32_canonical_ties),
        cmocka_unit_test(test_f32_exp_edges),
        cmocka_unit_test(test_f32_log_edges),
        cmocka_unit_test(test_f32_integrate),
        cmocka_unit_test(test_f32_is_finite),
        cmocka_unit_test(test_f32_lecture_examples),
        cmocka_unit_test(test_f32_simd_same_bits_as_scalar),
        cmocka_unit_test(test_q30_identity_conj_inverse_canonical),
        cmocka_unit_test(test_q30_mul_saturation),
        cmocka_unit_test(test_q30_normalize),
        cmocka_unit_test(test_q30_rotate_edges),
        cmocka_unit_test(test_q30_exp_log_edges),
        cmocka_unit_test(test_q30_integrate_edges),
    };
    return cmocka_run_group_tests_name("quat", tests, NULL, NULL);
}
