/*
 * tests/common/dq.h - short names for the double-precision quaternion algebra the
 * interpolation tests and accuracy programs (tests/core/test_interp*.c, bench/accuracy_interp*.c)
 * compute their references with. `dq` is the reference quaternion of common/ref.h (one
 * reference for every test and bench program, linked from tests/common/ref.c); the helpers
 * here are the few vector-space operations ref.h has no use for.
 */
#ifndef QORIENT_TESTS_DQ_H
#define QORIENT_TESTS_DQ_H

#include <math.h>

#include "common/ref.h"
#include "qorient/fxconv.h"
#include "qorient/types.h"

typedef ref_quat dq;

static inline qo_quat_f32 f_from(dq q) { return ref_quat_to_f32(q); }
/* q as the fixed core receives a double rotation: rounded to float32, then qorient/fxconv.h. */
static inline qo_quat_q30 fx_from(dq q) { return qo_q30_quat_from_f32(ref_quat_to_f32(q)); }
static inline double dq_dot(dq a, dq b) { return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z; }
static inline double dq_norm(dq a) { return sqrt(dq_dot(a, a)); }
static inline dq dq_scale(dq a, double k) { dq r = { a.w * k, a.x * k, a.y * k, a.z * k }; return r; }
static inline dq dq_neg(dq a) { return dq_scale(a, -1.0); }
static inline dq dq_unit(dq a) { return dq_scale(a, 1.0 / dq_norm(a)); }
static inline dq dq_add(dq a, dq b) { dq r = { a.w + b.w, a.x + b.x, a.y + b.y, a.z + b.z }; return r; }
static inline dq dq_conj(dq a) { dq r = { a.w, -a.x, -a.y, -a.z }; return r; }
static inline dq dq_mul(dq a, dq b) { return ref_quat_mul(a, b); }
/* Rotation angle (rad, [0, pi]) between two quaternions, normalised first; the same for b and -b. */
static inline double dq_angle(dq a, dq b) { return ref_quat_angle_between(a, b); }
/* The rotation of a float32 quaternion: its exact value, normalised in double. */
static inline dq dq_unit_from_f(qo_quat_f32 q) { return ref_quat_normalize(ref_quat_from_f32(q)); }
/* Rotation matrix of q/|q| (ref_quat_to_mat3) as a plain array. */
static inline void dq_to_mat(dq q, double m[3][3])
{
    ref_mat3 r = ref_quat_to_mat3(q);
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) m[i][j] = r.m[i][j];
}
/* Canonical unit quaternion of a rotation matrix given as a plain array (ref_mat3_to_quat). */
static inline dq dq_from_mat(double m[3][3])
{
    ref_mat3 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = m[i][j];
    return ref_mat3_to_quat(&r);
}
/* rotation by angle about the axis (ax, ay, az), which need not be unit */
static inline dq dq_axis_angle(double ax, double ay, double az, double ang)
{
    ref_vec3 a = { ax, ay, az };
    return ref_quat_from_axis_angle(a, ang);
}

#endif
