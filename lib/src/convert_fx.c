/* Rotation conversions in fixed point (Q1.30 / Q3.28). See qorient/convert_fx.h.
 * Integer arithmetic only, on the primitives of qorient/fxmath.h. */
#include "qorient/convert_fx.h"

#include "qorient/fxmath.h"
#include "qorient/quat_fx.h"

#include "fx_internal.h"

#define P(a, b) ((int64_t)(a) * (b))

static qo_mat3_q30 mat3_identity(void)
{
    qo_mat3_q30 m = { { { QO_Q30_ONE, 0, 0 }, { 0, QO_Q30_ONE, 0 }, { 0, 0, QO_Q30_ONE } } };
    return m;
}

/* The three components of a non-zero int32 vector scaled exactly (by a power of two) so the
 * largest magnitude is in [2^30, 2^31], and its length in the same units (>= 2^30; the
 * squares of three values <= 2^31 sum below 2^64). Returns 0 for the zero vector. */
static uint64_t scale_vec3(int64_t c[3])
{
    uint64_t m = qo_fx_abs_u64(c[0]);
    int i;
    if (qo_fx_abs_u64(c[1]) > m) m = qo_fx_abs_u64(c[1]);
    if (qo_fx_abs_u64(c[2]) > m) m = qo_fx_abs_u64(c[2]);
    if (m == 0) return 0;
    while (m < ((uint64_t)1 << 30)) {
        m <<= 1;
        for (i = 0; i < 3; i++) c[i] *= 2;
    }
    return qo_fx_sqrt_u64(qo_fx_abs_u64(c[0]) * qo_fx_abs_u64(c[0]) + qo_fx_abs_u64(c[1]) * qo_fx_abs_u64(c[1]) + qo_fx_abs_u64(c[2]) * qo_fx_abs_u64(c[2]));
}

qo_status qo_axis_angle_to_quat_q30(qo_vec3_q30 axis, qo_q28 angle, qo_quat_q30 *out)
{
    int64_t c[3];
    uint64_t n;
    qo_q30 s, co;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_q30();
    c[0] = axis.x; c[1] = axis.y; c[2] = axis.z;
    n = scale_vec3(c);
    if (n == 0) return QO_E_DEGENERATE;
    (void)qo_fx_sincos_half_q28(angle, &s, &co);
    /* sin(angle/2) * c_i / |c|, one rounding; |c_i * s| <= 2^61. */
    out->w = co;
    out->x = (qo_q30)qo_fx_div_round_away(c[0] * s, n);
    out->y = (qo_q30)qo_fx_div_round_away(c[1] * s, n);
    out->z = (qo_q30)qo_fx_div_round_away(c[2] * s, n);
    return QO_OK;
}

qo_status qo_axis_angle_from_quat_q30(qo_quat_q30 q, qo_vec3_q30 *axis, qo_q28 *angle)
{
    qo_quat_q30 u;
    int64_t c[3];
    uint64_t n;
    if (axis != NULL) { axis->x = QO_Q30_ONE; axis->y = 0; axis->z = 0; }
    if (angle != NULL) *angle = 0;
    if (axis == NULL || angle == NULL) return QO_E_NULL;
    if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) return QO_E_DEGENERATE;
    /* Work on q itself, not on a rounded unit copy: the axis of a small rotation comes from a
     * short vector part, whose direction a Q1.30 normalisation would blur. */
    u = qo_quat_canonical_q30(q);
    c[0] = u.x; c[1] = u.y; c[2] = u.z;
    n = scale_vec3(c);
    if (n == 0) return QO_OK;   /* zero rotation: axis (1, 0, 0), angle 0 */
    axis->x = (qo_q30)qo_fx_div_round_away(c[0] * QO_Q30_ONE, n);
    axis->y = (qo_q30)qo_fx_div_round_away(c[1] * QO_Q30_ONE, n);
    axis->z = (qo_q30)qo_fx_div_round_away(c[2] * QO_Q30_ONE, n);
    /* 2 atan2(|v|, |w|), scale-free: the angle between the identity and q. */
    *angle = qo_quat_angle_between_q30(qo_quat_identity_q30(), u);
    return QO_OK;
}

qo_status qo_rotvec_to_quat_q30(qo_vec3_q28 rv, qo_quat_q30 *out)
{
    return qo_fx_quat_from_rotvec(rv, out);
}

