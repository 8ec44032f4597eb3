/*
 * lib/src/fx_internal.h - the integer helpers of the fixed core, in one place (private: not
 * installed, not part of the API). Modelled on CMSIS-DSP's Include/dsp/utils.h: static inline,
 * each named by what it does and how it rounds, so a caller picks the rounding it relies on:
 *
 *   qo_fx_abs_u64              |v| of an int64 as uint64, exact for every value (INT64_MIN too)
 *   qo_fx_abs_u32              |v| of an int32 as uint32, exact for every value (INT32_MIN too)
 *   qo_fx_usq_u64              m^2 of a uint32 m <= 2^31, exact (three 16x16 products on ARMv6-M)
 *   qo_fx_sq_u64               v^2 of an int32, exact (<= 2^62)
 *   qo_fx_rshift_round_up      round(v / 2^s), ties toward +infinity (add half, floor)
 *   qo_fx_urshift_round_up_u32 round(v / 2^s) of a uint64, ties up, s <= 34, result < 2^32
 *                              (on 32-bit words: no 64-bit variable shift on Cortex-M0)
 *   qo_fx_rshift_round_away    round(v / 2^s), ties away from zero (odd: f(-v) == -f(v))
 *   qo_fx_rshift_round_away_clamped  the same for any int32 s: s <= 0 gives v, s >= 64 gives 0
 *   qo_fx_rshift_floor         floor(v / 2^s) (plain arithmetic shift, named for its rounding)
 *   qo_fx_div_round_away       round(num / den), ties away from zero (64-bit division)
 *   qo_fx_div_floor            floor(num / den) for den > 0 (64-bit division)
 *   qo_fx_sat_i32_flag         qo_fx_sat_i32 (clamp to [INT32_MIN, INT32_MAX]) that also sets a
 *                              flag when it clamped
 *   qo_fx_add_sat_sym_i64      a + b clamped to the symmetric [-INT64_MAX, INT64_MAX], flag
 *   qo_fx_mul_sat_sym_i64      a * k (small k > 0) clamped to [-INT64_MAX, INT64_MAX], flag
 *   qo_fx_recip62_u32          about 2^62 / d for d in [2^31, 2^32) (Newton, no division)
 *   qo_fx_recip62_step         one more Newton step of that reciprocal
 *   qo_fx_rsqrt32_q30          about 2^30 / sqrt(x / 2^32) for x in [2^30, 2^32) (Newton)
 *   qo_fx_sincos_2y_q30        sin and cos of 2y for y in [0, pi/4] (no reduction, 32-bit)
 *   qo_fx_bits_above_30_u64    max(0, bit length of v - 30): the shift that brings v below 2^30
 *                              (a leading-zero count on 32-bit words: no CLZ on ARMv6-M)
 *
 * The rounding shifts rely on >> of a negative int64 being an arithmetic shift (implementation-
 * defined in C99, arithmetic on gcc and clang for every target): checked here, once, for every
 * file that includes this header.
 */
#ifndef QORIENT_FX_INTERNAL_H
#define QORIENT_FX_INTERNAL_H

#include <stdint.h>

#include "qorient/fxmath.h"

/* 1 where the fast paths take the ARMv6-M (Cortex-M0/M0+) form: no 32x32 -> 64 multiply
 * there, so exact sums of products are built from 16-bit partial products in 32-bit words.
 * Everywhere else (x86-64, aarch64, ARMv7-M SMULL, RV32M mulh) a widening multiply is one or
 * two instructions and plain int64 sums are shorter. Both forms are exact and round once, so
 * results are bit-identical; QO_FX_MUL_PARTS forces the ARMv6-M form on any target (the
 * tests build it on the host and compare). */
#if defined(__ARM_ARCH_6M__) || defined(QO_FX_MUL_PARTS)
#define QO_FX_NARROW_MUL 1
#else
#define QO_FX_NARROW_MUL 0
#endif

typedef char qo_fx_arith_shift_check[((-1) >> 1) == -1 && (((int64_t)-1) >> 1) == -1 ? 1 : -1];

/* |v| as an unsigned 64-bit value; exact for every int64 including INT64_MIN (2^63). */
static inline uint64_t qo_fx_abs_u64(int64_t v)
{
    return v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
}

/* |v| as an unsigned 32-bit value; exact for every int32 including INT32_MIN (2^31). */
static inline uint32_t qo_fx_abs_u32(int32_t v)
{
    return v < 0 ? 0u - (uint32_t)v : (uint32_t)v;
}

/* m^2 exactly, for m <= 2^31 (so m^2 <= 2^62). On ARMv6-M (no 32x32 -> 64 multiply) three
 * 16x16 products, the cross term once and doubled (h l < 2^31 for m <= 2^31), which is
 * shorter than qo_fx_umul32_u64's four; elsewhere one widening multiply. Exact both ways. */
