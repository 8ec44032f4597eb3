/* float32 rotation conversions. See qorient/convert.h for the contract of each function. */
/* The header's inline functions are also compiled here as external definitions (ABI). */
#define QORIENT_CONVERT_EXTERN_DEFS
#include "qorient/convert.h"
#include "qorient/quat.h"

#include <float.h>
#include <math.h>

#include "qorient/fmath.h"
#include "fmath_internal.h"

/* Newton polar iteration: at most this many steps (scaled Newton needs < 10 for any matrix we
 * accept; the cap only stops a pathological input from looping). */
#define CONV_NEWTON_MAX_ITER 30
/* Stop when no entry moved more than this: the iteration is quadratic, so the remaining error
 * is ~ the square of it, far below float32 round-off. */
#define CONV_NEWTON_STEP_TOL 1e-6f
/* Below this step size Higham's scale factor no longer helps and only adds rounding. */
#define CONV_NEWTON_SCALE_UNTIL 1e-2f
/* Frobenius condition number |A|_F |A^-1|_F above which a matrix counts as rank-deficient.
 * Measured (random rotations U, V, M = U diag(1, s, s) V^T): the float32 iteration's error is
 * ~2e-8/s rad down to s = 1e-4, and at s = 7e-5 it can converge to a rotation pi away (the
 * float cofactors of a matrix that close to rank 1 have no correct digits). 3e3 rejects
 * s < ~5e-4: a factor of 7 of margin. */
#define CONV_COND_MAX 3e3f

/* On the rare paths of qo_mat3_to_quat_f32: kept out of line, so that the common case makes
 * no call and needs no stack frame (gcc and clang; elsewhere a plain static function). */
#if defined(__GNUC__)
#define CONV_COLD __attribute__((noinline, cold))
#else
#define CONV_COLD
#endif

static qo_vec3_f32 vec3(float x, float y, float z)
{
    qo_vec3_f32 v;
    v.x = x; v.y = y; v.z = z;
    return v;
}

static int vec3_is_finite(qo_vec3_f32 v)
{
    return isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
}

static int mat3_is_finite(const qo_mat3_f32 *m)
{
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            if (!isfinite(m->m[i][j])) return 0;
    return 1;
}

/* Overflow/underflow-safe length of a 3-vector (reuses the scaled quaternion norm). */
static float vec3_norm(qo_vec3_f32 v)
{
    qo_quat_f32 q;
    q.w = 0.0f; q.x = v.x; q.y = v.y; q.z = v.z;
    return qo_quat_norm_f32(q);
}

qo_mat3_f32 qo_mat3_identity_f32(void)
{
    qo_mat3_f32 r = { { { 1.0f, 0.0f, 0.0f }, { 0.0f, 1.0f, 0.0f }, { 0.0f, 0.0f, 1.0f } } };
    return r;
}

qo_vec3_f32 qo_mat3_mul_vec3_f32(const qo_mat3_f32 *m, qo_vec3_f32 v)
{
    return vec3(m->m[0][0] * v.x + m->m[0][1] * v.y + m->m[0][2] * v.z,
                m->m[1][0] * v.x + m->m[1][1] * v.y + m->m[1][2] * v.z,
                m->m[2][0] * v.x + m->m[2][1] * v.y + m->m[2][2] * v.z);
}

qo_mat3_f32 qo_mat3_mul_f32(const qo_mat3_f32 *a, const qo_mat3_f32 *b)
{
    qo_mat3_f32 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            r.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] + a->m[i][2] * b->m[2][j];
    return r;
}

qo_mat3_f32 qo_mat3_transpose_f32(const qo_mat3_f32 *m)
{
    qo_mat3_f32 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = m->m[j][i];
    return r;
}

/* Cofactor matrix: C[i][j] = (-1)^(i+j) minor(i, j). det M = row0 . C row0, and
 * M^-T = C / det M (which is exactly what the polar iteration needs, no transpose). */
static qo_mat3_f32 mat3_cofactor(const qo_mat3_f32 *m)
{
    const float (*a)[3] = m->m;
    qo_mat3_f32 c;
    c.m[0][0] = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    c.m[0][1] = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    c.m[0][2] = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    c.m[1][0] = a[0][2] * a[2][1] - a[0][1] * a[2][2];
    c.m[1][1] = a[0][0] * a[2][2] - a[0][2] * a[2][0];
    c.m[1][2] = a[0][1] * a[2][0] - a[0][0] * a[2][1];
    c.m[2][0] = a[0][1] * a[1][2] - a[0][2] * a[1][1];
    c.m[2][1] = a[0][2] * a[1][0] - a[0][0] * a[1][2];
    c.m[2][2] = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    return c;
}

