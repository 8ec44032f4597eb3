/* Interpolation on the unit-quaternion sphere, float32. See qorient/interp.h for the contract
 * of each function. */
#include "qorient/interp.h"

#include <math.h>
#include <stdint.h>

#include "qorient/fmath.h"

#include "qorient/quat.h"
#include "fmath_internal.h"

#define QO_PI_F 3.14159265358979f

static qo_quat_f32 neg_q(qo_quat_f32 q)
{
    qo_quat_f32 r = { -q.w, -q.x, -q.y, -q.z };
    return r;
}

/* wa*a + wb*b */
static qo_quat_f32 comb_q(float wa, qo_quat_f32 a, float wb, qo_quat_f32 b)
{
    qo_quat_f32 r;
    r.w = wa * a.w + wb * b.w;
    r.x = wa * a.x + wb * b.x;
    r.y = wa * a.y + wb * b.y;
    r.z = wa * a.z + wb * b.z;
    return r;
}

/* b, negated when it lies in the other hemisphere than ref. dot == 0 keeps b. */
static qo_quat_f32 align_to(qo_quat_f32 b, qo_quat_f32 ref)
{
    return (qo_quat_dot_f32(ref, b) < 0.0f) ? neg_q(b) : b;
}

/* 4-D angle between unit a and unit b in [0, pi]: 2*atan2(|a-b|, |a+b|). Unlike acos(dot) it
 * keeps full relative precision of the small differences near 0 and near pi. */
/* *sin_th = sin(th) from the same two lengths: th = 2 phi with tan(phi) = d/s, so
 * sin(th) = 2 d s / (d^2 + s^2) - all terms positive, a few ulp, and no sin call. */
static float angle4(qo_quat_f32 a, qo_quat_f32 b, float *sin_th)
{
    float dw = a.w - b.w, dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
    float sw = a.w + b.w, sx = a.x + b.x, sy = a.y + b.y, sz = a.z + b.z;
    float d2 = dw * dw + dx * dx + dy * dy + dz * dz;
    float s2 = sw * sw + sx * sx + sy * sy + sz * sz;
    float d = sqrtf(d2), s = sqrtf(s2);
    *sin_th = (d2 + s2 > 0.0f) ? 2.0f * d * s / (d2 + s2) : 0.0f;
    return 2.0f * qo_fm_atan2_f32(d, s);
}

/* sin(u th)/sin(th) for th < QO_INTERP_SLERP_SERIES_ANGLE: u (1 + (1 - u^2) th^2/6) + O(th^4). */
static float series_weight(float u, float th2)
{
    return u * (1.0f + (1.0f - u * u) * th2 * (1.0f / 6.0f));
}

/* Great-circle interpolation of unit a and b with angle th = angle4(a, b), any real u
 * (extrapolation allowed), no sign flip, result normalised. th must be < pi - series angle. */
static qo_quat_f32 slerp_weights(qo_quat_f32 a, qo_quat_f32 b, float th, float sin_th, float u)
{
    float wa, wb;
    qo_quat_f32 r, n;
    if (th < QO_INTERP_SLERP_SERIES_ANGLE) {
        float th2 = th * th;
        wa = series_weight(1.0f - u, th2);
        wb = series_weight(u, th2);
    } else if (th <= 0.5f * QO_PI_F) {
        float inv = 1.0f / sin_th;
        wa = qo_fm_sin_f32((1.0f - u) * th) * inv;
        wb = qo_fm_sin_f32(u * th) * inv;
    } else {
        /* Beyond 90 deg (long way, extrapolated control points) the weights grow like
         * 1/sin(th) and their difference amplifies the error of th by 1/sin^2(th). Instead
         * rotate a towards the unit direction e of the a-b plane orthogonal to a:
         * out = cos(u th) a + sin(u th) e. e is built from s = a + b, which is small near
         * th = pi but computed with small RELATIVE error (b ~ -a: the sums are exact), as
         * s - (s.a) a; the textbook b - (a.b) a would cancel two O(1) terms. |s| >= 2 sin of
         * half the series angle, so e is defined. */
        qo_quat_f32 e, sum = comb_q(1.0f, a, 1.0f, b);
        (void)qo_quat_normalize_f32(comb_q(1.0f, sum, -qo_quat_dot_f32(sum, a), a), &e);
        qo_fm_sincos_f32_t sc = qo_fm_sincos_f32(u * th);
        r = comb_q(sc.c, a, sc.s, e);
        (void)qo_quat_normalize_f32(r, &n);
        return n;
    }
    r = comb_q(wa, a, wb, b);
    /* |r| is 1 up to rounding (never near 0 in the allowed range of th), so this cannot fail;
     * it removes the few-ulp norm drift of the weighted sum. */
    (void)qo_quat_normalize_f32(r, &n);
    return n;
}

