/*
 * The SIMD bodies of the float32 core against their portable scalar bodies, bit for bit
 * (issue 14: the same results on every target, and x86-64 is the only one with these bodies):
 *  - qo_interp_slerp_f32's SSE2 body (three dot products, the range test and the half-arc series
 *    4-wide) against its scalar body: this file compiles lib/src/interp.c once more with
 *    QO_NO_SIMD under other names (scalar_*), and the library's result must be the same bits
 *    and status on random pairs, both sides of every branch (flip, t <= 1/2, endpoints, the
 *    fast range of the squared norms) and every error; each result is also checked against a
 *    double-precision slerp.
 *  - qo_fm_atan2x4_f32 (lib/src/fmath_internal.h, the Euler decomposition's four atan2 at
 *    once, 4-wide on SSE2) against qo_fm_atan2_f32 lane by lane, on random pairs of every
 *    octant and scale, both sides of each branch of the scalar kernel, and groups holding a
 *    special value (zero, subnormal, Inf, NaN) that take the per-lane path.
 *  - qo_mat3_to_quat_f32's SSE2 paths (the rotation test qo_mat3_internal_is_rotation_f32,
 *    the Shepperd formula's pivot rows as shuffles of D, S and c) against lib/src/convert.c
 *    compiled once more with QO_NO_SIMD (nosimd_*), bit for bit with the status, on rotations
 *    of every pivot, half turns, drifted, reflected, scaled and random matrices, signed zeros
 *    and bad entries; rotations also against double; qo_mat3_to_quat_trusted_f32 (the same
 *    formula with its finiteness test) on the same matrices.
 * Where SSE2 is not used both sides are the scalar code and only the double check can fail.
 * Linux only (make test, aarch64 and armhf under make test-qemu): it includes private files
 * of lib/src, which keeps it off the Cortex-M list (tests/qemu/run-target.sh is_core).
 * Fixed seeds; a failure names the case and its inputs.
 */
/* The scalar bodies: QO_NO_SIMD before the first qorient header (the library's own objects
 * keep their SIMD bodies). */
#define QO_NO_SIMD
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "qorient/quat.h"
#include "common/ref.h"

/* qorient/interp.h comes in with interp.c below, its names renamed there. */
/* lib/src/interp.c again, every external name renamed (so it links beside the library). */
#define qo_interp_lerp_f32 scalar_quat_lerp_f32
#define qo_interp_nlerp_f32 scalar_quat_nlerp_f32
#define qo_interp_slerp_f32 scalar_quat_slerp_f32
#define qo_interp_slerp_long_f32 scalar_quat_slerp_long_f32
#define qo_interp_slerp_rate_f32 scalar_quat_slerp_rate_f32
#define qo_interp_align_keys_f32 scalar_quat_align_keys_f32
#define qo_interp_bezier_f32 scalar_quat_bezier_f32
#define qo_interp_bezier3_f32 scalar_quat_bezier3_f32
#define qo_interp_spline_controls_f32 scalar_quat_spline_controls_f32
#define qo_interp_spline_eval_f32 scalar_quat_spline_eval_f32
#define qo_interp_squad_f32 scalar_quat_squad_f32
#define qo_interp_squad_controls_f32 scalar_quat_squad_controls_f32
#include "../lib/src/interp.c"
#undef qo_interp_lerp_f32
#undef qo_interp_nlerp_f32
#undef qo_interp_slerp_f32
#undef qo_interp_slerp_long_f32
#undef qo_interp_slerp_rate_f32
#undef qo_interp_align_keys_f32
#undef qo_interp_bezier_f32
#undef qo_interp_bezier3_f32
#undef qo_interp_spline_controls_f32
#undef qo_interp_spline_eval_f32
#undef qo_interp_squad_f32
#undef qo_interp_squad_controls_f32
qo_status qo_interp_slerp_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out);
/* lib/src/convert.c again in the same way (qorient/convert.h comes in with it, its names
 * renamed, so the scalar bodies of its inline functions are external definitions here too,
 * under nosimd_ names: tests/common/scalar_inline.c already has scalar_quat_to_mat3_f32). */
