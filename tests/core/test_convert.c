/*
 * tests/core/test_convert.c - the rotation conversions of qorient/convert.h (float32) and
 * qorient/convert_fx.h (Q1.30): axis-angle, rotation vector, to/from rotation matrix and the
 * mat3 helpers, one test program for the concept (docs/TESTING.md, "One body for both cores").
 *
 * First section: one body per behaviour both cores have, registered with BOTH against the
 * adapter table of tests/common/cores.h: inputs rounded as each core receives them, the
 * reference computed in double from those rounded values, each core with its own tolerance;
 * the edges (identity, antipodal, zero, non-rotations, each core's out-of-range value) in the
 * same body. Then the core-only behaviour: float32 (an edge table of 180-degree turns and
 * the four Shepperd pivots, drifted and rank-deficient matrices, NaN/Inf, NULL) and Q1.30
 * (results to the LSB, fxconv.h inputs, saturation, NULL outputs).
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "common/cores.h"
#include "common/ref.h"
#include "qorient/convert.h"
#include "qorient/convert_fx.h"
#include "qorient/fxconv.h"
#include "qorient/fxmath.h"
#include "qorient/quat.h"
#include "qorient/quat_fx.h"

#define N_RANDOM 1000
#define N_LONG 20000

/* ==== one body, both cores (common/cores.h) ==================================== */

/* from_axis_angle against the double formula of the ROUNDED axis and angle (float32: axes of
 * length 1e-30 to 1e30, angles to 4 pi, L1 error 2e-6; Q1.30: axes down to 2^-28, angles to
 * 8 rad, 1.5 LSB); to_axis_angle against the canonical double axis and angle (float32: 1e-6;
 * Q1.30: 3 LSB) over q of any sign and scale, the axis a unit vector, the angle in [0, pi] */
static void test_axis_angle(void **state)
{
    const core *c = *state;
    static const double f_scale[] = { 1.0, 1e-30, 1e30, 3.7 }, f_qscale[] = { -3.0, 1e-20, 1.0 };
    const double pi_max = c->fixed ? PI + c->tol_ang : (double)3.14159274f;
    const double tol_ang = c->fixed ? 3 / Q28 : 1e-6, tol_axis = c->fixed ? 3 / Q30 : 1e-6;
    int n;
    dq o;
    ref_vec3 ax;
    double ang;
    rng_seed(106);
    for (n = 0; n < N_LONG; n++) {
        double sc = c->fixed ? ldexp(1.0, -(int)(rng_next() % 29u)) : f_scale[n % 4];
        ref_vec3 axis = v_in(c, v_rand(-sc, sc), 0), cax;
        double a = c->a_in(c->fixed ? 7.99 * rng_range(-1, 1) : rng_range(-4 * PI, 4 * PI));
        double qs = c->fixed ? (n % 4 == 0 ? -1.0 : n % 4 == 1 ? rng_range(0.5, 1.5) : 1.0)
                             : (n % 4 == 3 ? rng_range(0.5, 1.5) : f_qscale[n % 4]);
        dq want = ref_quat_from_axis_angle(axis, a), q, back, cq;
        double err, vn;
        if (v_norm(axis) > 0) {
            if (c->from_axis_angle(axis, a, &o) != QO_OK ||
                (c->fixed ? q_dist(o, want) > 1.5 / Q30
                          : fabs(o.w - want.w) + fabs(o.x - want.x) + fabs(o.y - want.y) +
                                fabs(o.z - want.z) > 2e-6))
                fail_msg("%s from_axis_angle case %d: axis (%.10g %.10g %.10g) angle %.10g got "
                         QFMT " want " QFMT, c->name, n, axis.x, axis.y, axis.z, a, QARG(o),
                         QARG(want));
        }
        q = c->q_in(dq_scale(rand_unit(), qs));
        if (c->to_axis_angle(q, &ax, &ang) != QO_OK || !(ang >= 0 && ang <= pi_max))
            fail_msg("%s to_axis_angle case %d: q " QFMT " angle %.10g", c->name, n, QARG(q), ang);
        back = ref_quat_from_axis_angle(ax, ang);
        err = rot_err(back, q);
        if (err > (c->fixed ? 4 * c->tol_ang : 1e-6) || fabs(v_norm(ax) - 1) > (c->fixed ? 4 * c->tol_abs : 1e-6))
            fail_msg("%s to_axis_angle case %d: q " QFMT " gives a rotation %.3g rad off, |axis| %.12g",
                     c->name, n, QARG(q), err, v_norm(ax));
        /* the angle and the axis against the canonical double ones (the short way) */
        cq = ref_quat_canonical(ref_quat_normalize(q));
        vn = sqrt(cq.x * cq.x + cq.y * cq.y + cq.z * cq.z);
        cax = v_make(cq.x / vn, cq.y / vn, cq.z / vn);
        if (fabs(ang - 2 * atan2(vn, cq.w)) > tol_ang || v_dist(ax, cax) > tol_axis)
            fail_msg("%s to_axis_angle case %d: q " QFMT " angle %.12g vs %.12g, axis error %.3g",
                     c->name, n, QARG(q), ang, 2 * atan2(vn, cq.w), v_dist(ax, cax));
    }
    /* identity: axis (1, 0, 0), angle 0; -identity (any scale) the same */
    assert_int_equal(c->to_axis_angle(ID, &ax, &ang), QO_OK);
    assert_true(ang == 0 && ax.x == 1 && ax.y == 0 && ax.z == 0);
    assert_int_equal(c->to_axis_angle(dq_neg(ID), &ax, &ang), QO_OK);
    assert_true(ang == 0 && ax.x == 1);
    assert_int_equal(c->to_axis_angle(dq_scale(ID, -0.125), &ax, &ang), QO_OK);
    assert_true(ang == 0 && ax.x == 1 && ax.y == 0 && ax.z == 0);
    /* exactly pi about -y: the canonical axis +y */
    {
        const dq ym = { 0, 0, -1, 0 };
        assert_int_equal(c->to_axis_angle(ym, &ax, &ang), QO_OK);
        assert_true(ax.x == 0 && ax.y == 1 && ax.z == 0);
        assert_true(fabs(ang - PI) <= (c->fixed ? 2 / Q28 : 1e-6) && ang <= pi_max);
    }
    assert_int_equal(c->to_axis_angle(ZERO_Q, &ax, &ang), QO_E_DEGENERATE);
    assert_true(ang == 0 && ax.x == 1 && ax.y == 0 && ax.z == 0);
    assert_int_equal(c->from_axis_angle(v_make(0, 0, 0), 1.0, &o), QO_E_DEGENERATE);
    assert_true(dq_is(o, ID));
    assert_int_equal(c->from_axis_angle(v_make(0, 0, 0), 0.0, &o), QO_E_DEGENERATE);
    assert_true(dq_is(o, ID));
    /* angle 0 about a valid axis: the identity exactly */
    assert_int_equal(c->from_axis_angle(v_in(c, v_make(0.25, 0.5, 0.75), 0), 0.0, &o), QO_OK);
    assert_true(dq_is(o, ID));
    /* out of range axis: Inf (float32) / saturated (fixed: a valid long axis) */
    assert_int_equal(c->from_axis_angle(v_make(c->big, 0, 0), 1.0, &o),
                     ST(c, QO_E_NONFINITE, QO_OK));
    if (c->fixed) assert_true(rot_err(o, dq_axis_angle(1, 0, 0, 1.0)) <= 4 * c->tol_ang);
}


/* the canonical (short-way) rotation vector of q, in double */
static ref_vec3 ref_rotvec(ref_quat q)
{
    ref_quat c = ref_quat_canonical(ref_quat_normalize(q));
    double vn = sqrt(c.x * c.x + c.y * c.y + c.z * c.z), k;
    ref_vec3 r = { 0.0, 0.0, 0.0 };
    if (vn == 0.0) return r;
    k = 2.0 * atan2(vn, c.w) / vn;
    r.x = k * c.x; r.y = k * c.y; r.z = k * c.z;
    return r;
}

/* from_rotvec against the double formula of the ROUNDED vector (float32: L1 2e-6, |rv| to 3 pi;
 * Q1.30: 2 LSB, components of 1e-6, 3.1 and 7.9 rad; both: |rv| from 1e-7); to_rotvec against
 * the canonical double vector (float32: L1 2e-6; Q1.30: 3 LSB of Q3.28) over random, nearly
 * identity and nearly half-turn rotations; the round trip from a short-way vector */
