/*
 * fuzz/fuzz_fxmath.c - the fixed-point primitives (qorient/fxmath.h) and the float <-> fixed
 * boundary (qorient/fxconv.h) fed int32 values (raw and the edges INT32_MIN/MAX, 0, +-1, the
 * Q ONEs, pi...) and floats (NaN, Inf, denormals...). Every result is checked against an exact
 * int64 or a double computation written here, to the accuracy each function documents:
 * add/sub/neg/mul exact (rounded once, ties toward +inf, saturated), div rounded to nearest
 * (ties away) with QO_E_DEGENERATE / QO_E_OVERFLOW, sqrt correctly rounded, rsqrt <= 1 LSB,
 * norms, sincos, atan2, asin/acos <= 1 LSB, wrap_pi congruent and in range, float -> fixed
 * exactly rounded or the documented status. UBSan watches every shift and product.
 */
#include "fuzz_common.h"
#include "qorient/fxconv.h"
#include "qorient/fxmath.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

/* One LSB plus what double rounding of the reference can add (far below 0.01 LSB). */
#define FUZZ_FX_TOL 1.01
#define FUZZ_FX_PI 3.14159265358979323846

static int64_t fuzz_fx_sat(int64_t v)
{
    return v > INT32_MAX ? INT32_MAX : v < INT32_MIN ? INT32_MIN : v;
}

/* round(a*b / 2^s), ties toward +inf, saturated: the contract of qo_fx_mul_*. */
static int32_t fuzz_fx_mul_ref(int32_t a, int32_t b, int s)
{
    int64_t p = (int64_t)a * b;
    int64_t r = (p + ((int64_t)1 << (s - 1))) >> s;   /* arithmetic shift: floor */
    return (int32_t)fuzz_fx_sat(r);
}

static void fuzz_fx_div(qo_status (*fn)(int32_t, int32_t, int32_t *), int32_t num, int32_t den, int s,
                        const char *what)
{
    int32_t o = 12345;
    qo_status st = fn(num, den, &o);
    if (den == 0) {
        QO_FUZZ_CHECK(st == QO_E_DEGENERATE && o == 0, "%s(%d, 0): status %d out %d", what, num, (int)st, o);
        return;
    } else {
        int64_t n = (int64_t)num * ((int64_t)1 << s), q = n / den, r = n % den;
        int64_t ar = r < 0 ? -r : r, ad = den < 0 ? -(int64_t)den : den;
        if (2 * ar >= ad) q += ((n < 0) != (den < 0)) ? -1 : 1;
        if (q > INT32_MAX || q < INT32_MIN) {
            QO_FUZZ_CHECK(st == QO_E_OVERFLOW && o == (q > 0 ? INT32_MAX : INT32_MIN), "%s(%d, %d): status %d out %d",
                          what, num, den, (int)st, o);
        } else {
            QO_FUZZ_CHECK(st == QO_OK && o == q, "%s(%d, %d): status %d out %d, exact %lld", what, num, den, (int)st,
                          o, (long long)q);
        }
    }
}

/* r == floor(sqrt(v) + 1/2) exactly. */
static int fuzz_fx_is_round_sqrt(uint64_t v, uint64_t r)
{
    if (r > ((uint64_t)1 << 32)) return 0;
    if (r == ((uint64_t)1 << 32)) return v >= UINT64_MAX - ((uint64_t)1 << 32) + 2;
    if (r == 0) return v == 0;
    return v >= r * r - r + 1 && v <= r * r + r;
}

static void fuzz_fx_near(double got, double want, double tol, const char *what, int32_t in)
{
    QO_FUZZ_CHECK(fabs(got - want) <= tol, "%s(%d): %.3f, reference %.3f (tol %.2f LSB)", what, in, got, want, tol);
}

