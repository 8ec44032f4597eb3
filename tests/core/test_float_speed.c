/*
 * The fast paths of the float32 core (issue 14) against the paths they shortcut:
 *  - qo_quat_from_mat3_f32's direct test (max |M^T M - I| <= 5e-7 and det > 0, 4-wide on SSE2)
 *    on matrices drifted to either side of that threshold: the result is the rotation nearest
 *    M (double reference) whichever path was taken, and on the direct side it is bit for bit
 *    the trusted conversion's (both are the pivot formula on the same matrix);
 *  - qo_quat_to_euler_f32's one range test on the largest |component| ([2^-20, 2^20]): q scaled
 *    by 2^k on both sides of the range gives the same bits as q (the checked path scales by
 *    powers of two, the decomposition is scale-free), in all 24 conventions, and the errors
 *    (NaN, Inf, zero, 1e39 rounded to float, bad convention, NULL) keep their statuses.
 *  - qo_quat_slerp_f32's SSE2 body (three dot products, the range test and the half-arc series
 *    4-wide) against its portable scalar body: this file compiles lib/src/interp.c once more
 *    with QO_NO_SIMD under other names (scalar_*), and the library's result must be the same
 *    bits and status on random pairs, both sides of every branch (flip, t <= 1/2, endpoints,
 *    the fast range of the squared norms) and every error. Where SSE2 is not used both are the
 *    scalar body and only the double-precision check below can fail.
 *  - qo_fm_atan2x4_f32 (lib/src/fmath_internal.h, the Euler decomposition's four atan2 at
 *    once, 4-wide on SSE2) against qo_fm_atan2_f32 lane by lane, bit for bit, on random pairs
 *    of every octant and scale, both sides of each branch of the scalar kernel, and groups
 *    holding a special value (zero, subnormal, Inf, NaN) that take the per-lane path.
 * Fixed seeds; a failure names the case and its inputs.
 */
/* The scalar slerp: QO_NO_SIMD before the first qorient header (the whole file then gets the
 * scalar inline bodies, which the tests below only use through library calls). */
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

#include "qorient/convert.h"
#include "qorient/euler.h"
#include "qorient/quat.h"
#include "common/ref.h"

/* lib/src/interp.c again, every external name renamed (so it links beside the library). */
#define qo_quat_lerp_f32 scalar_quat_lerp_f32
#define qo_quat_nlerp_f32 scalar_quat_nlerp_f32
#define qo_quat_slerp_f32 scalar_quat_slerp_f32
#define qo_quat_slerp_long_f32 scalar_quat_slerp_long_f32
#define qo_quat_slerp_rate_f32 scalar_quat_slerp_rate_f32
#define qo_quat_align_keys_f32 scalar_quat_align_keys_f32
#define qo_quat_bezier_f32 scalar_quat_bezier_f32
#define qo_quat_bezier3_f32 scalar_quat_bezier3_f32
#define qo_quat_spline_controls_f32 scalar_quat_spline_controls_f32
#define qo_quat_spline_eval_f32 scalar_quat_spline_eval_f32
#define qo_quat_squad_f32 scalar_quat_squad_f32
#define qo_quat_squad_controls_f32 scalar_quat_squad_controls_f32
#include "../lib/src/interp.c"
#undef qo_quat_lerp_f32
#undef qo_quat_nlerp_f32
#undef qo_quat_slerp_f32
#undef qo_quat_slerp_long_f32
#undef qo_quat_slerp_rate_f32
#undef qo_quat_align_keys_f32
#undef qo_quat_bezier_f32
#undef qo_quat_bezier3_f32
#undef qo_quat_spline_controls_f32
#undef qo_quat_spline_eval_f32
#undef qo_quat_squad_f32
#undef qo_quat_squad_controls_f32
qo_status qo_quat_slerp_f32(qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 *out);
#include "qorient/fmath.h"
#include "../lib/src/fmath_internal.h"

#define N_MAT 4000
#define N_EUL 300

static double orth_error(const ref_mat3 *m)
{
    double worst = 0.0;
    int i, j, r;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            double s = (i == j) ? -1.0 : 0.0;
            for (r = 0; r < 3; r++) s += m->m[r][i] * m->m[r][j];
            if (fabs(s) > worst) worst = fabs(s);
        }
    return worst;
}

