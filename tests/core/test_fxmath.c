/* Fixed-point primitives (qorient/fxmath.h) and the float boundary (qorient/fxconv.h):
 * edge tables and fixed-seed sweeps against exact integer (128-bit) or long double / double
 * references computed here, independently of the code under test. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <cmocka.h>

#include "qorient/fxconv.h"
#include "qorient/fxmath.h"

/* The core's private integer helpers (lib/src/fx_internal.h), tested here directly. */
#include "../lib/src/fx_internal.h"
#include "common/ref.h"

/* The exact references below need 128-bit integers. 32-bit targets (Cortex-M, armhf under
 * tests/qemu) have none: there the tests that need them are skipped, the others run. */
#if defined(__SIZEOF_INT128__)
#define HAVE_I128 1
__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;
#endif

#define TWO30 1073741824.0
#define TWO28 268435456.0

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
        err = (double)o - sqrt((double)x / TWO30) * TWO30;
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
        err = (double)o - TWO30 / sqrt((double)x / TWO30);
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

static void check_sincos(qo_q28 a)
{
    qo_q30 s = 7, c = 7, hs = 7, hc = 7;
    double es, ec, ehs, ehc;
    assert_int_equal(qo_fx_sincos_q28(a, &s, &c), QO_OK);
    assert_int_equal(qo_fx_sincos_half_q28(a, &hs, &hc), QO_OK);
    es = (double)s - sin((double)a / TWO28) * TWO30;
    ec = (double)c - cos((double)a / TWO28) * TWO30;
    ehs = (double)hs - sin((double)a / (2.0 * TWO28)) * TWO30;
    ehc = (double)hc - cos((double)a / (2.0 * TWO28)) * TWO30;
    if (fabs(es) > 1.0 || fabs(ec) > 1.0 || fabs(ehs) > 1.0 || fabs(ehc) > 1.0)
        fail_msg("sincos(%ld): errors sin %.3f cos %.3f half-sin %.3f half-cos %.3f LSB", (long)a, es, ec, ehs, ehc);
    if (s != qo_fx_sin_q28(a) || c != qo_fx_cos_q28(a)) fail_msg("sin/cos != sincos at %ld", (long)a);
    if (s > QO_Q30_ONE || s < -QO_Q30_ONE || c > QO_Q30_ONE || c < -QO_Q30_ONE) fail_msg("sincos(%ld) beyond +-1", (long)a);
}

static void test_sincos(void **state)
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
        check_sincos(e[i]);
        check_sincos(e[i] > INT32_MIN ? e[i] - 1 : e[i]);
        check_sincos(e[i] + (e[i] < INT32_MAX ? 1 : 0));
    }
    assert_int_equal(qo_fx_sincos_q28(0, &s, &c), QO_OK);
    assert_int_equal(s, 0); assert_int_equal(c, QO_Q30_ONE);
    assert_int_equal(qo_fx_sincos_q28(QO_Q28_HALF_PI, NULL, &c), QO_E_NULL);
    assert_true(c >= -1 && c <= 1);
    assert_int_equal(qo_fx_sincos_q28(QO_Q28_HALF_PI, &s, NULL), QO_E_NULL);
    assert_int_equal(s, QO_Q30_ONE);
    rng_state = 7;
    for (k = 0; k < 300000; k++) check_sincos(k % 2 ? rnd_i32() : rnd_i32_mag());
    /* Q3.60 kernel: random int64 angles. */
    for (k = 0; k < 100000; k++) {
        int64_t a = (int64_t)rnd();
        double x = (double)a / 1152921504606846976.0, es, ec;
        assert_int_equal(qo_fx_sincos_q60(a, &s, &c), QO_OK);
        es = (double)s - sin(x) * TWO30;
        ec = (double)c - cos(x) * TWO30;
        if (fabs(es) > 1.0 || fabs(ec) > 1.0) fail_msg("sincos_q60(%lld): %.3f %.3f LSB", (long long)a, es, ec);
    }
}

static void check_atan2(int32_t y, int32_t x)
{
    qo_q28 got = qo_fx_atan2_q28(y, x);
    double want = (x == 0 && y == 0) ? 0.0 : atan2((double)y, (double)x) * TWO28, err;
    if (y == 0 && x < 0) want = M_PI * TWO28; /* +pi for y == 0: integers have no -0 */
    err = (double)got - want;
    if (fabs(err) > 1.0 || got > QO_Q28_PI || got < -QO_Q28_PI)
        fail_msg("atan2(%ld, %ld) = %ld, error %.3f LSB", (long)y, (long)x, (long)got, err);
}

