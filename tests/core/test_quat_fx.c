/* Fixed-point quaternion algebra (qorient/quat_fx.h) against double / long double references
 * written here, over fixed-seed random rotations (inputs enter through qorient/fxconv.h). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <cmocka.h>

#include "common/dq.h"
#include "qorient/fxconv.h"
#include "qorient/fxmath.h"
#include "qorient/quat_fx.h"

#define TWO30 1073741824.0
#define TWO28 268435456.0

/* The double-precision reference and the fixed-seed PRNG are tests/common/ref.c (dq.h). */
static ref_rng rng;

#define QFMT "(%ld %ld %ld %ld)"
#define QARG(q) (long)(q).w, (long)(q).x, (long)(q).y, (long)(q).z

static void test_identity_conj_inverse_canonical(void **state)
{
    qo_quat_q30 q = { -5, 6, -7, INT32_MIN }, c;
    static const struct { qo_quat_q30 in, want; } canon[] = {
        { { 1, -2, 3, -4 }, { 1, -2, 3, -4 } },
        { { -1, -2, 3, -4 }, { 1, 2, -3, 4 } },
        { { 0, -2, 3, -4 }, { 0, 2, -3, 4 } },
        { { 0, 0, -3, 4 }, { 0, 0, 3, -4 } },
        { { 0, 0, 0, -4 }, { 0, 0, 0, 4 } },
        { { 0, 0, 0, 0 }, { 0, 0, 0, 0 } },
        { { 0, 2, -3, 4 }, { 0, 2, -3, 4 } },
        { { INT32_MIN, 0, 0, 0 }, { INT32_MAX, 0, 0, 0 } },
    };
    size_t i;
    (void)state;
    c = qo_quat_identity_q30();
    assert_int_equal(c.w, QO_Q30_ONE); assert_int_equal(c.x, 0); assert_int_equal(c.y, 0); assert_int_equal(c.z, 0);
    c = qo_quat_conj_q30(q);
    assert_int_equal(c.w, -5); assert_int_equal(c.x, -6); assert_int_equal(c.y, 7);
    assert_int_equal(c.z, INT32_MAX); /* -(-2.0) saturates */
    c = qo_quat_inverse_q30(q);
    assert_int_equal(c.x, -6); assert_int_equal(c.z, INT32_MAX);
    for (i = 0; i < sizeof canon / sizeof canon[0]; i++) {
        c = qo_quat_canonical_q30(canon[i].in);
        if (c.w != canon[i].want.w || c.x != canon[i].want.x || c.y != canon[i].want.y || c.z != canon[i].want.z)
            fail_msg("canonical" QFMT " = " QFMT, QARG(canon[i].in), QARG(c));
    }
}

