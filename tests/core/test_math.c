/*
 * The scalar math kernels of both cores: qorient/fmath.h (float32, qo_fm_*_f32) and
 * qorient/fxmath.h + fxconv.h (fixed point, qo_fx_*). One program, in three sections
 * (docs/TESTING.md, "One body for both cores"):
 *
 *   shared bodies   sin/cos, atan2, asin/acos: ONE body each, run on both cores through the
 *                   adapter table `mcore` below (CORE_F32, CORE_FX), registered with BOTH.
 *   float32 only    exp/log (the fixed core has none).
 *   fixed only      mul, add/sub/neg, sum_round, div, sqrt, rsqrt, norm, wrap, the fxconv
 *                   boundary, and the fixed-only forms of sin/cos (half angle, Q3.60, NULL).
 *
 * Every result is judged against double-precision libm (glibc's correctly reduced double
 * functions) or an exact integer (128-bit) reference, computed from the input EXACTLY as the
 * core received it (float32, or Q3.28 / Q1.30 / raw int32 rounded to nearest and saturated),
 * with the core's documented bound: float32 in ulp of the correctly rounded result (fmath.h:
 * sin/cos 1, atan2 1.5, asin/acos 2), fixed point in LSB of the output format (fxmath.h: 1 LSB
 * of Q1.30 for sin/cos, of Q3.28 for atan2/asin/acos). The measured worst cases are printed.
 * The private integer helpers (lib/src/fx_internal.h) are in test_fx_internal.c.
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

#define CORES_OWN_TABLE   /* the kernels' table `mcore` below, judged in ulp / LSB */
#include "common/cores.h"
#include "common/ref.h"
#include "qorient/fmath.h"
#include "qorient/fxconv.h"
#include "qorient/fxmath.h"

/* The exact references of the fixed-only section need 128-bit integers. 32-bit targets
 * (Cortex-M, armhf under tests/qemu) have none: there those tests are skipped, the others run. */
#if defined(__SIZEOF_INT128__)
#define HAVE_I128 1
__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;
#endif

/* Sweep density: the emulated Cortex-M targets run double libm in software, ~100x slower, so
 * there the float32 strided sweeps take every 16th point of the host's (the edges are all kept). */
#if defined(__arm__) && !defined(__linux__)
#define SPARSE 16u
#else
#define SPARSE 1u
#endif

static uint64_t rng_state;
static uint64_t rnd(void) { return ref_splitmix64(&rng_state); } /* tests/common/ref.c */
static int32_t rnd_i32(void) { return (int32_t)(uint32_t)rnd(); }
/* A random int32 of random magnitude (so tiny and huge values both occur). */
static int32_t rnd_i32_mag(void)
{
    int32_t v = rnd_i32();
    unsigned sh = (unsigned)(rnd() % 32u);
    return (int32_t)(v / ((int64_t)1 << sh));
}

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

/* The worst error of a sweep, with its input; the failure message starts with the core. */
typedef struct worst { double err; double x, y; const char *name; double bound; const char *core; } worst;

static void note(worst *w, double err, double x, double y)
{
    if (!(err <= w->err)) {
        w->err = err;
        w->x = x;
        w->y = y;
    }
}

static void check(const worst *w)
{
    printf("  %s %-6s worst %.3f at (%.9e, %.9e), bound %.1f\n", w->core ? w->core : "f32",
           w->name, w->err, w->x, w->y, w->bound);
    if (!(w->err <= w->bound))
        fail_msg("%s %s: %.3f at x = %.9e (y = %.9e), bound %.1f", w->core ? w->core : "f32",
                 w->name, w->err, w->x, w->y, w->bound);
}

/* ==== the adapter table of the shared bodies ==== */

typedef struct mcore mcore;
/* A sweep hands each input (as the core holds it, in double) to the body's judge. */
typedef void (*visit1)(const mcore *c, double x, void *ctx);
typedef void (*visit2)(const mcore *c, double y, double x, void *ctx);

struct mcore {
    const char *name;
    int fixed;
    double b_sincos, b_atan2, b_asincos;   /* the header's bounds, in the unit of err_* */
    double pi, half_pi;                    /* pi and pi/2 as the core returns them (exact ends) */
    double unit_lsb;                       /* the step of a unit value just below 1 */
    int clamps_unit;                       /* asin/acos clamp |x| > 1 (fixed) or give NaN */
    double (*ang_in)(double a);            /* angle (rad) as received: float32 / Q3.28 */
    double (*unit_in)(double x);           /* unit value as received: float32 / Q1.30 */
    double (*ang_next)(double a, int dir); /* the neighbouring representable angle */
    double (*err_unit)(double got, double ref);   /* sin/cos: ulp / LSB of Q1.30 */
    double (*err_ang)(double got, double ref);    /* atan2/asin/acos: ulp / LSB of Q3.28 */
    /* the kernels, on exactly representable inputs; *agree: sin()/cos() give sincos's values */
    void (*sincos)(double a, double *s, double *co, int *agree);
    double (*atan2)(double y, double x);   /* x, y as unit_in gives them (ratio only matters) */
    double (*asin)(double x);
    double (*acos)(double x);
    /* each core's own sweep of its whole input domain */
    void (*sweep_sincos)(const mcore *c, visit1 v, void *ctx);
    void (*sweep_atan2)(const mcore *c, visit2 v, void *ctx);
    void (*sweep_asin)(const mcore *c, visit1 v, void *ctx);
};

/* -- float32 row -- */
static double f32_in(double x) { return (double)(float)x; }
static double f32_next(double a, int dir) { return (double)nextafterf((float)a, dir > 0 ? INFINITY : -INFINITY); }
static double f32_err(double got, double ref) { return ulp_err((float)got, ref); }
static void f32_sincos(double a, double *s, double *co, int *agree)
{
    qo_fm_sincos_f32_t sc = qo_fm_sincos_f32((float)a);
    *s = (double)sc.s;
    *co = (double)sc.c;
    *agree = same_bits(sc.s, qo_fm_sin_f32((float)a)) && same_bits(sc.c, qo_fm_cos_f32((float)a));
}
static double f32_atan2(double y, double x) { return (double)qo_fm_atan2_f32((float)y, (float)x); }
static double f32_asin(double x) { return (double)qo_fm_asin_f32((float)x); }
static double f32_acos(double x) { return (double)qo_fm_acos_f32((float)x); }

