/* Fixed-point rotation conversions (qorient/convert_fx.h) against double references written
 * here, over fixed-seed random rotations; inputs enter through qorient/fxconv.h. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <cmocka.h>

#include "common/dq.h"
#include "qorient/convert_fx.h"
#include "qorient/fxconv.h"
#include "qorient/fxmath.h"
#include "qorient/quat_fx.h"

#define TWO30 1073741824.0
#define TWO28 268435456.0

/* The double-precision reference and the fixed-seed PRNG are tests/common/ref.c (dq.h). */
static ref_rng rng;

#define QFMT "(%ld %ld %ld %ld)"
#define QARG(q) (long)(q).w, (long)(q).x, (long)(q).y, (long)(q).z

static void test_axis_angle(void **state)
{
    qo_quat_q30 r;
    qo_vec3_q30 ax;
    qo_q28 an;
    int k;
    (void)state;
    /* Edges: zero axis, NULLs, identity, zero vector part, zero quaternion, exactly pi. */
    assert_int_equal(qo_quat_from_axis_angle_q30((qo_vec3_q30){ 0, 0, 0 }, QO_Q28_ONE, &r), QO_E_DEGENERATE);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
    assert_int_equal(qo_quat_from_axis_angle_q30((qo_vec3_q30){ 1, 0, 0 }, 0, NULL), QO_E_NULL);
    assert_int_equal(qo_quat_to_axis_angle_q30(qo_quat_identity_q30(), &ax, &an), QO_OK);
    assert_int_equal(ax.x, QO_Q30_ONE); assert_int_equal(ax.y, 0); assert_int_equal(ax.z, 0); assert_int_equal(an, 0);
    assert_int_equal(qo_quat_to_axis_angle_q30((qo_quat_q30){ -77, 0, 0, 0 }, &ax, &an), QO_OK);
    assert_int_equal(ax.x, QO_Q30_ONE); assert_int_equal(an, 0);
    assert_int_equal(qo_quat_to_axis_angle_q30((qo_quat_q30){ 0, 0, 0, 0 }, &ax, &an), QO_E_DEGENERATE);
    assert_int_equal(ax.x, QO_Q30_ONE); assert_int_equal(an, 0);
    an = 99;
    assert_int_equal(qo_quat_to_axis_angle_q30(qo_quat_identity_q30(), NULL, &an), QO_E_NULL);
    assert_int_equal(an, 0);
    assert_int_equal(qo_quat_to_axis_angle_q30((qo_quat_q30){ 0, 0, -QO_Q30_ONE, 0 }, &ax, &an), QO_OK);
    assert_int_equal(ax.y, QO_Q30_ONE);   /* canonical sign at pi */
    assert_true(an >= QO_Q28_PI - 2 && an <= QO_Q28_PI);
    /* A 1-LSB axis keeps its direction. */
    assert_int_equal(qo_quat_from_axis_angle_q30((qo_vec3_q30){ 0, -1, 0 }, QO_Q28_PI, &r), QO_OK);
    assert_true(r.y <= -QO_Q30_ONE + 1 && r.x == 0 && r.z == 0 && r.w >= -1 && r.w <= 1);
    rng.s = 21;
    for (k = 0; k < 20000; k++) {
        double axd[3] = { ref_rng_range(&rng, -1.0, 1.0), ref_rng_range(&rng, -1.0, 1.0), ref_rng_range(&rng, -1.0, 1.0) }, sc = ldexp(1.0, -(int)(ref_rng_next(&rng) % 29u));
        double angle = 7.99 * ref_rng_range(&rng, -1.0, 1.0), n, s, e;
        qo_vec3_f32 f;
        qo_vec3_q30 a;
        qo_q28 ang;
        dq want, back;
        f.x = (float)(axd[0] * sc); f.y = (float)(axd[1] * sc); f.z = (float)(axd[2] * sc);
        a = qo_vec3_q30_from_f32(f);
        ang = qo_q28_from_f32((float)angle);
        if (a.x == 0 && a.y == 0 && a.z == 0) continue;
        n = sqrt((double)a.x * a.x + (double)a.y * a.y + (double)a.z * a.z);
        s = sin(ang / TWO28 / 2);
        want.w = cos(ang / TWO28 / 2); want.x = s * a.x / n; want.y = s * a.y / n; want.z = s * a.z / n;
        assert_int_equal(qo_quat_from_axis_angle_q30(a, ang, &r), QO_OK);
        e = ref_quat_err_lsb_q30(r, want);
        if (e > 1.5) fail_msg("from_axis_angle (%ld %ld %ld) %ld = " QFMT ": %.3f LSB", (long)a.x, (long)a.y, (long)a.z, (long)ang, QARG(r), e);
        /* Back: axis and angle of a random quaternion against the double formula. */
        r = fx_from(ref_rng_quat(&rng));
        back = ref_quat_canonical(ref_quat_normalize(ref_quat_from_q30(r)));
        n = sqrt(back.x * back.x + back.y * back.y + back.z * back.z);
        assert_int_equal(qo_quat_to_axis_angle_q30(r, &ax, &an), QO_OK);
        e = fabs(an - 2 * atan2(n, back.w) * TWO28);
        if (e > 3.0) fail_msg("to_axis_angle " QFMT " angle %ld: %.3f LSB", QARG(r), (long)an, e);
        e = fabs(ax.x - back.x / n * TWO30);
        if (fabs(ax.y - back.y / n * TWO30) > e) e = fabs(ax.y - back.y / n * TWO30);
        if (fabs(ax.z - back.z / n * TWO30) > e) e = fabs(ax.z - back.z / n * TWO30);
        if (e > 3.0) fail_msg("to_axis_angle " QFMT " axis: %.3f LSB", QARG(r), e);
    }
}

