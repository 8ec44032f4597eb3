/* float32 transcendental kernels. See qorient/fmath.h for the contract, methods and bounds.
 * Only IEEE-exact operations are used (+, -, *, /, sqrtf, conversions, integer arithmetic), so
 * with contraction off every target computes the same bits; no double anywhere (a Cortex-M4F
 * has single precision only). */
#include "qorient/fmath.h"

#include <math.h>
#include <stdint.h>

#include "fmath_internal.h"

#define FM_SSE2 QO_FM_ATAN2X4_WIDE
#if FM_SSE2
#include <emmintrin.h>   /* a compiler header, not an OS one */
#endif

typedef union { float f; uint32_t u; } fbits;

static uint32_t bits_of(float f)
{
    fbits b;
    b.f = f;
    return b.u;
}

static float float_of(uint32_t u)
{
    fbits b;
    b.u = u;
    return b.f;
}

/* pi/4, pi/2, 3pi/4, pi as hi + lo (hi = the float nearest, lo = the float nearest the rest). */
#define PIO4_HI  0x1.921fb6p-1f
#define PIO4_LO  (-0x1.777a5cp-26f)
#define PIO2_HI  0x1.921fb6p+0f
#define PIO2_LO  (-0x1.777a5cp-25f)
#define PI3O4_HI 0x1.2d97c8p+1f
#define PI3O4_LO (-0x1.99bc5cp-28f)
#define PI_HI    0x1.921fb6p+1f
#define PI_LO    (-0x1.777a5cp-24f)

/* Veltkamp split: a = hi + lo with hi holding the top 12 bits, so products of halves are
 * exact. |a| < 2^115 (no overflow of a * 4097). */
static void split12(float a, float *hi, float *lo)
{
    float c = a * 4097.0f;
    *hi = c - (c - a);
    *lo = a - *hi;
}

/* ---- sin, cos ------------------------------------------------------------------------- */

/* 2/pi, bits 1..224 after the binary point (big-endian words): 224 bits cover the window
 * the largest float exponent needs (bit 102 + 96). */
static const uint32_t two_over_pi[7] = {
    0xA2F9836Eu, 0x4E441529u, 0xFC2757D1u, 0xF534DDC0u, 0xDB629599u, 0x3C439041u, 0xFE5163ABu
};

/* Bits p+1 .. p+32 of 2/pi (bits at or before the point are 0): p >= -32. */
static uint32_t two_over_pi_at(int p)
{
    int i, s;
    if (p <= -32) return 0u;
    if (p < 0) return two_over_pi[0] >> (unsigned)(-p);
    i = p >> 5;
    s = p & 31;
    if (s == 0) return two_over_pi[i];
    return (two_over_pi[i] << (unsigned)s) | (two_over_pi[i + 1] >> (unsigned)(32 - s));
}

/* pi/2 * 2^-64 split so that a 12-bit float times RED_CH is exact. */
#define RED_C  0x1.921fb6p-64f
#define RED_CH 0x1.922p-64f
#define RED_CL (-0x1.2aeef4p-82f)

/* Reduced argument: x = k pi/2 + (r + rlo), |r| <= pi/4 (rlo a few ulp of r or less). */
typedef struct reduced { float r, rlo; unsigned k; } reduced;

/* x finite, |x| > pi/4. x = m 2^sh with m < 2^24, so x 2/pi mod 4 needs only the bits of 2/pi
 * from sh - 2 on (earlier ones give multiples of 4): a 96-bit window V, and (m V) mod 2^96 is
 * x 2/pi mod 4 with 94 fraction bits - exact to far below the closest a float comes to a
 * multiple of pi/2. */
