/*
 * tests/common/dq_interp.h - the double-precision interpolation references (textbook slerp,
 * Shoemake spline controls, de Casteljau on the sphere, log/exp) and the fixed-seed PRNG that
 * the interpolation tests and accuracy programs (tests/core/test_interp*.c,
 * bench/accuracy_interp*.c) share. Built on common/dq.h (common/ref.c); independent of the
 * library. Static inline: each user takes what it needs; the PRNG state is per file.
 *
 * Index:
 *   rng_state, rng_seed, rng_next, rng_u, rng_range   splitmix64 (ref_splitmix64), this file's state
 *   rand_unit, rand_axis_rot                          random unit quaternion (rejection from the
 *                                                     ball), rotation by a given angle about a
 *                                                     random axis
 *   rot_err, dist4                                    rotation angle between two orientations
 *                                                     (any norm), 4-D distance
 *   d_slerp_raw, d_slerp_unit                         textbook slerp, no flip; the same normalised
 *   d_spline_controls, d_bez                          Shoemake C1 inner controls; Bezier on the sphere
 *   dq_log, dq_exp                                    log of a unit quaternion, exp of a pure one
 *   d_squad_controls                                  Squad inner points from log/exp
 *   fx_from_d, x_from, dq_from_x, dq_from_f           the float / Q1.30 boundary written in the
 *                                                     test (not fxconv.h): round to nearest,
 *                                                     saturate; exact values back
 */
#ifndef QORIENT_TESTS_DQ_INTERP_H
#define QORIENT_TESTS_DQ_INTERP_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "common/dq.h"

static uint64_t rng_state;
static inline void rng_seed(uint64_t s) { rng_state = s; }
static inline uint64_t rng_next(void) { return ref_splitmix64(&rng_state); }
/* uniform in [0, 1) */
static inline double rng_u(void) { return ref_unit_from_bits(rng_next()); }
static inline double rng_range(double lo, double hi) { return lo + (hi - lo) * rng_u(); }

/* rotation angle (sign-free) between the orientations of a and b, any norm */
static inline double rot_err(dq a, dq b)
{
    dq d = dq_mul(dq_conj(dq_unit(a)), dq_unit(b));
    return 2.0 * atan2(sqrt(d.x * d.x + d.y * d.y + d.z * d.z), fabs(d.w));
}
static inline double dist4(dq a, dq b) { return dq_norm(dq_add(a, dq_neg(b))); }

/* Uniform direction in 4-D by rejection from the ball (norms in [1e-2, 1]), normalised. */
static inline dq rand_unit(void)
{
    dq q;
    double n;
    do {
        q.w = rng_range(-1, 1); q.x = rng_range(-1, 1);
        q.y = rng_range(-1, 1); q.z = rng_range(-1, 1);
        n = dq_norm(q);
    } while (n > 1.0 || n < 1e-2);
    return dq_scale(q, 1.0 / n);
}
static inline dq rand_axis_rot(double ang)
{
    dq a = rand_unit();
    return dq_axis_angle(a.x, a.y, a.z + 1e-3, ang);
}

/* Textbook slerp: sin((1-u)th)/sin th p + sin(u th)/sin th q, th = acos(p.q), no flip. */
static inline dq d_slerp_raw(dq p, dq q, double u)
{
    double c = dq_dot(p, q), th, wa, wb;
    if (c > 1) c = 1;
    if (c < -1) c = -1;
    th = acos(c);
    if (th < 1e-12) { wa = 1 - u; wb = u; }
    else { wa = sin((1 - u) * th) / sin(th); wb = sin(u * th) / sin(th); }
    return dq_add(dq_scale(p, wa), dq_scale(q, wb));
}
static inline dq d_slerp_unit(dq p, dq q, double u) { return dq_unit(d_slerp_raw(p, q, u)); }

/* Shoemake's C1 inner control points a_i, b_i of aligned unit keys q[0..n-1], n >= 2 (the
 * construction interp.h documents, written from its formulas with the textbook slerp). */
static inline void d_spline_controls(const dq *q, size_t n, dq *a, dq *b)
{
    size_t i;
    if (n == 2) {
        a[0] = d_slerp_unit(q[0], q[1], 1.0 / 3);
        b[1] = d_slerp_unit(q[0], q[1], 2.0 / 3);
        return;
    }
    a[0] = d_slerp_unit(q[0], d_slerp_unit(q[2], q[1], 2.0), 1.0 / 3);
    b[n - 1] = d_slerp_unit(q[n - 1], d_slerp_unit(q[n - 3], q[n - 2], 2.0), 1.0 / 3);
    for (i = 1; i + 1 < n; i++) {
        dq dbl = d_slerp_unit(q[i - 1], q[i], 2.0);
        dq abar = d_slerp_unit(dbl, q[i + 1], 0.5);
        a[i] = d_slerp_unit(q[i], abar, 1.0 / 3);
        b[i] = d_slerp_unit(q[i], abar, -1.0 / 3);
    }
}
/* Bezier curve on the sphere through the n control points p (overwritten), de Casteljau. */
static inline dq d_bez(dq *p, size_t n, double t)
{
    size_t lev, i;
    for (lev = n - 1; lev > 0; lev--)
        for (i = 0; i < lev; i++) p[i] = d_slerp_unit(p[i], p[i + 1], t);
    return p[0];
}

/* log of a unit quaternion: (0, angle/2 * axis) */
static inline dq dq_log(dq q)
{
    double vn = sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
    dq r = { 0, 0, 0, 0 };
    if (vn > 0) {
        double k = atan2(vn, q.w) / vn;
        r.x = q.x * k; r.y = q.y * k; r.z = q.z * k;
    }
    return r;
}
/* exp of a pure quaternion p = (0, v): (cos |v|, sin |v| v/|v|) */
static inline dq dq_exp(dq p)
{
    double vn = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    double k = (vn > 0) ? sin(vn) / vn : 1.0;
    dq r = { cos(vn), p.x * k, p.y * k, p.z * k };
    return r;
}

/* Squad inner points s_i = q_i exp(-(log(q_i^-1 q_(i+1)) + log(q_i^-1 q_(i-1))) / 4), ends = keys. */
static inline void d_squad_controls(const dq *q, size_t n, dq *s)
{
    size_t i;
    s[0] = q[0];
    s[n - 1] = q[n - 1];
    for (i = 1; i + 1 < n; i++) {
        dq qi = dq_conj(q[i]);
        dq l1 = dq_log(dq_mul(qi, q[i + 1])), l2 = dq_log(dq_mul(qi, q[i - 1]));
        s[i] = dq_mul(q[i], dq_exp(dq_scale(dq_add(l1, l2), -0.25)));
    }
}

/* The float / Q1.30 boundary, written here (not fxconv.h): round to nearest, saturate. */
static inline int32_t fx_from_d(double v, double scale) { return ref_to_fixed(v, scale); }
static inline qo_quat_q30 x_from(dq q) { return ref_quat_to_q30(q); }
static inline dq dq_from_x(qo_quat_q30 q) { return ref_quat_from_q30(q); }
static inline dq dq_from_f(qo_quat_f32 q) { return ref_quat_from_f32(q); }

#endif
