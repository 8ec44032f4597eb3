/* parity float32 (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   interp.lerp             qo_interp_lerp_f32
 *   interp.nlerp            qo_interp_nlerp_f32
 *   interp.slerp            qo_interp_slerp_f32
 *   interp.slerp_fast       - the fast tier is a fixed-point option (no divide on Cortex-M0)
 *   interp.slerp_long       qo_interp_slerp_long_f32
 *   interp.slerp_rate       qo_interp_slerp_rate_f32
 *   interp.align_keys       qo_interp_align_keys_f32
 *   interp.bezier           qo_interp_bezier_f32
 *   interp.bezier3          qo_interp_bezier3_f32
 *   interp.spline_controls  qo_interp_spline_controls_f32
 *   interp.spline_eval      qo_interp_spline_eval_f32
 *   interp.squad            qo_interp_squad_f32
 *   interp.squad_controls   qo_interp_squad_controls_f32
 */
/*
 * qorient/interp.h - interpolation of orientations on the unit-quaternion sphere, float32.
 *
 * Conventions: see qorient/types.h (scalar-first, Hamilton, active, right-handed).
 * Angles are radians. A "4-D angle" is the angle between two unit quaternions seen as points
 * of the 3-sphere; the rotation angle between the orientations is twice the 4-D angle.
 *
 * Index:
 *   QO_INTERP_SLERP_SERIES_ANGLE  4-D angle below which slerp_long, Bezier, ... use a small-angle series
 *   QO_INTERP_BEZIER_MAX_POINTS  largest control polygon qo_interp_bezier_f32 accepts (stack array)
 *   qo_interp_lerp_f32            component-wise lerp, not normalised
 *   qo_interp_nlerp_f32           normalised lerp, short way
 *   qo_interp_slerp_f32           spherical linear interpolation, short way, exact endpoints
 *   qo_interp_slerp_long_f32      spherical linear interpolation, the long way (explicit)
 *   qo_interp_slerp_rate_f32      the constant body-frame angular velocity of a timed slerp
 *   qo_interp_align_keys_f32      copy of keyframes, normalised and made sign-continuous
 *   qo_interp_bezier_f32          Bezier curve on the sphere (de Casteljau with slerp), n points
 *   qo_interp_bezier3_f32         cubic Bezier on the sphere (4 control points)
 *   qo_interp_spline_controls_f32 Shoemake C1 spline through N keys: inner control points a, b
 *   qo_interp_spline_eval_f32     evaluate that spline at s in [0, N-1]
 *   qo_interp_squad_f32           Squad segment between two keys with their inner quadrangle points
 *   qo_interp_squad_controls_f32  Squad inner points s_i for N keys
 *
 * Common rules of this module:
 *   - Quaternion inputs that describe orientations (everything except qo_interp_lerp_f32) are
 *     normalised first; a zero input gives QO_E_DEGENERATE, a NaN/Inf one QO_E_NONFINITE.
 *   - Interpolation parameters (t, s) outside their documented range are an error
 *     (QO_E_RANGE), never silently clamped or extrapolated; NaN/Inf parameters give
 *     QO_E_NONFINITE. Either way the output is the documented end value (usually a).
 *   - The output is always written when its pointer is not NULL, also on error.
 *   - Signs: q and -q are the same rotation. "Short way" means b is replaced by -b when
 *     dot(a, b) < 0, so the path is the smaller rotation (<= pi). Each function says which sign
 *     it returns.
 *   - Results are unit length within 1e-6 (checked by tests/core/test_interp.c on every slerp,
 *     slerp_long, nlerp, Bezier, spline and Squad case; the worst measured: docs/FIGURES.md, accuracy).
 *   - No heap, no static state; all storage is the caller's or a bounded stack array.
 */
#ifndef QORIENT_INTERP_H
#define QORIENT_INTERP_H

#include <stddef.h>

