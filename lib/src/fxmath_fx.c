/* Fixed-point primitives. See qorient/fxmath.h for the contract, methods and error bounds.
 * Integer arithmetic only (int64 products and divisions): no floating point, no libm. */
#include "qorient/fxmath.h"

#include "fx_internal.h"

/* pi/2 in Q3.60 and 2pi in Q3.60 (rounded): the reduction constants of sincos and wrap. */
#define HALF_PI_Q60 ((int64_t)1811004864519280711LL)
#define TWO_PI_Q60  ((int64_t)7244019458077122842LL)
/* pi and pi/2 in Q1.31 (held in int64): the octant constants of atan2. */
#define PI_Q31      ((int64_t)6746518852LL)
#define HALF_PI_Q31 ((int64_t)3373259426LL)
#define ONE_Q31     ((int64_t)2147483648LL)

/* atan(k/8) in Q1.31, k = 0..8 (const: lives in flash). */
static const int64_t atan_k8_q31[9] = {
    0, 267050317, 526087673, 770454148, 995675659,
    1199582895, 1381908109, 1543675670, 1686629713
};

int32_t qo_fx_sat_i32(int64_t v)
{
    if (v > INT32_MAX) return INT32_MAX;
    if (v < INT32_MIN) return INT32_MIN;
    return (int32_t)v;
}

qo_q30 qo_fx_add_q30(qo_q30 a, qo_q30 b) { return qo_fx_sat_i32((int64_t)a + b); }
qo_q30 qo_fx_sub_q30(qo_q30 a, qo_q30 b) { return qo_fx_sat_i32((int64_t)a - b); }
qo_q30 qo_fx_neg_q30(qo_q30 a) { return qo_fx_sat_i32(-(int64_t)a); }

/* a*b / 2^shift, rounded (ties up), saturated. |a*b| <= 2^62 so adding the half cannot
 * overflow. */
static int32_t mul_shift(int32_t a, int32_t b, unsigned shift)
{
    return qo_fx_sat_i32(qo_fx_rshift_round_up((int64_t)a * b, shift));
}

qo_q30 qo_fx_mul_q30(int32_t a, qo_q30 b) { return mul_shift(a, b, 30); }
qo_q28 qo_fx_mul_q28(int32_t a, qo_q28 b) { return mul_shift(a, b, 28); }
qo_q16 qo_fx_mul_q16(int32_t a, qo_q16 b) { return mul_shift(a, b, 16); }

int64_t qo_fx_sum_round_i64(const int64_t *terms, size_t n, unsigned shift)
{
    /* Each term = hi * 2^shift + lo with 0 <= lo < 2^shift; summing the parts separately
     * keeps the exact total without a 128-bit accumulator, and we round once at the end. */
    int64_t hi = 0, lo = 0;
    int64_t mask = ((int64_t)1 << shift) - 1;
    size_t i;
    for (i = 0; i < n; i++) {
        hi += terms[i] >> shift;
        lo += terms[i] & mask;
    }
    return hi + ((lo + ((int64_t)1 << (shift - 1))) >> shift);
}

static qo_status div_shift(int32_t num, int32_t den, unsigned shift, int32_t *out)
{
    uint64_t n, d, q;
    int neg;
    if (out == NULL) return QO_E_NULL;
    if (den == 0) { *out = 0; return QO_E_DEGENERATE; }
    neg = (num < 0) != (den < 0);
    n = num < 0 ? (uint64_t)(-(int64_t)num) : (uint64_t)num;
    d = den < 0 ? (uint64_t)(-(int64_t)den) : (uint64_t)den;
    /* n * 2^shift <= 2^61; + d/2 rounds to nearest, ties away from zero. */
    q = ((n << shift) + d / 2u) / d;
    if (neg) {
        if (q > (uint64_t)1 << 31) { *out = INT32_MIN; return QO_E_OVERFLOW; }
        *out = (int32_t)(-(int64_t)q);
    } else {
        if (q > (uint64_t)INT32_MAX) { *out = INT32_MAX; return QO_E_OVERFLOW; }
        *out = (int32_t)q;
    }
    return QO_OK;
}