/* Unchecked great-circle slerp for internal use (control points need u = 2, 1/2, +-1/3).
 * Returns 0 and *out = a when a and b are (nearly) antipodal, where the circle is undefined. */
static int slerp_raw(qo_quat_f32 a, qo_quat_f32 b, float u, qo_quat_f32 *out)
{
    float sin_th;
    float th = angle4(a, b, &sin_th);
    if (QO_PI_F - th < QO_INTERP_SLERP_SERIES_ANGLE) {
        *out = a;
        return 0;
    }
    *out = slerp_weights(a, b, th, sin_th, u);
    return 1;
}

/* Checks and normalises one orientation input. */
static qo_status unit_in(qo_quat_f32 q, qo_quat_f32 *u)
{
    if (!qo_quat_is_finite_f32(q)) {
        *u = qo_quat_identity_f32();
        return QO_E_NONFINITE;
    }
    return qo_quat_normalize_f32(q, u);
}

/* Checks two orientation inputs: NaN/Inf in either wins over zero in either. */
static qo_status unit_in2(qo_quat_f32 a, qo_quat_f32 b, qo_quat_f32 *ua, qo_quat_f32 *ub)
{
    qo_status sa, sb;
    /* Normalising succeeds only for finite non-zero inputs, so the finiteness pass is only
     * needed to rank the errors (NaN/Inf in either input is reported before a zero one). */
    sa = qo_quat_normalize_f32(a, ua);
    sb = qo_quat_normalize_f32(b, ub);
    if (sa == QO_OK && sb == QO_OK) return QO_OK;
    if (!qo_quat_is_finite_f32(a) || !qo_quat_is_finite_f32(b)) return QO_E_NONFINITE;
    return (sa != QO_OK) ? sa : sb;
}

/* Common checks of t: out already holds the value to return on error. */
static qo_status check_t(float t)
{
    if (!isfinite(t)) return QO_E_NONFINITE;
    if (t < 0.0f || t > 1.0f) return QO_E_RANGE;
    return QO_OK;
}

qo_status qo_interp_lerp_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out)
{
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    if (!qo_quat_is_finite_f32(a) || !qo_quat_is_finite_f32(b)) return QO_E_NONFINITE;
    *out = a;
    st = check_t(t);
    if (st != QO_OK || t == 0.0f) return st;
    if (t == 1.0f) {
        *out = b;
        return QO_OK;
    }
    *out = comb_q(1.0f - t, a, t, b);
    return QO_OK;
}

qo_status qo_interp_nlerp_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out)
{
    qo_quat_f32 ua, ub;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    st = unit_in2(a, b, &ua, &ub);
    if (st != QO_OK) return st;
    *out = ua;
    st = check_t(t);
    if (st != QO_OK || t == 0.0f) return st;
    ub = align_to(ub, ua);
    if (t == 1.0f) {
        *out = ub;
        return QO_OK;
    }
    /* After the flip dot >= 0, so |(1-t)a + tb| >= 1/sqrt(2): normalising cannot fail. */
    (void)qo_quat_normalize_f32(comb_q(1.0f - t, ua, t, ub), out);
    return QO_OK;
}

/* sin(u th)/sin(th) for u in [0, 1] and th in [0, pi/4], from y = cos(th) - 1 alone (no
 * angle, no sine): the series sum_i b_i(u) y^i, b_0 = u, b_i = b_(i-1) (u^2/(i(2i+1)) -
 * i/(2i+1)) (Eberly 2011, "A fast and accurate algorithm for computing SLERP"), nested and
 * cut after i = 7: on |y| <= 1 - cos(pi/4) the truncation is < 2.5e-8 (term ratio < 0.15;
 * a double sweep of u and th: 2.4e-8 at 7 terms, 3.3e-9 at 8, which measured no better in
 * bench/accuracy_interp). Its derivative in y is below 0.13, so the rounding of y (near
 * th = 0, where y cancels) costs < 1e-8. Two weights at once: shared y terms. */
