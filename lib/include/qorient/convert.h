/* parity float32 (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   convert.axis_angle_to_quat    qo_axis_angle_to_quat_f32
 *   convert.axis_angle_from_quat  qo_axis_angle_from_quat_f32
 *   convert.rotvec_to_quat        qo_rotvec_to_quat_f32
 *   convert.rotvec_from_quat      qo_rotvec_from_quat_f32
 *   convert.mat3_from_quat        qo_mat3_from_quat_f32
 *   convert.mat3_from_quat        qo_mat3_from_quat_full_f32 (its out-of-line path)
 *   convert.mat3_to_quat          qo_mat3_to_quat_f32
 *   convert.mat3_to_quat          qo_mat3_to_quat_full_f32 (its out-of-line path)
 *   convert.mat3_to_quat_trusted  qo_mat3_to_quat_trusted_f32
 *   convert.mat3_to_quat_trusted  qo_mat3_to_quat_trusted_full_f32 (its out-of-line path)
 *   convert.mat3_to_quat_ortho    qo_mat3_to_quat_ortho_f32
 *   mat3.identity                 qo_mat3_identity_f32
 *   mat3.transpose                qo_mat3_transpose_f32
 *   mat3.mul                      qo_mat3_mul_f32
 *   mat3.mul_vec3                 qo_mat3_mul_vec3_f32
 *   mat3.det                      qo_mat3_det_f32
 *   mat3.orthonormalize           qo_mat3_orthonormalize_f32
 */
/*
 * qorient/convert.h - float32 conversions between rotation representations, and the small
 * 3x3 matrix helpers they need.
 *
 * Conventions: see qorient/types.h (quaternions scalar-first, Hamilton, active rotations,
 * right-handed frames; matrices row-major m[row][col] acting on column vectors v' = M v).
 * For every q, qo_mat3_from_quat_f32(q) rotates a vector exactly as qo_quat_rotate_f32(q, .).
 * Angles are radians.
 *
 * Index:
 *   QO_MAT3_ROTATION_TOL_F32     tolerance of the "is this a rotation matrix" test
 *   qo_axis_angle_to_quat_f32    axis (any length) + angle -> unit quaternion
 *   qo_axis_angle_from_quat_f32  quaternion -> unit axis + angle in [0, pi]
 *   qo_rotvec_to_quat_f32        rotation vector (axis * angle) -> unit quaternion
 *   qo_rotvec_from_quat_f32      quaternion -> rotation vector, |rv| in [0, pi]
 *   qo_mat3_from_quat_f32        quaternion -> rotation matrix (static inline fast path)
 *   qo_mat3_from_quat_full_f32   its out-of-line complete path
 *   qo_mat3_to_quat_f32          rotation matrix -> canonical unit quaternion (strict check;
 *                                static inline fast path)
 *   qo_mat3_to_quat_full_f32     its out-of-line complete path
 *   qo_mat3_orthonormalize_f32   nearest rotation matrix (orthogonal polar factor)
 *   qo_mat3_to_quat_ortho_f32    orthonormalise, then convert (for drifted matrices)
 *   qo_mat3_to_quat_trusted_f32  no rotation check (for matrices known to be rotations;
 *                                static inline fast path)
 *   qo_mat3_to_quat_trusted_full_f32  its out-of-line complete path
 *   qo_mat3_mul_vec3_f32         M v
 *   qo_mat3_mul_f32              A B
 *   qo_mat3_transpose_f32        M^T
 *   qo_mat3_identity_f32         I
 *   qo_mat3_det_f32              det M
 *
 * Sign of returned quaternions: qo_mat3_to_quat_f32 / _ortho_f32 return the canonical sign
 * (w >= 0, ties as qo_quat_canonical_f32). qo_axis_angle_to_quat_f32 and
 * qo_rotvec_to_quat_f32 return (cos(angle/2), sin(angle/2) * unit axis) exactly as the
 * formula gives it, so an angle beyond pi gives w < 0 (the same rotation; canonicalise with
 * qo_quat_canonical_f32 if you need the short representative).
 */
#ifndef QORIENT_CONVERT_H
#define QORIENT_CONVERT_H

#include <float.h>
#include <math.h>
#include <stddef.h>

#include "qorient/status.h"
#include "qorient/types.h"
#include "qorient/quat.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * A matrix is accepted as a rotation by qo_mat3_to_quat_f32 when every entry of M^T M - I
 * is at most this in magnitude and det M > 0. 1e-4 is ~800 float32 ulps of 1: it accepts a
 * rotation matrix that went through a few dozen float32 products (each adds ~1e-7 of
 * non-orthogonality) or was printed with 5-6 significant digits, and still rejects anything
 * visibly scaled or sheared (a 1e-4 error in M^T M is a ~5e-5 scale or shear). Matrices
 * further off must be repaired explicitly with qo_mat3_orthonormalize_f32 /
 * qo_mat3_to_quat_ortho_f32 - we never silently guess.
 */
#define QO_MAT3_ROTATION_TOL_F32 1e-4f