qo_status qo_fx_div_q30(int32_t num, int32_t den, qo_q30 *out) { return div_shift(num, den, 30, out); }
qo_status qo_fx_div_q28(int32_t num, int32_t den, qo_q28 *out) { return div_shift(num, den, 28, out); }
qo_status qo_fx_div_q16(int32_t num, int32_t den, qo_q16 *out) { return div_shift(num, den, 16, out); }

/* 2^15 / sqrt(h) at the midpoint of each of 96 intervals of h in [1/4, 1) of width 2^-7
 * (index h 2^7, i.e. the top 7 bits of a 32-bit fraction), rounded: relative error
 * <= 2^-7.8. The seed of the Newton square root below (192 bytes of flash). */
static const uint16_t rsqrt_seed[96] = {
    65030, 64052, 63117, 62222, 61363, 60540, 59748, 58987, 58254, 57548, 56867, 56210,
    55574, 54960, 54366, 53791, 53233, 52693, 52169, 51660, 51165, 50685, 50218, 49763,
    49321, 48890, 48470, 48061, 47663, 47273, 46894, 46523, 46161, 45807, 45462, 45124,
    44793, 44470, 44153, 43843, 43540, 43243, 42951, 42666, 42386, 42112, 41843, 41579,
    41320, 41065, 40816, 40571, 40330, 40093, 39861, 39632, 39408, 39187, 38970, 38756,
    38546, 38340, 38136, 37936, 37739, 37545, 37354, 37166, 36980, 36798, 36618, 36441,
    36266, 36093, 35924, 35756, 35591, 35428, 35267, 35109, 34953, 34798, 34646, 34496,
    34347, 34201, 34056, 33913, 33772, 33633, 33496, 33360, 33225, 33093, 32962, 32832,
};

uint64_t qo_fx_sqrt_u64(uint64_t v)
{
    /* Newton iterations with multiplications only (Cortex-M0 has no divider and no 64-bit
     * multiply): x = v 4^k in [2^62, 2^64); y ~ 1/sqrt(x) from a table and one 16-bit Newton
     * step; s ~ sqrt(x) refined once by s += (x - s^2) y / 2; then s is made exactly
     * floor(sqrt(x)) against the exact remainder x - s^2, so the result does not depend on
     * the estimates' error (they only bound the number of final +-1 steps, 0 to 2). */
    uint64_t x = v, sq, rem;
    uint32_t hi, y, t, e, s;
    int64_t r, sl;
    unsigned k = 0;
    if (v == 0) return 0;
    if ((x >> 32) == 0) { x <<= 32; k = 16; }
    if ((x >> 48) == 0) { x <<= 16; k += 8; }
    if ((x >> 56) == 0) { x <<= 8; k += 4; }
    if ((x >> 60) == 0) { x <<= 4; k += 2; }
    if ((x >> 62) == 0) { x <<= 2; k += 1; }
    hi = (uint32_t)(x >> 32);                       /* h = hi / 2^32 in [1/4, 1) */
    y = rsqrt_seed[(hi >> 25) - 32u];               /* 1/sqrt(h), Q1.15 */
    t = y * y;                                      /* y^2, Q2.30 (< 2^32) */
    e = 3u * ((uint32_t)1 << 30) - (hi >> 16) * (t >> 16);   /* 3 - h y^2, Q2.30 */
    y = y * (e >> 16);                              /* y (3 - h y^2) / 2, Q2.30, ~2^-14 */
    /* sqrt(x) = 2^32 sqrt(h) ~ hi * y / 2^30 (error ~2^18). */
    sq = qo_fx_umul32_u64(hi, y) >> 30;
    s = sq > 0xFFFFFFFFu ? 0xFFFFFFFFu : (uint32_t)sq;
    /* One Newton step on the root: s += (x - s^2) / (2 s), 1/(2 s) ~ y / 2^63 (error ~2^4). */
    r = (int64_t)(x - qo_fx_umul32_u64(s, s));      /* |r| < 2^52: exact as int64 */
    sl = (int64_t)s + (qo_fx_mul32_i64((int32_t)(r >> 32), (int32_t)(y >> 1)) >> 30);
    s = sl > 0xFFFFFFFF ? 0xFFFFFFFFu : sl < 0 ? 0u : (uint32_t)sl;
    /* Exact: floor(sqrt(x)) is the s with s^2 <= x < (s + 1)^2 (< 2^32, so no wrap). */
    sq = qo_fx_umul32_u64(s, s);
    while (sq > x) { sq -= 2u * (uint64_t)s - 1u; s--; }
    rem = x - sq;
    while (rem > 2u * (uint64_t)s) { rem -= 2u * (uint64_t)s + 1u; s++; }
    /* Round to nearest. k = 0: v >= (s + 1/2)^2 = s^2 + s + 1/4 <=> rem > s. k >= 1:
     * floor(sqrt(v) + 1/2) = floor((sqrt(x) + 2^(k-1)) / 2^k), and the integer 2^(k-1) lets
     * floor(sqrt(x)) stand for sqrt(x). Never a tie. */
    if (k == 0) return (uint64_t)s + (rem > s);
    return ((uint64_t)s + ((uint64_t)1 << (k - 1u))) >> k;
}