#define QO_SER_K1(i) ((float)(i) / (float)(2 * (i) + 1))
#define QO_SER_K2(i) (1.0f / (float)((i) * (2 * (i) + 1)))
#define QO_SER_STEP(i) \
    vy = y * QO_SER_K1(i); \
    ra = 1.0f + (ua * QO_SER_K2(i) - vy) * ra; \
    rb = 1.0f + (ub * QO_SER_K2(i) - vy) * rb
#if !QO_QUAT_SIMD_SSE2
static void sin_ratios(float u, float y, float *wa, float *wb)
{
    float va = 1.0f - u, vb = u;
    float ua = va * va * y, ub = vb * vb * y, vy, ra = 1.0f, rb = 1.0f;
    QO_SER_STEP(7); QO_SER_STEP(6); QO_SER_STEP(5);
    QO_SER_STEP(4); QO_SER_STEP(3); QO_SER_STEP(2); QO_SER_STEP(1);
    *wa = va * ra;
    *wb = vb * rb;
}
#undef QO_SER_STEP
#endif

#if QO_QUAT_SIMD_SSE2
/* sin_ratios with the two weights in lanes 0 and 1, lane for lane the same operations (so the
 * same bits). The step coefficients uu K2(i) - y K1(i) do not depend on the running sums, so
 * two steps' pairs are made in one 4-wide operation (lanes 2, 3 hold step i - 1); only the
 * nested 1 + c r is sequential. */
#define QO_SER_C(k2, k1, i) \
    _mm_sub_ps(_mm_mul_ps(uu, _mm_set_ps(k2, k2, QO_SER_K2(i), QO_SER_K2(i))), \
               _mm_mul_ps(y4, _mm_set_ps(k1, k1, QO_SER_K1(i), QO_SER_K1(i))))
#define QO_SER_PAIR(v, i) QO_SER_C(QO_SER_K2(v), QO_SER_K1(v), i)
static __m128 sin_ratios_ps(float u, float y)
{
    /* (va, vb, 0, 0) = (1 - u, u, 0, 0) as 1 + (-1) u: the same rounding as 1 - u */
    const __m128 v = _mm_add_ps(_mm_mul_ps(_mm_set1_ps(u), _mm_set_ps(0.0f, 0.0f, 1.0f, -1.0f)),
                                _mm_set_ps(0.0f, 0.0f, 0.0f, 1.0f));
    const __m128 y4 = _mm_set1_ps(y), one = _mm_set1_ps(1.0f);
    const __m128 uv = _mm_mul_ps(_mm_mul_ps(v, v), y4), uu = _mm_movelh_ps(uv, uv);
    const __m128 c76 = QO_SER_PAIR(6, 7), c54 = QO_SER_PAIR(4, 5), c32 = QO_SER_PAIR(2, 3);
    const __m128 c1 = QO_SER_C(0.0f, 0.0f, 1);        /* lanes 2, 3 unused */
    __m128 r = _mm_add_ps(one, c76);                  /* 1 + c7 * 1: the product is exact */
    r = _mm_add_ps(one, _mm_mul_ps(_mm_movehl_ps(r, c76), r));
    r = _mm_add_ps(one, _mm_mul_ps(c54, r));
    r = _mm_add_ps(one, _mm_mul_ps(_mm_movehl_ps(r, c54), r));
    r = _mm_add_ps(one, _mm_mul_ps(c32, r));
    r = _mm_add_ps(one, _mm_mul_ps(_mm_movehl_ps(r, c32), r));
    r = _mm_add_ps(one, _mm_mul_ps(c1, r));
    return _mm_mul_ps(v, r);
}
#undef QO_SER_PAIR
#undef QO_SER_C
#endif
#undef QO_SER_K1
#undef QO_SER_K2