static void test_mul_dot_norm(void **state)
{
    int k;
    qo_quat_q30 r;
    qo_quat_q30 big = { INT32_MIN, INT32_MIN, 0, 0 };
    (void)state;
    rng.s = 11;
    for (k = 0; k < 20000; k++) {
        qo_quat_q30 a = fx_from(ref_rng_quat(&rng)), b = fx_from(ref_rng_quat(&rng));
        long double w = (long double)a.w * b.w - (long double)a.x * b.x - (long double)a.y * b.y - (long double)a.z * b.z;
        long double x = (long double)a.w * b.x + (long double)a.x * b.w + (long double)a.y * b.z - (long double)a.z * b.y;
        long double y = (long double)a.w * b.y - (long double)a.x * b.z + (long double)a.y * b.w + (long double)a.z * b.x;
        long double z = (long double)a.w * b.z + (long double)a.x * b.y - (long double)a.y * b.x + (long double)a.z * b.w;
        long double d = (long double)a.w * b.w + (long double)a.x * b.x + (long double)a.y * b.y + (long double)a.z * b.z;
        long double n = sqrtl((long double)a.w * a.w + (long double)a.x * a.x + (long double)a.y * a.y + (long double)a.z * a.z);
        double e;
        r = qo_quat_mul_q30(a, b);
        e = (double)fabsl(r.w - w / TWO30);
        if ((double)fabsl(r.x - x / TWO30) > e) e = (double)fabsl(r.x - x / TWO30);
        if ((double)fabsl(r.y - y / TWO30) > e) e = (double)fabsl(r.y - y / TWO30);
        if ((double)fabsl(r.z - z / TWO30) > e) e = (double)fabsl(r.z - z / TWO30);
        if (e > 0.5 + 1e-6) fail_msg("mul " QFMT " * " QFMT ": %.3f LSB", QARG(a), QARG(b), e);
        e = (double)fabsl(qo_quat_dot_q30(a, b) - d / TWO30);
        if (e > 0.5 + 1e-6) fail_msg("dot " QFMT " . " QFMT ": %.3f LSB", QARG(a), QARG(b), e);
        e = (double)fabsl(qo_quat_norm_q30(a) - n);
        if (e > 0.5 + 1e-6) fail_msg("norm " QFMT ": %.3f LSB", QARG(a), e);
    }
    /* Saturation: non-unit inputs whose product leaves [-2, 2). */
    assert_int_equal(qo_quat_mul_q30_checked(big, big, &r), QO_E_OVERFLOW);
    assert_int_equal(r.x, INT32_MAX);   /* 2 * (-2)(-2) = 8 */
    assert_int_equal(r.w, 0);           /* 4 - 4 */
    r = qo_quat_mul_q30(big, big);
    assert_int_equal(r.x, INT32_MAX);
    assert_int_equal(qo_quat_mul_q30_checked(qo_quat_identity_q30(), big, &r), QO_OK);
    assert_int_equal(r.w, INT32_MIN);
    assert_int_equal(qo_quat_mul_q30_checked(big, big, NULL), QO_E_NULL);
    assert_int_equal(qo_quat_dot_q30(big, big), INT32_MAX);
    assert_int_equal(qo_quat_norm_q30(big), INT32_MAX);
    {
        qo_quat_q30 all = { INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN };
        assert_int_equal(qo_quat_norm_q30(all), INT32_MAX);
    }
}

/* The exact normalisation (1 LSB) and its fast tier (16 LSB, never beyond +-1.0) run through
 * the same checks. */
typedef struct norm_impl {
    const char *name;
    qo_status (*fn)(qo_quat_q30, qo_quat_q30 *);
    double bound_lsb;
} norm_impl;
static const norm_impl norm_impls[] = {
    { "normalize", qo_quat_normalize_q30, 1.0 },
    { "normalize_fast", qo_quat_normalize_fast_q30, 16.0 },
};

static void check_normalize(const norm_impl *f, qo_quat_q30 q)
{
    qo_quat_q30 r;
    dq want = ref_quat_normalize(ref_quat_from_q30(q));
    double e;
    assert_int_equal(f->fn(q, &r), QO_OK);
    e = ref_quat_err_lsb_q30(r, want);
    if (e > f->bound_lsb + 1e-6)
        fail_msg("%s " QFMT " = " QFMT ": %.3f LSB", f->name, QARG(q), QARG(r), e);
    if (r.w > QO_Q30_ONE || r.w < -QO_Q30_ONE || r.x > QO_Q30_ONE || r.x < -QO_Q30_ONE ||
        r.y > QO_Q30_ONE || r.y < -QO_Q30_ONE || r.z > QO_Q30_ONE || r.z < -QO_Q30_ONE)
        fail_msg("%s " QFMT " = " QFMT ": beyond 1", f->name, QARG(q), QARG(r));
}

