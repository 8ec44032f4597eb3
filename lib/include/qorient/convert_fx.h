/* parity fixed (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   convert.axis_angle_to_quat    qo_axis_angle_to_quat_q30
 *   convert.axis_angle_from_quat  qo_axis_angle_from_quat_q30
 *   convert.rotvec_to_quat        qo_rotvec_to_quat_q30
 *   convert.rotvec_from_quat      qo_rotvec_from_quat_q30
 *   convert.mat3_from_quat        qo_mat3_from_quat_q30
 *   convert.mat3_to_quat          qo_mat3_to_quat_q30
 *   convert.mat3_to_quat_trusted  qo_mat3_to_quat_trusted_q30
 *   convert.mat3_to_quat_ortho    qo_mat3_to_quat_ortho_q30
 *   mat3.identity                 qo_mat3_identity_q30
 *   mat3.transpose                qo_mat3_transpose_q30
 *   mat3.mul                      qo_mat3_mul_q30
 *   mat3.mul_vec3                 qo_mat3_mul_vec3_q30
 *   mat3.det                      qo_mat3_det_q30 (Q1.30, saturating)
 *   mat3.orthonormalize           qo_mat3_orthonormalize_q30 (Newton-Schulz, no division)
 */
/*
 * qorient/convert_fx.h - conversions between rotation representations in fixed point.
 *
 * The fixed-point twin of qorient/convert.h: the same names with the _q30 suffix and the same
 * documented edge behaviour. Quaternion, unit-vector and matrix components are Q1.30
 * (qo_q30), angles and rotation vectors Q3.28 radians (qo_q28, qo_vec3_q28).
 * Conventions: see qorient/types.h (scalar-first, Hamilton, active rotations, right-handed,
 * matrices row-major m[row][col] acting on column vectors). For every q,
 * qo_mat3_from_quat_q30(q) rotates a vector as qo_quat_rotate_q30(q, .) does.
 * No float, no libm: integer arithmetic on the primitives of qorient/fxmath.h.
 *
 * Index:
 *   QO_MAT3_ROTATION_TOL_Q30     tolerance of the "is this a rotation matrix" test
 *   qo_axis_angle_to_quat_q30    axis (any length) + angle -> unit quaternion
 *   qo_axis_angle_from_quat_q30  quaternion -> unit axis + angle in [0, pi]
 *   qo_rotvec_to_quat_q30        rotation vector (axis * angle) -> unit quaternion
 *   qo_rotvec_from_quat_q30      quaternion -> rotation vector, |rv| in [0, pi]
 *   qo_mat3_from_quat_q30        quaternion -> rotation matrix
 *   qo_mat3_to_quat_q30          rotation matrix -> canonical unit quaternion (strict check)
 *   qo_mat3_orthonormalize_q30   nearest rotation matrix (orthogonal polar factor)
 *   qo_mat3_to_quat_ortho_q30    orthonormalise, then convert (for drifted matrices)
 *   qo_mat3_to_quat_trusted_q30 no rotation check (for matrices known to be rotations)
 *   qo_mat3_mul_vec3_q30         M v
 *   qo_mat3_mul_q30              A B
 *   qo_mat3_transpose_q30        M^T
 *   qo_mat3_identity_q30         I
 *   qo_mat3_det_q30              det M (Q1.30, saturating)
 *
 * Signs: qo_mat3_to_quat_q30 returns the canonical sign (w >= 0, ties as
 * qo_quat_canonical_q30); qo_axis_angle_to_quat_q30 and qo_rotvec_to_quat_q30 return
 * (cos(angle/2), sin(angle/2) * unit axis) as the formula gives it (angle beyond pi: w < 0).
 * Accuracy: every conversion is within a few LSB of Q1.30 / Q3.28 of the exact result for its
 * exact fixed-point input: within 8e-8 rad of rotation, checked by tests/core/test_convert.c
 * (its Q1.30 row: test_axis_angle, test_rotvec, test_mat3_quat, test_round_trips); the worst
 * measured by bench/accuracy_fx.c: docs/FIGURES.md, accuracy.
 */
