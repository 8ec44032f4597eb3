/* parity float32 (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   spline.storage qo_spline_coef_len
 *   spline.plan    qo_spline_init_f32
 *   spline.sample  qo_spline_sample_f32
 *   spline.export  qo_spline_export_q16 (float32 code: writes the fixed core's table)
 */
/*
 * qorient/spline.h - multi-joint trajectories through keyframes, float32.
 *
 * Index:
 *   qo_spline_profile           LINEAR, CUBIC_HERMITE, CATMULL_ROM, CUBIC_C2, QUINTIC
 *   qo_spline_end               end condition: CLAMPED (given end velocities, default rest)
 *                               or NATURAL
 *   qo_spline_derivs            key derivatives the caller did not give: ESTIMATED or ZERO
 *   qo_spline_settings_f32      plan settings; qo_spline_settings_default is the const default
 *   qo_spline_f32               a planned trajectory (coefficients in caller storage)
 *   qo_spline_coef_len()        floats of storage a plan of N joints and K keyframes needs
 *   qo_spline_init_f32()        validate keyframes and plan the per-segment polynomials
 *   qo_spline_sample_f32()      position, velocity, acceleration of every joint at time t
 *   qo_spline_export_q16()      the plan as a fixed-point table, once (spline_fx.h)
 *
 * Model. N joints (scalars in the caller's unit: rad, deg, counts) pass through K keyframes:
 * key k is reached at time t[k] (seconds, strictly increasing) with positions p[k*N + j]
 * (row-major: one row of N per key). Between keys k and k+1 each joint follows a polynomial
 * of degree <= 5 in the normalised time s = (t - t[k]) / h, h = t[k+1] - t[k], s in [0, 1]:
 *   p(s) = b0 + b1 s + ... + b5 s^5,  vel = p'(s) / h,  acc = p''(s) / h^2.
 * (Normalised time keeps the coefficients in position units for any h, which is also what
 * the fixed-point table stores.) Every key is interpolated exactly: at t == t[k] the sample
 * is b0 == the key's position (for a wrapped joint, up to the rounding of one wrap).
 *
 * Profiles (continuity at the keys, for sampled position / velocity / acceleration):
 *   LINEAR         straight lines, C0. Velocity is the segment's slope, acceleration 0
 *                  (the velocity step at a key is not reported as an acceleration).
 *   CUBIC_HERMITE  cubic segments through the keys with the velocities the caller gives
 *                  (settings.key_vel, K*N), C1.
 *   CATMULL_ROM    cubic Hermite with non-uniform Catmull-Rom tangents at inner keys,
 *                  m_k = (s0*h1 + s1*h0) / (h0 + h1) with s0, s1 the chord slopes before and
 *                  after key k (the Barry-Goldman time-parameterised form), C1. The end keys
 *                  follow settings.end (below).
 *   CUBIC_C2       the interpolating cubic spline, C2: one tridiagonal solve per joint for
 *                  the key accelerations (Thomas algorithm in the coefficient storage itself,
 *                  no extra scratch). Ends per settings.end.
 *   QUINTIC        quintic segments with position, velocity and acceleration given at both
 *                  keys: velocities from settings.key_vel or else (settings.derivs) the
 *                  Catmull-Rom tangents or zero; accelerations from settings.key_acc or else
 *                  estimated as the same weighted slope of the key velocities (C2 because
 *                  each key has one acceleration) or zero. Zero derivatives make every key a
 *                  stop (rest-to-rest segments). Given arrays cover every key including the
 *                  ends (settings.end then only shapes what is estimated). Inconsistent given
 *                  p/v/a overshoot: that is the caller's data.
 * End conditions (settings.end; ignored by LINEAR and CUBIC_HERMITE):
 *   CLAMPED   the first/last key velocities are settings.end_vel[j] / end_vel[N + j]
 *             (NULL = 0: start and stop at rest); QUINTIC also has zero end accelerations.
 *   NATURAL   zero acceleration at the end keys: CUBIC_C2 the natural spline; CATMULL_ROM
 *             and estimated QUINTIC velocities use m_end = (3 s - m_next) / 2, the tangent
 *             that makes the end segment's second derivative zero. For K == 2 a natural
 *             cubic / Catmull-Rom is the straight line.
 *
 * Outside the keys: before t[0] the first key is held at rest (vel = acc = 0); at exactly
 * t[K-1] the last key with the end velocity/acceleration of the last segment; after t[K-1]
 * the last key at rest.
 *
 * Continuous joints (settings.wrap[j] != 0): keys are unwrapped before planning so that
 * every step between consecutive keys takes the short way round, d = wrap(p[k] - p[k-1]) in
 * (-period/2, period/2] (an exact half turn goes in the + direction). Samples are output in
 * (-period/2, period/2] when settings.wrap_output is set (the default: the same range as
 * the keys, fine for absolute-angle servos), else unwrapped, continuing from the first key
 * (for multi-turn drives that must not see the +-period/2 jump).
 *
 * Position limits (settings.pos_min / pos_max, N each, NULL = none, +-Inf allowed): samples
 * are clamped to [min, max] (after wrapping); a clamped joint reports vel = acc = 0 and is
 * flagged in the sample's clamped[] output. Keys outside the limits are accepted (they get
 * clamped and reported when sampled).
 *
 * Re-planning mid-motion: a plan is immutable. To change the keys while moving, sample the
 * current plan at the switch time and plan again with that sample as the first key and its
 * velocity as the CLAMPED start velocity (end_vel[j]): position and velocity continue without
 * a jump (for QUINTIC pass key_vel / key_acc to carry the acceleration as well).
 *
 * Storage: everything the sampler needs (times, limits, wrap periods, coefficients) is copied
 * into the caller's coef array, so t, p and the settings arrays may be freed after init.
 * Sampling reads only; one plan may be sampled from several contexts at once.
 */