float qo_mat3_det_f32(const qo_mat3_f32 *m)
{
    /* Expansion along the first row: only its three cofactors (as mat3_cofactor computes
     * them, so the same value), not all nine. */
    const float (*a)[3] = m->m;
    float c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    float c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    float c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    return a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
}

static float mat3_frobenius(const qo_mat3_f32 *m)
{
    float s = 0.0f;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) s += m->m[i][j] * m->m[i][j];
    return sqrtf(s);
}

/* Largest |(M^T M - I)_ij|; NaN/Inf (from overflowing entries) propagate as "not small". */
static float mat3_col_dot(const qo_mat3_f32 *m, int i, int j)
{
    return m->m[0][i] * m->m[0][j] + m->m[1][i] * m->m[1][j] + m->m[2][i] * m->m[2][j];
}

static float mat3_orthogonality_error(const qo_mat3_f32 *m)
{
    /* Written out (the generic i <= j loop was not unrolled at -O2 and cost 2.5x as much);
     * the same six dot products in the same order, so the same value. */
    float e[6];
    float worst;
    e[0] = fabsf(mat3_col_dot(m, 0, 0) - 1.0f);
    e[1] = fabsf(mat3_col_dot(m, 0, 1));
    e[2] = fabsf(mat3_col_dot(m, 0, 2));
    e[3] = fabsf(mat3_col_dot(m, 1, 1) - 1.0f);
    e[4] = fabsf(mat3_col_dot(m, 1, 2));
    e[5] = fabsf(mat3_col_dot(m, 2, 2) - 1.0f);
    /* The largest by plain comparisons (no loop, no libm call); NaN must win (the caller
     * relies on a NaN entry giving a NaN error): the sum is NaN exactly when one e is. */
    worst = e[0] > e[1] ? e[0] : e[1];
    if (e[2] > worst) worst = e[2];
    if (e[3] > worst) worst = e[3];
    if (e[4] > worst) worst = e[4];
    if (e[5] > worst) worst = e[5];
    if (isnan(e[0] + e[1] + e[2] + e[3] + e[4] + e[5])) return NAN;
    return worst;
}

qo_status qo_axis_angle_to_quat_f32(qo_vec3_f32 axis, float angle, qo_quat_f32 *out)
{
    qo_quat_f32 u;
    qo_status st;
    float s;
    qo_fm_sincos_f32_t sc;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    if (!vec3_is_finite(axis) || !isfinite(angle)) return QO_E_NONFINITE;
    /* Normalising (0, axis) as a quaternion reuses the overflow/underflow-safe scaling. */
    u.w = 0.0f; u.x = axis.x; u.y = axis.y; u.z = axis.z;
    st = qo_quat_normalize_f32(u, &u);
    if (st != QO_OK) {
        *out = qo_quat_identity_f32();
        return QO_E_DEGENERATE;
    }
    sc = qo_fm_sincos_f32(0.5f * angle);
    s = sc.s;
    out->w = sc.c;
    out->x = s * u.x; out->y = s * u.y; out->z = s * u.z;
    return QO_OK;
}

qo_status qo_axis_angle_from_quat_f32(qo_quat_f32 q, qo_vec3_f32 *axis, float *angle)
{
    qo_quat_f32 n, v;
    qo_status st;
    float vn;
    if (axis != NULL) *axis = vec3(1.0f, 0.0f, 0.0f);
    if (angle != NULL) *angle = 0.0f;
    if (axis == NULL || angle == NULL) return QO_E_NULL;
    st = qo_quat_normalize_f32(q, &n);
    if (st != QO_OK) return st;
    n = qo_quat_canonical_f32(n);
    v.w = 0.0f; v.x = n.x; v.y = n.y; v.z = n.z;
    vn = qo_quat_norm_f32(v);
    if (vn == 0.0f) return QO_OK; /* identity: documented axis x, angle 0 */
    /* Unit axis through the safe normaliser: v can be subnormal after normalising q. */
    if (qo_quat_normalize_f32(v, &v) != QO_OK) return QO_OK;
    *axis = vec3(v.x, v.y, v.z);
    *angle = 2.0f * qo_fm_atan2_f32(vn, n.w);
    return QO_OK;
}