static void test_atan2(void **state)
{
    static const int32_t e[] = { 0, 1, -1, 2, -2, 3, INT32_MAX, INT32_MIN, INT32_MIN + 1,
                                 INT32_MAX - 1, QO_Q30_ONE, -QO_Q30_ONE, 1000000, -999999,
                                 46341, 1 << 20 };
    size_t i, j;
    int k;
    (void)state;
    /* Axes and (0, 0) exactly. */
    assert_int_equal(qo_fx_atan2_q28(0, 0), 0);
    assert_int_equal(qo_fx_atan2_q28(0, 5), 0);
    assert_int_equal(qo_fx_atan2_q28(0, -5), QO_Q28_PI);
    assert_int_equal(qo_fx_atan2_q28(5, 0), QO_Q28_HALF_PI);
    assert_int_equal(qo_fx_atan2_q28(-5, 0), -QO_Q28_HALF_PI);
    assert_int_equal(qo_fx_atan2_q28(INT32_MIN, 0), -QO_Q28_HALF_PI);
    assert_int_equal(qo_fx_atan2_q28(0, INT32_MIN), QO_Q28_PI);
    /* Diagonals and huge / tiny ratios, every combination of the edge values. */
    for (i = 0; i < sizeof e / sizeof e[0]; i++)
        for (j = 0; j < sizeof e / sizeof e[0]; j++) check_atan2(e[i], e[j]);
    assert_int_equal(qo_fx_atan2_q28(-7, 7), -qo_fx_atan2_q28(7, 7));
    rng_state = 8;
    for (k = 0; k < 300000; k++) check_atan2(rnd_i32_mag(), rnd_i32_mag());
    /* Odd symmetry is exact. */
    for (k = 0; k < 10000; k++) {
        int32_t y = rnd_i32_mag(), x = rnd_i32_mag();
        if (y == INT32_MIN || y == 0) continue;
        if (qo_fx_atan2_q28(-y, x) != -qo_fx_atan2_q28(y, x)) fail_msg("atan2 odd symmetry at (%ld, %ld)", (long)y, (long)x);
    }
}

static void check_asin_acos(qo_q30 x)
{
    double xc = (double)x / TWO30, es, ec;
    qo_q28 s = qo_fx_asin_q28(x), c = qo_fx_acos_q28(x);
    if (xc > 1.0) xc = 1.0;
    if (xc < -1.0) xc = -1.0;
    es = (double)s - asin(xc) * TWO28;
    ec = (double)c - acos(xc) * TWO28;
    if (fabs(es) > 1.0 || fabs(ec) > 1.0 || c < 0 || c > QO_Q28_PI || s < -QO_Q28_HALF_PI || s > QO_Q28_HALF_PI)
        fail_msg("asin/acos(%ld): asin %ld (%.3f LSB), acos %ld (%.3f LSB)", (long)x, (long)s, es, (long)c, ec);
}

static void test_asin_acos(void **state)
{
    static const qo_q30 e[] = { 0, 1, -1, QO_Q30_ONE, -QO_Q30_ONE, QO_Q30_ONE - 1, -QO_Q30_ONE + 1,
                                QO_Q30_ONE - 2, QO_Q30_ONE + 1, -QO_Q30_ONE - 1, INT32_MAX,
                                INT32_MIN, QO_Q30_ONE / 2, -QO_Q30_ONE / 2, 759250125 /* ~1/sqrt2 */ };
    size_t i;
    int k;
    (void)state;
    for (i = 0; i < sizeof e / sizeof e[0]; i++) check_asin_acos(e[i]);
    /* The ends are exact. */
    assert_int_equal(qo_fx_asin_q28(QO_Q30_ONE), QO_Q28_HALF_PI);
    assert_int_equal(qo_fx_asin_q28(-QO_Q30_ONE), -QO_Q28_HALF_PI);
    assert_int_equal(qo_fx_acos_q28(QO_Q30_ONE), 0);
    assert_int_equal(qo_fx_acos_q28(-QO_Q30_ONE), QO_Q28_PI);
    assert_int_equal(qo_fx_asin_q28(INT32_MAX), QO_Q28_HALF_PI);
    assert_int_equal(qo_fx_acos_q28(INT32_MIN), QO_Q28_PI);
    assert_int_equal(qo_fx_asin_q28(0), 0);
    /* Just inside the ends (where asin is steep) and a sweep over [-1, 1]. */
    for (k = 1; k < 2000; k++) { check_asin_acos(QO_Q30_ONE - k * k); check_asin_acos(-QO_Q30_ONE + k * k); }
    rng_state = 9;
    for (k = 0; k < 200000; k++) check_asin_acos((qo_q30)(rnd() % (2u * QO_Q30_ONE + 1u)) - QO_Q30_ONE);
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
        double want = remainder((double)a / TWO28, 2.0 * M_PI) * TWO28;
        double err = (double)r - want;
        if (fabs(err) > 2.0 * M_PI * TWO28 - 2.0) err = fabs(err) - 2.0 * M_PI * TWO28; /* +-pi ties */
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
    assert_true(fabs((double)o28 - 3.14159265f * TWO28) <= 0.5);
    assert_int_equal(qo_q16_from_f32_checked(40000.0f, &o16), QO_E_OVERFLOW); assert_int_equal(o16, INT32_MAX);
    assert_true(qo_q30_to_f32(QO_Q30_ONE) == 1.0f);
    assert_true(qo_q28_to_f32(-QO_Q28_ONE) == -1.0f);
    assert_true(qo_q16_to_f32(QO_Q16_ONE / 2) == 0.5f);
    assert_true(qo_q30_to_f32(INT32_MIN) == -2.0f);
}