/* Short (longway == 0) or long (longway != 0) slerp. */
static qo_status slerp_common(qo_quat_f32 a, qo_quat_f32 b, float t, int longway,
                              qo_quat_f32 *out)
{
    qo_quat_f32 ua, ub;
    qo_status st;
    float d, th, sin_th;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    st = unit_in2(a, b, &ua, &ub);
    if (st != QO_OK) return st;
    *out = ua;
    st = check_t(t);
    if (st != QO_OK) return st;
    d = qo_quat_dot_f32(ua, ub);
    /* The flipped copy is what every branch below uses (including the series branch), so a
     * and -a interpolate to a unit quaternion, never through the origin. */
    if (longway ? (d > 0.0f) : (d < 0.0f)) ub = neg_q(ub);
    /* the short way once the inputs are unit (qo_interp_slerp_f32's one-pass case); its
     * endpoints are the unit inputs as normalised here (normalising twice can move the last
     * bit) */
    if (!longway) {
        if (t == 0.0f) return QO_OK;          /* *out is ua */
        if (t == 1.0f) {
            *out = ub;
            return QO_OK;
        }
        return qo_interp_slerp_f32(ua, ub, t, out);
    }
    th = angle4(ua, ub, &sin_th);
    if (QO_PI_F - th < QO_INTERP_SLERP_SERIES_ANGLE) return QO_E_DEGENERATE;
    *out = slerp_weights(ua, ub, th, sin_th, t);
    return QO_OK;
}

#if QO_QUAT_SIMD_SSE2
static uint32_t bits_of(float f)
{
    union { float f; uint32_t u; } b;
    b.f = f;
    return b.u;
}
#endif

/* The weights of a' and b' (wa a' + wb b', not yet normalised) for t in (0, 1) and
 * x = cos th >= 0 of the unit inputs after the short-way flip.
 * The unit midpoint m = (a' + b') / (2 c), c = cos(th/2) = sqrt((1 + x)/2) >= 0.707, splits
 * the arc into two halves of th/2 <= pi/4; the weights of the half that holds t come from
 * sin_ratios (no angle, no sine), and m's weight is folded into those of a' and b'
 * (r = alpha a' + beta b'), so m is never formed. */
static void slerp_half_weights(float t, float x, float *wa, float *wb)
{
    float c = qo_fm_sqrt_nonneg(0.5f + 0.5f * x), h = 0.5f / c;
    /* 2t and 2t - 1 are exact (the latter by Sterbenz) */
    float u = t <= 0.5f ? 2.0f * t : 2.0f * t - 1.0f;
#if QO_QUAT_SIMD_SSE2
    __m128 w = sin_ratios_ps(u, c - 1.0f);
    *wa = _mm_cvtss_f32(w);
    *wb = _mm_cvtss_f32(QO_QUAT_SIMD_SHUFFLE_PS(w, 0x55));
#else
    sin_ratios(u, c - 1.0f, wa, wb);
#endif
    if (t <= 0.5f) {                                 /* r = wa a' + wb m */
        *wb *= h;
        *wa += *wb;
    } else {                                         /* r = wa m + wb b' */
        *wa *= h;
        *wb += *wa;
    }
}

/* t == 0 or t == 1 in the one-pass case: the endpoints are qo_quat_normalize_f32's own result
 * (the squared norms are in [1e-30, 1e30], finite and non-zero, so it cannot fail), b' = -b
 * negated after it (negation is exact). */
static qo_status slerp_end(qo_quat_f32 a, qo_quat_f32 b, float t, int flip, qo_quat_f32 *out)
{
    (void)qo_quat_normalize_f32(t == 0.0f ? a : b, out);
    if (t == 1.0f && flip) *out = neg_q(*out);
    return QO_OK;
}

