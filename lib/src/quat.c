/* Quaternion algebra, float32. See qorient/quat.h for the contract of each function. */
/* The header's inline functions are also compiled here as external definitions (ABI). */
#define QORIENT_QUAT_EXTERN_DEFS
#include "qorient/quat.h"

#include <math.h>

#include "qorient/fmath.h"

float qo_quat_norm_f32(qo_quat_f32 q)
{
    /* Scale by the largest magnitude so that the sum of squares neither overflows (components
     * near FLT_MAX) nor underflows (components near FLT_MIN): the naive form returns Inf or 0
     * for quaternions that are perfectly normalisable. */
    float m = fabsf(q.w);
    float w, x, y, z;
    if (fabsf(q.x) > m) m = fabsf(q.x);
    if (fabsf(q.y) > m) m = fabsf(q.y);
    if (fabsf(q.z) > m) m = fabsf(q.z);
    if (!(m > 0.0f)) {
        /* m is 0, or NaN (comparisons with NaN are false): propagate NaN, else 0. */
        return (isnan(q.w) || isnan(q.x) || isnan(q.y) || isnan(q.z)) ? NAN : 0.0f;
    }
    /* NaN first: the header promises NaN for any NaN input, also next to an Inf. */
    if (isnan(q.w) || isnan(q.x) || isnan(q.y) || isnan(q.z)) return NAN;
    if (isinf(m)) return INFINITY;
    /* Fast path: no risk of overflow or harmful underflow. */
    if (m > 1e-18f && m < 1e18f) {
        return sqrtf(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    }
    /* Divide rather than multiply by 1/m: for m above ~3e38 or below ~3e-39 the reciprocal is
     * subnormal or overflows, and a subnormal 1/m has too few bits (norm(FLT_MAX,0,0,0) came
     * out an ulp low; 3e38 too). The division of a component by the largest one is exact-ish
     * and always in [-1, 1]. */
    w = q.w / m; x = q.x / m; y = q.y / m; z = q.z / m;
    return m * sqrtf(w * w + x * x + y * y + z * z);
}

qo_status qo_quat_normalize_full_f32(qo_quat_f32 q, qo_quat_f32 *out)
{
    float n, r, inv, m;
    if (out == NULL) return QO_E_NULL;
    /* The inline fast path's case first, the same expressions and test (every quaternion in
     * ordinary use): r = sqrt(n) and r / n both >= 1e-15 mean a sum of squares n in ~[1e-30,
     * 1e30], finite, so every component is finite, and large enough that no square that
     * matters lost bits to underflow. */
    n = qo_quat_internal_sumsq_f32(q);
    r = sqrtf(n);
    inv = r / n;
    if (r >= 1e-15f && inv >= 1e-15f) {
        out->w = q.w * inv; out->x = q.x * inv; out->y = q.y * inv; out->z = q.z * inv;
        return QO_OK;
    }
    *out = qo_quat_identity_f32();
    if (!qo_quat_is_finite_f32(q)) return QO_E_NONFINITE;
    /* |q| itself overflows float for components near FLT_MAX although q/|q| is perfectly
     * representable: bring the largest component to 1 first when it is far from 1. */
    m = fabsf(q.w);
    if (fabsf(q.x) > m) m = fabsf(q.x);
    if (fabsf(q.y) > m) m = fabsf(q.y);
    if (fabsf(q.z) > m) m = fabsf(q.z);
    if (m > 1e18f || (m > 0.0f && m < 1e-18f)) {
        q.w /= m; q.x /= m; q.y /= m; q.z /= m;
    }
    n = qo_quat_norm_f32(q);
    if (!(n > 0.0f) || isinf(n)) return QO_E_DEGENERATE;
    inv = 1.0f / n;
    if (isinf(inv)) {
        /* n is subnormal: divide instead of multiplying by an overflowing reciprocal. */
        out->w = q.w / n; out->x = q.x / n; out->y = q.y / n; out->z = q.z / n;
    } else {
        out->w = q.w * inv; out->x = q.x * inv; out->y = q.y * inv; out->z = q.z * inv;
    }
    return QO_OK;
}

qo_status qo_quat_inverse_f32(qo_quat_f32 q, qo_quat_f32 *out)
{
    float n, inv;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    if (!qo_quat_is_finite_f32(q)) return QO_E_NONFINITE;
    n = qo_quat_norm_f32(q);
    if (!(n > 0.0f) || isinf(n)) return QO_E_DEGENERATE;
    /* conj(q)/|q|^2 computed as (conj(q)/|q|)/|q| so |q|^2 never over- or underflows. */
    inv = 1.0f / n;
    if (isinf(inv) || inv == 0.0f) {
        out->w = (q.w / n) / n; out->x = (-q.x / n) / n;
        out->y = (-q.y / n) / n; out->z = (-q.z / n) / n;
    } else {
        out->w = q.w * inv * inv; out->x = -q.x * inv * inv;
        out->y = -q.y * inv * inv; out->z = -q.z * inv * inv;
    }
    if (!qo_quat_is_finite_f32(*out)) {
        *out = qo_quat_identity_f32();
        return QO_E_DEGENERATE;
    }
    return QO_OK;
}

float qo_quat_angle_between_f32(qo_quat_f32 a, qo_quat_f32 b)
{
    qo_quat_f32 d = qo_quat_mul_f32(qo_quat_conj_f32(a), b);
    float vn = sqrtf(d.x * d.x + d.y * d.y + d.z * d.z);
    return 2.0f * qo_fm_atan2_f32(vn, fabsf(d.w));
}

/* sin(r)/r, accurate also for r -> 0 where the quotient loses all digits. */
static float sinc_f32(float r)
{
    if (r < 1e-2f) {
        float r2 = r * r;
        return 1.0f - r2 * (1.0f / 6.0f) * (1.0f - r2 * (1.0f / 20.0f));
    }
    return qo_fm_sin_f32(r) / r;
}

qo_status qo_quat_exp_f32(qo_vec3_f32 v, qo_quat_f32 *out)
{
    float r, k;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    if (!isfinite(v.x) || !isfinite(v.y) || !isfinite(v.z)) return QO_E_NONFINITE;
    r = sqrtf(v.x * v.x + v.y * v.y + v.z * v.z);
    if (isinf(r)) return QO_E_NONFINITE;
    k = sinc_f32(r);
    out->w = qo_fm_cos_f32(r);
    out->x = k * v.x; out->y = k * v.y; out->z = k * v.z;
    return QO_OK;
}

qo_status qo_quat_log_f32(qo_quat_f32 q, qo_vec3_f32 *out)
{
    float n, vn, ang, m;
    qo_quat_f32 v;
    if (out == NULL) return QO_E_NULL;
    out->x = out->y = out->z = 0.0f;
    if (!qo_quat_is_finite_f32(q)) return QO_E_NONFINITE;
    /* Huge components: |q| or |v| would overflow. Scale by 2^-64 (exact); the angle and the
     * axis do not depend on the scale. */
    m = fabsf(q.w);
    if (fabsf(q.x) > m) m = fabsf(q.x);
    if (fabsf(q.y) > m) m = fabsf(q.y);
    if (fabsf(q.z) > m) m = fabsf(q.z);
    if (m > 1e18f) {
        q.w *= 0x1p-64f; q.x *= 0x1p-64f; q.y *= 0x1p-64f; q.z *= 0x1p-64f;
    }
    n = qo_quat_norm_f32(q);
    if (!(n > 0.0f)) return QO_E_DEGENERATE;
    /* |v| with the scaled norm: a naive sqrt(x^2+y^2+z^2) underflows to 0 for |v| < 1e-19,
     * which dropped the vector part (and near w = -1 replaced its axis by the fallback x). */
    v.w = 0.0f; v.x = q.x; v.y = q.y; v.z = q.z;
    vn = qo_quat_norm_f32(v);
    if (vn == 0.0f) {
        /* Real quaternion: no rotation for w > 0; for w < 0 the angle is pi about an arbitrary
         * axis - we take x and say so in the header. */
        if (q.w < 0.0f) out->x = 3.14159265358979f;
        return QO_OK;
    }
    ang = qo_fm_atan2_f32(vn, q.w);
    /* angle * unit axis; v/vn rather than (ang/vn)*v so a subnormal vn cannot overflow. */
    out->x = ang * (q.x / vn); out->y = ang * (q.y / vn); out->z = ang * (q.z / vn);
    return QO_OK;
}

qo_status qo_quat_integrate_f32(qo_quat_f32 q, qo_vec3_f32 omega, float dt, qo_quat_f32 *out)
{
    qo_quat_f32 dq, qn;
    qo_vec3_f32 half;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    st = qo_quat_normalize_f32(q, &qn);
    *out = qn;
    if (st != QO_OK) return st;
    if (!isfinite(omega.x) || !isfinite(omega.y) || !isfinite(omega.z) || !isfinite(dt))
        return QO_E_NONFINITE;
    half.x = 0.5f * omega.x * dt; half.y = 0.5f * omega.y * dt; half.z = 0.5f * omega.z * dt;
    st = qo_quat_exp_f32(half, &dq);
    if (st != QO_OK) return st;
    return qo_quat_normalize_f32(qo_quat_mul_f32(qn, dq), out);
}
