/* parity float32 (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   quat.identity        qo_quat_identity_f32
 *   quat.conj            qo_quat_conj_f32
 *   quat.dot             qo_quat_dot_f32
 *   quat.norm            qo_quat_norm_f32
 *   quat.normalize       qo_quat_normalize_f32
 *   quat.normalize       qo_quat_normalize_full_f32 (its out-of-line path: tiny, huge, non-finite)
 *   quat.normalize_fast  - the float32 normalize is already one square root and a multiply
 *   quat.canonical       qo_quat_canonical_f32
 *   quat.inverse         qo_quat_inverse_f32
 *   quat.mul             qo_quat_mul_f32
 *   quat.mul_checked     - float32 overflow gives Inf, which qo_quat_is_finite_f32 reports
 *   quat.rotate          qo_quat_rotate_f32
 *   quat.angle_between   qo_quat_angle_between_f32
 *   quat.exp             qo_quat_exp_f32
 *   quat.log             qo_quat_log_f32
 *   quat.integrate       qo_quat_integrate_f32
 *   quat.is_finite       qo_quat_is_finite_f32
 */
/*
 * qorient/quat.h - quaternion algebra, float32.
 *
 * Conventions: see qorient/types.h (scalar-first, Hamilton, active, right-handed).
 *
 * Index:
 *   qo_quat_identity_f32        (1, 0, 0, 0)
 *   qo_quat_mul_f32             Hamilton product a*b (apply b first, then a)
 *   qo_quat_conj_f32            conjugate (w, -x, -y, -z)
 *   qo_quat_dot_f32             4-D dot product
 *   qo_quat_norm_f32            Euclidean length, overflow-safe
 *   qo_quat_normalize_f32       unit length; zero / non-finite input -> identity + status
 *   qo_quat_inverse_f32         q^-1 = conj(q) / |q|^2; zero / non-finite -> identity + status
 *   qo_quat_canonical_f32       the sign with w >= 0 (ties broken by the first non-zero of x, y, z)
 *   qo_quat_rotate_f32          rotate a vector by a unit quaternion: q v q*
 *   qo_quat_angle_between_f32   rotation angle from a to b, in [0, pi]
 *   qo_quat_exp_f32             exp of a pure quaternion (0, v), v in radians
 *   qo_quat_log_f32             log of a quaternion, vector part in radians
 *   qo_quat_integrate_f32       advance an orientation by a body-frame angular velocity over dt
 *   qo_quat_is_finite_f32       all four components finite
 *   qo_quat_normalize_full_f32  the out-of-line complete path of qo_quat_normalize_f32
 *
 * Inline functions: identity, mul, conj, dot, rotate, is_finite, canonical and normalize's fast
 * path are `static inline` here (a call would cost more than the arithmetic: mul is 16 multiplies).
 * libqorient also exports each of them under the same name, built from these same bodies,
 * so code linked against an older header keeps working. The inline copies compute exactly
 * the library's bits when the caller's compiler does not fuse a*b+c into one rounding:
 * clang honours the #pragma STDC FP_CONTRACT OFF below; gcc ignores it, and contracts by
 * default in its GNU modes (-std=gnu99/gnu11) on FMA targets (aarch64, x86-64 with -mfma):
 * there compile with -ffp-contract=off (or -std=c99/c11) for bit-identical results.
 * On SSE2 targets (x86-64) mul, rotate, normalize, qo_mat3_from_quat_f32 and
 * qo_mat3_to_quat_trusted_f32 have 4-wide bodies with the scalar code's per-component
 * rounding order, so the bits are the same (see QO_QUAT_SIMD_SSE2 below; tests/core/test_quat.c
 * and test_simd_bodies.c compare both bodies on random inputs).
 */
#ifndef QORIENT_QUAT_H
#define QORIENT_QUAT_H

#include <math.h>
#include <stddef.h>

#include "qorient/status.h"
#include "qorient/types.h"

/* QO_QUAT_SIMD_SSE2: the inline bodies use SSE2 4-wide arithmetic (a compiler header, not an OS one)
 * where the compiler targets it; define QO_NO_SIMD to get the scalar bodies everywhere. Both
 * paths round every component in the same order, so the results are bit-identical (NaN
 * results stay NaN; IEEE 754 leaves the sign and payload of a NaN result unspecified). */
