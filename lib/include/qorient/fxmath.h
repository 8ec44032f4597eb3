/*
 * qorient/fxmath.h - fixed-point primitives of the fixed core (no float, no double, no libm).
 *
 * Formats: see qorient/types.h. Q1.30 (qo_q30) unit-range values, Q3.28 (qo_q28) radians,
 * Q16.16 (qo_q16) user units. Every function is pure: no static caches, no tables in RAM, no
 * hidden state, safe from interrupts and on several cores at once.
 *
 * Index:
 *   QO_Q28_PI, QO_Q28_HALF_PI, QO_Q28_TWO_PI   (qorient/types.h) pi, pi/2, 2pi in Q3.28
 *   qo_fx_sat_i32          saturate an int64 to int32
 *   qo_fx_mul32_i64        exact signed 32x32 -> 64 product (static inline; 4 16x16 products on ARMv6-M)
 *   qo_fx_umul32_u64       exact unsigned 32x32 -> 64 product (static inline; likewise)
 *   qo_fx_mul32_i64_parts, qo_fx_umul32_u64_parts   the 16x16 partial-product forms themselves
 *   qo_fx_add_q30          saturating a + b (any one format)
 *   qo_fx_sub_q30          saturating a - b (any one format)
 *   qo_fx_neg_q30          saturating -a (any one format)
 *   qo_fx_mul_q30          a * b with b in Q1.30, result in a's format (rounded, saturated)
 *   qo_fx_mul_q28          a * b with b in Q3.28, result in a's format (rounded, saturated)
 *   qo_fx_mul_q16          a * b with b in Q16.16, result in a's format (rounded, saturated)
 *   qo_fx_sum_round_i64    round(sum of int64 terms / 2^shift), exact, one rounding
 *   qo_fx_div_q30          num / den -> Q1.30 (status: den 0, overflow)
 *   qo_fx_div_q28          num / den -> Q3.28 (status: den 0, overflow)
 *   qo_fx_div_q16          num / den -> Q16.16 (status: den 0, overflow)
 *   qo_fx_sqrt_u64         integer square root, rounded to nearest
 *   qo_fx_sqrt_q30         square root of a Q1.30 value (status: negative)
 *   qo_fx_rsqrt_q30        1/sqrt of a Q1.30 value (status: <= 0, overflow)
 *   qo_fx_norm3_q30        sqrt(x^2+y^2+z^2) with 64-bit accumulation (saturated)
 *   qo_fx_norm4_q30        sqrt(w^2+x^2+y^2+z^2) with 64-bit accumulation (saturated)
 *   qo_fx_sincos_q28       sin and cos of a Q3.28 angle (any angle, reduced mod 2pi)
 *   qo_fx_sincos_half_q28  sin and cos of HALF a Q3.28 angle (no rounding of the halving)
 *   qo_fx_sincos_q60       sin and cos of an int64 Q3.60 angle (the kernel of the two above)
 *   qo_fx_sin_q28          sin of a Q3.28 angle
 *   qo_fx_cos_q28          cos of a Q3.28 angle
 *   qo_fx_atan2_q28        atan2(y, x) of two int32 of any one scale -> Q3.28 in [-pi, pi]
 *   qo_fx_asin_q28         asin of a Q1.30 input clamped to [-1, 1] -> Q3.28 in [-pi/2, pi/2]
 *   qo_fx_acos_q28         acos of a Q1.30 input clamped to [-1, 1] -> Q3.28 in [0, pi]
 *   qo_fx_wrap_pi_q28      an angle reduced to [-pi, pi]
 *
 * Rounding: "rounded" means round to nearest with ties toward +infinity (add half an LSB,
 * then floor), unless a function says otherwise. Saturation clamps to [INT32_MIN, INT32_MAX].
 *
 * Methods and accuracy. "within b LSB" = the bound tests/core/test_math.c asserts against
 * double libm or an exact 128-bit integer reference (the test named); bench/accuracy_fx.c
 * measures the worst case (strided sweeps of the whole int32 domain + 4M random inputs),
 * printed in docs/FIGURES.md, accuracy. Code size: Thumb for Cortex-M0+ at -O2, the module
 * fxmath_fx in docs/FIGURES.md, sizes (tools/size-report.sh). No RAM tables, no static state.
 * Cortex-M0/M0+ (ARMv6-M) has no divider and only a 32x32 -> 32 multiply, so the hot paths
 * (sqrt_u64, atan2_q28 and the quaternion operations built on them) use no 64-bit division
 * and take their 64-bit products through qo_fx_umul32_u64 / qo_fx_mul32_i64 below; the
 * instruction counts per call on an emulated M0 are measured by tools/qemu-icount.sh
 * (docs/FIGURES.md, m0).
 *   mul_q30/q28/q16    exact 64-bit product, rounded once, saturated.  within 0.5 LSB
 *                      (correctly rounded; test_mul_edges_and_sweep).
 *   add/sub/neg, sat   saturating.  exact.
 *   sum_round_i64      exact hi/lo split sum, one rounding.  exact (test_sum_round).
 *   div_q30/q28/q16    64-bit integer division, remainder rounding.  within 0.5 LSB (test_div).
 *   sqrt_u64           Newton with multiplications only: v normalised by an even shift,
 *                      1/sqrt seed from a 96-entry table (192 bytes) + one 16-bit Newton
 *                      step, the root refined once by s += (x - s^2) y / 2, then made exactly
 *                      floor(sqrt) against the exact remainder (0-2 steps) and rounded:
 *                      correctly rounded, every uint64.
 *   sqrt_q30           sqrt_u64(x << 30).  within 0.5 LSB (correctly rounded; test_sqrt).
 *   rsqrt_q30          correctly rounded sqrt of x * 2^32 or 2^34, one rounded division.
 *                      within 1 LSB (test_rsqrt).
 *   norm3/norm4_q30    exact 64-bit sum of squares + sqrt_u64.  within 0.5 LSB (test_norm).
 *   sincos (q28, half, q60)  reduction mod pi/2 in Q3.60 with a 61-bit pi/2 (exact to 2^-60
 *                      for every input), then Taylor polynomials on [-pi/4, pi/4] (sin to
 *                      r^11, cos to r^12; truncation < 1e-11): the leading r and 1 kept exact
 *                      in Q2.62, r^2 exact in 64 bits, only the correction terms through a
 *                      Q1.31 Horner evaluation, one final rounding to Q1.30.
 *                      within 1 LSB (test_sincos; the half and Q3.60 forms:
 *                      test_q30_sincos_half_q60_null).  11 consts.
 *   atan2_q28          octant folding to t = min/max in [0, 1]; the nearest k = 0..8 is
 *                      taken and (x, y) rotated by -atan(k/8) EXACTLY in integers
 *                      (8x + ky, 8y - kx), so |t'| <= 1/16; k by three comparisons and
 *                      t' = by/bx through a Newton reciprocal of bx's top 32 bits (64-entry
 *                      seed table, 256 bytes, a 16-bit and a 64-bit step: ~2^-28, < 2^-32
 *                      absolute on t'), no division; then atan(t') = t'(1 - t'^2/3 + t'^4/5
 *                      - t'^6/7) in Q1.31 plus the 9-entry atan(k/8) const table (72 bytes).
 *                      within 1 LSB of Q3.28 (test_atan2; libfixmath's fix16_atan2 beside
 *                      it: docs/FIGURES.md, ir).
 *   asin/acos_q28      atan2 of (x, sqrt(1 - x^2)) with 1 - x^2 exact in Q2.60, so +-1 and
 *                      their neighbourhood keep full accuracy. within 1 LSB (test_asin_acos).
 *   wrap_pi_q28        one exact 2pi step in Q3.60. within 0.5 LSB (test_wrap).
 * Portability: the fixed core needs two's-complement int32_t/int64_t and an arithmetic right
 * shift of negative values (true of gcc and clang on every target); fxmath_fx.c checks this at
 * compile time.
 */
