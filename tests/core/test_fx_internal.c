/* The fixed-point core's private integer helpers (lib/src/fx_internal.h), tested directly.
 * Apart from tests/core/test_math.c (the public kernels of both cores) because the private
 * header keeps this program off the emulated Cortex-M list (tests/qemu/run-target.sh runs only
 * tests that include the public "qorient/..." and "common/..." headers). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <math.h>
#include <cmocka.h>

#include "qorient/fxmath.h"

#include "../lib/src/fx_internal.h"
#include "common/ref.h"

#define TWO30 1073741824.0

static uint64_t rng_state;
static uint64_t rnd(void) { return ref_splitmix64(&rng_state); } /* tests/common/ref.c */

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
        /* the clamped form agrees inside its range (spline_fx.c's sampler) */
        if (qo_fx_rshift_round_away_clamped(v, (int32_t)s) != want)
            fail_msg("rshift_round_away_clamped(%lld, %u) = %lld, want %lld", (long long)v, s,
                     (long long)qo_fx_rshift_round_away_clamped(v, (int32_t)s), (long long)want);
    }
    if (s <= 62) {
        int64_t r, want = ref_floor(v, s, &r);
        if (qo_fx_rshift_floor(v, s) != want)
            fail_msg("rshift_floor(%lld, %u) = %lld, want %lld", (long long)v, s,
                     (long long)qo_fx_rshift_floor(v, s), (long long)want);
    }
    /* the 32-bit-word unsigned form (euler_fx.c): v >= 0, s <= 34, a result below 2^32 */
    if (v >= 0 && s <= 34 && s <= 62 && ref_round_up(v, s) <= (int64_t)UINT32_MAX &&
        v <= INT64_MAX - ((int64_t)1 << (s - 1))) {
        uint32_t got = qo_fx_urshift_round_up_u32((uint64_t)v, s);
        if ((int64_t)got != ref_round_up(v, s))
            fail_msg("urshift_round_up_u32(%lld, %u) = %lu, want %lld", (long long)v, s,
                     (unsigned long)got, (long long)ref_round_up(v, s));
    }
}

/* floor(num / den) checked by its definition: num - q den in [0, den), worked mod 2^64 so
 * no product overflows (an off-by-k quotient moves the remainder by k den out of range). */
static void check_div_floor(int64_t num, int64_t den)
{
    int64_t q = qo_fx_div_floor(num, den);
    uint64_t r = (uint64_t)num - (uint64_t)q * (uint64_t)den;
    if (r >= (uint64_t)den)
        fail_msg("div_floor(%lld, %lld) = %lld", (long long)num, (long long)den, (long long)q);
}

/* The int32 helpers: |v| and v^2 against int64 arithmetic (exact for every int32), every
 * edge and random values; floor division by its definition; clamped shifts out of range. */