/*
 * Unit quaternion of the rotation by `angle` radians about `axis` (right-hand rule), in the
 * frame of axis: q = (cos(angle/2), sin(angle/2) * axis/|axis|). axis need not be unit; any
 * finite non-zero length works (the length is computed overflow/underflow-safe, so components
 * near FLT_MAX or subnormal are fine). angle may be any finite value (negative turns the other
 * way; |angle| > pi gives w < 0, see the header note on signs).
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_NONFINITE if a component of axis or angle is
 * NaN/Inf; QO_E_DEGENERATE if axis is (0,0,0) (whatever the angle). *out is the identity on
 * every error.
 */
qo_status qo_axis_angle_to_quat_f32(qo_vec3_f32 axis, float angle, qo_quat_f32 *out);

/*
 * Axis and angle of the rotation q (q need not be unit: it is normalised first). The short
 * way is returned: angle in [0, pi] (q and -q give the same answer; the upper end is the
 * float nearest pi, 3.14159274f, a hair above pi), *axis a unit vector.
 * For the identity (and any q with zero vector part) the axis is undefined: we return
 * axis (1, 0, 0) and angle 0. At exactly pi the axis sign follows qo_quat_canonical_f32
 * (its first non-zero component is positive).
 * Returns QO_OK; QO_E_NULL if axis or angle is NULL (the other is still written if non-NULL);
 * QO_E_NONFINITE for a NaN/Inf component; QO_E_DEGENERATE for q == 0. On every error
 * *axis = (1, 0, 0) and *angle = 0.
 */
qo_status qo_axis_angle_from_quat_f32(qo_quat_f32 q, qo_vec3_f32 *axis, float *angle);

/*
 * Unit quaternion of the rotation vector rv (axis * angle, radians: |rv| is the angle, its
 * direction the axis). q = (cos(|rv|/2), sin(|rv|/2)/|rv| * rv). Near zero the coefficients
 * use a Taylor series, so a tiny rv gives exactly (1, rv/2) - no digits lost, no 0/0 - and
 * rv = 0 gives the identity with QO_OK. |rv| > pi gives w < 0 (see the header note on signs).
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_NONFINITE for a NaN/Inf component;
 * QO_E_RANGE if |rv| overflows float (components near FLT_MAX; such an angle has no
 * meaningful float32 rotation). *out is the identity on every error.
 */
qo_status qo_rotvec_to_quat_f32(qo_vec3_f32 rv, qo_quat_f32 *out);

/*
 * Rotation vector (unit axis * angle, radians) of q. q is normalised, then the canonical sign
 * (w >= 0) is taken, so |*out| is in [0, pi]. The angle is 2*atan2(|v|, w): accurate at 0
 * (a tiny rotation gives 2*v/w to full relative precision, also for subnormal v) and at pi
 * (no acos / asin blow-up). At exactly pi the sign follows qo_quat_canonical_f32.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_NONFINITE for a NaN/Inf component;
 * QO_E_DEGENERATE for q == 0. *out is (0, 0, 0) on every error.
 */
qo_status qo_rotvec_from_quat_f32(qo_quat_f32 q, qo_vec3_f32 *out);

/*
 * qo_mat3_from_quat_f32's complete path, out of line (every input; for |q|^2 outside
 * ~[1e-30, 1e30] it normalises with range scaling first). Same contract as qo_mat3_from_quat_f32.
 */
qo_status qo_mat3_from_quat_full_f32(qo_quat_f32 q, qo_mat3_f32 *out);

/*
 * qo_mat3_to_quat_f32's complete path, out of line: the same contract and, for every input, the
 * same result (including the inline fast path's cases).
 */
qo_status qo_mat3_to_quat_full_f32(const qo_mat3_f32 *m, qo_quat_f32 *out);

/*
 * The rotation matrix nearest *m in the Frobenius norm: the orthogonal factor R of the polar
 * decomposition M = R S (S symmetric positive definite). Computed by scaled Newton iteration
 * R <- (g R + R^-T / g) / 2 (Higham), after scaling M by its largest entry so no
 * intermediate overflows; converges in a handful of steps and gives a matrix orthonormal to
 * float32 round-off (max |R^T R - I| within 1e-6). A uniformly scaled rotation gives that
 * rotation back. m and out may point to the same matrix.
 * Accuracy, checked by tests/core/test_convert.c: for a drifted, noisy or uniformly scaled
 * rotation the result is within 1e-6 rad of the exact nearest rotation of the float input
 * (test_orthonormalize). For a strongly stretched M with singular values s1 >= s2 >= s3 the
 * nearest rotation is itself sensitive (it moves by ~|dM|/(s2 + s3)) and the error grows like
 * s1/(s2 + s3): within 5e-7 + 1.2e-7 * s1/(s2 + s3) rad (test_f32_orthonormalize_scaled). The
 * worst measured by bench/accuracy_convert.c: docs/FIGURES.md, accuracy.
 * Returns QO_OK; QO_E_NULL if m or out is NULL; QO_E_NONFINITE for a NaN/Inf entry;
 * QO_E_NOT_ROTATION if det M <= 0 (a reflection, whose nearest orthogonal matrix is not a
 * rotation) or M is numerically rank-deficient (Frobenius condition |M| |M^-1| above 3e3,
 * i.e. smallest/largest singular value below ~5e-4, where float32 cannot find the nearest
 * rotation reliably), or the iteration fails to converge. *out is the identity matrix on
 * every error.
 */