static void f32_sweep_sincos(const mcore *c, visit1 v, void *ctx)
{
    uint32_t u;
    long k;
    int s;
    /* the whole domain, every 1009th bit pattern, both signs */
    for (u = 0; u < 0x7f800000u; u += 1009u * SPARSE)
        for (s = 0; s < 2; s++) v(c, (double)f_of(u | (s ? 0x80000000u : 0u)), ctx);
    /* every float in [pi/4, 8 pi] with a stride of 23 (the core's half-angles and angles) */
    for (u = 0x3f490fdbu; u < 0x41c90fdbu; u += 23u * SPARSE) v(c, (double)f_of(u), ctx);
    /* the floats nearest k pi/2 and their neighbours, k < 2^16 (the hard range reductions) */
    for (k = 1; k < 65536; k += (k < 512) ? 1 : 97 * (long)SPARSE) {
        float x = (float)((double)k * (REF_PI / 2.0));
        uint32_t b;
        memcpy(&b, &x, sizeof b);
        for (u = b - 2u; u <= b + 2u; u++) v(c, (double)f_of(u), ctx);
    }
}

static void f32_sweep_atan2(const mcore *c, visit2 v, void *ctx)
{
    ref_rng rng = { 0x5eedf00dULL };
    long n;
    /* random bit patterns (any magnitude ratio) and random points of [-2, 2]^2 */
    for (n = 0; n < 1000000 / (long)SPARSE; n++) {
        uint64_t r = ref_rng_next(&rng);
        float y = f_of((uint32_t)r), x = f_of((uint32_t)(r >> 32));
        double y2, x2;
        y2 = (double)(float)ref_rng_range(&rng, -2.0, 2.0);
        x2 = (double)(float)ref_rng_range(&rng, -2.0, 2.0);
        if (!isnan(x) && !isnan(y)) v(c, (double)y, (double)x, ctx);
        v(c, y2, x2, ctx);
    }
    /* dense around the octant boundaries (ratio near tan(pi/8), 1) and the axes */
    for (n = -20000; n <= 20000; n += (long)SPARSE) {
        float d = (float)n * 0x1p-24f;
        v(c, (double)(0.41421356f + d), 1.0, ctx);
        v(c, (double)(1.0f + d), -1.0, ctx);
        v(c, -1.0, (double)(0.41421356f + d), ctx);
        v(c, (double)d, -1.0, ctx);
    }
}

static void f32_sweep_asin(const mcore *c, visit1 v, void *ctx)
{
    uint32_t u;
    int s;
    for (u = 0; u <= 0x3f800000u; u += 401u * SPARSE)
        for (s = 0; s < 2; s++) v(c, (double)f_of(u | (s ? 0x80000000u : 0u)), ctx);
}

/* -- fixed-point row: Q3.28 angles, Q1.30 unit values, raw int32 atan2 coordinates -- */
/* x * 2^q rounded to nearest and saturated to int32 (NaN: 0), then back: what the core holds */
static int32_t fx_raw(double x, double scale)
{
    double r;
    if (isnan(x)) return 0;
    r = floor(x * scale + 0.5);
    if (r >= 2147483647.0) return INT32_MAX;
    if (r <= -2147483648.0) return INT32_MIN;
    return (int32_t)r;
}
static double q28_in(double a) { return (double)fx_raw(a, Q28) / Q28; }
static double q30_in(double x) { return (double)fx_raw(x, Q30) / Q30; }
static double q28_next(double a, int dir)
{
    int32_t r = fx_raw(a, Q28);
    if (dir > 0 && r < INT32_MAX) r++;
    if (dir < 0 && r > INT32_MIN) r--;
    return (double)r / Q28;
}
static double q30_err(double got, double ref) { return fabs(got - ref) * Q30; }
static double q28_err(double got, double ref) { return fabs(got - ref) * Q28; }
static void q28_sincos(double a, double *s, double *co, int *agree)
{
    qo_q28 x = fx_raw(a, Q28);
    qo_q30 si = 7, ci = 7;
    qo_status st = qo_fx_sincos_q28(x, &si, &ci);
    *s = (double)si / Q30;
    *co = (double)ci / Q30;
    *agree = st == QO_OK && si == qo_fx_sin_q28(x) && ci == qo_fx_cos_q28(x);
}
static double q28_atan2(double y, double x) { return (double)qo_fx_atan2_q28(fx_raw(y, Q30), fx_raw(x, Q30)) / Q28; }
static double q28_asin(double x) { return (double)qo_fx_asin_q28(fx_raw(x, Q30)) / Q28; }
static double q28_acos(double x) { return (double)qo_fx_acos_q28(fx_raw(x, Q30)) / Q28; }

static void q28_sweep_sincos(const mcore *c, visit1 v, void *ctx)
{
    int k;
    rng_state = 7;
    for (k = 0; k < 300000; k++) v(c, (double)(k % 2 ? rnd_i32() : rnd_i32_mag()) / Q28, ctx);
}

static void q28_sweep_atan2(const mcore *c, visit2 v, void *ctx)
{
    int k;
    rng_state = 8;
    for (k = 0; k < 300000; k++) {
        int32_t y = rnd_i32_mag();
        v(c, (double)y / Q30, (double)rnd_i32_mag() / Q30, ctx);
    }
    /* Odd symmetry is exact in fixed point (documented: integers have no -0). */
    for (k = 0; k < 10000; k++) {
        int32_t y = rnd_i32_mag(), x = rnd_i32_mag();
        if (y == INT32_MIN || y == 0) continue;
        if (qo_fx_atan2_q28(-y, x) != -qo_fx_atan2_q28(y, x))
            fail_msg("%s atan2 odd symmetry at (%ld, %ld)", c->name, (long)y, (long)x);
    }
}

static void q28_sweep_asin(const mcore *c, visit1 v, void *ctx)
{
    int k;
    rng_state = 9;
    for (k = 0; k < 200000; k++)
        v(c, (double)((qo_q30)(rnd() % (2u * QO_Q30_ONE + 1u)) - QO_Q30_ONE) / Q30, ctx);
}