static void test_rotvec(void **state)
{
    const core *c = *state;
    static const double x_scale[] = { 1e-6, 3.1, 7.9 };
    int n;
    dq o;
    ref_vec3 rv;
    rng_seed(107);
    for (n = 0; n < N_LONG; n++) {
        ref_vec3 d = v_rand(-1, 1), r, rb, rt;
        dq want, q, back;
        double err;
        if (n % 4 == 0) {
            double s = pow(10.0, rng_range(-7, -2)) / v_norm(d);
            d = v_make(d.x * s, d.y * s, d.z * s);
        } else if (c->fixed) {
            double s = x_scale[n % 3];
            d = v_make(d.x * s, d.y * s, d.z * s);
        } else {
            double s = rng_range(0, 3 * PI) / v_norm(d);
            d = v_make(d.x * s, d.y * s, d.z * s);
        }
        r = v_in(c, d, 1);
        want = ref_quat_from_axis_angle(r, v_norm(r));
        if (c->from_rotvec(r, &o) != QO_OK ||
            (c->fixed ? q_dist(o, want) > 2 / Q30
                      : fabs(o.w - want.w) + fabs(o.x - want.x) + fabs(o.y - want.y) +
                            fabs(o.z - want.z) > 2e-6))
            fail_msg("%s from_rotvec case %d: rv (%.10g %.10g %.10g) got " QFMT " want " QFMT,
                     c->name, n, r.x, r.y, r.z, QARG(o), QARG(want));
        /* to_rotvec of random rotations, including near-identity and near-pi ones */
        q = rand_unit();
        if (n % 4 == 1) { q.w = 1.0; q.x *= 1e-6; q.y *= 1e-6; q.z *= 1e-6; }
        if (n % 4 == 2) q.w *= 1e-6;
        q = c->q_in(q);
        rb = ref_rotvec(q);
        if (c->to_rotvec(q, &rv) != QO_OK || v_norm(rv) > PI + (c->fixed ? 2 * c->tol_ang : 1e-6) ||
            (c->fixed ? v_dist(rv, rb) > 3 / Q28
                      : fabs(rv.x - rb.x) + fabs(rv.y - rb.y) + fabs(rv.z - rb.z) > 2e-6))
            fail_msg("%s to_rotvec case %d: q " QFMT " got (%.10g %.10g %.10g) want (%.10g %.10g "
                     "%.10g)", c->name, n, QARG(q), rv.x, rv.y, rv.z, rb.x, rb.y, rb.z);
        back = v_norm(rv) > 0 ? ref_quat_from_axis_angle(rv, v_norm(rv)) : ID;
        if (rot_err(back, q) > 4 * c->tol_ang)
            fail_msg("%s to_rotvec case %d: q " QFMT " gives a rotation %.3g rad off", c->name,
                     n, QARG(q), rot_err(back, q));
        /* short-way vectors come back unchanged; near pi the canonical flip may give the
         * antipode -rv (2 pi - |rv|) / |rv| (the same rotation): compared as rotations there */
        r = v_in(c, ref_rotvec(ref_quat_canonical(rand_unit())), 1);
        if (c->from_rotvec(r, &o) != QO_OK || c->to_rotvec(o, &rt) != QO_OK)
            fail_msg("%s rotvec round trip case %d: refused", c->name, n);
        err = fabs(rt.x - r.x) + fabs(rt.y - r.y) + fabs(rt.z - r.z);
        if (err > (c->fixed ? 16 / Q28 : 3e-6) &&
            ref_quat_angle_between(ref_quat_from_axis_angle(r, v_norm(r)),
                                   ref_quat_from_axis_angle(rt, v_norm(rt))) > c->tol_ang / 2)
            fail_msg("%s rotvec round trip case %d: (%.10g %.10g %.10g) -> (%.10g %.10g %.10g)",
                     c->name, n, r.x, r.y, r.z, rt.x, rt.y, rt.z);
    }
    assert_int_equal(c->from_rotvec(v_make(0, 0, 0), &o), QO_OK);
    assert_true(dq_is(o, ID));
    /* identity and -identity: zero exactly; exactly pi about -z: +z (canonical sign) */
    assert_int_equal(c->to_rotvec(ID, &rv), QO_OK);
    assert_true(rv.x == 0 && rv.y == 0 && rv.z == 0);
    assert_int_equal(c->to_rotvec(dq_neg(ID), &rv), QO_OK);
    assert_true(rv.x == 0 && rv.y == 0 && rv.z == 0);
    {
        const dq zm = { 0, 0, 0, -1 };
        assert_int_equal(c->to_rotvec(zm, &rv), QO_OK);
        assert_true(rv.x == 0 && rv.y == 0 && fabs(rv.z - PI) <= (c->fixed ? 2 / Q28 : 1e-6));
        if (c->fixed) assert_true(rv.z <= QO_Q28_PI / Q28);
    }
    /* q and -q: the same rotation vector (canonical sign) */
    o = c->q_in(dq_axis_angle(1, -2, 0.5, 2.0));
    assert_int_equal(c->to_rotvec(o, &rv), QO_OK);
    {
        ref_vec3 rn;
        assert_int_equal(c->to_rotvec(dq_neg(o), &rn), QO_OK);
        assert_true(v_dist(rv, rn) <= 2 * c->tol_ang);
    }
    rv = v_make(9, 9, 9);
    assert_int_equal(c->to_rotvec(ZERO_Q, &rv), QO_E_DEGENERATE);
    assert_true(v_norm(rv) == 0);
    /* out of range: Inf (float32) / saturated Q3.28 (fixed: |rv| ~ 8 rad, a valid turn) */
    assert_int_equal(c->from_rotvec(v_make(c->big, 0, 0), &o), ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(fabs(dq_norm(o) - 1) <= 4 * c->tol_abs);
}


/* to_mat3 against the double matrix of q/|q| (float32: 1e-6 per entry, any scale 0.1..10 and
 * sign; Q1.30: 3 LSB, |q| down to 1e-3), orthonormal, the same rotation as normalize + rotate;
 * mat3_mul_vec3 of that matrix to one rounding; from_mat3 (checked, trusted, ortho) of the
 * rounded matrix against its canonical double quaternion (float32: 1e-6 rad, |q| = 1; Q1.30:
 * 3 LSB), w >= 0; random, near-identity and near-half-turn rotations */
static void test_mat3_quat(void **state)
{
    const core *c = *state;
    /* Q1.30: half an LSB (1e-14 for the double reference's own rounding of 62-bit products) */
    const double half_lsb = 0.5 / Q30 + 1e-14, vr = c->fixed ? 0.57 : 2.0;
    int n;
    dq o;
    ref_mat3 m;
    rng_seed(108);
    for (n = 0; n < N_LONG; n++) {
        dq q = n % 5 == 1 ? rand_axis_rot(rng_range(PI - 1e-3, PI)) : rand_unit(), qn, wq;
        ref_mat3 want, mr;
        ref_vec3 v = v_in(c, v_rand(-vr, vr), 0), mv, rv, mw;
        double e;
        int i, j;
        if (n % 5 == 0) q = dq_scale(q, c->fixed ? 1e-3 : rng_range(0.1, 10.0));
        if (n % 5 == 2) q = dq_unit((dq){ q.w * 1e-5, q.x, q.y, q.z });
        if (n % 5 == 3) q = dq_unit((dq){ q.w, q.x * 1e-5, q.y * 1e-5, q.z * 1e-5 });
        if (n % 2) q = dq_neg(q);
        q = c->q_in(q);
        want = ref_quat_to_mat3(q);
        if (c->to_mat3(q, &m) != QO_OK || m_dist(&m, &want) > (c->fixed ? 3 / Q30 : 1e-6) ||
            ref_mat3_rotation_distance(&m, &want) > (c->fixed ? 4 * c->tol_rot : 1e-6) ||
            m_orth_err(&m) > (c->fixed ? 4 * c->tol_abs : 1e-6))
            fail_msg("%s mat3_from_quat case %d: q " QFMT " error %.3g, orthogonality %.3g", c->name, n,
                     QARG(q), m_dist(&m, &want), m_orth_err(&m));
        /* M v to one rounding, and the rotation of v by q/|q| */
        mv = c->mat3_mul_vec3(&m, v);
        for (i = 0; i < 3; i++) {
            double s = 0;
            for (j = 0; j < 3; j++) s += m.m[i][j] * (j == 0 ? v.x : j == 1 ? v.y : v.z);
            if (i == 0) mw.x = s; else if (i == 1) mw.y = s; else mw.z = s;
        }
        if (v_dist(mv, mw) > (c->fixed ? half_lsb : 4e-7 * (fabs(v.x) + fabs(v.y) + fabs(v.z))))
            fail_msg("%s mat3_mul_vec3 case %d: (%.12g %.12g %.12g) vs (%.12g %.12g %.12g)",
                     c->name, n, mv.x, mv.y, mv.z, mw.x, mw.y, mw.z);
        if (c->normalize(q, &qn) != QO_OK) fail_msg("%s normalize case %d", c->name, n);
        rv = c->rotate(qn, v);
        if (v_dist(mv, rv) > (c->fixed ? 8 / Q30 : 2e-6))
            fail_msg("%s mat3_from_quat case %d disagrees with rotate: (%.12g %.12g %.12g) vs "
                     "(%.12g %.12g %.12g)", c->name, n, mv.x, mv.y, mv.z, rv.x, rv.y, rv.z);
        mr = m_in(c, &want);
        wq = ref_mat3_to_quat(&mr);
        if (c->from_mat3(&mr, &o) != QO_OK || rot_err(o, wq) > 4 * c->tol_rot || o.w < 0)
            fail_msg("%s mat3_to_quat case %d: q " QFMT " got " QFMT, c->name, n, QARG(q), QARG(o));
        /* float32: the angle and the norm; Q1.30: each component (at w == 0 either sign) */
        e = c->fixed ? fmin(q_dist(o, wq), fabs(wq.w) < 1e-8 ? q_dist(o, dq_neg(wq)) : 1)
                     : rot_err(o, wq);
        if (e > (c->fixed ? 3 / Q30 : 1e-6) || (!c->fixed && fabs(dq_norm(o) - 1) > 1e-6))
            fail_msg("%s mat3_to_quat case %d: q " QFMT " got " QFMT " want " QFMT " error %.3g",
                     c->name, n, QARG(q), QARG(o), QARG(wq), e);
        if (c->from_mat3_trusted(&mr, &o) != QO_OK || rot_err(o, wq) > 4 * c->tol_rot || o.w < 0)
            fail_msg("%s mat3_to_quat_trusted case %d: q " QFMT " got " QFMT, c->name, n, QARG(q),
                     QARG(o));
        if (c->from_mat3_ortho(&mr, &o) != QO_OK || rot_err(o, wq) > 4 * c->tol_rot || o.w < 0)
            fail_msg("%s mat3_to_quat_ortho case %d: q " QFMT " got " QFMT, c->name, n, QARG(q),
                     QARG(o));
    }
    /* identity both ways; q and -q give the same matrix */
    assert_int_equal(c->to_mat3(ID, &m), QO_OK);
    assert_true(m_dist(&m, (const ref_mat3[]){ c->mat3_identity() }) == 0);
    assert_int_equal(c->from_mat3(&m, &o), QO_OK);
    assert_true(dq_is(o, ID));
    {
        ref_mat3 mn;
        o = c->q_in(rand_unit());
        assert_int_equal(c->to_mat3(o, &m), QO_OK);
        assert_int_equal(c->to_mat3(dq_neg(o), &mn), QO_OK);
        assert_true(m_dist(&m, &mn) <= c->tol_abs);
    }
    assert_int_equal(c->to_mat3(ZERO_Q, &m), QO_E_DEGENERATE);
    assert_true(m_dist(&m, (const ref_mat3[]){ c->mat3_identity() }) == 0);
    /* not rotations: scaled by 1.01, a reflection, zero */
    m = c->mat3_identity();
    m.m[1][1] = c->u_in(1.01);
    assert_int_equal(c->from_mat3(&m, &o), QO_E_NOT_ROTATION);
    assert_true(dq_is(o, ID));
    m.m[1][1] = -1;
    assert_int_equal(c->from_mat3(&m, &o), QO_E_NOT_ROTATION);
    memset(&m, 0, sizeof m);
    assert_int_equal(c->from_mat3(&m, &o), QO_E_NOT_ROTATION);
    /* out of range entries: Inf (float32) / saturated (fixed: scaled, not a rotation) */
    m = c->mat3_identity();
    m.m[0][0] = c->big;
    assert_int_equal(c->from_mat3(&m, &o), ST(c, QO_E_NONFINITE, QO_E_NOT_ROTATION));
    assert_true(dq_is(o, ID));
}


static void test_mat3_ops(void **state)
{
    const core *c = *state;
    int n, i, j;
    ref_mat3 o, id = c->mat3_identity();
    const double gr = c->fixed ? 1.9 : 2.0, vr = c->fixed ? 1.0 : 10.0;
    rng_seed(109);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) assert_true(id.m[i][j] == (i == j));
    for (n = 0; n < N_RANDOM; n++) {
        ref_mat3 a = m_rand_rot(c), b = m_rand_rot(c), want = ref_mat3_mul(&a, &b), g, g2, t;
        ref_vec3 v = v_in(c, v_rand(-vr, vr), 0), mv, mw;
        /* general matrices, entries up to 2 (float32) or 1.9: products saturate in fixed point */
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) {
                g.m[i][j] = c->u_in(rng_range(-gr, gr));
                g2.m[i][j] = c->u_in(rng_range(-gr, gr));
            }
        o = c->mat3_mul(&a, &b);
        if (m_dist(&o, &want) > 2 * c->tol_abs)
            fail_msg("%s mat3_mul case %d: error %.3g", c->name, n, m_dist(&o, &want));
        want = ref_mat3_mul(&g, &a);
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) want.m[i][j] = clampd(want.m[i][j], c->u_min, c->u_max);
        o = c->mat3_mul(&g, &a);
        if (m_dist(&o, &want) > 4 * c->tol_abs * (1 + 3 * 1.9)) {
            print_m("g", &g);
            fail_msg("%s mat3_mul (general) case %d: error %.3g", c->name, n, m_dist(&o, &want));
        }
        /* two general matrices (float32: 1e-5; fixed: clamped where the product saturates) */
        want = ref_mat3_mul(&g, &g2);
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) want.m[i][j] = clampd(want.m[i][j], c->u_min, c->u_max);
        o = c->mat3_mul(&g, &g2);
        if (m_dist(&o, &want) > (c->fixed ? 4 * c->tol_abs * (1 + 3 * 1.9) : 1e-5)) {
            print_m("g", &g);
            print_m("g2", &g2);
            fail_msg("%s mat3_mul (two general) case %d: error %.3g", c->name, n, m_dist(&o, &want));
        }
        /* M v of a general matrix (float32: v up to 10, 1e-4) */
        mv = c->mat3_mul_vec3(&g, v);
        mw = v_make(clampd(g.m[0][0] * v.x + g.m[0][1] * v.y + g.m[0][2] * v.z, c->u_min, c->u_max),
                    clampd(g.m[1][0] * v.x + g.m[1][1] * v.y + g.m[1][2] * v.z, c->u_min, c->u_max),
                    clampd(g.m[2][0] * v.x + g.m[2][1] * v.y + g.m[2][2] * v.z, c->u_min, c->u_max));
        if (v_dist(mv, mw) > (c->fixed ? 4 * c->tol_abs * (1 + 3 * 1.9) : 1e-4))
            fail_msg("%s mat3_mul_vec3 (general) case %d: (%.10g %.10g %.10g) vs (%.10g %.10g %.10g)",
                     c->name, n, mv.x, mv.y, mv.z, mw.x, mw.y, mw.z);
        t = c->mat3_transpose(&g);
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) assert_true(t.m[i][j] == g.m[j][i]);
        /* det: 1 for a rotation, -1 for a reflection, the general value (clamped) */
        if (fabs(c->mat3_det(&a) - 1) > 4 * c->tol_abs)
            fail_msg("%s mat3_det rotation case %d: %.12g", c->name, n, c->mat3_det(&a));
        for (j = 0; j < 3; j++) a.m[1][j] = -a.m[1][j];
        if (fabs(c->mat3_det(&a) + 1) > 4 * c->tol_abs)
            fail_msg("%s mat3_det reflection case %d: %.12g", c->name, n, c->mat3_det(&a));
        {
            double wd = clampd(ref_mat3_det(&g), c->u_min, c->u_max), gd = c->mat3_det(&g);
            /* float32: the cofactor expansion cancels (|terms| up to ~7 x 6e-8);
             * fixed: Q3.28 cofactors for entries beyond 1 + 1/16 (<= ~8 LSB) */
            if (fabs(gd - wd) > (c->fixed ? 16 / Q30 : 1e-5)) {
                print_m("g", &g);
                fail_msg("%s mat3_det case %d: %.12g want %.12g", c->name, n, gd, wd);
            }
        }
    }
    /* edges: det of I, of zero, of the largest entries */
    assert_true(c->mat3_det(&id) == 1);
    o = id;
    o.m[2][2] = -1;
    assert_true(c->mat3_det(&o) == -1);
    memset(&o, 0, sizeof o);
    assert_true(c->mat3_det(&o) == 0);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) o.m[i][j] = c->u_in(i == j ? c->big : 0);
    /* fixed: 8 saturates; float32: Inf * 0 in the cofactors, not finite */
    if (c->fixed) assert_true(c->mat3_det(&o) == c->u_max);
    else assert_true(!isfinite(c->mat3_det(&o)));
}