#ifndef QORIENT_FXMATH_H
#define QORIENT_FXMATH_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* v clamped to [INT32_MIN, INT32_MAX]. */
int32_t qo_fx_sat_i32(int64_t v);

/*
 * Exact products (int64_t)a * b and (uint64_t)a * b, for every int32 / uint32 input.
 * Why they exist: ARMv6-M (Cortex-M0/M0+) has only a 32x32 -> 32 MULS, so a C 64-bit product
 * becomes a call to libgcc's general 64x64 __aeabi_lmul (the full 64x64 product, plus the call).
 * Written as four 16x16 partial products, the same product is 4 MULS and a few adds inline.
 * On targets with a widening multiply the compiler does as well either way.
 * The signed product is the unsigned one of the two's-complement bit patterns with the
 * high word corrected (the int64 conversion of a value below 2^63 in magnitude is exact).
 */
static inline uint64_t qo_fx_umul32_u64_parts(uint32_t a, uint32_t b)
{
    uint32_t ah = a >> 16, bh = b >> 16, al = a & 0xFFFFu, bl = b & 0xFFFFu;
    uint32_t ll = al * bl, mid = al * bh, hi = ah * bh, lo;
    uint32_t hl = ah * bl;
    mid += hl;                                   /* may carry: worth 2^48 */
    hi += (mid >> 16) + ((uint32_t)(mid < hl) << 16);
    lo = ll + (mid << 16);
    hi += (uint32_t)(lo < ll);
    return ((uint64_t)hi << 32) | lo;
}