static int same_quat_bits(qo_quat_f32 a, qo_quat_f32 b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static void test_from_mat3_direct_threshold(void **state)
{
    ref_rng rng = { 0x14F5EED };
    int n, below = 0, above = 0;
    (void)state;
    for (n = 0; n < N_MAT; n++) {
        ref_quat rq = ref_rng_quat(&rng);
        ref_mat3 r = ref_quat_to_mat3(rq), md, near;
        /* drift scale 3e-8 .. 1e-6 (log-uniform): max |M^T M - I| from ~1e-7 to ~4e-6 */
        double s = 3e-8 * pow(1e-6 / 3e-8, ref_rng_unit(&rng)), orth, err;
        qo_mat3_f32 m;
        qo_quat_f32 q, qt;
        qo_status st;
        int i, j;
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) r.m[i][j] += s * ref_rng_range(&rng, -1.0, 1.0);
        m = ref_mat3_to_f32(&r);
        md = ref_mat3_from_f32(&m);
        orth = orth_error(&md);
        near = ref_mat3_nearest_rotation(&md);
        q.w = 7.0f;
        st = qo_quat_from_mat3_f32(&m, &q);
        err = ref_quat_angle_between(ref_quat_from_f32(q), ref_mat3_to_quat(&near));
        if (st != QO_OK || err > 1e-6 || q.w < 0.0f ||
            fabs(ref_quat_norm(ref_quat_from_f32(q)) - 1.0) > 1e-6)
            fail_msg("from_mat3 case %d (drift %.3g, |M^T M - I| %.3g): status %d, error %.3g rad, "
                     "q (%.9g, %.9g, %.9g, %.9g)", n, s, orth, (int)st, err, (double)q.w,
                     (double)q.x, (double)q.y, (double)q.z);
        /* clearly on the direct side (the float test rounds the products: stay 20 % clear) */
        if (orth < 4e-7) {
            below++;
            if (qo_quat_from_mat3_trusted_f32(&m, &qt) != QO_OK || !same_quat_bits(q, qt))
                fail_msg("from_mat3 case %d (|M^T M - I| %.3g): not the trusted result", n, orth);
        } else if (orth > 6e-7) {
            above++;
        }
    }
    /* both paths were exercised, many times */
    if (below < N_MAT / 10 || above < N_MAT / 10)
        fail_msg("from_mat3: %d cases below and %d above the direct threshold", below, above);
}

static void test_from_mat3_fast_path_errors(void **state)
{
    ref_rng rng = { 0x14F5EEE };
    int n, k;
    (void)state;
    for (n = 0; n < 200; n++) {
        ref_quat rq = ref_rng_quat(&rng);
        ref_mat3 r = ref_quat_to_mat3(rq);
        qo_mat3_f32 m = ref_mat3_to_f32(&r), bad;
        qo_quat_f32 q;
        /* a reflection passes the orthogonality test: the determinant must refuse it */
        for (k = 0; k < 9; k++) bad.m[k / 3][k % 3] = -m.m[k / 3][k % 3];
        q.w = 7.0f;
        if (qo_quat_from_mat3_f32(&bad, &q) != QO_E_NOT_ROTATION || !same_quat_bits(q, qo_quat_identity_f32()))
            fail_msg("from_mat3 case %d: reflection -R not refused with the identity", n);
        for (k = 0; k < 9; k++) {
            const float v[3] = { NAN, INFINITY, 1e30f };
            const qo_status want[3] = { QO_E_NONFINITE, QO_E_NONFINITE, QO_E_NOT_ROTATION };
            int c;
            for (c = 0; c < 3; c++) {
                bad = m;
                bad.m[k / 3][k % 3] = v[c];
                q.w = 7.0f;
                if (qo_quat_from_mat3_f32(&bad, &q) != want[c] ||
                    !same_quat_bits(q, qo_quat_identity_f32()))
                    fail_msg("from_mat3 case %d: entry %d = %g not refused as %d", n, k,
                             (double)v[c], (int)want[c]);
            }
        }
    }
}