#define qo_mat3_identity_f32 nosimd_mat3_identity_f32
#define qo_mat3_mul_vec3_f32 nosimd_mat3_mul_vec3_f32
#define qo_mat3_mul_f32 nosimd_mat3_mul_f32
#define qo_mat3_transpose_f32 nosimd_mat3_transpose_f32
#define qo_mat3_det_f32 nosimd_mat3_det_f32
#define qo_axis_angle_to_quat_f32 nosimd_quat_from_axis_angle_f32
#define qo_axis_angle_from_quat_f32 nosimd_quat_to_axis_angle_f32
#define qo_rotvec_to_quat_f32 nosimd_quat_from_rotvec_f32
#define qo_rotvec_from_quat_f32 nosimd_quat_to_rotvec_f32
#define qo_mat3_from_quat_full_f32 nosimd_quat_to_mat3_full_f32
#define qo_mat3_from_quat_f32 nosimd_quat_to_mat3_f32
#define qo_mat3_to_quat_f32 nosimd_quat_from_mat3_f32
#define qo_mat3_to_quat_full_f32 nosimd_quat_from_mat3_full_f32
#define qo_mat3_to_quat_trusted_f32 nosimd_quat_from_mat3_trusted_f32
#define qo_mat3_to_quat_trusted_full_f32 nosimd_quat_from_mat3_trusted_full_f32
#define qo_mat3_orthonormalize_f32 nosimd_mat3_orthonormalize_f32
#define qo_mat3_to_quat_ortho_f32 nosimd_quat_from_mat3_ortho_f32
#include "../lib/src/convert.c"
#undef qo_mat3_identity_f32
#undef qo_mat3_mul_vec3_f32
#undef qo_mat3_mul_f32
#undef qo_mat3_transpose_f32
#undef qo_mat3_det_f32
#undef qo_axis_angle_to_quat_f32
#undef qo_axis_angle_from_quat_f32
#undef qo_rotvec_to_quat_f32
#undef qo_rotvec_from_quat_f32
#undef qo_mat3_from_quat_full_f32
#undef qo_mat3_from_quat_f32
#undef qo_mat3_to_quat_f32
#undef qo_mat3_to_quat_full_f32
#undef qo_mat3_to_quat_trusted_f32
#undef qo_mat3_to_quat_trusted_full_f32
#undef qo_mat3_orthonormalize_f32
#undef qo_mat3_to_quat_ortho_f32
qo_status qo_mat3_to_quat_f32(const qo_mat3_f32 *m, qo_quat_f32 *out);
qo_status qo_mat3_to_quat_full_f32(const qo_mat3_f32 *m, qo_quat_f32 *out);
qo_status qo_mat3_to_quat_trusted_f32(const qo_mat3_f32 *m, qo_quat_f32 *out);
qo_status qo_mat3_to_quat_trusted_full_f32(const qo_mat3_f32 *m, qo_quat_f32 *out);
#include "qorient/fmath.h"
#include "../lib/src/fmath_internal.h"

