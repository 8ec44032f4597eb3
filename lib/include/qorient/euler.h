/* parity float32 (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   euler.to_quat         qo_euler_to_quat_f32
 *   euler.from_quat       qo_euler_from_quat_f32
 *   euler.from_quat_near  qo_euler_from_quat_near_f32
 *   euler.from_quat_band  qo_euler_from_quat_band_f32
 */
/*
 * qorient/euler.h - Euler angles, float32: all 12 axis sequences, intrinsic and extrinsic
 * (24 conventions), both directions, with gimbal lock reported as data.
 *
 * Index:
 *   qo_euler_seq and its helpers  (qorient/euler_seq.h, shared with the fixed core)
 *   qo_euler_f32  three angles a1, a2, a3 (rad) in the order the sequence names them
 *   qo_euler_info_f32  gimbal-lock report: locked flag and margin (rad) to the singularity
 *   QO_EULER_LOCK_BAND_F32         default lock band (rad) of qo_euler_from_quat_f32
 *   qo_euler_to_quat_f32()         angles -> quaternion
 *   qo_euler_from_quat_f32()       quaternion -> angles, scipy ranges, default lock band
 *   qo_euler_from_quat_band_f32()  the same with a caller-chosen lock band
 *   qo_euler_from_quat_near_f32()  quaternion -> the solution nearest previous angles (joints)
 *
 * Conventions (the same as scipy.spatial.transform.Rotation.from_euler / as_euler):
 *   - A sequence names three axes, e.g. "xyz". Lower case = EXTRINSIC: rotate about the fixed
 *     (world) axes x, then y, then z. Upper case = INTRINSIC: rotate about the body's own axes
 *     X, then the new Y', then the newer Z''. Cases cannot be mixed.
 *   - Angles (a1, a2, a3) belong to the axes in the order written. With R_x(t) the active
 *     rotation by t about x (types.h: Hamilton, active, right-handed):
 *       extrinsic "xyz": q = q_z(a3) * q_y(a2) * q_x(a1)     (x applied first)
 *       intrinsic "XYZ": q = q_X(a1) * q_Y(a2) * q_Z(a3)
 *     so intrinsic "XYZ" (a1, a2, a3) is the same rotation as extrinsic "zyx" (a3, a2, a1).
 *     Example: intrinsic "ZYX" = (yaw, pitch, roll) of aerospace; yaw 90 deg = (pi/2, 0, 0).
 *   - Tait-Bryan sequences (three different axes: xyz, xzy, yxz, yzx, zxy, zyx) are singular
 *     (gimbal lock) when the middle angle is +-pi/2. Proper Euler sequences (first axis ==
 *     third: xyx, xzx, yxy, yzy, zxz, zyz) are singular when the middle angle is 0 or pi -
 *     including the identity rotation.
 *   - Ranges returned by qo_euler_from_quat_f32 / _band_f32 (scipy's): a1, a3 in [-pi, pi];
 *     a2 in [-pi/2, pi/2] (Tait-Bryan) or [0, pi] (proper). (pi here is the float nearest pi.)
 *
 * Gimbal lock. margin = the angle (rad, in [0, pi/2]) between the middle angle and its nearest
 * singular value; locked = (margin <= band). At lock only the sum (or difference) of a1 and a3
 * is determined by the rotation. Our documented choice, scipy's: a3 = 0 and a1 takes all of
 * it, so the angles still compose to the input rotation. When the input is not exactly
 * singular but inside the band, forcing a3 = 0 moves the composed rotation by at most about
 * 2*margin rad (2*asin(2*sin(margin/2)) for margin <= pi/3): the part of the rotation that
 * tells a1 from a3 has size sin(margin/2). The middle angle is never snapped; a1 is the best
 * fit given a2 and a3.
 *
 * Why QO_EULER_LOCK_BAND_F32 is 2e-6 rad (and not the 1e-3 of matrix-based code):
 *   - The middle angle and the margin are computed directly from the quaternion (Bernardes &
 *     Viollet 2022: atan2 of two norms, no asin/acos, never NaN), so float32 noise moves the
 *     margin LINEARLY: an exactly singular rotation built by qo_euler_to_quat_f32 with the float
 *     nearest pi/2 (or pi), and the same with every component further moved by up to 2 ulp
 *     (upstream float noise), keeps its margin inside the band, so it is flagged
 *     (tests/core/test_euler.c: test_exactly_singular_all24; the largest margins seen are in
 *     docs/FIGURES.md, accuracy, accuracy_euler). An asin/acos form would turn 1e-7 of noise
 *     into sqrt(2e-7) ~ 4.5e-4 rad, which is why such code (PX4) needs 1e-3.
 *   - A flagged input recomposes within 2*margin <= 4e-6 rad, inside the 1e-5 rad goal
 *     (test_exactly_singular_all24, test_just_off_singular_all24). A band of 1e-3 would let
 *     flagged inputs recompose up to 2e-3 rad off.
 *   - Outside the band the full decomposition is returned and recomposes to float precision
 *     however close to lock (a1 and a3 are individually ill-conditioned there, like
 *     1e-7/margin, but their composition is not): within 1e-6 rad, checked by
 *     test_just_off_singular_all24 (the worst seen: docs/FIGURES.md, accuracy).
 *   - 2e-6 rad is 1.1e-4 degrees: the flag is never raised anywhere near 2 degrees away.
 *   A gimbal that wants a wider "hold" zone (e.g. 0.5 deg) passes its own band to
 *   qo_euler_from_quat_band_f32 / qo_euler_from_quat_near_f32 and accepts the 2*margin bound.
 *
 * Inputs: any finite non-zero quaternion, unit or not: every quantity used is a ratio of its
 * components, so it is only scaled by an exact power of two (normalising would round each
 * component once more); q and -q give the same angles. Angles of any finite size for
 * from_euler (they are periodic; float32 carries them with ulp(|angle|) resolution).
 *
 * Accuracy, composed in double, bounds checked by tests/core/test_euler.c on fixed-seed cases in
 * all 24 conventions: from_euler <= 1e-6 rad (test_from_euler_random_all24); to_euler <= 1e-6
 * rad generic and at/near lock outside the band (test_to_euler_random_rotations_all24,
 * test_just_off_singular_all24), <= 2*margin + 1e-5 rad inside the band
 * (test_exactly_singular_all24); to_euler_near <= 2e-6 rad off lock (its outputs may leave
 * [-pi, pi], where float32's spacing is coarser; test_near_through_singularity_all24). The
 * worst errors measured (bench/accuracy_euler, 20000 cases x 24 conventions): docs/FIGURES.md,
 * accuracy.
 */