#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* 4-D angle (radians, between the two unit inputs after the short-way flip) below which
 * slerp_long, Bezier, the spline controls and squad (not qo_interp_slerp_f32, whose weights are
 * always a series) evaluate their weights sin((1-t)th)/sin(th), sin(t th)/sin(th) by the series
 * w(u) = u * (1 + (1 - u^2) th^2 / 6), whose truncation error (< th^4 / 40 < 3e-14) is far below
 * float resolution, instead of dividing by a vanishing sin(th). The result is normalised after
 * either branch. 1e-3 rad of 4-D angle is 2e-3 rad (0.11 deg) of rotation. */
#define QO_INTERP_SLERP_SERIES_ANGLE 1e-3f

/* Largest number of control points qo_interp_bezier_f32 takes. The de Casteljau pyramid is kept
 * in one stack array of this many quaternions (16 bytes each: 128 bytes for 8). */
#define QO_INTERP_BEZIER_MAX_POINTS 8

/* Component-wise linear interpolation (1-t)*a + t*b. No normalisation and no sign flip: the
 * result is generally not unit length (it is a building block, not a rotation interpolator).
 * t in [0, 1]; t == 0 gives a exactly, t == 1 gives b exactly.
 * Returns QO_OK; QO_E_NULL (out NULL, nothing written); QO_E_NONFINITE if a or b has a NaN/Inf
 * component (*out = identity) or t is NaN/Inf (*out = a); QO_E_RANGE if t is outside [0, 1]
 * (*out = a). Zero quaternions are accepted (plain arithmetic). */
qo_status qo_interp_lerp_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out);

/* Normalised lerp: a and b are normalised, b is replaced by -b when dot(a, b) < 0 (short way),
 * then out = normalise((1-t)*a + t*b). Cheaper than slerp; same path, but the angular rate is
 * not constant (fastest at the middle; for a rotation of angle phi the speed ratio middle/ends
 * is 1/cos^2(phi/4): 1.17 at 90 deg, 2 at 180 deg). t == 0 gives unit a, t == 1 the (possibly
 * negated) unit b, exactly. The middle is always defined: after the flip dot >= 0, so the sum
 * has length >= 1/sqrt(2) (also for orientations exactly 180 deg apart, dot == 0).
 * Returns QO_OK; QO_E_NULL (out NULL, nothing written); QO_E_NONFINITE for NaN/Inf in a or b
 * (*out = identity) or t NaN/Inf (*out = unit a); QO_E_DEGENERATE if a or b is zero
 * (*out = identity); QO_E_RANGE if t is outside [0, 1] (*out = unit a). */
qo_status qo_interp_nlerp_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out);

/* Spherical linear interpolation, short way, constant angular rate:
 *   a, b normalised; b' = (dot(a, b) < 0) ? -b : b;  th = 4-D angle between a and b' in [0, pi/2]
 *   out = normalise(sin((1-t) th)/sin(th) * a + sin(t th)/sin(th) * b').
 * The rotation from a to out is t times the rotation from a to b (angle grows linearly in t).
 * No angle and no sine are computed: the unit midpoint of a and b' splits the arc into halves
 * of th/2 <= pi/4, and the weights of the half that holds t are Eberly's series in
 * cos(th/2) - 1 (7 terms, truncation < 2.5e-8; lib/src/interp.c), which stays accurate as
 * th -> 0 (the weights depend smoothly on the cosine there; acos(dot) would not). Rotation
 * error and |norm - 1| within 1e-6 (tests/core/test_interp.c: test_slerp_random_vs_double,
 * test_slerp_edge_table); the worst measured by bench/accuracy_interp: docs/FIGURES.md, accuracy.
 * The flipped b' is used throughout, so q and -q (the same rotation) interpolate to that
 * rotation, unit length.
 * Endpoints are exact: t == 0 returns unit a (a/|a| exactly as qo_quat_normalize_f32 gives it,
 * which is a itself up to the last bit for a unit a), t == 1 returns unit b' - i.e. -b/|b| when
 * dot(a, b) < 0 (the sign nearest a), else b/|b|.
 * Exactly 180 deg apart (dot == 0, th = pi/2) is not special: b is kept (no flip) and the path
 * is the great circle through a and b, which is one of the two equally short rotations.
 * Returns QO_OK; QO_E_NULL (out NULL, nothing written); QO_E_NONFINITE for NaN/Inf in a or b
 * (*out = identity) or for t NaN/Inf (*out = unit a); QO_E_DEGENERATE if a or b is zero
 * (*out = identity); QO_E_RANGE if t is outside [0, 1] (*out = unit a). */
