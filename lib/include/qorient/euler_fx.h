/* parity fixed (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   euler.to_quat         qo_euler_to_quat_q30
 *   euler.from_quat       qo_euler_from_quat_q30
 *   euler.from_quat       qo_euler_from_quat_fast_q30 (the fast tier for Cortex-M0: within 5e-8 rad; docs/FIGURES.md, m0)
 *   euler.from_quat_near  qo_euler_from_quat_near_q30
 *   euler.from_quat_band  qo_euler_from_quat_band_q30
 */
/*
 * qorient/euler_fx.h - Euler angles, fixed point: Q1.30 quaternions <-> Q3.28 radians, all 12
 * axis sequences, intrinsic and extrinsic (24 conventions), both directions, gimbal lock
 * reported as data. The fixed-point mirror of qorient/euler.h: same conventions, ranges,
 * method, lock choice and nearest-solution rule; no float, no double, no libm.
 *
 * Index:
 *   qo_euler_q28  three angles a1, a2, a3 (Q3.28 rad) in the order the sequence names them
 *   qo_euler_info_q28              gimbal-lock report: locked flag and margin (Q3.28 rad)
 *   QO_EULER_LOCK_BAND_Q28         default lock band (Q3.28 rad) of qo_euler_from_quat_q30
 *   qo_euler_to_quat_q30()         angles -> quaternion
 *   qo_euler_from_quat_q30()       quaternion -> angles, scipy ranges, default lock band
 *   qo_euler_from_quat_band_q30()  the same with a caller-chosen lock band
 *   qo_euler_from_quat_near_q30()  quaternion -> the solution nearest previous angles (joints)
 *   qo_euler_from_quat_fast_q30()  quaternion -> angles, fast tier (Cortex-M0), a few LSB off
 * The sequence type qo_euler_seq and its helpers (qo_euler_seq_parse, _name, _is_intrinsic,
 * _is_proper) are qorient/euler_seq.h's, shared by both cores (lib/src/euler_seq.c: no float,
 * part of the fixed-only build too).
 *
 * Conventions: exactly those of qorient/euler.h (scipy's names: lower case extrinsic, upper
 * case intrinsic; a1, a2, a3 belong to the axes in the order written; extrinsic "xyz" is
 * q = q_z(a3) q_y(a2) q_x(a1), intrinsic "XYZ" is q = q_X(a1) q_Y(a2) q_Z(a3); Tait-Bryan
 * singular at a2 = +-pi/2, proper Euler at a2 = 0 and pi, including the identity). Ranges
 * returned by qo_euler_from_quat_q30 / _band_q30: a1, a3 in [-QO_Q28_PI, QO_Q28_PI]; a2 in
 * [-QO_Q28_HALF_PI, QO_Q28_HALF_PI] (Tait-Bryan) or [0, QO_Q28_PI] (proper).
 *
 * Gimbal lock, as in euler.h: margin = angle (Q3.28 rad, [0, pi/2]) between the middle angle
 * and its nearest singular value; locked = (margin <= band). At lock a3 = 0 and a1 takes the
 * whole determined sum/difference (scipy's choice), so the angles still compose to q exactly
 * at the singularity and within 2*asin(2 sin(margin/2)) ~= 2*margin inside the band. The
 * middle angle is never snapped.
 *
 * Why QO_EULER_LOCK_BAND_Q28 is 27 LSB = 1.006e-7 rad (the float core's 2e-6, re-derived for
 * Q1.30 noise; the reasoning is the same):
 *   - The middle angle and the margin come straight from the quaternion as atan2 of two
 *     norms, so component noise moves the margin LINEARLY: k LSB of Q1.30 on each component
 *     of an exactly singular unit quaternion give a margin of at most about 4k/2^30 rad, i.e.
 *     k LSB of Q3.28. An exactly singular rotation rounded from double to Q1.30, built by
 *     qo_euler_to_quat_q30 with the Q3.28 nearest pi/2 (or pi), or with every component then
 *     moved by up to 2 LSB (upstream fixed-point noise), is flagged
 *     (tests/core/test_euler.c: test_exactly_singular_all24; the largest margins seen:
 *     docs/FIGURES.md, accuracy, accuracy_euler_fx). By the linear rule above, 27 LSB also
 *     flags singular Q1.30 inputs whose components are off by up to ~25 LSB (a normalised
 *     filter output, a product of a few quaternions).
 *   - A flagged input recomposes within 2*margin <= 2e-7 rad, inside the 1e-5 goal. A larger
 *     band only loosens that bound: outside it the full decomposition recomposes within
 *     5e-8 rad however close to lock (test_just_off_singular_all24), because every product
 *     is exact in int64.
 *   - 1e-7 rad is 5.8e-6 degrees: the flag is never raised anywhere near 2 degrees away.
 *   A quaternion that carries FLOAT32 noise (converted from the float core with fxconv.h)
 *   sits up to ~4e-7 rad off an exact singularity: pass the float core's band, 537 LSB
 *   (= 2e-6 rad, the Q3.28 value of QO_EULER_LOCK_BAND_F32), to the _band_q30 / _near_q30
 *   forms if such inputs must be flagged. A gimbal that wants a wider hold zone passes its own
 *   band likewise and accepts the 2*margin bound.
 *
 * Inputs: any non-zero Q1.30 quaternion, unit or not, every int32 component value including
 * INT32_MIN and INT32_MAX (saturated upstream values): only ratios of the components are used.
 * The quaternion is scaled by a power of two so its largest component is in (0.5, 1] (exact
 * for every input whose components are below 1.0; a component >= 1.0 loses its last bit,
 * 1e-9 relative). q and -q give bit-identical angles (every rounding is odd-symmetric).
 * from_euler takes any Q3.28 angle (the whole int32 range, [-8, 8) rad; angles are periodic).
 *
 * Method and accuracy: the float core's (Bernardes & Viollet 2022, one atan2 per angle, no
 * asin/acos, a1 fitted at lock) in integer arithmetic. After the power-of-two scaling every
 * product of the decomposition is exact in int64; its roundings are two correctly rounded
 * square roots, the reduction of each atan2 argument pair to 30 significant bits and the
 * atan2 itself (<= 1 LSB, qorient/fxmath.h). The fit at lock and from_euler round each
 * quaternion product once (at 2^-30 or finer). Bounds checked by tests/core/test_euler.c on
 * fixed-seed cases in all 24 conventions (the Q3.28 result composed in double vs the Q1.30
 * input): from_euler within 1e-8 per component (test_from_euler_random_all24); to_euler
 * <= 5e-8 rad generic (test_to_euler_random_rotations_all24), at exact lock
 * (test_exactly_singular_all24) and near lock outside the band (test_just_off_singular_all24),
 * <= 2*margin + 5e-8 inside the band; to_euler_near <= 1e-7 off lock
 * (test_near_through_singularity_all24). Goals: 1e-6 generic, 1e-5 at/near lock. The worst
 * errors measured (bench/accuracy_euler_fx, 20000 cases x 24 conventions), beside the float
 * core's: docs/FIGURES.md, accuracy.
 * Cost (Cortex-M0+, arm-none-eabi-gcc -O2): code and stack of the module in docs/FIGURES.md,
 * sizes (tools/size-report.sh; the deepest path is the nearest variant at lock); libgcc's
 * 64-bit multiply and divide helpers only. Every function is pure (no state, reentrant).
 */