static int same_quat_bits(qo_quat_f32 a, qo_quat_f32 b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

#define N_SLERP 200000

/* Double slerp of the short way, for the library's result: the rotation error in radians. */
static double slerp_error(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 q)
{
    ref_quat ra = ref_quat_normalize(ref_quat_from_f32(a)), rb = ref_quat_normalize(ref_quat_from_f32(b));
    ref_quat r;
    double d = ra.w * rb.w + ra.x * rb.x + ra.y * rb.y + ra.z * rb.z, th, wa, wb, n;
    if (d < 0.0) { rb.w = -rb.w; rb.x = -rb.x; rb.y = -rb.y; rb.z = -rb.z; d = -d; }
    th = acos(d > 1.0 ? 1.0 : d);
    if (th < 1e-9) { wa = 1.0 - t; wb = t; }
    else { wa = sin((1.0 - t) * th) / sin(th); wb = sin(t * th) / sin(th); }
    r.w = wa * ra.w + wb * rb.w; r.x = wa * ra.x + wb * rb.x;
    r.y = wa * ra.y + wb * rb.y; r.z = wa * ra.z + wb * rb.z;
    n = ref_quat_norm(r);
    r.w /= n; r.x /= n; r.y /= n; r.z /= n;
    return ref_quat_angle_between(r, ref_quat_from_f32(q));
}

static qo_quat_f32 quat4(float w, float x, float y, float z)
{
    qo_quat_f32 q;
    q.w = w; q.x = x; q.y = y; q.z = z;
    return q;
}

static void test_slerp_simd_same_bits(void **state)
{
    ref_rng rng = { 0x51E4B175 };
    const float special_t[] = { 0.0f, -0.0f, 1.0f, 0.5f, 0x1p-24f, 0x1.fffffep-1f, 0x1.000002p-1f,
                                -0x1p-149f, 0x1.000002p+0f, 2.0f, NAN, INFINITY, -INFINITY };
    /* multipliers that move a squared norm across [1e-30, 1e30] (the fast range) */
    const float scale[] = { 1.0f, 0.5f, 2.0f, 1e-15f, 0.99e-15f, 1.01e-15f, 1e15f, 0.99e15f,
                            1.01e15f, 1e-20f, 1e20f, 0.0f, INFINITY, NAN };
    long n, fast = 0, flipped = 0;
    double worst = 0.0;
    (void)state;
    for (n = 0; n < N_SLERP; n++) {
        qo_quat_f32 a = ref_quat_to_f32(ref_rng_quat(&rng)), b = ref_quat_to_f32(ref_rng_quat(&rng));
        qo_quat_f32 q1, q2;
        float t = (float)ref_rng_unit(&rng), sa = 1.0f, sb = 1.0f;
        qo_status s1, s2;
        int kind = (int)(ref_rng_next(&rng) % 24u);
        switch (kind) {
        case 0: b = a; break;                                           /* identical */
        case 1: b = quat4(-a.w, -a.x, -a.y, -a.z); break;               /* antipodal: same rotation */
        case 2: b = quat4(-a.w, -a.x, -a.y, -a.z); b.x += 0x1p-22f; break;     /* nearly so */
        case 3: b = quat4(a.x, -a.w, a.z, -a.y); break;                 /* dot == 0: 180 deg */
        case 4: b = a; b.y += 0x1p-23f; break;                          /* nearly identical */
        case 5: t = special_t[ref_rng_next(&rng) % (sizeof special_t / sizeof special_t[0])]; break;
        case 6:
            sa = scale[ref_rng_next(&rng) % (sizeof scale / sizeof scale[0])];
            sb = scale[ref_rng_next(&rng) % (sizeof scale / sizeof scale[0])];
            break;
        case 7: a.z = NAN; break;
        case 8: b.w = -INFINITY; break;
        default: break;
        }
        a = quat4(a.w * sa, a.x * sa, a.y * sa, a.z * sa);
        b = quat4(b.w * sb, b.x * sb, b.y * sb, b.z * sb);
        memset(&q1, 0x5a, sizeof q1);
        memset(&q2, 0xa5, sizeof q2);
        s1 = qo_interp_slerp_f32(a, b, t, &q1);
        s2 = scalar_quat_slerp_f32(a, b, t, &q2);
        if (s1 != s2 || !same_quat_bits(q1, q2))
            fail_msg("slerp case %ld (kind %d): SIMD status %d (%a, %a, %a, %a), scalar status %d "
                     "(%a, %a, %a, %a); a (%a, %a, %a, %a) b (%a, %a, %a, %a) t %a", n, kind,
                     (int)s1, (double)q1.w, (double)q1.x, (double)q1.y, (double)q1.z, (int)s2,
                     (double)q2.w, (double)q2.x, (double)q2.y, (double)q2.z, (double)a.w,
                     (double)a.x, (double)a.y, (double)a.z, (double)b.w, (double)b.x, (double)b.y,
                     (double)b.z, (double)t);
        if (s1 == QO_OK) {
            double err = slerp_error(a, b, t, q1);
            if (err > worst) worst = err;
            if (err > 1e-6)
                fail_msg("slerp case %ld (kind %d): %.3g rad from the double slerp; a (%a, %a, %a, "
                         "%a) b (%a, %a, %a, %a) t %a", n, kind, err, (double)a.w, (double)a.x,
                         (double)a.y, (double)a.z, (double)b.w, (double)b.x, (double)b.y,
                         (double)b.z, (double)t);
            fast++;
            if (a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z < 0.0f) flipped++;
        }
    }
    /* the cases above reach both sides of the flip and most inputs succeed */
    assert_true(fast > N_SLERP / 2);
    assert_true(flipped > N_SLERP / 8);
    print_message("slerp: %ld of %d cases succeeded (%ld flipped), SIMD == scalar bits, "
                  "worst %.3g rad vs double\n", fast, N_SLERP, flipped, worst);
}

#define N_M2Q 300000

/* A 3x3 matrix of a random kind around qo_mat3_to_quat_f32's branches: a float-rounded
 * rotation (every Shepperd pivot), one with every entry moved by up to eps (eps on both sides
 * of the direct test's 5e-7 and of the tolerance 1e-4), a half turn (w == 0, axes with zero
 * components: the sign rule's ties), a reflection (one row negated, or -R: half of those of a
 * 120 degree rotation, so trace 0, where the determinant's sign is all that tells them from
 * rotations), a scaled rotation, random entries, signed zeros, huge, NaN and Inf entries.
 * *rot gets the double rotation it came from (identity for the non-rotations). */
static qo_mat3_f32 m2q_input(ref_rng *rng, int kind, ref_quat *rot)
{
    static const double eps[] = { 1e-7, 3e-7, 5e-7, 7e-7, 1e-6, 1e-5, 4e-5, 1e-4, 2e-4 };
    static const float bad[] = { NAN, INFINITY, -INFINITY, 3e38f, -3e38f, 1e20f, 0x1p-149f };
    ref_quat q = ref_rng_quat(rng);
    ref_mat3 r;
    qo_mat3_f32 m;
    int i, j;
    if (kind == 9) {                                      /* about an axis: exact zeros */
        ref_vec3 v;
        uint64_t k = ref_rng_next(rng) % 3u;
        v.x = k == 0; v.y = k == 1; v.z = k == 2;
        q = ref_quat_from_axis_angle(v, ref_rng_range(rng, -2 * REF_PI, 2 * REF_PI));
    }
    if (kind == 11 && (ref_rng_next(rng) & 1u)) {         /* -R of a 120 degree turn */
        ref_vec3 v;
        v.x = ref_rng_range(rng, -1, 1);
        v.y = ref_rng_range(rng, -1, 1);
        v.z = ref_rng_range(rng, -1, 1);
        q = ref_quat_from_axis_angle(v, 2 * REF_PI / 3);
    }
    if (kind == 1 || kind == 2) {                         /* half turns: w = 0 */
        static const double ax[][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 1, 0 },
                                        { 0, 1, -1 }, { -1, 0, 1 }, { 1, -1, 1 } };
        const double *a = ax[ref_rng_next(rng) % (sizeof ax / sizeof ax[0])];
        ref_vec3 v;
        v.x = a[0]; v.y = a[1]; v.z = a[2];
        if (kind == 2) { v.x = ref_rng_range(rng, -1, 1); v.y = ref_rng_range(rng, -1, 1); v.z = 0; }
        q = ref_quat_from_axis_angle(v, REF_PI);
    }
    *rot = q;
    r = ref_quat_to_mat3(q);
    m = ref_mat3_to_f32(&r);
    switch (kind) {
    case 3: case 4: case 5: {                             /* drifted rotation */
        double e = eps[ref_rng_next(rng) % (sizeof eps / sizeof eps[0])];
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) m.m[i][j] = (float)(r.m[i][j] + ref_rng_range(rng, -e, e));
        break;
    }
    case 6:                                                 /* reflection */
        for (j = 0; j < 3; j++) m.m[1][j] = -m.m[1][j];
        break;
    case 7:                                                 /* scaled */
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) m.m[i][j] *= 1.001f;
        break;
    case 8:                                                 /* random entries */
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) m.m[i][j] = (float)ref_rng_range(rng, -2, 2);
        break;
    case 9:                                                 /* signed zeros */
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++)
                if (m.m[i][j] == 0.0f) m.m[i][j] = (ref_rng_next(rng) & 1u) ? -0.0f : 0.0f;
        break;
    case 11:                                                /* -R: a reflection */
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) m.m[i][j] = -m.m[i][j];
        break;
    case 10:                                                /* a bad entry */
        m.m[ref_rng_next(rng) % 3u][ref_rng_next(rng) % 3u] =
            bad[ref_rng_next(rng) % (sizeof bad / sizeof bad[0])];
        break;
    default: break;
    }
    return m;
}