qo_status qo_interp_slerp_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out)
{
    /* The common case in one pass: both squared norms in [1e-30, 1e30] (so finite, non-zero
     * and needing no scaling) and t in [0, 1]. Everything else - every error, NaN t, inputs
     * that need scaling - takes slerp_common (same contract; its endpoints are these bits).
     * a * ia is unit a (ia = 1/sqrt(a.a), the dot product summed left to right, as the SSE2
     * body's columns); x = cos th; b' = -b (ib < 0) for the short way. The output goes
     * through qo_quat_normalize_f32 (its norm is 1 to a few ulp before). */
    float ia, ib, x, wa, wb;
#if QO_QUAT_SIMD_SSE2
    /* The three dot products a.a, b.b, a.b at once: the products transposed to columns and
     * summed ((p0 + p1) + p2) + p3 per lane, the scalar order; the range test is one compare
     * pair on both norms plus t's bits (t in [+0, 1] <=> bits <= those of 1). Every lane
     * operation is the scalar code's, so the bits are the same on every target. */
    const __m128 a4 = _mm_set_ps(a.z, a.y, a.x, a.w), b4 = _mm_set_ps(b.z, b.y, b.x, b.w);
    const __m128 pa = _mm_mul_ps(a4, a4), pb = _mm_mul_ps(b4, b4), pab = _mm_mul_ps(a4, b4);
    const __m128 lo = _mm_unpacklo_ps(pa, pb), hi = _mm_unpackhi_ps(pa, pb);
    const __m128 plo = _mm_unpacklo_ps(pab, pab), phi = _mm_unpackhi_ps(pab, pab);
    const uint32_t tb = bits_of(t);
    __m128 s, inv, r4;
    s = _mm_add_ps(_mm_movelh_ps(lo, plo), _mm_movehl_ps(plo, lo));
    s = _mm_add_ps(s, _mm_movelh_ps(hi, phi));
    s = _mm_add_ps(s, _mm_movehl_ps(phi, hi));        /* (a.a, b.b, a.b, a.b) */
    if (out == NULL || tb > 0x3f800000u ||
        (_mm_movemask_ps(_mm_and_ps(_mm_cmpge_ps(s, _mm_set_ps(0.0f, 0.0f, 1e-30f, 1e-30f)),
                                    _mm_cmple_ps(s, _mm_set_ps(0.0f, 0.0f, 1e30f, 1e30f)))) & 3) != 3)
        return slerp_common(a, b, t, 0, out);
    inv = _mm_div_ps(_mm_set1_ps(1.0f), _mm_sqrt_ps(s));
    ia = _mm_cvtss_f32(inv);
    ib = _mm_cvtss_f32(QO_QUAT_SIMD_SHUFFLE_PS(inv, 0x55));
    x = _mm_cvtss_f32(_mm_movehl_ps(s, s)) * (ia * ib);
    if (x < 0.0f) { ib = -ib; x = -x; }
    if (tb - 1u >= 0x3f7fffffu) return slerp_end(a, b, t, ib < 0.0f, out);  /* t 0 or 1 */
    slerp_half_weights(t, x, &wa, &wb);
    /* comb_q and qo_quat_normalize_f32's SSE2 body (|r| ~ 1 is in its fast range) */
    r4 = _mm_add_ps(_mm_mul_ps(_mm_set1_ps(wa * ia), a4), _mm_mul_ps(_mm_set1_ps(wb * ib), b4));
    (void)qo_quat_internal_normalize_ps(r4, &r4);
    _mm_storeu_ps(&out->w, r4);
#else
    float na = qo_quat_dot_f32(a, a), nb = qo_quat_dot_f32(b, b);
    if (out == NULL || !(na >= 1e-30f && na <= 1e30f && nb >= 1e-30f && nb <= 1e30f &&
                         t >= 0.0f && t <= 1.0f))
        return slerp_common(a, b, t, 0, out);
    ia = 1.0f / sqrtf(na);
    ib = 1.0f / sqrtf(nb);
    x = qo_quat_dot_f32(a, b) * (ia * ib);
    if (x < 0.0f) { ib = -ib; x = -x; }
    if (t == 0.0f || t == 1.0f) return slerp_end(a, b, t, ib < 0.0f, out);
    slerp_half_weights(t, x, &wa, &wb);
    (void)qo_quat_normalize_f32(comb_q(wa * ia, a, wb * ib, b), out);   /* cannot fail */
#endif
    return QO_OK;
}

qo_status qo_interp_slerp_long_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out)
{
    return slerp_common(a, b, t, 1, out);
}