/* ---- lib/src/fx_internal.h: each helper against a reference built from C's truncating
 * division and remainder (a different algorithm from the shifts under test, and exact on
 * every target, so these run on 32-bit ones too). ---- */

/* floor(v / 2^s) and the remainder in [0, 2^s), for 1 <= s <= 62, from / and %. */
static int64_t ref_floor(int64_t v, unsigned s, int64_t *rem)
{
    int64_t d = (int64_t)1 << s, q = v / d, r = v % d;
    if (r < 0) { q -= 1; r += d; }
    *rem = r;
    return q;
}

static int64_t ref_round_up(int64_t v, unsigned s)
{
    int64_t r, q = ref_floor(v, s, &r);
    return q + (r >= ((int64_t)1 << s) - r);   /* frac >= 1/2 rounds up */
}

/* Ties away from zero, on the magnitude (also s = 63 and v = INT64_MIN). */
static int64_t ref_round_away(int64_t v, unsigned s)
{
    uint64_t m = v < 0 ? (uint64_t)0 - (uint64_t)v : (uint64_t)v;
    uint64_t d = (uint64_t)1 << s, q = m / d, r = m % d;
    q += (r >= d - r);
    return v < 0 ? (int64_t)((uint64_t)0 - q) : (int64_t)q;
}

static void check_rshift(int64_t v, unsigned s)
{
    if (s <= 62 && v <= INT64_MAX - ((int64_t)1 << (s - 1))) {
        int64_t got = qo_fx_rshift_round_up(v, s), want = ref_round_up(v, s);
        if (got != want)
            fail_msg("rshift_round_up(%lld, %u) = %lld, want %lld", (long long)v, s,
                     (long long)got, (long long)want);
    }
    {
        int64_t got = qo_fx_rshift_round_away(v, s), want = ref_round_away(v, s);
        if (got != want)
            fail_msg("rshift_round_away(%lld, %u) = %lld, want %lld", (long long)v, s,
                     (long long)got, (long long)want);
        /* odd: the property euler_fx.c relies on for q and -q */
        if (v != INT64_MIN && qo_fx_rshift_round_away(-v, s) != -got)
            fail_msg("rshift_round_away(%lld, %u) not odd", (long long)v, s);
    }
}