qo_status qo_mat3_orthonormalize_f32(const qo_mat3_f32 *m, qo_mat3_f32 *out);

/*
 * Canonical unit quaternion of the rotation nearest *m: qo_mat3_orthonormalize_f32 followed by
 * qo_mat3_to_quat_f32. Use it when the caller KNOWS the matrix is a drifted or noisy
 * rotation (integrated, filtered, read from a sensor); qo_mat3_to_quat_f32 refuses such
 * matrices instead of guessing.
 * Returns QO_OK, QO_E_NULL, QO_E_NONFINITE, QO_E_NOT_ROTATION (as for
 * qo_mat3_orthonormalize_f32). *out is the identity on every error.
 */
qo_status qo_mat3_to_quat_ortho_f32(const qo_mat3_f32 *m, qo_quat_f32 *out);

/* qo_mat3_to_quat_trusted_f32's complete path, out of line: the same contract and, for every
 * input, the same result (including the inline fast path's cases). */
qo_status qo_mat3_to_quat_trusted_full_f32(const qo_mat3_f32 *m, qo_quat_f32 *out);

/* M v (no checks; NaN propagates). */
qo_vec3_f32 qo_mat3_mul_vec3_f32(const qo_mat3_f32 *m, qo_vec3_f32 v);

/* A B: as rotations, applies B first, then A (same order as qo_quat_mul_f32). */
qo_mat3_f32 qo_mat3_mul_f32(const qo_mat3_f32 *a, const qo_mat3_f32 *b);

/* M^T: the inverse of a rotation matrix. */
qo_mat3_f32 qo_mat3_transpose_f32(const qo_mat3_f32 *m);

/* The identity matrix. */
qo_mat3_f32 qo_mat3_identity_f32(void);

/* Determinant (cofactor expansion along the first row): +1 for a rotation, -1 for a
 * reflection. */
float qo_mat3_det_f32(const qo_mat3_f32 *m);


/* ---- inline functions (as in qorient/quat.h: also exported under the same name; bit-identical
 * to the library when the caller does not contract a*b+c, see quat.h) -------------------- */
#if defined(QORIENT_CONVERT_EXTERN_DEFS)
#define QO_CONVERT_INLINE
qo_status qo_mat3_from_quat_f32(qo_quat_f32 q, qo_mat3_f32 *out);
qo_status qo_mat3_to_quat_f32(const qo_mat3_f32 *m, qo_quat_f32 *out);
qo_status qo_mat3_to_quat_trusted_f32(const qo_mat3_f32 *m, qo_quat_f32 *out);
#else
#define QO_CONVERT_INLINE static inline
#endif

#ifdef __clang__
#pragma STDC FP_CONTRACT OFF
#endif

/*
 * Rotation matrix of q (row-major, v' = M v, the same rotation as qo_quat_rotate_f32).
 * q is normalised first, so any non-zero finite q (and q or -q) gives a proper rotation.
 * Returns QO_OK; QO_E_NULL if out is NULL; QO_E_NONFINITE for a NaN/Inf component;
 * QO_E_DEGENERATE for q == 0. *out is the identity matrix on every error.
 * Inline: |q| and 1/|q| both >= 1e-15 (|q|^2 in ~[1e-30, 1e30]: q finite, non-zero, no scaling
 * needed) is handled here; the rest by qo_mat3_from_quat_full_f32.
 */
