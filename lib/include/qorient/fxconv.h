/*
 * qorient/fxconv.h - the float32 <-> fixed-point boundary.
 *
 * Everything here is `static inline` on purpose: firmware for an FPU-less core that never
 * includes this header links none of it (and so no soft-float helper). Include it where
 * float values enter or leave the fixed core (host tools, tests, an M4F talking to an M0+).
 *
 * Index:
 *   qo_q30_from_f32, qo_q28_from_f32, qo_q16_from_f32        float -> fixed, saturating
 *   qo_q30_from_f32_checked, ..._q28_..., ..._q16_...         same, with a status
 *   qo_q30_to_f32, qo_q28_to_f32, qo_q16_to_f32               fixed -> float (nearest float)
 *   qo_q30_quat_from_f32, qo_q30_quat_to_f32                  quaternion, component-wise
 *   qo_q30_vec3_from_f32, qo_q30_vec3_to_f32                  Q1.30 vector
 *   qo_q28_vec3_from_f32, qo_q28_vec3_to_f32                  Q3.28 vector (rotation vector)
 *   qo_q30_mat3_from_f32, qo_q30_mat3_to_f32                  Q1.30 matrix
 *
 * float -> fixed: value * 2^F rounded to the nearest integer, ties away from zero (exact: the
 * scaling by a power of two is exact and the rounding uses the exact fractional part, so e.g.
 * 0.49999997 * 2^0 does not round up), then saturated to [INT32_MIN, INT32_MAX].
 * NaN gives 0 in the unchecked form. The _checked forms return QO_OK; QO_E_NULL (out NULL);
 * QO_E_NONFINITE for NaN (*out = 0) or +-Inf (*out saturated by sign); QO_E_OVERFLOW when the
 * rounded value does not fit (*out saturated).
 * fixed -> float: the float nearest raw / 2^F (one rounding, in the int -> float conversion).
 * The struct forms never fail: they use the saturating scalar form per component.
 */
#ifndef QORIENT_FXCONV_H
#define QORIENT_FXCONV_H

#include <float.h>

#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* scale = 2^F as a float. Returns the status and writes the saturated rounded raw value. */
static inline qo_status qo_fxconv_from_f32_scaled(float v, float scale, int32_t *out)
{
    float s, frac;
    int32_t t;
    /* Ordered comparisons only (clean under -Wfloat-equal): NaN fails both, Inf one. */
    if (!(v <= FLT_MAX && v >= -FLT_MAX)) {
        *out = v > 0.0f ? INT32_MAX : v < 0.0f ? INT32_MIN : 0;
        return QO_E_NONFINITE;
    }
    s = v * scale;   /* exact unless it overflows to Inf, which saturates below */
    if (s >= 2147483648.0f) { *out = INT32_MAX; return QO_E_OVERFLOW; }
    if (s < -2147483648.0f) { *out = INT32_MIN; return QO_E_OVERFLOW; }
    t = (int32_t)s;              /* toward zero; in range */
    frac = s - (float)t;         /* exact */
    if (frac >= 0.5f) {
        if (t == INT32_MAX) { *out = INT32_MAX; return QO_E_OVERFLOW; }
        t++;
    } else if (frac <= -0.5f) {
        if (t == INT32_MIN) { *out = INT32_MIN; return QO_E_OVERFLOW; }
        t--;
    }
    *out = t;
    return QO_OK;
}

static inline qo_status qo_q30_from_f32_checked(float v, qo_q30 *out)
{
    if (out == NULL) return QO_E_NULL;
    return qo_fxconv_from_f32_scaled(v, 1073741824.0f, out);
}
static inline qo_status qo_q28_from_f32_checked(float v, qo_q28 *out)
{
    if (out == NULL) return QO_E_NULL;
    return qo_fxconv_from_f32_scaled(v, 268435456.0f, out);
}
static inline qo_status qo_q16_from_f32_checked(float v, qo_q16 *out)
{
    if (out == NULL) return QO_E_NULL;
    return qo_fxconv_from_f32_scaled(v, 65536.0f, out);
}

static inline qo_q30 qo_q30_from_f32(float v) { qo_q30 r; (void)qo_q30_from_f32_checked(v, &r); return r; }
static inline qo_q28 qo_q28_from_f32(float v) { qo_q28 r; (void)qo_q28_from_f32_checked(v, &r); return r; }
static inline qo_q16 qo_q16_from_f32(float v) { qo_q16 r; (void)qo_q16_from_f32_checked(v, &r); return r; }

static inline float qo_q30_to_f32(qo_q30 v) { return (float)v * (1.0f / 1073741824.0f); }
static inline float qo_q28_to_f32(qo_q28 v) { return (float)v * (1.0f / 268435456.0f); }
static inline float qo_q16_to_f32(qo_q16 v) { return (float)v * (1.0f / 65536.0f); }

static inline qo_quat_q30 qo_q30_quat_from_f32(qo_quat_f32 q)
{
    qo_quat_q30 r;
    r.w = qo_q30_from_f32(q.w); r.x = qo_q30_from_f32(q.x);
    r.y = qo_q30_from_f32(q.y); r.z = qo_q30_from_f32(q.z);
    return r;
}
static inline qo_quat_f32 qo_q30_quat_to_f32(qo_quat_q30 q)
{
    qo_quat_f32 r;
    r.w = qo_q30_to_f32(q.w); r.x = qo_q30_to_f32(q.x);
    r.y = qo_q30_to_f32(q.y); r.z = qo_q30_to_f32(q.z);
    return r;
}
static inline qo_vec3_q30 qo_q30_vec3_from_f32(qo_vec3_f32 v)
{
    qo_vec3_q30 r;
    r.x = qo_q30_from_f32(v.x); r.y = qo_q30_from_f32(v.y); r.z = qo_q30_from_f32(v.z);
    return r;
}
static inline qo_vec3_f32 qo_q30_vec3_to_f32(qo_vec3_q30 v)
{
    qo_vec3_f32 r;
    r.x = qo_q30_to_f32(v.x); r.y = qo_q30_to_f32(v.y); r.z = qo_q30_to_f32(v.z);
    return r;
}
static inline qo_vec3_q28 qo_q28_vec3_from_f32(qo_vec3_f32 v)
{
    qo_vec3_q28 r;
    r.x = qo_q28_from_f32(v.x); r.y = qo_q28_from_f32(v.y); r.z = qo_q28_from_f32(v.z);
    return r;
}
static inline qo_vec3_f32 qo_q28_vec3_to_f32(qo_vec3_q28 v)
{
    qo_vec3_f32 r;
    r.x = qo_q28_to_f32(v.x); r.y = qo_q28_to_f32(v.y); r.z = qo_q28_to_f32(v.z);
    return r;
}
static inline qo_mat3_q30 qo_q30_mat3_from_f32(const qo_mat3_f32 *m)
{
    qo_mat3_q30 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = qo_q30_from_f32(m->m[i][j]);
    return r;
}
static inline qo_mat3_f32 qo_q30_mat3_to_f32(const qo_mat3_q30 *m)
{
    qo_mat3_f32 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = qo_q30_to_f32(m->m[i][j]);
    return r;
}

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_FXCONV_H */