uint32_t qo_fx_rsqrt32_q30(uint32_t x)
{
    /* Two Newton steps y (3 - h y^2) / 2, h = x / 2^32, from the table seed (2^-7.8), in
     * 32x32 -> 64 products (truncations <= 2^-30): 2^-7.8 -> ~2^-15 -> ~2^-29. */
    uint32_t y = rsqrt_seed[(x >> 25) - 32u], y2, e;          /* Q1.15 */
    e = 3u * ((uint32_t)1 << 30) - (uint32_t)(qo_fx_umul32_u64(x, y * y) >> 32);   /* Q2.30 */
    y = (uint32_t)(qo_fx_umul32_u64(y, e) >> 16);             /* Q2.30, ~2^-15 */
    if (y > 0x7FFFFFFFu) y = 0x7FFFFFFFu;                     /* 1/sqrt(h) <= 2: y^2 < 2^62 */
    y2 = (uint32_t)(qo_fx_umul32_u64(y, y) >> 30);            /* y^2, Q2.30 (< 4) */
    e = 3u * ((uint32_t)1 << 30) - (uint32_t)(qo_fx_umul32_u64(x, y2) >> 32);
    return (uint32_t)(qo_fx_umul32_u64(y, e) >> 31);          /* y e / 2, Q2.30 */
}

qo_status qo_fx_sqrt_q30(qo_q30 x, qo_q30 *out)
{
    if (out == NULL) return QO_E_NULL;
    if (x < 0) { *out = 0; return QO_E_RANGE; }
    /* sqrt(x / 2^30) * 2^30 = sqrt(x * 2^30); x * 2^30 < 2^61. */
    *out = (qo_q30)qo_fx_sqrt_u64((uint64_t)x << 30);
    return QO_OK;
}

qo_status qo_fx_rsqrt_q30(qo_q30 x, qo_q30 *out)
{
    uint64_t s, r;
    unsigned e;
    if (out == NULL) return QO_E_NULL;
    if (x <= 0) { *out = INT32_MAX; return QO_E_RANGE; }
    if (x <= (QO_Q30_ONE >> 2)) { *out = INT32_MAX; return QO_E_OVERFLOW; }
    /* 2^30 / sqrt(x / 2^30) = 2^45 / sqrt(x) = 2^(45 + e/2) / sqrt(x * 2^e). The largest even
     * e keeping x * 2^e < 2^64 gives sqrt(x * 2^e) >= 2^31, so its 0.5 rounding error costs
     * at most 0.5 LSB of the result. */
    e = x < QO_Q30_ONE ? 34u : 32u;
    s = qo_fx_sqrt_u64((uint64_t)x << e);
    r = (((uint64_t)1 << (45u + e / 2u)) + s / 2u) / s;
    *out = r > (uint64_t)INT32_MAX ? INT32_MAX : (qo_q30)r;
    return r > (uint64_t)INT32_MAX ? QO_E_OVERFLOW : QO_OK;
}

static qo_q30 sqrt_sat(uint64_t sum, int carried)
{
    uint64_t r;
    if (carried) return INT32_MAX;
    r = qo_fx_sqrt_u64(sum);
    return r > (uint64_t)INT32_MAX ? INT32_MAX : (qo_q30)r;
}

qo_q30 qo_fx_norm3_q30(qo_q30 x, qo_q30 y, qo_q30 z)
{
    /* Each square <= 2^62, three of them < 2^64: no carry possible. */
    return sqrt_sat(qo_fx_sq_u64(x) + qo_fx_sq_u64(y) + qo_fx_sq_u64(z), 0);
}

