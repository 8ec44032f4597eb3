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

#endif /* QORIENT_EULER_SEQ_INTERNAL_H */