static void test_rotvec(void **state)
{
    qo_quat_q30 r;
    qo_vec3_q28 v;
    int k;
    (void)state;
    assert_int_equal(qo_quat_from_rotvec_q30((qo_vec3_q28){ 0, 0, 0 }, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0); assert_int_equal(r.y, 0); assert_int_equal(r.z, 0);
    assert_int_equal(qo_quat_from_rotvec_q30((qo_vec3_q28){ 0, 0, 0 }, NULL), QO_E_NULL);
    /* Tiny: (1, rv/2) to the LSB. rv = 4 LSB of Q3.28 = 16 LSB of Q1.30 -> 8. */
    assert_int_equal(qo_quat_from_rotvec_q30((qo_vec3_q28){ 0, 0, 4 }, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.z, 8);
    /* The largest rotation vector the format holds does not overflow anything. */
    assert_int_equal(qo_quat_from_rotvec_q30((qo_vec3_q28){ INT32_MIN, INT32_MIN, INT32_MIN }, &r), QO_OK);
    assert_int_equal(qo_quat_to_rotvec_q30((qo_quat_q30){ 0, 0, 0, 0 }, &v), QO_E_DEGENERATE);
    assert_int_equal(v.x, 0); assert_int_equal(v.y, 0); assert_int_equal(v.z, 0);
    assert_int_equal(qo_quat_to_rotvec_q30(qo_quat_identity_q30(), NULL), QO_E_NULL);
    assert_int_equal(qo_quat_to_rotvec_q30((qo_quat_q30){ -QO_Q30_ONE, 0, 0, 0 }, &v), QO_OK);
    assert_int_equal(v.x, 0);
    /* Exactly pi about -z: canonical sign makes it +z. */
    assert_int_equal(qo_quat_to_rotvec_q30((qo_quat_q30){ 0, 0, 0, -QO_Q30_ONE }, &v), QO_OK);
    assert_true(v.z >= QO_Q28_PI - 2 && v.z <= QO_Q28_PI && v.x == 0 && v.y == 0);
    rng.s = 22;
    for (k = 0; k < 20000; k++) {
        double sc = k % 3 == 0 ? 1e-6 : k % 3 == 1 ? 3.1 : 7.9, n, s, e, a[3];
        qo_vec3_f32 f;
        qo_vec3_q28 rv;
        dq want, q;
        f.x = (float)(sc * ref_rng_range(&rng, -1.0, 1.0)); f.y = (float)(sc * ref_rng_range(&rng, -1.0, 1.0)); f.z = (float)(sc * ref_rng_range(&rng, -1.0, 1.0));
        rv = qo_vec3_q28_from_f32(f);
        a[0] = rv.x / TWO28; a[1] = rv.y / TWO28; a[2] = rv.z / TWO28;
        n = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        s = n > 0 ? sin(n / 2) / n : 0.5;
        want.w = cos(n / 2); want.x = s * a[0]; want.y = s * a[1]; want.z = s * a[2];
        assert_int_equal(qo_quat_from_rotvec_q30(rv, &r), QO_OK);
        e = ref_quat_err_lsb_q30(r, want);
        if (e > 2.0) fail_msg("from_rotvec (%ld %ld %ld) = " QFMT ": %.3f LSB", (long)rv.x, (long)rv.y, (long)rv.z, QARG(r), e);
        /* to_rotvec of random rotations, including near-identity and near-pi ones. */
        q = ref_rng_quat(&rng);
        if (k % 4 == 1) { q.w = 1.0; q.x *= 1e-6; q.y *= 1e-6; q.z *= 1e-6; }
        if (k % 4 == 2) { q.w *= 1e-6; }
        r = fx_from(q);
        q = ref_quat_canonical(ref_quat_from_q30(r));
        n = sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
        s = n > 0 ? 2 * atan2(n, q.w) / n : 2.0 / q.w;
        assert_int_equal(qo_quat_to_rotvec_q30(r, &v), QO_OK);
        e = fabs(v.x - s * q.x * TWO28);
        if (fabs(v.y - s * q.y * TWO28) > e) e = fabs(v.y - s * q.y * TWO28);
        if (fabs(v.z - s * q.z * TWO28) > e) e = fabs(v.z - s * q.z * TWO28);
        if (e > 3.0) fail_msg("to_rotvec " QFMT " = (%ld %ld %ld): %.3f LSB", QARG(r), (long)v.x, (long)v.y, (long)v.z, e);
    }
}

static void test_to_mat3_and_mul_vec3(void **state)
{
    qo_mat3_q30 m;
    qo_vec3_q30 r;
    int k, i, j;
    (void)state;
    assert_int_equal(qo_quat_to_mat3_q30((qo_quat_q30){ 0, 0, 0, 0 }, &m), QO_E_DEGENERATE);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) assert_int_equal(m.m[i][j], i == j ? QO_Q30_ONE : 0);
    assert_int_equal(qo_quat_to_mat3_q30(qo_quat_identity_q30(), NULL), QO_E_NULL);
    r = qo_mat3_mul_vec3_q30(NULL, (qo_vec3_q30){ 1, 2, 3 });
    assert_int_equal(r.x, 0); assert_int_equal(r.y, 0); assert_int_equal(r.z, 0);
    rng.s = 23;
    for (k = 0; k < 20000; k++) {
        qo_quat_q30 q = fx_from(ref_rng_quat(&rng));
        double d[3][3], e = 0, vx, vy, vz;
        qo_vec3_q30 v, rq;
        qo_vec3_f32 f;
        long double ex, ey, ez;
        if (k % 5 == 0) { q.w /= 1000; q.x /= 1000; q.y /= 1000; q.z /= 1000; }   /* non-unit */
        dq_to_mat(ref_quat_normalize(ref_quat_from_q30(q)), d);
        assert_int_equal(qo_quat_to_mat3_q30(q, &m), QO_OK);
        for (i = 0; i < 3; i++) for (j = 0; j < 3; j++)
            if (fabs(m.m[i][j] - d[i][j] * TWO30) > e) e = fabs(m.m[i][j] - d[i][j] * TWO30);
        if (e > 3.0) fail_msg("to_mat3 " QFMT ": %.3f LSB", QARG(q), e);
        /* M v against long double, and against rotate (same rotation). */
        f.x = (float)(0.57 * ref_rng_range(&rng, -1.0, 1.0)); f.y = (float)(0.57 * ref_rng_range(&rng, -1.0, 1.0)); f.z = (float)(0.57 * ref_rng_range(&rng, -1.0, 1.0));
        v = qo_vec3_q30_from_f32(f);
        r = qo_mat3_mul_vec3_q30(&m, v);
        ex = ((long double)m.m[0][0] * v.x + (long double)m.m[0][1] * v.y + (long double)m.m[0][2] * v.z) / TWO30;
        ey = ((long double)m.m[1][0] * v.x + (long double)m.m[1][1] * v.y + (long double)m.m[1][2] * v.z) / TWO30;
        ez = ((long double)m.m[2][0] * v.x + (long double)m.m[2][1] * v.y + (long double)m.m[2][2] * v.z) / TWO30;
        if (fabsl(r.x - ex) > 0.5L + 1e-6L || fabsl(r.y - ey) > 0.5L + 1e-6L || fabsl(r.z - ez) > 0.5L + 1e-6L)
            fail_msg("mat3_mul_vec3 case %d: off by more than 0.5 LSB", k);
        assert_int_equal(qo_quat_normalize_q30(q, &q), QO_OK);
        rq = qo_quat_rotate_q30(q, v);
        vx = fabs((double)rq.x - r.x); vy = fabs((double)rq.y - r.y); vz = fabs((double)rq.z - r.z);
        if (vx > 8 || vy > 8 || vz > 8) fail_msg("to_mat3 vs rotate " QFMT ": %.0f %.0f %.0f LSB apart", QARG(q), vx, vy, vz);
    }
    /* Saturation of M v: (2, 2, 2) . (2, 2, 2) = 12. */
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) m.m[i][j] = INT32_MIN;
    r = qo_mat3_mul_vec3_q30(&m, (qo_vec3_q30){ INT32_MIN, INT32_MIN, INT32_MIN });
    assert_int_equal(r.x, INT32_MAX);
}

