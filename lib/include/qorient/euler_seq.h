/*
 * qorient/euler_seq.h - the 24 Euler conventions as a type, shared by the float32 core
 * (qorient/euler.h) and the fixed-point core (qorient/euler_fx.h). No float, no fixed point:
 * lib/src/euler_seq.c links into either core alone.
 *
 * Index:
 *   qo_euler_seq                 enum of the 24 conventions (scipy's names: xyz extrinsic, XYZ intrinsic)
 *   qo_euler_seq_parse()         "xyz" / "ZYX" / "zxz" ... -> qo_euler_seq
 *   qo_euler_seq_name()          qo_euler_seq -> "xyz" / "ZYX" / ...
 *   qo_euler_seq_is_intrinsic()  1 for the upper-case (intrinsic) sequences
 *   qo_euler_seq_is_proper()     1 for proper Euler sequences (first axis == third axis)
 *
 * What the conventions mean (extrinsic/intrinsic, angle order, ranges, gimbal lock) is written
 * in qorient/euler.h.
 */
#ifndef QORIENT_EULER_SEQ_H
#define QORIENT_EULER_SEQ_H

#include "qorient/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * The 24 conventions. The constant names mirror scipy's sequence strings exactly, so they are
 * the one place in qorient where enum constants are mixed case: QO_EULER_xyz is extrinsic
 * x-y-z, QO_EULER_XYZ is intrinsic X-Y'-Z''. Values 0..11 extrinsic, 12..23 intrinsic, in the
 * same axis order; Tait-Bryan first, then proper. The values are part of the ABI.
 */
typedef enum qo_euler_seq {
    QO_EULER_xyz = 0, QO_EULER_xzy, QO_EULER_yxz, QO_EULER_yzx, QO_EULER_zxy, QO_EULER_zyx,
    QO_EULER_xyx, QO_EULER_xzx, QO_EULER_yxy, QO_EULER_yzy, QO_EULER_zxz, QO_EULER_zyz,
    QO_EULER_XYZ, QO_EULER_XZY, QO_EULER_YXZ, QO_EULER_YZX, QO_EULER_ZXY, QO_EULER_ZYX,
    QO_EULER_XYX, QO_EULER_XZX, QO_EULER_YXY, QO_EULER_YZY, QO_EULER_ZXZ, QO_EULER_ZYZ,
    QO_EULER_SEQ_COUNT_   /* number of conventions; not a convention */
} qo_euler_seq;

/*
 * Parses a sequence string: exactly three letters, each x, y or z, all lower case (extrinsic)
 * or all upper case (intrinsic), no two consecutive letters equal (the first and third may be
 * equal: proper Euler). Nothing may follow the three letters.
 * Returns QO_OK; QO_E_NULL if s or out is NULL; QO_E_ARG for any other string (mixed case,
 * "xxy", "xy", "xyzx", "abc", ""). On error *out (if out is not NULL) is QO_EULER_SEQ_COUNT_,
 * which every function below rejects with QO_E_ARG, so an unchecked failure cannot silently
 * become some sequence.
 */
qo_status qo_euler_seq_parse(const char *s, qo_euler_seq *out);

/* The sequence's string as scipy spells it ("xyz", "ZYX", ...); "invalid" for a value that is
 * not one of the 24. Never NULL; the string is constant. */
const char *qo_euler_seq_name(qo_euler_seq seq);

/* 1 if seq is one of the 12 intrinsic (upper-case) sequences, 0 otherwise (also for an invalid
 * value). */
int qo_euler_seq_is_intrinsic(qo_euler_seq seq);

/* 1 if seq is one of the 12 proper Euler sequences (first axis == third axis: singular at a
 * middle angle of 0 or pi), 0 for Tait-Bryan (singular at +-pi/2) and for an invalid value. */
int qo_euler_seq_is_proper(qo_euler_seq seq);

#ifdef __cplusplus
}
#endif

#endif /* QORIENT_EULER_SEQ_H */