#if defined(__SSE2__) && !defined(QO_NO_SIMD)
#define QO_QUAT_SIMD_SSE2 1
#include <emmintrin.h>
/* Lanes of v picked by the constant imm (_MM_SHUFFLE order) with pshufd, which unlike shufps
 * leaves its source intact (no register copies); a macro because imm must be a constant. */
#define QO_QUAT_SIMD_SHUFFLE_PS(v, imm) _mm_castsi128_ps(_mm_shuffle_epi32(_mm_castps_si128(v), (imm)))
#else
#define QO_QUAT_SIMD_SSE2 0
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Euclidean norm sqrt(w^2+x^2+y^2+z^2), computed with scaling so that components up to
 * FLT_MAX do not overflow and tiny ones do not underflow to 0. NaN in -> NaN out. */
float qo_quat_norm_f32(qo_quat_f32 q);

/* Multiplicative inverse conj(q)/|q|^2 (for a unit quaternion: the conjugate), computed as
 * (conj(q)/|q|)/|q| so |q|^2 itself may overflow or underflow float (|q| = 1e30 is fine).
 * Returns QO_OK, QO_E_NULL, QO_E_NONFINITE, or QO_E_DEGENERATE for |q| == 0, |q| overflowing
 * float (components near FLT_MAX) or 1/|q| overflowing (|q| below ~3e-39);
 * *out is the identity on error. */
qo_status qo_quat_inverse_f32(qo_quat_f32 q, qo_quat_f32 *out);

/* Angle in radians, in [0, pi], of the rotation that takes orientation a to orientation b
 * (both unit). Computed as 2*atan2(|vec(conj(a)*b)|, |scalar(conj(a)*b)|), accurate for
 * tiny angles (no acos), and the same for b and -b. */
float qo_quat_angle_between_f32(qo_quat_f32 a, qo_quat_f32 b);

/* exp of the pure quaternion (0, v), v in radians: (cos|v|, sin|v| v/|v|), the unit
 * rotation by 2|v| about v (so v = theta/2 * axis gives the rotation by theta). v = 0 gives the
 * identity; a Taylor series for sin|v|/|v| keeps a tiny v exact, (1, v). The shape of
 * qo_quat_exp_q30: a rotation has no use for a scalar part (it would scale by e^w), so both
 * cores take the vector.
 * Returns QO_OK; QO_E_NULL (out NULL); QO_E_NONFINITE (a NaN/Inf component, or |v|
 * overflowing float). *out is the identity on error. */
qo_status qo_quat_exp_f32(qo_vec3_f32 v, qo_quat_f32 *out);

/* Vector part of log(q / |q|): atan2(|u|, w) u/|u|, u = (x, y, z), in radians: for a unit
 * quaternion theta/2 * axis with theta in [0, 2pi] (canonicalise q first for the short
 * rotation: then |result| <= pi/2). The scalar part ln|q| is not returned (q is taken as a
 * rotation; measure it with qo_quat_norm_f32), the shape of qo_quat_log_q30. Any non-zero
 * finite q, components up to FLT_MAX and subnormal vector parts included. For u == 0:
 * (0, 0, 0) if w > 0, and (pi, 0, 0) if w < 0 (a rotation by 2pi about an undefined axis - a
 * documented choice of axis x).
 * Returns QO_OK; QO_E_NULL (out NULL); QO_E_NONFINITE (NaN/Inf component); QO_E_DEGENERATE for
 * q == 0. *out is (0, 0, 0) on error. */
qo_status qo_quat_log_f32(qo_quat_f32 q, qo_vec3_f32 *out);

/* Integrates a constant BODY-frame angular velocity omega (rad/s, about the body's own axes)
 * over dt seconds: out = q * exp((0, omega*dt/2)), then normalised. This is exact for constant
 * omega (no first-order drift). For a WORLD-frame omega pass conj(q) omega q (or use
 * exp(...) * q). dt may be negative (integrates backwards).
 * Returns QO_OK, QO_E_NULL, QO_E_NONFINITE (q, omega or dt not finite), QO_E_DEGENERATE
 * (q is zero); *out is q normalised (or identity if that fails) on error. */