static const mcore CORE_F32 = {
    "f32", 0, 1.0, 1.5, 2.0, (double)(float)REF_PI, (double)(float)(REF_PI / 2.0), 0x1p-24, 0,
    f32_in, f32_in, f32_next, f32_err, f32_err, f32_sincos, f32_atan2, f32_asin, f32_acos,
    f32_sweep_sincos, f32_sweep_atan2, f32_sweep_asin
};
static const mcore CORE_FX = {
    "q30", 1, 1.0, 1.0, 1.0, (double)QO_Q28_PI / Q28, (double)QO_Q28_HALF_PI / Q28, 0x1p-30, 1,
    q28_in, q30_in, q28_next, q30_err, q28_err, q28_sincos, q28_atan2, q28_asin, q28_acos,
    q28_sweep_sincos, q28_sweep_atan2, q28_sweep_asin
};

/* BOTH (common/cores.h): one body, two cmocka entries; a failure message starts with the
 * core's name. */

/* ==== shared bodies ==== */

typedef struct pair_worst { worst a, b; } pair_worst;

static void judge_sincos(const mcore *c, double a, void *ctx)
{
    pair_worst *w = ctx;
    double s, co;
    int agree;
    c->sincos(a, &s, &co, &agree);
    note(&w->a, c->err_unit(s, sin(a)), a, 0.0);
    note(&w->b, c->err_unit(co, cos(a)), a, 0.0);
    /* the single functions are the pair's members; |sin|, |cos| <= 1 (fixed: not 1 + 1 LSB) */
    if (!agree || fabs(s) > 1.0 || fabs(co) > 1.0) note(&w->a, 1e30, a, 1.0);
}

static void test_sincos(void **state)
{
    const mcore *c = *state;
    pair_worst w = { { 0.0, 0.0, 0.0, "sin", c->b_sincos, c->name },
                     { 0.0, 0.0, 0.0, "cos", c->b_sincos, c->name } };
    /* the union of both cores' edges, in radians; each core gets them as it holds them, and
     * their neighbours (+-1 ulp / LSB): zeros, subnormals, the multiples of pi/4 (the hard range
     * reductions), huge values (Inf / saturated past FLT_MAX), Inf and NaN */
    static const double e[] = {
        0.0, -0.0, 0x1p-149, -0x1p-149, FLT_MIN, 0x1p-12, 0x1p-28, -0x1p-28, 0x1.921fb4p-1,
        0x1.921fb6p-1, REF_PI / 4, REF_PI / 2, -REF_PI / 2, REF_PI, -REF_PI, 3 * REF_PI / 2,
        2 * REF_PI, -2 * REF_PI, 1.0, -1.0, 0x1.921fb6p+0, 0x1.921fb6p+1, 0x1.2d97c8p+2, 7.9,
        8.0, -8.0, 1e10, 1e20, 1e30, 1e38, FLT_MAX, -FLT_MAX, 1e39, -1e39, 0x1.ba1794p+101,
        0x1.bc3186p+64, 105414350.0, 8.35e22, INFINITY, -INFINITY, NAN
    };
    double s, co;
    int agree;
    size_t i;
    for (i = 0; i < sizeof e / sizeof e[0]; i++) {
        double a = c->ang_in(e[i]);
        judge_sincos(c, a, &w);
        if (!isnan(a) && !isinf(a)) {
            judge_sincos(c, c->ang_next(a, -1), &w);
            judge_sincos(c, c->ang_next(a, +1), &w);
        }
    }
    c->sweep_sincos(c, judge_sincos, &w);
    check(&w.a);
    check(&w.b);
    /* exact: sin(0) = 0, cos(0) = 1; sin(-0) = -0 in float32 (fixed point has no -0) */
    c->sincos(0.0, &s, &co, &agree);
    assert_true(s == 0.0 && !signbit(s) && co == 1.0);
    c->sincos(c->ang_in(-0.0), &s, &co, &agree);
    assert_true(s == 0.0 && co == 1.0 && !signbit(s) == !!c->fixed);
    /* beyond the domain: float32 Inf / NaN give NaN; fixed 1e39 saturates to 8 - 2^-28 rad */
    c->sincos(c->ang_in(INFINITY), &s, &co, &agree);
    assert_true(c->fixed ? fabs(s - sin(c->ang_in(1e39))) * Q30 <= 1.0 : isnan(s) && isnan(co));
    c->sincos(c->ang_in(NAN), &s, &co, &agree);
    assert_true(c->fixed ? s == 0.0 && co == 1.0 : isnan(s) && isnan(co));
}

static void judge_atan2(const mcore *c, double y, double x, void *ctx)
{
    worst *w = ctx;
    double got = c->atan2(y, x), want = atan2(y, x);
    /* fixed atan2(0, 0) = 0 (documented); float32 follows C Annex F, as libm does */
    if (c->fixed && x == 0.0 && y == 0.0) want = 0.0;
    note(w, c->err_ang(got, want), x, y);
    if (fabs(got) > c->pi) note(w, 1e30, x, y);
}

static void test_atan2(void **state)
{
    const mcore *c = *state;
    worst w = { 0.0, 0.0, 0.0, "atan2", c->b_atan2, c->name };
    /* the union of both cores' edge tables: float32 specials (Annex F, subnormals, FLT_MAX, Inf)
     * and the fixed raw int32 edges (1 LSB, INT32_MIN/MAX, 1.0 in Q1.30), here in Q1.30 units */
    static const double e[] = {
        0.0, -0.0, 0x1p-149, -0x1p-149, FLT_MIN, 1e-20, 0.5, 1.0, -1.0, 2.0, 1e20, FLT_MAX,
        -FLT_MAX, INFINITY, -INFINITY, 0.41421354, 0.41421357, 3.0, -7.5, 0x1p-30, -0x1p-30,
        0x1p-29, -0x1p-29, 0x3p-30, 2147483647 / Q30, -2.0, -2147483647 / Q30,
        2147483646 / Q30, 1000000 / Q30, -999999 / Q30, 46341 / Q30, 0x1p-10, 1e39
    };
    size_t i, j;
    for (i = 0; i < sizeof e / sizeof e[0]; i++)
        for (j = 0; j < sizeof e / sizeof e[0]; j++) judge_atan2(c, c->unit_in(e[i]), c->unit_in(e[j]), &w);
    c->sweep_atan2(c, judge_atan2, &w);
    check(&w);
    /* the axes and (0, 0) exactly, in each core's own pi and pi/2 */
    assert_true(c->atan2(0.0, 0.0) == 0.0 && !signbit(c->atan2(0.0, 0.0)));
    assert_true(c->atan2(0.0, 0.5) == 0.0);
    assert_true(c->atan2(0.0, -0.5) == c->pi);
    assert_true(c->atan2(0.5, 0.0) == c->half_pi);
    assert_true(c->atan2(-0.5, 0.0) == -c->half_pi);
    assert_true(c->atan2(-2.0, 0.0) == -c->half_pi);
    assert_true(c->atan2(0.0, -2.0) == c->pi);
    assert_true(c->atan2(c->unit_in(-7 / Q30), c->unit_in(7 / Q30)) ==
                -c->atan2(c->unit_in(7 / Q30), c->unit_in(7 / Q30)));
    /* -0: float32 atan2(-0, -x) = -pi (Annex F); fixed point has no -0, so +pi */
    assert_true(c->atan2(c->unit_in(-0.0), -0.5) == (c->fixed ? c->pi : -c->pi));
    /* NaN: float32 gives NaN; fixed receives 0 for it (the conversion's documented answer) */
    if (!c->fixed) assert_true(isnan(c->atan2(NAN, 1.0)) && isnan(c->atan2(1.0, NAN)));
}

