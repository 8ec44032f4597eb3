/* parity fixed (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   convert.from_axis_angle    qo_quat_from_axis_angle_q30
 *   convert.to_axis_angle      qo_quat_to_axis_angle_q30
 *   convert.from_rotvec        qo_quat_from_rotvec_q30
 *   convert.to_rotvec          qo_quat_to_rotvec_q30
 *   convert.to_mat3            qo_quat_to_mat3_q30
 *   convert.from_mat3          qo_quat_from_mat3_q30
 *   convert.from_mat3_trusted  - not yet (issue 16): the checked qo_quat_from_mat3_q30 only
 *   convert.from_mat3_ortho    - not yet (issue 16): repair matrices in float32 first
 *   mat3.identity              - not yet (issue 16): no fixed-point caller so far
 *   mat3.transpose             - not yet (issue 16): no fixed-point caller so far
 *   mat3.mul                   - not yet (issue 16): no fixed-point caller so far
 *   mat3.mul_vec3              qo_mat3_mul_vec3_q30
 *   mat3.det                   - not yet (issue 16): no fixed-point caller so far
 *   mat3.orthonormalize        - not yet (issue 16): repair matrices in float32 first
 */
/*
 * qorient/convert_fx.h - conversions between rotation representations in fixed point.
 *
 * The fixed-point twin of qorient/convert.h: the same names with the _q30 suffix and the same
 * documented edge behaviour. Quaternion, unit-vector and matrix components are Q1.30
 * (qo_q30), angles and rotation vectors Q3.28 radians (qo_q28, qo_vec3_q28).
 * Conventions: see qorient/types.h (scalar-first, Hamilton, active rotations, right-handed,
 * matrices row-major m[row][col] acting on column vectors). For every q,
 * qo_quat_to_mat3_q30(q) rotates a vector as qo_quat_rotate_q30(q, .) does.
 * No float, no libm: integer arithmetic on the primitives of qorient/fxmath.h.
 *
 * Index:
 *   QO_MAT3_ROTATION_TOL_Q30      tolerance of the "is this a rotation matrix" test
 *   qo_quat_from_axis_angle_q30   axis (any length) + angle -> unit quaternion
 *   qo_quat_to_axis_angle_q30     quaternion -> unit axis + angle in [0, pi]
 *   qo_quat_from_rotvec_q30       rotation vector (axis * angle) -> unit quaternion
 *   qo_quat_to_rotvec_q30         quaternion -> rotation vector, |rv| in [0, pi]
 *   qo_quat_to_mat3_q30           quaternion -> rotation matrix
 *   qo_quat_from_mat3_q30         rotation matrix -> canonical unit quaternion (strict check)
 *   qo_mat3_mul_vec3_q30          M v
 *
 * Signs: qo_quat_from_mat3_q30 returns the canonical sign (w >= 0, ties as
 * qo_quat_canonical_q30); qo_quat_from_axis_angle_q30 and qo_quat_from_rotvec_q30 return
 * (cos(angle/2), sin(angle/2) * unit axis) as the formula gives it (angle beyond pi: w < 0).
 * Accuracy (bench/accuracy_fx.c): every conversion is within a few LSB of Q1.30 / Q3.28 of
 * the exact result for its exact fixed-point input, i.e. ~1e-8 rad of rotation.
 */
#ifndef QORIENT_CONVERT_FX_H
#define QORIENT_CONVERT_FX_H

#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* qo_quat_from_mat3_q30 accepts *m as a rotation when every entry of M^T M - I is at most
 * this in magnitude (Q1.30 raw: 107374 = 1e-4, the float32 tolerance QO_MAT3_ROTATION_TOL_F32)
 * and det M > 0. A Q1.30 rotation matrix rounded from exact values is off by ~1e-9, so 1e-4
 * accepts anything a fixed or float pipeline produced and rejects visible scale or shear. */
#define QO_MAT3_ROTATION_TOL_Q30 ((qo_q30)107374)