qo_status qo_interp_slerp_rate_f32(qo_quat_f32 a, qo_quat_f32 b, float duration,
                                 qo_vec3_f32 *omega)
{
    qo_quat_f32 ua, ub;
    qo_vec3_f32 lg;
    qo_status st;
    float k;
    if (omega == NULL) return QO_E_NULL;
    omega->x = omega->y = omega->z = 0.0f;
    st = unit_in2(a, b, &ua, &ub);
    if (st != QO_OK) return st;
    if (!isfinite(duration)) return QO_E_NONFINITE;
    if (!(duration > 0.0f)) return QO_E_RANGE;
    ub = align_to(ub, ua);
    /* conj(a)*b' has w = dot >= 0, so its log is the short rotation's (0, phi/2 * axis). */
    st = qo_quat_log_f32(qo_quat_mul_f32(qo_quat_conj_f32(ua), ub), &lg);
    if (st != QO_OK) return st;
    k = 2.0f / duration;
    omega->x = k * lg.x;
    omega->y = k * lg.y;
    omega->z = k * lg.z;
    if (!isfinite(omega->x) || !isfinite(omega->y) || !isfinite(omega->z)) {
        /* a tiny duration can overflow the rate */
        omega->x = omega->y = omega->z = 0.0f;
        return QO_E_RANGE;
    }
    return QO_OK;
}

/* Checks that every key is finite and non-zero (NaN/Inf anywhere wins over zero). */
static qo_status check_keys(const qo_quat_f32 *keys, size_t n)
{
    size_t i;
    qo_status st = QO_OK;
    qo_quat_f32 u;
    for (i = 0; i < n; i++) {
        if (!qo_quat_is_finite_f32(keys[i])) return QO_E_NONFINITE;
        if (st == QO_OK && qo_quat_normalize_f32(keys[i], &u) != QO_OK) st = QO_E_DEGENERATE;
    }
    return st;
}

static void fill_identity(qo_quat_f32 *q, size_t n)
{
    size_t i;
    if (q == NULL) return;
    for (i = 0; i < n; i++) q[i] = qo_quat_identity_f32();
}

/* Unit key (validated beforehand) aligned to prev. */
static qo_quat_f32 next_key(qo_quat_f32 k, qo_quat_f32 prev)
{
    qo_quat_f32 u;
    (void)qo_quat_normalize_f32(k, &u);
    return align_to(u, prev);
}

qo_status qo_interp_align_keys_f32(const qo_quat_f32 *keys, size_t n, qo_quat_f32 *out)
{
    size_t i;
    qo_status st;
    qo_quat_f32 prev;
    if (keys == NULL || out == NULL) {
        fill_identity(out, n);
        return QO_E_NULL;
    }
    if (n == 0) return QO_E_TOO_FEW;
    st = check_keys(keys, n);
    if (st != QO_OK) {
        fill_identity(out, n);
        return st;
    }
    (void)qo_quat_normalize_f32(keys[0], &prev);
    out[0] = prev;
    for (i = 1; i < n; i++) {
        prev = next_key(keys[i], prev);
        out[i] = prev;
    }
    return QO_OK;
}

/* de Casteljau on p[0..n-1] (unit, sign-aligned), in place. Exact endpoints. */
static qo_quat_f32 casteljau(qo_quat_f32 *p, size_t n, float t)
{
    size_t lev, i;
    if (t == 0.0f) return p[0];
    if (t == 1.0f) return p[n - 1];
    for (lev = n - 1; lev > 0; lev--) {
        for (i = 0; i < lev; i++) {
            qo_quat_f32 r;
            /* An antipodal pair inside the pyramid has no circle: keep its first point. */
            (void)slerp_raw(p[i], p[i + 1], t, &r);
            p[i] = r;
        }
    }
    return p[0];
}

qo_status qo_interp_bezier_f32(const qo_quat_f32 *ctrl, size_t n, float t, qo_quat_f32 *out)
{
    qo_quat_f32 p[QO_INTERP_BEZIER_MAX_POINTS];
    size_t i;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    if (ctrl == NULL) return QO_E_NULL;
    if (n < 2) return QO_E_TOO_FEW;
    if (n > QO_INTERP_BEZIER_MAX_POINTS) return QO_E_CAPACITY;
    st = check_keys(ctrl, n);
    if (st != QO_OK) return st;
    (void)qo_quat_normalize_f32(ctrl[0], &p[0]);
    *out = p[0];
    st = check_t(t);
    if (st != QO_OK) return st;
    for (i = 1; i < n; i++) p[i] = next_key(ctrl[i], p[i - 1]);
    *out = casteljau(p, n, t);
    return QO_OK;
}