static void judge_asin(const mcore *c, double x, void *ctx)
{
    pair_worst *w = ctx;
    /* fixed clamps |x| > 1 to +-1 first (documented); float32 gives NaN there, as libm */
    double xc = c->clamps_unit ? fmax(-1.0, fmin(1.0, x)) : x;
    double s = c->asin(x), a = c->acos(x);
    note(&w->a, c->err_ang(s, asin(xc)), x, 0.0);
    note(&w->b, c->err_ang(a, acos(xc)), x, 0.0);
    if (fabs(s) > c->half_pi || a < 0.0 || a > c->pi) note(&w->a, 1e30, x, 1.0);
}

static void test_asin_acos(void **state)
{
    const mcore *c = *state;
    pair_worst w = { { 0.0, 0.0, 0.0, "asin", c->b_asincos, c->name },
                     { 0.0, 0.0, 0.0, "acos", c->b_asincos, c->name } };
    static const double e[] = {
        0.0, -0.0, 0x1p-30, -0x1p-30, 1.0, -1.0, 1.0 - 0x1p-30, -1.0 + 0x1p-30, 1.0 - 0x1p-29,
        1.0 + 0x1p-30, -1.0 - 0x1p-30, 1.0000001, -1.0000001, 2147483647 / Q30, -2.0, 0.5,
        -0.5, 759250125 / Q30 /* ~1/sqrt2 */, 0x1p-149, FLT_MIN, 1e39, -1e39, INFINITY, NAN
    };
    size_t i;
    int k;
    for (i = 0; i < sizeof e / sizeof e[0]; i++) judge_asin(c, c->unit_in(e[i]), &w);
    /* just inside the ends, where asin is steep */
    for (k = 1; k < 2000; k++) {
        judge_asin(c, c->unit_in(1.0 - k * k * c->unit_lsb), &w);
        judge_asin(c, c->unit_in(-1.0 + k * k * c->unit_lsb), &w);
    }
    c->sweep_asin(c, judge_asin, &w);
    check(&w.a);
    check(&w.b);
    /* the ends: acos(1) = +0 and asin(+-0) = +-0 in both; fixed: every end exact, and beyond
     * +-1 clamped; float32: beyond +-1, Inf and NaN give NaN */
    assert_true(c->acos(1.0) == 0.0 && !signbit(c->acos(1.0)) && c->asin(0.0) == 0.0);
    assert_true(c->asin(c->unit_in(-0.0)) == 0.0 && !signbit(c->asin(c->unit_in(-0.0))) == !!c->fixed);
    if (c->fixed) {
        assert_true(c->asin(1.0) == c->half_pi && c->asin(-1.0) == -c->half_pi);
        assert_true(c->acos(-1.0) == c->pi);
        assert_true(c->asin(c->unit_in(2.0)) == c->half_pi && c->acos(-2.0) == c->pi);
    } else {
        assert_true(isnan(c->asin(1.0000001)) && isnan(c->acos(-1.0000001)));
        assert_true(isnan(c->asin(INFINITY)) && isnan(c->acos(NAN)));
    }
}

/* ==== float32 only: exp and log (the fixed core has none) ==== */

#define BOUND_EXPLOG 1.0   /* ulp, qorient/fmath.h */