/*
 * Unit quaternion of the rotation by `angle` (Q3.28 radians, any value in [-8, 8)) about
 * `axis` (Q1.30, any non-zero length - it is normalised with a 64-bit exact length, so a
 * short axis a few LSB long keeps its direction): (cos(angle/2), sin(angle/2) axis/|axis|).
 * The half-angle is not rounded. |angle| > pi gives w < 0.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE if axis is (0,0,0). *out is the
 * identity on every error.
 */
qo_status qo_quat_from_axis_angle_q30(qo_vec3_q30 axis, qo_q28 angle, qo_quat_q30 *out);

/*
 * Axis (unit, Q1.30) and angle (Q3.28, in [0, pi]) of q (normalised first; q and -q give the
 * same answer). For the identity (and any q with zero vector part) the axis is undefined: we
 * return axis (1, 0, 0) and angle 0. At exactly pi the axis sign follows
 * qo_quat_canonical_q30. The angle is 2*atan2(|v|, |w|) (accurate at 0 and at pi).
 * Returns QO_OK; QO_E_NULL if axis or angle is NULL (the other is still written if non-NULL);
 * QO_E_DEGENERATE for q == 0. On every error *axis = (1, 0, 0) and *angle = 0.
 */
qo_status qo_quat_to_axis_angle_q30(qo_quat_q30 q, qo_vec3_q30 *axis, qo_q28 *angle);

/*
 * Unit quaternion of the rotation vector rv (Q3.28 radians: |rv| is the angle, any length up
 * to the format's |rv| < 8 sqrt 3), q = (cos(|rv|/2), sin(|rv|/2)/|rv| * rv). |rv| is the
 * correctly rounded 64-bit norm and its half is never rounded; a tiny rv gives (1, rv/2) to
 * the LSB, rv = 0 gives the identity with QO_OK. |rv| > pi gives w < 0.
 * Returns QO_OK; QO_E_NULL if out is NULL (nothing else can fail).
 */
qo_status qo_quat_from_rotvec_q30(qo_vec3_q28 rv, qo_quat_q30 *out);

/*
 * Rotation vector (Q3.28 radians) of q: canonical sign first (w >= 0), so |*out| is in
 * [0, pi]; angle 2*atan2(|v|, w). At exactly pi the sign follows qo_quat_canonical_q30.
 * q need not be unit. <= 3 LSB of Q3.28 per component.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE for q == 0 (*out = (0, 0, 0)).
 */
qo_status qo_quat_to_rotvec_q30(qo_quat_q30 q, qo_vec3_q28 *out);

/*
 * Rotation matrix (Q1.30, row-major, v' = M v) of q, normalised first: any non-zero q (and q
 * or -q) gives a proper rotation. q is normalised to Q1.31 and each entry is the exact sum of
 * products rounded once (<= 3 LSB of Q1.30).
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE for q == 0. *out is the identity
 * matrix on every error.
 */
qo_status qo_quat_to_mat3_q30(qo_quat_q30 q, qo_mat3_q30 *out);

/*
 * Canonical unit quaternion (w >= 0) of the rotation matrix *m (Q1.30, row-major). The matrix
 * must be a rotation within QO_MAT3_ROTATION_TOL_Q30 (max entry of |M^T M - I|) with
 * det M > 0; the small residual is absorbed (the result is normalised). The pivot is the
 * largest of trace, m00, m11, m22 (Shepperd), so 180-degree rotations lose no precision.
 * Returns QO_OK; QO_E_NULL if m or out is NULL; QO_E_NOT_ROTATION for a scaled, sheared,
 * reflected (det < 0) or singular matrix. *out is the identity on every error.
 */
qo_status qo_quat_from_mat3_q30(const qo_mat3_q30 *m, qo_quat_q30 *out);

/* M v, each component the exact sum of three products rounded once, saturated.
 * m == NULL gives (0, 0, 0) (there is no status to return; do not pass NULL). */
qo_vec3_q30 qo_mat3_mul_vec3_q30(const qo_mat3_q30 *m, qo_vec3_q30 v);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_CONVERT_FX_H */