qo_status qo_interp_bezier3_f32(qo_quat_f32 q0, qo_quat_f32 q1, qo_quat_f32 q2, qo_quat_f32 q3,
                              float t, qo_quat_f32 *out)
{
    qo_quat_f32 c[4];
    c[0] = q0; c[1] = q1; c[2] = q2; c[3] = q3;
    return qo_interp_bezier_f32(c, 4, t, out);
}

/* Slerp(q_i, Bisect(Double(q_{i-1}, q_i), q_{i+1}), u) for u = +-1/3: returns a_i and b_i. */
static void inner_controls(qo_quat_f32 qm, qo_quat_f32 qc, qo_quat_f32 qn,
                           qo_quat_f32 *ai, qo_quat_f32 *bi)
{
    qo_quat_f32 dbl, abar;
    (void)slerp_raw(qm, qc, 2.0f, &dbl);
    if (!slerp_raw(dbl, qn, 0.5f, &abar)) {
        /* Double(q_{i-1}, q_i) antipodal to q_{i+1}: no bisector. The Euclidean formula's
         * limit (q_{i+1} == q_{i-1}) is a zero tangent, so abar = q_i (documented). */
        abar = qc;
    }
    (void)slerp_raw(qc, abar, 1.0f / 3.0f, ai);
    (void)slerp_raw(qc, abar, -1.0f / 3.0f, bi);
}

/* End control point Slerp(q_end, Slerp(q_far, q_near, 2), 1/3) of the notes. */
static qo_quat_f32 end_control(qo_quat_f32 q_end, qo_quat_f32 q_near, qo_quat_f32 q_far)
{
    qo_quat_f32 dbl, r;
    (void)slerp_raw(q_far, q_near, 2.0f, &dbl);
    if (!slerp_raw(q_end, dbl, 1.0f / 3.0f, &r)) r = q_end;
    return r;
}

qo_status qo_interp_spline_controls_f32(const qo_quat_f32 *keys, size_t n,
                                      qo_quat_f32 *a, qo_quat_f32 *b)
{
    qo_quat_f32 qm, qc, qn;
    qo_status st;
    size_t i;
    if (keys == NULL || a == NULL || b == NULL) {
        fill_identity(a, n);
        fill_identity(b, n);
        return QO_E_NULL;
    }
    fill_identity(a, n);
    fill_identity(b, n);
    if (n < 2) return QO_E_TOO_FEW;
    st = check_keys(keys, n);
    if (st != QO_OK) return st;
    (void)qo_quat_normalize_f32(keys[0], &qm);
    qc = next_key(keys[1], qm);
    if (n == 2) {
        /* Evenly spaced on the arc: the cubic Bezier is then the constant-rate slerp. */
        (void)slerp_raw(qm, qc, 1.0f / 3.0f, &a[0]);
        (void)slerp_raw(qm, qc, 2.0f / 3.0f, &b[1]);
        b[0] = qm;
        a[1] = qc;
        return QO_OK;
    }
    qn = next_key(keys[2], qc);
    a[0] = end_control(qm, qc, qn);
    b[0] = qm;
    /* Rolling window (q_{i-1}, q_i, q_{i+1}) over the aligned keys: no scratch array. */
    for (i = 1; i + 1 < n; i++) {
        if (i > 1) {
            qm = qc;
            qc = qn;
            qn = next_key(keys[i + 1], qc);
        }
        inner_controls(qm, qc, qn, &a[i], &b[i]);
    }
    /* Window is now (q_{n-3}, q_{n-2}, q_{n-1}). */
    b[n - 1] = end_control(qn, qc, qm);
    a[n - 1] = qn;
    return QO_OK;
}