static reduced reduce(float x)
{
    uint32_t u = bits_of(x), m, v0, v1, v2, l0, l1, l2;
    int sh = (int)((u >> 23) & 0xffu) - 150;
    uint64_t lo, mid, t, frac, mag, mh;
    float hi, big, r_hi, r_lo, lo_f;
    int neg;
    reduced out;
    m = (u & 0x7fffffu) | 0x800000u;
    v2 = two_over_pi_at(sh - 2);
    v1 = two_over_pi_at(sh - 2 + 32);
    v0 = two_over_pi_at(sh - 2 + 64);
    lo = (uint64_t)m * v0;
    mid = (uint64_t)m * v1;
    l0 = (uint32_t)lo;
    t = (lo >> 32) + (mid & 0xffffffffu);
    l1 = (uint32_t)t;
    l2 = (uint32_t)((t >> 32) + (mid >> 32)) + m * v2; /* mod 2^32 */
    (void)l0;
    /* Quadrant = the 2 integer bits; frac = the next 64 bits (l0's low 30 bits are below
     * 2^-64 turns and dropped). Round to the nearest quadrant: frac >= 1/2 means k + 1 and a
     * negative remainder frac - 1. */
    out.k = l2 >> 30;
    frac = ((uint64_t)l2 << 34) | ((uint64_t)l1 << 2) | (l0 >> 30);
    neg = (int)(frac >> 63);
    if (neg) {
        out.k += 1u;
        mag = (uint64_t)0 - frac; /* 2^64 - frac, in (0, 2^63] */
    } else {
        mag = frac;
    }
    /* r = mag 2^-64 pi/2 as a float pair: hi = mag rounded to 12 bits (Veltkamp), so
     * hi * RED_CH is exact; the rest (mag - hi, exact in integers) and RED_CL give the low
     * part. */
    big = (float)mag;
    hi = big * 4097.0f;
    hi = hi - (hi - big);
    mh = (uint64_t)hi;
    lo_f = (mh > mag) ? -(float)(mh - mag) : (float)(mag - mh);
    r_hi = hi * RED_CH;
    r_lo = hi * RED_CL + lo_f * RED_C;
    out.r = r_hi + r_lo;
    out.rlo = r_lo - (out.r - r_hi);
    if (neg) {
        out.r = -out.r;
        out.rlo = -out.rlo;
    }
    if (u >> 31) { /* x < 0: x 2/pi = -(|x| 2/pi) */
        out.r = -out.r;
        out.rlo = -out.rlo;
        out.k = 0u - out.k;
    }
    out.k &= 3u;
    return out;
}

/* pi/2 - PIO2_HI - PIO2_LO */
#define PIO2_LO2 (-0x1.ee59dap-50f)

/* x - k pi/2 for pi/4 < |x| < 5pi/4 (k = +-1, +-2: k PIO2_HI is exact and x - k PIO2_HI is
 * exact by Sterbenz), the rest of k pi/2 subtracted as a float pair (TwoSum), so r + rlo
 * carries pi/2 to 2^-74: the whole Payne-Hanek reduction is not needed for the angles the
 * core passes (half angles, slerp's u th). */
static reduced reduce_small(float x)
{
    reduced out;
    float kf, r1, b, r, bb;
    int k = (int)(x * 0x1.45f306p-1f + (x < 0.0f ? -0.5f : 0.5f)); /* round(x 2/pi) */
    kf = (float)k;
    r1 = x - kf * PIO2_HI;
    b = -kf * PIO2_LO;
    r = r1 + b;
    bb = r - r1;
    out.r = r;
    out.rlo = ((r1 - (r - bb)) + (b - bb)) - kf * PIO2_LO2;
    out.k = (unsigned)k & 3u;
    return out;
}

/* Taylor coefficients: on |r| <= pi/4 the first omitted terms (r^11/11!, r^12/12!) are below
 * 2e-9, a few hundredths of an ulp, so rounding - not the approximation - sets the error. */
#define S1 (-1.0f / 6.0f)
#define S2 (1.0f / 120.0f)
#define S3 (-1.0f / 5040.0f)
#define S4 (1.0f / 362880.0f)
#define C1 (1.0f / 24.0f)
#define C2 (-1.0f / 720.0f)
#define C3 (1.0f / 40320.0f)
#define C4 (-1.0f / 3628800.0f)

/* sin(r + rlo), |r| <= pi/4, |rlo| <= ulp(r): r + (r^3 P + rlo cos r), cos r ~ 1 - r^2/2
 * (rlo reaches half an ulp of r: taking cos r as 1 cost 0.14 ulp at r = pi/4). */
static float sin_kernel(float r, float rlo)
{
    float z = r * r;
    return r + (r * z * (S1 + z * (S2 + z * (S3 + z * S4))) + rlo * (1.0f - 0.5f * z));
}

