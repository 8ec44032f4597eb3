/* Quaternion algebra in fixed point (Q1.30). See qorient/quat_fx.h for the contracts.
 * Integer arithmetic only: products in int64, sums rounded once with qo_fx_sum_round_i64.
 * mul, rotate and normalize have a fast path for components within +-1.25 (every normalised
 * quaternion). mul and rotate take it in two forms chosen per architecture (QO_FX_NARROW_MUL,
 * fx_internal.h): 16-bit column sums on Cortex-M0/M0+ (no 64-bit multiply), plain int64 sums
 * where a widening multiply exists (x86-64, aarch64, ARMv7-M). normalize uses one Newton
 * reciprocal instead of four 64-bit divisions (no divider on Cortex-M0). Every form gives the
 * identical result (same exact sum, same single rounding; tests/core/test_parts_fx.c compares
 * them); other inputs take the general path. This file is the kernel of the fixed core: it
 * depends on fxmath only (convert_fx.c, interp_fx.c build on it, not the other way). */
#include "qorient/quat_fx.h"

#include "qorient/fxmath.h"

#include "fx_internal.h"

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
/* The same exact product without libgcc's 64x64 multiply (4 MULS on Cortex-M0). */
#define PF(a, b) qo_fx_mul32_i64((a), (b))

/* Fast paths: every component |c| <= 1.25 (Q1.30), i.e. any normalised quaternion with ample
 * room for drift. Then the few products summed by mul and rotate stay below 2^63 (the bound
 * is given at each use) and one plain int64 sum is exact: no split hi/lo sums. Other inputs
 * take the general path, which gives the identical result. One add and compare each. */
#define FAST_LIM 0x50000000u
static int fast_quat(qo_quat_q30 q)
{
    return (uint32_t)q.w + FAST_LIM <= 2u * FAST_LIM && (uint32_t)q.x + FAST_LIM <= 2u * FAST_LIM &&
           (uint32_t)q.y + FAST_LIM <= 2u * FAST_LIM && (uint32_t)q.z + FAST_LIM <= 2u * FAST_LIM;
}

#if QO_FX_NARROW_MUL
/*
 * The exact sum of a_i b_i, i < n, as three int32 columns, for |a_i| <= 1.25 * 2^30 and
 * either n <= 3 or also |b_i| <= 1.25 * 2^30 (the fast paths below). Cortex-M0 has only a
 * 32x32 -> 32 multiply and gcc's 64-bit code for it is slow, so each product is taken in
 * centred 16-bit halves, x = xh 2^16 + xl with xl = (int16_t)x in [-2^15, 2^15) and
 * xh = round(x / 2^16) in [-2^15, 2^15], and summed with no 64-bit arithmetic:
 *   sum = H 2^32 + M 2^16 + L,
 *   H: ah bh and the high part of the cross sum ah bl + al bh,
 *   M: the low 16 bits of the cross sum and the high part of al bl,
 *   L: the low 16 bits of al bl (unsigned).
 * Bounds: |ah| <= 20481, |al|, |bl|, |bh| <= 2^15: the cross sum is below
 * 20481 * 2^15 + 2^30 < 2^31, |al bl| <= 2^30, |ah bh| <= 1.25 * 2^29 (1.57 * 2^28 when b is
 * bounded too), so |H| < 2^31 for the n used; |M| < n 2^17, L < n 2^16.
 * (int16_t) of an int32 is modular on every two's-complement compiler (see fxmath.h).
 */
typedef struct dsum { int32_t h, m; uint32_t l; } dsum;

/* The loops over 2 to 4 products, unrolled where gcc allows it (a loop counter and its branch
 * cost more than a tenth of each product on Cortex-M0). */
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 8
#define QO_UNROLL_4 _Pragma("GCC unroll 4")
#else
#define QO_UNROLL_4
#endif