#ifndef QORIENT_CONVERT_FX_H
#define QORIENT_CONVERT_FX_H

#include "qorient/status.h"
#include "qorient/types.h"
#include "qorient/quat_fx.h"

#ifdef __cplusplus
extern "C" {
#endif

/* qo_mat3_to_quat_q30 accepts *m as a rotation when every entry of M^T M - I is at most
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
qo_status qo_axis_angle_to_quat_q30(qo_vec3_q30 axis, qo_q28 angle, qo_quat_q30 *out);

/*
 * Axis (unit, Q1.30) and angle (Q3.28, in [0, pi]) of q (normalised first; q and -q give the
 * same answer). For the identity (and any q with zero vector part) the axis is undefined: we
 * return axis (1, 0, 0) and angle 0. At exactly pi the axis sign follows
 * qo_quat_canonical_q30. The angle is 2*atan2(|v|, |w|) (accurate at 0 and at pi).
 * Returns QO_OK; QO_E_NULL if axis or angle is NULL (the other is still written if non-NULL);
 * QO_E_DEGENERATE for q == 0. On every error *axis = (1, 0, 0) and *angle = 0.
 */
qo_status qo_axis_angle_from_quat_q30(qo_quat_q30 q, qo_vec3_q30 *axis, qo_q28 *angle);

/*
 * Unit quaternion of the rotation vector rv (Q3.28 radians: |rv| is the angle, any length up
 * to the format's |rv| < 8 sqrt 3), q = (cos(|rv|/2), sin(|rv|/2)/|rv| * rv). |rv| is the
 * correctly rounded 64-bit norm and its half is never rounded; a tiny rv gives (1, rv/2) to
 * the LSB, rv = 0 gives the identity with QO_OK. |rv| > pi gives w < 0.
 * Returns QO_OK; QO_E_NULL if out is NULL (nothing else can fail).
 */
qo_status qo_rotvec_to_quat_q30(qo_vec3_q28 rv, qo_quat_q30 *out);

/*
 * Rotation vector (Q3.28 radians) of q: canonical sign first (w >= 0), so |*out| is in
 * [0, pi]; angle 2*atan2(|v|, w). At exactly pi the sign follows qo_quat_canonical_q30.
 * q need not be unit. <= 3 LSB of Q3.28 per component.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE for q == 0 (*out = (0, 0, 0)).
 */
qo_status qo_rotvec_from_quat_q30(qo_quat_q30 q, qo_vec3_q28 *out);

/*
 * Rotation matrix (Q1.30, row-major, v' = M v) of q, normalised first: any non-zero q (and q
 * or -q) gives a proper rotation. q is normalised to Q1.31 and each entry is the exact sum of
 * products rounded once (<= 3 LSB of Q1.30).
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE for q == 0. *out is the identity
 * matrix on every error.
 */
qo_status qo_mat3_from_quat_q30(qo_quat_q30 q, qo_mat3_q30 *out);

/*
 * Canonical unit quaternion (w >= 0) of the rotation matrix *m (Q1.30, row-major). The matrix
 * must be a rotation within QO_MAT3_ROTATION_TOL_Q30 (max entry of |M^T M - I|) with
 * det M > 0; the small residual is absorbed (the result is normalised). The pivot is the
 * largest of trace, m00, m11, m22 (Shepperd), so 180-degree rotations lose no precision.
 * Returns QO_OK; QO_E_NULL if m or out is NULL; QO_E_NOT_ROTATION for a scaled, sheared,
 * reflected (det < 0) or singular matrix. *out is the identity on every error.
 */
qo_status qo_mat3_to_quat_q30(const qo_mat3_q30 *m, qo_quat_q30 *out);

/* M v, each component the exact sum of three products rounded once, saturated.
 * m == NULL gives (0, 0, 0) (there is no status to return; do not pass NULL). */
qo_vec3_q30 qo_mat3_mul_vec3_q30(const qo_mat3_q30 *m, qo_vec3_q30 v);

/*
 * The rotation matrix nearest *m in the Frobenius norm (the orthogonal factor R of the polar
 * decomposition M = R S), the twin of qo_mat3_orthonormalize_f32 by another algorithm: M is
 * scaled to X = M / |M|_F (exact power-of-two pre-scaling, one rounded division), then the
 * Newton-Schulz (Bjorck) iteration X <- X (3I - X^T X) / 2 runs until no entry moves by more
 * than 2 LSB (at most 48 steps): no inverse, no division, every entry an exact 64-bit sum
 * rounded once. A uniformly scaled rotation gives that rotation back (to a few LSB); m and
 * out may point to the same matrix. The result is orthonormal to a few LSB (max
 * |R^T R - I| checked against QO_MAT3_ROTATION_TOL_Q30) and within 8e-8 rad of the exact
 * nearest rotation for a drifted or noisy rotation (tests/core/test_convert.c:
 * test_orthonormalize).
 * Returns QO_OK; QO_E_NULL if m or out is NULL; QO_E_NOT_ROTATION if M is zero, a reflection,
 * singular or too close to singular (det(M / |M|_F) <= 2^-14, which keeps every singular
 * value of M / |M|_F above 1.2e-4: the float core's limit is a condition number of 3e3). *out
 * is the identity matrix on every error.
 */
qo_status qo_mat3_orthonormalize_q30(const qo_mat3_q30 *m, qo_mat3_q30 *out);

/*
 * Canonical unit quaternion of the rotation nearest *m: qo_mat3_orthonormalize_q30 followed
 * by qo_mat3_to_quat_q30 (for a matrix KNOWN to be a drifted or noisy rotation).
 * Returns QO_OK, QO_E_NULL, QO_E_NOT_ROTATION (as qo_mat3_orthonormalize_q30). *out is the
 * identity on every error.
 */
qo_status qo_mat3_to_quat_ortho_q30(const qo_mat3_q30 *m, qo_quat_q30 *out);

/*
 * Canonical unit quaternion of *m for a matrix KNOWN to be a rotation: the Shepperd formula
 * of qo_mat3_to_quat_q30 and one normalisation, without its rotation check. A matrix that
 * is not a rotation gives an unspecified unit quaternion.
 * Returns QO_OK; QO_E_NULL if m or out is NULL; QO_E_NOT_ROTATION only when the pivot
 * quaternion is zero (no rotation gives that: e.g. M = -I/3). *out is the identity on every
 * error.
 */
qo_status qo_mat3_to_quat_trusted_q30(const qo_mat3_q30 *m, qo_quat_q30 *out);

/* A B, each entry the exact sum of three products rounded once (<= 0.5 LSB), saturated to the
 * Q1.30 range (only possible for entries beyond a rotation's). As rotations B first, then A.
 * a or b NULL gives the zero matrix (there is no status to return; do not pass NULL). */
qo_mat3_q30 qo_mat3_mul_q30(const qo_mat3_q30 *a, const qo_mat3_q30 *b);

/* M^T (exact): the inverse of a rotation matrix. m NULL gives the zero matrix. */
qo_mat3_q30 qo_mat3_transpose_q30(const qo_mat3_q30 *m);

/* The identity matrix (QO_Q30_ONE on the diagonal). */
qo_mat3_q30 qo_mat3_identity_q30(void);

/* Determinant in Q1.30 (cofactor expansion along the first row): 1.0 (QO_Q30_ONE) for a
 * rotation, -1.0 for a reflection. Exact 64-bit products, the cofactors and the sum each
 * rounded once: within 2 LSB when no entry exceeds 1 + 1/16 in magnitude; larger entries
 * (up to the format's 2) are handled with Q3.28 cofactors (within 12 LSB), and a determinant
 * beyond [-2, 2) saturates. m NULL gives 0. */
qo_q30 qo_mat3_det_q30(const qo_mat3_q30 *m);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_CONVERT_FX_H */