static void test_exp_log(void **state)
{
    worst we = { 0.0, 0.0f, 0.0f, "exp", BOUND_EXPLOG, NULL }, wl = { 0.0, 0.0f, 0.0f, "log", BOUND_EXPLOG, NULL };
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

/* ==== fixed only: qorient/fxmath.h and fxconv.h ==== */


#ifdef HAVE_I128
/* floor(v / 2^s) exactly in 128 bits. */
static i128 floor_shift(i128 v, unsigned s)
{
    i128 d = (i128)1 << s;
    i128 q = v / d;
    if (v % d != 0 && v < 0) q -= 1;
    return q;
}

/* Reference: round(a*b / 2^s) ties up, saturated. */
static int32_t ref_mul(int32_t a, int32_t b, unsigned s)
{
    i128 p = (i128)a * b;
    i128 r = floor_shift(p + ((i128)1 << (s - 1)), s);
    if (r > INT32_MAX) return INT32_MAX;
    if (r < INT32_MIN) return INT32_MIN;
    return (int32_t)r;
}

static void check_mul(int32_t a, int32_t b)
{
    int32_t g30 = qo_fx_mul_q30(a, b), g28 = qo_fx_mul_q28(a, b), g16 = qo_fx_mul_q16(a, b);
    if (g30 != ref_mul(a, b, 30) || g28 != ref_mul(a, b, 28) || g16 != ref_mul(a, b, 16))
        fail_msg("mul(%ld, %ld): q30 %ld want %ld, q28 %ld want %ld, q16 %ld want %ld",
                 (long)a, (long)b, (long)g30, (long)ref_mul(a, b, 30), (long)g28,
                 (long)ref_mul(a, b, 28), (long)g16, (long)ref_mul(a, b, 16));
}

#endif

static void test_mul_edges_and_sweep(void **state)
{
#ifndef HAVE_I128
    (void)state;
    skip();
#else
    static const int32_t e[] = { 0, 1, -1, 2, -2, 3, (1 << 29), -(1 << 29), (1 << 29) + 1,
                                 QO_Q30_ONE, -QO_Q30_ONE, QO_Q30_ONE - 1, QO_Q30_ONE + 1,
                                 (1 << 15), (1 << 16), INT32_MAX, INT32_MIN, INT32_MIN + 1,
                                 INT32_MAX - 1, 12345, -777777 };
    size_t i, j;
    int k;
    (void)state;
    for (i = 0; i < sizeof e / sizeof e[0]; i++)
        for (j = 0; j < sizeof e / sizeof e[0]; j++) check_mul(e[i], e[j]);
    /* Ties: 1 * 0.5 LSB rounds up to 1, -1 * 0.5 LSB rounds (toward +inf) to 0. */
    assert_int_equal(qo_fx_mul_q30(1, 1 << 29), 1);
    assert_int_equal(qo_fx_mul_q30(-1, 1 << 29), 0);
    assert_int_equal(qo_fx_mul_q30(3, 1 << 29), 2);
    /* Saturation: (-2) * (-2) = 4 does not fit Q1.30. */
    assert_int_equal(qo_fx_mul_q30(INT32_MIN, INT32_MIN), INT32_MAX);
    assert_int_equal(qo_fx_mul_q30(INT32_MIN, INT32_MAX), INT32_MIN);
    assert_int_equal(qo_fx_mul_q30(QO_Q30_ONE, QO_Q30_ONE), QO_Q30_ONE);
    rng_state = 1;
    for (k = 0; k < 200000; k++) check_mul(rnd_i32_mag(), rnd_i32_mag());
#endif
}

/* The 16x16 partial-product forms used on ARMv6-M against the native 64-bit product: edge
 * table (0, +-1, INT32_MIN/MAX, 0xFFFF carries) and 2M random pairs. */
static void test_mul32_parts(void **state)
{
    static const uint32_t edge[] = { 0u, 1u, 2u, 0xFFFFu, 0x10000u, 0x1FFFFu, 0x7FFFFFFFu, 0x80000000u,
                                     0x80000001u, 0xFFFF0000u, 0xFFFF8000u, 0xFFFFFFFFu, 0x40000000u,
                                     0xC0000000u, 0x0000FFFFu, 0x12345678u, 0xDEADBEEFu };
    size_t i, j;
    long k;
    (void)state;
    for (i = 0; i < sizeof edge / sizeof edge[0]; i++) {
        for (j = 0; j < sizeof edge / sizeof edge[0]; j++) {
            uint32_t a = edge[i], b = edge[j];
            if (qo_fx_umul32_u64_parts(a, b) != (uint64_t)a * b) fail_msg("umul parts %08lx * %08lx", (unsigned long)a, (unsigned long)b);
            if (qo_fx_mul32_i64_parts((int32_t)a, (int32_t)b) != (int64_t)(int32_t)a * (int32_t)b)
                fail_msg("mul parts %ld * %ld", (long)(int32_t)a, (long)(int32_t)b);
        }
    }
    rng_state = 77;
    for (k = 0; k < 2000000; k++) {
        uint64_t r = rnd();
        uint32_t a = (uint32_t)r, b = (uint32_t)(r >> 32);
        if (qo_fx_umul32_u64_parts(a, b) != (uint64_t)a * b) fail_msg("umul parts %08lx * %08lx", (unsigned long)a, (unsigned long)b);
        if (qo_fx_mul32_i64_parts((int32_t)a, (int32_t)b) != (int64_t)(int32_t)a * (int32_t)b)
            fail_msg("mul parts %ld * %ld", (long)(int32_t)a, (long)(int32_t)b);
        if (qo_fx_mul32_i64((int32_t)a, (int32_t)b) != (int64_t)(int32_t)a * (int32_t)b)
            fail_msg("mul %ld * %ld", (long)(int32_t)a, (long)(int32_t)b);
    }
}

static void test_add_sub_neg_saturate(void **state)
{
    (void)state;
    assert_int_equal(qo_fx_add_q30(INT32_MAX, 1), INT32_MAX);
    assert_int_equal(qo_fx_add_q30(INT32_MIN, -1), INT32_MIN);
    assert_int_equal(qo_fx_add_q30(INT32_MAX, INT32_MIN), -1);
    assert_int_equal(qo_fx_sub_q30(INT32_MIN, 1), INT32_MIN);
    assert_int_equal(qo_fx_sub_q30(INT32_MAX, -1), INT32_MAX);
    assert_int_equal(qo_fx_sub_q30(0, INT32_MIN), INT32_MAX);
    assert_int_equal(qo_fx_neg_q30(INT32_MIN), INT32_MAX);
    assert_int_equal(qo_fx_neg_q30(INT32_MAX), -INT32_MAX);
    assert_int_equal(qo_fx_neg_q30(0), 0);
    assert_int_equal(qo_fx_sat_i32((int64_t)INT32_MAX + 1), INT32_MAX);
    assert_int_equal(qo_fx_sat_i32((int64_t)INT32_MIN - 1), INT32_MIN);
    assert_int_equal(qo_fx_sat_i32(-5), -5);
}

static void test_sum_round(void **state)
{
#ifndef HAVE_I128
    (void)state;
    skip();
#else
    int64_t t[16];
    int k;
    (void)state;
    /* Carries between the low parts: four terms of 3/4 LSB sum to exactly 3 LSB. */
    t[0] = t[1] = t[2] = t[3] = (int64_t)3 << 28;
    assert_int_equal(qo_fx_sum_round_i64(t, 4, 30), 3);
    /* Ties toward +inf, also for a negative total. */
    t[0] = (int64_t)1 << 29; assert_int_equal(qo_fx_sum_round_i64(t, 1, 30), 1);
    t[0] = -((int64_t)1 << 29); assert_int_equal(qo_fx_sum_round_i64(t, 1, 30), 0);
    t[0] = -((int64_t)3 << 29); assert_int_equal(qo_fx_sum_round_i64(t, 1, 30), -1);
    /* Extreme terms that would overflow a naive int64 sum. */
    t[0] = t[1] = t[2] = t[3] = (int64_t)1 << 62;
    assert_true(qo_fx_sum_round_i64(t, 4, 30) == ((int64_t)1 << 34));
    rng_state = 2;
    for (k = 0; k < 100000; k++) {
        size_t n = 1 + (size_t)(rnd() % 16u), i;
        unsigned sh = 8u + (unsigned)(rnd() % 33u);
        i128 sum = 0, want;
        int64_t got;
        for (i = 0; i < n; i++) {
            t[i] = (int64_t)rnd_i32_mag() * rnd_i32_mag();
            sum += t[i];
        }
        want = floor_shift(sum + ((i128)1 << (sh - 1)), sh);
        got = qo_fx_sum_round_i64(t, n, sh);
        if ((i128)got != want) fail_msg("sum_round n=%u shift=%u: got %lld", (unsigned)n, sh, (long long)got);
    }
#endif
}

#ifdef HAVE_I128
/* Reference division: round(num * 2^s / den), ties away from zero, in 128 bits. */
static void check_div(int32_t n, int32_t d)
{
    static const unsigned sh[3] = { 30, 28, 16 };
    int f;
    for (f = 0; f < 3; f++) {
        int32_t got = 12345;
        qo_status st = f == 0 ? qo_fx_div_q30(n, d, &got)
                     : f == 1 ? qo_fx_div_q28(n, d, &got) : qo_fx_div_q16(n, d, &got);
        i128 N, D, q, r;
        int neg;
        int32_t want;
        qo_status wst = QO_OK;
        if (d == 0) {
            if (st != QO_E_DEGENERATE || got != 0) fail_msg("div(%ld, 0) shift %u: st %d out %ld", (long)n, sh[f], st, (long)got);
            continue;
        }
        N = (i128)n * ((i128)1 << sh[f]);
        D = d;
        neg = (N < 0) != (D < 0);
        if (N < 0) N = -N;
        if (D < 0) D = -D;
        q = N / D; r = N % D;
        if (2 * r >= D) q++;
        if (neg) q = -q;
        if (q > INT32_MAX) { want = INT32_MAX; wst = QO_E_OVERFLOW; }
        else if (q < INT32_MIN) { want = INT32_MIN; wst = QO_E_OVERFLOW; }
        else want = (int32_t)q;
        if (st != wst || got != want)
            fail_msg("div(%ld, %ld) shift %u: got %ld st %d, want %ld st %d", (long)n, (long)d, sh[f], (long)got, st, (long)want, wst);
    }
}
#endif

static void test_div(void **state)
{
#ifndef HAVE_I128
    (void)state;
    skip();
#else
    static const int32_t e[] = { 0, 1, -1, 2, -2, 3, -3, QO_Q30_ONE, -QO_Q30_ONE, INT32_MAX,
                                 INT32_MIN, INT32_MIN + 1, 1 << 29, 7, 65536 };
    size_t i, j;
    int k;
    qo_q30 o;
    (void)state;
    for (i = 0; i < sizeof e / sizeof e[0]; i++)
        for (j = 0; j < sizeof e / sizeof e[0]; j++) check_div(e[i], e[j]);
    assert_int_equal(qo_fx_div_q30(1, 2, NULL), QO_E_NULL);
    /* -2 exactly fits, +2 does not. */
    assert_int_equal(qo_fx_div_q30(-2, 1, &o), QO_OK); assert_int_equal(o, INT32_MIN);
    assert_int_equal(qo_fx_div_q30(2, 1, &o), QO_E_OVERFLOW); assert_int_equal(o, INT32_MAX);
    /* Tie: 1/2^31 = 0.5 LSB of Q1.30 rounds away from zero. */
    assert_int_equal(qo_fx_div_q30(1, INT32_MIN, &o), QO_OK); assert_int_equal(o, -1);
    rng_state = 3;
    for (k = 0; k < 200000; k++) check_div(rnd_i32_mag(), rnd_i32_mag());
#endif
}

#ifdef HAVE_I128
static void check_sqrt_u64(uint64_t v)
{
    u128 r = qo_fx_sqrt_u64(v);
    /* r is the nearest integer to sqrt(v): (r - 1/2)^2 <= v < (r + 1/2)^2, i.e.
     * r^2 - r < v + 1 and v < r^2 + r + 1 (never a tie: v is an integer). */
    int ok = (r * r + r + 1 > (u128)v) && (r == 0 ? v == 0 : r * r - r < (u128)v + 1);
    if (!ok) fail_msg("sqrt_u64(%llu) = %llu", (unsigned long long)v, (unsigned long long)r);
}
#endif

static void test_sqrt(void **state)
{
#ifndef HAVE_I128
    (void)state;
    skip();
#else
    static const uint64_t e[] = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 0xFFFFFFFFFFFFFFFFULL,
                                  0xFFFFFFFE00000001ULL, 0xFFFFFFFF00000000ULL,
                                  0xFFFFFFFF00000001ULL, (uint64_t)1 << 62, ((uint64_t)1 << 62) - 1 };
    size_t i;
    int k;
    qo_q30 o;
    (void)state;
    for (i = 0; i < sizeof e / sizeof e[0]; i++) check_sqrt_u64(e[i]);
    /* Values right at the rounding boundaries k^2 + k (round down) and k^2 + k + 1 (up). */
    rng_state = 4;
    for (k = 0; k < 100000; k++) {
        uint64_t r = rnd() >> 32, v = rnd() >> (rnd() % 64u);
        check_sqrt_u64(v);
        check_sqrt_u64(r * r);
        check_sqrt_u64(r * r + r);
        if (r < 0xFFFFFFFFULL) check_sqrt_u64(r * r + r + 1);
        if (r > 0) check_sqrt_u64(r * r - 1);
    }
    assert_true(qo_fx_sqrt_u64(0xFFFFFFFFFFFFFFFFULL) == ((uint64_t)1 << 32));
    /* Q1.30 square root: correctly rounded over the whole domain. */
    assert_int_equal(qo_fx_sqrt_q30(-1, &o), QO_E_RANGE); assert_int_equal(o, 0);
    assert_int_equal(qo_fx_sqrt_q30(INT32_MIN, &o), QO_E_RANGE); assert_int_equal(o, 0);
    assert_int_equal(qo_fx_sqrt_q30(0, NULL), QO_E_NULL);
    assert_int_equal(qo_fx_sqrt_q30(0, &o), QO_OK); assert_int_equal(o, 0);
    assert_int_equal(qo_fx_sqrt_q30(QO_Q30_ONE, &o), QO_OK); assert_int_equal(o, QO_Q30_ONE);
    assert_int_equal(qo_fx_sqrt_q30(QO_Q30_ONE / 4, &o), QO_OK); assert_int_equal(o, QO_Q30_ONE / 2);
    for (k = 0; k < 200000; k++) {
        int32_t x = k < 3 ? (k == 0 ? 1 : k == 1 ? INT32_MAX : 2) : (int32_t)(rnd() & 0x7FFFFFFF) >> (rnd() % 31u);
        double err;
        assert_int_equal(qo_fx_sqrt_q30(x, &o), QO_OK);
        err = (double)o - sqrt((double)x / Q30) * Q30;
        if (fabs(err) > 0.5 + 1e-6) fail_msg("sqrt_q30(%ld) = %ld, error %.3f LSB", (long)x, (long)o, err);
    }
#endif
}