static void test_internal_int32_helpers(void **state)
{
    static const int32_t e[] = { 0, 1, -1, 2, -2, 46340, -46340, 46341, -46341, 65535, 65536,
                                 -65536, 0x7FFF0000, INT32_MAX, INT32_MIN, INT32_MIN + 1 };
    static const int64_t dn[] = { 1, 2, 3, 7, 1000000007, ((int64_t)1 << 32) + 1,
                                  (int64_t)7244019458077122842, INT64_MAX };
    size_t i, j;
    (void)state;
    rng_state = 0x5EED0016u;
    for (i = 0; i < sizeof e / sizeof e[0] + 1000000u; i++) {
        int32_t v = i < sizeof e / sizeof e[0] ? e[i] : (int32_t)(uint32_t)(rnd() >> (rnd() % 33u));
        uint64_t a = (uint64_t)(v < 0 ? -(int64_t)v : (int64_t)v);
        if (qo_fx_abs_u32(v) != a)
            fail_msg("abs_u32(%ld) = %lu", (long)v, (unsigned long)qo_fx_abs_u32(v));
        if (qo_fx_sq_u64(v) != (uint64_t)((int64_t)v * v) || qo_fx_usq_u64((uint32_t)a) != a * a)
            fail_msg("sq_u64(%ld) = %llu", (long)v, (unsigned long long)qo_fx_sq_u64(v));
    }
    assert_true(qo_fx_sq_u64(INT32_MIN) == (uint64_t)1 << 62);
    assert_true(qo_fx_div_floor(-7, 2) == -4 && qo_fx_div_floor(7, 2) == 3);
    assert_true(qo_fx_div_floor(-6, 2) == -3 && qo_fx_div_floor(INT64_MIN, 1) == INT64_MIN);
    for (i = 0; i < sizeof dn / sizeof dn[0]; i++) {
        static const int64_t nm[] = { 0, 1, -1, INT64_MAX, INT64_MIN, INT64_MIN + 1, 5, -5 };
        for (j = 0; j < sizeof nm / sizeof nm[0]; j++) check_div_floor(nm[j], dn[i]);
    }
    for (i = 0; i < 200000; i++) {
        int64_t d = (int64_t)(rnd() >> (1u + rnd() % 63u));
        check_div_floor((int64_t)rnd() >> (rnd() % 63u), d > 0 ? d : 1);
    }
    /* out of the shift range: s <= 0 leaves v, s >= 64 gives 0 for every v */
    assert_true(qo_fx_rshift_round_away_clamped(-12345, 0) == -12345);
    assert_true(qo_fx_rshift_round_away_clamped(12345, -9) == 12345);
    assert_true(qo_fx_rshift_round_away_clamped(INT64_MIN, INT32_MIN) == INT64_MIN);
    assert_true(qo_fx_rshift_round_away_clamped(((int64_t)1 << 62) - 1, 63) == 0);
    assert_true(qo_fx_rshift_round_away_clamped(INT64_MAX, 63) == 1);
    assert_true(qo_fx_rshift_round_away_clamped(INT64_MIN, 64) == 0);
    assert_true(qo_fx_rshift_round_away_clamped(INT64_MAX, INT32_MAX) == 0);
    /* the unsigned form at its top shift and its s == 0 and s == 32 paths */
    assert_true(qo_fx_urshift_round_up_u32(((uint64_t)1 << 34) * 3 + ((uint64_t)1 << 33), 34) == 4u);
    assert_true(qo_fx_urshift_round_up_u32(0xFFFFFFFFu, 0) == 0xFFFFFFFFu);
    assert_true(qo_fx_urshift_round_up_u32(((uint64_t)5 << 32) | 0x80000000u, 32) == 6u);
    assert_true(qo_fx_urshift_round_up_u32(((uint64_t)5 << 32) | 0x7FFFFFFFu, 32) == 5u);
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

/* ---- the saturating helpers (spline_fx.c, motion_fx.c) and the bit count (euler_fx.c),
 * each against its specification computed another way: the exact sum or product in two
 * 64-bit words (a 128-bit value, no __int128: this runs on 32-bit targets too), the int32
 * clamp in double (exact for every value near the int32 range), the bit count by a linear
 * search with 64-bit shifts. A flag starts at 2: a clamp must set it to 1, anything else must
 * leave it at 2 (the helpers collect one flag over a run of calls, never clear it). ---- */

/* An exact 128-bit two's complement value hi 2^64 + lo. */
typedef struct wide { int64_t hi; uint64_t lo; } wide;

static wide wide_from(int64_t a)
{
    wide w;
    w.hi = a < 0 ? -1 : 0;
    w.lo = (uint64_t)a;
    return w;
}

static wide wide_add(wide a, wide b)
{
    wide r;
    r.lo = a.lo + b.lo;
    r.hi = a.hi + b.hi + (r.lo < a.lo);
    return r;
}

/* The exact value clamped to the symmetric int64 range; *clamped says whether it was
 * outside [-INT64_MAX, INT64_MAX]. */
static int64_t wide_clamp_sym(wide w, int *clamped)
{
    int fits = w.hi == ((w.lo >> 63) ? -1 : 0);
    *clamped = 1;
    if (!fits) return w.hi < 0 ? -INT64_MAX : INT64_MAX;
    if (w.lo == (uint64_t)1 << 63) return -INT64_MAX;   /* INT64_MIN itself */
    *clamped = 0;
    return (int64_t)w.lo;
}

static void check_add_sat(int64_t a, int64_t b)
{
    int ovf = 2, clamped;
    int64_t got = qo_fx_add_sat_sym_i64(a, b, &ovf);
    int64_t want = wide_clamp_sym(wide_add(wide_from(a), wide_from(b)), &clamped);
    if (b == 0) { want = a; clamped = 0; }   /* documented: a + 0 is a, even INT64_MIN */
    if (got != want || ovf != (clamped ? 1 : 2))
        fail_msg("add_sat_sym_i64(%lld, %lld) = %lld flag %d, want %lld flag %d", (long long)a,
                 (long long)b, (long long)got, ovf, (long long)want, clamped ? 1 : 2);
    if (got == INT64_MIN && !(a == INT64_MIN && b == 0))
        fail_msg("add_sat_sym_i64(%lld, %lld) = INT64_MIN", (long long)a, (long long)b);
}

static void check_mul_sat(int64_t a, int k)
{
    int ovf = 2, clamped, i;
    int64_t got = qo_fx_mul_sat_sym_i64(a, k, &ovf), want;
    wide w = wide_from(0);
    for (i = 0; i < k; i++) w = wide_add(w, wide_from(a));   /* k a by repeated addition */
    want = wide_clamp_sym(w, &clamped);
    if (got != want || ovf != (clamped ? 1 : 2))
        fail_msg("mul_sat_sym_i64(%lld, %d) = %lld flag %d, want %lld flag %d", (long long)a, k,
                 (long long)got, ovf, (long long)want, clamped ? 1 : 2);
}

static void check_sat_i32(int64_t v)
{
    int ovf = 2;
    int32_t got = qo_fx_sat_i32_flag(v, &ovf);
    double d = (double)v, want = d > 2147483647.0 ? 2147483647.0 : d < -2147483648.0 ? -2147483648.0 : d;
    int clamped = d > 2147483647.0 || d < -2147483648.0;
    if ((double)got != want || ovf != (clamped ? 1 : 2) || got != qo_fx_sat_i32(v))
        fail_msg("sat_i32_flag(%lld) = %ld flag %d, want %.0f flag %d", (long long)v, (long)got,
                 ovf, want, clamped ? 1 : 2);
}

static void check_bits_above_30(uint64_t v)
{
    unsigned want = 0, got = qo_fx_bits_above_30_u64(v);
    while ((v >> want) >= ((uint64_t)1 << 30)) want++;
    if (got != want)
        fail_msg("bits_above_30_u64(%llu) = %u, want %u", (unsigned long long)v, got, want);
}

static void test_internal_saturate_count(void **state)
{
    static const int64_t e[] = { 0, 1, -1, 2, -2, INT32_MAX, INT32_MIN, (int64_t)INT32_MAX + 1,
                                 (int64_t)INT32_MIN - 1, INT64_MAX, INT64_MIN, INT64_MAX - 1,
                                 INT64_MIN + 1, INT64_MAX / 2, INT64_MIN / 2, INT64_MAX / 2 + 1,
                                 INT64_MIN / 2 - 1, INT64_MAX / 3, INT64_MAX / 3 + 1,
                                 -(INT64_MAX / 3) - 1, INT64_MAX / 6, INT64_MAX / 6 + 1,
                                 -(INT64_MAX / 6) - 1, (int64_t)1 << 62, -((int64_t)1 << 62) };
    static const int ks[] = { 1, 2, 3, 6, 7, 16 };
    size_t i, j;
    unsigned k;
    int ovf;
    (void)state;
    rng_state = 0x5EED001Au;
    /* the documented edges by value */
    ovf = 0;
    assert_true(qo_fx_sat_i32_flag((int64_t)INT32_MAX + 1, &ovf) == INT32_MAX && ovf == 1);
    ovf = 0;
    assert_true(qo_fx_sat_i32_flag(INT64_MIN, &ovf) == INT32_MIN && ovf == 1);
    ovf = 0;
    assert_true(qo_fx_sat_i32_flag(INT32_MIN, &ovf) == INT32_MIN && ovf == 0);
    ovf = 0;
    assert_true(qo_fx_add_sat_sym_i64(INT64_MAX, 1, &ovf) == INT64_MAX && ovf == 1);
    ovf = 0;
    assert_true(qo_fx_add_sat_sym_i64(INT64_MIN + 1, -1, &ovf) == -INT64_MAX && ovf == 1);
    ovf = 0;
    assert_true(qo_fx_add_sat_sym_i64(-INT64_MAX, 0, &ovf) == -INT64_MAX && ovf == 0);
    assert_true(qo_fx_add_sat_sym_i64(INT64_MIN, 0, &ovf) == INT64_MIN && ovf == 0);
    assert_true(qo_fx_add_sat_sym_i64(INT64_MIN, 1, &ovf) == INT64_MIN + 1 && ovf == 0);
    assert_true(qo_fx_mul_sat_sym_i64(INT64_MAX / 6, 6, &ovf) == INT64_MAX / 6 * 6 && ovf == 0);
    assert_true(qo_fx_mul_sat_sym_i64(INT64_MIN, 1, &ovf) == -INT64_MAX && ovf == 1);
    ovf = 0;
    assert_true(qo_fx_mul_sat_sym_i64(-(INT64_MAX / 3) - 1, 3, &ovf) == -INT64_MAX && ovf == 1);
    assert_true(qo_fx_bits_above_30_u64(0) == 0 && qo_fx_bits_above_30_u64((1u << 30) - 1u) == 0);
    assert_true(qo_fx_bits_above_30_u64(1u << 30) == 1 && qo_fx_bits_above_30_u64(UINT64_MAX) == 34);
    /* every pair of edges, every edge times every k */
    for (i = 0; i < sizeof e / sizeof e[0]; i++) {
        check_sat_i32(e[i]);
        check_bits_above_30((uint64_t)e[i]);
        for (j = 0; j < sizeof e / sizeof e[0]; j++) check_add_sat(e[i], e[j]);
        for (j = 0; j < sizeof ks / sizeof ks[0]; j++) check_mul_sat(e[i], ks[j]);
    }
    /* each power of two and its neighbours, both signs */
    for (k = 0; k < 64; k++) {
        uint64_t p = (uint64_t)1 << k;
        check_bits_above_30(p);
        check_bits_above_30(p - 1u);
        check_bits_above_30(p + 1u);
        if (k < 63) {
            int64_t sp = (int64_t)p;
            check_sat_i32(sp); check_sat_i32(-sp); check_sat_i32(sp - 1); check_sat_i32(-sp - 1);
            check_add_sat(sp, INT64_MAX - sp + 1); check_add_sat(-sp, -INT64_MAX + sp - 1);
            check_add_sat(sp, INT64_MAX - sp); check_add_sat(-sp, -INT64_MAX + sp);
        }
    }
    /* random values of random magnitude */
    for (i = 0; i < 400000; i++) {
        int64_t a = (int64_t)rnd() >> (rnd() % 64u), b = (int64_t)rnd() >> (rnd() % 64u);
        check_sat_i32(a);
        check_bits_above_30(rnd() >> (rnd() % 64u));
        check_add_sat(a, b);
        check_mul_sat(a, 1 + (int)(rnd() % 16u));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_internal_rshift_abs),
        cmocka_unit_test(test_internal_div_round_away),
        cmocka_unit_test(test_internal_int32_helpers),
        cmocka_unit_test(test_internal_newton),
        cmocka_unit_test(test_internal_sincos_2y),
        cmocka_unit_test(test_internal_saturate_count),
    };
    return cmocka_run_group_tests_name("fx_internal", tests, NULL, NULL);
}