qo_status qo_quat_integrate_f32(qo_quat_f32 q, qo_vec3_f32 omega, float dt, qo_quat_f32 *out);

/* qo_quat_normalize_f32's complete path, out of line: the same contract and, for every
 * input, the same result (including the fast-path cases). */
qo_status qo_quat_normalize_full_f32(qo_quat_f32 q, qo_quat_f32 *out);

/* ---- inline functions (see the file comment) ------------------------------------------- */
#if defined(QORIENT_QUAT_EXTERN_DEFS)
/* lib/src/quat.c: the same bodies once more as the library's external definitions. */
#define QO_QUAT_INLINE
qo_quat_f32 qo_quat_identity_f32(void);
qo_quat_f32 qo_quat_mul_f32(qo_quat_f32 a, qo_quat_f32 b);
qo_quat_f32 qo_quat_conj_f32(qo_quat_f32 q);
float qo_quat_dot_f32(qo_quat_f32 a, qo_quat_f32 b);
int qo_quat_is_finite_f32(qo_quat_f32 q);
qo_vec3_f32 qo_quat_rotate_f32(qo_quat_f32 q, qo_vec3_f32 v);
qo_status qo_quat_normalize_f32(qo_quat_f32 q, qo_quat_f32 *out);
qo_quat_f32 qo_quat_canonical_f32(qo_quat_f32 q);
#else
#define QO_QUAT_INLINE static inline
#endif

#ifdef __clang__
#pragma STDC FP_CONTRACT OFF
#endif

/* qo_quat_internal_*: helpers of the inline bodies (here and in convert.h) and of the SSE2
 * paths of convert.c and interp.c. Not API: not in the index or the parity table, may change
 * or vanish in any release; call the documented functions instead. The marker is a word, not
 * a double underscore, because these headers are also read by C++ (which reserves "__"). */
#if QO_QUAT_SIMD_SSE2
/* Lane 0 of the result is ((v0 + v1) + v2) + v3, the left-to-right order of the scalar sums
 * (a pairwise horizontal add would round differently). Internal, not API (see above). */
static inline __m128 qo_quat_internal_sum4_ss(__m128 v)
{
    __m128 s = _mm_add_ss(QO_QUAT_SIMD_SHUFFLE_PS(v, 0x55), v);   /* x + w: addition commutes */
    s = _mm_add_ss(s, QO_QUAT_SIMD_SHUFFLE_PS(v, 0xaa));
    return _mm_add_ss(s, QO_QUAT_SIMD_SHUFFLE_PS(v, 0xff));
}
#endif

#if QO_QUAT_SIMD_SSE2
/* u x b in lanes (x, y, z) as u.yzx * b.zxy - u.zxy * b.yzx, given u's two rotations.
 * Internal, not API (see above). */
static inline __m128 qo_quat_internal_cross_ps(__m128 uyzx, __m128 uzxy, __m128 b)
{
    return _mm_sub_ps(_mm_mul_ps(uyzx, QO_QUAT_SIMD_SHUFFLE_PS(b, _MM_SHUFFLE(3, 1, 0, 2))),
                      _mm_mul_ps(uzxy, QO_QUAT_SIMD_SHUFFLE_PS(b, _MM_SHUFFLE(3, 0, 2, 1))));
}
#endif

#if QO_QUAT_SIMD_SSE2
/* The inline fast range of normalize and to_mat3, from r = sqrt(n) and inv ~ 1/r (1/r in
 * to_mat3, r/n in normalize) in lane 0 (n = |q|^2): 1 when both are >= 1e-15, i.e. n in
 * ~[1e-30, 1e30] - q finite, non-zero and needing no range scaling. One minss and one
 * comparison; a NaN n gives a NaN min, which fails. The scalar bodies test
 * r >= 1e-15f && inv >= 1e-15f: the same predicate. Internal, not API (see above). */
static inline int qo_quat_internal_fast_range_ss(__m128 r, __m128 inv)
{
    return _mm_comige_ss(_mm_min_ss(r, inv), _mm_set_ss(1e-15f));
}