qo_q30 qo_fx_norm4_q30(qo_q30 w, qo_q30 x, qo_q30 y, qo_q30 z)
{
    uint64_t s3 = qo_fx_sq_u64(x) + qo_fx_sq_u64(y) + qo_fx_sq_u64(z);
    uint64_t s4 = s3 + qo_fx_sq_u64(w);
    /* Only w = x = y = z = INT32_MIN reaches 2^64 (a norm of 4, saturated anyway). */
    return sqrt_sat(s4, s4 < s3);
}

/* round(a * b / 2^31) for |a|, |b| <= 2^31 (product <= 2^62). */
static int64_t mul31(int64_t a, int64_t b)
{
    return qo_fx_rshift_round_up(a * b, 31);
}

/* Taylor coefficients in Q1.31 (rounded): sin = r + r*u*(c3 + u*(c5 + ...)) to r^11 and
 * cos = 1 + u*(d2 + u*(d4 + ...)) to r^12, u = r^2, on |r| <= pi/4 (truncation < 1e-11). */
static const int64_t sin_c[5] = { -357913941, 17895697, -426088, 5918, -54 };
static const int64_t cos_c[6] = { -1073741824, 89478485, -2982616, 53261, -592, 4 };

qo_status qo_fx_sincos_q60(int64_t angle_q60, qo_q30 *s, qo_q30 *c)
{
    int64_t k = angle_q60 / HALF_PI_Q60;
    int64_t r = angle_q60 - k * HALF_PI_Q60;   /* |r| < pi/2, exact */
    int64_t r32, u31, u33, ws, wc, w34, sv, cv, t;
    uint64_t ar, u64;
    int quadrant;
    if (r > HALF_PI_Q60 / 2) { r -= HALF_PI_Q60; k++; }
    else if (r < -(HALF_PI_Q60 / 2)) { r += HALF_PI_Q60; k--; }
    /* Precision plan (each rounding below costs < 0.25 LSB of Q1.30 in the result): the
     * leading terms r and 1 are kept exact in Q2.62; u = r^2 is formed from r in Q32 as an
     * exact unsigned 64-bit square; only the small correction terms go through the Q1.31
     * Horner evaluation. |r| <= pi/4, so |r32| < 2^31.7 and r32^2 < 2^63.3 (unsigned). */
    r32 = qo_fx_rshift_round_up(r, 28);
    ar = (uint64_t)(r32 < 0 ? -r32 : r32);
    u64 = ar * ar;                                   /* Q64 */
    u31 = (int64_t)((u64 + ((uint64_t)1 << 32)) >> 33);
    u33 = (int64_t)((u64 + ((uint64_t)1 << 30)) >> 31);
    ws = sin_c[4];
    ws = sin_c[3] + mul31(u31, ws);
    ws = sin_c[2] + mul31(u31, ws);
    ws = sin_c[1] + mul31(u31, ws);
    ws = sin_c[0] + mul31(u31, ws);                  /* ~ -1/6, Q1.31 */
    w34 = qo_fx_rshift_round_up(u31 * ws, 28);       /* u * ws ~ -u/6 in Q34 (< 2^30.8) */
    sv = r * 4 + qo_fx_rshift_round_up(r32 * w34, 4);   /* Q62: r + r u ws */
    wc = cos_c[5];
    wc = cos_c[4] + mul31(u31, wc);
    wc = cos_c[3] + mul31(u31, wc);
    wc = cos_c[2] + mul31(u31, wc);
    wc = cos_c[1] + mul31(u31, wc);
    wc = cos_c[0] + mul31(u31, wc);                  /* ~ -1/2, Q1.31 */
    cv = ((int64_t)1 << 62) + qo_fx_rshift_round_up(u33 * wc, 2);   /* Q62: 1 + u wc */
    quadrant = (int)(((k % 4) + 4) % 4);
    switch (quadrant) {
    case 1: t = sv; sv = cv; cv = -t; break;
    case 2: sv = -sv; cv = -cv; break;
    case 3: t = sv; sv = -cv; cv = t; break;
    default: break;
    }
    /* Q2.62 -> Q1.30, rounded once, and kept within [-1, 1]. */
    sv = qo_fx_rshift_round_up(sv, 32);
    cv = qo_fx_rshift_round_up(cv, 32);
    if (sv > QO_Q30_ONE) sv = QO_Q30_ONE;
    if (sv < -QO_Q30_ONE) sv = -QO_Q30_ONE;
    if (cv > QO_Q30_ONE) cv = QO_Q30_ONE;
    if (cv < -QO_Q30_ONE) cv = -QO_Q30_ONE;
    if (s != NULL) *s = (qo_q30)sv;
    if (c != NULL) *c = (qo_q30)cv;
    return (s == NULL || c == NULL) ? QO_E_NULL : QO_OK;
}