/* cos(r + rlo) = 1 - r^2/2 + r^4 Q - r rlo; the rounding error of 1 - r^2/2 is recovered
 * ((1 - w) - hz is exact) and added back with the small terms. */
static float cos_kernel(float r, float rlo)
{
    float z = r * r, rh, rl, zlo, hz, w;
    /* r^2 = z + zlo exactly (Dekker): the rounding of z would otherwise cost 0.15 ulp */
    split12(r, &rh, &rl);
    zlo = ((rh * rh - z) + 2.0f * rh * rl) + rl * rl;
    hz = 0.5f * z;
    w = 1.0f - hz;
    return w + ((((1.0f - w) - hz) - 0.5f * zlo) +
                (z * z * (C1 + z * (C2 + z * (C3 + z * C4))) - r * rlo));
}

qo_fm_sincos_f32_t qo_fm_sincos_f32(float x)
{
    qo_fm_sincos_f32_t o;
    float s, c;
    reduced rd;
    uint32_t ax = bits_of(x) & 0x7fffffffu;
    if (ax <= 0x3f490fdau) { /* |x| <= pi/4 (rounded down) */
        if (ax < 0x39800000u) { /* |x| < 2^-12: sin x = x, cos x = 1 to within 2^-25 rel */
            o.s = x;
            o.c = 1.0f;
            return o;
        }
        o.s = sin_kernel(x, 0.0f);
        o.c = cos_kernel(x, 0.0f);
        return o;
    }
    if (ax >= 0x7f800000u) { /* Inf or NaN */
        o.s = o.c = x - x;
        return o;
    }
    if (ax < 0x407b53d1u) rd = reduce_small(x); /* |x| < 5pi/4: k = +-1, +-2 */
    else rd = reduce(x);
    s = sin_kernel(rd.r, rd.rlo);
    c = cos_kernel(rd.r, rd.rlo);
    switch (rd.k) {
    case 0u: o.s = s; o.c = c; break;
    case 1u: o.s = c; o.c = -s; break;
    case 2u: o.s = -s; o.c = -c; break;
    default: o.s = -c; o.c = s; break;
    }
    return o;
}

/* sin or cos alone: the same reduction and kernels as qo_fm_sincos_f32 (so the same bits),
 * only the one kernel the quadrant needs. */
static int reduce_any(float x, reduced *rd)
{
    uint32_t ax = bits_of(x) & 0x7fffffffu;
    if (ax <= 0x3f490fdau) {
        rd->r = x;
        rd->rlo = 0.0f;
        rd->k = 0u;
        return 1;
    }
    if (ax >= 0x7f800000u) return 0;
    if (ax < 0x407b53d1u) *rd = reduce_small(x);
    else *rd = reduce(x);
    return 1;
}

/* sin(k pi/2 + r): the sin or cos kernel by k's parity, negated in the lower half-turn. */
static float sin_quadrant(reduced rd)
{
    float v = (rd.k & 1u) ? cos_kernel(rd.r, rd.rlo) : sin_kernel(rd.r, rd.rlo);
    return (rd.k & 2u) ? -v : v;
}

float qo_fm_sin_f32(float x)
{
    reduced rd;
    if ((bits_of(x) & 0x7fffffffu) < 0x39800000u) return x; /* as qo_fm_sincos_f32 */
    if (!reduce_any(x, &rd)) return x - x;
    return sin_quadrant(rd);
}

float qo_fm_cos_f32(float x)
{
    reduced rd;
    if ((bits_of(x) & 0x7fffffffu) < 0x39800000u) return 1.0f;
    if (!reduce_any(x, &rd)) return x - x;
    rd.k = (rd.k + 1u) & 3u; /* cos x = sin(x + pi/2) */
    return sin_quadrant(rd);
}

/* ---- atan2, asin, acos ---------------------------------------------------------------- */

/* atan(u) - u = u^3 P(u^2) for |u| <= tan(pi/8): P of degree 4 interpolating at the Chebyshev
 * nodes of [0, tan^2(pi/8)], coefficients rounded to float (made by tools/fmath-fit-atan.c:
 * 2.8e-9 relative to atan(u), 0.05 ulp; checked with the rest by tests/core/test_math.c). */
static float atan_tail(float u)
{
    float z = u * u;
    return u * z * (-0x1.555554p-2f + z * (0x1.99973p-3f + z * (-0x1.242036p-3f +
           z * (0x1.b8103p-4f + z * -0x1.08455ep-4f))));
}