/* The partial products pay only where there is no widening multiply (ARMv6-M); everywhere
 * else (x86-64, ARMv7-M UMULL/SMULL, RV32M mulhu) the plain C product is one or two
 * instructions. Both are exact, so results are bit-identical on every target; define
 * QO_FX_MUL_PARTS to force the partial products (tests compare the two). */
static inline uint64_t qo_fx_umul32_u64(uint32_t a, uint32_t b)
{
#if defined(__ARM_ARCH_6M__) || defined(QO_FX_MUL_PARTS)
    return qo_fx_umul32_u64_parts(a, b);
#else
    return (uint64_t)a * b;
#endif
}

/* Two's complement: a * b = ua * ub - 2^32 (b [a < 0] + a [b < 0]) mod 2^64. */
static inline int64_t qo_fx_mul32_i64_parts(int32_t a, int32_t b)
{
    uint64_t u = qo_fx_umul32_u64_parts((uint32_t)a, (uint32_t)b);
    uint32_t corr = ((uint32_t)b & (uint32_t)(a >> 31)) + ((uint32_t)a & (uint32_t)(b >> 31));
    return (int64_t)(u - ((uint64_t)corr << 32));
}

static inline int64_t qo_fx_mul32_i64(int32_t a, int32_t b)
{
#if defined(__ARM_ARCH_6M__) || defined(QO_FX_MUL_PARTS)
    return qo_fx_mul32_i64_parts(a, b);
#else
    return (int64_t)a * b;
#endif
}

/* a + b, a - b and -a, saturated. Formats must match; the result is in that format. Used for
 * every format (Q1.30, Q3.28, Q16.16): the _q30 suffix names the family, not a restriction.
 * qo_fx_neg_q30(INT32_MIN) is INT32_MAX. */
qo_q30 qo_fx_add_q30(qo_q30 a, qo_q30 b);
qo_q30 qo_fx_sub_q30(qo_q30 a, qo_q30 b);
qo_q30 qo_fx_neg_q30(qo_q30 a);

/* Product a * b where b is in Q1.30 (resp. Q3.28, Q16.16) and a in any format F: the result
 * is in F. Exact 64-bit product, rounded once (ties toward +inf), saturated. So
 * qo_fx_mul_q30(q30, q30) -> Q1.30, qo_fx_mul_q30(angle_q28, q30) -> Q3.28,
 * qo_fx_mul_q28(q28, q28) -> Q3.28, qo_fx_mul_q16(q16, q16) -> Q16.16. */
qo_q30 qo_fx_mul_q30(int32_t a, qo_q30 b);
qo_q28 qo_fx_mul_q28(int32_t a, qo_q28 b);
qo_q16 qo_fx_mul_q16(int32_t a, qo_q16 b);

/*
 * round(sum(terms[0..n-1]) / 2^shift) computed exactly (every term is split into a high and a
 * low part, so no intermediate overflows and there is one rounding, ties toward +inf), NOT
 * saturated. Preconditions (unchecked, documented): |terms[i]| <= 2^62, n <= 16,
 * 8 <= shift <= 40. The typical use is a dot product of Q1.30 values: terms are
 * (int64_t)a_i * b_i (Q2.60), shift 30, result Q1.30 in an int64 (saturate with
 * qo_fx_sat_i32 or check the range yourself).
 */
int64_t qo_fx_sum_round_i64(const int64_t *terms, size_t n, unsigned shift);

/*
 * num / den with both in one format (any), result in Q1.30 (resp. Q3.28, Q16.16), rounded to
 * nearest (ties away from zero).
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_DEGENERATE if den == 0 (*out = 0);
 * QO_E_OVERFLOW if the quotient does not fit (*out = INT32_MAX or INT32_MIN by the sign).
 */
qo_status qo_fx_div_q30(int32_t num, int32_t den, qo_q30 *out);
qo_status qo_fx_div_q28(int32_t num, int32_t den, qo_q28 *out);
qo_status qo_fx_div_q16(int32_t num, int32_t den, qo_q16 *out);

/* floor(sqrt(v) + 1/2): the integer square root rounded to nearest (never a tie), for every
 * uint64 v. The result is at most 2^32 (for v >= (2^32 - 1/2)^2), hence the uint64 type. */