static void test_to_euler_fast_range(void **state)
{
    static const int ks[] = { -40, -22, -21, -20, -19, -1, 1, 19, 20, 21, 22, 40 };
    ref_rng rng = { 0x14F5EEF };
    int n, s;
    size_t k;
    (void)state;
    for (n = 0; n < N_EUL; n++) {
        qo_quat_f32 q = ref_quat_to_f32(ref_rng_quat(&rng));
        for (s = 0; s < (int)QO_EULER_SEQ_COUNT_; s++) {
            qo_euler_f32 e0, e;
            qo_euler_info_f32 i0, i;
            qo_status st0 = qo_quat_to_euler_f32(q, (qo_euler_seq)s, &e0, &i0);
            if (st0 != QO_OK) fail_msg("to_euler case %d seq %d: status %d", n, s, (int)st0);
            for (k = 0; k < sizeof ks / sizeof ks[0]; k++) {
                float f = ldexpf(1.0f, ks[k]);
                qo_quat_f32 qs;
                qs.w = q.w * f; qs.x = q.x * f; qs.y = q.y * f; qs.z = q.z * f;
                if (qo_quat_to_euler_f32(qs, (qo_euler_seq)s, &e, &i) != QO_OK ||
                    memcmp(&e, &e0, sizeof e) != 0 || i.locked != i0.locked ||
                    memcmp(&i.margin, &i0.margin, sizeof i.margin) != 0)
                    fail_msg("to_euler case %d seq %d: q * 2^%d gives (%.9g, %.9g, %.9g), "
                             "q gives (%.9g, %.9g, %.9g)", n, s, ks[k], (double)e.a1,
                             (double)e.a2, (double)e.a3, (double)e0.a1, (double)e0.a2,
                             (double)e0.a3);
                /* without info: the same angles (the margin shortcut only skips work) */
                if (qo_quat_to_euler_f32(qs, (qo_euler_seq)s, &e, NULL) != QO_OK ||
                    memcmp(&e, &e0, sizeof e) != 0)
                    fail_msg("to_euler case %d seq %d: q * 2^%d without info differs", n, s, ks[k]);
            }
        }
    }
}

static void test_to_euler_fast_range_errors(void **state)
{
    const float bad[5] = { NAN, INFINITY, -INFINITY, (float)1e39, 0.0f };
    const qo_status want[5] = { QO_E_NONFINITE, QO_E_NONFINITE, QO_E_NONFINITE, QO_E_NONFINITE,
                                QO_OK };
    qo_quat_f32 q = { 0.5f, 0.5f, -0.5f, 0.5f }, z = { 0.0f, 0.0f, 0.0f, 0.0f };
    qo_euler_f32 e;
    qo_euler_info_f32 info;
    int c, k;
    (void)state;
    for (c = 0; c < 5; c++) {
        for (k = 0; k < 4; k++) {
            qo_quat_f32 b = q;
            float *p = (k == 0) ? &b.w : (k == 1) ? &b.x : (k == 2) ? &b.y : &b.z;
            qo_status st;
            *p = bad[c];
            e.a1 = e.a2 = e.a3 = 7.0f;
            st = qo_quat_to_euler_f32(b, QO_EULER_ZYX, &e, &info);
            if (st != want[c] || (st != QO_OK && (e.a1 != 0.0f || e.a2 != 0.0f || e.a3 != 0.0f)))
                fail_msg("to_euler: component %d = %g gives status %d, want %d", k, (double)bad[c],
                         (int)st, (int)want[c]);
        }
    }
    assert_int_equal(qo_quat_to_euler_f32(z, QO_EULER_XYZ, &e, &info), QO_E_DEGENERATE);
    assert_true(e.a1 == 0.0f && e.a2 == 0.0f && e.a3 == 0.0f && info.locked == 0);
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_SEQ_COUNT_, &e, NULL), QO_E_ARG);
    assert_int_equal(qo_quat_to_euler_f32(q, (qo_euler_seq)-1, &e, NULL), QO_E_ARG);
    assert_int_equal(qo_quat_to_euler_f32(q, QO_EULER_XYZ, NULL, &info), QO_E_NULL);
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
        s1 = qo_quat_slerp_f32(a, b, t, &q1);
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
        cmocka_unit_test(test_from_mat3_direct_threshold),
        cmocka_unit_test(test_from_mat3_fast_path_errors),
        cmocka_unit_test(test_to_euler_fast_range),
        cmocka_unit_test(test_to_euler_fast_range_errors),
        cmocka_unit_test(test_slerp_simd_same_bits),
        cmocka_unit_test(test_atan2x4_same_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