/* quaternion -> matrix / rotation vector / axis-angle -> quaternion: the same rotation
 * (float32: 1e-6 rad; Q1.30: 16 LSB of Q3.28), q canonical and as the core holds it */
static void test_round_trips(void **state)
{
    const core *c = *state;
    const double tol = c->fixed ? 16 / Q28 : 1e-6;
    int n;
    rng_seed(116);
    for (n = 0; n < 5000; n++) {
        dq q = c->q_in(ref_quat_canonical(rand_unit())), back;
        ref_mat3 m;
        ref_vec3 v;
        double an;
        if (c->to_mat3(q, &m) != QO_OK || c->from_mat3(&m, &back) != QO_OK || rot_err(q, back) > tol)
            fail_msg("%s mat3 round trip case %d: " QFMT " -> " QFMT, c->name, n, QARG(q), QARG(back));
        if (c->to_rotvec(q, &v) != QO_OK || c->from_rotvec(v, &back) != QO_OK || rot_err(q, back) > tol)
            fail_msg("%s rotvec round trip case %d: " QFMT " -> " QFMT, c->name, n, QARG(q),
                     QARG(back));
        if (c->to_axis_angle(q, &v, &an) != QO_OK || c->from_axis_angle(v, an, &back) != QO_OK ||
            rot_err(q, back) > tol)
            fail_msg("%s axis-angle round trip case %d: " QFMT " -> " QFMT, c->name, n, QARG(q),
                     QARG(back));
    }
}

/* U diag(s1, s2, s3) V^T with U, V the rotations of u, v, in double */
static ref_mat3 svd_of(dq u, dq v, double s1, double s2, double s3)
{
    ref_mat3 mu = ref_quat_to_mat3(u), mv = ref_quat_to_mat3(v);
    ref_mat3 d = { { { 0 } } }, vt, t;
    int i, j;
    d.m[0][0] = s1; d.m[1][1] = s2; d.m[2][2] = s3;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) vt.m[i][j] = mv.m[j][i];
    t = ref_mat3_mul(&mu, &d);
    return ref_mat3_mul(&t, &vt);
}

/* the same with random U, V */
static ref_mat3 svd_m(double s1, double s2, double s3)
{
    dq u = rand_unit(), v = rand_unit();
    return svd_of(u, v, s1, s2, s3);
}

/* m (as the core holds it) orthonormalised: within tol of the double polar factor (float32:
 * 1e-6 rad; Q1.30: 4 tol_rot), orthonormal (1e-6; 8 tol_abs), det > 0.999, and
 * from_mat3_ortho lands on the same rotation with w >= 0; returns the distance */
static double core_check_ortho(const core *c, const char *what, int n, const ref_mat3 *m)
{
    ref_mat3 o, want = ref_mat3_nearest_rotation(m);
    dq q;
    double e;
    const double tol = c->fixed ? 4 * c->tol_rot : 1e-6;
    if (c->orthonormalize(m, &o) != QO_OK) {
        print_m("m", m);
        fail_msg("%s orthonormalize %s case %d: refused", c->name, what, n);
    }
    e = ref_mat3_rotation_distance(&o, &want);
    if (e > tol || m_orth_err(&o) > (c->fixed ? 8 * c->tol_abs : 1e-6) || ref_mat3_det(&o) < 0.999) {
        print_m("m", m);
        print_m("got", &o);
        fail_msg("%s orthonormalize %s case %d: %.3g rad from the nearest rotation, "
                 "orthogonality error %.3g", c->name, what, n, e, m_orth_err(&o));
    }
    if (c->from_mat3_ortho(m, &q) != QO_OK || rot_err(q, ref_mat3_to_quat(&want)) > tol || q.w < 0)
        fail_msg("%s mat3_to_quat_ortho %s case %d: " QFMT, c->name, what, n, QARG(q));
    return e;
}

/* orthonormalize and from_mat3_ortho: drifted and scaled rotations, noise from 1e-7 to 0.3,
 * exact rotations and the identity, in place; refused (identity out): reflections, zero,
 * rank 2, nearly singular, nearly rank 1 */
static void test_orthonormalize(void **state)
{
    const core *c = *state;
    static const double amp[] = { 1e-7, 1e-5, 1e-3, 1e-2, 0.1, 0.3 };
    size_t k;
    int n, i, j;
    ref_mat3 o;
    dq q;
    double worst = 0;
    rng_seed(110);
    for (n = 0; n < N_RANDOM; n++) {
        /* a rotation, drifted (noise 1e-6 .. 0.1) and uniformly scaled (0.3 .. 1.7) */
        ref_mat3 m = ref_quat_to_mat3(rand_unit());
        double noise = pow(10.0, rng_range(-6, -1)), s = rng_range(0.3, 1.7);
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) m.m[i][j] = s * m.m[i][j] + rng_range(-noise, noise);
        m = m_in(c, &m);
        worst = fmax(worst, core_check_ortho(c, "drifted", n, &m));
    }
    for (k = 0; k < sizeof amp / sizeof amp[0]; k++) {
        for (n = 0; n < 300; n++) {
            ref_mat3 m = ref_quat_to_mat3(rand_unit());
            for (i = 0; i < 3; i++)
                for (j = 0; j < 3; j++) m.m[i][j] += rng_range(-amp[k], amp[k]);
            m = m_in(c, &m);
            worst = fmax(worst, core_check_ortho(c, "noisy", n, &m));
        }
    }
    /* refused, the outputs the identity: the cases both formats hold */
    {
        struct { const char *name; ref_mat3 m; } no[10];
        const ref_mat3 r = ref_quat_to_mat3(rand_unit());
        const ref_mat3 diag = { { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, -1 } } };
        const ref_mat3 noisy = { { { 1.01, 0.02, 0 }, { -0.01, 0.98, 0.03 }, { 0, 0.01, -1.02 } } };
        size_t nn = 0;
        no[nn].name = "reflection diag(1,1,-1)"; no[nn++].m = diag;
        no[nn].name = "noisy reflection"; no[nn++].m = noisy;
        no[nn].name = "reflected random rotation"; no[nn].m = r;
        for (j = 0; j < 3; j++) no[nn].m.m[2][j] = -r.m[2][j];
        nn++;
        no[nn].name = "zero"; memset(&no[nn++].m, 0, sizeof(ref_mat3));
        no[nn].name = "rank 2 (exactly singular)"; no[nn].m = diag; no[nn++].m.m[2][2] = 0;
        no[nn].name = "just singular: sigma3 = 1e-7"; no[nn].m = diag; no[nn++].m.m[2][2] = 1e-7;
        no[nn].name = "U diag(1, 7e-5, 7e-5) V^T"; no[nn++].m = svd_m(1.0, 7e-5, 7e-5);
        no[nn].name = "U diag(1, 3e-4, 3e-4) V^T"; no[nn++].m = svd_m(1.0, 3e-4, 3e-4);
        no[nn].name = "U diag(1, 1, 1e-4) V^T"; no[nn++].m = svd_m(1.0, 1.0, 1e-4);
        for (k = 0; k < nn; k++) {
            ref_mat3 m = m_in(c, &no[k].m), out;
            qo_status st = c->orthonormalize(&m, &out), st2 = c->from_mat3_ortho(&m, &q);
            if (st != QO_E_NOT_ROTATION || st2 != QO_E_NOT_ROTATION || !dq_is(q, ID) ||
                m_dist(&out, (const ref_mat3[]){ c->mat3_identity() }) != 0) {
                print_m("m", &m);
                fail_msg("%s orthonormalize %s: status %d / %d, expected QO_E_NOT_ROTATION, "
                         "outputs the identity", c->name, no[k].name, (int)st, (int)st2);
            }
        }
    }
    /* just off singular, well inside the accepted condition range: converted */
    {
        ref_mat3 m = c->mat3_identity();
        m.m[2][2] = c->u_in(1e-3);
        (void)core_check_ortho(c, "sigma3 = 1e-3", 0, &m);
        m = c->mat3_identity();
        assert_int_equal(c->orthonormalize(&m, &o), QO_OK);
        assert_true(m_dist(&o, &m) == 0);
    }
    print_message("%s orthonormalize: worst %.3g rad from the nearest rotation\n", c->name, worst);
    /* a rotation comes back (within rounding); m and out may alias */
    o = m_rand_rot(c);
    {
        ref_mat3 r;
        assert_int_equal(c->orthonormalize(&o, &r), QO_OK);
        assert_true(m_dist(&o, &r) <= (c->fixed ? 4 * c->tol_abs : 3e-7));
        assert_int_equal(c->orthonormalize(&o, &o), QO_OK);
        assert_true(m_dist(&o, &r) == 0);
    }
    /* refused: zero, rank 2, a reflection; the output is the identity */
    {
        ref_mat3 r;
        memset(&o, 0, sizeof o);
        assert_int_equal(c->orthonormalize(&o, &r), QO_E_NOT_ROTATION);
        assert_true(m_dist(&r, (const ref_mat3[]){ c->mat3_identity() }) == 0);
        o = c->mat3_identity();
        o.m[2][2] = 0;
        assert_int_equal(c->orthonormalize(&o, &r), QO_E_NOT_ROTATION);
        o.m[2][2] = -1;
        assert_int_equal(c->orthonormalize(&o, &r), QO_E_NOT_ROTATION);
        assert_int_equal(c->from_mat3_ortho(&o, &q), QO_E_NOT_ROTATION);
        assert_true(dq_is(q, ID));
    }
    /* out of range: Inf (float32) / every entry saturated (fixed: rank 1, refused) */
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) o.m[i][j] = c->u_in(c->big);
    assert_int_equal(c->orthonormalize(&o, &o), ST(c, QO_E_NONFINITE, QO_E_NOT_ROTATION));
    /* a saturated diagonal (fixed: 2 - 2^-30 times the identity, a scaled rotation) */
    o = c->mat3_identity();
    for (i = 0; i < 3; i++) o.m[i][i] = c->u_in(fmin(c->u_max, 1.9));
    assert_int_equal(c->orthonormalize(&o, &o), QO_OK);
    assert_true(m_dist(&o, (const ref_mat3[]){ c->mat3_identity() }) <= 4 * c->tol_abs);
}