#ifndef QORIENT_SPLINE_H
#define QORIENT_SPLINE_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/status.h"
#include "qorient/types.h"
#include "qorient/spline_fx.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum qo_spline_profile {
    QO_SPLINE_LINEAR = 0,
    QO_SPLINE_CUBIC_HERMITE,
    QO_SPLINE_CATMULL_ROM,
    QO_SPLINE_CUBIC_C2,
    QO_SPLINE_QUINTIC
} qo_spline_profile;

typedef enum qo_spline_end {
    QO_SPLINE_END_CLAMPED = 0, /* end velocities given (default: rest) */
    QO_SPLINE_END_NATURAL      /* zero acceleration at the end keys */
} qo_spline_end;

typedef enum qo_spline_derivs {
    QO_SPLINE_DERIVS_ESTIMATED = 0, /* Catmull-Rom style weighted slopes */
    QO_SPLINE_DERIVS_ZERO           /* stop at every key */
} qo_spline_derivs;

/* Plan settings. Arrays are read during qo_spline_init_f32() only. */
typedef struct qo_spline_settings_f32 {
    qo_spline_profile profile;   /* default QO_SPLINE_CUBIC_C2 */
    qo_spline_end end;           /* default QO_SPLINE_END_CLAMPED */
    const float *end_vel;        /* 2N: start velocities, then end velocities (CLAMPED); NULL = 0 */
    const float *key_vel;        /* K*N key velocities: CUBIC_HERMITE (required), QUINTIC */
    const float *key_acc;        /* K*N key accelerations: optional for QUINTIC */
    qo_spline_derivs derivs;     /* QUINTIC: key velocities / accelerations not given */
    const float *pos_min;        /* N lower position limits, NULL = none */
    const float *pos_max;        /* N upper position limits, NULL = none */
    const unsigned char *wrap;   /* N flags, nonzero = continuous joint; NULL = none */
    float wrap_period;           /* period of continuous joints, > 0 (default 2 pi; 360 deg) */
    int wrap_output;             /* nonzero (default): wrapped joints out in (-P/2, P/2] */
} qo_spline_settings_f32;

/* CUBIC_C2, CLAMPED at rest, no derivative arrays, no limits, no wrap, period 2 pi, wrapped
 * output. */
extern const qo_spline_settings_f32 qo_spline_settings_default;

/* A planned trajectory. Written by qo_spline_init_f32(); n_keys == 0 marks a failed or
 * missing plan. The coef memory belongs to the caller and must outlive the plan. */
typedef struct qo_spline_f32 {
    size_t n_joints;          /* N */
    size_t n_keys;            /* K >= 2, 0 = not usable */
    qo_spline_profile profile;
    int wrap_output;
    const float *coef;        /* K times, N*(min, max, period), K*N*6 coefficients */
} qo_spline_f32;

/* Supported range: every position, velocity and acceleration a plan can produce between its
 * keys must stay within +-QO_SPLINE_MAX_VALUE (units, units/s, units/s^2), so that the
 * float32 sampler cannot overflow. qo_spline_init_f32() checks a bound on each segment
 * (sum of |b_n|, sum of n |b_n| / h, sum of n (n-1) |b_n| / h^2) and refuses a plan beyond it
 * with QO_E_RANGE: e.g. keys near FLT_MAX, or a step of 1e30 in 1 s, or 1 in 1e-16 s. */
#define QO_SPLINE_MAX_VALUE 1e30f

