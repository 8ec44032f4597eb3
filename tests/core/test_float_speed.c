/*
 * The fast paths of the float32 core (issue 14) against the paths they shortcut:
 *  - qo_mat3_to_quat_f32's direct test (max |M^T M - I| <= 3.6e-7 and det > 0, 4-wide on SSE2)
 *    on matrices drifted to either side of that threshold: the result is the rotation nearest
 *    M (double reference) whichever path was taken, and on the direct side it is the trusted
 *    conversion's result, bit for bit (both take the same formula there); and the worst case
 *    of the direct side: a hill-climbing search for the matrix just inside the threshold whose
 *    result is furthest from its nearest rotation stays within the documented 1e-6 rad;
 *  - qo_euler_from_quat_f32's one range test on the largest |component| ([2^-20, 2^20]): q scaled
 *    by 2^k on both sides of the range gives the same bits as q (the checked path scales by
 *    powers of two, the decomposition is scale-free), in all 24 conventions, and the errors
 *    (NaN, Inf, zero, 1e39 rounded to float, bad convention, NULL) keep their statuses.
 * Fixed seeds; a failure names the case and its inputs.
 */
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
        st = qo_mat3_to_quat_f32(&m, &q);
        err = ref_quat_angle_between(ref_quat_from_f32(q), ref_mat3_to_quat(&near));
        if (st != QO_OK || err > 1e-6 || q.w < 0.0f ||
            fabs(ref_quat_norm(ref_quat_from_f32(q)) - 1.0) > 1e-6)
            fail_msg("from_mat3 case %d (drift %.3g, |M^T M - I| %.3g): status %d, error %.3g rad, "
                     "q (%.9g, %.9g, %.9g, %.9g)", n, s, orth, (int)st, err, (double)q.w,
                     (double)q.x, (double)q.y, (double)q.z);
        /* clearly on the direct side (the float test rounds the products: stay 20 % clear) */
        if (orth < 2.8e-7) {
            below++;
            if (qo_mat3_to_quat_trusted_f32(&m, &qt) != QO_OK || !same_quat_bits(q, qt))
                fail_msg("from_mat3 case %d (|M^T M - I| %.3g): the trusted result (%a, %a, %a, "
                         "%a) is not the validating one", n, orth, (double)qt.w, (double)qt.x,
                         (double)qt.y, (double)qt.z);
        } else if (orth > 4.4e-7) {
            above++;
        }
    }
    /* both paths were exercised, many times */
    if (below < N_MAT / 10 || above < N_MAT / 10)
        fail_msg("from_mat3: %d cases below and %d above the direct threshold", below, above);
}

/* M = R(q) (I + s S), S symmetric, s as large as the float rotation test still passes
 * (bisection): the direct formula's result for it, and its distance to the nearest rotation
 * (double reference; for such a matrix it is R(q) up to rounding). 0 when none passes. */
static double direct_edge_error(ref_quat q, double S[3][3])
{
    const ref_mat3 r = ref_quat_to_mat3(ref_quat_normalize(q));
    double lo = 0.0, hi = 1e-6;
    qo_mat3_f32 best, m;
    qo_quat_f32 o;
    int i, j, k, it;
    for (it = 0; it < 26; it++) {
        const double mid = 0.5 * (lo + hi);
        ref_mat3 d;
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) {
                double a = r.m[i][j];
                for (k = 0; k < 3; k++) a += r.m[i][k] * S[k][j] * mid;
                d.m[i][j] = a;
            }
        m = ref_mat3_to_f32(&d);
        if (qo_mat3_internal_is_rotation_f32(&m)) { lo = mid; best = m; } else { hi = mid; }
    }
    if (lo == 0.0) return 0.0;
    if (qo_mat3_to_quat_f32(&best, &o) != QO_OK) fail_msg("direct_edge_error: a rotation refused");
    {
        const ref_mat3 d = ref_mat3_from_f32(&best), near = ref_mat3_nearest_rotation(&d);
        return ref_quat_angle_between(ref_quat_from_f32(o), ref_mat3_to_quat(&near));
    }
}

/* The worst of the direct side (QO_MAT3_INTERNAL_DIRECT_TOL_F32 in convert.h): the formula
 * carries up to 2.16 e rad of a non-orthogonality e into the result, worst at w = 1/2, where
 * the trace stops being the pivot. A hill climb from rotations by 120 degrees (w = 1/2) over
 * q and S, each candidate pushed to the edge of the test, must stay within 1e-6 rad; it must
 * also get near the predicted worst (> 6e-7), or the search proves nothing. */