/* n - q d exactly (Dekker's product q d = p + e, then n - p is exact by Sterbenz as q is n/d
 * rounded); inputs well inside the float range. */
static float quotient_residual(float n, float d, float q)
{
    float qh, ql, dh, dl, p, e;
    split12(q, &qh, &ql);
    split12(d, &dh, &dl);
    p = q * d;
    e = ((qh * dh - p) + qh * dl + ql * dh) + ql * dl;
    return (n - p) - e;
}

float qo_fm_atan2_f32(float y, float x)
{
    float ay = fabsf(y), ax = fabsf(x), num, den, u, du, hi, lo, r, s, t;
    int swap, xneg = (bits_of(x) >> 31) != 0u;
    /* One test for the common case, both finite and non-zero (magnitude bits - 1 below
     * those of +Inf - 1); the special cases follow only when it fails. */
    if (!((bits_of(ax) - 1u) < 0x7f7fffffu && (bits_of(ay) - 1u) < 0x7f7fffffu)) {
        if (isnan(x) || isnan(y)) return x + y;
        if (isinf(ax) || isinf(ay)) {
            if (isinf(ax) && isinf(ay)) r = xneg ? (PI3O4_HI + PI3O4_LO) : (PIO4_HI + PIO4_LO);
            else if (isinf(ax)) r = xneg ? (PI_HI + PI_LO) : 0.0f;
            else r = PIO2_HI + PIO2_LO;
            return (bits_of(y) >> 31) ? -r : r;
        }
        if (ay == 0.0f) {
            r = xneg ? (PI_HI + PI_LO) : 0.0f;
            return (bits_of(y) >> 31) ? -r : r;
        }
        if (ax == 0.0f) {
            r = PIO2_HI + PIO2_LO;
            return (y < 0.0f) ? -r : r;
        }
    }
    swap = ay > ax;
    num = swap ? ax : ay;
    den = swap ? ay : ax;
    /* Bring den to [1, 2^64) by an exact power of two (both inputs alike): the ratio is
     * unchanged and the residual products below neither overflow nor lose bits to
     * underflow unless num/den itself is below 2^-64 (atan = the ratio then). */
    if (den >= 0x1p64f) { num *= 0x1p-64f; den *= 0x1p-64f; }
    else if (den < 1.0f) { num *= 0x1p64f; den *= 0x1p64f; }
    /* Result = base + sign * atan(u + du), base and sign from the octant; du is the rounding
     * error of u (computed exactly), base is hi + lo, and hi + u is summed exactly, so the
     * result is rounded once at its own size (plus the small terms' rounding). */
    if (num > 0.41421356f * den) {
        /* atan(num/den) = pi/4 + atan((num - den)/(num + den)): the rounding errors of the
         * difference and the sum (ed, es: Fast2Sum, den >= num) and the quotient's residual
         * are exact, so du = ((d - u s) + ed - u es)/s. */
        float dn = num - den, ed = num - (dn + den), sm = num + den, es = num - (sm - den);
        u = dn / sm;
        du = ((quotient_residual(dn, sm, u) + ed) - u * es) / sm;
        if (!swap && !xneg) { hi = PIO4_HI; lo = PIO4_LO; }                     /* pi/4 + a */
        else if (swap && !xneg) { hi = PIO4_HI; lo = PIO4_LO; u = -u; du = -du; } /* pi/2 - (pi/4 + a) */
        else if (!swap) { hi = PI3O4_HI; lo = PI3O4_LO; u = -u; du = -du; }      /* pi - (pi/4 + a) */
        else { hi = PI3O4_HI; lo = PI3O4_LO; }                                   /* pi/2 + pi/4 + a */
    } else {
        u = num / den;
        du = (num >= 0x1p-60f) ? quotient_residual(num, den, u) / den : 0.0f;
        if (!swap && !xneg) { hi = 0.0f; lo = 0.0f; }
        else if (swap && !xneg) { hi = PIO2_HI; lo = PIO2_LO; u = -u; du = -du; }
        else if (!swap) { hi = PI_HI; lo = PI_LO; u = -u; du = -du; }
        else { hi = PIO2_HI; lo = PIO2_LO; }
    }
    /* atan(u + du) = atan(u) + du/(1 + u^2); hi + u exactly as s + t (|hi| >= |u| or hi = 0) */
    s = hi + u;
    t = (hi - s) + u;
    r = s + (t + (lo + (atan_tail(u) + du / (1.0f + u * u))));
    return (y < 0.0f) ? -r : r;
}