qo_status qo_rotvec_from_quat_q30(qo_quat_q30 q, qo_vec3_q28 *out)
{
    qo_vec3_q28 h;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    out->x = out->y = out->z = 0;
    /* With w >= 0 the half-angle vector of the log is at most pi/2 long: doubling fits. */
    st = qo_quat_log_q30(qo_quat_canonical_q30(q), &h);
    if (st != QO_OK) return st;
    out->x = 2 * h.x;
    out->y = 2 * h.y;
    out->z = 2 * h.z;
    return QO_OK;
}

/* round(sum of n terms / 2^30), saturated: one matrix entry from Q2.60 products. */
static qo_q30 entry(const int64_t *t, size_t n)
{
    return qo_fx_sat_i32(qo_fx_sum_round_i64(t, n, 30));
}

/* The same from Q2.62 products. */
static qo_q30 entry32(const int64_t *t, size_t n)
{
    return qo_fx_sat_i32(qo_fx_sum_round_i64(t, n, 32));
}

/* q / |q| with components in Q1.31 held in int64 (one more bit than Q1.30, so the matrix
 * entries built from products of them round to Q1.30 with less accumulated error).
 * Returns 0 for q == 0. Same scaling scheme as qo_quat_normalize_q30. */
static int unit_q31(qo_quat_q30 q, int64_t u[4])
{
    int64_t c[4];
    uint64_t m = 0, n2 = 0, n;
    int i, all = 1;
    c[0] = q.w; c[1] = q.x; c[2] = q.y; c[3] = q.z;
    for (i = 0; i < 4; i++) if (qo_fx_abs_u64(c[i]) > m) m = qo_fx_abs_u64(c[i]);
    if (m == 0) return 0;
    while (m < ((uint64_t)1 << 30)) {
        m <<= 1;
        for (i = 0; i < 4; i++) c[i] *= 2;
    }
    for (i = 0; i < 4; i++) if (qo_fx_abs_u64(c[i]) != ((uint64_t)1 << 31)) all = 0;
    if (all) for (i = 0; i < 4; i++) c[i] /= 2;   /* four of 2^31 would carry out of 64 bits */
    for (i = 0; i < 4; i++) n2 += qo_fx_abs_u64(c[i]) * qo_fx_abs_u64(c[i]);
    n = qo_fx_sqrt_u64(n2);
    for (i = 0; i < 4; i++) u[i] = qo_fx_div_round_away(c[i] * ((int64_t)1 << 31), n);
    return 1;
}

qo_status qo_mat3_from_quat_q30(qo_quat_q30 q, qo_mat3_q30 *out)
{
    int64_t u[4], t[5];
    int64_t xx, yy, zz, xy, xz, yz, wx, wy, wz;
    const int64_t one = (int64_t)1 << 62;
    if (out == NULL) return QO_E_NULL;
    *out = mat3_identity();
    if (!unit_q31(q, u)) return QO_E_DEGENERATE;
    /* Products of Q1.31 unit components are Q2.62 and at most 2^62; the factor 2 is written
     * as two terms; each entry is the exact sum rounded once to Q1.30. */
    xx = u[1] * u[1]; yy = u[2] * u[2]; zz = u[3] * u[3];
    xy = u[1] * u[2]; xz = u[1] * u[3]; yz = u[2] * u[3];
    wx = u[0] * u[1]; wy = u[0] * u[2]; wz = u[0] * u[3];
    t[0] = one; t[1] = t[2] = -yy; t[3] = t[4] = -zz; out->m[0][0] = entry32(t, 5);
    t[0] = one; t[1] = t[2] = -xx; t[3] = t[4] = -zz; out->m[1][1] = entry32(t, 5);
    t[0] = one; t[1] = t[2] = -xx; t[3] = t[4] = -yy; out->m[2][2] = entry32(t, 5);
    t[0] = t[1] = xy; t[2] = t[3] = -wz; out->m[0][1] = entry32(t, 4);
    t[0] = t[1] = xy; t[2] = t[3] = wz;  out->m[1][0] = entry32(t, 4);
    t[0] = t[1] = xz; t[2] = t[3] = wy;  out->m[0][2] = entry32(t, 4);
    t[0] = t[1] = xz; t[2] = t[3] = -wy; out->m[2][0] = entry32(t, 4);
    t[0] = t[1] = yz; t[2] = t[3] = -wx; out->m[1][2] = entry32(t, 4);
    t[0] = t[1] = yz; t[2] = t[3] = wx;  out->m[2][1] = entry32(t, 4);
    return QO_OK;
}