typedef qo_status (*m2q_fn)(const qo_mat3_f32 *m, qo_quat_f32 *out);

/* simd(m) and scalar(m) from different garbage in the outputs: the same status and bits, or
 * the test fails naming the case, both results and m. Returns the status, *q the result. */
static qo_status m2q_same_bits(const char *what, long n, int kind, const qo_mat3_f32 *m,
                               m2q_fn simd, m2q_fn scalar, qo_quat_f32 *q)
{
    qo_quat_f32 q2;
    qo_status s1, s2;
    memset(q, 0x5a, sizeof *q);
    memset(&q2, 0xa5, sizeof q2);
    s1 = simd(m, q);
    s2 = scalar(m, &q2);
    if (s1 != s2 || !same_quat_bits(*q, q2))
        fail_msg("%s case %ld (kind %d): SIMD status %d (%a, %a, %a, %a), scalar status %d (%a, "
                 "%a, %a, %a); m %a %a %a / %a %a %a / %a %a %a", what, n, kind, (int)s1,
                 (double)q->w, (double)q->x, (double)q->y, (double)q->z, (int)s2, (double)q2.w,
                 (double)q2.x, (double)q2.y, (double)q2.z, (double)m->m[0][0],
                 (double)m->m[0][1], (double)m->m[0][2], (double)m->m[1][0], (double)m->m[1][1],
                 (double)m->m[1][2], (double)m->m[2][0], (double)m->m[2][1], (double)m->m[2][2]);
    return s1;
}