qo_status qo_interp_slerp_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out);

/* Spherical linear interpolation the LONG way: like qo_interp_slerp_f32 but b' = (dot(a, b) > 0)
 * ? -b : b, so the path is the rotation of angle 2*pi - phi (phi = the short rotation angle)
 * about the opposite sense of the same axis. For dot == 0 b is kept (both ways are 180 deg).
 * When a and b are the same rotation (phi -> 0) the long way is a full turn about an axis the
 * inputs no longer define: the plane of the path, and so the result, is only known to about
 * 1e-6/phi rad (float rounding of the inputs divided by |a + b'| ~ phi/2): within
 * 1e-6 (1 + 1/phi) of the double slerp, checked by tests/core/test_interp.c: test_slerp_long
 * (the worst error x phi measured by bench/accuracy_interp: docs/FIGURES.md, accuracy). The function refuses phi < 2*QO_INTERP_SLERP_SERIES_ANGLE (0.002 rad)
 * with QO_E_DEGENERATE (*out = unit a).
 * Endpoints: t == 0 gives unit a, t == 1 gives unit b' exactly.
 * Other statuses and outputs as qo_interp_slerp_f32. */
qo_status qo_interp_slerp_long_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out);

/* Angular velocity of qo_interp_slerp_f32(a, b, t) when t runs from 0 to 1 in `duration`
 * seconds: the slerp is a rotation about one fixed axis at constant rate, so omega is
 * constant. It is written in the BODY frame (the frame of the moving orientation, and also of
 * a): omega = 2*log(conj(a)*b')/duration (rad/s), b' the short-way b. The world-frame velocity
 * is qo_quat_rotate_f32(a, omega) (equally constant). |omega| = rotation angle / duration.
 * Returns QO_OK; QO_E_NULL (omega NULL, nothing written); QO_E_NONFINITE (NaN/Inf in a, b or
 * duration); QO_E_DEGENERATE (a or b zero); QO_E_RANGE (duration <= 0). *omega = 0 on error. */
qo_status qo_interp_slerp_rate_f32(qo_quat_f32 a, qo_quat_f32 b, float duration,
                                 qo_vec3_f32 *omega);

/* Writes out[i] = keys[i] normalised and sign-aligned: out[0] = keys[0]/|keys[0]| and each
 * following key is negated when its dot product with the previous ALIGNED key is negative.
 * The rotations are unchanged; consecutive keys are then at most 180 deg of rotation apart on
 * the short way. This is the key sequence the spline and Squad functions below use internally.
 * out may be the same array as keys (in-place); other overlaps are not allowed.
 * Returns QO_OK; QO_E_NULL (keys or out NULL; out, when not NULL, is filled with identities);
 * QO_E_TOO_FEW (n == 0); QO_E_NONFINITE / QO_E_DEGENERATE (a key is NaN/Inf / zero; out is
 * filled with identities). */
qo_status qo_interp_align_keys_f32(const qo_quat_f32 *keys, size_t n, qo_quat_f32 *out);

/* Bezier curve on the sphere through its end points, built by de Casteljau's construction
 * with slerp in place of linear interpolation (Shoemake 1985). ctrl[0..n-1] are normalised and
 * sign-aligned as in qo_interp_align_keys_f32 (so the caller's signs do not change the curve),
 * then each level slerps neighbours with parameter t, without further flips (which keeps the
 * curve continuous in t). 2 <= n <= QO_INTERP_BEZIER_MAX_POINTS; n == 2 is qo_interp_slerp_f32.
 * t in [0, 1]; t == 0 gives unit ctrl[0] exactly, t == 1 the last aligned control point
 * exactly (ctrl[n-1]/|ctrl[n-1]| or its negative, whichever the alignment chose).
 * Returns QO_OK; QO_E_NULL (out NULL: nothing written; ctrl NULL: *out = identity);
 * QO_E_TOO_FEW (n < 2), QO_E_CAPACITY (n > QO_INTERP_BEZIER_MAX_POINTS), QO_E_NONFINITE /
 * QO_E_DEGENERATE (a control point NaN/Inf / zero): *out = identity; QO_E_NONFINITE (t NaN/Inf)
 * or QO_E_RANGE (t outside [0, 1]): *out = unit ctrl[0]. */