/* (ww + yy) + (xx + zz) in every lane, from q in lanes (w, x, y, z): the squared norm of
 * qo_quat_normalize_f32 as qo_quat_internal_sumsq_f32 computes it. Two swaps and two adds;
 * each lane adds the same two pairs (in the other order, which addition does not see), so the
 * sum comes out broadcast and the square root, reciprocal and scaling that follow are 4-wide
 * with no shuffle. Internal, not API (see above). */
static inline __m128 qo_quat_internal_sumsq_ps(__m128 q4)
{
    const __m128 sq = _mm_mul_ps(q4, q4);
    const __m128 h = _mm_add_ps(sq, QO_QUAT_SIMD_SHUFFLE_PS(sq, _MM_SHUFFLE(1, 0, 3, 2)));
    return _mm_add_ps(h, QO_QUAT_SIMD_SHUFFLE_PS(h, _MM_SHUFFLE(2, 3, 0, 1)));
}

/* qo_quat_normalize_f32's fast path in lanes, its one home (normalize and slerp's result):
 * n = (ww + yy) + (xx + zz) broadcast, r = sqrt(n), inv = r / n, *u = q * inv. Returns
 * qo_quat_internal_fast_range_ss(r, inv): 1 when *u is normalize's answer; 0 when q needs its
 * full path (*u is then meaningless). Internal, not API (see above). */
static inline int qo_quat_internal_normalize_ps(__m128 q4, __m128 *u)
{
    const __m128 n = qo_quat_internal_sumsq_ps(q4), r = _mm_sqrt_ps(n), inv = _mm_div_ps(r, n);
    *u = _mm_mul_ps(q4, inv);
    return qo_quat_internal_fast_range_ss(r, inv);
}

/* The quaternion in the lanes (w, x, y, z) of v, lane by lane, for the out-of-line call of a
 * fast path's other branch: passing the caller's q instead makes gcc store q to the stack
 * on the fast path too. Internal, not API (see above). */
static inline qo_quat_f32 qo_quat_internal_from_ps(__m128 v)
{
    qo_quat_f32 q;
    q.w = _mm_cvtss_f32(v);
    q.x = _mm_cvtss_f32(QO_QUAT_SIMD_SHUFFLE_PS(v, 0x55));
    q.y = _mm_cvtss_f32(QO_QUAT_SIMD_SHUFFLE_PS(v, 0xaa));
    q.z = _mm_cvtss_f32(QO_QUAT_SIMD_SHUFFLE_PS(v, 0xff));
    return q;
}
#endif

/* (ww + yy) + (xx + zz): the squared norm in qo_quat_normalize_f32's order (pairwise, as its
 * SSE2 body adds). Internal, not API (see above). */
static inline float qo_quat_internal_sumsq_f32(qo_quat_f32 q)
{
    return (q.w * q.w + q.y * q.y) + (q.x * q.x + q.z * q.z);
}

/* The identity rotation (1, 0, 0, 0). */
QO_QUAT_INLINE qo_quat_f32 qo_quat_identity_f32(void)
{
    qo_quat_f32 q = { 1.0f, 0.0f, 0.0f, 0.0f };
    return q;
}

/* Hamilton product a*b. As rotations, a*b applies b first and then a (active, v' = a(b v b*)a*).
 * Not commutative. Norms multiply: |a*b| = |a||b|. */