static void fuzz_fx_from_f32(qo_status (*fn)(float, int32_t *), float v, double scale, const char *what)
{
    int32_t o = 12345;
    qo_status st = fn(v, &o);
    if (v != v) {
        QO_FUZZ_CHECK(st == QO_E_NONFINITE && o == 0, "%s(NaN): %d %d", what, (int)st, o);
    } else if (isinf(v)) {
        QO_FUZZ_CHECK(st == QO_E_NONFINITE && o == (v > 0 ? INT32_MAX : INT32_MIN), "%s(inf): %d %d", what, (int)st, o);
    } else {
        double x = (double)v * scale;   /* exact: float times a power of two */
        double r = x >= 0 ? floor(x + 0.5) : -floor(-x + 0.5);   /* ties away from zero */
        if (r > INT32_MAX || r < INT32_MIN)
            QO_FUZZ_CHECK(st == QO_E_OVERFLOW && o == (r > 0 ? INT32_MAX : INT32_MIN), "%s(%a): %d %d", what, (double)v,
                          (int)st, o);
        else
            QO_FUZZ_CHECK(st == QO_OK && (double)o == r, "%s(%a): status %d out %d, exact %.1f", what, (double)v,
                          (int)st, o, r);
    }
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    int32_t a = qo_fz_i32(&f), b = qo_fz_i32(&f), c = qo_fz_i32(&f), d = qo_fz_i32(&f), o;
    uint32_t hi = (uint32_t)qo_fz_i32(&f), lo = (uint32_t)qo_fz_i32(&f);
    int64_t big = (int64_t)(((uint64_t)hi << 32) | lo);   /* two's complement: implementation-defined, not UB */
    float v = qo_fz_f32(&f);
    const double two30 = 1073741824.0, two28 = 268435456.0;
    qo_q30 s, co;
    qo_status st;
    double ang, ref, dd;
    uint64_t u;

    /* saturating arithmetic */
    QO_FUZZ_CHECK(qo_fx_sat_i32(big) == fuzz_fx_sat(big), "sat_i32");
    QO_FUZZ_CHECK(qo_fx_add_q30(a, b) == fuzz_fx_sat((int64_t)a + b), "add(%d, %d)", a, b);
    QO_FUZZ_CHECK(qo_fx_sub_q30(a, b) == fuzz_fx_sat((int64_t)a - b), "sub(%d, %d)", a, b);
    QO_FUZZ_CHECK(qo_fx_neg_q30(a) == fuzz_fx_sat(-(int64_t)a), "neg(%d)", a);
    QO_FUZZ_CHECK(qo_fx_mul_q30(a, b) == fuzz_fx_mul_ref(a, b, 30), "mul_q30(%d, %d) = %d", a, b, qo_fx_mul_q30(a, b));
    QO_FUZZ_CHECK(qo_fx_mul_q28(a, b) == fuzz_fx_mul_ref(a, b, 28), "mul_q28(%d, %d)", a, b);
    QO_FUZZ_CHECK(qo_fx_mul_q16(a, b) == fuzz_fx_mul_ref(a, b, 16), "mul_q16(%d, %d)", a, b);

    /* exact dot product rounding (preconditions: |term| <= 2^62, n <= 16, shift 8..40) */
    {
        int64_t t[4];
        int64_t r;
        unsigned sh = 8u + (unsigned)((uint32_t)d % 33u);
        t[0] = (int64_t)a * b; t[1] = (int64_t)c * d; t[2] = (int64_t)a * d; t[3] = (int64_t)b * c;
        int64_t hs = 0, ls = 0, one = (int64_t)1 << sh;
        int q;
        r = qo_fx_sum_round_i64(t, 4, sh);
        /* exact reference: each term = h * 2^sh + l with 0 <= l < 2^sh (floor division) */
        for (q = 0; q < 4; q++) {
            int64_t h = t[q] >> sh;   /* arithmetic shift: floor */
            hs += h;
            ls += t[q] - h * one;
        }
        hs += (ls + (one >> 1)) >> sh;   /* round half up */
        QO_FUZZ_CHECK(r == hs, "sum_round(shift %u) = %lld, exact %lld", sh, (long long)r, (long long)hs);
    }

    /* division */
    fuzz_fx_div(qo_fx_div_q30, a, b, 30, "div_q30");
    fuzz_fx_div(qo_fx_div_q28, a, b, 28, "div_q28");
    fuzz_fx_div(qo_fx_div_q16, a, b, 16, "div_q16");
    QO_FUZZ_CHECK(qo_fx_div_q30(a, b, NULL) == QO_E_NULL, "div NULL");

    /* square roots */
    u = (uint64_t)big;
    QO_FUZZ_CHECK(fuzz_fx_is_round_sqrt(u, qo_fx_sqrt_u64(u)), "sqrt_u64(%llu) = %llu", (unsigned long long)u,
                  (unsigned long long)qo_fx_sqrt_u64(u));
    st = qo_fx_sqrt_q30(a, &o);
    if (a < 0) QO_FUZZ_CHECK(st == QO_E_RANGE && o == 0, "sqrt_q30(%d): %d %d", a, (int)st, o);
    else QO_FUZZ_CHECK(st == QO_OK && fuzz_fx_is_round_sqrt((uint64_t)a << 30, (uint64_t)o), "sqrt_q30(%d) = %d", a, o);
    st = qo_fx_rsqrt_q30(a, &o);
    if (a <= 0) QO_FUZZ_CHECK(st == QO_E_RANGE && o == INT32_MAX, "rsqrt_q30(%d): %d %d", a, (int)st, o);
    else if (a <= (1 << 28)) QO_FUZZ_CHECK(st == QO_E_OVERFLOW && o == INT32_MAX, "rsqrt_q30(%d): %d %d", a, (int)st, o);
    else {
        QO_FUZZ_CHECK(st == QO_OK, "rsqrt_q30(%d) status %d", a, (int)st);
        fuzz_fx_near(o, ldexp(1.0, 45) / sqrt((double)a), FUZZ_FX_TOL, "rsqrt_q30", a);
    }
    ref = sqrt((double)a * a + (double)b * b + (double)c * c);
    fuzz_fx_near(qo_fx_norm3_q30(a, b, c), ref >= INT32_MAX ? INT32_MAX : ref, 0.51, "norm3_q30", a);
    ref = sqrt((double)a * a + (double)b * b + (double)c * c + (double)d * d);
    fuzz_fx_near(qo_fx_norm4_q30(a, b, c, d), ref >= INT32_MAX ? INT32_MAX : ref, 0.51, "norm4_q30", a);

    /* sin / cos */
    ang = (double)a / two28;
    st = qo_fx_sincos_q28(a, &s, &co);
    QO_FUZZ_CHECK(st == QO_OK && s >= -QO_Q30_ONE && s <= QO_Q30_ONE && co >= -QO_Q30_ONE && co <= QO_Q30_ONE,
                  "sincos_q28(%d): %d %d %d", a, (int)st, s, co);
    fuzz_fx_near(s, sin(ang) * two30, FUZZ_FX_TOL, "sincos_q28 sin", a);
    fuzz_fx_near(co, cos(ang) * two30, FUZZ_FX_TOL, "sincos_q28 cos", a);
    QO_FUZZ_CHECK(qo_fx_sin_q28(a) == s && qo_fx_cos_q28(a) == co, "sin_q28/cos_q28 differ from sincos");
    st = qo_fx_sincos_half_q28(a, &s, &co);
    QO_FUZZ_CHECK(st == QO_OK, "sincos_half status %d", (int)st);
    fuzz_fx_near(s, sin(ang / 2.0) * two30, FUZZ_FX_TOL, "sincos_half sin", a);
    fuzz_fx_near(co, cos(ang / 2.0) * two30, FUZZ_FX_TOL, "sincos_half cos", a);
    st = qo_fx_sincos_q60(big, &s, &co);
    QO_FUZZ_CHECK(st == QO_OK, "sincos_q60 status %d", (int)st);
    fuzz_fx_near(s, sin((double)big / ldexp(1.0, 60)) * two30, FUZZ_FX_TOL, "sincos_q60 sin", (int32_t)(big >> 32));
    fuzz_fx_near(co, cos((double)big / ldexp(1.0, 60)) * two30, FUZZ_FX_TOL, "sincos_q60 cos", (int32_t)(big >> 32));
    st = qo_fx_sincos_q28(0, &s, &co);
    QO_FUZZ_CHECK(s == 0 && co == QO_Q30_ONE, "sincos(0) = %d %d", s, co);
    QO_FUZZ_CHECK(qo_fx_sincos_q28(a, NULL, &co) == QO_E_NULL, "sincos NULL");

    /* atan2 of any int32 pair, a difference taken modulo 2pi (+-pi is one angle) */
    o = qo_fx_atan2_q28(a, b);
    QO_FUZZ_CHECK(o >= -QO_Q28_PI && o <= QO_Q28_PI, "atan2(%d, %d) = %d out of [-pi, pi]", a, b, o);
    if (a == 0 && b == 0) {
        QO_FUZZ_CHECK(o == 0, "atan2(0, 0) = %d", o);
    } else {
        dd = (double)o - atan2((double)a, (double)b) * two28;
        if (dd > FUZZ_FX_PI * two28) dd -= 2.0 * FUZZ_FX_PI * two28;
        if (dd < -FUZZ_FX_PI * two28) dd += 2.0 * FUZZ_FX_PI * two28;
        QO_FUZZ_CHECK(fabs(dd) <= FUZZ_FX_TOL, "atan2(%d, %d) = %d off by %.3f LSB", a, b, o, dd);
        if (a == 0) QO_FUZZ_CHECK(o == (b > 0 ? 0 : QO_Q28_PI), "atan2(0, %d) = %d", b, o);
    }

    /* asin / acos with the input clamped to [-1, 1] */
    {
        double x = (double)a / two30;
        if (x > 1.0) x = 1.0;
        if (x < -1.0) x = -1.0;
        fuzz_fx_near(qo_fx_asin_q28(a), asin(x) * two28, FUZZ_FX_TOL, "asin_q28", a);
        fuzz_fx_near(qo_fx_acos_q28(a), acos(x) * two28, FUZZ_FX_TOL, "acos_q28", a);
    }

    /* wrap to [-pi, pi], congruent mod 2pi */
    o = qo_fx_wrap_pi_q28(a);
    QO_FUZZ_CHECK(o >= -QO_Q28_PI && o <= QO_Q28_PI, "wrap_pi(%d) = %d", a, o);
    if (a >= -QO_Q28_PI && a <= QO_Q28_PI) QO_FUZZ_CHECK(o == a, "wrap_pi(%d) changed an in-range angle to %d", a, o);
    dd = ((double)a - (double)o) / (2.0 * FUZZ_FX_PI * two28);
    QO_FUZZ_CHECK(fabs(dd - floor(dd + 0.5)) * 2.0 * FUZZ_FX_PI * two28 <= FUZZ_FX_TOL, "wrap_pi(%d) = %d not congruent", a, o);

    /* float -> fixed boundary */
    fuzz_fx_from_f32(qo_q30_from_f32_checked, v, two30, "q30_from_f32");
    fuzz_fx_from_f32(qo_q28_from_f32_checked, v, two28, "q28_from_f32");
    fuzz_fx_from_f32(qo_q16_from_f32_checked, v, 65536.0, "q16_from_f32");
    QO_FUZZ_CHECK(qo_q30_to_f32(a) == (float)((double)a / two30), "q30_to_f32(%d)", a);
    QO_FUZZ_CHECK(qo_q28_to_f32(a) == (float)((double)a / two28), "q28_to_f32(%d)", a);
    QO_FUZZ_CHECK(qo_q16_to_f32(a) == (float)((double)a / 65536.0), "q16_to_f32(%d)", a);
    return 0;
}