static void check_from_mat3(const qo_mat3_q30 *m, const char *what)
{
    double d[3][3], e;
    int i, j;
    qo_quat_q30 r;
    dq want;
    qo_status st = qo_quat_from_mat3_q30(m, &r);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) d[i][j] = m->m[i][j] / TWO30;
    want = dq_from_mat(d);
    if (st != QO_OK) fail_msg("from_mat3 %s: status %d", what, st);
    if (r.w < 0) fail_msg("from_mat3 %s: not canonical " QFMT, what, QARG(r));
    e = ref_quat_err_lsb_q30(r, want);
    /* At w == 0 (exact half turns) both signs are canonical candidates: compare either. */
    if (e > 3.0) {
        dq nw = { -want.w, -want.x, -want.y, -want.z };
        if (!(fabs(want.w) < 1e-8 && ref_quat_err_lsb_q30(r, nw) <= 3.0)) fail_msg("from_mat3 %s = " QFMT ": %.3f LSB", what, QARG(r), e);
    }
}

static void test_from_mat3(void **state)
{
    static const double half_turns[][4] = {
        { 0, 1, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 0, 1 }, { 0, 0.70710678118654752, 0.70710678118654752, 0 },
        { 0, 0.57735026918962576, -0.57735026918962576, 0.57735026918962576 }, { 1, 0, 0, 0 },
        { 0.70710678118654752, 0.70710678118654752, 0, 0 }, { 1e-4, 0, 0.99999999500000, 0 },
    };
    qo_mat3_q30 m, bad;
    qo_quat_q30 r;
    double d[3][3];
    size_t c;
    int k, i, j;
    (void)state;
    assert_int_equal(qo_quat_from_mat3_q30(NULL, &r), QO_E_NULL);
    assert_int_equal(r.w, QO_Q30_ONE);
    assert_int_equal(qo_quat_from_mat3_q30(&m, NULL), QO_E_NULL);
    for (c = 0; c < sizeof half_turns / sizeof half_turns[0]; c++) {
        dq q = ref_quat_normalize((dq){ half_turns[c][0], half_turns[c][1], half_turns[c][2], half_turns[c][3] });
        qo_mat3_f32 f;
        dq_to_mat(q, d);
        for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) f.m[i][j] = (float)d[i][j];
        m = qo_mat3_q30_from_f32(&f);
        check_from_mat3(&m, "edge");
    }
    /* Rejections: reflection, scale, shear, singular, and a just-inside / just-outside pair. */
    dq_to_mat(ref_quat_normalize((dq){ 0.3, 0.5, -0.2, 0.7 }), d);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) m.m[i][j] = qo_q30_from_f32((float)d[i][j]);
    bad = m;
    for (j = 0; j < 3; j++) bad.m[0][j] = -bad.m[0][j];
    assert_int_equal(qo_quat_from_mat3_q30(&bad, &r), QO_E_NOT_ROTATION);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
    bad = m;
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) bad.m[i][j] = qo_fx_mul_q30(bad.m[i][j], QO_Q30_ONE + QO_Q30_ONE / 1000);
    assert_int_equal(qo_quat_from_mat3_q30(&bad, &r), QO_E_NOT_ROTATION);
    bad = m; bad.m[0][1] += QO_Q30_ONE / 100;
    assert_int_equal(qo_quat_from_mat3_q30(&bad, &r), QO_E_NOT_ROTATION);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) bad.m[i][j] = 0;
    assert_int_equal(qo_quat_from_mat3_q30(&bad, &r), QO_E_NOT_ROTATION);
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) bad.m[i][j] = INT32_MIN;
    assert_int_equal(qo_quat_from_mat3_q30(&bad, &r), QO_E_NOT_ROTATION);
    /* Identity scaled so the diagonal of M^T M is 1 + 0.9 tol (accepted) or 1 + 1.1 tol. */
    for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) bad.m[i][j] = 0;
    for (i = 0; i < 3; i++) bad.m[i][i] = QO_Q30_ONE + (QO_MAT3_ROTATION_TOL_Q30 * 9) / 20;
    assert_int_equal(qo_quat_from_mat3_q30(&bad, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE);
    for (i = 0; i < 3; i++) bad.m[i][i] = QO_Q30_ONE + (QO_MAT3_ROTATION_TOL_Q30 * 11) / 20;
    assert_int_equal(qo_quat_from_mat3_q30(&bad, &r), QO_E_NOT_ROTATION);
    rng.s = 24;
    for (k = 0; k < 20000; k++) {
        dq q = ref_rng_quat(&rng);
        qo_mat3_f32 f;
        if (k % 4 == 1) { q.w *= 1e-5; q = ref_quat_normalize(q); }            /* near half turn */
        if (k % 4 == 2) { q.x *= 1e-5; q.y *= 1e-5; q.z *= 1e-5; q = ref_quat_normalize(q); }  /* near identity */
        dq_to_mat(q, d);
        for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) f.m[i][j] = (float)d[i][j];
        m = qo_mat3_q30_from_f32(&f);
        check_from_mat3(&m, "random");
    }
}