static void test_normalize(void **state)
{
    qo_quat_q30 r, z = { 0, 0, 0, 0 };
    qo_quat_q30 edges[] = {
        { 1, 0, 0, 0 }, { 0, 0, 0, -1 }, { 1, 1, 1, 1 }, { 1, -1, 2, 0 },
        { INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN }, { INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX },
        { INT32_MIN, 0, 0, 0 }, { INT32_MAX, INT32_MIN, 1, -1 }, { QO_Q30_ONE, 0, 0, 0 },
        { 3, 4, 0, 0 }, { 1 << 29, 1 << 29, 1 << 29, 1 << 29 }, { (1 << 29) - 1, 0, 0, 0 },
        { 0x3FFFFFFF, 0x3FFFFFFF, 0x3FFFFFFF, 0x3FFFFFFF }, { 0, 1 << 30, 0, 1 << 30 },
        /* |q|^2 just below 2^60 (normalize_fast's 2^30 boundary of its scaled square) */
        { 717548339, 401245721, 510734886, 464970573 }, { 1 << 29, 1, 1, 1 },
    };
    size_t i, f;
    int k;
    (void)state;
    for (f = 0; f < sizeof norm_impls / sizeof norm_impls[0]; f++) {
        const norm_impl *n = &norm_impls[f];
        r.w = 7;
        assert_int_equal(n->fn(z, &r), QO_E_DEGENERATE);
        assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
        assert_int_equal(n->fn(z, NULL), QO_E_NULL);
        for (i = 0; i < sizeof edges / sizeof edges[0]; i++) check_normalize(n, edges[i]);
        /* Sign kept (-1 exactly for the exact one). */
        assert_int_equal(n->fn(edges[6], &r), QO_OK);
        assert_true(r.w >= -QO_Q30_ONE && r.w <= -QO_Q30_ONE + (int32_t)n->bound_lsb);
        if (n->bound_lsb <= 1.0) assert_int_equal(r.w, -QO_Q30_ONE);
        rng.s = 12;
        for (k = 0; k < 20000; k++) {
            /* Random directions at random scales, from a few LSB to the end of the range. */
            dq d = ref_rng_quat(&rng);
            double s = ldexp(1.0, -(int)(ref_rng_next(&rng) % 28u)) * (1.0 + ref_rng_unit(&rng));
            qo_quat_q30 q;
            q.w = qo_q30_from_f32((float)(d.w * s)); q.x = qo_q30_from_f32((float)(d.x * s));
            q.y = qo_q30_from_f32((float)(d.y * s)); q.z = qo_q30_from_f32((float)(d.z * s));
            if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) continue;
            check_normalize(n, q);
        }
        /* Raw int32 components of random magnitude (every scaling branch). */
        for (k = 0; k < 200000; k++) {
            unsigned sh = (unsigned)(ref_rng_next(&rng) % 32u);
            qo_quat_q30 q;
            q.w = (int32_t)(uint32_t)ref_rng_next(&rng) >> sh; q.x = (int32_t)(uint32_t)ref_rng_next(&rng) >> sh;
            q.y = (int32_t)(uint32_t)ref_rng_next(&rng) >> sh; q.z = (int32_t)(uint32_t)ref_rng_next(&rng) >> sh;
            if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) continue;
            check_normalize(n, q);
        }
    }
}