QO_CONVERT_INLINE qo_status qo_mat3_from_quat_f32(qo_quat_f32 q, qo_mat3_f32 *out)
{
#if QO_QUAT_SIMD_SSE2
    /* The scalar body below, lane for lane in the same order (see quat.h's QO_QUAT_SIMD_SSE2):
     * d = the diagonal, pl and mi = the s * (a + b) and s * (a - b) off-diagonal terms. */
    const __m128 q4 = _mm_loadu_ps(&q.w);
    const __m128 r = _mm_sqrt_ss(qo_quat_internal_sum4_ss(_mm_mul_ps(q4, q4)));
    const __m128 inv = _mm_div_ss(_mm_set1_ps(1.0f), r);
    __m128 u, uu, s, da, db, d, pr, wr, pl, mi, lo, hi;
    if (out == NULL || !qo_quat_internal_fast_range_ss(r, inv))
        return qo_mat3_from_quat_full_f32(qo_quat_internal_from_ps(q4), out);
    u = _mm_mul_ps(QO_QUAT_SIMD_SHUFFLE_PS(inv, 0x00), q4);                          /* w x y z */
    uu = _mm_mul_ps(u, u);
    /* ((ww + xx) + yy) + zz as in qo_quat_internal_sum4_ss, with the xx and yy lanes taken
     * from the two shuffles the diagonal needs anyway (lane 0: m22's xx + yy) */
    da = QO_QUAT_SIMD_SHUFFLE_PS(uu, _MM_SHUFFLE(2, 0, 1, 1));                     /* xx xx . yy */
    db = QO_QUAT_SIMD_SHUFFLE_PS(uu, _MM_SHUFFLE(3, 0, 3, 2));                     /* yy zz . zz */
    s = _mm_add_ss(_mm_add_ss(_mm_add_ss(uu, da), db), QO_QUAT_SIMD_SHUFFLE_PS(uu, 0xff));
    s = _mm_div_ss(_mm_set_ss(2.0f), s);
    s = _mm_shuffle_ps(s, s, 0);
    /* 1 - sd as 1 + (-sd), the same rounding; the constants leave the unused lane 2 alone,
     * which makes gcc read them from memory instead of building a register copy */
    d = _mm_xor_ps(_mm_mul_ps(_mm_add_ps(da, db), s), _mm_setr_ps(-0.0f, -0.0f, 0.0f, -0.0f));
    d = _mm_add_ps(d, _mm_setr_ps(1.0f, 1.0f, 0.0f, 1.0f));                   /* m22 m11 . m00 */
    /* w times (w x y z) in place, so the products of x, y, z are laid out to match */
    wr = _mm_mul_ps(QO_QUAT_SIMD_SHUFFLE_PS(u, 0x00), u);                          /* . wx wy wz */
    pr = _mm_mul_ps(QO_QUAT_SIMD_SHUFFLE_PS(u, _MM_SHUFFLE(1, 1, 2, 0)),           /* . yz xz xy */
                    QO_QUAT_SIMD_SHUFFLE_PS(u, _MM_SHUFFLE(2, 3, 3, 0)));
    pl = _mm_mul_ps(_mm_add_ps(pr, wr), s);                                   /* . m21 m02 m10 */
    mi = _mm_mul_ps(_mm_sub_ps(pr, wr), s);                                   /* . m12 m20 m01 */
    /* rows are contiguous: m00 m01 m02 m10 | m11 m12 m20 m21 | m22 */
    _mm_store_ss(&out->m[2][2], d);
    hi = _mm_unpackhi_ps(d, mi);                                              /* . m20 m00 m01 */
    lo = _mm_unpacklo_ps(d, mi);                                              /* m22 . m11 m12 */
    _mm_storeu_ps(&out->m[0][0], _mm_shuffle_ps(hi, pl, _MM_SHUFFLE(3, 2, 3, 2)));
    _mm_storeu_ps(&out->m[0][0] + 4,
                  _mm_shuffle_ps(lo, _mm_shuffle_ps(mi, pl, _MM_SHUFFLE(0, 1, 0, 2)), /* m20 . m21 . */
                                 _MM_SHUFFLE(2, 0, 3, 2)));
    return QO_OK;
#else
    float r = sqrtf(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z), s = 1.0f / r;
    float w, x, y, z, xx, yy, zz, xy, xz, yz, wx, wy, wz;
    if (out == NULL || !(r >= 1e-15f && s >= 1e-15f)) return qo_mat3_from_quat_full_f32(q, out);
    /* Normalising is kept although s = 2/|n|^2 below would absorb any scale: the unnormalised
     * form rounds the products of unnormalised components and is less accurate. */
    w = q.w * s; x = q.x * s; y = q.y * s; z = q.z * s;
    /* s = 2/|n|^2 rather than 2: I + s(...) is orthogonal for ANY non-zero n, so the few-ulp
     * norm error left by normalising does not leak into the matrix as non-orthogonality. */
    s = 2.0f / (w * w + x * x + y * y + z * z);
    xx = x * x; yy = y * y; zz = z * z;
    xy = x * y; xz = x * z; yz = y * z;
    wx = w * x; wy = w * y; wz = w * z;
    out->m[0][0] = 1.0f - s * (yy + zz);
    out->m[0][1] = s * (xy - wz);
    out->m[0][2] = s * (xz + wy);
    out->m[1][0] = s * (xy + wz);
    out->m[1][1] = 1.0f - s * (xx + zz);
    out->m[1][2] = s * (yz - wx);
    out->m[2][0] = s * (xz - wy);
    out->m[2][1] = s * (yz + wx);
    out->m[2][2] = 1.0f - s * (xx + yy);
    return QO_OK;
#endif
}

/* k = 1/(2 sqrt(c)) of the trusted formula as sqrt(c) / (c + c): one square root and one
 * divide, no constant to load, and rounds closer than 0.5 / sqrt(c) (measured: bench acc
 * lines). Unless bounded (then c <= 4), c is first clamped at FLT_MAX/2 so that c + c cannot
 * overflow to a zero k (the pivot entry keeps the unclamped c, so a NaN c, which the clamp
 * turns into FLT_MAX/2 as minss does, still makes q NaN). */
