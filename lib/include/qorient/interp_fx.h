/* parity fixed (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   interp.lerp             qo_interp_lerp_q30
 *   interp.nlerp            qo_interp_nlerp_q30
 *   interp.slerp            qo_interp_slerp_q30
 *   interp.slerp_fast       qo_interp_slerp_fast_q30
 *   interp.slerp_long       qo_interp_slerp_long_q30
 *   interp.slerp_rate       qo_interp_slerp_rate_q30 (duration Q16.16 s, omega Q16.16 rad/s)
 *   interp.align_keys       qo_interp_align_keys_q30
 *   interp.bezier           qo_interp_bezier_q30
 *   interp.bezier3          qo_interp_bezier3_q30
 *   interp.spline_controls  qo_interp_spline_controls_q30
 *   interp.spline_eval      qo_interp_spline_eval_q30
 *   interp.squad            qo_interp_squad_q30
 *   interp.squad_controls   qo_interp_squad_controls_q30
 */
/*
 * qorient/interp_fx.h - interpolation of orientations on the unit-quaternion sphere, fixed
 * point (Q1.30 quaternions). The fixed-point mirror of qorient/interp.h: same names with the
 * _q30 suffix, same constructions, signs, endpoint and degenerate-case rules. Integer
 * arithmetic only (int32 values, int64 intermediates): no float, no double, no libm.
 *
 * Conventions: see qorient/types.h (scalar-first, Hamilton, active, right-handed). Angles are
 * radians. A "4-D angle" is the angle between two unit quaternions seen as points of the
 * 3-sphere; the rotation angle between the orientations is twice the 4-D angle.
 *
 * Index:
 *   QO_INTERP_SLERP_NEAR_PI_Q28          4-D angle from antipodal below which two points have no circle
 *   QO_INTERP_BEZIER_MAX_POINTS  largest control polygon qo_interp_bezier_q30 accepts (stack array)
 *   qo_interp_lerp_q30            component-wise lerp, not normalised
 *   qo_interp_nlerp_q30           normalised lerp, short way
 *   qo_interp_slerp_q30           spherical linear interpolation, short way, exact endpoints
 *   qo_interp_slerp_fast_q30      the same to ~5e-8 rad with no square root or division (fast tier)
 *   qo_interp_slerp_long_q30      spherical linear interpolation the long way
 *   qo_interp_slerp_rate_q30      constant angular velocity of the slerp over a duration
 *   qo_interp_align_keys_q30      copy of keyframes, normalised and made sign-continuous
 *   qo_interp_bezier_q30          Bezier curve on the sphere (de Casteljau with slerp), n points
 *   qo_interp_bezier3_q30         cubic Bezier on the sphere (4 control points)
 *   qo_interp_spline_controls_q30 Shoemake C1 spline through N keys: inner control points a, b
 *   qo_interp_spline_eval_q30     evaluate that spline at s in [0, N-1] (Q16.16)
 *   qo_interp_squad_q30           Squad segment between two keys with their inner quadrangle points
 *   qo_interp_squad_controls_q30  Squad inner points s_i for N keys (exp/log of qorient/quat_fx.h)
 *
 * Formats: quaternions Q1.30 (qo_quat_q30, components in [-2, 2)); the interpolation
 * parameter t is Q1.30 with the valid range [0, QO_Q30_ONE] (raw 0 .. 2^30), so t == 1 is
 * exactly representable; the spline parameter s is Q16.16 segment coordinates (one unit per
 * segment, raw 0 .. (n-1) * 65536).
 *
 * Common rules of this module (as interp.h, minus NaN/Inf which fixed point cannot hold):
 *   - Quaternion inputs that describe orientations (everything except qo_interp_lerp_q30) are
 *     normalised first, any non-zero length accepted (from 1 LSB up to a norm of 4, every
 *     component INT32_MIN); a zero input gives QO_E_DEGENERATE with *out = identity.
 *   - Inputs are normalised by qo_quat_normalize_q30 (qorient/quat_fx.h: within 1 LSB per
 *     component, the sign kept; a Q1.30 input that is already unit within rounding may come
 *     back with its last bit changed, exactly representable unit quaternions such as the
 *     identity or (1/2, 1/2, 1/2, 1/2) come back unchanged). "unit a" below means exactly
 *     qo_quat_normalize_q30(a). Internal 64-bit sums are normalised by the same method.
 *   - Interpolation parameters outside their range are an error (QO_E_RANGE), never clamped
 *     or extrapolated; the output is then the documented end value (usually unit a).
 *   - The output is always written when its pointer is not NULL, also on error.
 *   - Signs: q and -q are the same rotation. "Short way" means b is replaced by -b when
 *     dot(a, b) < 0 (the dot product is exact in 64 bits, so dot == 0 is exact too).
 *   - Accuracy vs double on the same Q1.30 inputs: slerp, nlerp and the spline at its keys
 *     within 3e-8 rad, Bezier within 6e-8, results unit length within 3e-9, checked by
 *     tests/core/test_interp.c (its fixed row; test_slerp_random_vs_double,
 *     test_slerp_edge_table, test_nlerp, test_bezier, test_spline_vs_double_and_through_keys).
 *     The worst measured by bench/accuracy_interp_fx.c, beside the float32
 *     core's on the same cases: docs/FIGURES.md, accuracy. The 4-D angle comes
 *     from qo_fx_atan2_q28 (1 LSB = 3.7e-9 rad); the weights sin(u th)/th come from a
 *     degree-20 sinc series in Q1.31 with 64-bit products, accurate in RELATIVE terms however
 *     small th is.
 *   - No heap, no static state; all storage is the caller's or a bounded stack array.
 *   - Cost on Cortex-M0+ (arm-none-eabi-gcc -O2, -fstack-usage): code and stack of the module
 *     interp_fx (plus fxmath, quat_fx) in docs/FIGURES.md, sizes (tools/size-report.sh); the
 *     deepest stack path is qo_interp_bezier_q30 -> de Casteljau -> slerp -> normalise. The only divisions are
 *     64-bit integer ones (__aeabi_uldivmod on Cortex-M0+).
 */