qo_status qo_interp_spline_eval_f32(const qo_quat_f32 *keys, const qo_quat_f32 *a,
                                  const qo_quat_f32 *b, size_t n, float s, qo_quat_f32 *out)
{
    qo_quat_f32 p[4];
    qo_status st;
    size_t i, k;
    float t;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    if (keys == NULL || a == NULL || b == NULL) return QO_E_NULL;
    if (n < 2) return QO_E_TOO_FEW;
    if (!(s >= 0.0f) || !isfinite(s) || s > (float)(n - 1)) {
        /* NaN and below 0 -> first key, above n-1 -> last key. */
        const qo_quat_f32 *end = (s > 0.0f) ? &keys[n - 1] : &keys[0];
        (void)unit_in(*end, out);
        return isfinite(s) ? QO_E_RANGE : QO_E_NONFINITE;
    }
    i = (size_t)s;
    if (i > n - 2) i = n - 2;
    t = s - (float)i;
    p[0] = keys[i];
    p[1] = a[i];
    p[2] = b[i + 1];
    p[3] = keys[i + 1];
    st = check_keys(p, 4);
    if (st != QO_OK) return st;
    for (k = 0; k < 4; k++) (void)qo_quat_normalize_f32(p[k], &p[k]);
    /* a_i and b_{i+1} carry the aligned signs and lie within 60 deg (4-D) of their keys, so
     * aligning the keys to them is unambiguous even for unaligned caller keys. */
    p[0] = align_to(p[0], p[1]);
    p[3] = align_to(p[3], p[2]);
    *out = casteljau(p, 4, t);
    return QO_OK;
}

qo_status qo_interp_squad_f32(qo_quat_f32 q0, qo_quat_f32 s0, qo_quat_f32 s1, qo_quat_f32 q1,
                            float t, qo_quat_f32 *out)
{
    qo_quat_f32 p[4], x, y;
    qo_status st;
    size_t k;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    p[0] = q0; p[1] = s0; p[2] = s1; p[3] = q1;
    st = check_keys(p, 4);
    if (st != QO_OK) return st;
    for (k = 0; k < 4; k++) (void)qo_quat_normalize_f32(p[k], &p[k]);
    *out = p[0];
    st = check_t(t);
    if (st != QO_OK || t == 0.0f) return st;
    p[3] = align_to(p[3], p[0]);
    p[1] = align_to(p[1], p[0]);
    p[2] = align_to(p[2], p[3]);
    if (t == 1.0f) {
        *out = p[3];
        return QO_OK;
    }
    (void)slerp_raw(p[0], p[3], t, &x);
    (void)slerp_raw(p[1], p[2], t, &y);
    (void)slerp_raw(x, y, 2.0f * t * (1.0f - t), out);
    return QO_OK;
}

/* log of a unit quaternion (its vector part; cannot fail for a unit q). */
static qo_vec3_f32 log_unit(qo_quat_f32 q)
{
    qo_vec3_f32 l;
    (void)qo_quat_log_f32(q, &l);
    return l;
}

qo_status qo_interp_squad_controls_f32(const qo_quat_f32 *keys, size_t n, qo_quat_f32 *s)
{
    qo_quat_f32 qm, qc, qn, qci, e;
    qo_vec3_f32 l1, l2, arg;
    qo_status st;
    size_t i;
    if (keys == NULL || s == NULL) {
        fill_identity(s, n);
        return QO_E_NULL;
    }
    fill_identity(s, n);
    if (n < 2) return QO_E_TOO_FEW;
    st = check_keys(keys, n);
    if (st != QO_OK) return st;
    (void)qo_quat_normalize_f32(keys[0], &qc);
    s[0] = qc;
    qn = next_key(keys[1], qc);
    for (i = 1; i + 1 < n; i++) {
        qm = qc;
        qc = qn;
        qn = next_key(keys[i + 1], qc);
        qci = qo_quat_conj_f32(qc);
        /* Aligned keys: both relative rotations have w >= 0, so the logs are the short ones. */
        l1 = log_unit(qo_quat_mul_f32(qci, qn));
        l2 = log_unit(qo_quat_mul_f32(qci, qm));
        arg.x = -0.25f * (l1.x + l2.x);
        arg.y = -0.25f * (l1.y + l2.y);
        arg.z = -0.25f * (l1.z + l2.z);
        (void)qo_quat_exp_f32(arg, &e);
        (void)qo_quat_normalize_f32(qo_quat_mul_f32(qc, e), &s[i]);
    }
    s[n - 1] = qn;
    return QO_OK;
}