static void test_rsqrt(void **state)
{
    qo_q30 o;
    int k;
    (void)state;
    assert_int_equal(qo_fx_rsqrt_q30(0, &o), QO_E_RANGE); assert_int_equal(o, INT32_MAX);
    assert_int_equal(qo_fx_rsqrt_q30(-5, &o), QO_E_RANGE); assert_int_equal(o, INT32_MAX);
    assert_int_equal(qo_fx_rsqrt_q30(INT32_MIN, &o), QO_E_RANGE);
    assert_int_equal(qo_fx_rsqrt_q30(QO_Q30_ONE / 4, &o), QO_E_OVERFLOW); assert_int_equal(o, INT32_MAX);
    assert_int_equal(qo_fx_rsqrt_q30(1, &o), QO_E_OVERFLOW);
    assert_int_equal(qo_fx_rsqrt_q30(1, NULL), QO_E_NULL);
    assert_int_equal(qo_fx_rsqrt_q30(QO_Q30_ONE, &o), QO_OK); assert_int_equal(o, QO_Q30_ONE);
    assert_int_equal(qo_fx_rsqrt_q30(QO_Q30_ONE / 4 + 1, &o), QO_OK);
    assert_true(o > INT32_MAX - 4);
    rng_state = 5;
    for (k = 0; k < 200000; k++) {
        int32_t x = (QO_Q30_ONE / 4 + 1) + (int32_t)(rnd() % (uint64_t)(INT32_MAX - QO_Q30_ONE / 4));
        double err;
        if (k == 0) x = INT32_MAX;
        assert_int_equal(qo_fx_rsqrt_q30(x, &o), QO_OK);
        err = (double)o - Q30 / sqrt((double)x / Q30);
        if (fabs(err) > 1.0) fail_msg("rsqrt_q30(%ld) = %ld, error %.3f LSB", (long)x, (long)o, err);
    }
}

