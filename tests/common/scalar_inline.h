/*
 * tests/common/scalar_inline.h - the portable scalar bodies of the float32 inline functions of
 * qorient/quat.h and qorient/convert.h, compiled in tests/common/scalar_inline.c with
 * QO_NO_SIMD, so a test can compare them bit for bit with the SIMD bodies a test file gets
 * (on a target without SIMD bodies both are the scalar code and the comparison is trivial).
 */
#ifndef QORIENT_TESTS_SCALAR_INLINE_H
#define QORIENT_TESTS_SCALAR_INLINE_H

#include "qorient/types.h"
#include "qorient/status.h"

qo_quat_f32 scalar_quat_mul_f32(qo_quat_f32 a, qo_quat_f32 b);
qo_vec3_f32 scalar_quat_rotate_f32(qo_quat_f32 q, qo_vec3_f32 v);
qo_status scalar_quat_normalize_f32(qo_quat_f32 q, qo_quat_f32 *out);
qo_status scalar_quat_to_mat3_f32(qo_quat_f32 q, qo_mat3_f32 *out);

#endif