static inline uint64_t qo_fx_usq_u64(uint32_t m)
{
#if QO_FX_NARROW_MUL
    uint32_t h = m >> 16, l = m & 0xFFFFu, c = h * l;
    return ((uint64_t)(h * h) << 32) + ((uint64_t)c << 17) + l * l;
#else
    return (uint64_t)m * m;
#endif
}

/* v^2 exactly as uint64 for every int32 v (<= 2^62, so three of them sum without a carry):
 * on the magnitude through qo_fx_usq_u64 on ARMv6-M, one signed widening multiply elsewhere
 * (no absolute value needed: SMULL on ARMv7-M, imul on x86-64). */
static inline uint64_t qo_fx_sq_u64(int32_t v)
{
#if QO_FX_NARROW_MUL
    return qo_fx_usq_u64(qo_fx_abs_u32(v));
#else
    return (uint64_t)((int64_t)v * v);
#endif
}

/* round(v / 2^s) with ties toward +infinity, 1 <= s <= 62. Precondition (unchecked): v plus
 * 2^(s-1) does not overflow, i.e. v <= INT64_MAX - 2^(s-1). Not odd: -5/2 gives -2, 5/2 gives 3. */
static inline int64_t qo_fx_rshift_round_up(int64_t v, unsigned s)
{
    return (v + ((int64_t)1 << (s - 1u))) >> s;
}

/* round(v / 2^s) with ties toward +infinity for a uint64 v, 0 <= s <= 34, when the result
 * is below 2^32 (unchecked precondition; a carry out of the top bit wraps). Worked on 32-bit
 * words: a variable 64-bit shift is a libgcc call or a long sequence on Cortex-M0. */
static inline uint32_t qo_fx_urshift_round_up_u32(uint64_t v, unsigned s)
{
    uint32_t hi = (uint32_t)(v >> 32), lo = (uint32_t)v, r, half;
    if (s == 0) return lo;
    if (s < 32) {
        r = (hi << (32u - s)) | (lo >> s);
        half = (lo >> (s - 1u)) & 1u;
    } else if (s == 32) {
        r = hi;
        half = lo >> 31;
    } else {
        r = hi >> (s - 32u);
        half = (hi >> (s - 33u)) & 1u;
    }
    return r + half;
}

/* round(v / 2^s) with ties away from zero, 1 <= s <= 63, every int64 v: computed on the
 * magnitude, so it is odd (the rounding of -v is exactly the negated rounding of v). */
static inline int64_t qo_fx_rshift_round_away(int64_t v, unsigned s)
{
    uint64_t m = (qo_fx_abs_u64(v) + ((uint64_t)1 << (s - 1u))) >> s;
    return v < 0 ? -(int64_t)m : (int64_t)m;
}

/* qo_fx_rshift_round_away for a shift that may leave its range (the spline sampler's
 * exponents), every int64 v: s <= 0 returns v unchanged (no scaling up: callers scale up
 * themselves, with a bound check), s >= 64 returns 0 (|v| / 2^64 < 1/2). */
static inline int64_t qo_fx_rshift_round_away_clamped(int64_t v, int32_t s)
{
    if (s <= 0) return v;
    if (s >= 64) return 0;
    return qo_fx_rshift_round_away(v, (unsigned)s);
}

/* floor(v / 2^s), 0 <= s <= 63, every int64 v: the arithmetic shift checked above. */
static inline int64_t qo_fx_rshift_floor(int64_t v, unsigned s)
{
    return v >> s;
}

/* round(num / den) to nearest with ties away from zero, for den > 0 and |num| + den / 2 < 2^64
 * (so every |num| < 2^63). A 64-bit division: a library call on cores without a divider. */
static inline int64_t qo_fx_div_round_away(int64_t num, uint64_t den)
{
    uint64_t q = (qo_fx_abs_u64(num) + den / 2u) / den;
    return num < 0 ? -(int64_t)q : (int64_t)q;
}

/* floor(num / den) for den > 0, every int64 num (C's / truncates toward zero: one down when
 * a negative quotient left a remainder). A 64-bit division. */
static inline int64_t qo_fx_div_floor(int64_t num, int64_t den)
{
    int64_t q = num / den;
    return (num % den < 0) ? q - 1 : q;
}

/* qo_fx_sat_i32(v) (v clamped to [INT32_MIN, INT32_MAX]), every int64 v, and *ovf = 1 when
 * it clamped (*ovf is left as it was otherwise, so one flag collects a run of calls). */
static inline int32_t qo_fx_sat_i32_flag(int64_t v, int *ovf)
{
    int32_t r = qo_fx_sat_i32(v);
    if ((int64_t)r != v) *ovf = 1;
    return r;
}