static void test_rotate(void **state)
{
    int k;
    qo_vec3_q30 r;
    (void)state;
    rng.s = 13;
    for (k = 0; k < 20000; k++) {
        qo_quat_q30 q;
        qo_vec3_q30 v;
        qo_vec3_f32 vf;
        dq dqq, p, out;
        double e, ex, ey, ez, vn;
        assert_int_equal(qo_quat_normalize_q30(fx_from(ref_rng_quat(&rng)), &q), QO_OK);
        vf.x = (float)ref_rng_range(&rng, -1.0, 1.0); vf.y = (float)ref_rng_range(&rng, -1.0, 1.0); vf.z = (float)ref_rng_range(&rng, -1.0, 1.0);
        vn = sqrt((double)vf.x * vf.x + (double)vf.y * vf.y + (double)vf.z * vf.z);
        if (vn > 1.0) { vf.x = (float)(vf.x / vn); vf.y = (float)(vf.y / vn); vf.z = (float)(vf.z / vn); }
        v = qo_vec3_q30_from_f32(vf);
        /* Reference: the sandwich q (0, v) q* in double with the exact fixed inputs. */
        dqq = ref_quat_from_q30(q);
        p.w = 0; p.x = v.x / TWO30; p.y = v.y / TWO30; p.z = v.z / TWO30;
        out = dq_mul(dq_mul(dqq, p), (dq){ dqq.w, -dqq.x, -dqq.y, -dqq.z });
        r = qo_quat_rotate_q30(q, v);
        ex = fabs(r.x - out.x * TWO30); ey = fabs(r.y - out.y * TWO30); ez = fabs(r.z - out.z * TWO30);
        e = ex > ey ? ex : ey; if (ez > e) e = ez;
        /* 2 LSB of rounding plus |q|^2 - 1 (within 2^-29 after normalisation) times |v|. */
        if (e > 4.0) fail_msg("rotate " QFMT " (%ld %ld %ld): %.3f LSB", QARG(q), (long)v.x, (long)v.y, (long)v.z, e);
    }
    /* Identity leaves v alone exactly; saturation for absurd inputs stays defined. */
    r = qo_quat_rotate_q30(qo_quat_identity_q30(), (qo_vec3_q30){ 123, INT32_MIN, INT32_MAX });
    assert_int_equal(r.x, 123); assert_int_equal(r.y, INT32_MIN); assert_int_equal(r.z, INT32_MAX);
    r = qo_quat_rotate_q30((qo_quat_q30){ INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN },
                           (qo_vec3_q30){ INT32_MIN, INT32_MAX, INT32_MIN });
    /* (The call above must merely be free of overflow UB: UBSan aborts the test otherwise.)
     * The zero quaternion leaves v unchanged (t = 0). */
    r = qo_quat_rotate_q30((qo_quat_q30){ 0, 0, 0, 0 }, (qo_vec3_q30){ 5, -6, 7 });
    assert_int_equal(r.x, 5); assert_int_equal(r.y, -6); assert_int_equal(r.z, 7);
    /* 90 degrees about z takes x to y. */
    {
        qo_quat_q30 qz = { 759250125, 0, 0, 759250125 };   /* (cos 45, 0, 0, sin 45) */
        r = qo_quat_rotate_q30(qz, (qo_vec3_q30){ QO_Q30_ONE, 0, 0 });
        assert_true(r.x >= -2 && r.x <= 2 && r.y >= QO_Q30_ONE - 2 && r.y <= QO_Q30_ONE + 2 && r.z == 0);
    }
}

static void test_angle_between(void **state)
{
    int k;
    qo_quat_q30 a, na;
    (void)state;
    rng.s = 14;
    for (k = 0; k < 20000; k++) {
        dq da = ref_rng_quat(&rng), db, r;
        qo_quat_q30 b;
        double vn, want, e;
        qo_q28 got;
        a = fx_from(da);
        /* Half the pairs close together (small angles), some near antipodal. */
        if (k % 3 == 0) {
            dq dd = { 1.0, 1e-5 * ref_rng_range(&rng, -1.0, 1.0), 1e-5 * ref_rng_range(&rng, -1.0, 1.0), 1e-5 * ref_rng_range(&rng, -1.0, 1.0) };
            db = dq_mul(da, ref_quat_normalize(dd));
            if (k % 2) { db.w = -db.w; db.x = -db.x; db.y = -db.y; db.z = -db.z; }
        } else {
            db = ref_rng_quat(&rng);
        }
        b = fx_from(db);
        r = dq_mul((dq){ a.w / TWO30, -a.x / TWO30, -a.y / TWO30, -a.z / TWO30 }, ref_quat_from_q30(b));
        vn = sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
        want = 2.0 * atan2(vn, fabs(r.w)) * TWO28;
        got = qo_quat_angle_between_q30(a, b);
        e = fabs(got - want);
        if (e > 2.0 || got < 0 || got > QO_Q28_PI) fail_msg("angle_between " QFMT " " QFMT " = %ld: %.3f LSB", QARG(a), QARG(b), (long)got, e);
    }
    a = fx_from(ref_rng_quat(&rng));
    assert_int_equal(qo_quat_angle_between_q30(a, a), 0);
    na.w = -a.w; na.x = -a.x; na.y = -a.y; na.z = -a.z;
    assert_int_equal(qo_quat_angle_between_q30(a, na), 0);
    /* Exactly pi: identity vs 180 degrees about x. */
    assert_true(qo_quat_angle_between_q30(qo_quat_identity_q30(), (qo_quat_q30){ 0, QO_Q30_ONE, 0, 0 }) >= QO_Q28_PI - 2);
}