qo_status qo_rotvec_to_quat_f32(qo_vec3_f32 rv, qo_quat_f32 *out)
{
    float theta, h, k;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    if (!vec3_is_finite(rv)) return QO_E_NONFINITE;
    theta = vec3_norm(rv);
    if (isinf(theta)) return QO_E_RANGE;
    h = 0.5f * theta;
    if (h < 1e-2f) {
        /* cos h and sin(h)/theta by Taylor: at h < 1e-2 the next terms are < 2e-15, and a
         * tiny rv gives w = 1, k = 1/2 exactly (qo_fm_sin_f32(h)/theta would lose the quotient). */
        float h2 = h * h;
        out->w = 1.0f - 0.5f * h2 * (1.0f - h2 * (1.0f / 12.0f));
        k = 0.5f * (1.0f - h2 * (1.0f / 6.0f) * (1.0f - h2 * (1.0f / 20.0f)));
    } else {
        qo_fm_sincos_f32_t sc = qo_fm_sincos_f32(h);
        out->w = sc.c;
        k = sc.s / theta;
    }
    out->x = k * rv.x; out->y = k * rv.y; out->z = k * rv.z;
    return QO_OK;
}

qo_status qo_rotvec_from_quat_f32(qo_quat_f32 q, qo_vec3_f32 *out)
{
    qo_quat_f32 n, v;
    qo_status st;
    float vn, k;
    if (out == NULL) return QO_E_NULL;
    *out = vec3(0.0f, 0.0f, 0.0f);
    st = qo_quat_normalize_f32(q, &n);
    if (st != QO_OK) return st;
    n = qo_quat_canonical_f32(n);
    v.w = 0.0f; v.x = n.x; v.y = n.y; v.z = n.z;
    vn = qo_quat_norm_f32(v);
    if (vn < 1e-3f) {
        /* 2 atan(t)/t * (1/w) with t = vn/w <= ~1e-3: series, so a subnormal vector part
         * keeps its full relative precision (atan2 would round in the subnormal range).
         * vn == 0 falls in here too and gives the zero vector. */
        float t2 = (vn / n.w) * (vn / n.w);
        k = (2.0f / n.w) * (1.0f - t2 * (1.0f / 3.0f));
    } else {
        k = 2.0f * qo_fm_atan2_f32(vn, n.w) / vn;
    }
    *out = vec3(k * n.x, k * n.y, k * n.z);
    return QO_OK;
}

qo_status qo_mat3_from_quat_full_f32(qo_quat_f32 q, qo_mat3_f32 *out)
{
    qo_quat_f32 n;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    *out = qo_mat3_identity_f32();
    st = qo_quat_normalize_f32(q, &n);
    if (st != QO_OK) return st;
    /* |n| is 1 to a few ulp: the inline path takes it */
    return qo_mat3_from_quat_f32(n, out);
}

/* fmaxf(v, FLT_MIN) without the libm call (NaN gives FLT_MIN as there). */
static float clamp_min(float v)
{
    return v > FLT_MIN ? v : FLT_MIN;
}

/* Shepperd's method with one square root and one divide. For a rotation, 4 w q = (4w^2,
 * m21 - m12, m02 - m20, m10 - m01) with 4w^2 = 1 + trace, and likewise 4 x q, 4 y q, 4 z q
 * from the other diagonal entries: so q is the normalised 4-vector of whichever of them has
 * the largest pivot 4c^2 = 1 + (t, 2 m00 - t, 2 m11 - t or 2 m22 - t), the largest of
 * t, m00, m11, m22 (the four pivots sum to 4, so it is >= 1 and the vector is never short).
 * Normalising that vector in one step replaces sqrt(pivot) and the divide by it of the
 * textbook form, and rounds less. The pivot is clamped at FLT_MIN, so a non-rotation cannot
 * give the zero vector (whose direction does not exist). */
static inline int mat3_pivot_vector(const qo_mat3_f32 *m, qo_quat_f32 *out)
{
    const float (*a)[3] = m->m;
    float t = a[0][0] + a[1][1] + a[2][2];
    qo_quat_f32 v;
    int p = 0;
    if (t >= a[0][0] && t >= a[1][1] && t >= a[2][2]) {
        v.w = clamp_min(1.0f + t);
        v.x = a[2][1] - a[1][2];
        v.y = a[0][2] - a[2][0];
        v.z = a[1][0] - a[0][1];
    } else if (a[0][0] >= a[1][1] && a[0][0] >= a[2][2]) {
        p = 1;
        v.w = a[2][1] - a[1][2];
        v.x = clamp_min(1.0f + a[0][0] - a[1][1] - a[2][2]);
        v.y = a[0][1] + a[1][0];
        v.z = a[0][2] + a[2][0];
    } else if (a[1][1] >= a[2][2]) {
        p = 2;
        v.w = a[0][2] - a[2][0];
        v.x = a[0][1] + a[1][0];
        v.y = clamp_min(1.0f - a[0][0] + a[1][1] - a[2][2]);
        v.z = a[1][2] + a[2][1];
    } else {
        p = 3;
        v.w = a[1][0] - a[0][1];
        v.x = a[0][2] + a[2][0];
        v.y = a[1][2] + a[2][1];
        v.z = clamp_min(1.0f - a[0][0] - a[1][1] + a[2][2]);
    }
    *out = v;
    return p;
}