/* a + b for every int64 a and b, clamped to the symmetric range [-INT64_MAX, INT64_MAX] (so
 * the result can be negated; INT64_MIN comes back only as a itself when b == 0), and
 * *ovf = 1 when it clamped (left as it was otherwise). */
static inline int64_t qo_fx_add_sat_sym_i64(int64_t a, int64_t b, int *ovf)
{
    if (b > 0 && a > INT64_MAX - b) {
        *ovf = 1;
        return INT64_MAX;
    }
    if (b < 0 && a < -INT64_MAX - b) {
        *ovf = 1;
        return -INT64_MAX;
    }
    return a + b;
}

/* a * k for every int64 a and a small k >= 1 (motion_fx.c: 2, 3, 6), clamped to the
 * symmetric range [-INT64_MAX, INT64_MAX] (INT64_MIN too is clamped, for every k), and
 * *ovf = 1 when it clamped (left as it was otherwise). One 64-bit division by k per call. */
static inline int64_t qo_fx_mul_sat_sym_i64(int64_t a, int k, int *ovf)
{
    if (a > INT64_MAX / k) {
        *ovf = 1;
        return INT64_MAX;
    }
    if (a < -INT64_MAX / k) {
        *ovf = 1;
        return -INT64_MAX;
    }
    return a * k;
}

/* One Newton step r += r (2^62 - d r) / 2^62 of a reciprocal r ~ 2^62 / d, d in [2^31, 2^32),
 * for r within 2^-13 relative of the true value (then |2^62 - d r| <= 2^50): the relative
 * error squares (plus ~2^-31 of truncation). Multiplications only (no divider on ARMv6-M). */
static inline uint32_t qo_fx_recip62_step(uint32_t d, uint32_t r)
{
    int64_t e = ((int64_t)1 << 62) - (int64_t)qo_fx_umul32_u64(d, r);
    return (uint32_t)((int64_t)r + (qo_fx_mul32_i64((int32_t)(r >> 1), (int32_t)(e >> 31)) >> 30));
}

/* About 2^62 / d for d in [2^31, 2^32), within ~2^-28 relative (a table seed of 2^-8, a
 * 16-bit Newton step and one qo_fx_recip62_step); a second qo_fx_recip62_step gives ~2^-31.
 * An estimate only: callers that need an exact quotient correct it against the remainder.
 * Defined in fxmath_fx.c (its seed table lives in flash once). */
uint32_t qo_fx_recip62_u32(uint32_t d);

/* About 2^30 / sqrt(x / 2^32) (Q2.30, in (2^30, 2^31)) for x in [2^30, 2^32): the 96-entry
 * seed of qo_fx_sqrt_u64, a 16-bit Newton step and one in 32x32 -> 64 products, within ~2^-28
 * relative (measured bound in tests/core/test_fx_internal.c). Multiplications only. In fxmath_fx.c. */
uint32_t qo_fx_rsqrt32_q30(uint32_t x);

/* sin(2y) and cos(2y) in Q1.30 for y in [0, pi/4] given in Q1.31 (y * 2^31 <= 1686629713):
 * the Taylor sums of qo_fx_sincos_q60 at y in 32x32 -> 64 products and the angle-doubling
 * formulas, no range reduction and no 64-bit multiply or division (the fast tier of slerp;
 * within 8 LSB, tests/core/test_fx_internal.c). In fxmath_fx.c. */
void qo_fx_sincos_2y_q30(uint32_t y, qo_q30 *s, qo_q30 *c);

/* The number of significant bits of v above bit 29: max(0, bit length(v) - 30), so v >> s
 * < 2^30 for s = qo_fx_bits_above_30_u64(v) and no smaller s (0 when v < 2^30, 34 for
 * v >= 2^63). A binary-search leading-zero count on 32-bit words (ARMv6-M has no CLZ and a
 * 64-bit shift per step is slow there). Defined in euler_fx.c, its one user, out of line:
 * static inline here, gcc copied it into its three callers (euler_fx.o 540 bytes larger on
 * Cortex-M0+). */
unsigned qo_fx_bits_above_30_u64(uint64_t v);

/* The unit quaternion of a rotation vector rv (Q3.28 radians, |rv| < 16): the kernel of
 * qo_quat_exp_q30 (quat_fx.c) and of qo_rotvec_to_quat_q30 (convert_fx.c), which calls it, so
 * the quaternion kernel depends on nothing above it. Contract: qo_rotvec_to_quat_q30. */
qo_status qo_fx_quat_from_rotvec(qo_vec3_q28 rv, qo_quat_q30 *out);

#endif /* QORIENT_FX_INTERNAL_H */