/* ==== float32 only: qorient/convert.h ====================================== */

/* Rotation error budget for one float32 conversion: round-off is ~1e-7 rad. */
#define TOL_RAD 1e-6
#define N_F32 2000

static qo_mat3_f32 mf(float a, float b, float c, float d, float e, float f, float g, float h,
                      float i)
{
    qo_mat3_f32 m;
    m.m[0][0] = a; m.m[0][1] = b; m.m[0][2] = c;
    m.m[1][0] = d; m.m[1][1] = e; m.m[1][2] = f;
    m.m[2][0] = g; m.m[2][1] = h; m.m[2][2] = i;
    return m;
}

static int is_identity_q(qo_quat_f32 q)
{
    return q.w == 1.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f;
}

static int is_identity_m(const qo_mat3_f32 *m)
{
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            if (m->m[i][j] != (i == j ? 1.0f : 0.0f)) return 0;
    return 1;
}

static double max_orth_error(const qo_mat3_f32 *m)
{
    double worst = 0.0;
    int i, j, k;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            double s = 0.0;
            for (k = 0; k < 3; k++) s += (double)m->m[k][i] * m->m[k][j];
            s -= (i == j);
            if (fabs(s) > worst) worst = fabs(s);
        }
    return worst;
}

static void print_q(const char *name, qo_quat_f32 q)
{
    print_error("  %s = (%.9g, %.9g, %.9g, %.9g)\n", name, q.w, q.x, q.y, q.z);
}

static void print_mf(const char *name, const qo_mat3_f32 *m)
{
    print_error("  %s = [%.9g %.9g %.9g; %.9g %.9g %.9g; %.9g %.9g %.9g]\n", name, m->m[0][0],
                m->m[0][1], m->m[0][2], m->m[1][0], m->m[1][1], m->m[1][2], m->m[2][0],
                m->m[2][1], m->m[2][2]);
}

/* A random rotation as an exact float32 matrix: the double matrix rounded to float. */
static qo_mat3_f32 rand_rot_f32(ref_rng *rng, ref_quat *q_out)
{
    ref_quat q = ref_rng_quat(rng);
    ref_mat3 r = ref_quat_to_mat3(q);
    if (q_out) *q_out = q;
    return ref_mat3_to_f32(&r);
}

/* ---- the edge table: rotations (axis, angle in degrees) where conversions are hardest ---- */
struct edge_rot { const char *name; double ax, ay, az, deg; };
static const struct edge_rot edges[] = {
    { "identity", 1, 0, 0, 0 },
    { "180 about x", 1, 0, 0, 180 },
    { "180 about y", 0, 1, 0, 180 },
    { "180 about z", 0, 0, 1, 180 },
    { "180 about -x", -1, 0, 0, 180 },
    { "180 about (1,1,0)", 1, 1, 0, 180 },
    { "180 about (1,0,1)", 1, 0, 1, 180 },
    { "180 about (0,1,1)", 0, 1, 1, 180 },
    { "180 about (1,-1,0)", 1, -1, 0, 180 },
    { "180 about (1,1,1)", 1, 1, 1, 180 },
    { "180 about (1,-1,1)", 1, -1, 1, 180 },
    { "179.999 about (1,1,1)", 1, 1, 1, 179.999 },
    { "180.001 about (1,2,3)", 1, 2, 3, 180.001 },
    { "120 about (1,1,1): trace 0, all pivots tie", 1, 1, 1, 120 },
    { "pivot trace: 10 about (1,2,3)", 1, 2, 3, 10 },
    { "pivot m00: 170 about (1,0.1,0.1)", 1, 0.1, 0.1, 170 },
    { "pivot m11: 170 about (0.1,1,0.1)", 0.1, 1, 0.1, 170 },
    { "pivot m22: 170 about (0.1,0.1,1)", 0.1, 0.1, 1, 170 },
    { "90 about z", 0, 0, 1, 90 },
    { "tiny 1e-6 rad about (3,-1,2)", 3, -1, 2, 1e-6 * 180.0 / REF_PI },
    { "tiny 1e-30 rad about y", 0, 1, 0, 1e-30 },
};
#define N_EDGES (sizeof edges / sizeof edges[0])

static ref_quat rscale_q(ref_quat q, double s)
{
    q.w *= s; q.x *= s; q.y *= s; q.z *= s;
    return q;
}

static ref_quat edge_quat(size_t k)
{
    ref_vec3 a = { edges[k].ax, edges[k].ay, edges[k].az };
    return ref_quat_from_axis_angle(a, edges[k].deg * REF_PI / 180.0);
}

/* ---- matrix helpers ---- */

/* ---- quaternion -> matrix ---- */

static void test_f32_mat3_from_quat_errors(void **state)
{
    qo_mat3_f32 m;
    (void)state;
    m = mf(5, 5, 5, 5, 5, 5, 5, 5, 5);
    assert_int_equal(qo_mat3_from_quat_f32(qf(0, 0, 0, 0), &m), QO_E_DEGENERATE);
    assert_true(is_identity_m(&m));
    m = mf(5, 5, 5, 5, 5, 5, 5, 5, 5);
    assert_int_equal(qo_mat3_from_quat_f32(qf(NAN, 0, 0, 0), &m), QO_E_NONFINITE);
    assert_true(is_identity_m(&m));
    m = mf(5, 5, 5, 5, 5, 5, 5, 5, 5);
    assert_int_equal(qo_mat3_from_quat_f32(qf(1, 0, -INFINITY, 0), &m), QO_E_NONFINITE);
    assert_true(is_identity_m(&m));
    assert_int_equal(qo_mat3_from_quat_f32(qf(1, 0, 0, 0), NULL), QO_E_NULL);
    /* Huge and subnormal components normalise fine. */
    assert_int_equal(qo_mat3_from_quat_f32(qf(0, FLT_MAX, 0, 0), &m), QO_OK);
    assert_true(fabsf(m.m[0][0] - 1.0f) < 1e-6f && fabsf(m.m[1][1] + 1.0f) < 1e-6f &&
                fabsf(m.m[2][2] + 1.0f) < 1e-6f);
    assert_int_equal(qo_mat3_from_quat_f32(qf(0, 0, 0, 1e-42f), &m), QO_OK);
    assert_true(fabsf(m.m[2][2] - 1.0f) < 1e-6f && fabsf(m.m[0][0] + 1.0f) < 1e-6f);
}

/* ---- matrix -> quaternion ---- */

static void check_from_mat3(const char *name, int n, const qo_mat3_f32 *m, ref_quat expect)
{
    qo_quat_f32 q;
    qo_status st = qo_mat3_to_quat_f32(m, &q);
    double err;
    if (st != QO_OK) {
        print_mf("m", m);
        fail_msg("mat3_to_quat %s (case %d): status %d", name, n, (int)st);
    }
    err = ref_quat_angle_between(ref_quat_from_f32(q), expect);
    if (err > TOL_RAD || q.w < 0.0f || fabs(ref_quat_norm(ref_quat_from_f32(q)) - 1.0) > 1e-6) {
        print_mf("m", m);
        print_q("got", q);
        print_q("expected", ref_quat_to_f32(ref_quat_canonical(expect)));
        fail_msg("mat3_to_quat %s (case %d): error %.3g rad (w must be >= 0, |q| 1)", name, n,
                 err);
    }
}

/* The trusted variant: random rotations and the edge table (every pivot, 180 deg, tiny) against
 * the double quaternion; non-finite entries (diagonal and off-diagonal) and NULL refused with
 * the identity written; a non-rotation gives some unit quaternion, never NaN. */
static void test_f32_mat3_to_quat_trusted(void **state)
{
    ref_rng rng = { 37 };
    int n, i;
    size_t k;
    qo_quat_f32 q;
    qo_mat3_f32 m;
    (void)state;
    for (n = 0; n < N_F32 + (int)N_EDGES; n++) {
        ref_quat rq;
        double err;
        if (n < N_F32) {
            m = rand_rot_f32(&rng, &rq);
        } else {
            ref_mat3 r;
            rq = edge_quat((size_t)(n - N_F32));
            r = ref_quat_to_mat3(rq);
            m = ref_mat3_to_f32(&r);
        }
        assert_int_equal(qo_mat3_to_quat_trusted_f32(&m, &q), QO_OK);
        err = ref_quat_angle_between(ref_quat_from_f32(q), rq);
        if (err > TOL_RAD || q.w < 0.0f || fabs(ref_quat_norm(ref_quat_from_f32(q)) - 1.0) > 1e-6) {
            print_mf("m", &m);
            print_q("got", q);
            fail_msg("mat3_to_quat_trusted case %d: error %.3g rad (w >= 0, |q| 1)", n, err);
        }
    }
    for (k = 0; k < 9; k++) {
        float bad[3] = { NAN, INFINITY, -INFINITY };
        for (i = 0; i < 3; i++) {
            m = qo_mat3_identity_f32();
            m.m[k / 3][k % 3] = bad[i];
            q.w = 7.0f;
            if (qo_mat3_to_quat_trusted_f32(&m, &q) != QO_E_NONFINITE || !is_identity_q(q))
                fail_msg("trusted: entry %d = %g not refused", (int)k, (double)bad[i]);
        }
    }
    assert_int_equal(qo_mat3_to_quat_trusted_f32(NULL, &q), QO_E_NULL);
    assert_true(is_identity_q(q));
    assert_int_equal(qo_mat3_to_quat_trusted_f32(&m, NULL), QO_E_NULL);
    memset(&m, 0, sizeof m);
    m.m[0][0] = 2.0f; m.m[1][2] = -3.0f; /* not a rotation: some finite quaternion, w >= 0 */
    assert_int_equal(qo_mat3_to_quat_trusted_f32(&m, &q), QO_OK);
    assert_true(qo_quat_is_finite_f32(q) && q.w >= 0.0f);
}