#ifndef QORIENT_INTERP_FX_H
#define QORIENT_INTERP_FX_H

#include <stddef.h>

#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 4-D angle (Q3.28 radians; 268435 = 1e-3 rad, the value of QO_INTERP_SLERP_SERIES_ANGLE in interp.h)
 * between a point and the antipode of another below which the internal great-circle slerp of
 * the Bezier and spline constructions treats the pair as having no circle (the float32 rule):
 * de Casteljau keeps the first point, the spline's bisector falls back to the key. The public
 * slerp never meets it: after the short-way flip its 4-D angle is at most pi/2. */
#define QO_INTERP_SLERP_NEAR_PI_Q28 ((qo_q28)268435)

/* Largest number of control points qo_interp_bezier_q30 takes (the same value and name as in
 * interp.h; an identical redefinition, so a divergence is a compile error where both are
 * included). The de Casteljau pyramid is one stack array of this many quaternions. */
#define QO_INTERP_BEZIER_MAX_POINTS 8

/* Component-wise linear interpolation a + t*(b - a) (= (1-t)*a + t*b), each component
 * rounded once to nearest (ties toward +inf). No normalisation and no sign flip (a building
 * block, not a rotation interpolator). Never overflows: each result component lies between
 * the two input components. t in [0, QO_Q30_ONE]; t == 0 gives a exactly, t == QO_Q30_ONE
 * gives b exactly. Zero quaternions are accepted (plain arithmetic).
 * Returns QO_OK; QO_E_NULL (out NULL, nothing written); QO_E_RANGE if t is outside
 * [0, QO_Q30_ONE] (*out = a). */
qo_status qo_interp_lerp_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out);

/* Normalised lerp: a and b are normalised, b is replaced by -b when dot(a, b) < 0 (short way),
 * then out = normalise((1-t)*a + t*b), the sum formed exactly in 64 bits. Same path as slerp,
 * but the angular rate is not constant (see qo_interp_nlerp_f32). t == 0 gives unit a,
 * t == QO_Q30_ONE the (possibly negated) unit b, exactly. The middle is always defined: after
 * the flip dot >= 0, so the sum has length >= 1/sqrt(2).
 * Returns QO_OK; QO_E_NULL (out NULL, nothing written); QO_E_DEGENERATE if a or b is zero
 * (*out = identity); QO_E_RANGE if t is outside [0, QO_Q30_ONE] (*out = unit a). */
qo_status qo_interp_nlerp_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out);