/* qo_mat3_to_quat_f32's SSE2 paths (the rotation test, the Shepperd formula) against the
 * scalar body (convert.c with QO_NO_SIMD), bit for bit with the status, on every kind of
 * m2q_input, and against its out-of-line path (the same for the trusted variant); every
 * reflection refused; each rotation's result also against the double quaternion it came from. */
static void test_from_mat3_simd_same_bits(void **state)
{
    ref_rng rng = { 0x3A7F0E11 };
    long n, ok = 0, refused = 0;
    double worst = 0.0;
    (void)state;
    for (n = 0; n < N_M2Q; n++) {
        const int kind = (int)(ref_rng_next(&rng) % 16u);
        ref_quat rq;
        qo_mat3_f32 m = m2q_input(&rng, kind, &rq);
        qo_quat_f32 q1, q3;
        const qo_status s1 = m2q_same_bits("from_mat3", n, kind, &m, qo_mat3_to_quat_f32,
                                           nosimd_quat_from_mat3_f32, &q1);
        /* the trusted variant: its SSE2 store and finiteness test, on the same matrices */
        (void)m2q_same_bits("from_mat3_trusted", n, kind, &m, qo_mat3_to_quat_trusted_f32,
                            nosimd_quat_from_mat3_trusted_f32, &q3);
        /* the inline functions and their out-of-line paths: the same result for every input */
        (void)m2q_same_bits("from_mat3 inline/full", n, kind, &m, qo_mat3_to_quat_f32,
                            qo_mat3_to_quat_full_f32, &q3);
        (void)m2q_same_bits("from_mat3_trusted inline/full", n, kind, &m,
                            qo_mat3_to_quat_trusted_f32, qo_mat3_to_quat_trusted_full_f32, &q3);
        if ((kind == 6 || kind == 11) && s1 != QO_E_NOT_ROTATION)
            fail_msg("from_mat3 case %ld (kind %d): a reflection not refused (status %d)", n, kind,
                     (int)s1);
        if (s1 != QO_OK) {
            refused++;
            continue;
        }
        ok++;
        if (kind <= 2 || kind == 9 || kind > 11) {          /* rotations to float rounding */
            double err = ref_quat_angle_between(ref_quat_from_f32(q1), rq);
            if (err > worst) worst = err;
            if (err > 1e-6 || q1.w < 0.0f)
                fail_msg("from_mat3 case %ld (kind %d): %.3g rad from the double rotation, w %a", n,
                         kind, err, (double)q1.w);
        }
    }
    /* both outcomes are reached (the reflections and bad entries are refused) */
    assert_true(ok > N_M2Q / 2 && refused > N_M2Q / 16);
    print_message("from_mat3: %ld of %d accepted, SIMD == scalar bits, worst %.3g rad vs double\n",
                  ok, N_M2Q, worst);
}