static void test_norm(void **state)
{
    int k;
    (void)state;
    assert_int_equal(qo_fx_norm3_q30(0, 0, 0), 0);
    assert_int_equal(qo_fx_norm4_q30(0, 0, 0, 0), 0);
    assert_int_equal(qo_fx_norm3_q30(QO_Q30_ONE, 0, 0), QO_Q30_ONE);
    assert_int_equal(qo_fx_norm3_q30(0, -QO_Q30_ONE, 0), QO_Q30_ONE);
    assert_int_equal(qo_fx_norm4_q30(QO_Q30_ONE / 2, QO_Q30_ONE / 2, QO_Q30_ONE / 2, -QO_Q30_ONE / 2), QO_Q30_ONE);
    assert_int_equal(qo_fx_norm4_q30(1, 0, 0, 0), 1);
    assert_int_equal(qo_fx_norm4_q30(INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN), INT32_MAX);
    assert_int_equal(qo_fx_norm3_q30(INT32_MIN, INT32_MIN, INT32_MIN), INT32_MAX);
    assert_int_equal(qo_fx_norm3_q30(INT32_MIN, 0, 0), INT32_MAX); /* 2.0 does not fit */
    rng_state = 6;
    for (k = 0; k < 100000; k++) {
        int32_t w = rnd_i32_mag() / 2, x = rnd_i32_mag() / 2, y = rnd_i32_mag() / 2, z = rnd_i32_mag() / 2;
        long double r3 = sqrtl((long double)x * x + (long double)y * y + (long double)z * z);
        long double r4 = sqrtl((long double)w * w + (long double)x * x + (long double)y * y + (long double)z * z);
        double e3, e4;
        if (r3 >= INT32_MAX) r3 = INT32_MAX;
        if (r4 >= INT32_MAX) r4 = INT32_MAX;
        e3 = (double)((long double)qo_fx_norm3_q30(x, y, z) - r3);
        e4 = (double)((long double)qo_fx_norm4_q30(w, x, y, z) - r4);
        if (fabs(e3) > 0.5 + 1e-6 || fabs(e4) > 0.5 + 1e-6)
            fail_msg("norm(%ld,%ld,%ld,%ld): errors %.3f %.3f LSB", (long)w, (long)x, (long)y, (long)z, e3, e4);
    }
}

/* The fixed-only forms of sin/cos: the half angle (same inputs as the shared body's fixed row),
 * the Q3.60 kernel, and the NULL outputs (the other output is still written). */
static void check_sincos_half(qo_q28 a)
{
    qo_q30 hs = 7, hc = 7;
    double ehs, ehc;
    assert_int_equal(qo_fx_sincos_half_q28(a, &hs, &hc), QO_OK);
    ehs = (double)hs - sin((double)a / (2.0 * Q28)) * Q30;
    ehc = (double)hc - cos((double)a / (2.0 * Q28)) * Q30;
    if (fabs(ehs) > 1.0 || fabs(ehc) > 1.0)
        fail_msg("sincos_half(%ld): errors half-sin %.3f half-cos %.3f LSB", (long)a, ehs, ehc);
}

static void test_q30_sincos_half_q60_null(void **state)
{
    static const qo_q28 e[] = { 0, 1, -1, 2, INT32_MAX, INT32_MIN, INT32_MIN + 1, QO_Q28_PI,
                                -QO_Q28_PI, QO_Q28_HALF_PI, -QO_Q28_HALF_PI, QO_Q28_TWO_PI,
                                -QO_Q28_TWO_PI, QO_Q28_PI / 4, QO_Q28_PI / 4 + 1, 3 * QO_Q28_HALF_PI,
                                QO_Q28_ONE, -QO_Q28_ONE };
    size_t i;
    int k;
    qo_q30 s, c;
    (void)state;
    for (i = 0; i < sizeof e / sizeof e[0]; i++) {
        check_sincos_half(e[i]);
        check_sincos_half(e[i] > INT32_MIN ? e[i] - 1 : e[i]);
        check_sincos_half(e[i] + (e[i] < INT32_MAX ? 1 : 0));
    }
    assert_int_equal(qo_fx_sincos_q28(0, &s, &c), QO_OK);
    assert_int_equal(s, 0); assert_int_equal(c, QO_Q30_ONE);
    assert_int_equal(qo_fx_sincos_q28(QO_Q28_HALF_PI, NULL, &c), QO_E_NULL);
    assert_true(c >= -1 && c <= 1);
    assert_int_equal(qo_fx_sincos_q28(QO_Q28_HALF_PI, &s, NULL), QO_E_NULL);
    assert_int_equal(s, QO_Q30_ONE);
    rng_state = 7;
    for (k = 0; k < 300000; k++) check_sincos_half(k % 2 ? rnd_i32() : rnd_i32_mag());
    /* Q3.60 kernel: random int64 angles. */
    for (k = 0; k < 100000; k++) {
        int64_t a = (int64_t)rnd();
        double x = (double)a / 1152921504606846976.0, es, ec;
        assert_int_equal(qo_fx_sincos_q60(a, &s, &c), QO_OK);
        es = (double)s - sin(x) * Q30;
        ec = (double)c - cos(x) * Q30;
        if (fabs(es) > 1.0 || fabs(ec) > 1.0) fail_msg("sincos_q60(%lld): %.3f %.3f LSB", (long long)a, es, ec);
    }
}