/* Spherical linear interpolation, short way, constant angular rate:
 *   a, b normalised; b' = (dot(a, b) < 0) ? -b : b;  th = 4-D angle between a and b' in [0, pi/2]
 *   out = normalise(sin((1-t) th)/th * a + sin(t th)/th * b')
 * (the common factor 1/sin(th) of the textbook weights is dropped: normalising removes it).
 * The rotation from a to out is t times the rotation from a to b.
 * th is 2*atan2(|a - b'|, |a + b'|) with both lengths from exact 64-bit sums of squares, so it
 * keeps its absolute accuracy (a few 1e-9 rad) at th -> 0, where acos(dot) of a Q1.30 dot
 * product would give 0 for every th below 3e-5. The weights w(u) = sin(u th)/th = u * sinc(u th)
 * come from the Taylor series of sinc (degree 20, truncation < 1e-11) evaluated in Q1.31 with
 * 64-bit products: no division by a vanishing sin(th), and no separate small-angle branch;
 * identical inputs (th == 0) give w(u) = u exactly, i.e. the normalised lerp, which is a.
 * The flipped b' is used throughout, so q and -q (the same rotation) interpolate to that
 * rotation, unit length.
 * Endpoints are exact: t == 0 returns unit a, t == QO_Q30_ONE returns unit b' - i.e. -(unit b)
 * when dot(a, b) < 0 (the sign nearest a), else unit b.
 * Exactly 180 deg apart (dot == 0 exactly, th = pi/2) is not special: b is kept (no flip) and
 * the path is the great circle through a and b, one of the two equally short rotations.
 * Returns QO_OK; QO_E_NULL (out NULL, nothing written); QO_E_DEGENERATE if a or b is zero
 * (*out = identity); QO_E_RANGE if t is outside [0, QO_Q30_ONE] (*out = unit a). */
qo_status qo_interp_slerp_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out);

/* The fast tier of qo_interp_slerp_q30 for cores without a 64-bit multiply or divider
 * (Cortex-M0/M0+): the inputs through qo_quat_normalize_fast_q30, then
 * out = cos(t th) a + sin(t th) e with e the unit direction of b' - cos(th) a (orthogonal to
 * a), th = atan2(|b' - cos(th) a|, cos th) from the Q1.30 dot product, one sincos: no square
 * root, no division, no 64-bit multiply from libgcc. The same contract as qo_interp_slerp_q30
 * (sign flip to the short way, exact endpoints t == 0 -> unit a and t == 1 -> unit b',
 * statuses and outputs on error), but "unit" is normalize_fast's (within 16 LSB), and the
 * result is within 5e-8 rad of the exact slerp of the inputs (checked in
 * tests/core/test_interp.c and measured by bench/accuracy_interp_fx.c), never beyond +-1.0.
 * a == b' to rounding gives unit a. */
qo_status qo_interp_slerp_fast_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out);

/* Spherical linear interpolation the LONG way, the twin of qo_interp_slerp_long_f32: like
 * qo_interp_slerp_q30 but b' = (dot(a, b) > 0) ? -b : b, so the path is the rotation of angle
 * 2 pi - phi (phi the short rotation angle) about the opposite sense of the same axis. For
 * dot == 0 (exact in 64 bits) b is kept. When a and b are the same rotation within 2e-3 rad
 * (phi < 2 * 1e-3, the 4-D angle of a and b' within QO_INTERP_SLERP_NEAR_PI_Q28 of pi) the plane of
 * the full turn is undefined: QO_E_DEGENERATE with *out = unit a (the float32 rule and limit).
 * Endpoints: t == 0 gives unit a, t == QO_Q30_ONE unit b' exactly.
 * Returns QO_OK; QO_E_NULL (out NULL, nothing written); QO_E_DEGENERATE if a or b is zero
 * (*out = identity) or the same rotation (*out = unit a); QO_E_RANGE if t is outside
 * [0, QO_Q30_ONE] (*out = unit a). */
qo_status qo_interp_slerp_long_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q30 t, qo_quat_q30 *out);

/* Angular velocity of qo_interp_slerp_q30(a, b, t) when t runs from 0 to 1 in `duration`
 * (Q16.16 seconds), the twin of qo_interp_slerp_rate_f32: constant, in the BODY frame,
 * omega = 2 log(conj(a) b') / duration (Q16.16 rad/s, b' the short-way b); |omega| = rotation
 * angle / duration. The half-angle vector comes from qo_quat_log_q30 (Q3.28) and is divided
 * once, rounded to nearest: within 1 LSB of Q16.16 (1.5e-5 rad/s) plus the log's 1.5 LSB of
 * Q3.28 scaled by 2/duration.
 * Returns QO_OK; QO_E_NULL (omega NULL, nothing written); QO_E_DEGENERATE (a or b zero);
 * QO_E_RANGE (duration <= 0, or a rate beyond the Q16.16 range: a duration below about
 * pi / 32768 s). *omega = (0, 0, 0) on every error. */