static void test_exp_log(void **state)
{
    int k;
    qo_quat_q30 r;
    qo_vec3_q28 v;
    (void)state;
    /* Edges. */
    assert_int_equal(qo_quat_exp_q30((qo_vec3_q28){ 0, 0, 0 }, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
    assert_int_equal(qo_quat_exp_q30((qo_vec3_q28){ 4 * QO_Q28_ONE, 0, 0 }, &r), QO_E_RANGE);
    assert_int_equal(r.w, QO_Q30_ONE);
    assert_int_equal(qo_quat_exp_q30((qo_vec3_q28){ 0, INT32_MIN, 0 }, &r), QO_E_RANGE);
    assert_int_equal(qo_quat_exp_q30((qo_vec3_q28){ 0, 0, 0 }, NULL), QO_E_NULL);
    assert_int_equal(qo_quat_log_q30((qo_quat_q30){ 0, 0, 0, 0 }, &v), QO_E_DEGENERATE);
    assert_int_equal(v.x, 0); assert_int_equal(v.y, 0); assert_int_equal(v.z, 0);
    assert_int_equal(qo_quat_log_q30((qo_quat_q30){ -QO_Q30_ONE, 0, 0, 0 }, &v), QO_OK);
    assert_int_equal(v.x, QO_Q28_PI); assert_int_equal(v.y, 0);
    assert_int_equal(qo_quat_log_q30((qo_quat_q30){ 5, 0, 0, 0 }, &v), QO_OK);
    assert_int_equal(v.x, 0);
    assert_int_equal(qo_quat_log_q30(qo_quat_identity_q30(), NULL), QO_E_NULL);
    /* A tiny rotation: log (1, e) = (e) to the LSB. */
    assert_int_equal(qo_quat_log_q30((qo_quat_q30){ QO_Q30_ONE, 64, 0, 0 }, &v), QO_OK);
    assert_int_equal(v.x, 16);
    rng.s = 15;
    for (k = 0; k < 20000; k++) {
        double vx = 3.9 * ref_rng_range(&rng, -1.0, 1.0) / (1 + (double)(k % 4) * 100), vy = 3.9 * ref_rng_range(&rng, -1.0, 1.0), vz = 3.9 * ref_rng_range(&rng, -1.0, 1.0);
        qo_vec3_f32 f;
        double n, s, e;
        dq want, lq;
        qo_quat_q30 q;
        if (k % 2) { vy /= 1e4; vz /= 1e5; }
        f.x = (float)vx; f.y = (float)vy; f.z = (float)vz;
        v = qo_vec3_q28_from_f32(f);
        vx = v.x / TWO28; vy = v.y / TWO28; vz = v.z / TWO28;
        n = sqrt(vx * vx + vy * vy + vz * vz);
        s = n > 0 ? sin(n) / n : 1.0;
        want.w = cos(n); want.x = s * vx; want.y = s * vy; want.z = s * vz;
        assert_int_equal(qo_quat_exp_q30(v, &r), QO_OK);
        e = ref_quat_err_lsb_q30(r, want);
        if (e > 2.0) fail_msg("exp(%ld %ld %ld) = " QFMT ": %.3f LSB", (long)v.x, (long)v.y, (long)v.z, QARG(r), e);
        /* log of a random (non-canonical too) quaternion. */
        q = fx_from(ref_rng_quat(&rng));
        lq = ref_quat_from_q30(q);
        n = sqrt(lq.x * lq.x + lq.y * lq.y + lq.z * lq.z);
        s = atan2(n, lq.w) / n;
        assert_int_equal(qo_quat_log_q30(q, &v), QO_OK);
        e = fabs(v.x - s * lq.x * TWO28);
        if (fabs(v.y - s * lq.y * TWO28) > e) e = fabs(v.y - s * lq.y * TWO28);
        if (fabs(v.z - s * lq.z * TWO28) > e) e = fabs(v.z - s * lq.z * TWO28);
        if (e > 1.5) fail_msg("log " QFMT " = (%ld %ld %ld): %.3f LSB", QARG(q), (long)v.x, (long)v.y, (long)v.z, e);
    }
}

static void test_integrate(void **state)
{
    int k;
    qo_quat_q30 r;
    (void)state;
    assert_int_equal(qo_quat_integrate_q30((qo_quat_q30){ 0, 0, 0, 0 }, (qo_vec3_q28){ 1, 2, 3 }, &r), QO_E_DEGENERATE);
    assert_int_equal(r.w, QO_Q30_ONE); assert_int_equal(r.x, 0);
    assert_int_equal(qo_quat_integrate_q30(qo_quat_identity_q30(), (qo_vec3_q28){ 1, 2, 3 }, NULL), QO_E_NULL);
    /* Zero increment: q normalised. */
    assert_int_equal(qo_quat_integrate_q30((qo_quat_q30){ 2 * 3, 0, 0, 0 }, (qo_vec3_q28){ 0, 0, 0 }, &r), QO_OK);
    assert_int_equal(r.w, QO_Q30_ONE);
    rng.s = 16;
    for (k = 0; k < 20000; k++) {
        qo_quat_q30 q = fx_from(ref_rng_quat(&rng));
        qo_vec3_f32 f;
        qo_vec3_q28 d;
        dq dd, want;
        double n, s, scale = k % 2 ? 1e-4 : 3.0;
        f.x = (float)(scale * ref_rng_range(&rng, -1.0, 1.0)); f.y = (float)(scale * ref_rng_range(&rng, -1.0, 1.0)); f.z = (float)(scale * ref_rng_range(&rng, -1.0, 1.0));
        d = qo_vec3_q28_from_f32(f);
        n = sqrt((double)d.x * d.x + (double)d.y * d.y + (double)d.z * d.z) / TWO28;
        s = n > 0 ? sin(n / 2) / n : 0.5;
        dd.w = cos(n / 2); dd.x = s * d.x / TWO28; dd.y = s * d.y / TWO28; dd.z = s * d.z / TWO28;
        want = ref_quat_normalize(dq_mul(ref_quat_normalize(ref_quat_from_q30(q)), dd));
        assert_int_equal(qo_quat_integrate_q30(q, d, &r), QO_OK);
        if (ref_quat_err_lsb_q30(r, want) > 4.0) fail_msg("integrate " QFMT " by (%ld %ld %ld): %.3f LSB", QARG(q), (long)d.x, (long)d.y, (long)d.z, ref_quat_err_lsb_q30(r, want));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_identity_conj_inverse_canonical),
        cmocka_unit_test(test_mul_dot_norm),
        cmocka_unit_test(test_normalize),
        cmocka_unit_test(test_rotate),
        cmocka_unit_test(test_angle_between),
        cmocka_unit_test(test_exp_log),
        cmocka_unit_test(test_integrate),
    };
    return cmocka_run_group_tests_name("quat_fx", tests, NULL, NULL);
}