#if FM_SSE2
/* split12, atan_tail and quotient_residual of four lanes: the same operations in the same
 * order, so each lane is the scalar result bit for bit. */
static void split12_ps(__m128 a, __m128 *hi, __m128 *lo)
{
    __m128 c = _mm_mul_ps(a, _mm_set1_ps(4097.0f));
    *hi = _mm_sub_ps(c, _mm_sub_ps(c, a));
    *lo = _mm_sub_ps(a, *hi);
}

static __m128 atan_tail_ps(__m128 u)
{
    __m128 z = _mm_mul_ps(u, u), p;
    p = _mm_add_ps(_mm_set1_ps(0x1.b8103p-4f), _mm_mul_ps(z, _mm_set1_ps(-0x1.08455ep-4f)));
    p = _mm_add_ps(_mm_set1_ps(-0x1.242036p-3f), _mm_mul_ps(z, p));
    p = _mm_add_ps(_mm_set1_ps(0x1.99973p-3f), _mm_mul_ps(z, p));
    p = _mm_add_ps(_mm_set1_ps(-0x1.555554p-2f), _mm_mul_ps(z, p));
    return _mm_mul_ps(_mm_mul_ps(u, z), p);
}

static __m128 quotient_residual_ps(__m128 n, __m128 d, __m128 q)
{
    __m128 qh, ql, dh, dl, p, e;
    split12_ps(q, &qh, &ql);
    split12_ps(d, &dh, &dl);
    p = _mm_mul_ps(q, d);
    e = _mm_add_ps(_mm_add_ps(_mm_add_ps(_mm_sub_ps(_mm_mul_ps(qh, dh), p), _mm_mul_ps(qh, dl)),
                              _mm_mul_ps(ql, dh)), _mm_mul_ps(ql, dl));
    return _mm_sub_ps(_mm_sub_ps(n, p), e);
}

/* m ? a : b, lane by lane (m all ones or all zeros) */
static __m128 select_ps(__m128 m, __m128 a, __m128 b)
{
    return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b));
}
#endif