static inline float qo_mat3_internal_shepperd_k_f32(float c, int bounded)
{
    const float cmax = 0.5f * FLT_MAX;
    if (!bounded) c = c < cmax ? c : cmax;
    return sqrtf(c) / (c + c);
}
#if QO_QUAT_SIMD_SSE2
/* The same k broadcast to four lanes, from lane 0 of c4. */
static inline __m128 qo_mat3_internal_shepperd_k_ps(__m128 c4, int bounded)
{
    if (!bounded) c4 = _mm_min_ss(c4, _mm_set_ss(0.5f * FLT_MAX));
    c4 = QO_QUAT_SIMD_SHUFFLE_PS(c4, 0x00);
    return _mm_div_ps(_mm_sqrt_ps(c4), _mm_add_ps(c4, c4));
}
/* The formula's last step: *out = q with -0.0 made +0.0, returning 1; unless bounded, 0 and
 * *out unwritten when q is not finite. */
static inline int qo_mat3_internal_shepperd_store_ps(__m128 q4, qo_quat_f32 *out, int bounded)
{
    if (bounded) {
        q4 = _mm_add_ps(q4, _mm_setzero_ps());          /* -0.0 -> +0.0 */
    } else {
        const __m128 e = _mm_sub_ps(q4, q4);            /* 0, or NaN where q is not finite */
        q4 = _mm_add_ps(q4, e);                         /* -0.0 -> +0.0, non-finite -> NaN */
        if (_mm_movemask_ps(_mm_cmpunord_ps(e, q4))) return 0;
    }
    _mm_storeu_ps(&out->w, q4);
    return 1;
}
#endif

/*
 * The conversion formula of qo_mat3_to_quat_trusted_f32, and of qo_mat3_to_quat_f32 for the
 * matrices its rotation test passes (its checked path, for everything else, pivots on the
 * largest of trace and diagonal and normalises the pivot's vector: lib/src/convert.c's
 * mat3_pivot_vector). Shepperd's method with one square root and one divide. The trace is the
 * pivot when t = (m00 + m11) + m22 has its sign bit clear (t >= +0, tested as one bit; then
 * c = 1 + t = 4w^2 >= 1), else the largest diagonal entry p (c = 1 + 2 m_pp - t = 4p^2 > 1
 * for every matrix that takes that pivot, only rounding takes it lower; t = -0.0 needs a
 * diagonal of -0.0, and any pivot serves there). v is the pivot's row of the symmetric 4x4
 * matrix 4 q q^T (its pivot entry c, the others sums and differences of opposite off-diagonal
 * entries) and q = k v with k = 1/(2 sqrt(c)) (qo_mat3_internal_shepperd_k_f32): one square
 * root, one divide and four multiplies (a divide costs several multiplies on a Cortex-M4F, far
 * more in soft float). Where c is Inf, or so small or negative (rounding of huge entries) that
 * k v is not finite, q is not finite and the complete path answers.
 * The sign: q negated when its w < 0 (0 - q in the scalar body; the SSE2 body multiplies by
 * -k instead, without a branch: both exact, the same bits once -0.0 is made +0.0); on the
 * trace pivot w = c k > 0.
 * Returns 1 with *out = q (-0.0 made +0.0); 0, *out unwritten, where it cannot answer: a
 * non-finite q (a NaN/Inf entry - every entry reaches q: c through the trace or the pivot
 * entry - or entries so large that the formula overflows), or q's w == 0 (a half turn, where
 * the canonical sign rule looks further, also when w only underflowed to 0). bounded != 0
 * (a constant: the caller has established that every |entry| <= ~1, e.g. by
 * qo_mat3_internal_is_rotation_f32) skips the finiteness test, which cannot fail then.
 * Internal, not API (see quat.h).
 */