/* The trusted variant off its domain and at its edge: rotations drifted by up to 1e-5 per entry
 * (max |M^T M - I| up to ~4e-5, within QO_MAT3_ROTATION_TOL_F32) stay near the nearest rotation
 * with |q| near 1 (the documented "off by e, |q| off 1 by about e"); any finite matrix, entries
 * of every magnitude up to FLT_MAX and both signs of zero, gives QO_OK with a finite q, w >= 0
 * (never NaN), or QO_E_NONFINITE with the identity (entries so large the formula overflows). */
static void test_f32_mat3_to_quat_trusted_domain(void **state)
{
    ref_rng rng = { 41 };
    int n, i, j, overflow = 0;
    double worst = 0.0, worst_norm = 0.0;
    (void)state;
    for (n = 0; n < N_F32; n++) {
        ref_quat rq;
        qo_mat3_f32 m = rand_rot_f32(&rng, &rq);
        ref_mat3 md, near;
        qo_quat_f32 q;
        double err, dn;
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) m.m[i][j] += (float)ref_rng_range(&rng, -1e-5, 1e-5);
        md = ref_mat3_from_f32(&m);
        near = ref_mat3_nearest_rotation(&md);
        assert_int_equal(qo_mat3_to_quat_trusted_f32(&m, &q), QO_OK);
        err = ref_quat_angle_between(ref_quat_from_f32(q), ref_mat3_to_quat(&near));
        dn = fabs(ref_quat_norm(ref_quat_from_f32(q)) - 1.0);
        if (err > worst) worst = err;
        if (dn > worst_norm) worst_norm = dn;
        if (err > 1e-4 || dn > 1e-4 || q.w < 0.0f) {
            print_mf("m", &m);
            print_q("got", q);
            fail_msg("trusted drift case %d: %.3g rad from the nearest rotation, |q| off 1 by %.3g",
                     n, err, dn);
        }
    }
    for (n = 0; n < 20 * N_F32; n++) {
        qo_mat3_f32 m;
        qo_quat_f32 q;
        qo_status st;
        for (i = 0; i < 3; i++) {
            for (j = 0; j < 3; j++) {
                uint64_t k = ref_rng_next(&rng);
                double mag = pow(10.0, ref_rng_range(&rng, -45.0, 38.5));
                m.m[i][j] = (k & 7u) == 0 ? ((k & 8u) ? -0.0f : 0.0f)
                                          : (float)((k & 16u) ? -mag : mag);
                if (!isfinite(m.m[i][j])) m.m[i][j] = (k & 16u) ? -FLT_MAX : FLT_MAX;
            }
        }
        q.w = NAN;
        st = qo_mat3_to_quat_trusted_f32(&m, &q);
        if (st == QO_E_NONFINITE && is_identity_q(q)) {
            overflow++;
            continue;
        }
        /* never the zero quaternion (it is no rotation at all): k stays > 0 however large c */
        if (st != QO_OK || !qo_quat_is_finite_f32(q) || !(q.w >= 0.0f) ||
            !(qo_quat_dot_f32(q, q) > 0.0f)) {
            print_mf("m", &m);
            print_q("got", q);
            fail_msg("trusted finite case %d: status %d", n, (int)st);
        }
    }
    /* both outcomes were reached */
    assert_true(overflow > 0 && overflow < 20 * N_F32);
    {
        /* Found by review: diag(1e38, 1e38, 0) made c + c overflow, k = 0 and q = 0 with QO_OK
         * (c is now clamped at FLT_MAX/2 for k); and a half turn whose w only underflows to 0
         * (a subnormal off-diagonal) came out (0, -1, 0, 0), not canonical: the sign is now
         * decided on q, so it takes the canonical path like qo_mat3_to_quat_f32. */
        qo_mat3_f32 m;
        qo_quat_f32 q, qc;
        memset(&m, 0, sizeof m);
        m.m[0][0] = 1e38f; m.m[1][1] = 1e38f;
        assert_int_equal(qo_mat3_to_quat_trusted_f32(&m, &q), QO_OK);
        assert_true(qo_quat_is_finite_f32(q) && q.w >= 0.0f && qo_quat_dot_f32(q, q) > 0.0f);
        m = qo_mat3_identity_f32();
        m.m[1][1] = -1.0f; m.m[2][2] = -1.0f; m.m[1][2] = 0x1p-149f;
        assert_int_equal(qo_mat3_to_quat_trusted_f32(&m, &q), QO_OK);
        assert_int_equal(qo_mat3_to_quat_f32(&m, &qc), QO_OK);
        if (!(q.w == 0.0f && q.x == 1.0f && q.y == 0.0f && q.z == 0.0f) ||
            memcmp(&q, &qc, sizeof q) != 0) {
            print_q("trusted", q);
            print_q("checked", qc);
            fail_msg("trusted: half turn about x with a subnormal entry is not (0, 1, 0, 0)");
        }
    }
    print_message("trusted: drift 1e-5 worst %.3g rad, |q| off 1 by %.3g; %d of %d random finite "
                  "matrices overflow\n", worst, worst_norm, overflow, 20 * N_F32);
}

static void test_f32_mat3_to_quat_edges(void **state)
{
    size_t k;
    int pivots[4] = { 0, 0, 0, 0 };
    (void)state;
    for (k = 0; k < N_EDGES; k++) {
        ref_quat rq = edge_quat(k);
        ref_mat3 rm = ref_quat_to_mat3(rq);
        qo_mat3_f32 m = ref_mat3_to_f32(&rm);
        float t = m.m[0][0] + m.m[1][1] + m.m[2][2];
        check_from_mat3(edges[k].name, (int)k, &m, rq);
        /* Record which pivot the table exercised (the largest of t, m00, m11, m22). */
        if (t >= m.m[0][0] && t >= m.m[1][1] && t >= m.m[2][2]) pivots[0]++;
        else if (m.m[0][0] >= m.m[1][1] && m.m[0][0] >= m.m[2][2]) pivots[1]++;
        else if (m.m[1][1] >= m.m[2][2]) pivots[2]++;
        else pivots[3]++;
    }
    for (k = 0; k < 4; k++)
        if (pivots[k] == 0) fail_msg("edge table misses pivot %d", (int)k);
    /* Exact 180-degree matrices: the canonical sign picks a positive first non-zero. */
    {
        qo_mat3_f32 m = mf(1, 0, 0, 0, -1, 0, 0, 0, -1);
        qo_quat_f32 q;
        assert_int_equal(qo_mat3_to_quat_f32(&m, &q), QO_OK);
        if (!(q.w == 0.0f && q.x == 1.0f && q.y == 0.0f && q.z == 0.0f)) {
            print_q("q", q);
            fail_msg("180 about x exact: expected (0,1,0,0)%s", "");
        }
        m = mf(-1, 0, 0, 0, -1, 0, 0, 0, 1);
        assert_int_equal(qo_mat3_to_quat_f32(&m, &q), QO_OK);
        if (!(q.w == 0.0f && q.x == 0.0f && q.y == 0.0f && q.z == 1.0f)) {
            print_q("q", q);
            fail_msg("180 about z exact: expected (0,0,0,1)%s", "");
        }
        /* 180 about (1,-1,0)/sqrt2: M = 2nn^T - I. */
        m = mf(0, -1, 0, -1, 0, 0, 0, 0, -1);
        assert_int_equal(qo_mat3_to_quat_f32(&m, &q), QO_OK);
        if (!(q.w == 0.0f && q.x > 0.0f && fabsf(q.x + q.y) < 1e-7f && q.z == 0.0f)) {
            print_q("q", q);
            fail_msg("180 about (1,-1,0) exact: expected (0, .707, -.707, 0)%s", "");
        }
    }
    /* Just off 180 degrees where w is tiny but non-zero: the result keeps w >= 0. */
    {
        ref_vec3 ax = { 0.3, -0.5, 0.8 };
        int s;
        for (s = -1; s <= 1; s += 2) {
            ref_quat rq = ref_quat_from_axis_angle(ax, REF_PI + s * 1e-5);
            ref_mat3 rm = ref_quat_to_mat3(rq);
            qo_mat3_f32 m = ref_mat3_to_f32(&rm);
            check_from_mat3("180 +- 1e-5", s, &m, rq);
        }
    }
}

static void test_f32_mat3_to_quat_non_rotations(void **state)
{
    struct { const char *name; qo_mat3_f32 m; qo_status st; } cases[13];
    qo_mat3_f32 r;
    size_t n = 0, k;
    int i, j;
    ref_rng rng = { 41 };
    (void)state;
    r = rand_rot_f32(&rng, NULL);
    cases[n].name = "scaled by 1.01"; cases[n].st = QO_E_NOT_ROTATION; cases[n].m = r;
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) cases[n].m.m[i][j] *= 1.01f;
    n++;
    cases[n].name = "scaled by 1.001"; cases[n].st = QO_E_NOT_ROTATION; cases[n].m = r;
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) cases[n].m.m[i][j] *= 1.001f;
    n++;
    cases[n].name = "sheared"; cases[n].st = QO_E_NOT_ROTATION;
    cases[n].m = mf(1, 0.01f, 0, 0, 1, 0, 0, 0, 1);
    n++;
    cases[n].name = "reflection diag(1,1,-1)"; cases[n].st = QO_E_NOT_ROTATION;
    cases[n].m = mf(1, 0, 0, 0, 1, 0, 0, 0, -1);
    n++;
    cases[n].name = "-I"; cases[n].st = QO_E_NOT_ROTATION;
    cases[n].m = mf(-1, 0, 0, 0, -1, 0, 0, 0, -1);
    n++;
    cases[n].name = "reflected random rotation"; cases[n].st = QO_E_NOT_ROTATION; cases[n].m = r;
    for (j = 0; j < 3; j++) cases[n].m.m[1][j] = -r.m[1][j];
    n++;
    cases[n].name = "zero"; cases[n].st = QO_E_NOT_ROTATION;
    cases[n].m = mf(0, 0, 0, 0, 0, 0, 0, 0, 0);
    n++;
    cases[n].name = "huge entries (M^T M overflows)"; cases[n].st = QO_E_NOT_ROTATION;
    cases[n].m = mf(1e30f, 0, 0, 0, 1e30f, 0, 0, 0, 1e30f);
    n++;
    cases[n].name = "NaN entry"; cases[n].st = QO_E_NONFINITE; cases[n].m = r;
    cases[n].m.m[2][1] = NAN;
    n++;
    cases[n].name = "Inf entry"; cases[n].st = QO_E_NONFINITE; cases[n].m = r;
    cases[n].m.m[0][0] = -INFINITY;
    n++;
    cases[n].name = "rank 2 projector"; cases[n].st = QO_E_NOT_ROTATION;
    cases[n].m = mf(1, 0, 0, 0, 1, 0, 0, 0, 0);
    n++;
    cases[n].name = "1e-5 off orthonormal (accepted)"; cases[n].st = QO_OK; cases[n].m = r;
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) cases[n].m.m[i][j] *= 1.0f + 1e-5f;
    n++;
    for (k = 0; k < n; k++) {
        qo_quat_f32 q = qf(9, 9, 9, 9);
        qo_status st = qo_mat3_to_quat_f32(&cases[k].m, &q);
        if (st != cases[k].st || (st != QO_OK && !is_identity_q(q))) {
            print_mf("m", &cases[k].m);
            print_q("out", q);
            fail_msg("mat3_to_quat %s: status %d, expected %d (out must be identity on error)",
                     cases[k].name, (int)st, (int)cases[k].st);
        }
    }
    {
        qo_quat_f32 q = qf(9, 9, 9, 9);
        assert_int_equal(qo_mat3_to_quat_f32(NULL, &q), QO_E_NULL);
        assert_true(is_identity_q(q));
        assert_int_equal(qo_mat3_to_quat_f32(&r, NULL), QO_E_NULL);
    }
}

