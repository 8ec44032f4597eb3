/*
 * qorient/fmath.h - float32 transcendental kernels of the float core (the twin of fxmath.h).
 *
 * Why: the float core used to call libm's sinf, cosf, atan2f, expf and logf, whose results
 * differ by an ulp between C libraries (glibc 2.36 vs 2.41, newlib, musl), so the same input
 * gave different bits on different targets. These kernels use only float +, -, *, /, sqrtf,
 * integer operations and conversions, all exactly specified by IEEE 754 and C99; built with
 * -ffp-contract=off (no fused multiply-add), every target with IEEE single precision in
 * round-to-nearest and without flush-to-zero gives bit-identical results.
 *
 * Index:
 *   qo_fm_sincos_f32   sin and cos of one angle (any finite float, exact range reduction)
 *   qo_fm_sin_f32      sin
 *   qo_fm_cos_f32      cos
 *   qo_fm_atan2_f32    atan2(y, x) in [-pi, pi], every C99 Annex F special case
 *   qo_fm_asin_f32     asin in [-pi/2, pi/2]
 *   qo_fm_acos_f32     acos in [0, pi]
 *   qo_fm_exp_f32      e^x
 *   qo_fm_log_f32      natural logarithm
 *
 * Units: angles in radians. Every function is pure (no state, no tables in RAM, no errno, no
 * floating-point environment access) and total: NaN in gives NaN out, no input is UB.
 *
 * Methods and error bounds. "ulp" = units in the last place of the correctly rounded float
 * result; every bound is checked by tests/core/test_math.c against double-precision libm over
 * dense sweeps of the float domain plus the edges (+-0, subnormals, +-Inf, NaN, FLT_MAX, the
 * floats nearest multiples of pi/2).
 *   sincos  range reduction x - k pi/2 EXACT for every float: x * 2/pi in integers with a
 *           224-bit table of 2/pi (Payne-Hanek; 3 32x32->64 products), the remainder carried
 *           as a float pair (|x| < 5pi/4: one exact k pi/2 step with a three-part pi/2);
 *           Taylor polynomials on [-pi/4, pi/4] (sin to r^9, cos to r^10: truncation
 *           below 0.04 ulp), r^2 and the 1 - r^2/2 step with their rounding errors
 *           recovered.  bound 1 ulp.
 *   atan2   octant folding; for min/max > tan(pi/8) the argument (n - d)/(n + d) straight
 *           from the inputs (no rounded quotient first); the offset (0, pi/4 ... pi) as a
 *           two-float constant added last, so the result is rounded once at its own size;
 *           u + u^3 P(u^2) on [-tan(pi/8), tan(pi/8)], P of degree 4
 *           (tools/fmath-fit-atan.c); the rounding errors of u = n/d (or (n-d)/(n+d)) are
 *           computed exactly (Dekker) and added as du/(1 + u^2).  bound 1.5 ulp.
 *   asin    atan2(x, sqrt((1 - x)(1 + x))); acos: atan2(sqrt((1 - x)(1 + x)), x): 1 - x is
 *           exact near 1, so +-1 and their neighbourhood keep full accuracy.  bound 2 ulp.
 *           |x| > 1 gives NaN.
 *   exp     x = k ln2 + r + rlo with a two-part ln 2 (the rounding of r kept, as is that of
 *           1 + r), Taylor to r^8 on |r| <= ln2/2, scaled
 *           by 2^k (two steps for subnormal results).  bound 1 ulp (normal results; subnormal
 *           ones within 2^-149).
 *           Overflows to +Inf above 88.7228, 0 below -103.98.
 *   log     exponent and mantissa split (subnormals scaled first), mantissa in
 *           [sqrt(1/2), sqrt(2)), degree-10 polynomial (Cephes logf), a two-part ln 2; the
 *           roundings of f - f^2/2 and of e ln 2 + that are recovered exactly.
 *           bound 1 ulp.
 *           log(+-0) = -Inf, log(x < 0) = NaN, log(+Inf) = +Inf.
 * The bounds above are the ones the tests enforce; the measured worst cases are printed by
 * `build/tests/test_math`.
 */
#ifndef QORIENT_FMATH_H
#define QORIENT_FMATH_H

#ifdef __cplusplus
extern "C" {
#endif

/* sin and cos of the same angle. */
typedef struct qo_fm_sincos_f32_t { float s, c; } qo_fm_sincos_f32_t;

/* sin(x) and cos(x), x in radians, any finite float (reduced exactly mod pi/2).
 * NaN or +-Inf gives NaN in both. sin(-0) = -0. */
qo_fm_sincos_f32_t qo_fm_sincos_f32(float x);

/* sin(x), x in radians; as qo_fm_sincos_f32. */
float qo_fm_sin_f32(float x);

/* cos(x), x in radians; as qo_fm_sincos_f32. */
float qo_fm_cos_f32(float x);

/* The angle in [-pi, pi] of the point (x, y), as C99 atan2f including every special case
 * of Annex F (signed zeros: atan2(+-0, -0) = +-pi, atan2(+-0, +0) = +-0; infinities:
 * atan2(+-Inf, -Inf) = +-3pi/4 ...). NaN in either gives NaN. */
float qo_fm_atan2_f32(float y, float x);

/* asin(x) in [-pi/2, pi/2] for x in [-1, 1]; NaN outside (and for NaN). asin(-0) = -0. */
float qo_fm_asin_f32(float x);

/* acos(x) in [0, pi] for x in [-1, 1]; NaN outside (and for NaN). */
float qo_fm_acos_f32(float x);

/* e^x. +Inf for x > 88.7228 (and x = +Inf), +0 for x < -103.98 (and x = -Inf), NaN for NaN. */
float qo_fm_exp_f32(float x);

/* Natural logarithm ln(x) for x > 0 (subnormals included). -Inf for +-0, NaN for x < 0 and
 * NaN, +Inf for +Inf. */
float qo_fm_log_f32(float x);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_FMATH_H */
