/* parity fixed (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   motion.plan    - planned in float32 (host or main loop): the fixed core samples the export
 *   motion.query   - the plan's times are in the float32 object that exported the table
 *   motion.sample  qo_motion_sample_q16
 *   motion.export  - qo_motion_sample_q16 reads the table qo_motion_export_q16 writes
 */
/*
 * qorient/motion_fx.h - per-tick sampling of a motion plan in fixed point (no float at all).
 *
 * Index:
 *   qo_motion_sample_q16     positions, velocities, accelerations of every joint at a local time
 *
 * The table is made by qo_motion_export_q16 (motion.h, float32 side) after each (re-)plan; a
 * core without an FPU can plan elsewhere (or rarely) and sample here every tick with integer
 * arithmetic only (int64 intermediates).
 *
 * Formats:
 *   - time: qo_q16, Q16.16 SECONDS since the plan's start (the t0 of the last re-plan): a
 *     scaled local time, range [0, 32768) s, LSB 15.26 us. The caller counts ticks since the
 *     re-plan and converts, e.g. t = (ticks << 16) / rate_hz.
 *   - outputs: Q16.16 user units (u, u/s, u/s^2), range [-32768, 32768), LSB 1.53e-5.
 *   - segment coefficients: int64 Q31.32 (value = raw / 2^32).
 *
 * Code: ~1.9 KB on Cortex-M0+ (arm-none-eabi-gcc -O2), ~130 B of stack.
 *
 * Each joint has QO_MOTION_Q16_SEGS segments (unused ones repeat the final rest segment); a
 * segment k holds its start time tk and c0 = p, c1 = v, c2 = a/2, c3 = j/6 at tk, and the
 * sample is c0 + c1*tau + c2*tau^2 + c3*tau^3 (Horner), tau = t - tk.
 *
 * Error bound (against the exact piecewise polynomial with the table's coefficients): each of
 * the three Horner steps rounds to 2^-33, the result rounds to 2^-17, so
 *   |pos error| <= 2^-17 + 2^-33 (1 + tau + tau^2)   (tau in s, within one segment)
 * i.e. <= 1 LSB of Q16.16 for segments shorter than ~180 s; likewise velocity and acceleration.
 * Against the float32 plan add the coefficient rounding to Q31.32 (2^-33 each, times tau^k) and
 * the float32 plan's own rounding. Saturation of a result to the Q16.16 range returns
 * QO_E_OVERFLOW with the saturated value.
 */
#ifndef QORIENT_MOTION_FX_H
#define QORIENT_MOTION_FX_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Segments per joint in a table: 7 phases + the ramp of a target acceleration to zero after
 * the end (qo_motion_set_target_state_f32) + the final segment (at rest, or moving on at the
 * end velocity). */
#define QO_MOTION_Q16_SEGS 9

/* One polynomial segment: from local time t (Q16.16 s) on, c0 + c1 tau + c2 tau^2 + c3 tau^3. */
typedef struct qo_motion_seg_q16 {
    int64_t c0, c1, c2, c3;   /* Q31.32: position, velocity, acceleration/2, jerk/6 at t */
    qo_q16 t;                 /* Q16.16 seconds since the plan start */
} qo_motion_seg_q16;

/* A plan's table: segs points to n * QO_MOTION_Q16_SEGS segments in caller storage, joint i's
 * at [i * QO_MOTION_Q16_SEGS, (i + 1) * QO_MOTION_Q16_SEGS), start times non-decreasing. */
typedef struct qo_motion_table_q16 {
    const qo_motion_seg_q16 *segs;
    size_t n;                 /* joints; 0 = empty table */
} qo_motion_table_q16;

/*
 * Samples every joint at local time t (Q16.16 seconds since the plan start) into n-element
 * arrays: positions (Q16.16 u), velocities (Q16.16 u/s), accelerations (Q16.16 u/s^2); vel and
 * acc may be NULL.
 * Returns QO_OK; QO_E_NULL (table or pos NULL: nothing is written; table->segs NULL: every
 * output is 0);
 * QO_E_STATE (table->n == 0); QO_E_RANGE (t < 0: the state at t = 0 is given);
 * QO_E_OVERFLOW (a value saturated to the Q16.16 range; the others are still exact).
 */
qo_status qo_motion_sample_q16(const qo_motion_table_q16 *table, qo_q16 t, qo_q16 *pos,
                               qo_q16 *vel, qo_q16 *acc);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_MOTION_FX_H */
