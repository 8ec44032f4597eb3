/*
 * qorient/fmath.h: every kernel against double-precision libm (an independent computation:
 * glibc's correctly reduced double functions) over strided sweeps of the whole float domain,
 * dense sweeps of the ranges the core uses, the floats nearest multiples of pi/2 (the hard
 * cases of range reduction) and the edges (+-0, subnormals, FLT_MAX, +-Inf, NaN). The bounds
 * checked are the ones qorient/fmath.h states; the measured worst cases are printed.
 */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "common/ref.h"
#include "qorient/fmath.h"

/* The stated bounds, in ulp of the correctly rounded result (qorient/fmath.h). */
#define BOUND_SINCOS 1.0
#define BOUND_ATAN2 1.5
#define BOUND_ASINCOS 2.0
#define BOUND_EXPLOG 1.0

/* Sweep density: the emulated Cortex-M targets run double libm in software, ~100x slower, so
 * there the strided sweeps take every 16th point of the host's (the edges are all kept). */
#if defined(__arm__) && !defined(__linux__)
#define SPARSE 16u
#else
#define SPARSE 1u
#endif

static float f_of(uint32_t u)
{
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static int same_bits(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* |got - ref| in ulp of ref rounded to float (ulp of the binade of |ref|, 2^-149 at the
 * bottom). Special values must match exactly: NaN for NaN, same Inf, same signed zero. */
static double ulp_err(float got, double ref)
{
    int e;
    double ulp;
    if (isnan(ref)) return isnan(got) ? 0.0 : 1e30;
    if (isnan(got)) return 1e30;
    if (isinf((float)ref)) return ((double)got == (double)(float)ref) ? 0.0 : 1e30;
    if (ref == 0.0) return (got == 0.0f && !signbit(got) == !signbit(ref)) ? 0.0 : 1e30;
    (void)frexp(fabs(ref), &e);
    ulp = ldexp(1.0, e - 24);
    if (ulp < ldexp(1.0, -149)) ulp = ldexp(1.0, -149);
    return fabs((double)got - ref) / ulp;
}

typedef struct worst { double err; float x, y; const char *name; double bound; } worst;

static void note(worst *w, double err, float x, float y)
{
    if (!(err <= w->err)) {
        w->err = err;
        w->x = x;
        w->y = y;
    }
}

static void check(const worst *w)
{
    printf("  %-6s worst %.3f ulp at (%.9e, %.9e), bound %.1f\n", w->name, w->err, (double)w->x,
           (double)w->y, w->bound);
    if (!(w->err <= w->bound))
        fail_msg("%s: %.3f ulp at x = %.9e (y = %.9e), bound %.1f", w->name, w->err, (double)w->x,
                 (double)w->y, w->bound);
}

static void one_sincos(worst *ws, worst *wc, float x)
{
    qo_fm_sincos_f32_t sc = qo_fm_sincos_f32(x);
    note(ws, ulp_err(sc.s, sin((double)x)), x, 0.0f);
    note(wc, ulp_err(sc.c, cos((double)x)), x, 0.0f);
    /* the single functions are the pair's members */
    if (!same_bits(sc.s, qo_fm_sin_f32(x))) note(ws, 1e30, x, 1.0f);
    if (!same_bits(sc.c, qo_fm_cos_f32(x))) note(wc, 1e30, x, 1.0f);
}

static void test_sincos(void **state)
{
    worst ws = { 0.0, 0.0f, 0.0f, "sin", BOUND_SINCOS }, wc = { 0.0, 0.0f, 0.0f, "cos", BOUND_SINCOS };
    uint32_t u;
    long k;
    int s;
    static const float edges[] = {
        0.0f, -0.0f, 0x1p-149f, -0x1p-149f, FLT_MIN, 0x1p-12f, 0x1.921fb4p-1f, 0x1.921fb6p-1f,
        0x1.921fb6p+0f, 0x1.921fb6p+1f, 0x1.2d97c8p+2f, 1e10f, 1e20f, 1e30f, 1e38f, FLT_MAX,
        -FLT_MAX, 0x1.ba1794p+101f, 0x1.bc3186p+64f, 105414350.0f, 8.35e22f
    };
    (void)state;
    /* the whole domain, every 97th bit pattern, both signs */
    for (u = 0; u < 0x7f800000u; u += 1009u * SPARSE)
        for (s = 0; s < 2; s++) one_sincos(&ws, &wc, f_of(u | (s ? 0x80000000u : 0u)));
    /* every float in [pi/4, 8 pi] with a stride of 5 (the core's half-angles and angles) */
    for (u = 0x3f490fdbu; u < 0x41c90fdbu; u += 23u * SPARSE) one_sincos(&ws, &wc, f_of(u));
    /* the floats nearest k pi/2 and their neighbours, k < 2^16 and some huge ones */
    for (k = 1; k < 65536; k += (k < 512) ? 1 : 97 * (long)SPARSE) {
        float x = (float)((double)k * (REF_PI / 2.0));
        uint32_t b;
        memcpy(&b, &x, sizeof b);
        for (u = b - 2u; u <= b + 2u; u++) one_sincos(&ws, &wc, f_of(u));
    }
    for (k = 0; k < (long)(sizeof edges / sizeof edges[0]); k++) one_sincos(&ws, &wc, edges[k]);
    check(&ws);
    check(&wc);
    /* specials */
    assert_true(isnan(qo_fm_sin_f32(INFINITY)) && isnan(qo_fm_cos_f32(-INFINITY)));
    assert_true(isnan(qo_fm_sin_f32(NAN)) && isnan(qo_fm_cos_f32(NAN)));
    assert_true(signbit(qo_fm_sin_f32(-0.0f)) && qo_fm_cos_f32(-0.0f) == 1.0f);
}

static void one_atan2(worst *w, float y, float x)
{
    note(w, ulp_err(qo_fm_atan2_f32(y, x), atan2((double)y, (double)x)), x, y);
}

static void test_atan2(void **state)
{
    worst w = { 0.0, 0.0f, 0.0f, "atan2", BOUND_ATAN2 };
    static const float sp[] = {
        0.0f, -0.0f, 0x1p-149f, -0x1p-149f, FLT_MIN, 1e-20f, 0.5f, 1.0f, -1.0f, 2.0f, 1e20f,
        FLT_MAX, -FLT_MAX, INFINITY, -INFINITY, 0.41421354f, 0.41421357f, 3.0f, -7.5f
    };
    ref_rng rng = { 0x5eedf00dULL };
    size_t i, j;
    long n;
    (void)state;
    /* every pair of the special table, Annex F cases included (NaN separately) */
    for (i = 0; i < sizeof sp / sizeof sp[0]; i++)
        for (j = 0; j < sizeof sp / sizeof sp[0]; j++) one_atan2(&w, sp[i], sp[j]);
    assert_true(isnan(qo_fm_atan2_f32(NAN, 1.0f)) && isnan(qo_fm_atan2_f32(1.0f, NAN)));
    /* random bit patterns (any magnitude ratio) and random points of [-2, 2]^2 */
    for (n = 0; n < 1000000 / (long)SPARSE; n++) {
        uint64_t r = ref_rng_next(&rng);
        float y = f_of((uint32_t)r), x = f_of((uint32_t)(r >> 32));
        if (isnan(x) || isnan(y)) continue;
        one_atan2(&w, y, x);
        one_atan2(&w, (float)ref_rng_range(&rng, -2.0, 2.0), (float)ref_rng_range(&rng, -2.0, 2.0));
    }
    /* dense around the octant boundaries (ratio near tan(pi/8), 1) and the axes */
    for (n = -20000; n <= 20000; n += (long)SPARSE) {
        float d = (float)n * 0x1p-24f;
        one_atan2(&w, 0.41421356f + d, 1.0f);
        one_atan2(&w, 1.0f + d, -1.0f);
        one_atan2(&w, -1.0f, 0.41421356f + d);
        one_atan2(&w, d, -1.0f);
    }
    check(&w);
}

static void test_asin_acos(void **state)
{
    worst wa = { 0.0, 0.0f, 0.0f, "asin", BOUND_ASINCOS }, wc = { 0.0, 0.0f, 0.0f, "acos", BOUND_ASINCOS };
    uint32_t u;
    int s;
    (void)state;
    for (u = 0; u <= 0x3f800000u; u += 401u * SPARSE) {
        for (s = 0; s < 2; s++) {
            float x = f_of(u | (s ? 0x80000000u : 0u));
            note(&wa, ulp_err(qo_fm_asin_f32(x), asin((double)x)), x, 0.0f);
            note(&wc, ulp_err(qo_fm_acos_f32(x), acos((double)x)), x, 0.0f);
        }
    }
    check(&wa);
    check(&wc);
    assert_true(isnan(qo_fm_asin_f32(1.0000001f)) && isnan(qo_fm_acos_f32(-1.0000001f)));
    assert_true(isnan(qo_fm_asin_f32(INFINITY)) && isnan(qo_fm_acos_f32(NAN)));
    assert_true(signbit(qo_fm_asin_f32(-0.0f)) && qo_fm_acos_f32(1.0f) == 0.0f);
}

static void test_exp_log(void **state)
{
    worst we = { 0.0, 0.0f, 0.0f, "exp", BOUND_EXPLOG }, wl = { 0.0, 0.0f, 0.0f, "log", BOUND_EXPLOG };
    uint32_t u;
    int s;
    (void)state;
    for (u = 0; u < 0x7f800000u; u += 1013u * SPARSE) {
        for (s = 0; s < 2; s++) {
            float x = f_of(u | (s ? 0x80000000u : 0u));
            double ref = exp((double)x);
            /* subnormal results: the 2^k scaling rounds twice; bound them by 1 ulp of 2^-149 */
            if (ref >= (double)FLT_MIN || ref == 0.0 || (float)ref == 0.0f)
                note(&we, ulp_err(qo_fm_exp_f32(x), ref), x, 0.0f);
            else if (fabs((double)qo_fm_exp_f32(x) - ref) > 0x1p-149)
                note(&we, 1e30, x, 0.0f);
        }
        note(&wl, ulp_err(qo_fm_log_f32(f_of(u)), log((double)f_of(u))), f_of(u), 0.0f);
    }
    /* dense where exp and log are used by the core: exp on [-10, 10], log on [0.5, 2] */
    for (u = 0x3f000000u; u < 0x40000000u; u += 11u * SPARSE) note(&wl, ulp_err(qo_fm_log_f32(f_of(u)), log((double)f_of(u))), f_of(u), 0.0f);
    for (u = 0; u < 0x41200000u; u += 211u * SPARSE)
        for (s = 0; s < 2; s++) {
            float x = f_of(u | (s ? 0x80000000u : 0u));
            note(&we, ulp_err(qo_fm_exp_f32(x), exp((double)x)), x, 0.0f);
        }
    check(&we);
    check(&wl);
    assert_true(qo_fm_exp_f32(88.72284f) == INFINITY && qo_fm_exp_f32(INFINITY) == INFINITY);
    assert_true(qo_fm_exp_f32(-INFINITY) == 0.0f && qo_fm_exp_f32(0.0f) == 1.0f);
    assert_true(isnan(qo_fm_exp_f32(NAN)) && isnan(qo_fm_log_f32(NAN)));
    assert_true(qo_fm_log_f32(0.0f) == -INFINITY && qo_fm_log_f32(-0.0f) == -INFINITY);
    assert_true(isnan(qo_fm_log_f32(-1.0f)) && qo_fm_log_f32(INFINITY) == INFINITY);
    assert_true(qo_fm_log_f32(1.0f) == 0.0f && !signbit(qo_fm_log_f32(1.0f)));
    assert_true(qo_fm_log_f32(0x1p-149f) < -103.27f && qo_fm_log_f32(0x1p-149f) > -103.28f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sincos),
        cmocka_unit_test(test_atan2),
        cmocka_unit_test(test_asin_acos),
        cmocka_unit_test(test_exp_log),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