/* (M^T M)_ij = sum_k m_ki m_kj in Q1.30, rounded once, not saturated. */
static int64_t gram(const qo_mat3_q30 *m, int i, int j)
{
    int64_t t[3];
    t[0] = P(m->m[0][i], m->m[0][j]);
    t[1] = P(m->m[1][i], m->m[1][j]);
    t[2] = P(m->m[2][i], m->m[2][j]);
    return qo_fx_sum_round_i64(t, 3, 30);
}

/* Shepperd: pivot on the largest of trace, m00, m11, m22, and use the quaternion scaled by
 * 4 * (pivot component), whose entries are plain sums of matrix entries (no square root, no
 * division); normalising afterwards removes the scale. Canonical sign. Returns 0 (and the
 * identity) when that vector is zero, which no rotation gives. */
static int shepperd(const qo_mat3_q30 *m, qo_quat_q30 *out)
{
    int64_t q[4], tr, best;
    int64_t a00, a11, a22;
    int i, pivot;
    uint64_t mx;
    qo_quat_q30 r;
    a00 = m->m[0][0]; a11 = m->m[1][1]; a22 = m->m[2][2];
    tr = a00 + a11 + a22;
    pivot = 0; best = tr;
    if (a00 > best) { pivot = 1; best = a00; }
    if (a11 > best) { pivot = 2; best = a11; }
    if (a22 > best) { pivot = 3; best = a22; }
    switch (pivot) {
    case 0:
        q[0] = QO_Q30_ONE + tr;
        q[1] = (int64_t)m->m[2][1] - m->m[1][2];
        q[2] = (int64_t)m->m[0][2] - m->m[2][0];
        q[3] = (int64_t)m->m[1][0] - m->m[0][1];
        break;
    case 1:
        q[0] = (int64_t)m->m[2][1] - m->m[1][2];
        q[1] = QO_Q30_ONE + a00 - a11 - a22;
        q[2] = (int64_t)m->m[0][1] + m->m[1][0];
        q[3] = (int64_t)m->m[0][2] + m->m[2][0];
        break;
    case 2:
        q[0] = (int64_t)m->m[0][2] - m->m[2][0];
        q[1] = (int64_t)m->m[0][1] + m->m[1][0];
        q[2] = QO_Q30_ONE - a00 + a11 - a22;
        q[3] = (int64_t)m->m[1][2] + m->m[2][1];
        break;
    default:
        q[0] = (int64_t)m->m[1][0] - m->m[0][1];
        q[1] = (int64_t)m->m[0][2] + m->m[2][0];
        q[2] = (int64_t)m->m[1][2] + m->m[2][1];
        q[3] = QO_Q30_ONE - a00 - a11 + a22;
        break;
    }
    /* For a rotation the pivot entry is in [1, 4] (2^30..2^32); any Q1.30 matrix keeps every
     * entry below 2^34: halve with rounding until all fit int32 (costs at most a few bits of
     * 2^32, far below an LSB of the normalised result). */
    for (;;) {
        mx = 0;
        for (i = 0; i < 4; i++) if (qo_fx_abs_u64(q[i]) > mx) mx = qo_fx_abs_u64(q[i]);
        if (mx < ((uint64_t)1 << 31)) break;
        for (i = 0; i < 4; i++) q[i] = (q[i] + 1) >> 1;
    }
    r.w = (qo_q30)q[0]; r.x = (qo_q30)q[1]; r.y = (qo_q30)q[2]; r.z = (qo_q30)q[3];
    if (qo_quat_normalize_q30(r, out) != QO_OK) {
        *out = qo_quat_identity_q30();
        return 0;
    }
    *out = qo_quat_canonical_q30(*out);
    return 1;
}

qo_status qo_mat3_to_quat_q30(const qo_mat3_q30 *m, qo_quat_q30 *out)
{
    int i, j;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_q30();
    if (m == NULL) return QO_E_NULL;
    for (i = 0; i < 3; i++) {
        for (j = i; j < 3; j++) {
            int64_t d = gram(m, i, j) - (i == j ? QO_Q30_ONE : 0);
            if (d > QO_MAT3_ROTATION_TOL_Q30 || d < -QO_MAT3_ROTATION_TOL_Q30) return QO_E_NOT_ROTATION;
        }
    }
    /* Orthonormal within the tolerance: det is +-1 +- 2e-4, so its sign is reliable. */
    if (qo_mat3_det_q30(m) < QO_Q30_ONE / 2) return QO_E_NOT_ROTATION;
    return shepperd(m, out) ? QO_OK : QO_E_NOT_ROTATION;
}

