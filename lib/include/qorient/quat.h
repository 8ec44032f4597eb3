/*
 * qorient/quat.h - quaternion algebra, float32.
 *
 * Conventions: see qorient/types.h (scalar-first, Hamilton, active, right-handed).
 *
 * Index:
 *   qo_quat_identity_f32     (1, 0, 0, 0)
 *   qo_quat_mul_f32          Hamilton product a*b (apply b first, then a)
 *   qo_quat_conj_f32         conjugate (w, -x, -y, -z)
 *   qo_quat_dot_f32          4-D dot product
 *   qo_quat_norm_f32         Euclidean length, overflow-safe
 *   qo_quat_normalize_f32    unit length; zero / non-finite input -> identity + status
 *   qo_quat_inverse_f32      q^-1 = conj(q) / |q|^2; zero / non-finite -> identity + status
 *   qo_quat_canonical_f32    the sign with w >= 0 (ties broken by the first non-zero of x, y, z)
 *   qo_quat_rotate_f32       rotate a vector by a unit quaternion: q v q*
 *   qo_quat_angle_between_f32  rotation angle from a to b, in [0, pi]
 *   qo_quat_exp_f32          exponential of a quaternion
 *   qo_quat_log_f32          natural logarithm of a quaternion
 *   qo_quat_integrate_f32    advance an orientation by a body-frame angular velocity over dt
 *   qo_quat_is_finite_f32    all four components finite
 */
#ifndef QORIENT_QUAT_H
#define QORIENT_QUAT_H

#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The identity rotation (1, 0, 0, 0). */
qo_quat_f32 qo_quat_identity_f32(void);

/* Hamilton product a*b. As rotations, a*b applies b first and then a (active, v' = a(b v b*)a*).
 * Not commutative. Norms multiply: |a*b| = |a||b|. */
qo_quat_f32 qo_quat_mul_f32(qo_quat_f32 a, qo_quat_f32 b);

/* Conjugate (w, -x, -y, -z): the inverse rotation for a unit quaternion. */
qo_quat_f32 qo_quat_conj_f32(qo_quat_f32 q);

/* Dot product a.w*b.w + a.x*b.x + a.y*b.y + a.z*b.z. For unit quaternions it is cos(theta/2)
 * of the rotation between them, with a sign that says which of +-b is nearer a. */
float qo_quat_dot_f32(qo_quat_f32 a, qo_quat_f32 b);

/* Euclidean norm sqrt(w^2+x^2+y^2+z^2), computed with scaling so that components up to
 * FLT_MAX do not overflow and tiny ones do not underflow to 0. NaN in -> NaN out. */
float qo_quat_norm_f32(qo_quat_f32 q);

/* Unit quaternion q/|q|.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_NONFINITE if a component is NaN or Inf;
 * QO_E_DEGENERATE if |q| == 0 (also for subnormal-only inputs whose norm underflows).
 * On any error *out is the identity. The sign of q is kept. */
qo_status qo_quat_normalize_f32(qo_quat_f32 q, qo_quat_f32 *out);

/* Multiplicative inverse conj(q)/|q|^2 (for a unit quaternion: the conjugate), computed as
 * (conj(q)/|q|)/|q| so |q|^2 itself may overflow or underflow float (|q| = 1e30 is fine).
 * Returns QO_OK, QO_E_NULL, QO_E_NONFINITE, or QO_E_DEGENERATE for |q| == 0, |q| overflowing
 * float (components near FLT_MAX) or 1/|q| overflowing (|q| below ~3e-39);
 * *out is the identity on error. */
qo_status qo_quat_inverse_f32(qo_quat_f32 q, qo_quat_f32 *out);

/* The representative of the same rotation with w >= 0; when w == 0 the first non-zero of
 * x, y, z is made positive. Matches scipy's as_quat(canonical=True). */
qo_quat_f32 qo_quat_canonical_f32(qo_quat_f32 q);

/* Rotates v by the unit quaternion q: v' = q (0,v) q*, evaluated as
 * v + 2w(u x v) + 2 u x (u x v) with u = (x, y, z) (no normalisation of q: pass a unit
 * quaternion; for a non-unit q the result is neither q v q* nor a rotation of v - normalise
 * first). */
qo_vec3_f32 qo_quat_rotate_f32(qo_quat_f32 q, qo_vec3_f32 v);

/* Angle in radians, in [0, pi], of the rotation that takes orientation a to orientation b
 * (both unit). Computed as 2*atan2(|vec(conj(a)*b)|, |scalar(conj(a)*b)|), accurate for
 * tiny angles (no acos), and the same for b and -b. */
float qo_quat_angle_between_f32(qo_quat_f32 a, qo_quat_f32 b);

/* Quaternion exponential exp(q) = e^w (cos|v|, sin|v| v/|v|), v = (x, y, z). For a pure
 * quaternion (0, theta/2 * axis) it is the unit rotation by theta about axis. Uses a Taylor
 * series for sin|v|/|v| at small |v|.
 * Returns QO_OK, QO_E_NULL, QO_E_NONFINITE (NaN/Inf input, or e^w overflowing float);
 * *out is the identity on error. */
qo_status qo_quat_exp_f32(qo_quat_f32 q, qo_quat_f32 *out);

/* Quaternion logarithm log(q) = (ln|q|, atan2(|v|, w) v/|v|). For a unit quaternion the
 * result is pure, (0, theta/2 * axis), with theta in [0, 2pi]; canonicalise q first for the
 * short rotation. For v == 0 and w < 0 (a rotation by 2pi about an undefined axis) the
 * vector part is (pi, 0, 0) - a documented choice of axis x.
 * Returns QO_OK, QO_E_NULL, QO_E_NONFINITE, QO_E_DEGENERATE for q == 0 (log 0 undefined);
 * *out is (0,0,0,0) on error. */
qo_status qo_quat_log_f32(qo_quat_f32 q, qo_quat_f32 *out);

/* Integrates a constant BODY-frame angular velocity omega (rad/s, about the body's own axes)
 * over dt seconds: out = q * exp((0, omega*dt/2)), then normalised. This is exact for constant
 * omega (no first-order drift). For a WORLD-frame omega pass conj(q) omega q (or use
 * exp(...) * q). dt may be negative (integrates backwards).
 * Returns QO_OK, QO_E_NULL, QO_E_NONFINITE (q, omega or dt not finite), QO_E_DEGENERATE
 * (q is zero); *out is q normalised (or identity if that fails) on error. */
qo_status qo_quat_integrate_f32(qo_quat_f32 q, qo_vec3_f32 omega, float dt, qo_quat_f32 *out);

/* 1 if all four components are finite, else 0. */
int qo_quat_is_finite_f32(qo_quat_f32 q);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_QUAT_H */