/* Floats of coef storage for N joints and K keys: K + 3N + 6KN. Returns 0 when n_joints == 0,
 * n_keys < 2 or the size overflows size_t. */
size_t qo_spline_coef_len(size_t n_joints, size_t n_keys);

/*
 * Plans the trajectory of n_joints joints through n_keys keyframes.
 *   t:    K times in seconds, strictly increasing, finite, with finite differences;
 *   p:    K*N positions, row-major (p[k*N + j]), finite;
 *   set:  settings (pass &qo_spline_settings_default for the defaults);
 *   coef: caller storage of coef_len >= qo_spline_coef_len(N, K) floats (also the solver's
 *         scratch); out: the plan.
 * Checked in this order; the first failure is returned:
 *   QO_E_NULL      out, t, p, set or coef NULL, or CUBIC_HERMITE without set->key_vel;
 *   QO_E_TOO_FEW   n_joints == 0 or n_keys < 2;
 *   QO_E_CAPACITY  coef_len too small (or the size overflows);
 *   QO_E_ARG       unknown profile, end condition or derivs value;
 *   QO_E_NONFINITE a time, position, given velocity/acceleration or end velocity is NaN/Inf;
 *   QO_E_ORDER     times not strictly increasing (equal times included);
 *   QO_E_RANGE     a time difference overflows, the wrap period is not finite and > 0 while a
 *                  joint is wrapped, a coefficient overflows float, or a segment could
 *                  sample a position, velocity or acceleration beyond QO_SPLINE_MAX_VALUE
 *                  (keys too large or too far apart for their time step; see above);
 *   QO_E_LIMIT     a position limit is NaN, or min > max for a joint.
 * On error *out is the empty plan (n_joints as given, n_keys == 0, coef NULL): sampling it
 * returns QO_E_STATE. The contents of coef are then unspecified.
 */
qo_status qo_spline_init_f32(size_t n_joints, size_t n_keys, const float *t, const float *p,
                             const qo_spline_settings_f32 *set, float *coef, size_t coef_len,
                             qo_spline_f32 *out);

/*
 * Samples every joint at time t (seconds); see the header text for before/at/after the ends,
 * wrapping and limits.
 * pos: N values (required); vel, acc, clamped: N values each or NULL when not wanted.
 * clamped[j] is -1 (held at min), +1 (held at max) or 0.
 * Returns QO_OK; QO_E_NULL (s or pos NULL: the non-NULL outputs are zeroed when N is known);
 * QO_E_STATE (s->n_keys == 0: outputs zeroed); QO_E_NONFINITE (t is NaN/Inf: the first key
 * held at rest is written, limits applied); QO_E_RANGE (last line of defence, not reachable
 * for a plan qo_spline_init_f32() accepted: a joint's sample would not be finite; that joint
 * gets the key its segment started from, held at rest, limits applied, and the other joints
 * their normal sample). QO_E_NONFINITE takes precedence.
 */
qo_status qo_spline_sample_f32(const qo_spline_f32 *s, float t, float *pos, float *vel,
                               float *acc, int8_t *clamped);

/*
 * Exports a float32 plan to the fixed-point table of qorient/spline_fx.h (float code: run it
 * once at plan time), with the argument pattern of qo_motion_export_q16: the float plan, the
 * table handle, its caller storage `words` of cap int32 entries, needing
 * qo_spline_q16_len(N, K). Times, positions, limits and wrap periods are rounded to Q16.16,
 * coefficients to Q16.16, 1/h and 1/h^2 to 24-bit mantissa + exponent computed from the
 * ROUNDED key times (so s reaches exactly 1 at the next key). Limits beyond the Q16.16 range
 * (and +-Inf) become INT32_MIN / INT32_MAX. Note the normalised coefficients are larger than
 * the positions: up to ~3x the step between keys for cubics and ~15x (b4 = -15 d for a
 * rest-to-rest quintic) for QUINTIC, and the end state holds the end velocity and
 * acceleration; all must fit Q16.16 (steps up to ~2000 units for QUINTIC).
 * Returns QO_OK; QO_E_NULL (s, table or words NULL); QO_E_STATE (s->n_keys == 0);
 * QO_E_CAPACITY (cap < qo_spline_q16_len(N, K)); QO_E_OVERFLOW (a time, coefficient,
 * end velocity/acceleration or wrap period does not fit Q16.16); QO_E_ORDER (two key times
 * round to the same Q16.16 value). On error *table is the empty table (n_keys == 0) and the
 * contents of words are unspecified. (Named qo_spline_to_q16_f32 before issue 16.)
 */
qo_status qo_spline_export_q16(const qo_spline_f32 *s, qo_spline_table_q16 *table, int32_t *words,
                               size_t cap);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_SPLINE_H */