static void test_round_trips(void **state)
{
    int k;
    (void)state;
    rng.s = 25;
    for (k = 0; k < 5000; k++) {
        qo_quat_q30 q, back;
        qo_mat3_q30 m;
        qo_vec3_q28 rv;
        qo_vec3_q30 ax;
        qo_q28 an;
        assert_int_equal(qo_quat_normalize_q30(fx_from(ref_rng_quat(&rng)), &q), QO_OK);
        q = qo_quat_canonical_q30(q);
        assert_int_equal(qo_quat_to_mat3_q30(q, &m), QO_OK);
        assert_int_equal(qo_quat_from_mat3_q30(&m, &back), QO_OK);
        if (qo_quat_angle_between_q30(q, back) > 16) fail_msg("mat3 round trip " QFMT " -> " QFMT, QARG(q), QARG(back));
        assert_int_equal(qo_quat_to_rotvec_q30(q, &rv), QO_OK);
        assert_int_equal(qo_quat_from_rotvec_q30(rv, &back), QO_OK);
        if (qo_quat_angle_between_q30(q, back) > 16) fail_msg("rotvec round trip " QFMT " -> " QFMT, QARG(q), QARG(back));
        assert_int_equal(qo_quat_to_axis_angle_q30(q, &ax, &an), QO_OK);
        assert_int_equal(qo_quat_from_axis_angle_q30(ax, an, &back), QO_OK);
        if (qo_quat_angle_between_q30(q, back) > 16) fail_msg("axis-angle round trip " QFMT " -> " QFMT, QARG(q), QARG(back));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_axis_angle),
        cmocka_unit_test(test_rotvec),
        cmocka_unit_test(test_to_mat3_and_mul_vec3),
        cmocka_unit_test(test_from_mat3),
        cmocka_unit_test(test_round_trips),
    };
    return cmocka_run_group_tests_name("convert_fx", tests, NULL, NULL);
}