qo_status qo_interp_bezier_f32(const qo_quat_f32 *ctrl, size_t n, float t, qo_quat_f32 *out);

/* Cubic Bezier on the sphere: qo_interp_bezier_f32 with the four control points q0..q3.
 * Same rules, statuses and outputs (n is 4). */
qo_status qo_interp_bezier3_f32(qo_quat_f32 q0, qo_quat_f32 q1, qo_quat_f32 q2, qo_quat_f32 q3,
                              float t, qo_quat_f32 *out);

/* Inner control points of Shoemake's C1 Bezier spline through n keyframes, as given in the
 * lecture notes on quaternion interpolation this module follows (Shoemake 1985, with the
 * 1/3 scaling of the Euclidean cubic Bezier). The keys are first normalised and aligned
 * (qo_interp_align_keys_f32); q_i below are the ALIGNED keys, and the spline passes through
 * them (the same rotations as the caller's keys, possibly opposite signs). Segment i (from q_i
 * to q_{i+1}) is the cubic Bezier q_i, a_i, b_{i+1}, q_{i+1}. With Slerp(p, q, u) the great-
 * circle interpolation, no flip, u may lie outside [0, 1] (extrapolation):
 *   interior 0 < i < n-1:
 *     abar_i = Slerp(Slerp(q_{i-1}, q_i, 2), q_{i+1}, 1/2)   ("Bisect(Double(q_{i-1}, q_i), q_{i+1})")
 *     a_i    = Slerp(q_i, abar_i,  1/3)
 *     b_i    = Slerp(q_i, abar_i, -1/3)   (the mirror of a_i through q_i on the same great circle)
 *   ends (n >= 3), exactly as the notes:
 *     a_0     = Slerp(q_0,     Slerp(q_2,     q_1,     2), 1/3)
 *     b_{n-1} = Slerp(q_{n-1}, Slerp(q_{n-3}, q_{n-2}, 2), 1/3)
 *   unused, written for definiteness: b_0 = q_0, a_{n-1} = q_{n-1}.
 * The Euclidean analogue is Catmull-Rom: a_i = q_i + (q_{i+1} - q_{i-1})/6, and a_i, b_i on one
 * great circle at equal distance make the angular velocity continuous at every key (C1 in s).
 * Note on the end rule: its Euclidean analogue is a_0 = q_0 + ((q_1 - q_0) - (q_2 - q_1))/3, so
 * keys at a uniform rate about one axis give a_0 = q_0: the spline STARTS AND ENDS AT REST
 * there (zero angular velocity), and in general the end velocity is minus the second difference.
 * If abar_i is undefined because Slerp(q_{i-1}, q_i, 2) is antipodal to q_{i+1} (within
 * QO_INTERP_SLERP_SERIES_ANGLE; e.g. a 180 deg swing out and back), abar_i = q_i: zero velocity at that
 * key, the limit of the Euclidean formula for q_{i+1} = q_{i-1}.
 * n == 2: the spline is the slerp between the two keys: a_0 = Slerp(q_0, q_1, 1/3),
 * b_1 = Slerp(q_0, q_1, 2/3) (evenly spaced on the arc, so the Bezier has constant rate).
 * a and b are caller arrays of n entries each; they must not overlap keys or each other.
 * Returns QO_OK; QO_E_NULL (keys, a or b NULL: the non-NULL outputs are filled with n
 * identities); QO_E_TOO_FEW (n < 2), QO_E_NONFINITE / QO_E_DEGENERATE (a key NaN/Inf / zero):
 * a and b filled with identities. */
