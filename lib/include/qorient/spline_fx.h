/* parity fixed (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   spline.storage qo_spline_q16_len
 *   spline.plan    - planned in float32 (host or main loop): the fixed core samples the export
 *   spline.sample  qo_spline_sample_q16
 *   spline.export  - qo_spline_sample_q16 reads the table qo_spline_export_q16 writes
 */
/*
 * qorient/spline_fx.h - fixed-point (Q16.16) sampling of a keyframe trajectory, no float.
 *
 * Index:
 *   qo_spline_table_q16            a planned trajectory as an int32 table in caller storage
 *   qo_spline_q16_len()      int32 words the table needs for N joints and K keyframes
 *   qo_spline_sample_q16()   position, velocity, acceleration of every joint at time t
 *
 * The table is made ONCE from a float32 plan by qo_spline_export_q16() (qorient/spline.h,
 * float code, run at plan time on the host or in the main loop); sampling here uses integers
 * only (int32 storage, int64 intermediates) and is meant for FPU-less cores and interrupts.
 *
 * Formats (all qo_q16 values are Q16.16 in the caller's units, range [-32768, 32768)):
 *   time t, key times             Q16.16 seconds (LSB 15.3 us)
 *   positions, velocities, accel. Q16.16 user units, units/s, units/s^2
 * Table layout (int32 words, row k = 0..K-1):
 *   K rows of 5 words: t_k, m1, e1, m2, e2 where 1/h_k = m1 * 2^-e1 and 1/h_k^2 = m2 * 2^-e2,
 *       m in [2^23, 2^24) (24-bit mantissas, h_k = t_(k+1) - t_k of the Q16.16 key times;
 *       the last row holds only t_(K-1));
 *   N rows of 3 words: position min, max (INT32_MIN / INT32_MAX = none), wrap period (0 = none);
 *   K*N rows of 7 words: segment k, joint j: b_0..b_5 and f, the b_n in Q(16+f) (16 + f
 *       fractional bits, f in [0, 14] per row: the most that keeps every |b_n| < 2^14 units,
 *       so small moves keep up to 14 more bits) of
 *       p(s) = b_0 + b_1 s + ... + b_5 s^5,  s = (t - t_k) / h_k in [0, 1]  (normalised time),
 *       v = p'(s) / h_k,  a = p''(s) / h_k^2;  row K-1 holds the end state (p, v, a, 0, 0, 0)
 *       in Q16.16 (f = 0).
 * Sampling: s is formed in Q5.27 with rounding, the three polynomials are evaluated by Horner
 * in int64 with rounding after every product (symmetric, half away from zero), and v, a are
 * scaled by the mantissa/exponent pairs. Intermediates are bounded so that int64 cannot
 * overflow for any table (coefficients are int32, s <= 2^27, mantissas < 2^24).
 *
 * Error bound (fixed sample vs the float32 sample of the same plan at the same t, where t
 * is a Q16.16 value), in Q16.16 LSB: position 0.5 + 5.5 * 2^-f (0.5 * 2^-f for rounding each
 * of the 6 coefficients and each of the 5 Horner steps, 0.5 for the final rounding) + |v| d,
 * where d <= 2^-17 s is how far the key times moved when rounded to Q16.16 (0 when they are
 * multiples of 2^-16 s) and |v| is in LSB per second; velocity 0.5 + 10 * 2^-f / h (in
 * seconds) and acceleration 0.5 + 23 * 2^-f / h^2 by the same count, each plus 2^-23 relative
 * (24-bit mantissas) and the key-time term. With f = 0 (moves of ~1000 units and more) that
 * is 6 LSB in position. The float32 sample itself carries ~1 float ulp of the coefficients;
 * bench/bench_spline.c measures the worst differences.
 */
#ifndef QORIENT_SPLINE_FX_H
#define QORIENT_SPLINE_FX_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Words per key row, per joint row and per (segment, joint) coefficient row of the table. */
#define QO_SPLINE_Q16_KEY_WORDS   5u
#define QO_SPLINE_Q16_JOINT_WORDS 3u
#define QO_SPLINE_Q16_COEF_WORDS  7u
/* Most extra fractional bits of a coefficient row. */
#define QO_SPLINE_Q16_MAX_FRAC    14

/* A keyframe trajectory for the fixed-point sampler. Made by qo_spline_export_q16(); n_keys
 * == 0 marks a table that is not usable (a failed conversion). The table memory belongs to
 * the caller and must outlive this struct. Read-only while sampling: several interrupts may
 * sample the same plan concurrently. */
typedef struct qo_spline_table_q16 {
    size_t n_joints;      /* N >= 1 */
    size_t n_keys;        /* K >= 2, 0 = not usable */
    int wrap_output;      /* nonzero: wrapped joints are output in (-period/2, period/2] */
    const int32_t *table; /* qo_spline_q16_len(N, K) words, layout above */
} qo_spline_table_q16;

/* int32 words the table needs: 5K + 3N + 7KN. Returns 0 when n_joints == 0, n_keys < 2 or the
 * size does not fit in size_t. */
size_t qo_spline_q16_len(size_t n_joints, size_t n_keys);

/*
 * Samples every joint at time t (Q16.16 seconds).
 *   t <  t_0:      pos = first keyframe, vel = acc = 0 (held at rest before the start);
 *   t_0 <= t < t_(K-1): the segment polynomial;
 *   t == t_(K-1):  pos = last keyframe, vel/acc = the end state of the last segment;
 *   t >  t_(K-1):  pos = last keyframe, vel = acc = 0 (held at rest after the end).
 * Wrapped (continuous) joints are output in (-period/2, period/2] when s->wrap_output is
 * set, else unwrapped (continuing from the first keyframe). Position limits then clamp pos;
 * a clamped joint reports vel = acc = 0 (it is held at the limit) and clamped[j] = -1 (at
 * min) or +1 (at max), else 0.
 * pos: N values (required). vel, acc, clamped: N values each or NULL when not wanted.
 * Returns QO_OK; QO_E_NULL (s, s->table or pos NULL; every non-NULL output is zeroed when N
 * is known); QO_E_STATE (s->n_keys == 0: a failed conversion; outputs zeroed);
 * QO_E_OVERFLOW when a position, velocity or acceleration does not fit Q16.16 (that value is
 * saturated to INT32_MIN/INT32_MAX, the others are valid).
 */
qo_status qo_spline_sample_q16(const qo_spline_table_q16 *s, qo_q16 t, qo_q16 *pos, qo_q16 *vel,
                               qo_q16 *acc, int8_t *clamped);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_SPLINE_FX_H */