uint64_t qo_fx_sqrt_u64(uint64_t v);

/*
 * sqrt(x) for x in Q1.30, result in Q1.30, correctly rounded (x < 2 so sqrt(x) < 1.42 fits).
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_RANGE if x < 0 (*out = 0).
 */
qo_status qo_fx_sqrt_q30(qo_q30 x, qo_q30 *out);

/*
 * 1/sqrt(x) for x in Q1.30, result in Q1.30 (<= 1 LSB error). Fits for x > 0.25.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_RANGE if x <= 0 (*out = INT32_MAX);
 * QO_E_OVERFLOW if 1/sqrt(x) >= 2, i.e. x <= 0.25 (*out = INT32_MAX).
 */
qo_status qo_fx_rsqrt_q30(qo_q30 x, qo_q30 *out);

/* Euclidean norm of a 3- or 4-vector of Q1.30 components, in Q1.30: the squares are summed
 * exactly in 64 bits and the square root is correctly rounded. Saturates at INT32_MAX
 * (~2.0) when the norm does not fit. Works for any single format (the result has the
 * format of the inputs). */
qo_q30 qo_fx_norm3_q30(qo_q30 x, qo_q30 y, qo_q30 z);
qo_q30 qo_fx_norm4_q30(qo_q30 w, qo_q30 x, qo_q30 y, qo_q30 z);

/*
 * sin and cos of angle_rad (Q3.28 radians, any value in [-8, 8): reduced mod 2pi exactly),
 * results in Q1.30 within 1 LSB of the true sin/cos of the exact input value. sin(0) = 0,
 * cos(0) = QO_Q30_ONE exactly; |results| <= QO_Q30_ONE.
 * Returns QO_OK; QO_E_NULL if s or c is NULL (the other one is still written).
 */
qo_status qo_fx_sincos_q28(qo_q28 angle_rad, qo_q30 *s, qo_q30 *c);

/* sin and cos of angle_rad / 2 (Q3.28 angle), without rounding the halved angle: what a
 * quaternion from an angle needs. Same accuracy and statuses as qo_fx_sincos_q28. */
qo_status qo_fx_sincos_half_q28(qo_q28 angle_rad, qo_q30 *s, qo_q30 *c);

/* sin and cos of an angle given as an int64 in Q3.60 (value = raw / 2^60, any raw value:
 * |angle| < 8 rad), results in Q1.30. For callers that hold angles with more than 28
 * fractional bits (sums, halves, norms computed in 64 bits). Same statuses as above. */
qo_status qo_fx_sincos_q60(int64_t angle_q60, qo_q30 *s, qo_q30 *c);

/* sin / cos of a Q3.28 angle in Q1.30 (the matching half of qo_fx_sincos_q28). */
qo_q30 qo_fx_sin_q28(qo_q28 angle_rad);
qo_q30 qo_fx_cos_q28(qo_q28 angle_rad);

/*
 * atan2(y, x) in Q3.28 radians, in [-QO_Q28_PI, QO_Q28_PI], for y and x of ANY one fixed
 * format (only the ratio matters), every int32 value including INT32_MIN. <= 1 LSB of Q3.28.
 * Axes: atan2(0, x>0) = 0, atan2(0, x<0) = +QO_Q28_PI (there is no -0 in integers),
 * atan2(y>0, 0) = QO_Q28_HALF_PI, atan2(y<0, 0) = -QO_Q28_HALF_PI, and atan2(0, 0) = 0
 * (a documented choice, as C's atan2(+0, +0)).
 */
qo_q28 qo_fx_atan2_q28(int32_t y, int32_t x);

/* asin(x) in [-QO_Q28_HALF_PI, QO_Q28_HALF_PI] and acos(x) in [0, QO_Q28_PI], Q3.28, for x in
 * Q1.30. x outside [-1, 1] (possible in Q1.30, e.g. a dot product that rounding pushed to
 * 1 + 1 LSB) is clamped to +-1 first: asin(+-1) = +-QO_Q28_HALF_PI, acos(1) = 0,
 * acos(-1) = QO_Q28_PI exactly. <= 1 LSB of Q3.28 over the whole domain. */
qo_q28 qo_fx_asin_q28(qo_q30 x);
qo_q28 qo_fx_acos_q28(qo_q30 x);

/* The angle congruent to a mod 2pi in [-QO_Q28_PI, QO_Q28_PI] (exact reduction with a
 * high-precision 2pi, then rounded; an input already in range is returned unchanged). */
qo_q28 qo_fx_wrap_pi_q28(qo_q28 a);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_FXMATH_H */