static void test_internal_rshift_abs(void **state)
{
    static const int64_t e[] = { 0, 1, -1, 2, -2, 3, -3, 5, -5, 6, -6, 7, -7, INT64_MAX,
                                 INT64_MIN, INT64_MAX - 1, INT64_MIN + 1, INT32_MAX, INT32_MIN,
                                 (int64_t)1 << 62, -((int64_t)1 << 62) };
    unsigned s, k;
    size_t i;
    int64_t v;
    (void)state;
    rng_state = 0x5EED0014u;
    /* |v|: exact for every value, INT64_MIN included */
    assert_true(qo_fx_abs_u64(INT64_MIN) == (uint64_t)1 << 63);
    assert_true(qo_fx_abs_u64(INT64_MAX) == (uint64_t)INT64_MAX);
    assert_true(qo_fx_abs_u64(-1) == 1u && qo_fx_abs_u64(0) == 0u && qo_fx_abs_u64(7) == 7u);
    /* ties: the two roundings differ exactly on negative halves */
    assert_true(qo_fx_rshift_round_up(-5, 1) == -2 && qo_fx_rshift_round_away(-5, 1) == -3);
    assert_true(qo_fx_rshift_round_up(5, 1) == 3 && qo_fx_rshift_round_away(5, 1) == 3);
    assert_true(qo_fx_rshift_round_up(-6, 2) == -1 && qo_fx_rshift_round_away(-6, 2) == -2);
    assert_true(qo_fx_rshift_round_away(INT64_MIN, 63) == -1);
    /* exhaustive on small values: every tie and every remainder of every shift up to 13 */
    for (s = 1; s <= 13; s++)
        for (v = -(1 << 14); v <= (1 << 14); v++) check_rshift(v, s);
    /* edges and their neighbours of each power of two, every shift */
    for (s = 1; s <= 63; s++) {
        for (i = 0; i < sizeof e / sizeof e[0]; i++) check_rshift(e[i], s);
        for (k = 1; k <= 62; k++) {
            int64_t p = (int64_t)1 << k;
            check_rshift(p, s); check_rshift(p - 1, s); check_rshift(p + 1, s);
            check_rshift(-p, s); check_rshift(-p - 1, s); check_rshift(1 - p, s);
            check_rshift(p / 2 * 3, s); check_rshift(-(p / 2 * 3), s);   /* ties at s = k */
        }
    }
    /* random values of random magnitude */
    for (i = 0; i < 400000; i++) {
        v = (int64_t)rnd();
        v >>= rnd() % 63u;
        check_rshift(v, 1u + (unsigned)(rnd() % 63u));
    }
}

static int64_t ref_div_away(int64_t num, uint64_t den)
{
    uint64_t m = num < 0 ? (uint64_t)0 - (uint64_t)num : (uint64_t)num;
    uint64_t q = m / den, r = m % den;
    q += (r >= den - r);
    return num < 0 ? -(int64_t)q : (int64_t)q;
}

static void check_div_away(int64_t num, uint64_t den)
{
    int64_t got = qo_fx_div_round_away(num, den), want = ref_div_away(num, den);
    if (got != want)
        fail_msg("div_round_away(%lld, %llu) = %lld, want %lld", (long long)num,
                 (unsigned long long)den, (long long)got, (long long)want);
}

static void test_internal_div_round_away(void **state)
{
    static const uint64_t d[] = { 1, 2, 3, 4, 5, 7, 10, 1u << 30, (1u << 30) + 1, 0xFFFFFFFFu,
                                  (uint64_t)1 << 32, ((uint64_t)1 << 62) + 3 };
    static const int64_t n[] = { 0, 1, -1, 2, -2, 3, -3, 5, -5, 15, -15, INT32_MAX, INT32_MIN,
                                 ((int64_t)1 << 61) - 1, -((int64_t)1 << 61),
                                 INT64_MAX / 2, -(INT64_MAX / 2) };
    size_t i, j;
    int64_t v;
    (void)state;
    rng_state = 0x5EED0015u;
    assert_true(qo_fx_div_round_away(5, 2) == 3 && qo_fx_div_round_away(-5, 2) == -3);
    assert_true(qo_fx_div_round_away(7, 2) == 4 && qo_fx_div_round_away(-7, 2) == -4);
    assert_true(qo_fx_div_round_away(-4, 3) == -1 && qo_fx_div_round_away(-5, 3) == -2);
    for (i = 0; i < sizeof n / sizeof n[0]; i++)
        for (j = 0; j < sizeof d / sizeof d[0]; j++) check_div_away(n[i], d[j]);
    /* exhaustive on small numerators and denominators (every tie of odd and even den) */
    for (j = 1; j <= 64; j++)
        for (v = -2000; v <= 2000; v++) check_div_away(v, j);
    for (i = 0; i < 400000; i++) {
        uint64_t den = rnd() >> (1u + rnd() % 63u);
        int64_t num = (int64_t)(rnd() >> 2) - ((int64_t)1 << 61);   /* |num| <= 2^61 */
        if (den == 0) den = 1;
        check_div_away(num >> (rnd() % 62u), den);
    }
}