void qo_fm_atan2x4_f32(const float y[4], const float x[4], float r[4], int n)
{
    int i;
#if FM_SSE2
    /* qo_fm_atan2_f32's common case (every input finite, non-zero and below 2^64, so only the
     * scaling up by 2^64 can apply) with its branches as lane masks: swap, that scaling, the
     * octant (u = (num - den)/(num + den) or num/den), the base angle and the signs; each lane
     * takes the values its branch would. */
    const __m128 sgn = _mm_set1_ps(-0.0f);
    const __m128 y4 = _mm_loadu_ps(y), x4 = _mm_loadu_ps(x);
    const __m128 ay = _mm_andnot_ps(sgn, y4), ax = _mm_andnot_ps(sgn, x4);
    const __m128i lim = _mm_set1_epi32(0x5f800000), zero = _mm_setzero_si128();   /* 2^64 */
    const __m128i by = _mm_castps_si128(ay), bx = _mm_castps_si128(ax);
    const __m128i ok = _mm_and_si128(_mm_and_si128(_mm_cmpgt_epi32(by, zero), _mm_cmplt_epi32(by, lim)),
                                     _mm_and_si128(_mm_cmpgt_epi32(bx, zero), _mm_cmplt_epi32(bx, lim)));
    if (_mm_movemask_epi8(ok) == 0xffff) {
        const __m128 xneg = _mm_castsi128_ps(_mm_srai_epi32(_mm_castps_si128(x4), 31));
        const __m128 swap = _mm_cmpgt_ps(ay, ax);
        const __m128 mx = _mm_max_ps(ay, ax);
        /* 2^64 where den < 1, else 1 */
        const __m128 f = _mm_max_ps(_mm_set1_ps(1.0f),
                                    _mm_and_ps(_mm_cmplt_ps(mx, _mm_set1_ps(1.0f)), _mm_set1_ps(0x1p64f)));
        const __m128 num = _mm_mul_ps(_mm_min_ps(ay, ax), f), den = _mm_mul_ps(mx, f);
        const __m128 big = _mm_cmpgt_ps(num, _mm_mul_ps(_mm_set1_ps(0.41421356f), den));
        const __m128 dn = _mm_sub_ps(num, den), sm = _mm_add_ps(num, den);
        const __m128 ed = _mm_sub_ps(num, _mm_add_ps(dn, den)), es = _mm_sub_ps(num, _mm_sub_ps(sm, den));
        const __m128 nn = select_ps(big, dn, num), dd = select_ps(big, sm, den);
        const __m128 neg = _mm_and_ps(_mm_xor_ps(swap, xneg), sgn);
        /* the base angle k pi/4: k = 1 or 3 (x < 0) when big, else 2 (swap), 4 (x < 0) or 0 */
        const __m128i bi = _mm_castps_si128(big), si = _mm_castps_si128(swap);
        const __m128i xi = _mm_castps_si128(xneg), bx3 = _mm_and_si128(bi, xi);
        const __m128i k = _mm_or_si128(
            _mm_or_si128(_mm_and_si128(bi, _mm_set1_epi32(1)), _mm_and_si128(bx3, _mm_set1_epi32(2))),
            _mm_andnot_si128(bi, _mm_or_si128(_mm_and_si128(si, _mm_set1_epi32(2)),
                                              _mm_andnot_si128(si, _mm_and_si128(xi, _mm_set1_epi32(4))))));
        const __m128 kf = _mm_cvtepi32_ps(k);
        __m128 u = _mm_div_ps(nn, dd), res, du, hi, lo, s, t, rr;
        res = quotient_residual_ps(nn, dd, u);
        du = _mm_div_ps(select_ps(big, _mm_sub_ps(_mm_add_ps(res, ed), _mm_mul_ps(u, es)), res), dd);
        du = _mm_and_ps(du, _mm_or_ps(big, _mm_cmpge_ps(num, _mm_set1_ps(0x1p-60f))));
        /* k PIO4_HI is exact for k = 0, 1, 2, 4 and rounds to PI3O4_HI for k = 3; k PIO4_LO is
         * exact for k != 3 (-0 for k = 0, where the scalar has +0: the sum lo + x below
         * never meets x = -0, as x >= +0 whenever it is zero there). */
        hi = _mm_mul_ps(kf, _mm_set1_ps(PIO4_HI));
        lo = select_ps(_mm_castsi128_ps(bx3), _mm_set1_ps(PI3O4_LO), _mm_mul_ps(kf, _mm_set1_ps(PIO4_LO)));
        u = _mm_xor_ps(u, neg);
        du = _mm_xor_ps(du, neg);
        s = _mm_add_ps(hi, u);
        t = _mm_add_ps(_mm_sub_ps(hi, s), u);
        rr = _mm_add_ps(s, _mm_add_ps(t, _mm_add_ps(lo, _mm_add_ps(atan_tail_ps(u),
                 _mm_div_ps(du, _mm_add_ps(_mm_set1_ps(1.0f), _mm_mul_ps(u, u)))))));
        _mm_storeu_ps(r, _mm_xor_ps(rr, _mm_and_ps(y4, sgn)));
        return;
    }
    n = 4;
#endif
    for (i = 0; i < n; i++) r[i] = qo_fm_atan2_f32(y[i], x[i]);
}

/* sqrt(1 - x^2) with 1 - x^2 = (1 - x)(1 + x): 1 - x is exact for |x| >= 1/2. */
static float cos_of_asin(float x)
{
    return sqrtf((1.0f - x) * (1.0f + x));
}

float qo_fm_asin_f32(float x)
{
    if (!(fabsf(x) <= 1.0f)) return (x - x) / (x - x); /* NaN, also for +-Inf */
    return qo_fm_atan2_f32(x, cos_of_asin(x));
}

float qo_fm_acos_f32(float x)
{
    if (!(fabsf(x) <= 1.0f)) return (x - x) / (x - x);
    return qo_fm_atan2_f32(cos_of_asin(x), x);
}

/* ---- exp, log ------------------------------------------------------------------------- */

#define LN2_HI 0x1.63p-1f         /* 0.693359375: 9 bits, k * LN2_HI exact for |k| < 2^15 */
#define LN2_LO (-0x1.bd0106p-13f) /* ln 2 - LN2_HI */
#define LOG2E  0x1.715476p+0f