#ifndef QORIENT_EULER_FX_H
#define QORIENT_EULER_FX_H

#include "qorient/euler_seq.h"
#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Three angles in radians, Q3.28 (range [-8, 8), LSB 3.7e-9 rad): a1 about the first axis
 * named by the sequence, a2 the second, a3 the third. */
typedef struct qo_euler_q28 { qo_q28 a1, a2, a3; } qo_euler_q28;

/* Gimbal-lock report of one decomposition.
 *   locked: 1 when margin <= the lock band in use (then a3 was chosen, not measured), else 0.
 *   margin: Q3.28 rad in [0, QO_Q28_HALF_PI], between the middle angle and the nearest
 *           singular value (+-pi/2 Tait-Bryan; 0 or pi proper). A property of the rotation and
 *           the sequence, not of the band: callers may apply their own threshold to it. */
typedef struct qo_euler_info_q28 { int locked; qo_q28 margin; } qo_euler_info_q28;

/* Default lock band of qo_euler_from_quat_q30: 27 LSB of Q3.28 = 1.006e-7 rad (justified in
 * the file comment above). */
#define QO_EULER_LOCK_BAND_Q28 ((qo_q28)27)

/*
 * Quaternion (Q1.30) of the rotation given by Euler angles e (Q3.28 rad, any value) in
 * convention seq: the product of the three elementary half-angle quaternions in composition
 * order, the product's sign (not canonicalised; the same as qo_euler_to_quat_f32 and
 * scipy). Each component within a few LSB of the exact value; never saturates.
 * Returns QO_OK; QO_E_NULL (out NULL); QO_E_ARG (seq not one of the 24). On error *out is
 * the identity (QO_Q30_ONE, 0, 0, 0).
 */
qo_status qo_euler_to_quat_q30(qo_euler_seq seq, qo_euler_q28 e, qo_quat_q30 *out);

/*
 * Euler angles (Q3.28) of the rotation q in convention seq, scipy's ranges (file comment),
 * lock band QO_EULER_LOCK_BAND_Q28. q need not be unit; q and -q give the same result.
 * At lock (info.locked == 1): a3 = 0 and a1 carries the rest; a2 as measured.
 * info may be NULL. Returns QO_OK; QO_E_NULL (out NULL); QO_E_ARG (bad seq); QO_E_DEGENERATE
 * (all four components are zero; any other input is fine). Checked in that order. On error
 * *out = (0, 0, 0) and *info = { 0, 0 }.
 */
