/* lib/src/euler_seq_internal.h - what euler.c and euler_fx.c share of lib/src/euler_seq.c
 * (not installed). */
#ifndef QORIENT_EULER_SEQ_INTERNAL_H
#define QORIENT_EULER_SEQ_INTERNAL_H

#include "qorient/euler_seq.h"

/* Axes of the 12 base sequences in enum order (0 = x, 1 = y, 2 = z); the intrinsic twin of a
 * sequence s is s + 12, with the same row. */
extern const unsigned char qo_euler_seq_axes[12][3];

/* 1 if seq is one of the 24 conventions. */
int qo_euler_seq_valid(qo_euler_seq seq);

/* The axes row of a valid seq, and the axis after i in the cyclic order x y z: without % (a
 * division, a library call on cores without a divider). */
static inline const unsigned char *qo_euler_seq_row(qo_euler_seq seq)
{
    return qo_euler_seq_axes[(int)seq >= 12 ? (int)seq - 12 : (int)seq];
}
static inline unsigned qo_euler_axis_next(unsigned i) { return i == 2u ? 0u : i + 1u; }

#endif /* QORIENT_EULER_SEQ_INTERNAL_H */