/* The reciprocal estimates against the exact floor(2^62 / d) (a 64-bit division). */
static void check_recip(uint32_t d)
{
    uint64_t ref = ((uint64_t)1 << 62) / d;
    uint32_t r1 = qo_fx_recip62_u32(d), r2 = qo_fx_recip62_step(d, r1);
    uint64_t e1 = r1 > ref ? r1 - ref : ref - r1, e2 = r2 > ref ? r2 - ref : ref - r2;
    /* documented: ~2^-28 after qo_fx_recip62_u32, ~2^-31 after one more step (bounds with
     * margin for the truncations: 2^-27 and 2^-29 relative) */
    if ((e1 << 27) > ref || (e2 << 29) > ref)
        fail_msg("recip62(%lu): %lu then %lu, want %lu", (unsigned long)d, (unsigned long)r1,
                 (unsigned long)r2, (unsigned long)ref);
}

/* The reciprocal square root of the fast normalisation against double (53 bits): within
 * 2^-26 relative over the whole domain (every top-20-bit value, both ends, random). */
static void check_rsqrt32(uint32_t x)
{
    double want = 1073741824.0 / sqrt((double)x / 4294967296.0);
    uint32_t got = qo_fx_rsqrt32_q30(x);
    if (fabs((double)got - want) > want * ldexp(1.0, -26))
        fail_msg("rsqrt32(%lu) = %lu, want %.1f", (unsigned long)x, (unsigned long)got, want);
}

/* Both Newton estimates over their whole domains: both ends, every value of the top 20 bits
 * (with random low bits), random values, and both sides of every recip62 seed boundary. */
static void test_internal_newton(void **state)
{
    uint32_t k, i;
    (void)state;
    rng_state = 0x5EED0016u;
    check_recip(0x80000000u);
    check_recip(0xFFFFFFFFu);
    check_rsqrt32(0x40000000u);
    check_rsqrt32(0xFFFFFFFFu);
    for (k = 64; k < 128; k++) {   /* 64 intervals of 2^25 */
        check_recip(k << 25);
        check_recip((k << 25) + 1u);
        if (k > 64) check_recip((k << 25) - 1u);
    }
    for (k = 1u << 18; k < (1u << 20); k++) {
        uint32_t x = (k << 12) | (uint32_t)(rnd() & 0xFFFu);   /* [2^30, 2^32) */
        check_rsqrt32(x);
        if (x >= 0x80000000u) check_recip(x);
    }
    for (i = 0; i < 200000; i++) {
        uint32_t x = (uint32_t)rnd();
        check_recip(x | 0x80000000u);
        check_rsqrt32(x < 0x40000000u ? x + 0x40000000u : x);
    }
}

/* sin and cos of 2y (the fast slerp's) against double libm over all of y in [0, pi/4]:
 * a strided sweep (every 997th value), both ends and random values; within 8 LSB. */
static void check_sincos_2y(uint32_t y)
{
    qo_q30 s, c;
    double a = 2.0 * (double)y / 2147483648.0, es, ec;
    qo_fx_sincos_2y_q30(y, &s, &c);
    es = fabs((double)s - sin(a) * TWO30);
    ec = fabs((double)c - cos(a) * TWO30);
    if (es > 8.0 || ec > 8.0)
        fail_msg("sincos_2y(%lu): sin %ld (%.2f LSB), cos %ld (%.2f LSB)", (unsigned long)y,
                 (long)s, es, (long)c, ec);
}

static void test_internal_sincos_2y(void **state)
{
    const uint32_t top = 1686629713u;   /* pi/4 in Q1.31, rounded up */
    uint32_t y;
    int i;
    (void)state;
    rng_state = 0x5EED0019u;
    check_sincos_2y(0);
    check_sincos_2y(top);
    for (y = 1; y < top - 997u; y += 997u) check_sincos_2y(y);
    for (i = 0; i < 100000; i++) check_sincos_2y((uint32_t)(rnd() % top));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mul_edges_and_sweep),
        cmocka_unit_test(test_mul32_parts),
        cmocka_unit_test(test_add_sub_neg_saturate),
        cmocka_unit_test(test_sum_round),
        cmocka_unit_test(test_div),
        cmocka_unit_test(test_sqrt),
        cmocka_unit_test(test_rsqrt),
        cmocka_unit_test(test_norm),
        cmocka_unit_test(test_sincos),
        cmocka_unit_test(test_atan2),
        cmocka_unit_test(test_asin_acos),
        cmocka_unit_test(test_wrap),
        cmocka_unit_test(test_fxconv_boundary),
        cmocka_unit_test(test_internal_rshift_abs),
        cmocka_unit_test(test_internal_div_round_away),
        cmocka_unit_test(test_internal_newton),
        cmocka_unit_test(test_internal_sincos_2y),
    };
    return cmocka_run_group_tests_name("fxmath", tests, NULL, NULL);
}