/* round(a * b / 2^31) for |a|, |b| < 2^31 through the 32x32 product (no libgcc call). */
static int64_t mul31s(int64_t a, int64_t b)
{
    return qo_fx_rshift_round_up(qo_fx_mul32_i64((int32_t)a, (int32_t)b), 31);
}

/* About a b / 2^31 for int32 a, b with |a b| < 2^62, from three 16x16 products (the low x
 * low one dropped) in 32-bit words: within 2 units of 2^-31 of the exact value. */
static int32_t mulq31_fast(int32_t a, int32_t b)
{
    int32_t ah = a >> 16, bh = b >> 16;
    int32_t al = (int32_t)((uint32_t)a & 0xFFFFu), bl = (int32_t)((uint32_t)b & 0xFFFFu);
    return 2 * ah * bh + (((ah * bl) >> 1) + ((al * bh) >> 1)) / 16384;
}

/* Taylor coefficients on |y| <= pi/4 in Q1.31: sin to y^9 (truncation < 2e-9), cos to y^10
 * (< 2e-10). */
static const int32_t sin2y_c[4] = { -357913941, 17895697, -426088, 5918 };
static const int32_t cos2y_c[5] = { -1073741824, 89478485, -2982616, 53261, -592 };

void qo_fx_sincos_2y_q30(uint32_t y, qo_q30 *s, qo_q30 *c)
{
    /* sin y = y (1 + u ws), cos y = 1 + u wc, u = y^2, Horner in 32-bit words; then the
     * angle doubling: sin 2y = 2 sin y cos y, cos 2y = (cos y - sin y)(cos y + sin y). */
    int32_t u = mulq31_fast((int32_t)y, (int32_t)y);   /* Q1.31, <= 0.62 */
    int32_t ws = sin2y_c[3], wc = cos2y_c[4];
    uint32_t sy, cy;
    int k;
    for (k = 2; k >= 0; k--) ws = sin2y_c[k] + mulq31_fast(u, ws);
    for (k = 3; k >= 0; k--) wc = cos2y_c[k] + mulq31_fast(u, wc);
    /* Q1.31, both < 2^31 for y <= pi/4 (the factor 1 + u ws is <= 2^31: unsigned) */
    sy = (uint32_t)(qo_fx_umul32_u64(y, (uint32_t)(((int32_t)1 << 30) + (mulq31_fast(u, ws) >> 1)) * 2u) >> 31);
    cy = (uint32_t)((int64_t)((uint32_t)1 << 31) + mulq31_fast(u, wc));
    *s = (qo_q30)(qo_fx_umul32_u64(sy, cy) >> 31);
    /* cos y - sin y >= 0 but for rounding at y = pi/4 itself */
    *c = (qo_q30)(qo_fx_umul32_u64(cy > sy ? cy - sy : 0u, cy + sy) >> 32);
}

qo_status qo_fx_sincos_q28(qo_q28 angle_rad, qo_q30 *s, qo_q30 *c)
{
    /* angle * 2^32 is in [-2^63, 2^63): exact in int64 (multiplication, not a shift of a
     * negative value). */
    return qo_fx_sincos_q60((int64_t)angle_rad * ((int64_t)1 << 32), s, c);
}

qo_status qo_fx_sincos_half_q28(qo_q28 angle_rad, qo_q30 *s, qo_q30 *c)
{
    return qo_fx_sincos_q60((int64_t)angle_rad * ((int64_t)1 << 31), s, c);
}

qo_q30 qo_fx_sin_q28(qo_q28 angle_rad)
{
    qo_q30 s, c;
    (void)qo_fx_sincos_q28(angle_rad, &s, &c);
    return s;
}