static void test_wrap(void **state)
{
    int k;
    (void)state;
    assert_int_equal(qo_fx_wrap_pi_q28(0), 0);
    assert_int_equal(qo_fx_wrap_pi_q28(QO_Q28_PI), QO_Q28_PI);
    assert_int_equal(qo_fx_wrap_pi_q28(-QO_Q28_PI), -QO_Q28_PI);
    assert_int_equal(qo_fx_wrap_pi_q28(QO_Q28_TWO_PI), 0);
    rng_state = 10;
    for (k = 0; k < 100000; k++) {
        qo_q28 a = k == 0 ? INT32_MAX : k == 1 ? INT32_MIN : k == 2 ? QO_Q28_PI + 1 : rnd_i32();
        qo_q28 r = qo_fx_wrap_pi_q28(a);
        double want = remainder((double)a / Q28, 2.0 * REF_PI) * Q28;
        double err = (double)r - want;
        if (fabs(err) > 2.0 * REF_PI * Q28 - 2.0) err = fabs(err) - 2.0 * REF_PI * Q28; /* +-pi ties */
        if (fabs(err) > 0.5 + 1e-3 || r > QO_Q28_PI || r < -QO_Q28_PI)
            fail_msg("wrap(%ld) = %ld, error %.3f LSB", (long)a, (long)r, err);
    }
}

static void test_fxconv_boundary(void **state)
{
    qo_q30 o;
    qo_q28 o28;
    qo_q16 o16;
    (void)state;
    assert_int_equal(qo_q30_from_f32(0.0f), 0);
    assert_int_equal(qo_q30_from_f32(1.0f), QO_Q30_ONE);
    assert_int_equal(qo_q30_from_f32(-2.0f), INT32_MIN);
    assert_int_equal(qo_q30_from_f32_checked(-2.0f, &o), QO_OK);
    assert_int_equal(qo_q30_from_f32_checked(2.0f, &o), QO_E_OVERFLOW); assert_int_equal(o, INT32_MAX);
    assert_int_equal(qo_q30_from_f32_checked(-3.0f, &o), QO_E_OVERFLOW); assert_int_equal(o, INT32_MIN);
    assert_int_equal(qo_q30_from_f32_checked(NAN, &o), QO_E_NONFINITE); assert_int_equal(o, 0);
    assert_int_equal(qo_q30_from_f32_checked(INFINITY, &o), QO_E_NONFINITE); assert_int_equal(o, INT32_MAX);
    assert_int_equal(qo_q30_from_f32_checked(-INFINITY, &o), QO_E_NONFINITE); assert_int_equal(o, INT32_MIN);
    assert_int_equal(qo_q30_from_f32_checked(1e30f, &o), QO_E_OVERFLOW);
    assert_int_equal(qo_q30_from_f32_checked(0.5f, NULL), QO_E_NULL);
    /* Ties away from zero: 0.5 LSB and -0.5 LSB; 1.5 LSB -> 2. */
    assert_int_equal(qo_q30_from_f32(ldexpf(1.0f, -31)), 1);
    assert_int_equal(qo_q30_from_f32(-ldexpf(1.0f, -31)), -1);
    assert_int_equal(qo_q30_from_f32(ldexpf(3.0f, -31)), 2);
    assert_int_equal(qo_q30_from_f32(ldexpf(1.0f, -32)), 0);
    /* The classic x + 0.5f trap: 0.49999997 in Q16.16 raw units must not round up. */
    assert_int_equal(qo_q16_from_f32(0.49999997f / 65536.0f), 0);
    /* Odd integers above 2^23 stay exact. */
    assert_int_equal(qo_q16_from_f32(8388609.0f / 65536.0f), 8388609);
    assert_int_equal(qo_q28_from_f32_checked(3.14159265f, &o28), QO_OK);
    assert_true(fabs((double)o28 - 3.14159265f * Q28) <= 0.5);
    assert_int_equal(qo_q16_from_f32_checked(40000.0f, &o16), QO_E_OVERFLOW); assert_int_equal(o16, INT32_MAX);
    assert_true(qo_q30_to_f32(QO_Q30_ONE) == 1.0f);
    assert_true(qo_q28_to_f32(-QO_Q28_ONE) == -1.0f);
    assert_true(qo_q16_to_f32(QO_Q16_ONE / 2) == 0.5f);
    assert_true(qo_q30_to_f32(INT32_MIN) == -2.0f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        /* shared bodies: float32, then fixed point */
        BOTH(test_sincos),
        BOTH(test_atan2),
        BOTH(test_asin_acos),
        /* float32 only */
        cmocka_unit_test(test_exp_log),
        /* fixed only */
        cmocka_unit_test(test_mul_edges_and_sweep),
        cmocka_unit_test(test_mul32_parts),
        cmocka_unit_test(test_add_sub_neg_saturate),
        cmocka_unit_test(test_sum_round),
        cmocka_unit_test(test_div),
        cmocka_unit_test(test_sqrt),
        cmocka_unit_test(test_rsqrt),
        cmocka_unit_test(test_norm),
        cmocka_unit_test(test_q30_sincos_half_q60_null),
        cmocka_unit_test(test_wrap),
        cmocka_unit_test(test_fxconv_boundary),
    };
    return cmocka_run_group_tests_name("math", tests, NULL, NULL);
}