static void test_from_mat3_direct_worst(void **state)
{
    ref_rng rng = { 0x5EA4C4 };
    double worst = 0.0;
    int rs, st, i, j;
    (void)state;
    for (rs = 0; rs < 200; rs++) {
        ref_vec3 a;
        ref_quat q;
        double S[3][3], T[3][3], best;
        a.x = ref_rng_range(&rng, -1, 1);
        a.y = ref_rng_range(&rng, -1, 1);
        a.z = ref_rng_range(&rng, -1, 1);
        q = ref_quat_from_axis_angle(a, 2.0 * REF_PI / 3.0 - ref_rng_range(&rng, 0.0, 0.05));
        for (i = 0; i < 3; i++)
            for (j = i; j < 3; j++) S[i][j] = S[j][i] = ref_rng_range(&rng, -1, 1);
        best = direct_edge_error(q, S);
        for (st = 0; st < 300; st++) {
            ref_quat qq = q;
            double e;
            qq.w += ref_rng_range(&rng, -5e-4, 5e-4); qq.x += ref_rng_range(&rng, -5e-4, 5e-4);
            qq.y += ref_rng_range(&rng, -5e-4, 5e-4); qq.z += ref_rng_range(&rng, -5e-4, 5e-4);
            for (i = 0; i < 3; i++)
                for (j = i; j < 3; j++)
                    T[i][j] = T[j][i] = S[i][j] + ref_rng_range(&rng, -0.05, 0.05);
            e = direct_edge_error(qq, T);
            if (e > best) {
                best = e;
                q = qq;
                memcpy(S, T, sizeof S);
            }
        }
        if (best > worst) worst = best;
    }
    print_message("from_mat3 direct side: worst %.3g rad from the nearest rotation\n", worst);
    if (!(worst <= 1e-6)) fail_msg("from_mat3: %.3g rad from the nearest rotation", worst);
    assert_true(worst > 6e-7);
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
        if (qo_mat3_to_quat_f32(&bad, &q) != QO_E_NOT_ROTATION || !same_quat_bits(q, qo_quat_identity_f32()))
            fail_msg("from_mat3 case %d: reflection -R not refused with the identity", n);
        for (k = 0; k < 9; k++) {
            const float v[3] = { NAN, INFINITY, 1e30f };
            const qo_status want[3] = { QO_E_NONFINITE, QO_E_NONFINITE, QO_E_NOT_ROTATION };
            int c;
            for (c = 0; c < 3; c++) {
                bad = m;
                bad.m[k / 3][k % 3] = v[c];
                q.w = 7.0f;
                if (qo_mat3_to_quat_f32(&bad, &q) != want[c] ||
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
            qo_status st0 = qo_euler_from_quat_f32(q, (qo_euler_seq)s, &e0, &i0);
            if (st0 != QO_OK) fail_msg("to_euler case %d seq %d: status %d", n, s, (int)st0);
            for (k = 0; k < sizeof ks / sizeof ks[0]; k++) {
                float f = ldexpf(1.0f, ks[k]);
                qo_quat_f32 qs;
                qs.w = q.w * f; qs.x = q.x * f; qs.y = q.y * f; qs.z = q.z * f;
                if (qo_euler_from_quat_f32(qs, (qo_euler_seq)s, &e, &i) != QO_OK ||
                    memcmp(&e, &e0, sizeof e) != 0 || i.locked != i0.locked ||
                    memcmp(&i.margin, &i0.margin, sizeof i.margin) != 0)
                    fail_msg("to_euler case %d seq %d: q * 2^%d gives (%.9g, %.9g, %.9g), "
                             "q gives (%.9g, %.9g, %.9g)", n, s, ks[k], (double)e.a1,
                             (double)e.a2, (double)e.a3, (double)e0.a1, (double)e0.a2,
                             (double)e0.a3);
                /* without info: the same angles (the margin shortcut only skips work) */
                if (qo_euler_from_quat_f32(qs, (qo_euler_seq)s, &e, NULL) != QO_OK ||
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
            st = qo_euler_from_quat_f32(b, QO_EULER_ZYX, &e, &info);
            if (st != want[c] || (st != QO_OK && (e.a1 != 0.0f || e.a2 != 0.0f || e.a3 != 0.0f)))
                fail_msg("to_euler: component %d = %g gives status %d, want %d", k, (double)bad[c],
                         (int)st, (int)want[c]);
        }
    }
    assert_int_equal(qo_euler_from_quat_f32(z, QO_EULER_XYZ, &e, &info), QO_E_DEGENERATE);
    assert_true(e.a1 == 0.0f && e.a2 == 0.0f && e.a3 == 0.0f && info.locked == 0);
    assert_int_equal(qo_euler_from_quat_f32(q, QO_EULER_SEQ_COUNT_, &e, NULL), QO_E_ARG);
    assert_int_equal(qo_euler_from_quat_f32(q, (qo_euler_seq)-1, &e, NULL), QO_E_ARG);
    assert_int_equal(qo_euler_from_quat_f32(q, QO_EULER_XYZ, NULL, &info), QO_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_from_mat3_direct_threshold),
        cmocka_unit_test(test_from_mat3_direct_worst),
        cmocka_unit_test(test_from_mat3_fast_path_errors),
        cmocka_unit_test(test_to_euler_fast_range),
        cmocka_unit_test(test_to_euler_fast_range_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
