/* Quaternion algebra in fixed point (Q1.30). See qorient/quat_fx.h for the contracts.
 * Integer arithmetic only: products in int64, sums rounded once with qo_fx_sum_round_i64. */
#include "qorient/quat_fx.h"

#include "qorient/convert_fx.h"
#include "qorient/fxmath.h"

qo_quat_q30 qo_quat_identity_q30(void)
{
    qo_quat_q30 q = { QO_Q30_ONE, 0, 0, 0 };
    return q;
}

/* round((p0 + p1 + p2 + p3) / 2^30) of four signed Q2.60 products. */
static int64_t sum4(int64_t p0, int64_t p1, int64_t p2, int64_t p3)
{
    int64_t t[4];
    t[0] = p0; t[1] = p1; t[2] = p2; t[3] = p3;
    return qo_fx_sum_round_i64(t, 4, 30);
}

#define P(a, b) ((int64_t)(a) * (b))

/* The four components of a*b, exact then rounded once, not saturated (|.| <= 2^34). */
static void mul_wide(qo_quat_q30 a, qo_quat_q30 b, int64_t r[4])
{
    r[0] = sum4(P(a.w, b.w), -P(a.x, b.x), -P(a.y, b.y), -P(a.z, b.z));
    r[1] = sum4(P(a.w, b.x), P(a.x, b.w), P(a.y, b.z), -P(a.z, b.y));
    r[2] = sum4(P(a.w, b.y), -P(a.x, b.z), P(a.y, b.w), P(a.z, b.x));
    r[3] = sum4(P(a.w, b.z), P(a.x, b.y), -P(a.y, b.x), P(a.z, b.w));
}

static int sat_quat(const int64_t r[4], qo_quat_q30 *out)
{
    int i, over = 0;
    int32_t c[4];
    for (i = 0; i < 4; i++) {
        c[i] = qo_fx_sat_i32(r[i]);
        if ((int64_t)c[i] != r[i]) over = 1;
    }
    out->w = c[0]; out->x = c[1]; out->y = c[2]; out->z = c[3];
    return over;
}

qo_quat_q30 qo_quat_mul_q30(qo_quat_q30 a, qo_quat_q30 b)
{
    int64_t r[4];
    qo_quat_q30 out;
    mul_wide(a, b, r);
    (void)sat_quat(r, &out);
    return out;
}

qo_status qo_quat_mul_q30_checked(qo_quat_q30 a, qo_quat_q30 b, qo_quat_q30 *out)
{
    int64_t r[4];
    if (out == NULL) return QO_E_NULL;
    mul_wide(a, b, r);
    return sat_quat(r, out) ? QO_E_OVERFLOW : QO_OK;
}

qo_quat_q30 qo_quat_conj_q30(qo_quat_q30 q)
{
    qo_quat_q30 r;
    r.w = q.w;
    r.x = qo_fx_neg_q30(q.x);
    r.y = qo_fx_neg_q30(q.y);
    r.z = qo_fx_neg_q30(q.z);
    return r;
}

qo_quat_q30 qo_quat_inverse_q30(qo_quat_q30 q)
{
    return qo_quat_conj_q30(q);
}

qo_q30 qo_quat_dot_q30(qo_quat_q30 a, qo_quat_q30 b)
{
    return qo_fx_sat_i32(sum4(P(a.w, b.w), P(a.x, b.x), P(a.y, b.y), P(a.z, b.z)));
}

qo_q30 qo_quat_norm_q30(qo_quat_q30 q)
{
    return qo_fx_norm4_q30(q.w, q.x, q.y, q.z);
}

static uint64_t mag(int64_t v) { return (uint64_t)(v < 0 ? -v : v); }

/* round(num / den) to nearest, ties away from zero; den > 0, |num| < 2^63. */
static int64_t div_round(int64_t num, uint64_t den)
{
    uint64_t q = (mag(num) + den / 2u) / den;
    return num < 0 ? -(int64_t)q : (int64_t)q;
}