qo_status qo_euler_from_quat_q30(qo_quat_q30 q, qo_euler_seq seq, qo_euler_q28 *out,
                               qo_euler_info_q28 *info);

/*
 * As qo_euler_from_quat_q30 with the lock band band_rad (Q3.28 rad, in [0, QO_Q28_HALF_PI]; 0
 * flags only a computed margin of exactly 0, which every quaternion with a zero norm pair
 * has; QO_Q28_HALF_PI flags everything). The composed result is within 2*margin of q when
 * locked. Returns as qo_euler_from_quat_q30, plus QO_E_RANGE for a band outside
 * [0, QO_Q28_HALF_PI] (checked after QO_E_DEGENERATE). On error *out = (0, 0, 0) and
 * *info = { 0, 0 }.
 */
qo_status qo_euler_from_quat_band_q30(qo_quat_q30 q, qo_euler_seq seq, qo_q28 band_rad,
                                    qo_euler_q28 *out, qo_euler_info_q28 *info);

/*
 * Euler angles of q nearest the previous joint angles prev (Q3.28), for joints that must not
 * jump: the rule of qo_euler_from_quat_near_f32. Of the two solutions (a1, a2, a3) and
 * (a1 + pi, pi - a2, a3 + pi) (Tait-Bryan) or (a1 + pi, -a2, a3 + pi) (proper), each angle
 * moved by the multiple of 2pi nearest the same angle of prev, the one with the smaller sum of
 * squared differences to prev (the first on a tie). Sums with pi and 2pi are exact at 2^-56
 * and rounded once. Outputs are NOT limited to [-pi, pi] - but Q3.28 ends at +-8 rad: an
 * output whose nearest value would reach 8 rad is returned one turn (2pi) nearer zero instead,
 * still composing to q, and the status is QO_E_OVERFLOW. A joint that turns on and on must
 * therefore re-wrap prev (qo_fx_wrap_pi_q28) before it passes 8 - pi = 4.86 rad.
 * At lock (margin <= band, Q3.28 in [0, QO_Q28_HALF_PI]): a3 = prev.a3 exactly, a2 the
 * measured middle angle of the branch nearer prev.a2, a1 the best fit given those (unwrapped
 * toward prev.a1). Composes to q exactly at the singularity, within 2*margin inside the band.
 * info may be NULL. Returns QO_OK; QO_E_NULL (out NULL); QO_E_ARG (bad seq); QO_E_DEGENERATE
 * (q zero); QO_E_RANGE (band outside [0, QO_Q28_HALF_PI]); QO_E_OVERFLOW (an output was taken
 * one turn back as above; *out and *info are the valid decomposition just described). On the
 * other errors *out = prev (hold the joint) and *info = { 0, 0 }.
 */
qo_status qo_euler_from_quat_near_q30(qo_quat_q30 q, qo_euler_seq seq, qo_euler_q28 prev,
                                    qo_q28 band, qo_euler_q28 *out, qo_euler_info_q28 *info);

/*
 * The fast tier of qo_euler_from_quat_band_q30, for cores without a 64-bit multiply
 * (Cortex-M0/M0+): the same conventions, ranges, lock band rule, lock choice (a3 = 0) and
 * statuses, from 32-bit arithmetic: three atan2 and one square root, no quaternion product
 * (lib/src/euler_fx.c). Not bit-identical to the exact function: each angle within a few LSB
 * of Q3.28. The composed result vs the Q1.30 input: within 5e-8 rad generic and at exact lock
 * (goal 2e-7), inside the band <= 2*margin (a1 is then twice the argument of the determined
 * component pair, not a fit): tests/core/test_euler.c runs every shared to_euler test body on
 * it with these bounds (the worst measured by bench/accuracy_euler_fx: docs/FIGURES.md,
 * accuracy). q need not be unit (a component of +-1.0 or beyond costs one bit);
 * q and -q give the same bits. Pass QO_EULER_LOCK_BAND_Q28 for the default band. Its
 * instructions on Cortex-M0 beside the exact function's: docs/FIGURES.md, m0
 * (tools/qemu-icount.sh).
 * Returns QO_OK; QO_E_NULL (out NULL); QO_E_ARG (bad seq); QO_E_DEGENERATE (q zero);
 * QO_E_RANGE (band outside [0, QO_Q28_HALF_PI]), checked in that order. On error
 * *out = (0, 0, 0) and *info = { 0, 0 }. info may be NULL.
 */
qo_status qo_euler_from_quat_fast_q30(qo_quat_q30 q, qo_euler_seq seq, qo_q28 band_rad,
                                    qo_euler_q28 *out, qo_euler_info_q28 *info);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_EULER_FX_H */
