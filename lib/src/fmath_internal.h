/*
 * lib/src/fmath_internal.h - kernels of lib/src/fmath.c shared inside the float core only
 * (not API: no install, no stability promise).
 */
#ifndef QORIENT_FMATH_INTERNAL_H
#define QORIENT_FMATH_INTERNAL_H

/* 1 where qo_fm_atan2x4_f32 computes four lanes in the time of about two scalar calls (SSE2),
 * so a caller gains nothing by asking for fewer; 0 where it is a loop over the lanes. */
#if defined(__SSE2__) && !defined(QO_NO_SIMD)
#define QO_FM_ATAN2X4_WIDE 1
#else
#define QO_FM_ATAN2X4_WIDE 0
#endif

#if QO_FM_ATAN2X4_WIDE
#include <emmintrin.h>   /* a compiler header, not an OS one */
#else
#include <math.h>
#endif

/* sqrtf(x) for x >= 0 (or NaN): sqrtss itself on SSE2, where sqrtf adds libm's errno branch for
 * x < 0 (the same correctly rounded result). With gcc and clang one sqrtss on the register
 * (the intrinsics first build a vector: a broadcast or a move through a general register). */
static inline float qo_fm_sqrt_nonneg(float x)
{
#if QO_FM_ATAN2X4_WIDE && defined(__GNUC__)
    float r;
    __asm__("sqrtss %1, %0" : "=x"(r) : "x"(x));
    return r;
#elif QO_FM_ATAN2X4_WIDE
    return _mm_cvtss_f32(_mm_sqrt_ss(_mm_set1_ps(x)));
#else
    return sqrtf(x);
#endif
}

/* r[i] = qo_fm_atan2_f32(y[i], x[i]) for i = 0 .. n - 1 (n <= 4), bit for bit, every special
 * case included. On SSE2 the four lanes are computed at once (when all eight inputs are finite
 * and non-zero; otherwise lane by lane), so the caller passes four valid pairs even when it
 * needs fewer (lanes n .. 3 are then computed and may be written); elsewhere one call per
 * lane. Used by the Euler decomposition, whose three or four atan2 are independent. */
void qo_fm_atan2x4_f32(const float y[4], const float x[4], float r[4], int n);

#endif /* QORIENT_FMATH_INTERNAL_H */