static dsum dot_exact(const int32_t *a, const int32_t *b, int n)
{
    dsum c = { 0, 0, 0 };
    int i;
    QO_UNROLL_4
    for (i = 0; i < n; i++) {
        int32_t al = (int16_t)a[i], bl = (int16_t)b[i];
        int32_t ah = ((a[i] >> 15) + 1) >> 1, bh = ((b[i] >> 15) + 1) >> 1;
        int32_t x = ah * bl + al * bh, ll = al * bl;
        c.h += ah * bh + (x >> 16);
        c.m += (int32_t)(uint16_t)x + (ll >> 16);
        c.l += (uint16_t)ll;
    }
    return c;
}

/* sum / 2^sh = h 2^(32-sh) + (m >> (sh-16)) + (l + (m mod 2^(sh-16)) 2^16) / 2^sh: only the
 * last term has a fraction (its numerator < 2^sh + 2^20 < 2^32), so it alone is rounded. */
static int64_t rnd30(dsum c)
{
    uint32_t f = c.l + (((uint32_t)c.m & 0x3FFFu) << 16) + ((uint32_t)1 << 29);
    return (int64_t)c.h * 4 + ((c.m >> 14) + (int32_t)(f >> 30));
}

static int64_t rnd29(dsum c)
{
    uint32_t f = c.l + (((uint32_t)c.m & 0x1FFFu) << 16) + ((uint32_t)1 << 28);
    return (int64_t)c.h * 8 + ((c.m >> 13) + (int32_t)(f >> 29));
}

/* rnd30 saturated to int32 (over set on saturation), in 32-bit arithmetic unless H is near
 * the int32 range of the result (then through rnd30's int64 value). */
static int32_t rnd30_sat(dsum c, int *over)
{
    if (c.h > -(1 << 28) && c.h < (1 << 28)) {
        uint32_t f = c.l + (((uint32_t)c.m & 0x3FFFu) << 16) + ((uint32_t)1 << 29);
        return c.h * 4 + (c.m >> 14) + (int32_t)(f >> 30);   /* |.| < 2^30 + 2^7 */
    } else {
        return qo_fx_sat_i32_flag(rnd30(c), over);
    }
}

#else
/* With a widening multiply the same exact sum is a plain int64 sum: for the operands of the
 * fast paths (bounds as above) every partial sum stays below 2^63. */
typedef int64_t dsum;

static dsum dot_exact(const int32_t *a, const int32_t *b, int n)
{
    dsum s = 0;
    int i;
    for (i = 0; i < n; i++) s += (int64_t)a[i] * b[i];
    return s;
}

static int64_t rnd30(dsum s) { return qo_fx_rshift_round_up(s, 30); }
static int64_t rnd29(dsum s) { return qo_fx_rshift_round_up(s, 29); }

static int32_t rnd30_sat(dsum s, int *over)
{
    return qo_fx_sat_i32_flag(rnd30(s), over);
}
#endif

/* a*b for the fast range (fast_quat of both): exact, rounded once, saturated; returns 1 if a
 * component saturated. */
static int mul_fast(qo_quat_q30 a, qo_quat_q30 b, qo_quat_q30 *out)
{
    /* b's components in the order and with the signs each output pairs them with a's
     * (negation is safe: |b_i| <= 1.25). */
    const int32_t av[4] = { a.w, a.x, a.y, a.z };
    const int32_t bv[16] = { b.w, -b.x, -b.y, -b.z,   b.x, b.w, b.z, -b.y,
                             b.y, -b.z, b.w, b.x,     b.z, b.y, -b.x, b.w };
    int over = 0;
    out->w = rnd30_sat(dot_exact(bv, av, 4), &over);
    out->x = rnd30_sat(dot_exact(bv + 4, av, 4), &over);
    out->y = rnd30_sat(dot_exact(bv + 8, av, 4), &over);
    out->z = rnd30_sat(dot_exact(bv + 12, av, 4), &over);
    return over;
}

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
    if (fast_quat(a) && fast_quat(b)) {
        (void)mul_fast(a, b, &out);
        return out;
    }
    mul_wide(a, b, r);
    (void)sat_quat(r, &out);
    return out;
}