qo_q30 qo_fx_cos_q28(qo_q28 angle_rad)
{
    qo_q30 s, c;
    (void)qo_fx_sincos_q28(angle_rad, &s, &c);
    return c;
}

/* 2^62 / d at the midpoint of each of 64 intervals of d in [2^31, 2^32) (index d >> 25),
 * rounded: relative error <= 2^-8, the seed of qo_fx_recip62_u32 (256 bytes of flash). */
static const uint32_t recip_seed[64] = {
    2130836488u, 2098304633u, 2066751180u, 2036132644u, 2006408080u, 1977538899u, 1949488702u, 1922223125u,
    1895709703u, 1869917734u, 1844818167u, 1820383490u, 1796587627u, 1773405851u, 1750814694u, 1728791868u,
    1707316192u, 1686367527u, 1665926709u, 1645975491u, 1626496491u, 1607473140u, 1588889636u, 1570730897u,
    1552982525u, 1535630765u, 1518662469u, 1502065065u, 1485826524u, 1469935331u, 1454380460u, 1439151345u,
    1424237860u, 1409630292u, 1395319325u, 1381296015u, 1367551776u, 1354078359u, 1340867839u, 1327912594u,
    1315205296u, 1302738895u, 1290506605u, 1278501893u, 1266718465u, 1255150260u, 1243791434u, 1232636354u,
    1221679586u, 1210915890u, 1200340205u, 1189947649u, 1179733506u, 1169693221u, 1159822392u, 1150116765u,
    1140572228u, 1131184802u, 1121950641u, 1112866020u, 1103927337u, 1095131103u, 1086473940u, 1077952576u,
};

/* See fx_internal.h. The first Newton step in 16x16 products (d r / 2^32 from the high
 * halves, relative truncation < 2^-14: 2^-8 -> ~2^-14), the second in full 64-bit products
 * (-> ~2^-28, the truncations included). */
uint32_t qo_fx_recip62_u32(uint32_t d)
{
    uint32_t r = recip_seed[(d >> 25) - 64u];
    int32_t e32 = (int32_t)((uint32_t)1 << 30) - (int32_t)((d >> 16) * (r >> 16));   /* |.| < 2^23 */
    r = (uint32_t)((int64_t)r + ((int32_t)(r >> 16) * (e32 / 128)) / 128);   /* may reach 2^31 */
    return qo_fx_recip62_step(d, r);
}