/* Accepted but drifted matrices (max |M^T M - I| up to the 1e-4 tolerance) give the quaternion
 * of their NEAREST rotation, not whatever the direct formula lands on. */
static void test_f32_mat3_to_quat_drifted(void **state)
{
    static const double amp[] = { 1e-7, 3e-7, 1e-6, 1e-5, 3e-5 };
    ref_rng rng = { 45 };
    size_t a;
    int n, i, j;
    (void)state;
    for (a = 0; a < sizeof amp / sizeof amp[0]; a++) {
        for (n = 0; n < 400; n++) {
            qo_mat3_f32 m = rand_rot_f32(&rng, NULL);
            ref_mat3 md, near;
            for (i = 0; i < 3; i++)
                for (j = 0; j < 3; j++) m.m[i][j] += (float)ref_rng_range(&rng, -amp[a], amp[a]);
            md = ref_mat3_from_f32(&m);
            near = ref_mat3_nearest_rotation(&md);
            if (max_orth_error(&m) > 1e-4) continue; /* refused by contract, tested elsewhere */
            check_from_mat3("drifted", n, &m, ref_mat3_to_quat(&near));
        }
    }
}

/* Every conversion on the edge table, both signs of q: the rotation survives. */
static void test_f32_edges_all_conversions(void **state)
{
    size_t k;
    int sgn;
    (void)state;
    for (k = 0; k < N_EDGES; k++) {
        for (sgn = -1; sgn <= 1; sgn += 2) {
            ref_quat rq = rscale_q(edge_quat(k), sgn);
            qo_quat_f32 q = ref_quat_to_f32(rq), q2;
            ref_quat qd = ref_quat_from_f32(q);
            qo_mat3_f32 m;
            qo_vec3_f32 ax, rv;
            float ang;
            ref_mat3 rm = ref_quat_to_mat3(qd), mm;
            double e_m, e_aa, e_rv, e_back, th;
            ref_quat b_aa, b_rv = { 1.0, 0.0, 0.0, 0.0 };
            EXPECT_OK(qo_mat3_from_quat_f32(q, &m), k);
            mm = ref_mat3_from_f32(&m);
            e_m = ref_mat3_rotation_distance(&rm, &mm);
            EXPECT_OK(qo_axis_angle_from_quat_f32(q, &ax, &ang), k);
            b_aa = ref_quat_from_axis_angle(ref_vec3_from_f32(ax), ang);
            e_aa = ref_quat_angle_between(b_aa, qd);
            EXPECT_OK(qo_rotvec_from_quat_f32(q, &rv), k);
            th = sqrt((double)rv.x * rv.x + (double)rv.y * rv.y + (double)rv.z * rv.z);
            if (th > 0.0) b_rv = ref_quat_from_axis_angle(ref_vec3_from_f32(rv), th);
            e_rv = ref_quat_angle_between(b_rv, qd);
            EXPECT_OK(qo_rotvec_to_quat_f32(rv, &q2), k);
            e_back = ref_quat_angle_between(ref_quat_from_f32(q2), qd);
            if (e_m > TOL_RAD || e_aa > TOL_RAD || e_rv > TOL_RAD || e_back > TOL_RAD ||
                !(ang >= 0.0f && ang <= 3.14159274f) || th > REF_PI + 1e-6) {
                print_q("q", q);
                fail_msg("edge %s (sign %d): errors mat3 %.3g, axis-angle %.3g, rotvec %.3g, "
                         "rotvec->quat %.3g rad; angle %.9g, |rv| %.9g",
                         edges[k].name, sgn, e_m, e_aa, e_rv, e_back, ang, th);
            }
        }
    }
}

/* ---- orthonormalisation ---- */

static void check_ortho_tol(const char *name, int n, const qo_mat3_f32 *m, double tol)
{
    qo_mat3_f32 r;
    ref_mat3 rm = ref_mat3_from_f32(m), ref, got;
    qo_quat_f32 q;
    qo_status st = qo_mat3_orthonormalize_f32(m, &r);
    double err, qerr;
    if (st != QO_OK) {
        print_mf("m", m);
        fail_msg("orthonormalize %s (case %d): status %d", name, n, (int)st);
    }
    ref = ref_mat3_nearest_rotation(&rm);
    got = ref_mat3_from_f32(&r);
    err = ref_mat3_rotation_distance(&ref, &got);
    if (err > tol || max_orth_error(&r) > 1e-6 || qo_mat3_det_f32(&r) < 0.999f) {
        print_mf("m", m);
        print_mf("got", &r);
        fail_msg("orthonormalize %s (case %d): %.3g rad from the double polar factor, orth %.3g",
                 name, n, err, max_orth_error(&r));
    }
    /* The "caller asks for it" path lands on the same rotation. */
    st = qo_mat3_to_quat_ortho_f32(m, &q);
    qerr = ref_quat_angle_between(ref_quat_from_f32(q), ref_mat3_to_quat(&ref));
    if (st != QO_OK || qerr > tol || q.w < 0.0f)
        fail_msg("mat3_to_quat_ortho %s (case %d): status %d, error %.3g rad", name, n, (int)st,
                 qerr);
}

static void check_ortho(const char *name, int n, const qo_mat3_f32 *m)
{
    check_ortho_tol(name, n, m, TOL_RAD);
}

/* U diag(s1, s2, s3) V^T with random rotations U, V, rounded to float. */
static qo_mat3_f32 rand_svd_f32(ref_rng *rng, double s1, double s2, double s3)
{
    ref_quat u = ref_rng_quat(rng), v = ref_rng_quat(rng);
    ref_mat3 t = svd_of(u, v, s1, s2, s3);
    return ref_mat3_to_f32(&t);
}

/* orthonormalize over the float32 range: uniform scales 1e-30 to 1e30, strong stretches (the
 * noise, the refusals both formats hold and the exact rotation are test_orthonormalize) */
static void test_f32_orthonormalize_scaled(void **state)
{
    ref_rng rng = { 61 };
    int n, i, j;
    (void)state;
    /* Uniform scale (tiny, huge) and a strong anisotropic stretch. */
    for (n = 0; n < 200; n++) {
        qo_mat3_f32 m = rand_rot_f32(&rng, NULL), s;
        static const float sc[] = { 1e-30f, 1e-3f, 2.5f, 1e30f };
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) s.m[i][j] = m.m[i][j] * sc[n % 4];
        check_ortho("uniformly scaled", n, &s);
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) s.m[i][j] = m.m[i][j] * (j == 0 ? 30.0f : j == 1 ? 1.0f : 0.1f);
        check_ortho("stretched 30:1:0.1", n, &s);
    }
    /* Strongly stretched: singular values log-uniform in [1e-3, 1]. The nearest rotation is
     * itself sensitive here (moves by |dM|/(s2+s3)): the documented error bound is
     * ~4e-8 s1/(s2+s3); allow 3x that. */
    for (n = 0; n < 600; n++) {
        double s[3], t;
        qo_mat3_f32 m;
        for (i = 0; i < 3; i++) s[i] = pow(10.0, ref_rng_range(&rng, -3.0, 0.0));
        /* sort descending */
        if (s[0] < s[1]) { t = s[0]; s[0] = s[1]; s[1] = t; }
        if (s[1] < s[2]) { t = s[1]; s[1] = s[2]; s[2] = t; }
        if (s[0] < s[1]) { t = s[0]; s[0] = s[1]; s[1] = t; }
        m = rand_svd_f32(&rng, s[0], s[1], s[2]);
        check_ortho_tol("stretched U diag(s) V^T", n, &m, 5e-7 + 1.2e-7 * s[0] / (s[1] + s[2]));
    }
}

/* refusals beyond the Q1.30 range: rank 1 with entries to 9, condition 1e4, NaN, Inf, NULL
 * (the refusals both formats hold are test_orthonormalize) */
static void test_f32_orthonormalize_rejects(void **state)
{
    struct { const char *name; qo_mat3_f32 m; qo_status st; } cases[4];
    size_t n = 0, k;
    ref_rng rng = { 71 };
    qo_mat3_f32 r = rand_rot_f32(&rng, NULL);
    (void)state;
    cases[n].name = "rank 1"; cases[n].st = QO_E_NOT_ROTATION;
    cases[n].m = mf(1, 2, 3, 2, 4, 6, 3, 6, 9); n++;
    cases[n].name = "U diag(100, 1, 0.01) V^T (condition 1e4)"; cases[n].st = QO_E_NOT_ROTATION;
    cases[n].m = rand_svd_f32(&rng, 100.0, 1.0, 0.01); n++;
    cases[n].name = "NaN"; cases[n].st = QO_E_NONFINITE;
    cases[n].m = mf(1, 0, 0, 0, NAN, 0, 0, 0, 1); n++;
    cases[n].name = "Inf"; cases[n].st = QO_E_NONFINITE;
    cases[n].m = mf(1, 0, 0, 0, 1, 0, INFINITY, 0, 1); n++;
    for (k = 0; k < n; k++) {
        qo_mat3_f32 out = mf(9, 9, 9, 9, 9, 9, 9, 9, 9);
        qo_quat_f32 q = qf(9, 9, 9, 9);
        qo_status st = qo_mat3_orthonormalize_f32(&cases[k].m, &out);
        qo_status st2 = qo_mat3_to_quat_ortho_f32(&cases[k].m, &q);
        if (st != cases[k].st || !is_identity_m(&out) || st2 != cases[k].st || !is_identity_q(q)) {
            print_mf("m", &cases[k].m);
            fail_msg("orthonormalize %s: status %d / %d, expected %d, outputs must be identity",
                     cases[k].name, (int)st, (int)st2, (int)cases[k].st);
        }
    }
    {
        qo_mat3_f32 out = mf(9, 9, 9, 9, 9, 9, 9, 9, 9);
        qo_quat_f32 q = qf(9, 9, 9, 9);
        assert_int_equal(qo_mat3_orthonormalize_f32(NULL, &out), QO_E_NULL);
        assert_true(is_identity_m(&out));
        assert_int_equal(qo_mat3_orthonormalize_f32(&r, NULL), QO_E_NULL);
        assert_int_equal(qo_mat3_to_quat_ortho_f32(NULL, &q), QO_E_NULL);
        assert_true(is_identity_q(q));
        assert_int_equal(qo_mat3_to_quat_ortho_f32(&r, NULL), QO_E_NULL);
    }
}

/* ---- axis-angle ---- */