static inline int qo_mat3_internal_shepperd_f32(const qo_mat3_f32 *m, qo_quat_f32 *out,
                                                int bounded)
{
#if QO_QUAT_SIMD_SSE2
    /* The same operations in lanes: the matrix in three loads (rows 0-1 as m00..m10 and
     * m11..m21, then m22; nothing read past it), A - B and A + B give the differences D and sums
     * S of opposite off-diagonal entries in lanes 1-3 (w's row of 4 q q^T), and the pivot's row
     * is two shuffles of D, S and c. The scalar body's t, c, k and comparisons are lane 0
     * (t's sign bit is bit 0 of movmskps, signbit(t) there). */
    const __m128 r0 = _mm_loadu_ps(&m->m[0][0]);                     /* m00 m01 m02 m10 */
    const __m128 r1 = _mm_loadu_ps(&m->m[1][1]);                     /* m11 m12 m20 m21 */
    const __m128 m22 = _mm_load_ss(&m->m[2][2]);
    const __m128 one = _mm_set_ss(1.0f), zero = _mm_setzero_ps();
    const __m128 t4 = _mm_add_ss(_mm_add_ss(r0, r1), m22);
    const __m128 ab = _mm_shuffle_ps(r1, r0, _MM_SHUFFLE(1, 1, 2, 1));       /* m12 m20 m01 . */
    const __m128 av = _mm_shuffle_ps(r1, r0, _MM_SHUFFLE(3, 2, 3, 0));       /* . m21 m02 m10 */
    const __m128 bv = QO_QUAT_SIMD_SHUFFLE_PS(ab, _MM_SHUFFLE(2, 1, 0, 0));  /* . m12 m20 m01 */
    const __m128 dv = _mm_sub_ps(av, bv);
    __m128 c4, v4;
    if (!(_mm_movemask_ps(t4) & 1)) {
        c4 = _mm_add_ss(t4, one);                                     /* 1 + t >= 1 */
        v4 = _mm_move_ss(dv, c4);
        v4 = _mm_mul_ps(v4, qo_mat3_internal_shepperd_k_ps(c4, bounded));
        return qo_mat3_internal_shepperd_store_ps(v4, out, bounded);
    } else {
        const __m128 sv = _mm_add_ps(av, bv);
        if (_mm_comige_ss(r0, r1) && _mm_comige_ss(r0, m22)) {
            c4 = _mm_sub_ss(_mm_sub_ss(_mm_add_ss(one, r0), r1), m22);
            v4 = _mm_shuffle_ps(_mm_move_ss(dv, c4), sv, _MM_SHUFFLE(2, 3, 0, 1));
        } else if (_mm_comige_ss(r1, m22)) {
            c4 = _mm_sub_ss(_mm_add_ss(_mm_sub_ss(one, r0), r1), m22);
            v4 = _mm_shuffle_ps(_mm_shuffle_ps(dv, sv, _MM_SHUFFLE(3, 3, 2, 2)),
                                _mm_move_ss(sv, c4), _MM_SHUFFLE(1, 0, 2, 0));
        } else {
            c4 = _mm_add_ss(_mm_sub_ss(_mm_sub_ss(one, r0), r1), m22);
            v4 = _mm_shuffle_ps(_mm_shuffle_ps(dv, sv, _MM_SHUFFLE(2, 2, 3, 3)),
                                _mm_move_ss(sv, c4), _MM_SHUFFLE(0, 1, 2, 0));
        }
        /* w >= 0 without a branch on its sign (random on random input, so a mispredicted
         * branch half the time): k takes the sign of w's entry (lane 0 of v; k > 0), the
         * -0.0 this makes of +0.0 lanes is undone by the store. */
        v4 = _mm_mul_ps(v4, _mm_xor_ps(qo_mat3_internal_shepperd_k_ps(c4, bounded),
                                       _mm_and_ps(QO_QUAT_SIMD_SHUFFLE_PS(v4, 0x00),
                                                  _mm_set1_ps(-0.0f))));
        if (!_mm_comigt_ss(v4, zero)) return 0;
    }
    return qo_mat3_internal_shepperd_store_ps(v4, out, bounded);
#else
    const float (*a)[3] = m->m;
    const float t = (a[0][0] + a[1][1]) + a[2][2];
    float c, w, x, y, z, k;
    if (!signbit(t)) {
        c = 1.0f + t;                                                 /* >= 1 */
        k = qo_mat3_internal_shepperd_k_f32(c, bounded);
        w = c * k;
        x = (a[2][1] - a[1][2]) * k;
        y = (a[0][2] - a[2][0]) * k;
        z = (a[1][0] - a[0][1]) * k;
    } else {
        if (a[0][0] >= a[1][1] && a[0][0] >= a[2][2]) {
            c = ((1.0f + a[0][0]) - a[1][1]) - a[2][2];
            w = a[2][1] - a[1][2];
            x = c;
            y = a[0][1] + a[1][0];
            z = a[0][2] + a[2][0];
        } else if (a[1][1] >= a[2][2]) {
            c = ((1.0f - a[0][0]) + a[1][1]) - a[2][2];
            w = a[0][2] - a[2][0];
            x = a[0][1] + a[1][0];
            y = c;
            z = a[1][2] + a[2][1];
        } else {
            c = ((1.0f - a[0][0]) - a[1][1]) + a[2][2];
            w = a[1][0] - a[0][1];
            x = a[0][2] + a[2][0];
            y = a[1][2] + a[2][1];
            z = c;
        }
        k = qo_mat3_internal_shepperd_k_f32(c, bounded);
        w *= k; x *= k; y *= k; z *= k;
        if (!(w > 0.0f)) {
            if (!(w < 0.0f)) return 0;
            w = 0.0f - w; x = 0.0f - x; y = 0.0f - y; z = 0.0f - z;
        }
    }
    if (!bounded && !(isfinite(w) && isfinite(x) && isfinite(y) && isfinite(z))) return 0;
    /* + 0.0f: -0.0 -> +0.0 as qo_quat_canonical_f32 */
    out->w = w + 0.0f; out->x = x + 0.0f; out->y = y + 0.0f; out->z = z + 0.0f;
    return 1;
#endif
}