qo_status qo_interp_spline_controls_f32(const qo_quat_f32 *keys, size_t n,
                                      qo_quat_f32 *a, qo_quat_f32 *b);

/* Evaluates the spline of qo_interp_spline_controls_f32 at s in [0, n-1]: segment
 * i = floor(s) (i = n-2 for s == n-1), local parameter t = s - i, cubic Bezier
 * q_i, a_i, b_{i+1}, q_{i+1} by de Casteljau with slerp. keys, a, b are the arrays given to /
 * written by qo_interp_spline_controls_f32 (keys may be the caller's unaligned ones: each segment's
 * key signs are re-aligned to a_i, so the result is the curve through the aligned keys). One
 * unit of s is one segment; the angular velocity in rad per unit s is continuous (C1).
 * At s == i exactly the result is the aligned unit key q_i (+-keys[i]/|keys[i]|). Output sign:
 * that of the aligned key sequence (which starts with the sign of keys[0]).
 * Only the four points of the evaluated segment are checked and normalised.
 * Returns QO_OK; QO_E_NULL (out NULL: nothing written; keys, a or b NULL: *out = identity);
 * QO_E_TOO_FEW (n < 2: *out = identity); QO_E_NONFINITE (NaN/Inf in a segment point:
 * *out = identity); QO_E_DEGENERATE (zero segment point: *out = identity); QO_E_NONFINITE for
 * s NaN/Inf and QO_E_RANGE for s outside [0, n-1]: *out = the nearest end key, normalised
 * (keys[0] for s < 0 and NaN, keys[n-1] for s > n-1), or identity if that key is invalid. */
qo_status qo_interp_spline_eval_f32(const qo_quat_f32 *keys, const qo_quat_f32 *a,
                                  const qo_quat_f32 *b, size_t n, float s, qo_quat_f32 *out);

/* Squad segment (Shoemake 1987) from key q0 to key q1 with inner quadrangle points s0, s1
 * (from qo_interp_squad_controls_f32):
 *   out = Slerp(Slerp(q0, q1, t), Slerp(s0, s1, t), 2t(1-t)).
 * All four are normalised; q1 is aligned to q0, s0 to q0 and s1 to q1 (negated where the dot
 * product is negative), and the inner slerps then take no further flip, so the result does not
 * depend on the caller's signs. t == 0 gives unit q0, t == 1 the aligned unit q1, exactly.
 * Returns QO_OK; QO_E_NULL (out NULL, nothing written); QO_E_NONFINITE (NaN/Inf input:
 * *out = identity; t NaN/Inf: *out = unit q0); QO_E_DEGENERATE (zero input, *out = identity);
 * QO_E_RANGE (t outside [0, 1], *out = unit q0). */
qo_status qo_interp_squad_f32(qo_quat_f32 q0, qo_quat_f32 s0, qo_quat_f32 s1, qo_quat_f32 q1,
                            float t, qo_quat_f32 *out);

/* Squad inner points for n keys: with q_i the aligned keys (qo_interp_align_keys_f32),
 *   s_i = q_i * exp(-(log(q_i^-1 q_{i+1}) + log(q_i^-1 q_{i-1})) / 4),  0 < i < n-1,
 *   s_0 = q_0, s_{n-1} = q_{n-1}   (zero end tangents).
 * Segment i is then qo_interp_squad_f32(q_i, s_i, s_{i+1}, q_{i+1}, t). These tangents assume
 * evenly spaced keys (the classic formula); Squad is C1 only for them.
 * s is a caller array of n entries, not overlapping keys.
 * Returns QO_OK; QO_E_NULL (keys or s NULL; s, when not NULL, filled with n identities);
 * QO_E_TOO_FEW (n < 2), QO_E_NONFINITE / QO_E_DEGENERATE (a key NaN/Inf / zero): s filled with
 * identities. */
qo_status qo_interp_squad_controls_f32(const qo_quat_f32 *keys, size_t n, qo_quat_f32 *s);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_INTERP_H */
