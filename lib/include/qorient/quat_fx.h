/* parity fixed (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   quat.identity        qo_quat_identity_q30
 *   quat.conj            qo_quat_conj_q30
 *   quat.dot             qo_quat_dot_q30
 *   quat.norm            qo_quat_norm_q30
 *   quat.normalize       qo_quat_normalize_q30
 *   quat.normalize_fast  qo_quat_normalize_fast_q30 (within 16 LSB, no division: Cortex-M0)
 *   quat.canonical       qo_quat_canonical_q30
 *   quat.inverse         qo_quat_inverse_q30
 *   quat.mul             qo_quat_mul_q30
 *   quat.mul_checked     qo_quat_mul_checked_q30
 *   quat.rotate          qo_quat_rotate_q30
 *   quat.angle_between   qo_quat_angle_between_q30
 *   quat.exp             qo_quat_exp_q30
 *   quat.log             qo_quat_log_q30
 *   quat.integrate       qo_quat_integrate_q30 (takes the increment omega*dt, Q3.28 rad: a Q16.16 dt times a rate would lose the small steps)
 *   quat.is_finite       - a fixed-point value is always finite
 */
/*
 * qorient/quat_fx.h - quaternion algebra in fixed point (Q1.30 components).
 *
 * The fixed-point twin of qorient/quat.h: the same operations and names with the _q30 suffix.
 * Conventions: see qorient/types.h (scalar-first, Hamilton, active, right-handed). Components
 * are Q1.30 (qo_q30, range [-2, 2)), angles Q3.28 radians (qo_q28). No float, no libm.
 *
 * Index:
 *   qo_quat_identity_q30        (1, 0, 0, 0)
 *   qo_quat_mul_q30             Hamilton product a*b (apply b first, then a), saturating
 *   qo_quat_mul_checked_q30     the same, with QO_E_OVERFLOW when a component saturated
 *   qo_quat_conj_q30            conjugate (w, -x, -y, -z)
 *   qo_quat_dot_q30             4-D dot product, Q1.30, rounded once
 *   qo_quat_norm_q30            Euclidean length, Q1.30, correctly rounded
 *   qo_quat_normalize_q30       unit length; zero -> identity + QO_E_DEGENERATE
 *   qo_quat_normalize_fast_q30  the same to ~2e-8 with no square root or division (fast tier)
 *   qo_quat_inverse_q30         inverse of a UNIT quaternion (= the conjugate)
 *   qo_quat_canonical_q30       the sign with w >= 0 (ties by the first non-zero of x, y, z)
 *   qo_quat_rotate_q30          rotate a Q1.30 vector by a unit quaternion
 *   qo_quat_angle_between_q30   rotation angle from a to b, Q3.28 in [0, pi]
 *   qo_quat_exp_q30             exp of a pure quaternion (0, v), v in Q3.28 radians
 *   qo_quat_log_q30             log of a quaternion, vector part in Q3.28 radians
 *   qo_quat_integrate_q30       advance an orientation by a body-frame rotation increment
 *
 * Rounding and saturation: every output component is the exact value rounded ONCE to
 * nearest (products summed exactly in 64 bits, see qo_fx_sum_round_i64), unless a function
 * says otherwise; a value beyond [-2, 2) saturates. For unit inputs nothing can saturate
 * except where a function says so. Errors quoted in LSB are of Q1.30 (9.3e-10) or Q3.28
 * (3.7e-9 rad) and are measured by bench/accuracy_fx.c.
 */
#ifndef QORIENT_QUAT_FX_H
#define QORIENT_QUAT_FX_H

#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The identity rotation (QO_Q30_ONE, 0, 0, 0). */
qo_quat_q30 qo_quat_identity_q30(void);

/* Hamilton product a*b; as rotations, b first, then a. Each component is the exact sum of
 * its four products rounded once (<= 0.5 LSB); for unit a and b no component exceeds 1. With
 * non-unit inputs a component can exceed the Q1.30 range: it saturates silently here, and
 * qo_quat_mul_checked_q30 says so. */
qo_quat_q30 qo_quat_mul_q30(qo_quat_q30 a, qo_quat_q30 b);

/* qo_quat_mul_q30 with a status. Returns QO_OK; QO_E_NULL if out is NULL; QO_E_OVERFLOW if a
 * component saturated (*out holds the saturated product). */
qo_status qo_quat_mul_checked_q30(qo_quat_q30 a, qo_quat_q30 b, qo_quat_q30 *out);

/* Conjugate (w, -x, -y, -z). A component equal to INT32_MIN (-2.0) negates to INT32_MAX. */
qo_quat_q30 qo_quat_conj_q30(qo_quat_q30 q);

/* a.w*b.w + a.x*b.x + a.y*b.y + a.z*b.z in Q1.30, summed exactly and rounded once; saturates
 * (only possible for non-unit inputs). For unit quaternions: cos(theta/2) of the rotation
 * between them, its sign telling which of +-b is nearer a. */
qo_q30 qo_quat_dot_q30(qo_quat_q30 a, qo_quat_q30 b);

/* sqrt(w^2 + x^2 + y^2 + z^2) in Q1.30, correctly rounded (exact 64-bit sum of squares).
 * Saturates at INT32_MAX (~2.0) when the norm is 2 or more. */
qo_q30 qo_quat_norm_q30(qo_quat_q30 q);