qo_status qo_quat_mul_checked_q30(qo_quat_q30 a, qo_quat_q30 b, qo_quat_q30 *out)
{
    int64_t r[4];
    if (out == NULL) return QO_E_NULL;
    if (fast_quat(a) && fast_quat(b)) return mul_fast(a, b, out) ? QO_E_OVERFLOW : QO_OK;
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

/* floor((a 2^30 + floor(n / 2)) / n), i.e. round(a 2^30 / n) with ties away from zero, for
 * a <= 2^31, 2^30 <= n < 2^32, given r ~ 2^62 / (n << sh) (sh = 1 if n < 2^31, else 0):
 * an estimate from the reciprocal, then made exact against the remainder (a few steps at
 * most; the result does not depend on the estimate's error). */
static uint32_t div30(uint32_t a, uint32_t n, uint32_t r, unsigned sh)
{
    uint32_t q = (uint32_t)(qo_fx_umul32_u64(a, r) >> (32u - sh));
    int64_t rem = (int64_t)(((uint64_t)a << 30) + (n >> 1)) - (int64_t)qo_fx_umul32_u64(q, n);
    while (rem < 0) { q--; rem += n; }
    while (rem >= (int64_t)n) { q++; rem -= n; }
    return q;
}

qo_status qo_quat_normalize_q30(qo_quat_q30 q, qo_quat_q30 *out)
{
    int32_t c[4];
    uint32_t a[4], m = 0, nn, r;
    uint64_t n2, n;
    unsigned sh;
    int i, all;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_q30();
    c[0] = q.w; c[1] = q.x; c[2] = q.y; c[3] = q.z;
    for (i = 0; i < 4; i++) {
        a[i] = qo_fx_abs_u32(c[i]);   /* <= 2^31 */
        if (a[i] > m) m = a[i];
    }
    if (m == 0) return QO_E_DEGENERATE;
    /* Scale (exactly) so the largest magnitude is in [2^30, 2^31]: short quaternions keep
     * their direction to full precision and |c|^2 uses the whole 64 bits. */
    sh = 0;
    while (m < ((uint32_t)1 << 30)) { m <<= 1; sh++; }
    for (i = 0; i < 4; i++) a[i] <<= sh;
    /* Four magnitudes below 2^31 sum to below 2^64 when squared; only four of exactly 2^31
     * (all INT32_MIN) would carry, and halving those is exact. */
    all = 1;
    for (i = 0; i < 4; i++) if (a[i] != ((uint32_t)1 << 31)) all = 0;
    if (all) for (i = 0; i < 4; i++) a[i] >>= 1;
    n2 = qo_fx_usq_u64(a[0]) + qo_fx_usq_u64(a[1]) + qo_fx_usq_u64(a[2]) + qo_fx_usq_u64(a[3]);
    n = qo_fx_sqrt_u64(n2);   /* |c| in units where 2^30 is 1, in [2^30, 2^32] */
    if (n >= ((uint64_t)1 << 32)) {
        /* Only for n2 >= (2^32 - 1/2)^2 (three components at -2^31): n = 2^32 exactly and
         * c_i 2^30 / n is a plain rounded shift, the same as the division. */
        int32_t o[4];
        for (i = 0; i < 4; i++) {
            uint32_t qi = (uint32_t)((((uint64_t)a[i] << 30) + ((uint64_t)1 << 31)) >> 32);
            o[i] = c[i] < 0 ? -(int32_t)qi : (int32_t)qi;
        }
        out->w = o[0]; out->x = o[1]; out->y = o[2]; out->z = o[3];
        return QO_OK;
    }
    /* The quotients round(a_i 2^30 / n) (ties away from zero) through one reciprocal instead
     * of four 64-bit divisions (each a long libgcc routine on a core without a divider),
     * each made exact against its remainder. */
    nn = (uint32_t)n;
    sh = nn < ((uint32_t)1 << 31) ? 1u : 0u;
    /* Two 64-bit Newton steps (~2^-31): div30's correction then takes 0 or 1 step. */
    r = qo_fx_recip62_step(nn << sh, qo_fx_recip62_u32(nn << sh));
    {
        int32_t o[4];
        for (i = 0; i < 4; i++) {
            uint32_t qi = div30(a[i], nn, r, sh);   /* <= 2^30 */
            o[i] = c[i] < 0 ? -(int32_t)qi : (int32_t)qi;
        }
        out->w = o[0]; out->x = o[1]; out->y = o[2]; out->z = o[3];
    }
    return QO_OK;
}

/* One output of normalize_fast: sign(c) min(round(a y / 2^31), 2^30) for a <= 2^31 (a < 2^31
 * unless a mod 2^16 == 0) and y < 2^31, in 16-bit partial products and 32-bit words (no 64-bit
 * arithmetic on Cortex-M0): a y = ah yh 2^32 + (ah yl + al yh) 2^16 + al yl, the cross sum
 * below 2^32 - 2^17; only the low 16 bits of al yl are dropped before the rounding. */
static int32_t nf_out(int32_t c, uint32_t a, uint32_t y)
{
    uint32_t ah = a >> 16, al = a & 0xFFFFu, yh = y >> 16, yl = y & 0xFFFFu;
    uint32_t mid = ah * yl + al * yh + ((al * yl) >> 16) + ((uint32_t)1 << 14);
    uint32_t v = ((ah * yh) << 1) + (mid >> 15);
    if (v > (uint32_t)QO_Q30_ONE) v = (uint32_t)QO_Q30_ONE;
    return c < 0 ? -(int32_t)v : (int32_t)v;
}

/* Columns of a^2 for a < 2^30 (a = ah 2^16 + al): ah^2 into *hh, ah al into *hl (the cross
 * term halved), al^2 / 2^16 into *ll; for four components none of the sums overflows. */
static void nf_sq(uint32_t a, uint32_t *hh, uint32_t *hl, uint32_t *ll)
{
    uint32_t ah = a >> 16, al = a & 0xFFFFu;
    *hh += ah * ah;
    *hl += ah * al;
    *ll += (al * al) >> 16;
}

qo_status qo_quat_normalize_fast_q30(qo_quat_q30 q, qo_quat_q30 *out)
{
    uint32_t aw = qo_fx_abs_u32(q.w), ax = qo_fx_abs_u32(q.x), ay = qo_fx_abs_u32(q.y), az = qo_fx_abs_u32(q.z);
    uint32_t m = aw | ax | ay | az, x, y, hh = 0, hl = 0, ll = 0;
    unsigned sh = 0;
    if (out == NULL) return QO_E_NULL;
    if (m == 0) {
        *out = qo_quat_identity_q30();
        return QO_E_DEGENERATE;
    }
    /* Exact power-of-two scaling so the largest magnitude is in [2^29, 2^30] (the OR of the
     * magnitudes has the top bit of the largest; a unit quaternion is there already): the
     * squares then sum to at most 2^62 and short inputs keep 30 significant bits. */
    if (m >= ((uint32_t)1 << 30)) {
        aw = (aw + 1u) >> 1; ax = (ax + 1u) >> 1; ay = (ay + 1u) >> 1; az = (az + 1u) >> 1;
    } else if (m < ((uint32_t)1 << 29)) {
        if ((m >> 14) == 0) { m <<= 16; sh = 16; }
        if ((m >> 22) == 0) { m <<= 8; sh += 8; }
        if ((m >> 26) == 0) { m <<= 4; sh += 4; }
        if ((m >> 28) == 0) { m <<= 2; sh += 2; }
        if ((m >> 29) == 0) sh += 1;
        aw <<= sh; ax <<= sh; ay <<= sh; az <<= sh;
    }
    /* |a|^2 = hh 2^32 + hl 2^17 + ll 2^16 (+ < 2^18 dropped) in [2^58, 2^62]: hh < 2^30,
     * hl < 2^32, ll < 2^18. x = |a|^2 / 2^30 in [2^28, 2^32], or / 2^28 when that is below
     * 2^30 (an even shift keeps the square root a power of two), so x is in [2^30, 2^32) and
     * 1/|a| = 2^(46 - s) / sqrt(x) with s = 31 (30 for the second case): y = 2^46 / sqrt(x)
     * and a_i 2^30 / |a| = a_i y / 2^s, taken as (2 a_i) y / 2^31 when s = 30. Truncation: a
     * few units of x (2^-28 relative). */
    nf_sq(aw, &hh, &hl, &ll); nf_sq(ax, &hh, &hl, &ll);
    nf_sq(ay, &hh, &hl, &ll); nf_sq(az, &hh, &hl, &ll);
    if (hh >= ((uint32_t)1 << 30)) {
        x = 0xFFFFFFFFu;                            /* |a|^2 = 2^62 exactly: 2^-32 off */
    } else {
        x = (hh << 2) + (hl >> 13) + (ll >> 14);
        if (x < ((uint32_t)1 << 30)) {
            /* The three truncations cost less than 3 in total: + 3 keeps x >= 2^30 (|a|^2 >=
             * 2^58), and x < 4 (x + 2) + 3 stays below 2^32 unless the first x is within 2
             * of 2^30, where 2^32 - 1 is within 2^-29. */
            x = x >= ((uint32_t)1 << 30) - 2u ? 0xFFFFFFFFu
                                               : (hh << 4) + (hl >> 11) + (ll >> 12) + 3u;
            aw <<= 1; ax <<= 1; ay <<= 1; az <<= 1;   /* a y / 2^30 = (2 a) y / 2^31, exact */
        }
    }
    y = qo_fx_rsqrt32_q30(x);
    out->w = nf_out(q.w, aw, y);
    out->x = nf_out(q.x, ax, y);
    out->y = nf_out(q.y, ay, y);
    out->z = nf_out(q.z, az, y);
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

/* v + 2 (w t + u x t) of rotate, rounded once: round((v 2^30 + 2 i) / 2^30) =
 * v + round(i / 2^29) for an integer v, with i = w t + u x t. */
static int32_t rot_out(int32_t v, int64_t i_rnd29)
{
    return qo_fx_sat_i32((int64_t)v + i_rnd29);
}

qo_vec3_q30 qo_quat_rotate_q30(qo_quat_q30 q, qo_vec3_q30 v)
{
    int64_t tt[7];
    int32_t tx, ty, tz;
    qo_vec3_q30 r;
    if (fast_quat(q)) {
        /* The 15-multiply form v' = v + 2 w t + 2 u x t, t = u x v. With |q_i| <= 1.25 and
         * |v_i|, |t_i| <= 2^31: each product <= 1.25 * 2^61, a sum of two < 2^63 and of three
         * <= 3.75 * 2^61 < 2^63 - 2^28: every int64 sum below is exact. Identical results to
         * the general path. */
        /* Signs folded into q (safe: |q_i| <= 1.25); v and t may be any int32. */
        const int32_t qa[15] = { q.y, -q.z, q.z, -q.x, q.x, -q.y,
                                 q.w, q.y, -q.z, q.w, q.z, -q.x, q.w, q.x, -q.y };
        int32_t vb[3], tb[3];
        vb[0] = v.z; vb[1] = v.y;
        tx = qo_fx_sat_i32(rnd30(dot_exact(qa, vb, 2)));
        vb[0] = v.x; vb[1] = v.z;
        ty = qo_fx_sat_i32(rnd30(dot_exact(qa + 2, vb, 2)));
        vb[0] = v.y; vb[1] = v.x;
        tz = qo_fx_sat_i32(rnd30(dot_exact(qa + 4, vb, 2)));
        tb[0] = tx; tb[1] = tz; tb[2] = ty;
        r.x = rot_out(v.x, rnd29(dot_exact(qa + 6, tb, 3)));
        tb[0] = ty; tb[1] = tx; tb[2] = tz;
        r.y = rot_out(v.y, rnd29(dot_exact(qa + 9, tb, 3)));
        tb[0] = tz; tb[1] = ty; tb[2] = tx;
        r.z = rot_out(v.z, rnd29(dot_exact(qa + 12, tb, 3)));
        return r;
    }
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
    uint64_t m = qo_fx_abs_u64(x);
    uint64_t n;
    if (qo_fx_abs_u64(y) > m) m = qo_fx_abs_u64(y);
    if (qo_fx_abs_u64(z) > m) m = qo_fx_abs_u64(z);
    if (qo_fx_abs_u64(w) > m) m = qo_fx_abs_u64(w);
    /* Components below 2^30 keep |v| < 2^31 (sqrt 3 * 2^30 < 2^31). */
    while (m >= ((uint64_t)1 << 30)) {
        m >>= 1;
        w /= 2; x /= 2; y /= 2; z /= 2;
    }
    n = qo_fx_sqrt_u64(qo_fx_abs_u64(x) * qo_fx_abs_u64(x) + qo_fx_abs_u64(y) * qo_fx_abs_u64(y) + qo_fx_abs_u64(z) * qo_fx_abs_u64(z));
    return qo_fx_atan2_q28((int32_t)n, (int32_t)w);
}

qo_q28 qo_quat_angle_between_q30(qo_quat_q30 a, qo_quat_q30 b)
{
    int64_t r[4];
    mul_wide(qo_quat_conj_q30(a), b, r);
    /* Precision: for unit inputs the components are < 2^31 and nothing is shifted. */
    return (qo_q28)(2 * half_angle(r[0] < 0 ? -r[0] : r[0], r[1], r[2], r[3]));
}

qo_status qo_fx_quat_from_rotvec(qo_vec3_q28 rv, qo_quat_q30 *out)
{
    uint64_t n;
    qo_q30 s, c;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_q30();
    /* Three squares of at most 2^62 sum below 2^64; the norm is below 2^32 (|rv| < 16). */
    n = qo_fx_sqrt_u64(qo_fx_abs_u64(rv.x) * qo_fx_abs_u64(rv.x) +
                       qo_fx_abs_u64(rv.y) * qo_fx_abs_u64(rv.y) +
                       qo_fx_abs_u64(rv.z) * qo_fx_abs_u64(rv.z));
    if (n == 0) return QO_OK;
    /* Half of |rv| in Q3.60 without rounding: n * 2^31 < 2^63. */
    (void)qo_fx_sincos_q60((int64_t)n * ((int64_t)1 << 31), &s, &c);
    out->w = c;
    out->x = (qo_q30)qo_fx_div_round_away(P(rv.x, s), n);
    out->y = (qo_q30)qo_fx_div_round_away(P(rv.y, s), n);
    out->z = (qo_q30)qo_fx_div_round_away(P(rv.z, s), n);
    return QO_OK;
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
    return qo_fx_quat_from_rotvec(rv, out);
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
    m = qo_fx_abs_u64(c[0]);
    if (qo_fx_abs_u64(c[1]) > m) m = qo_fx_abs_u64(c[1]);
    if (qo_fx_abs_u64(c[2]) > m) m = qo_fx_abs_u64(c[2]);
    while (m < ((uint64_t)1 << 30)) {
        m <<= 1;
        c[0] *= 2; c[1] *= 2; c[2] *= 2;
    }
    n = qo_fx_sqrt_u64(qo_fx_abs_u64(c[0]) * qo_fx_abs_u64(c[0]) + qo_fx_abs_u64(c[1]) * qo_fx_abs_u64(c[1]) + qo_fx_abs_u64(c[2]) * qo_fx_abs_u64(c[2]));
    out->x = (qo_q28)qo_fx_div_round_away(phi * c[0], n);
    out->y = (qo_q28)qo_fx_div_round_away(phi * c[1], n);
    out->z = (qo_q28)qo_fx_div_round_away(phi * c[2], n);
    return QO_OK;
}

qo_status qo_quat_integrate_q30(qo_quat_q30 q, qo_vec3_q28 dtheta, qo_quat_q30 *out)
{
    qo_quat_q30 dq, qn;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    st = qo_quat_normalize_q30(q, &qn);
    if (st != QO_OK) { *out = qn; return st; }
    (void)qo_fx_quat_from_rotvec(dtheta, &dq);
    return qo_quat_normalize_q30(qo_quat_mul_q30(qn, dq), out);
}