QO_QUAT_INLINE qo_quat_f32 qo_quat_mul_f32(qo_quat_f32 a, qo_quat_f32 b)
{
    qo_quat_f32 r;
#if QO_QUAT_SIMD_SSE2
    /* Eigen's grouping, (m1 - m2) + (s1 + s2) per lane with the w lane's second pair negated
     * (x - y == x + (-y) exactly), so each lane rounds as the scalar expression below, in 7
     * shuffles, 4 multiplies, 3 adds and 1 sign flip. m1 = aw * b rather than Eigen's a * bw:
     * measured, that choice leaves every worst error of the accuracy figures unchanged (a * bw
     * raised squad's). The loads read the four floats of a quaternion (the struct has no
     * padding). Lanes are (w, x, y, z). */
    const __m128 a4 = _mm_loadu_ps(&a.w), b4 = _mm_loadu_ps(&b.w);
    const __m128 sw = _mm_castsi128_ps(_mm_set_epi32(0, 0, 0, INT32_MIN));
    const __m128 m1 = _mm_mul_ps(QO_QUAT_SIMD_SHUFFLE_PS(a4, 0x00), b4);           /* aw * b */
    const __m128 m2 = _mm_mul_ps(QO_QUAT_SIMD_SHUFFLE_PS(a4, _MM_SHUFFLE(2, 1, 3, 1)),  /* x z x y */
                                 QO_QUAT_SIMD_SHUFFLE_PS(b4, _MM_SHUFFLE(1, 3, 2, 1))); /* x y z x */
    const __m128 s1 = _mm_mul_ps(QO_QUAT_SIMD_SHUFFLE_PS(a4, _MM_SHUFFLE(1, 3, 2, 3)),  /* z y z x */
                                 QO_QUAT_SIMD_SHUFFLE_PS(b4, _MM_SHUFFLE(2, 1, 3, 3))); /* z z x y */
    const __m128 s2 = _mm_mul_ps(QO_QUAT_SIMD_SHUFFLE_PS(a4, _MM_SHUFFLE(3, 2, 1, 2)),  /* y x y z */
                                 QO_QUAT_SIMD_SHUFFLE_PS(b4, _MM_SHUFFLE(0, 0, 0, 2))); /* y w w w */
    _mm_storeu_ps(&r.w, _mm_add_ps(_mm_sub_ps(m1, m2), _mm_xor_ps(_mm_add_ps(s1, s2), sw)));
#else
    r.w = (a.w * b.w - a.x * b.x) - (a.z * b.z + a.y * b.y);
    r.x = (a.w * b.x - a.z * b.y) + (a.y * b.z + a.x * b.w);
    r.y = (a.w * b.y - a.x * b.z) + (a.z * b.x + a.y * b.w);
    r.z = (a.w * b.z - a.y * b.x) + (a.x * b.y + a.z * b.w);
#endif
    return r;
}

/* Conjugate (w, -x, -y, -z): the inverse rotation for a unit quaternion. */
QO_QUAT_INLINE qo_quat_f32 qo_quat_conj_f32(qo_quat_f32 q)
{
    qo_quat_f32 r;
    r.w = q.w; r.x = -q.x; r.y = -q.y; r.z = -q.z;
    return r;
}

/* Dot product a.w*b.w + a.x*b.x + a.y*b.y + a.z*b.z. For unit quaternions it is cos(theta/2)
 * of the rotation between them, with a sign that says which of +-b is nearer a. */
QO_QUAT_INLINE float qo_quat_dot_f32(qo_quat_f32 a, qo_quat_f32 b)
{
    return a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
}

/* 1 if all four components are finite, else 0. */
QO_QUAT_INLINE int qo_quat_is_finite_f32(qo_quat_f32 q)
{
    return isfinite(q.w) && isfinite(q.x) && isfinite(q.y) && isfinite(q.z);
}

/* Rotates v by the unit quaternion q: v' = q (0,v) q*, evaluated as
 * v + 2w(u x v) + 2 u x (u x v) with u = (x, y, z) (no normalisation of q: pass a unit
 * quaternion; for a non-unit q the result is neither q v q* nor a rotation of v - normalise
 * first). 15 multiplies, 15 adds: t = 2 u x v; v' = v + w t + u x t. */