/* max |entry| of M^T M - I up to which qo_mat3_to_quat_f32 converts with the direct formula
 * (no projection first): ~3 float32 ulps of 1, above the ~2e-7 of a rounded rotation (every
 * rotation rounded from double passes, and all but ~0.4 % of those computed in float32 by
 * qo_mat3_from_quat_f32). Why not more: the formula carries the non-rotation part of M into
 * the result, up to 2.16 e rad for e = max |M^T M - I| (first order, the worst over rotations
 * and over symmetric errors M = R (I + S), at w = 1/2 where the trace stops being the pivot),
 * so 3.6e-7 keeps the result within 1e-6 rad of the nearest rotation with float rounding
 * (worst found 9.0e-7: tests/core/test_float_speed.c, test_from_mat3_direct_worst). */
#define QO_MAT3_INTERNAL_DIRECT_TOL_F32 3.6e-7f

/*
 * 1 when *m is a rotation to float32 rounding: every |(M^T M - I)_ij| <= 3.6e-7 (the columns
 * orthonormal) and every -(r0 x r1)_j r2_j <= 3.6e-7 for its rows r0, r1, r2 (the sign of the
 * determinant: orthonormal rows have r0 x r1 = det M r2, so the tested products are
 * -r2_j^2 <= 0 for a rotation, and r2_j^2 for a reflection, at least 1/3 in its largest
 * lane); 0 otherwise, NaN and Inf included. Sums in the order ((row 0 + row 1) + row 2);
 * both bodies decide alike. Internal, not API (see quat.h).
 */
static inline int qo_mat3_internal_is_rotation_f32(const qo_mat3_f32 *m)
{
#if QO_QUAT_SIMD_SSE2
    /* Rows as lanes (x, y, z, unused): lane j of sum_i r_i * r_i is column j's squared norm,
     * of sum_i r_i * r_i.yzx the dot of columns j and j+1 (mod 3), and r0.zxy * r1.yzx -
     * r0.yzx * r1.zxy is -(r0 x r1). Row 2 is loaded from m[1][2] on, so no read passes the
     * matrix. */
    const __m128 r0 = _mm_loadu_ps(&m->m[0][0]), r1 = _mm_loadu_ps(&m->m[1][0]);
    const __m128 r2 = QO_QUAT_SIMD_SHUFFLE_PS(_mm_loadu_ps(&m->m[1][2]), _MM_SHUFFLE(3, 3, 2, 1));
    const __m128 r0yzx = QO_QUAT_SIMD_SHUFFLE_PS(r0, _MM_SHUFFLE(3, 0, 2, 1));
    const __m128 r1yzx = QO_QUAT_SIMD_SHUFFLE_PS(r1, _MM_SHUFFLE(3, 0, 2, 1));
    const __m128 r0zxy = QO_QUAT_SIMD_SHUFFLE_PS(r0, _MM_SHUFFLE(3, 1, 0, 2));
    const __m128 r1zxy = QO_QUAT_SIMD_SHUFFLE_PS(r1, _MM_SHUFFLE(3, 1, 0, 2));
    /* lane 3 of the constants is unused: a constant that is not four equal lanes is read from
     * memory by the instruction that uses it, where gcc 12 builds a uniform one in two */
    const __m128 tol = _mm_setr_ps(QO_MAT3_INTERNAL_DIRECT_TOL_F32, QO_MAT3_INTERNAL_DIRECT_TOL_F32,
                                   QO_MAT3_INTERNAL_DIRECT_TOL_F32, 0.0f);
    const __m128 abs = _mm_castsi128_ps(_mm_setr_epi32(0x7fffffff, 0x7fffffff, 0x7fffffff, 0));
    __m128 d = _mm_add_ps(_mm_add_ps(_mm_mul_ps(r0, r0), _mm_mul_ps(r1, r1)), _mm_mul_ps(r2, r2));
    __m128 o = _mm_add_ps(_mm_add_ps(_mm_mul_ps(r0, r0yzx), _mm_mul_ps(r1, r1yzx)),
                          _mm_mul_ps(r2, QO_QUAT_SIMD_SHUFFLE_PS(r2, _MM_SHUFFLE(3, 0, 2, 1))));
    const __m128 x = _mm_mul_ps(_mm_sub_ps(_mm_mul_ps(r0zxy, r1yzx), _mm_mul_ps(r0yzx, r1zxy)), r2);
    d = _mm_and_ps(_mm_sub_ps(d, _mm_setr_ps(1.0f, 1.0f, 1.0f, 0.0f)), abs);
    o = _mm_and_ps(o, abs);
    /* A lane fails when the largest of the three is above tol or NaN. max returns its second
     * operand when either is NaN: o is NaN wherever d is (a NaN entry of column j is in both
     * d_j and o_j) and Inf or NaN wherever d is Inf, so max(d, o) loses no non-finite entry;
     * x can only be NaN when an entry is not finite or its products overflow, and then
     * max(d, o) fails. Lane 3 is not tested (x is not masked there). */
    return !(_mm_movemask_ps(_mm_cmpnle_ps(_mm_max_ps(x, _mm_max_ps(d, o)), tol)) & 7);
#else
    const float (*a)[3] = m->m;
    const float tol = QO_MAT3_INTERNAL_DIRECT_TOL_F32;
    int j;
    for (j = 0; j < 3; j++) {
        const int k = j < 2 ? j + 1 : 0, l = k < 2 ? k + 1 : 0;
        const float d = ((a[0][j] * a[0][j] + a[1][j] * a[1][j]) + a[2][j] * a[2][j]) - 1.0f;
        const float o = (a[0][j] * a[0][k] + a[1][j] * a[1][k]) + a[2][j] * a[2][k];
        const float x = (a[0][l] * a[1][k] - a[0][k] * a[1][l]) * a[2][j];
        if (!(fabsf(d) <= tol && fabsf(o) <= tol && x <= tol)) return 0;
    }
    return 1;
#endif
}