#ifndef QORIENT_EULER_H
#define QORIENT_EULER_H

#include "qorient/euler_seq.h"
#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Three angles in radians, a1 about the first axis named by the sequence, a2 the second,
 * a3 the third (scipy's from_euler(seq, [a1, a2, a3])). */
typedef struct qo_euler_f32 { float a1, a2, a3; } qo_euler_f32;

/* Gimbal-lock report of one decomposition.
 *   locked: 1 when margin <= the lock band in use (then a3 was chosen, not measured), else 0.
 *   margin: angle in rad, in [0, pi/2], between the middle angle and the nearest singular
 *           value (+-pi/2 for Tait-Bryan; 0 or pi for proper). A property of the rotation and
 *           the sequence, not of the band: callers may apply their own threshold to it. */
typedef struct qo_euler_info_f32 { int locked; float margin; } qo_euler_info_f32;

/* Default lock band of qo_euler_from_quat_f32, rad (justified in the file comment above). */
#define QO_EULER_LOCK_BAND_F32 2e-6f

/*
 * Quaternion of the rotation given by Euler angles e (rad, any finite value) in convention seq:
 * the product of the three elementary half-angle quaternions in composition order (see the
 * file comment). The sign is that product's, not canonicalised - the same as scipy's
 * from_euler(...).as_quat() - apply qo_quat_canonical_f32 for w >= 0. Unit to float rounding.
 * Returns QO_OK; QO_E_NULL (out NULL); QO_E_ARG (seq not one of the 24); QO_E_NONFINITE (an
 * angle is NaN or Inf). On error *out is the identity.
 */
qo_status qo_euler_to_quat_f32(qo_euler_seq seq, qo_euler_f32 e, qo_quat_f32 *out);

/*
 * Euler angles of the rotation q in convention seq, scipy's ranges (file comment), lock band
 * QO_EULER_LOCK_BAND_F32. q need not be unit (file comment); q and -q give the same result.
 * Method: Bernardes & Viollet 2022, directly from the quaternion, atan2 only (never NaN).
 * At lock (info.locked == 1): a3 = 0 and a1 carries the rest (file comment); a2 as measured.
 * Accuracy (tests/core/test_euler.c): composing the result in double gives q within 1e-6 rad
 * generically and within 1e-5 rad at or near lock (the measured worst: docs/FIGURES.md,
 * accuracy).
 * info may be NULL. Returns QO_OK; QO_E_NULL (out NULL); QO_E_ARG (bad seq); QO_E_NONFINITE
 * (a component of q is NaN or Inf); QO_E_DEGENERATE (all four components are zero; tiny and
 * subnormal quaternions are fine). Checked in that order. On error *out = (0, 0, 0) and
 * *info = { 0, 0 }.
 */
qo_status qo_euler_from_quat_f32(qo_quat_f32 q, qo_euler_seq seq, qo_euler_f32 *out,
                               qo_euler_info_f32 *info);

/*
 * As qo_euler_from_quat_f32 with the lock band band_rad (rad, in [0, pi/2]; 0 flags only an
 * exactly computed margin of 0, pi/2 flags everything). The composed result is within
 * 2*margin (<= 2*band_rad) of q when locked.
 * Returns as qo_euler_from_quat_f32, plus QO_E_NONFINITE for a NaN/Inf band and QO_E_RANGE for
 * a finite band outside [0, pi/2]. On error *out = (0, 0, 0) and *info = { 0, 0 }.
 */
qo_status qo_euler_from_quat_band_f32(qo_quat_f32 q, qo_euler_seq seq, float band_rad,
                                    qo_euler_f32 *out, qo_euler_info_f32 *info);

/*
 * Euler angles of q nearest the previous joint angles prev, for joints that must not jump.
 * Every rotation has two solutions off lock: (a1, a2, a3) and (a1 + pi, pi - a2, a3 + pi)
 * (Tait-Bryan) or (a1 + pi, -a2, a3 + pi) (proper). Each angle of each is moved by a multiple
 * of 2*pi to the value nearest the same angle of prev, and the solution with the smaller sum
 * of squared differences to prev is returned (the first one on a tie). So the outputs are NOT
 * limited to [-pi, pi]: a continuous joint keeps counting turns (precision is float32's at the
 * size of prev: re-wrap prev now and then on a joint that turns forever).
 * At lock (margin <= band, rad in [0, pi/2]): the free split stays where prev had it: a3 =
 * prev.a3 exactly, a2 the measured middle angle of the branch nearer prev.a2, and a1 the best
 * fit given those (unwrapped toward prev.a1). Exactly at the singularity this composes to q;
 * inside the band it is within 2*margin of q (and much closer while prev tracks the motion).
 * info may be NULL. Returns QO_OK; QO_E_NULL (out NULL); QO_E_ARG (bad seq); QO_E_NONFINITE
 * (NaN/Inf in q, prev or band); QO_E_DEGENERATE (q zero); QO_E_RANGE (band outside
 * [0, pi/2]). On error *out = prev if prev is finite (hold the joint), else (0, 0, 0), and
 * *info = { 0, 0 }.
 */
qo_status qo_euler_from_quat_near_f32(qo_quat_f32 q, qo_euler_seq seq, qo_euler_f32 prev,
                                    float band, qo_euler_f32 *out, qo_euler_info_f32 *info);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_EULER_H */