qo_vec3_q30 qo_mat3_mul_vec3_q30(const qo_mat3_q30 *m, qo_vec3_q30 v)
{
    qo_vec3_q30 r = { 0, 0, 0 };
    int64_t t[3];
    qo_q30 *o[3];
    int i;
    if (m == NULL) return r;
    o[0] = &r.x; o[1] = &r.y; o[2] = &r.z;
    for (i = 0; i < 3; i++) {
        t[0] = P(m->m[i][0], v.x);
        t[1] = P(m->m[i][1], v.y);
        t[2] = P(m->m[i][2], v.z);
        *o[i] = entry(t, 3);
    }
    return r;
}

/* ---- matrix helpers and the remaining twins of convert.h (issue 16) ---- */

qo_mat3_q30 qo_mat3_identity_q30(void)
{
    return mat3_identity();
}

qo_mat3_q30 qo_mat3_transpose_q30(const qo_mat3_q30 *m)
{
    qo_mat3_q30 r = { { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } } };
    int i, j;
    if (m == NULL) return r;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = m->m[j][i];
    return r;
}

qo_mat3_q30 qo_mat3_mul_q30(const qo_mat3_q30 *a, const qo_mat3_q30 *b)
{
    qo_mat3_q30 r = { { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } } };
    int64_t t[3];
    int i, j;
    if (a == NULL || b == NULL) return r;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            t[0] = P(a->m[i][0], b->m[0][j]);
            t[1] = P(a->m[i][1], b->m[1][j]);
            t[2] = P(a->m[i][2], b->m[2][j]);
            r.m[i][j] = entry(t, 3);
        }
    }
    return r;
}

/* Largest entry magnitude of m. */
static uint64_t mat3_max_abs(const qo_mat3_q30 *m)
{
    uint64_t mx = 0;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            if (qo_fx_abs_u64(m->m[i][j]) > mx) mx = qo_fx_abs_u64(m->m[i][j]);
    return mx;
}

/* Entries up to this (1 + 1/16, every rounded rotation and everything near one) keep the
 * first-row cofactors in Q1.30 (<= 2.26, int64) and each product with an entry below 2^62. */
#define DET_DIRECT_MAX (((uint64_t)1 << 30) + ((uint64_t)1 << 26))

qo_q30 qo_mat3_det_q30(const qo_mat3_q30 *m)
{
    const qo_q30 (*a)[3];
    int64_t c[3], t[3];
    unsigned sh;
    if (m == NULL) return 0;
    a = m->m;
    /* Larger entries (up to 2): cofactors (<= 8) in Q3.28 instead, so the products stay
     * below 2^62; the result is then rounded twice at Q3.28 (a few LSB of Q1.30). */
    sh = mat3_max_abs(m) <= DET_DIRECT_MAX ? 30u : 32u;
    t[0] = P(a[1][1], a[2][2]); t[1] = -P(a[1][2], a[2][1]);
    c[0] = qo_fx_sum_round_i64(t, 2, sh);
    t[0] = P(a[1][2], a[2][0]); t[1] = -P(a[1][0], a[2][2]);
    c[1] = qo_fx_sum_round_i64(t, 2, sh);
    t[0] = P(a[1][0], a[2][1]); t[1] = -P(a[1][1], a[2][0]);
    c[2] = qo_fx_sum_round_i64(t, 2, sh);
    t[0] = a[0][0] * c[0]; t[1] = a[0][1] * c[1]; t[2] = a[0][2] * c[2];
    return qo_fx_sat_i32(qo_fx_sum_round_i64(t, 3, 60u - sh));
}

qo_status qo_mat3_to_quat_trusted_q30(const qo_mat3_q30 *m, qo_quat_q30 *out)
{
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_q30();
    if (m == NULL) return QO_E_NULL;
    return shepperd(m, out) ? QO_OK : QO_E_NOT_ROTATION;
}

/* det(M / |M|_F) at or below this (Q1.30 raw 2^16 = 2^-14) is refused: singular, too close to
 * singular (smallest singular value of M/|M|_F below 2 * 2^-14 = 1.2e-4 at the worst) or a
 * reflection. Above it the iteration below reaches the polar factor in at most ~30 steps. */
