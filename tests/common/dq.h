/*
 * tests/common/dq.h - the small double-precision quaternion algebra that the interpolation tests
 * and accuracy programs (tests/test_interp*.c, bench/accuracy_interp*.c) compute their
 * references with. Written independently of the library; static inline so each user takes what
 * it needs (the bench programs are built from one source file and include this header).
 */
#ifndef QORIENT_TESTS_DQ_H
#define QORIENT_TESTS_DQ_H

#include <math.h>

#include "qorient/types.h"

typedef struct { double w, x, y, z; } dq;

static inline qo_quat_f32 f_from(dq q)
{
    qo_quat_f32 r = { (float)q.w, (float)q.x, (float)q.y, (float)q.z };
    return r;
}
static inline double dq_dot(dq a, dq b) { return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z; }
static inline double dq_norm(dq a) { return sqrt(dq_dot(a, a)); }
static inline dq dq_scale(dq a, double k) { dq r = { a.w * k, a.x * k, a.y * k, a.z * k }; return r; }
static inline dq dq_neg(dq a) { return dq_scale(a, -1.0); }
static inline dq dq_unit(dq a) { return dq_scale(a, 1.0 / dq_norm(a)); }
static inline dq dq_add(dq a, dq b) { dq r = { a.w + b.w, a.x + b.x, a.y + b.y, a.z + b.z }; return r; }
static inline dq dq_conj(dq a) { dq r = { a.w, -a.x, -a.y, -a.z }; return r; }
static inline dq dq_mul(dq a, dq b)
{
    dq r;
    r.w = a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z;
    r.x = a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y;
    r.y = a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x;
    r.z = a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w;
    return r;
}
/* rotation by angle about the axis (ax, ay, az), which need not be unit */
static inline dq dq_axis_angle(double ax, double ay, double az, double ang)
{
    double n = sqrt(ax * ax + ay * ay + az * az), s = sin(ang / 2) / n;
    dq r = { cos(ang / 2), ax * s, ay * s, az * s };
    return r;
}

#endif