qo_q28 qo_fx_atan2_q28(int32_t y, int32_t x)
{
    uint32_t ax = qo_fx_abs_u32(x);
    uint32_t ay = qo_fx_abs_u32(y);
    uint32_t mx, mn, d, r;
    uint64_t bx;
    int32_t by;
    int64_t t, u, p, a;
    int swap;
    unsigned k, f;
    if (ax == 0 && ay == 0) return 0;
    swap = ay > ax;
    mx = swap ? ay : ax;
    mn = swap ? ax : ay;
    /* Scale so mx is in [2^30, 2^31]: the rotation below then cannot overflow, and no input
     * bit is lost (|int32| <= 2^31). */
    while (mx < ((uint32_t)1 << 30)) { mx <<= 1; mn <<= 1; }
    /* k ~ round(8 mn / mx) in 0..8 by comparisons on mn, mx / 16 (no division): a neighbour
     * of the exact rounding only at a boundary, where |t'| below is still <= 1/16 + 2^-25. */
    {
        uint32_t n16 = (mn >> 4) * 16u, m1 = mx >> 4;   /* < 2^31 each */
        k = 0;
        if (n16 >= 7u * m1) k = 4;                    /* 16 mn >= (2k - 1) mx  <=> k up */
        if (n16 >= (2u * k + 3u) * m1) k += 2;
        if (n16 >= (2u * k + 1u) * m1) k += 1;
        if (n16 >= (2u * k + 1u) * m1) k += 1;
    }
    /* Rotate (mx, mn) by -atan(k/8), scaled by 8: the angle left is atan(by / bx) with
     * |by / bx| <= 1/16 (+ tiny). Exact integer arithmetic: bx <= 2^35, |by| <= 2^31 + ... */
    bx = 8u * (uint64_t)mx + (((uint64_t)(k * (mn >> 16)) << 16) + k * (mn & 0xFFFFu));
    /* |8 mn - k mx| <= mx / 2 + tiny fits an int32: the wrapped uint32 difference is it. */
    by = (int32_t)(8u * mn - k * mx);
    /* t = by / bx in Q1.31 through a reciprocal of bx's top 32 bits (bx in [2^33, 2^36):
     * d = bx / 2^f in [2^31, 2^32), truncation <= 2^-31 relative). |t| <= 1/16, so the
     * relative errors of d and of the reciprocal (< 2^-30) cost < 2^-34 absolute, and the
     * final rounding 2^-32: about 0.3 LSB of Q1.31 in all (0.04 LSB of the Q3.28 result). */
    f = (bx >> 35) ? 4u : (bx >> 34) ? 3u : 2u;
    d = (uint32_t)(bx >> f);
    r = qo_fx_recip62_u32(d);                         /* ~2^62 / d */
    t = (qo_fx_mul32_i64(by, (int32_t)(r >> 1)) + ((int64_t)1 << (29u + f))) >> (30u + f);
    /* atan(t) = t (1 - t^2/3 + t^4/5 - t^6/7); the next term is < 2e-12. u = t^2 <= 2^-8:
     * the two inner Horner steps only feed terms below u^2/5 < 2^-18, so 16x16 products
     * (u in Q1.23, coefficients to 15 bits, truncation < 2^-22 each, < 2^-34 in the result
     * after the two factors u and t) do; only u and the last step are full products. */
    u = mul31s(t, t);                                 /* Q1.31, <= 2^23 */
    {
        int32_t u16 = (int32_t)(u >> 8);              /* Q1.23, <= 2^15 */
        int32_t v = 429496730 + (u16 * (-306783378 >> 16)) / 128;
        int32_t w = -715827883 + (u16 * (v >> 16)) / 128;
        p = ONE_Q31 + mul31s(u, w);                   /* <= 2^31 */
    }
    /* t p with p = 2^31 possible (t = 0): as t (p - 1) + t, every factor an int32. */
    a = atan_k8_q31[k] + ((qo_fx_mul32_i64((int32_t)t, (int32_t)(p - 1)) + t + ((int64_t)1 << 30)) >> 31);
    if (swap) a = HALF_PI_Q31 - a;
    if (x < 0) a = PI_Q31 - a;
    if (a < 0) a = 0;
    /* Q1.31 -> Q3.28 rounded on the magnitude, so atan2(-y, x) == -atan2(y, x). */
    a = (a + 4) >> 3;
    if (a > QO_Q28_PI) a = QO_Q28_PI;
    return (qo_q28)(y < 0 ? -a : a);
}

/* sqrt(1 - x^2) in Q1.30 for |x| <= 1 (Q1.30): 1 - x^2 is exact in Q2.60. */
static int32_t cofactor(int32_t x)
{
    int64_t rest = ((int64_t)1 << 60) - (int64_t)x * x;
    return (int32_t)qo_fx_sqrt_u64((uint64_t)rest);
}

static int32_t clamp_unit(qo_q30 x)
{
    if (x > QO_Q30_ONE) return QO_Q30_ONE;
    if (x < -QO_Q30_ONE) return -QO_Q30_ONE;
    return x;
}

qo_q28 qo_fx_asin_q28(qo_q30 x)
{
    int32_t v = clamp_unit(x);
    return qo_fx_atan2_q28(v, cofactor(v));
}

qo_q28 qo_fx_acos_q28(qo_q30 x)
{
    int32_t v = clamp_unit(x);
    return qo_fx_atan2_q28(cofactor(v), v);
}

qo_q28 qo_fx_wrap_pi_q28(qo_q28 a)
{
    int64_t r;
    if (a >= -QO_Q28_PI && a <= QO_Q28_PI) return a;
    /* |a| < 8 < 3pi: one turn of 2pi (in Q3.60, exact) brings it into range. */
    r = (int64_t)a * ((int64_t)1 << 32);
    r = a > 0 ? r - TWO_PI_Q60 : r + TWO_PI_Q60;
    r = (r + ((int64_t)1 << 31)) >> 32;
    if (r > QO_Q28_PI) r = QO_Q28_PI;
    if (r < -QO_Q28_PI) r = -QO_Q28_PI;
    return (qo_q28)r;
}