/* q / |q|, for any non-zero q (including components at the ends of the Q1.30 range and
 * quaternions a few LSB long: the input is scaled up first, so small inputs keep their
 * direction to full precision). Each component is within 1 LSB of the exact unit quaternion;
 * the sign of q is kept.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE if q is (0,0,0,0) (*out is the
 * identity). */
qo_status qo_quat_normalize_q30(qo_quat_q30 q, qo_quat_q30 *out);

/* The fast tier of qo_quat_normalize_q30, for loops that renormalise every step on a core
 * without a 64-bit multiply or divider (Cortex-M0/M0+): q / |q| through one Newton reciprocal
 * square root (two steps, ~2^-26 relative) and four products in 32-bit words, no square root,
 * no division, no 64-bit arithmetic. Each component within 16 LSB (1.5e-8) of the exact unit
 * quaternion (checked in tests/core/test_quat.c, worst seen 14 LSB, e.g. (0, 0, -1, 0) gives
 * -(1 - 14 LSB); the exact function: 1 LSB), never beyond +-1.0; the sign of q is kept; any
 * non-zero q, as qo_quat_normalize_q30. About a third of the exact one's instructions on
 * Cortex-M0 (tools/qemu-icount.sh).
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE if q is (0,0,0,0) (*out is the
 * identity). */
qo_status qo_quat_normalize_fast_q30(qo_quat_q30 q, qo_quat_q30 *out);

/* The inverse of a UNIT quaternion, which is its conjugate (exact). In fixed point the
 * general conj(q)/|q|^2 is rarely wanted (a short q has an inverse beyond the Q1.30 range);
 * for a non-unit q, normalise first. Same as qo_quat_conj_q30. */
qo_quat_q30 qo_quat_inverse_q30(qo_quat_q30 q);

/* The representative with w >= 0; when w == 0 the first non-zero of x, y, z is made positive
 * (matches qo_quat_canonical_f32 and scipy). Negation saturates (INT32_MIN -> INT32_MAX). */
qo_quat_q30 qo_quat_canonical_q30(qo_quat_q30 q);

/* v' = q (0, v) q* for a unit q, evaluated as v + 2w t + 2 u x t, t = u x v, u = (x, y, z),
 * with t rounded once and each output component rounded once: within 4 LSB of the exact
 * q v q* for a Q1.30-normalised q and |v| <= 1 (tests; bench/accuracy_fx.c: 4.3e-9 rad end to
 * end). q is not normalised (a non-unit q scales v by about |q|^2). Components saturate. */
qo_vec3_q30 qo_quat_rotate_q30(qo_quat_q30 q, qo_vec3_q30 v);

/* Angle in Q3.28 radians, in [0, QO_Q28_PI], of the rotation taking orientation a to b
 * (both unit; the result depends only on their directions): 2*atan2(|vec(r)|, |r.w|),
 * r = conj(a)*b in 64 bits. Accurate near 0 and near pi (no acos), the same for b and -b;
 * <= 2 LSB of Q3.28. Identical inputs give exactly 0. */
qo_q28 qo_quat_angle_between_q30(qo_quat_q30 a, qo_quat_q30 b);

/*
 * exp of the pure quaternion (0, v) with v in Q3.28 radians: (cos|v|, sin|v| v/|v|), the
 * unit rotation by 2|v| about v. (The scalar part of a general exponent would scale by e^w,
 * which has no Q1.30 meaning for a unit rotation: both cores take the vector only, see
 * qo_quat_exp_f32.)
 * v = 0 gives the identity. Each component within ~2 LSB.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_RANGE if a component of v is 4 rad or more in
 * magnitude (|v| <= pi already reaches every rotation) - *out is the identity then.
 */
qo_status qo_quat_exp_q30(qo_vec3_q28 v, qo_quat_q30 *out);

/*
 * Vector part of log(q / |q|): atan2(|u|, w) u/|u| in Q3.28 radians, u = (x, y, z); for a unit
 * quaternion this is theta/2 * axis with theta in [0, 2pi] (canonicalise q first for the
 * short rotation: then |result| <= pi/2). The scalar part ln|q| is not returned (q is taken
 * as a rotation; normalise or measure it with qo_quat_norm_q30). For u == 0: (0, 0, 0) if
 * w > 0, and (pi, 0, 0) if w < 0 (a 2pi rotation about an undefined axis: axis x, as
 * qo_quat_log_f32). <= 1.5 LSB of Q3.28 per component (the angle and the direction are each
 * rounded once).
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE if q == 0 (*out = (0, 0, 0)).
 */
qo_status qo_quat_log_q30(qo_quat_q30 q, qo_vec3_q28 *out);

/*
 * Integrates a body-frame rotation increment: out = normalize(q * exp(dtheta / 2)), where
 * dtheta = omega * dt is the rotation vector (Q3.28 radians, in the body's own axes) turned
 * through in this step - the caller forms it in whatever time format it uses, so no time
 * format is imposed here. Exact for a constant omega over the step (no first-order drift); the
 * half-angle is never rounded (see qo_rotvec_to_quat_q30). For a WORLD-frame increment use
 * exp(dtheta/2) * q, i.e. qo_quat_mul_q30(from_rotvec(dtheta), q).
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE if q is zero (*out = identity).
 */
qo_status qo_quat_integrate_q30(qo_quat_q30 q, qo_vec3_q28 dtheta, qo_quat_q30 *out);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_QUAT_FX_H */