/* The canonical unit quaternion of the pivot vector (a NaN/Inf vector, from entries so large
 * that the formula overflows, is reported by the normaliser). The pivot component p of a
 * rotation's result is positive (>= 1/2), so qo_quat_canonical_f32's choice of sign only
 * looks at the components before it: none for the trace pivot (w). */
static CONV_COLD qo_status quat_from_pivot(const qo_mat3_f32 *m, qo_quat_f32 *out)
{
    qo_quat_f32 v;
    int p, flip;
    qo_status st;
    p = mat3_pivot_vector(m, &v);
    st = qo_quat_normalize_f32(v, out);
    if (st != QO_OK) return st;
    v = *out;
    flip = p > 0 && (v.w < 0.0f || (v.w == 0.0f && p > 1 &&
                                    (v.x < 0.0f || (v.x == 0.0f && p > 2 && v.y < 0.0f))));
    if (flip) { v.w = -v.w; v.x = -v.x; v.y = -v.y; v.z = -v.z; }
    /* -0.0 -> +0.0 as qo_quat_canonical_f32 */
    out->w = v.w + 0.0f; out->x = v.x + 0.0f; out->y = v.y + 0.0f; out->z = v.z + 0.0f;
    return QO_OK;
}

/* The full check of qo_mat3_to_quat_f32, for the matrices qo_mat3_internal_is_rotation_f32 and
 * the direct formula do not answer. */
static CONV_COLD qo_status quat_from_mat3_checked(const qo_mat3_f32 *m, qo_quat_f32 *out)
{
    qo_mat3_f32 r;
    float orth;
    *out = qo_quat_identity_f32();
    /* Every entry enters a diagonal dot product squared, so a NaN or Inf entry makes orth NaN
     * or Inf: the finiteness pass is only needed to tell the two errors apart. */
    orth = mat3_orthogonality_error(m);
    if (!(orth <= QO_MAT3_ROTATION_TOL_F32))
        return mat3_is_finite(m) ? QO_E_NOT_ROTATION : QO_E_NONFINITE;
    /* Orthonormal within tolerance means det is +-1 +- 2e-4: the sign test is reliable. */
    if (!(qo_mat3_det_f32(m) > 0.0f)) return QO_E_NOT_ROTATION;
    /* Shepperd on a matrix off by e = max|M^T M - I| lands up to 2.16 e rad from the nearest
     * rotation (QO_MAT3_INTERNAL_DIRECT_TOL_F32). A float32-rounded rotation has e ~ 2e-7 and
     * goes straight through; anything further off (but accepted) is first projected onto the
     * nearest rotation, which takes one or two Newton steps at this distance. */
    if (orth > QO_MAT3_INTERNAL_DIRECT_TOL_F32) {
        if (qo_mat3_orthonormalize_f32(m, &r) != QO_OK) return QO_E_NOT_ROTATION;
        m = &r;
    }
    return quat_from_pivot(m, out) == QO_OK ? QO_OK : QO_E_NOT_ROTATION;
}

qo_status qo_mat3_to_quat_full_f32(const qo_mat3_f32 *m, qo_quat_f32 *out)
{
    if (out == NULL) return QO_E_NULL;
    if (m == NULL) {
        *out = qo_quat_identity_f32();
        return QO_E_NULL;
    }
    /* A float32-rounded rotation takes the trusted formula (as the inline function); the rest
     * (its half turns off the trace pivot, everything further off) the full check. */
    if (qo_mat3_internal_is_rotation_f32(m) && qo_mat3_internal_shepperd_f32(m, out, 1))
        return QO_OK;
    return quat_from_mat3_checked(m, out);
}