#define ORTHO_DET_MIN ((qo_q30)1 << 16)
#define ORTHO_MAX_ITER 48
/* Stop when no entry moved by more than this (LSB): the iteration has reached its rounding. */
#define ORTHO_STEP_TOL 2

qo_status qo_mat3_orthonormalize_q30(const qo_mat3_q30 *m, qo_mat3_q30 *out)
{
    qo_mat3_q30 x, xn;
    int64_t x0[3][3], h[3][3], t[3];
    uint64_t mx, f2 = 0, f;
    int i, j, k, it, shl = 0, shr = 0;
    if (out == NULL) return QO_E_NULL;
    if (m == NULL) {
        *out = mat3_identity();
        return QO_E_NULL;
    }
    /* The polar factor does not change under uniform scaling. Bring the largest entry into
     * [2^28, 2^29) (exact for small entries; entries >= 2^29 lose at most 3 low bits), then
     * divide by the Frobenius norm: X = M / |M|_F has every singular value in (0, 1]. */
    mx = mat3_max_abs(m);
    if (mx == 0) {
        *out = mat3_identity();
        return QO_E_NOT_ROTATION;
    }
    while ((mx << shl) < ((uint64_t)1 << 28)) shl++;
    while ((mx >> shr) >= ((uint64_t)1 << 29)) shr++;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            int64_t v = (int64_t)m->m[i][j] * ((int64_t)1 << shl);
            x0[i][j] = shr ? qo_fx_rshift_round_up(v, (unsigned)shr) : v;
            f2 += (uint64_t)(x0[i][j] * x0[i][j]);
        }
    }
    *out = mat3_identity();   /* m may alias out: x0 holds the input from here on */
    f = qo_fx_sqrt_u64(f2);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            x.m[i][j] = (qo_q30)qo_fx_div_round_away(x0[i][j] * ((int64_t)1 << 30), f);
    if (qo_mat3_det_q30(&x) <= ORTHO_DET_MIN) return QO_E_NOT_ROTATION;
    /* Newton-Schulz (Bjorck) iteration X <- X (3I - X^T X) / 2: no inverse and no division,
     * every product of entries <= 1, so all of it is exact 64-bit sums rounded once per entry.
     * Each singular value s maps to s (3 - s^2) / 2: quadratic convergence to 1 near 1, growth
     * by 1.5x per step from below; the polar factor is the fixed point. (convert.c uses
     * Higham's scaled Newton iteration, which needs an inverse per step.) */
    for (it = 0; it < ORTHO_MAX_ITER; it++) {
        int64_t step = 0;
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++)   /* (3I - G) in Q1.30 read as (3I - G)/2 in Q1.31 */
                h[i][j] = (i == j ? 3 * (int64_t)QO_Q30_ONE : 0) - gram(&x, i, j);
        for (i = 0; i < 3; i++) {
            for (j = 0; j < 3; j++) {
                int64_t d;
                for (k = 0; k < 3; k++) t[k] = x.m[i][k] * h[k][j];
                xn.m[i][j] = qo_fx_sat_i32(qo_fx_sum_round_i64(t, 3, 31));
                d = (int64_t)xn.m[i][j] - x.m[i][j];
                if (d < 0) d = -d;
                if (d > step) step = d;
            }
        }
        x = xn;
        if (step <= ORTHO_STEP_TOL) break;
    }
    for (i = 0; i < 3; i++) {
        for (j = i; j < 3; j++) {
            int64_t d = gram(&x, i, j) - (i == j ? QO_Q30_ONE : 0);
            if (d > QO_MAT3_ROTATION_TOL_Q30 || d < -QO_MAT3_ROTATION_TOL_Q30) return QO_E_NOT_ROTATION;
        }
    }
    if (qo_mat3_det_q30(&x) < QO_Q30_ONE / 2) return QO_E_NOT_ROTATION;
    *out = x;
    return QO_OK;
}

qo_status qo_mat3_to_quat_ortho_q30(const qo_mat3_q30 *m, qo_quat_q30 *out)
{
    qo_mat3_q30 r;
    qo_status st = qo_mat3_orthonormalize_q30(m, &r);
    if (out == NULL) return QO_E_NULL;
    if (st == QO_OK) return qo_mat3_to_quat_q30(&r, out);
    *out = qo_quat_identity_q30();
    return st;
}