#define N_ATAN 400000

/* A float of a random kind: a unit-scale value, one scaled to the edges of the kernel's
 * 2^-+64 rescaling and the 2^-60 residual cut, any bit pattern, or a special value. */
static float atan_arg(ref_rng *rng)
{
    static const float special[] = { 0.0f, -0.0f, 0x1p-149f, -0x1p-130f, INFINITY, -INFINITY,
                                     NAN, FLT_MAX, -FLT_MIN, 1.0f, 0x1p64f, 0x1.fffffep63f };
    static const float scale[] = { 1.0f, 0x1p-60f, 0x1p-64f, 0x1p-70f, 0x1p64f, 0x1p70f, 0x1p-100f,
                                   0x1p100f };
    uint64_t k = ref_rng_next(rng);
    float v = (float)ref_rng_range(rng, -1.0, 1.0);
    uint32_t u = (uint32_t)(k >> 32);
    switch (k % 16u) {
    case 0: memcpy(&v, &u, sizeof v); return v;
    case 1: return special[u % (sizeof special / sizeof special[0])];
    case 2: case 3: return v * scale[u % (sizeof scale / sizeof scale[0])];
    default: return v;
    }
}

static void test_atan2x4_same_bits(void **state)
{
    ref_rng rng = { 0xA7A42F4 };
    long n, wide = 0;
    (void)state;
    for (n = 0; n < N_ATAN; n++) {
        float y[4], x[4], r[4], s;
        int l, all_ok = 1;
        for (l = 0; l < 4; l++) {
            x[l] = atan_arg(&rng);
            /* y on or near the octant lines |y| = |x| and |y| = tan(pi/8) |x| half the time */
            switch (ref_rng_next(&rng) % 6u) {
            case 0: y[l] = x[l]; break;
            case 1: y[l] = -0.41421356f * x[l]; break;
            case 2: y[l] = x[l] * (float)ref_rng_range(&rng, 0.41, 0.42); break;
            default: y[l] = atan_arg(&rng); break;
            }
            if (!(isfinite(x[l]) && isfinite(y[l]) && x[l] != 0.0f && y[l] != 0.0f)) all_ok = 0;
        }
        wide += all_ok;
        qo_fm_atan2x4_f32(y, x, r, 4);
        for (l = 0; l < 4; l++) {
            s = qo_fm_atan2_f32(y[l], x[l]);
            if (memcmp(&s, &r[l], sizeof s) != 0 && !(isnan(s) && isnan(r[l])))
                fail_msg("atan2x4 case %ld lane %d: atan2(%a, %a) = %a, the scalar kernel %a",
                         n, l, (double)y[l], (double)x[l], (double)r[l], (double)s);
        }
    }
    /* most groups take the 4-wide path (all finite and non-zero), some the per-lane one */
    assert_true(wide > N_ATAN / 4 && wide < N_ATAN);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_slerp_simd_same_bits),
        cmocka_unit_test(test_atan2x4_same_bits),
        cmocka_unit_test(test_from_mat3_simd_same_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