QO_QUAT_INLINE qo_vec3_f32 qo_quat_rotate_f32(qo_quat_f32 q, qo_vec3_f32 v)
{
#if QO_QUAT_SIMD_SSE2
    /* Lanes (x, y, z, unused): both cross products as a.yzx * b.zxy - a.zxy * b.yzx, then
     * (v + w t) + u x t, each lane in the scalar order; 2 * (...) is exact. v and the result
     * are moved as 8 + 4 bytes (never past the vector's 12). */
    const __m128 q4 = _mm_loadu_ps(&q.w);
    const __m64 *vxy = (const __m64 *)(const void *)&v.x;
    const __m128 v4 = _mm_movelh_ps(_mm_loadl_pi(_mm_setzero_ps(), vxy), _mm_load_ss(&v.z));
    const __m128 uyzx = QO_QUAT_SIMD_SHUFFLE_PS(q4, _MM_SHUFFLE(0, 1, 3, 2));
    const __m128 uzxy = QO_QUAT_SIMD_SHUFFLE_PS(q4, _MM_SHUFFLE(0, 2, 1, 3));
    __m128 t = qo_quat_internal_cross_ps(uyzx, uzxy, v4), r4;
    qo_vec3_f32 r;
    t = _mm_add_ps(t, t);
    r4 = _mm_add_ps(v4, _mm_mul_ps(QO_QUAT_SIMD_SHUFFLE_PS(q4, 0x00), t));
    r4 = _mm_add_ps(r4, qo_quat_internal_cross_ps(uyzx, uzxy, t));
    _mm_storel_pi((__m64 *)(void *)&r.x, r4);
    _mm_store_ss(&r.z, _mm_movehl_ps(r4, r4));
    return r;
#else
    float tx = 2.0f * (q.y * v.z - q.z * v.y);
    float ty = 2.0f * (q.z * v.x - q.x * v.z);
    float tz = 2.0f * (q.x * v.y - q.y * v.x);
    qo_vec3_f32 r;
    r.x = v.x + q.w * tx + (q.y * tz - q.z * ty);
    r.y = v.y + q.w * ty + (q.z * tx - q.x * tz);
    r.z = v.z + q.w * tz + (q.x * ty - q.y * tx);
    return r;
#endif
}

/* Unit quaternion q/|q|.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_NONFINITE if a component is NaN or Inf;
 * QO_E_DEGENERATE if |q| == 0 (also for subnormal-only inputs whose norm underflows).
 * On any error *out is the identity. The sign of q is kept.
 * Each component is q_i * inv with n = (ww + yy) + (xx + zz), r = sqrt(n) and inv = r / n
 * (= 1/|q|, with no constant 1 to load): one divide and four multiplies (a divide costs
 * several multiplies on a Cortex-M4F and far more in soft float).
 * Inline fast path: r and inv both >= 1e-15 (n in ~[1e-30, 1e30]) means every component is
 * finite and no range scaling is needed, so q * inv is the whole answer (bit for bit what the
 * full path computes); anything else goes to qo_quat_normalize_full_f32. */
QO_QUAT_INLINE qo_status qo_quat_normalize_f32(qo_quat_f32 q, qo_quat_f32 *out)
{
#if QO_QUAT_SIMD_SSE2
    /* The same operations lane for lane, 4-wide on the broadcast sum: sqrtps (correctly
     * rounded like sqrtf, and without libm's errno branch), r / n, the range test on lane 0 as
     * the scalar body's, the scaling. */
    const __m128 q4 = _mm_loadu_ps(&q.w);
    __m128 u;
    if (out != NULL && qo_quat_internal_normalize_ps(q4, &u)) {
        _mm_storeu_ps(&out->w, u);
        return QO_OK;
    }
    return qo_quat_normalize_full_f32(qo_quat_internal_from_ps(q4), out);
#else
    float n = qo_quat_internal_sumsq_f32(q), r = sqrtf(n), inv = r / n;
    if (out != NULL && r >= 1e-15f && inv >= 1e-15f) {
        out->w = q.w * inv; out->x = q.x * inv; out->y = q.y * inv; out->z = q.z * inv;
        return QO_OK;
    }
    return qo_quat_normalize_full_f32(q, out);
#endif
}

/* The representative of the same rotation with w >= 0; when w == 0 the first non-zero of
 * x, y, z is made positive. Matches scipy's as_quat(canonical=True). -0.0 components become
 * +0.0, so canonical quaternions compare equal bitwise. */
QO_QUAT_INLINE qo_quat_f32 qo_quat_canonical_f32(qo_quat_f32 q)
{
    int flip;
    if (q.w != 0.0f) flip = q.w < 0.0f;
    else if (q.x != 0.0f) flip = q.x < 0.0f;
    else if (q.y != 0.0f) flip = q.y < 0.0f;
    else flip = q.z < 0.0f;
    if (flip) { q.w = -q.w; q.x = -q.x; q.y = -q.y; q.z = -q.z; }
    q.w += 0.0f; q.x += 0.0f; q.y += 0.0f; q.z += 0.0f;
    return q;
}

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_QUAT_H */