/*
 * Canonical unit quaternion (w >= 0) of the rotation matrix *m (row-major, v' = M v).
 * The matrix must already be a rotation within QO_MAT3_ROTATION_TOL_F32 (max entry of
 * |M^T M - I|) with det M > 0. The result is the rotation nearest M (within 1e-6 rad,
 * tests/core/test_convert.c: test_f32_quat_from_mat3_edges, test_f32_quat_from_mat3_drifted):
 * a matrix off by more than float32 rounding (max |M^T M - I| > 3.6e-7) is first projected
 * with qo_mat3_orthonormalize_f32, since the direct formula would carry that error into the
 * result (up to 2.16 times it, in rad). Robust at every angle (Shepperd: the pivot is never
 * a component smaller than 1/2, so 180-degree rotations, where the trace is -1, lose no
 * precision).
 * A matrix within ~3 ulps of a rotation (qo_mat3_internal_is_rotation_f32: max |M^T M - I|
 * <= 3.6e-7, det > 0) takes the trusted conversion's formula (the trace as pivot when it is
 * >= 0, else the largest diagonal entry; q = v / (2 sqrt(c)) for the pivot's row v of 4 q q^T
 * and c = 4 p^2): there |v| = 2 sqrt(c) to the same 3 ulps, so |q| is 1 within ~3e-7, and
 * the bits are qo_mat3_to_quat_trusted_f32's. The others (drifted, and half turns off the
 * trace pivot) take the largest of trace, m00, m11, m22 as pivot and normalise its row.
 * Returns QO_OK; QO_E_NULL if m or out is NULL; QO_E_NONFINITE for a NaN/Inf entry;
 * QO_E_NOT_ROTATION for a matrix that is scaled, sheared, a reflection (det < 0) or singular.
 * *out is the identity on every error.
 * Inline: the matrices of that test (every such rotation but a half turn off the trace pivot)
 * are handled here; the rest (NULL, the half turns, everything the test refuses) by
 * qo_mat3_to_quat_full_f32.
 */
QO_CONVERT_INLINE qo_status qo_mat3_to_quat_f32(const qo_mat3_f32 *m, qo_quat_f32 *out)
{
    if (m != NULL && out != NULL && qo_mat3_internal_is_rotation_f32(m) &&
        qo_mat3_internal_shepperd_f32(m, out, 1))
        return QO_OK;
    return qo_mat3_to_quat_full_f32(m, out);
}

/*
 * Canonical quaternion (w >= 0) of *m for callers whose matrix is KNOWN to be a rotation (built
 * from a quaternion or from rotations, to float rounding), without the rotation check
 * (orthogonality, determinant) of qo_mat3_to_quat_f32. Shepperd's method with one square
 * root and one divide: the pivot is the trace when it is >= 0, else the largest diagonal
 * entry, and q = v / (2 sqrt(c)) for that pivot's vector v and c = 4 p^2 (|v| = 2 sqrt(c) for
 * a rotation, so the pivot vector is not normalised by its own length).
 * Defined for rotation matrices within QO_MAT3_ROTATION_TOL_F32 (max |M^T M - I|): for a
 * float-rounded rotation the result is the same rotation within 1e-6 rad, w >= 0
 * (tests/core/test_convert.c: test_f32_mat3_to_quat_trusted; the worst measured by
 * bench/accuracy_convert.c: docs/FIGURES.md, accuracy); off a rotation by e, |q| is off 1
 * by about e. For any other
 * finite matrix the quaternion is unspecified (not unit, possibly not near any rotation of
 * it), but finite, never NaN, with w >= 0 - use qo_mat3_to_quat_f32 or _ortho_f32 when
 * that can happen.
 * Returns QO_OK; QO_E_NULL if m or out is NULL; QO_E_NONFINITE for a NaN/Inf entry (or
 * entries so large that the formula overflows: not a rotation). *out is the identity on every
 * error.
 * Inline: qo_mat3_internal_shepperd_f32's cases (every rotation but a half turn off the trace
 * pivot) are handled here; the rest (NULL, non-finite, those half turns) by
 * qo_mat3_to_quat_trusted_full_f32.
 */
QO_CONVERT_INLINE qo_status qo_mat3_to_quat_trusted_f32(const qo_mat3_f32 *m, qo_quat_f32 *out)
{
    if (m != NULL && out != NULL && qo_mat3_internal_shepperd_f32(m, out, 0)) return QO_OK;
    return qo_mat3_to_quat_trusted_full_f32(m, out);
}

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_CONVERT_H */