qo_status qo_quat_normalize_q30(qo_quat_q30 q, qo_quat_q30 *out)
{
    int64_t c[4];
    uint64_t m = 0, n2, n;
    int i;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_q30();
    c[0] = q.w; c[1] = q.x; c[2] = q.y; c[3] = q.z;
    for (i = 0; i < 4; i++) if (mag(c[i]) > m) m = mag(c[i]);
    if (m == 0) return QO_E_DEGENERATE;
    /* Scale (exactly) so the largest component is in [2^30, 2^31]: short quaternions keep
     * their direction to full precision and |c|^2 uses the whole 64 bits. */
    while (m < ((uint64_t)1 << 30)) {
        m <<= 1;
        for (i = 0; i < 4; i++) c[i] *= 2;
    }
    /* Four components below 2^31 sum to below 2^64; only four of exactly 2^31 (all INT32_MIN)
     * would carry, and halving those is exact. */
    if (m == ((uint64_t)1 << 31)) {
        int all = 1;
        for (i = 0; i < 4; i++) if (mag(c[i]) != m) all = 0;
        if (all) for (i = 0; i < 4; i++) c[i] /= 2;
    }
    n2 = 0;
    for (i = 0; i < 4; i++) n2 += mag(c[i]) * mag(c[i]);
    n = qo_fx_sqrt_u64(n2);   /* |c| in units where 2^30 is 1, >= 2^30 */
    out->w = qo_fx_sat_i32(div_round(c[0] * QO_Q30_ONE, n));
    out->x = qo_fx_sat_i32(div_round(c[1] * QO_Q30_ONE, n));
    out->y = qo_fx_sat_i32(div_round(c[2] * QO_Q30_ONE, n));
    out->z = qo_fx_sat_i32(div_round(c[3] * QO_Q30_ONE, n));
    return QO_OK;
}

qo_quat_q30 qo_quat_canonical_q30(qo_quat_q30 q)
{
    int neg;
    qo_quat_q30 r;
    if (q.w != 0) neg = q.w < 0;
    else if (q.x != 0) neg = q.x < 0;
    else if (q.y != 0) neg = q.y < 0;
    else neg = q.z < 0;
    if (!neg) return q;
    r.w = qo_fx_neg_q30(q.w);
    r.x = qo_fx_neg_q30(q.x);
    r.y = qo_fx_neg_q30(q.y);
    r.z = qo_fx_neg_q30(q.z);
    return r;
}

qo_vec3_q30 qo_quat_rotate_q30(qo_quat_q30 q, qo_vec3_q30 v)
{
    int64_t tt[7];
    int32_t tx, ty, tz;
    qo_vec3_q30 r;
    /* t = u x v, rounded once and saturated so every later product stays <= 2^62. */
    tx = qo_fx_sat_i32(sum4(P(q.y, v.z), -P(q.z, v.y), 0, 0));
    ty = qo_fx_sat_i32(sum4(P(q.z, v.x), -P(q.x, v.z), 0, 0));
    tz = qo_fx_sat_i32(sum4(P(q.x, v.y), -P(q.y, v.x), 0, 0));
    /* v' = v + 2 w t + 2 u x t: seven terms of at most 2^62, summed exactly. */
    tt[0] = (int64_t)v.x * QO_Q30_ONE;
    tt[1] = tt[2] = P(q.w, tx);
    tt[3] = tt[4] = P(q.y, tz);
    tt[5] = tt[6] = -P(q.z, ty);
    r.x = qo_fx_sat_i32(qo_fx_sum_round_i64(tt, 7, 30));
    tt[0] = (int64_t)v.y * QO_Q30_ONE;
    tt[1] = tt[2] = P(q.w, ty);
    tt[3] = tt[4] = P(q.z, tx);
    tt[5] = tt[6] = -P(q.x, tz);
    r.y = qo_fx_sat_i32(qo_fx_sum_round_i64(tt, 7, 30));
    tt[0] = (int64_t)v.z * QO_Q30_ONE;
    tt[1] = tt[2] = P(q.w, tz);
    tt[3] = tt[4] = P(q.x, ty);
    tt[5] = tt[6] = -P(q.y, tx);
    r.z = qo_fx_sat_i32(qo_fx_sum_round_i64(tt, 7, 30));
    return r;
}