qo_status qo_mat3_to_quat_trusted_full_f32(const qo_mat3_f32 *m, qo_quat_f32 *out)
{
    if (out == NULL) return QO_E_NULL;
    if (m == NULL) {
        *out = qo_quat_identity_f32();
        return QO_E_NULL;
    }
    if (qo_mat3_internal_shepperd_f32(m, out, 0)) return QO_OK;
    /* Each pivot branch combines all six off-diagonal entries, so a NaN/Inf there reaches q
     * (and normalising reports it); the diagonal enters through the clamped pivot, which
     * would hide a NaN: the trace catches any non-finite diagonal entry. */
    if (!isfinite(m->m[0][0] + m->m[1][1] + m->m[2][2])) {
        *out = qo_quat_identity_f32();
        return QO_E_NONFINITE;
    }
    return quat_from_pivot(m, out);
}

qo_status qo_mat3_orthonormalize_f32(const qo_mat3_f32 *m, qo_mat3_f32 *out)
{
    qo_mat3_f32 x, c;
    float mx = 0.0f, d, gamma, step;
    int i, j, it, scaling = 1, converged = 0;
    if (out == NULL) return QO_E_NULL;
    if (m == NULL) {
        *out = qo_mat3_identity_f32();
        return QO_E_NULL;
    }
    if (!mat3_is_finite(m)) {
        *out = qo_mat3_identity_f32();
        return QO_E_NONFINITE;
    }
    /* The polar factor does not change under uniform scaling: bring the largest entry to 1 so
     * that cofactors (products of two entries) and the determinant cannot overflow or
     * underflow whatever the caller's magnitudes. */
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++)
            if (fabsf(m->m[i][j]) > mx) mx = fabsf(m->m[i][j]);
    if (mx == 0.0f) {
        *out = qo_mat3_identity_f32();
        return QO_E_NOT_ROTATION;
    }
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) x.m[i][j] = m->m[i][j] / mx;
    *out = qo_mat3_identity_f32(); /* m may alias out: x holds the input from here on */

    for (it = 0; it < CONV_NEWTON_MAX_ITER; it++) {
        c = mat3_cofactor(&x);
        d = x.m[0][0] * c.m[0][0] + x.m[0][1] * c.m[0][1] + x.m[0][2] * c.m[0][2];
        if (!(fabsf(d) > 0.0f)) return QO_E_NOT_ROTATION;
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) c.m[i][j] /= d; /* c = X^-T */
        if (it == 0) {
            /* Rank test on the input: a float32 inverse of a matrix this ill-conditioned has
             * no correct digits, and its nearest rotation is not well determined. */
            float cond = mat3_frobenius(&x) * mat3_frobenius(&c);
            if (!(cond <= CONV_COND_MAX)) return QO_E_NOT_ROTATION;
        }
        /* Higham's scaling gamma = sqrt(|X^-1|_F / |X|_F) makes the first steps converge fast
         * for scaled or stretched inputs; near convergence it is ~1 and only adds rounding. */
        gamma = scaling ? sqrtf(mat3_frobenius(&c) / mat3_frobenius(&x)) : 1.0f;
        step = 0.0f;
        for (i = 0; i < 3; i++) {
            for (j = 0; j < 3; j++) {
                float nx = 0.5f * (gamma * x.m[i][j] + c.m[i][j] / gamma);
                float dlt = fabsf(nx - x.m[i][j]);
                if (!(dlt <= step)) step = dlt;
                x.m[i][j] = nx;
            }
        }
        if (!(step < CONV_NEWTON_SCALE_UNTIL)) continue;
        scaling = 0;
        if (step <= CONV_NEWTON_STEP_TOL) {
            converged = 1;
            break;
        }
    }
    /* The iteration converges to the orthogonal polar factor, whose determinant has the sign
     * of det M: -1 means the input was a reflection (its nearest orthogonal matrix is no
     * rotation). The determinant of the result is +-1 to round-off, so the test is reliable
     * even where det M itself was too small to trust its sign. */
    if (!converged || !(qo_mat3_det_f32(&x) > 0.5f) ||
        !(mat3_orthogonality_error(&x) <= QO_MAT3_ROTATION_TOL_F32))
        return QO_E_NOT_ROTATION;
    *out = x;
    return QO_OK;
}

qo_status qo_mat3_to_quat_ortho_f32(const qo_mat3_f32 *m, qo_quat_f32 *out)
{
    qo_mat3_f32 r;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    st = qo_mat3_orthonormalize_f32(m, &r);
    if (st != QO_OK) return st;
    return qo_mat3_to_quat_f32(&r, out);
}