qo_status qo_interp_slerp_rate_q30(qo_quat_q30 a, qo_quat_q30 b, qo_q16 duration,
                                 qo_vec3_q16 *omega);

/* Writes out[i] = keys[i] normalised and sign-aligned: out[0] = unit keys[0] and each
 * following key is negated when its dot product with the previous ALIGNED key is negative.
 * The rotations are unchanged; consecutive keys are then at most 180 deg of rotation apart on
 * the short way. This is the key sequence the spline functions below use internally.
 * out may be the same array as keys (in-place); other overlaps are not allowed.
 * Returns QO_OK; QO_E_NULL (keys or out NULL; out, when not NULL, is filled with n
 * identities); QO_E_TOO_FEW (n == 0); QO_E_DEGENERATE (a key is zero; out is filled with
 * identities). */
qo_status qo_interp_align_keys_q30(const qo_quat_q30 *keys, size_t n, qo_quat_q30 *out);

/* Bezier curve on the sphere through its end points, de Casteljau's construction with slerp
 * in place of linear interpolation (Shoemake 1985), as qo_interp_bezier_f32: ctrl[0..n-1] are
 * normalised and sign-aligned as in qo_interp_align_keys_q30 (so the caller's signs do not
 * change the curve), then each level slerps neighbours with parameter t without further flips
 * (which keeps the curve continuous in t); a pair inside the pyramid that is within
 * QO_INTERP_SLERP_NEAR_PI_Q28 of antipodal has no circle and keeps its first point.
 * 2 <= n <= QO_INTERP_BEZIER_MAX_POINTS; n == 2 is qo_interp_slerp_q30.
 * t in [0, QO_Q30_ONE]; t == 0 gives unit ctrl[0] exactly, t == QO_Q30_ONE the last aligned
 * control point exactly (unit ctrl[n-1] or its negative, whichever the alignment chose).
 * Returns QO_OK; QO_E_NULL (out NULL: nothing written; ctrl NULL: *out = identity);
 * QO_E_TOO_FEW (n < 2), QO_E_CAPACITY (n > QO_INTERP_BEZIER_MAX_POINTS), QO_E_DEGENERATE (a control
 * point is zero): *out = identity; QO_E_RANGE (t outside [0, QO_Q30_ONE]): *out = unit
 * ctrl[0]. */
qo_status qo_interp_bezier_q30(const qo_quat_q30 *ctrl, size_t n, qo_q30 t, qo_quat_q30 *out);

/* Cubic Bezier on the sphere: qo_interp_bezier_q30 with the four control points q0..q3.
 * Same rules, statuses and outputs (n is 4). */
qo_status qo_interp_bezier3_q30(qo_quat_q30 q0, qo_quat_q30 q1, qo_quat_q30 q2, qo_quat_q30 q3,
                              qo_q30 t, qo_quat_q30 *out);

/* Inner control points of Shoemake's C1 Bezier spline through n keyframes, exactly the
 * construction of qo_interp_spline_controls_f32 (see there for the formulas, the end rule and
 * its "starts and ends at rest" consequence). In short, on the aligned unit keys q_i and with
 * Slerp(p, q, u) the great-circle interpolation, no flip, u outside [0, 1] allowed:
 *   interior: abar_i = Slerp(Slerp(q_{i-1}, q_i, 2), q_{i+1}, 1/2),
 *             a_i = Slerp(q_i, abar_i, 1/3),  b_i = Slerp(q_i, abar_i, -1/3)
 *   ends (n >= 3): a_0 = Slerp(q_0, Slerp(q_2, q_1, 2), 1/3),
 *                  b_{n-1} = Slerp(q_{n-1}, Slerp(q_{n-3}, q_{n-2}, 2), 1/3)
 *   unused, written for definiteness: b_0 = q_0, a_{n-1} = q_{n-1}
 *   n == 2: a_0 = Slerp(q_0, q_1, 1/3), b_1 = Slerp(q_0, q_1, 2/3) (the spline is the slerp).
 * The fractions 1/3, 2/3, -1/3 are Q1.30 constants rounded to nearest (1/3 -> 357913941,
 * error 3e-10, far below the result's rounding).
 * If abar_i is undefined because Slerp(q_{i-1}, q_i, 2) is within QO_INTERP_SLERP_NEAR_PI_Q28 of
 * antipodal to q_{i+1} (a 180 deg swing out and back), abar_i = q_i: zero velocity at that key.
 * Segment i (from q_i to q_{i+1}) is the cubic Bezier q_i, a_i, b_{i+1}, q_{i+1}.
 * a and b are caller arrays of n entries each; they must not overlap keys or each other.
 * Returns QO_OK; QO_E_NULL (keys, a or b NULL: the non-NULL outputs are filled with n
 * identities); QO_E_TOO_FEW (n < 2), QO_E_DEGENERATE (a key is zero): a and b filled with
 * identities. */