static void test_f32_axis_angle_from_edges(void **state)
{
    qo_quat_f32 q;
    (void)state;
    q = qf(9, 9, 9, 9);
    assert_int_equal(qo_axis_angle_to_quat_f32(vf(0, 0, 0), 1.0f, &q), QO_E_DEGENERATE);
    assert_true(is_identity_q(q));
    q = qf(9, 9, 9, 9);
    assert_int_equal(qo_axis_angle_to_quat_f32(vf(0, 0, 0), 0.0f, &q), QO_E_DEGENERATE);
    assert_true(is_identity_q(q));
    q = qf(9, 9, 9, 9);
    assert_int_equal(qo_axis_angle_to_quat_f32(vf(NAN, 0, 1), 1.0f, &q), QO_E_NONFINITE);
    assert_true(is_identity_q(q));
    q = qf(9, 9, 9, 9);
    assert_int_equal(qo_axis_angle_to_quat_f32(vf(0, 0, 1), INFINITY, &q), QO_E_NONFINITE);
    assert_true(is_identity_q(q));
    q = qf(9, 9, 9, 9);
    assert_int_equal(qo_axis_angle_to_quat_f32(vf(0, 0, 1), NAN, &q), QO_E_NONFINITE);
    assert_true(is_identity_q(q));
    assert_int_equal(qo_axis_angle_to_quat_f32(vf(0, 0, 1), 1.0f, NULL), QO_E_NULL);
    /* Components at FLT_MAX and subnormal: the axis length must not overflow / underflow. */
    assert_int_equal(qo_axis_angle_to_quat_f32(vf(FLT_MAX, FLT_MAX, 0), 2.0f, &q), QO_OK);
    assert_true(fabsf(q.x - 0.70710678f * sinf(1.0f)) < 1e-6f && fabsf(q.x - q.y) < 1e-7f &&
                q.z == 0.0f && fabsf(q.w - cosf(1.0f)) < 1e-6f);
    assert_int_equal(qo_axis_angle_to_quat_f32(vf(0, 0, -1e-44f), 1.0f, &q), QO_OK);
    assert_true(fabsf(q.z + sinf(0.5f)) < 1e-6f && q.x == 0.0f && q.y == 0.0f);
    /* Angle 0 about a valid axis is the identity rotation (w = 1, vector 0). */
    assert_int_equal(qo_axis_angle_to_quat_f32(vf(1, 2, 3), 0.0f, &q), QO_OK);
    assert_true(q.w == 1.0f && q.x == 0.0f && q.y == 0.0f && q.z == 0.0f);
}

static void test_f32_axis_angle_to_edges(void **state)
{
    qo_vec3_f32 ax;
    float ang;
    (void)state;
    assert_int_equal(qo_axis_angle_from_quat_f32(qf(1, 0, 0, 0), &ax, &ang), QO_OK);
    assert_true(ax.x == 1.0f && ax.y == 0.0f && ax.z == 0.0f && ang == 0.0f);
    assert_int_equal(qo_axis_angle_from_quat_f32(qf(-2, 0, 0, 0), &ax, &ang), QO_OK);
    assert_true(ax.x == 1.0f && ax.y == 0.0f && ax.z == 0.0f && ang == 0.0f);
    /* Exactly pi: q and -q both give the canonical axis. */
    assert_int_equal(qo_axis_angle_from_quat_f32(qf(0, 0, -1, 0), &ax, &ang), QO_OK);
    assert_true(ax.x == 0.0f && ax.y == 1.0f && ax.z == 0.0f);
    assert_true(fabs(ang - REF_PI) < 1e-6);
    assert_int_equal(qo_axis_angle_from_quat_f32(qf(-1e-8f, 0.6f, 0, -0.8f), &ax, &ang), QO_OK);
    assert_true(fabsf(ax.x + 0.6f) < 1e-6f && fabsf(ax.z - 0.8f) < 1e-6f);
    assert_true(fabs(ang - REF_PI) < 1e-6 && ang <= 3.14159274f);
    /* Tiny angle: full relative precision (no acos). */
    assert_int_equal(qo_axis_angle_from_quat_f32(qf(1, 0, 0, 1e-20f), &ax, &ang), QO_OK);
    assert_true(fabsf(ang - 2e-20f) < 1e-26f && ax.z == 1.0f);
    /* Errors: documented outputs. */
    ax = vf(9, 9, 9); ang = 9;
    assert_int_equal(qo_axis_angle_from_quat_f32(qf(0, 0, 0, 0), &ax, &ang), QO_E_DEGENERATE);
    assert_true(ax.x == 1.0f && ax.y == 0.0f && ax.z == 0.0f && ang == 0.0f);
    ax = vf(9, 9, 9); ang = 9;
    assert_int_equal(qo_axis_angle_from_quat_f32(qf(1, NAN, 0, 0), &ax, &ang), QO_E_NONFINITE);
    assert_true(ax.x == 1.0f && ax.y == 0.0f && ax.z == 0.0f && ang == 0.0f);
    ang = 9;
    assert_int_equal(qo_axis_angle_from_quat_f32(qf(1, 0, 0, 0), NULL, &ang), QO_E_NULL);
    assert_true(ang == 0.0f);
    ax = vf(9, 9, 9);
    assert_int_equal(qo_axis_angle_from_quat_f32(qf(1, 0, 0, 0), &ax, NULL), QO_E_NULL);
    assert_true(ax.x == 1.0f && ax.y == 0.0f && ax.z == 0.0f);
}

/* ---- rotation vector ---- */

static void test_f32_rotvec_edges(void **state)
{
    qo_quat_f32 q;
    qo_vec3_f32 v;
    (void)state;
    /* Zero -> identity, OK. Tiny vectors are exact: (1, rv/2). */
    assert_int_equal(qo_rotvec_to_quat_f32(vf(0, 0, 0), &q), QO_OK);
    assert_true(is_identity_q(q));
    assert_int_equal(qo_rotvec_to_quat_f32(vf(1e-20f, -3e-20f, 2e-38f), &q), QO_OK);
    assert_true(q.w == 1.0f && q.x == 0.5e-20f && q.y == -1.5e-20f && q.z == 1e-38f);
    assert_int_equal(qo_rotvec_to_quat_f32(vf(0, 0x1p-147f, 0), &q), QO_OK);
    assert_true(q.w == 1.0f && q.y == 0x1p-148f);
    /* Around the Taylor switch (|rv| = 0.02): both sides agree with the closed form. */
    {
        static const float th[] = { 0.0199999f, 0.02f, 0.0200001f, 1e-4f, 0.5f };
        size_t k;
        for (k = 0; k < sizeof th / sizeof th[0]; k++) {
            qo_vec3_f32 rv = vf(0.6f * th[k], 0, 0.8f * th[k]);
            ref_vec3 a = ref_vec3_from_f32(rv);
            ref_quat e = ref_quat_from_axis_angle(a, sqrt(a.x * a.x + a.z * a.z));
            assert_int_equal(qo_rotvec_to_quat_f32(rv, &q), QO_OK);
            if (fabs(q.w - e.w) > 6e-8 || fabs(q.x - e.x) > 3e-8 || fabs(q.z - e.z) > 3e-8 ||
                q.y != 0.0f)
                fail_msg("from_rotvec |rv| = %.9g: (%.9g %.9g %.9g) vs (%.9g %.9g %.9g)", th[k],
                         q.w, q.x, q.z, e.w, e.x, e.z);
        }
    }
    q = qf(9, 9, 9, 9);
    assert_int_equal(qo_rotvec_to_quat_f32(vf(NAN, 0, 0), &q), QO_E_NONFINITE);
    assert_true(is_identity_q(q));
    q = qf(9, 9, 9, 9);
    assert_int_equal(qo_rotvec_to_quat_f32(vf(0, INFINITY, 0), &q), QO_E_NONFINITE);
    assert_true(is_identity_q(q));
    q = qf(9, 9, 9, 9);
    assert_int_equal(qo_rotvec_to_quat_f32(vf(FLT_MAX, FLT_MAX, 0), &q), QO_E_RANGE);
    assert_true(is_identity_q(q));
    assert_int_equal(qo_rotvec_to_quat_f32(vf(1, 0, 0), NULL), QO_E_NULL);

    /* to_rotvec: identity, tiny (and subnormal) with full relative precision, pi both signs. */
    assert_int_equal(qo_rotvec_from_quat_f32(qf(1, 0, 0, 0), &v), QO_OK);
    assert_true(v.x == 0.0f && v.y == 0.0f && v.z == 0.0f);
    assert_int_equal(qo_rotvec_from_quat_f32(qf(1, 1e-30f, 0, -2e-30f), &v), QO_OK);
    assert_true(fabsf(v.x - 2e-30f) <= 2e-37f && fabsf(v.z + 4e-30f) <= 4e-37f && v.y == 0.0f);
    assert_int_equal(qo_rotvec_from_quat_f32(qf(-1, 0, 0x1p-133f, 0), &v), QO_OK);
    assert_true(v.y == -0x1p-132f && v.x == 0.0f && v.z == 0.0f);
    assert_int_equal(qo_rotvec_from_quat_f32(qf(0, 0, 0, -1), &v), QO_OK);
    assert_true(v.x == 0.0f && v.y == 0.0f && fabs(v.z - REF_PI) < 1e-6);
    assert_int_equal(qo_rotvec_from_quat_f32(qf(-1e-7f, 0, 1, 0), &v), QO_OK);
    assert_true(v.y < 0.0f && fabs(-v.y - (REF_PI - 2e-7)) < 1e-6);
    /* Around the series switch (|v| = 1e-3): relative precision on both sides. */
    {
        static const struct { float vn; double rel; } t[] = {
            { 1e-4f, 1.5e-7 }, { 5e-4f, 1.5e-7 }, { 9.99e-4f, 1.5e-7 }, { 1.001e-3f, 4e-7 },
            { 1e-2f, 4e-7 },
        };
        size_t k;
        for (k = 0; k < sizeof t / sizeof t[0]; k++) {
            qo_quat_f32 qq = qf(sqrtf(1.0f - t[k].vn * t[k].vn), 0.6f * t[k].vn, 0, -0.8f * t[k].vn);
            ref_vec3 e = ref_rotvec(ref_quat_from_f32(qq));
            double en = sqrt(e.x * e.x + e.z * e.z);
            assert_int_equal(qo_rotvec_from_quat_f32(qq, &v), QO_OK);
            if (fabs(v.x - e.x) > t[k].rel * en || fabs(v.z - e.z) > t[k].rel * en || v.y != 0.0f)
                fail_msg("to_rotvec |v| = %g: (%.9g %.9g) vs (%.9g %.9g)", t[k].vn, v.x, v.z, e.x,
                         e.z);
        }
    }
    v = vf(9, 9, 9);
    assert_int_equal(qo_rotvec_from_quat_f32(qf(0, 0, 0, 0), &v), QO_E_DEGENERATE);
    assert_true(v.x == 0.0f && v.y == 0.0f && v.z == 0.0f);
    v = vf(9, 9, 9);
    assert_int_equal(qo_rotvec_from_quat_f32(qf(1, 0, NAN, 0), &v), QO_E_NONFINITE);
    assert_true(v.x == 0.0f && v.y == 0.0f && v.z == 0.0f);
    assert_int_equal(qo_rotvec_from_quat_f32(qf(1, 0, 0, 0), NULL), QO_E_NULL);
}

/* ==== Q1.30 only: qorient/convert_fx.h ===================================== */

#define TWO30 1073741824.0

#define XFMT "(%ld %ld %ld %ld)"
#define XARG(q) (long)(q).w, (long)(q).x, (long)(q).y, (long)(q).z

/* axis-angle at the ends of the format: NULL outputs, a 1-LSB axis, -77 LSB and pi to the
 * LSB (the rounding is test_axis_angle, both cores) */