float qo_fm_exp_f32(float x)
{
    float kf, r, r1, rlo, t, one_r, z, p;
    int k;
    if (isnan(x)) return x + x;
    if (x > 88.72283935546875f) return INFINITY;
    if (x < -103.972084045410156f) return 0.0f;
    /* k = round(x / ln 2), halves away from zero (any tie rule works: |r| <= ln2/2 + ulp) */
    kf = x * LOG2E;
    k = (int)(kf + (kf < 0.0f ? -0.5f : 0.5f));
    kf = (float)k;
    /* r + rlo = x - k ln 2: x - k LN2_HI is exact, the LN2_LO step's rounding is kept
     * (Fast2Sum), as is that of 1 + r below: at k != 0 each cost a quarter ulp. */
    r1 = x - kf * LN2_HI;
    t = kf * LN2_LO;
    r = r1 - t;
    rlo = (r1 - r) - t;
    z = r * r;
    /* e^r = 1 + (r + r^2 P(r)), Taylor to r^8: on |r| <= ln2/2 the first omitted term
     * r^9/9! is 2e-10, below 0.01 ulp. */
    one_r = 1.0f + r;
    t = (1.0f - one_r) + r; /* exact: |1| >= |r| */
    p = one_r + (t + (rlo + z * (0.5f + r * (1.0f / 6.0f + r * (1.0f / 24.0f + r * (1.0f / 120.0f +
        r * (1.0f / 720.0f + r * (1.0f / 5040.0f + r * (1.0f / 40320.0f)))))))));
    /* times 2^k: 2^k itself is a normal float for k in [-126, 127]; outside, two steps. */
    if (k > 127) return p * 0x1p127f * float_of((uint32_t)(k - 127 + 127) << 23);
    if (k < -126) return p * 0x1p-100f * float_of((uint32_t)(k + 100 + 127) << 23);
    return p * float_of((uint32_t)(k + 127) << 23);
}

float qo_fm_log_f32(float x)
{
    uint32_t u;
    int e;
    float f, fe, z, y, fh, fl, zlo, w, t, h;
    if (isnan(x)) return x + x;
    if (x == 0.0f) return -INFINITY;
    if (x < 0.0f) return (x - x) / (x - x);
    if (isinf(x)) return x;
    u = bits_of(x);
    e = 0;
    if (u < 0x00800000u) { /* subnormal: scale by 2^25 exactly */
        u = bits_of(x * 0x1p25f);
        e = -25;
    }
    e += (int)(u >> 23) - 127;
    /* mantissa in [1, 2); fold to [sqrt(1/2), sqrt(2)) so the polynomial sees |f| < 0.42 */
    u = (u & 0x7fffffu) | 0x3f800000u;
    if (u > 0x3fb504f3u) { /* > sqrt(2) */
        u -= 0x00800000u;   /* halve */
        e += 1;
    }
    f = float_of(u) - 1.0f; /* exact (Sterbenz) */
    fe = (float)e;
    z = f * f;
    /* ln(1 + f) = f - f^2/2 + f^3 P(f), Cephes logf coefficients. */
    y = ((((((((7.0376836292e-2f * f - 1.1514610310e-1f) * f + 1.1676998740e-1f) * f
              - 1.2420140846e-1f) * f + 1.4249322787e-1f) * f - 1.6668057665e-1f) * f
              + 2.0000714765e-1f) * f - 2.4999993993e-1f) * f + 3.3333331174e-1f) * f * z;
    /* f - f^2/2 with its rounding recovered: f^2 = z + zlo exactly (Dekker), w = f - z/2
     * rounded and (f - w) - z/2 its exact error, so only the final sum rounds at full size. */
    split12(f, &fh, &fl);
    zlo = ((fh * fh - z) + 2.0f * fh * fl) + fl * fl;
    w = f - 0.5f * z;
    y += fe * LN2_LO + (((f - w) - 0.5f * z) - 0.5f * zlo);
    /* e ln 2 + w exactly as h + err (|e LN2_HI| >= |w| when e != 0; e = 0 gives h = w) */
    t = fe * LN2_HI;
    h = t + w;
    return h + (((t - h) + w) + y);
}