qo_status qo_interp_spline_controls_q30(const qo_quat_q30 *keys, size_t n,
                                      qo_quat_q30 *a, qo_quat_q30 *b);

/* Evaluates the spline of qo_interp_spline_controls_q30 at s (Q16.16 segment coordinates) in
 * [0, n-1]: segment i = floor(s) (i = n-2 for s == n-1), local parameter t = frac(s) (exact:
 * the 16 fraction bits shifted to Q1.30), cubic Bezier q_i, a_i, b_{i+1}, q_{i+1} by
 * de Casteljau with slerp. keys, a, b are the arrays given to / written by
 * qo_interp_spline_controls_q30 (keys may be the caller's unaligned ones: each segment's key
 * signs are re-aligned to a_i and b_{i+1}, so the result is the curve through the aligned
 * keys). At s == i exactly the result is the aligned unit key q_i. Output sign: that of the
 * aligned key sequence (which starts with the sign of keys[0]).
 * Only the four points of the evaluated segment are checked and normalised.
 * Returns QO_OK; QO_E_NULL (out NULL: nothing written; keys, a or b NULL: *out = identity);
 * QO_E_TOO_FEW (n < 2: *out = identity); QO_E_DEGENERATE (zero segment point:
 * *out = identity); QO_E_RANGE for s outside [0, n-1]: *out = the nearest end key, normalised
 * (keys[0] for s < 0, keys[n-1] for s > n-1), or identity if that key is zero. */
qo_status qo_interp_spline_eval_q30(const qo_quat_q30 *keys, const qo_quat_q30 *a,
                                  const qo_quat_q30 *b, size_t n, qo_q16 s, qo_quat_q30 *out);

/* Squad segment (Shoemake 1987) from key q0 to key q1 with inner quadrangle points s0, s1
 * (from qo_interp_squad_controls_q30):
 *   out = Slerp(Slerp(q0, q1, t), Slerp(s0, s1, t), 2t(1-t)),
 * as qo_interp_squad_f32: all four normalised; q1 aligned to q0, s0 to q0 and s1 to q1, the
 * inner slerps without further flips, so the result does not depend on the caller's signs.
 * 2t(1-t) is formed exactly in 64 bits and rounded once to Q1.30.
 * t == 0 gives unit q0, t == QO_Q30_ONE the aligned unit q1, exactly.
 * Returns QO_OK; QO_E_NULL (out NULL, nothing written); QO_E_DEGENERATE (zero input,
 * *out = identity); QO_E_RANGE (t outside [0, QO_Q30_ONE], *out = unit q0). */
qo_status qo_interp_squad_q30(qo_quat_q30 q0, qo_quat_q30 s0, qo_quat_q30 s1, qo_quat_q30 q1,
                            qo_q30 t, qo_quat_q30 *out);

/* Squad inner points for n keys, as qo_interp_squad_controls_f32: with q_i the aligned keys
 * (qo_interp_align_keys_q30),
 *   s_i = q_i * exp(-(log(q_i^-1 q_{i+1}) + log(q_i^-1 q_{i-1})) / 4),  0 < i < n-1,
 *   s_0 = q_0, s_{n-1} = q_{n-1}   (zero end tangents),
 * with qo_quat_log_q30 / qo_quat_exp_q30 (vector parts in Q3.28 radians; the quarter sum is
 * rounded once per component) and the product normalised. Segment i is then
 * qo_interp_squad_q30(q_i, s_i, s_{i+1}, q_{i+1}, t). These tangents assume evenly spaced keys
 * (the classic formula); Squad is C1 only for them.
 * s is a caller array of n entries, not overlapping keys.
 * Returns QO_OK; QO_E_NULL (keys or s NULL; s, when not NULL, filled with n identities);
 * QO_E_TOO_FEW (n < 2), QO_E_DEGENERATE (a key is zero): s filled with identities. */
qo_status qo_interp_squad_controls_q30(const qo_quat_q30 *keys, size_t n, qo_quat_q30 *s);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_INTERP_FX_H */