static void test_q30_axis_angle_edges(void **state)
{
    qo_quat_q30 r;
    qo_vec3_q30 ax;
    qo_q28 an;
    (void)state;
    /* Edges: zero axis, NULLs, identity, zero vector part, zero quaternion, exactly pi. */
    assert_int_equal(qo_axis_angle_to_quat_q30((qo_vec3_q30){ 0, 0, 0 }, QO_Q28_ONE, &r), QO_E_DEGENERATE);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
    assert_int_equal(qo_axis_angle_to_quat_q30((qo_vec3_q30){ 1, 0, 0 }, 0, NULL), QO_E_NULL);
    assert_int_equal(qo_axis_angle_from_quat_q30(qo_quat_identity_q30(), &ax, &an), QO_OK);
    assert_int_equal(ax.x, QO_Q30_ONE); assert_int_equal(ax.y, 0); assert_int_equal(ax.z, 0); assert_int_equal(an, 0);
    assert_int_equal(qo_axis_angle_from_quat_q30((qo_quat_q30){ -77, 0, 0, 0 }, &ax, &an), QO_OK);
    assert_int_equal(ax.x, QO_Q30_ONE); assert_int_equal(an, 0);
    assert_int_equal(qo_axis_angle_from_quat_q30((qo_quat_q30){ 0, 0, 0, 0 }, &ax, &an), QO_E_DEGENERATE);
    assert_int_equal(ax.x, QO_Q30_ONE); assert_int_equal(an, 0);
    an = 99;
    assert_int_equal(qo_axis_angle_from_quat_q30(qo_quat_identity_q30(), NULL, &an), QO_E_NULL);
    assert_int_equal(an, 0);
    assert_int_equal(qo_axis_angle_from_quat_q30((qo_quat_q30){ 0, 0, -QO_Q30_ONE, 0 }, &ax, &an), QO_OK);
    assert_int_equal(ax.y, QO_Q30_ONE);   /* canonical sign at pi */
    assert_true(an >= QO_Q28_PI - 2 && an <= QO_Q28_PI);
    /* A 1-LSB axis keeps its direction. */
    assert_int_equal(qo_axis_angle_to_quat_q30((qo_vec3_q30){ 0, -1, 0 }, QO_Q28_PI, &r), QO_OK);
    assert_true(r.y <= -QO_Q30_ONE + 1 && r.x == 0 && r.z == 0 && r.w >= -1 && r.w <= 1);
}

/* rotation vectors at the ends of the format: NULL, a 4-LSB vector to the LSB, INT32_MIN
 * components, -1, pi to the LSB (the rounding is test_rotvec, both cores) */
static void test_q30_rotvec_edges(void **state)
{
    qo_quat_q30 r;
    qo_vec3_q28 v;
    (void)state;
    assert_int_equal(qo_rotvec_to_quat_q30((qo_vec3_q28){ 0, 0, 0 }, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0); assert_int_equal(r.y, 0); assert_int_equal(r.z, 0);
    assert_int_equal(qo_rotvec_to_quat_q30((qo_vec3_q28){ 0, 0, 0 }, NULL), QO_E_NULL);
    /* Tiny: (1, rv/2) to the LSB. rv = 4 LSB of Q3.28 = 16 LSB of Q1.30 -> 8. */
    assert_int_equal(qo_rotvec_to_quat_q30((qo_vec3_q28){ 0, 0, 4 }, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.z, 8);
    /* The largest rotation vector the format holds does not overflow anything. */
    assert_int_equal(qo_rotvec_to_quat_q30((qo_vec3_q28){ INT32_MIN, INT32_MIN, INT32_MIN }, &r), QO_OK);
    assert_int_equal(qo_rotvec_from_quat_q30((qo_quat_q30){ 0, 0, 0, 0 }, &v), QO_E_DEGENERATE);
    assert_int_equal(v.x, 0); assert_int_equal(v.y, 0); assert_int_equal(v.z, 0);
    assert_int_equal(qo_rotvec_from_quat_q30(qo_quat_identity_q30(), NULL), QO_E_NULL);
    assert_int_equal(qo_rotvec_from_quat_q30((qo_quat_q30){ -QO_Q30_ONE, 0, 0, 0 }, &v), QO_OK);
    assert_int_equal(v.x, 0);
    /* Exactly pi about -z: canonical sign makes it +z. */
    assert_int_equal(qo_rotvec_from_quat_q30((qo_quat_q30){ 0, 0, 0, -QO_Q30_ONE }, &v), QO_OK);
    assert_true(v.z >= QO_Q28_PI - 2 && v.z <= QO_Q28_PI && v.x == 0 && v.y == 0);
}

/* to_mat3 and mat3_mul_vec3 at the ends of the format: zero, NULL, saturation (the rounding is
 * test_mat3_quat, both cores) */
static void test_q30_mat3_from_quat_edges(void **state)
{
    qo_mat3_q30 m;
    qo_vec3_q30 r;
    int i, j;
    (void)state;
    assert_int_equal(qo_mat3_from_quat_q30((qo_quat_q30){ 0, 0, 0, 0 }, &m), QO_E_DEGENERATE);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) assert_int_equal(m.m[i][j], i == j ? QO_Q30_ONE : 0);
    assert_int_equal(qo_mat3_from_quat_q30(qo_quat_identity_q30(), NULL), QO_E_NULL);
    r = qo_mat3_mul_vec3_q30(NULL, (qo_vec3_q30){ 1, 2, 3 });
    assert_int_equal(r.x, 0); assert_int_equal(r.y, 0); assert_int_equal(r.z, 0);
    /* Saturation of M v: (2, 2, 2) . (2, 2, 2) = 12. */
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) m.m[i][j] = INT32_MIN;
    r = qo_mat3_mul_vec3_q30(&m, (qo_vec3_q30){ INT32_MIN, INT32_MIN, INT32_MIN });
    assert_int_equal(r.x, INT32_MAX);
}

static void x_check_from_mat3(const qo_mat3_q30 *m, const char *what)
{
    double d[3][3], e;
    int i, j;
    qo_quat_q30 r;
    dq want;
    qo_status st = qo_mat3_to_quat_q30(m, &r);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) d[i][j] = m->m[i][j] / TWO30;
    want = dq_from_mat(d);
    if (st != QO_OK) fail_msg("mat3_to_quat %s: status %d", what, st);
    if (r.w < 0) fail_msg("mat3_to_quat %s: not canonical " XFMT, what, XARG(r));
    e = ref_quat_err_lsb_q30(r, want);
    /* At w == 0 (exact half turns) both signs are canonical candidates: compare either. */
    if (e > 3.0) {
        dq nw = { -want.w, -want.x, -want.y, -want.z };
        if (!(fabs(want.w) < 1e-8 && ref_quat_err_lsb_q30(r, nw) <= 3.0)) fail_msg("mat3_to_quat %s = " XFMT ": %.3f LSB", what, XARG(r), e);
    }
}

/* from_mat3 at the edges: exact half turns (either sign at w == 0), NULL, reflection, scale,
 * shear, zero, INT32_MIN, the tolerance just inside and outside (random rotations: test_mat3_quat,
 * both cores) */
static void test_q30_mat3_to_quat_edges(void **state)
{
    static const double half_turns[][4] = {
        { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 }, { 0, 0.70710678118654752, 0.70710678118654752, 0 },
        { 0, 0.57735026918962576, -0.57735026918962576, 0.57735026918962576 }, { 1, 0, 0, 0 },
        { 0.70710678118654752, 0.70710678118654752, 0, 0 }, { 1e-4, 0, 0.99999999500000, 0 },
    };
    qo_mat3_q30 m, bad;
    qo_quat_q30 r;
    double d[3][3];
    size_t c;
    int i, j;
    (void)state;
    assert_int_equal(qo_mat3_to_quat_q30(NULL, &r), QO_E_NULL);
    assert_int_equal(r.w, QO_Q30_ONE);
    assert_int_equal(qo_mat3_to_quat_q30(&m, NULL), QO_E_NULL);
    for (c = 0; c < sizeof half_turns / sizeof half_turns[0]; c++) {
        dq q = ref_quat_normalize((dq){ half_turns[c][0], half_turns[c][1], half_turns[c][2], half_turns[c][3] });
        qo_mat3_f32 f;
        dq_to_mat(q, d);
        for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) f.m[i][j] = (float)d[i][j];
        m = qo_q30_mat3_from_f32(&f);
        x_check_from_mat3(&m, "edge");
    }
    /* Rejections: reflection, scale, shear, singular, and a just-inside / just-outside pair. */
    dq_to_mat(ref_quat_normalize((dq){ 0.3, 0.5, -0.2, 0.7 }), d);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) m.m[i][j] = qo_q30_from_f32((float)d[i][j]);
    bad = m;
    for (j = 0; j < 3; j++) bad.m[0][j] = -bad.m[0][j];
    assert_int_equal(qo_mat3_to_quat_q30(&bad, &r), QO_E_NOT_ROTATION);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
    bad = m;
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) bad.m[i][j] = qo_fx_mul_q30(bad.m[i][j], QO_Q30_ONE + QO_Q30_ONE / 1000);
    assert_int_equal(qo_mat3_to_quat_q30(&bad, &r), QO_E_NOT_ROTATION);
    bad = m; bad.m[0][1] += QO_Q30_ONE / 100;
    assert_int_equal(qo_mat3_to_quat_q30(&bad, &r), QO_E_NOT_ROTATION);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) bad.m[i][j] = 0;
    assert_int_equal(qo_mat3_to_quat_q30(&bad, &r), QO_E_NOT_ROTATION);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) bad.m[i][j] = INT32_MIN;
    assert_int_equal(qo_mat3_to_quat_q30(&bad, &r), QO_E_NOT_ROTATION);
    /* Identity scaled so the diagonal of M^T M is 1 + 0.9 tol (accepted) or 1 + 1.1 tol. */
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) bad.m[i][j] = 0;
    for (i = 0; i < 3; i++) bad.m[i][i] = QO_Q30_ONE + (QO_MAT3_ROTATION_TOL_Q30 * 9) / 20;
    assert_int_equal(qo_mat3_to_quat_q30(&bad, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE);
    for (i = 0; i < 3; i++) bad.m[i][i] = QO_Q30_ONE + (QO_MAT3_ROTATION_TOL_Q30 * 11) / 20;
    assert_int_equal(qo_mat3_to_quat_q30(&bad, &r), QO_E_NOT_ROTATION);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        BOTH(test_axis_angle),
        BOTH(test_rotvec),
        BOTH(test_mat3_quat),
        BOTH(test_mat3_ops),
        BOTH(test_orthonormalize),
        BOTH(test_round_trips),
        cmocka_unit_test(test_f32_mat3_from_quat_errors),
        cmocka_unit_test(test_f32_mat3_to_quat_edges),
        cmocka_unit_test(test_f32_mat3_to_quat_trusted),
        cmocka_unit_test(test_f32_mat3_to_quat_trusted_domain),
        cmocka_unit_test(test_f32_mat3_to_quat_non_rotations),
        cmocka_unit_test(test_f32_mat3_to_quat_drifted),
        cmocka_unit_test(test_f32_edges_all_conversions),
        cmocka_unit_test(test_f32_orthonormalize_scaled),
        cmocka_unit_test(test_f32_orthonormalize_rejects),
        cmocka_unit_test(test_f32_axis_angle_from_edges),
        cmocka_unit_test(test_f32_axis_angle_to_edges),
        cmocka_unit_test(test_f32_rotvec_edges),
        cmocka_unit_test(test_q30_axis_angle_edges),
        cmocka_unit_test(test_q30_rotvec_edges),
        cmocka_unit_test(test_q30_mat3_from_quat_edges),
        cmocka_unit_test(test_q30_mat3_to_quat_edges),
    };
    return cmocka_run_group_tests_name("convert", tests, NULL, NULL);
}