/* atan2(|(x, y, z)|, w) in Q3.28 from 64-bit components of any common scale (|.| <= 2^35):
 * scaled down together until the vector norm and w fit int32. */
static qo_q28 half_angle(int64_t w, int64_t x, int64_t y, int64_t z)
{
    uint64_t m = mag(x);
    uint64_t n;
    if (mag(y) > m) m = mag(y);
    if (mag(z) > m) m = mag(z);
    if (mag(w) > m) m = mag(w);
    /* Components below 2^30 keep |v| < 2^31 (sqrt 3 * 2^30 < 2^31). */
    while (m >= ((uint64_t)1 << 30)) {
        m >>= 1;
        w /= 2; x /= 2; y /= 2; z /= 2;
    }
    n = qo_fx_sqrt_u64(mag(x) * mag(x) + mag(y) * mag(y) + mag(z) * mag(z));
    return qo_fx_atan2_q28((int32_t)n, (int32_t)w);
}

qo_q28 qo_quat_angle_between_q30(qo_quat_q30 a, qo_quat_q30 b)
{
    int64_t r[4];
    mul_wide(qo_quat_conj_q30(a), b, r);
    /* Precision: for unit inputs the components are < 2^31 and nothing is shifted. */
    return (qo_q28)(2 * half_angle(r[0] < 0 ? -r[0] : r[0], r[1], r[2], r[3]));
}

qo_status qo_quat_exp_q30(qo_vec3_q28 v, qo_quat_q30 *out)
{
    qo_vec3_q28 rv;
    const int32_t lim = 4 * QO_Q28_ONE;
    if (out == NULL) return QO_E_NULL;
    if (v.x >= lim || v.x <= -lim || v.y >= lim || v.y <= -lim || v.z >= lim || v.z <= -lim) {
        *out = qo_quat_identity_q30();
        return QO_E_RANGE;
    }
    /* exp((0, v)) is the rotation by the rotation vector 2v; doubling is exact here. */
    rv.x = 2 * v.x; rv.y = 2 * v.y; rv.z = 2 * v.z;
    return qo_quat_from_rotvec_q30(rv, out);
}

qo_status qo_quat_log_q30(qo_quat_q30 q, qo_vec3_q28 *out)
{
    uint64_t n, m;
    int64_t c[3];
    int64_t phi;
    if (out == NULL) return QO_E_NULL;
    out->x = out->y = out->z = 0;
    if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) return QO_E_DEGENERATE;
    if (q.x == 0 && q.y == 0 && q.z == 0) {
        if (q.w < 0) out->x = QO_Q28_PI;
        return QO_OK;
    }
    phi = half_angle(q.w, q.x, q.y, q.z);
    /* phi * u_i / |u|. u is first scaled (exactly) so its largest component is in
     * [2^30, 2^31]: then the rounded |u| is good to 2^-31 relative even for a short u (a
     * rotation near 2pi), and phi * c_i <= 2^61. */
    c[0] = q.x; c[1] = q.y; c[2] = q.z;
    m = mag(c[0]);
    if (mag(c[1]) > m) m = mag(c[1]);
    if (mag(c[2]) > m) m = mag(c[2]);
    while (m < ((uint64_t)1 << 30)) {
        m <<= 1;
        c[0] *= 2; c[1] *= 2; c[2] *= 2;
    }
    n = qo_fx_sqrt_u64(mag(c[0]) * mag(c[0]) + mag(c[1]) * mag(c[1]) + mag(c[2]) * mag(c[2]));
    out->x = (qo_q28)div_round(phi * c[0], n);
    out->y = (qo_q28)div_round(phi * c[1], n);
    out->z = (qo_q28)div_round(phi * c[2], n);
    return QO_OK;
}

qo_status qo_quat_integrate_q30(qo_quat_q30 q, qo_vec3_q28 dtheta, qo_quat_q30 *out)
{
    qo_quat_q30 dq, qn;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    st = qo_quat_normalize_q30(q, &qn);
    if (st != QO_OK) { *out = qn; return st; }
    (void)qo_quat_from_rotvec_q30(dtheta, &dq);
    return qo_quat_normalize_q30(qo_quat_mul_q30(qn, dq), out);
}
