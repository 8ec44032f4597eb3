/* qorient/interp.h and qorient/interp_fx.h: lerp, nlerp, slerp (short, long, rate), key
 * alignment, Bezier, Shoemake spline and Squad, float32 and fixed point (Q1.30), checked against
 * double-precision references written here from the textbook formulas (not from the code under
 * test), with fixed-seed random inputs and edge tables.
 *
 * One body per behaviour both cores have (docs/TESTING.md, "One body for both cores", as
 * cglm's TEST_IMPL): each body gets a `core` (float32 interp.h or fixed interp_fx.h) through
 * cmocka's prestate, whose adapters take double quaternions, round them to what that core takes
 * (float, or Q1.30 / Q16.16 rounded to nearest and saturated) and give the result back as
 * double; the reference is always computed from the rounded inputs the core actually received,
 * and each core is judged with its own tolerance from the table. The out-of-range input of each
 * core goes through one field, `big` (1e39: Inf in float32, a saturated value in fixed point);
 * where the cores document different answers the body says both (ST).
 *
 * Sections: the adapter table; the shared bodies (BOTH, and the fixed fast tier through the
 * same slerp bodies, FAST); fixed point only (integer ranges, bit-exact ends, Q16.16 spline
 * parameter, saturation-free lerp, extreme magnitudes, agreement with the float32 core);
 * float32 only (NaN, which fixed point cannot hold). Every failure names the core, the case and
 * its inputs. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#define CORES_OWN_TABLE   /* interpolation's table below: key arrays, t, the fast tier */
#include "common/cores.h"
#include "qorient/fxconv.h"
#include "qorient/interp.h"
#include "qorient/interp_fx.h"
#include "qorient/quat.h"
#include "qorient/quat_fx.h"

/* ---- double reference quaternion algebra ------------------------------------------------ */
#include "common/dq_interp.h"

/* Sign-exact dot product for the short-way decision: the products of two Q1.30 values need
 * 60 bits, beyond double; long double (64-bit mantissa or more) holds them and their sum. */
static long double dq_dot_exact(dq a, dq b)
{
    return (long double)a.w * b.w + (long double)a.x * b.x + (long double)a.y * b.y +
           (long double)a.z * b.z;
}
static double norm_dev(dq q) { return fabs(dq_norm(q) - 1.0); }
/* Bit-equal, so -0 and +0 differ (a float32 output is exactly representable in double). */
static int dq_equal(dq a, dq b) { return memcmp(&a, &b, sizeof a) == 0; }

/* Shortest-way slerp of (normalised) a, b; the flip decided by the exact sign of the dot. */
static dq d_slerp(dq a, dq b, double t)
{
    if (dq_dot_exact(a, b) < 0) b = dq_neg(b);
    return dq_unit(d_slerp_raw(dq_unit(a), dq_unit(b), t));
}

/* ---- the two cores behind one interface -------------------------------------------------- */

#define MAXK 12

typedef struct core {
    const char *name;
    int fixed;
    double tol_rot;    /* slerp / nlerp / Bezier vs double, rad */
    double tol_norm;   /* | |q| - 1 | */
    double tol_key;    /* rad: an aligned key vs its input (one normalisation) */
    double tol_long;   /* rad: slerp_long / slerp_rate (the bounds the former both-core twins test used) */
    double tol_abs;    /* absolute error of a unit-range component */
    double tol_ang;    /* rad: the log inside slerp_rate (fixed: Q3.28) */
    double tol_lerp;   /* lerp vs double, absolute per component */
    double max_scale;  /* largest input norm the core can hold (non-unit input tests) */
    double big;        /* beyond the core's range: Inf in float32, saturated in fixed */
    dq (*q_in)(dq q);            /* the input as the core receives it */
    double (*t_in)(double t);    /* t as the core receives it */
    double (*s_in)(double s);    /* spline s / duration (Q16.16 in fixed) as received */
    qo_status (*unit)(dq q, dq *out);   /* the core's own normalisation */
    /* Every wrapper passes a NULL output through to the library (the NULL statuses). */
    qo_status (*lerp)(dq a, dq b, double t, dq *out);
    qo_status (*slerp)(dq a, dq b, double t, dq *out);
    qo_status (*slerp_long)(dq a, dq b, double t, dq *out);
    qo_status (*nlerp)(dq a, dq b, double t, dq *out);
    qo_status (*slerp_rate)(dq a, dq b, double dur, ref_vec3 *w);
    qo_status (*align_keys)(const dq *k, size_t n, dq *out);
    qo_status (*bezier)(const dq *c, size_t n, double t, dq *out);
    qo_status (*bezier3)(dq q0, dq q1, dq q2, dq q3, double t, dq *out);
    qo_status (*spline_controls)(const dq *k, size_t n, dq *a, dq *b);
    qo_status (*spline_eval)(const dq *k, const dq *a, const dq *b, size_t n, double s,
                             dq *out);
    qo_status (*squad_controls)(const dq *k, size_t n, dq *s);
    qo_status (*squad)(dq q0, dq s0, dq s1, dq q1, double t, dq *out);
} core;

/* Each core provides its boundary under its prefix P (f: float32, x: Q1.30):
 *   P##_q / P##_qb   dq <-> quaternion      P##_t   t (float / Q1.30)
 *   P##_s            spline s, duration (float / Q16.16)   P##_rb  rate vector back
 * and the macros below write every wrapper from them, the same text for both cores. */
#define ADAPT_2(P, NAME, FN, QT)                                                              \
    static qo_status P##_##NAME(dq a, dq b, double t, dq *out)                                \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = FN(P##_q(a), P##_q(b), P##_t(t), out ? &o : NULL);                     \
        if (out) *out = P##_qb(o);                                                            \
        return st;                                                                            \
    }
/* Arrays: the core's copy of up to n (<= MAXK) entries, NULL kept NULL. */
#define TO_CORE(P, dst, src, n)                                                               \
    do {                                                                                      \
        size_t i_;                                                                            \
        memset(dst, 0, sizeof dst);                                                           \
        for (i_ = 0; (src) && i_ < (n) && i_ < MAXK; i_++) dst[i_] = P##_q((src)[i_]);        \
    } while (0)
#define FROM_CORE(P, dst, src, n)                                                             \
    do {                                                                                      \
        size_t i_;                                                                            \
        for (i_ = 0; (dst) && i_ < (n) && i_ < MAXK; i_++) (dst)[i_] = P##_qb(src[i_]);       \
    } while (0)
/* Four quaternions and t (bezier3, squad). */
#define ADAPT_4(P, NAME, FN, QT)                                                              \
    static qo_status P##_##NAME(dq q0, dq q1, dq q2, dq q3, double t, dq *out)                \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = FN(P##_q(q0), P##_q(q1), P##_q(q2), P##_q(q3), P##_t(t),               \
                          out ? &o : NULL);                                                   \
        if (out) *out = P##_qb(o);                                                            \
        return st;                                                                            \
    }
/* Keys in, as many out (align_keys, squad_controls); out == keys works in place in the core
 * too. */
#define ADAPT_KEYS(P, NAME, FN, QT)                                                           \
    static qo_status P##_##NAME(const dq *k, size_t n, dq *out)                               \
    {                                                                                         \
        QT pk[MAXK], po[MAXK];                                                                \
        qo_status st;                                                                         \
        TO_CORE(P, pk, k, n);                                                                 \
        memset(po, 0, sizeof po);                                                             \
        st = FN(k ? pk : NULL, n, out == k ? pk : out ? po : NULL);                           \
        if (out == k) FROM_CORE(P, out, pk, n);                                               \
        else FROM_CORE(P, out, po, n);                                                        \
        return st;                                                                            \
    }
#define DEFINE_ADAPTERS(P, SFX, QT, RVT)                                                      \
    ADAPT_2(P, lerp, qo_interp_lerp_##SFX, QT)                                                  \
    ADAPT_2(P, slerp, qo_interp_slerp_##SFX, QT)                                                \
    ADAPT_2(P, slerp_long, qo_interp_slerp_long_##SFX, QT)                                      \
    ADAPT_2(P, nlerp, qo_interp_nlerp_##SFX, QT)                                                \
    static qo_status P##_unit(dq q, dq *out)                                                  \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = qo_quat_normalize_##SFX(P##_q(q), &o);                                 \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_slerp_rate(dq a, dq b, double dur, ref_vec3 *w)                      \
    {                                                                                         \
        RVT o;                                                                                \
        qo_status st = qo_interp_slerp_rate_##SFX(P##_q(a), P##_q(b), P##_s(dur),               \
                                                 w ? &o : NULL);                              \
        if (w) *w = P##_rb(o);                                                                \
        return st;                                                                            \
    }                                                                                         \
    ADAPT_KEYS(P, align_keys, qo_interp_align_keys_##SFX, QT)                                   \
    ADAPT_KEYS(P, squad_controls, qo_interp_squad_controls_##SFX, QT)                           \
    static qo_status P##_bezier(const dq *c, size_t n, double t, dq *out)                     \
    {                                                                                         \
        QT pc[MAXK], o;                                                                       \
        qo_status st;                                                                         \
        TO_CORE(P, pc, c, n);                                                                 \
        st = qo_interp_bezier_##SFX(c ? pc : NULL, n, P##_t(t), out ? &o : NULL);               \
        if (out) *out = P##_qb(o);                                                            \
        return st;                                                                            \
    }                                                                                         \
    ADAPT_4(P, bezier3, qo_interp_bezier3_##SFX, QT)                                            \
    static qo_status P##_spline_controls(const dq *k, size_t n, dq *a, dq *b)                 \
    {                                                                                         \
        QT pk[MAXK], pa[MAXK], pb[MAXK];                                                      \
        qo_status st;                                                                         \
        TO_CORE(P, pk, k, n);                                                                 \
        memset(pa, 0, sizeof pa);                                                             \
        memset(pb, 0, sizeof pb);                                                             \
        st = qo_interp_spline_controls_##SFX(k ? pk : NULL, n, a ? pa : NULL, b ? pb : NULL);   \
        FROM_CORE(P, a, pa, n);                                                               \
        FROM_CORE(P, b, pb, n);                                                               \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_spline_eval(const dq *k, const dq *a, const dq *b, size_t n,         \
                                     double s, dq *out)                                       \
    {                                                                                         \
        QT pk[MAXK], pa[MAXK], pb[MAXK], o;                                                   \
        qo_status st;                                                                         \
        TO_CORE(P, pk, k, n);                                                                 \
        TO_CORE(P, pa, a, n);                                                                 \
        TO_CORE(P, pb, b, n);                                                                 \
        st = qo_interp_spline_eval_##SFX(k ? pk : NULL, a ? pa : NULL, b ? pb : NULL, n,        \
                                       P##_s(s), out ? &o : NULL);                            \
        if (out) *out = P##_qb(o);                                                            \
        return st;                                                                            \
    }                                                                                         \
    ADAPT_4(P, squad, qo_interp_squad_##SFX, QT)

/* The table entries after the header fields, in the order of `core`. */
#define CORE_FUNCS(P)                                                                         \
    P##_lerp, P##_slerp, P##_slerp_long, P##_nlerp, P##_slerp_rate, P##_align_keys,           \
    P##_bezier, P##_bezier3, P##_spline_controls, P##_spline_eval, P##_squad_controls,        \
    P##_squad

/* float32: a double rounded to float, the exact value back */
static dq f_q_in(dq q) { return dq_from_f(f_from(q)); }
static double f_t_in(double t) { return (double)(float)t; }
static float f_t(double t) { return (float)t; }
#define f_q f_from
#define f_qb dq_from_f
#define f_s f_t
#define f_rb ref_vec3_from_f32
DEFINE_ADAPTERS(f, f32, qo_quat_f32, qo_vec3_f32)

/* Q1.30: the boundary rounds to nearest and saturates (ref_to_fixed), the exact value back */
static dq x_q_in(dq q) { return dq_from_x(x_from(q)); }
static double x_t_in(double t) { return fx_from_d(t, Q30) / Q30; }
static double x_s_in(double s) { return fx_from_d(s, Q16) / Q16; }
static qo_q30 x_t(double t) { return fx_from_d(t, Q30); }
static qo_q16 x_s(double s) { return fx_from_d(s, Q16); }
static ref_vec3 x_rb(qo_vec3_q16 v)
{
    ref_vec3 r = { v.x / Q16, v.y / Q16, v.z / Q16 };
    return r;
}
#define x_q x_from
#define x_qb dq_from_x
DEFINE_ADAPTERS(x, q30, qo_quat_q30, qo_vec3_q16)
/* The fast tier: its own normalisation (qo_quat_normalize_fast_q30) and slerp. */
static qo_status x_unit_fast(dq q, dq *out)
{
    qo_quat_q30 o;
    qo_status st = qo_quat_normalize_fast_q30(x_from(q), &o);
    *out = dq_from_x(o);
    return st;
}
ADAPT_2(x, slerp_fast, qo_interp_slerp_fast_q30, qo_quat_q30)

/* Tolerances: float32 as measured by bench/accuracy_interp.c with a margin; fixed point
 * measured by bench/accuracy_interp_fx.c at 5e-9 rad (slerp) and 1e-9 (norm), checked here
 * with a margin; tol_long / tol_abs / tol_ang as the former twins test judged slerp_long and
 * slerp_rate. */
static const core CORE_F32 = {
    "float32", 0, 1e-6, 1e-6, 1e-6, 2e-6, 1e-6, 2e-6, 1e-6, 1e3, 1e39,
    f_q_in, f_t_in, f_t_in, f_unit, CORE_FUNCS(f)
};
static const core CORE_FX = {
    "q30", 1, 3e-8, 3e-9, 1e-8, 2e-8, 5e-9, 2e-8, 1.0 / Q30, 1.99, 1e39,
    x_q_in, x_t_in, x_s_in, x_unit, CORE_FUNCS(x)
};
/* The fast tier (slerp bodies only): documented 5e-8 rad; its unit is normalize_fast's
 * (16 LSB, 1.5e-8 of norm). */
static const core CORE_FX_FAST = {
    "q30 fast", 1, 5e-8, 3e-8, 1e-8, 2e-8, 5e-9, 2e-8, 1.0 / Q30, 1.99, 1e39,
    x_q_in, x_t_in, x_s_in, x_unit_fast,
    x_lerp, x_slerp_fast, x_slerp_long, x_nlerp, x_slerp_rate, x_align_keys, x_bezier,
    x_bezier3, x_spline_controls, x_spline_eval, x_squad_controls, x_squad
};

/* ---- check helpers ---------------------------------------------------------------------- */
#define CHECK(cond, ...) do { if (!(cond)) { fail_msg(__VA_ARGS__); } } while (0)
#define QF(q) (q).w, (q).x, (q).y, (q).z
#define QFMT "(%.12g %.12g %.12g %.12g)"

static const dq ID = { 1, 0, 0, 0 };
static const dq ZERO_Q = { 0, 0, 0, 0 };
static double v_norm(ref_vec3 v) { return sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
static double v_dist(ref_vec3 a, ref_vec3 b)
{
    return sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}
static ref_vec3 v_make(double x, double y, double z)
{
    ref_vec3 r = { x, y, z };
    return r;
}
/* the core's unit q (asserting the normalisation succeeded) */
static dq cu(const core *c, dq q)
{
    dq u;
    assert_int_equal(c->unit(q, &u), QO_OK);
    return u;
}
/* a quaternion with one component at the core's out-of-range value */
static dq big_q(const core *c)
{
    dq q = ID;
    q.x = c->big;
    return q;
}

/* ---- slerp, both cores ------------------------------------------------------------------ */

/* One slerp case against the double reference of the inputs the core received: rotation
 * error, 4-D error (the sign is specified: nearest a), unit norm. */
static void check_slerp_case(const core *c, const char *name, dq a, dq b, double t)
{
    dq out, ia = c->q_in(a), ib = c->q_in(b);
    double it = c->t_in(t);
    qo_status st = c->slerp(a, b, t, &out);
    dq ref = d_slerp(ia, ib, it);
    double re = rot_err(ref, out), d4 = dist4(ref, out);
    CHECK(st == QO_OK, "%s %s: status %d a=" QFMT " b=" QFMT " t=%.12g", c->name, name, (int)st,
          QF(ia), QF(ib), it);
    CHECK(re <= c->tol_rot && d4 <= c->tol_rot, "%s %s: rotation error %.3g, 4-D error %.3g a="
          QFMT " b=" QFMT " t=%.12g out=" QFMT, c->name, name, re, d4, QF(ia), QF(ib), it,
          QF(out));
    CHECK(norm_dev(out) <= c->tol_norm, "%s %s: norm deviation %.3g a=" QFMT " b=" QFMT
          " t=%.12g", c->name, name, norm_dev(out), QF(ia), QF(ib), it);
}

static void test_slerp_random_vs_double(void **state)
{
    const core *c = *state;
    int i;
    rng_seed(0x51E4F00Dull);
    for (i = 0; i < 3000; i++) {
        dq a = rand_unit(), b = rand_unit();
        double t = rng_u();
        if (i % 3 == 1) { /* non-unit inputs, 1e-3 .. the core's largest */
            double hi = log10(c->max_scale);
            a = dq_scale(a, pow(10.0, rng_range(-3, hi)));
            b = dq_scale(b, pow(10.0, rng_range(-3, hi)));
        }
        check_slerp_case(c, "random", a, b, t);
    }
}

/* Edge table: b at rotation angle delta from a (random axis), with both signs of b, at a grid
 * of t including the exact ends and one LSB-scale step from them. delta covers identical,
 * nearly identical (1e-9..1e-3 rad), around the float series threshold, and nearly 180 deg. */
static void test_slerp_edge_table(void **state)
{
    static const double deltas[] = { 0.0, 1e-9, 1e-8, 1e-7, 3e-7, 1e-6, 1e-5, 1e-4, 1e-3,
                                     1.9e-3, 2e-3, 2.1e-3, 1e-2, 0.5, 2.0, PI - 1e-2, PI - 1e-3,
                                     PI - 1e-4, PI - 1e-5 };
    static const double ts[] = { 0.0, 1e-9, 1e-7, 1e-3, 0.25, 0.5, 0.75, 0.999, 0.9999999,
                                 1.0 - 1e-9, 1.0 };
    const core *c = *state;
    size_t di, ti;
    int k, sgn;
    rng_seed(0xED6Eull);
    for (k = 0; k < 8; k++) {
        dq a = rand_unit();
        for (di = 0; di < sizeof deltas / sizeof deltas[0]; di++) {
            dq b = dq_mul(a, rand_axis_rot(deltas[di]));
            for (sgn = 0; sgn < 2; sgn++) {
                for (ti = 0; ti < sizeof ts / sizeof ts[0]; ti++) {
                    char name[96];
                    snprintf(name, sizeof name, "edge delta=%.3g sign=%s", deltas[di],
                             sgn ? "-b" : "+b");
                    check_slerp_case(c, name, a, sgn ? dq_neg(b) : b, ts[ti]);
                }
            }
        }
    }
}

/* q vs -q and q vs q: the result is the rotation q for every t, with the sign of a, unit
 * length (the cglm / filament bug averages q and -q to near zero). */
static void test_slerp_same_rotation_opposite_sign(void **state)
{
    const core *c = *state;
    int i, k;
    rng_seed(0x0990ull);
    for (i = 0; i < 200; i++) {
        dq q = c->q_in(rand_unit()), uq;
        assert_int_equal(c->unit(q, &uq), QO_OK);
        for (k = 0; k <= 16; k++) {
            double t = (double)k / 16.0;
            dq o1, o2;
            assert_int_equal(c->slerp(q, dq_neg(q), t, &o1), QO_OK);
            assert_int_equal(c->slerp(q, q, t, &o2), QO_OK);
            CHECK(dist4(q, o1) <= c->tol_rot && norm_dev(o1) <= c->tol_norm,
                  "%s q vs -q (sign of a, unit): q=" QFMT " t=%g out=" QFMT, c->name, QF(q), t,
                  QF(o1));
            CHECK(dist4(q, o2) <= c->tol_rot && norm_dev(o2) <= c->tol_norm,
                  "%s q vs q: q=" QFMT " t=%g out=" QFMT, c->name, QF(q), t, QF(o2));
            /* identical unit inputs: exactly the core's unit q (lerp weights of one point) */
            if (k == 0 || k == 16)
                CHECK(dq_equal(o2, uq) && dq_equal(o1, uq), "%s q vs +-q at t=%g must be the "
                      "unit input exactly", c->name, t);
        }
    }
}

/* Exactly 180 deg of rotation apart: dot == 0 exactly in both cores' number formats (checked
 * with the sign-exact dot). No flip; the path is the great circle through a and b (the double
 * reference makes the same choice). */
static void test_slerp_exact_180(void **state)
{
    static const dq pairs[][2] = {
        { { 1, 0, 0, 0 }, { 0, 1, 0, 0 } },
        { { 1, 0, 0, 0 }, { 0, 0, 0, -1 } },
        { { 0.5, 0.5, 0.5, 0.5 }, { 0.5, -0.5, 0.5, -0.5 } },
        { { 0, 0.6, 0.8, 0 }, { 0, -0.8, 0.6, 0 } },
    };
    const core *c = *state;
    size_t i;
    int k;
    for (i = 0; i < sizeof pairs / sizeof pairs[0]; i++) {
        assert_true(dq_dot_exact(c->q_in(pairs[i][0]), c->q_in(pairs[i][1])) == 0.0L);
        for (k = 0; k <= 8; k++) {
            char name[64];
            snprintf(name, sizeof name, "exact 180 pair %u", (unsigned)i);
            check_slerp_case(c, name, pairs[i][0], pairs[i][1], (double)k / 8.0);
        }
    }
}

/* Nearly 180 deg where |dot| is at the resolution of the format: which of the two (almost
 * equally short) ways is taken is decided by rounding, so either reference is accepted; the
 * result must still be one of them and unit length. */
static void test_slerp_nearly_180_ambiguous(void **state)
{
    const core *c = *state;
    int i, k;
    rng_seed(0x180180ull);
    for (i = 0; i < 100; i++) {
        dq a = rand_unit(), b = dq_mul(a, rand_axis_rot(PI - 1e-7 * rng_u()));
        dq ua = dq_unit(c->q_in(a)), ub = dq_unit(c->q_in(b));
        for (k = 0; k <= 8; k++) {
            double t = (double)k / 8.0, it = c->t_in(t), e1, e2;
            dq out;
            assert_int_equal(c->slerp(a, b, t, &out), QO_OK);
            e1 = rot_err(dq_unit(d_slerp_raw(ua, ub, it)), out);
            e2 = rot_err(dq_unit(d_slerp_raw(ua, dq_neg(ub), it)), out);
            CHECK((e1 <= c->tol_rot || e2 <= c->tol_rot) && norm_dev(out) <= c->tol_norm,
                  "%s nearly 180: errors %.3g / %.3g a=" QFMT " b=" QFMT " t=%g", c->name, e1,
                  e2, QF(ua), QF(ub), t);
        }
    }
}

/* t == 0 and t == 1 give the core's normalised inputs exactly; t == 1 with dot < 0 gives -b. */
static void test_slerp_exact_endpoints(void **state)
{
    const core *c = *state;
    int i;
    rng_seed(0xE4D5ull);
    for (i = 0; i < 500; i++) {
        dq a = c->q_in(dq_scale(rand_unit(), rng_range(0.5, 1.9)));
        dq b = c->q_in(dq_scale(rand_unit(), rng_range(0.5, 1.9)));
        dq o0, o1, ua, ub;
        assert_int_equal(c->unit(a, &ua), QO_OK);
        assert_int_equal(c->unit(b, &ub), QO_OK);
        if (dq_dot_exact(ua, ub) < 0) ub = dq_neg(ub);
        assert_int_equal(c->slerp(a, b, 0.0, &o0), QO_OK);
        assert_int_equal(c->slerp(a, b, 1.0, &o1), QO_OK);
        CHECK(dq_equal(o0, ua), "%s t=0: a=" QFMT " b=" QFMT " out=" QFMT, c->name, QF(a),
              QF(b), QF(o0));
        CHECK(dq_equal(o1, ub), "%s t=1: a=" QFMT " b=" QFMT " out=" QFMT " want " QFMT,
              c->name, QF(a), QF(b), QF(o1), QF(ub));
    }
}

/* Constant angular rate: angle(a, slerp(a, b, t)) == t * angle(a, b). */
static void test_slerp_constant_rate(void **state)
{
    const core *c = *state;
    int i, k;
    rng_seed(0xC0457ull);
    for (i = 0; i < 300; i++) {
        dq a = c->q_in(rand_unit()), b = c->q_in(dq_mul(a, rand_axis_rot(rng_range(0, PI))));
        double phi = rot_err(a, b);
        for (k = 0; k <= 20; k++) {
            double t = (double)k / 20.0, it = c->t_in(t), ang;
            dq out;
            assert_int_equal(c->slerp(a, b, t, &out), QO_OK);
            ang = rot_err(a, out);
            CHECK(fabs(ang - it * phi) <= 2 * c->tol_rot, "%s rate: angle %.12g want %.12g "
                  "a=" QFMT " b=" QFMT " t=%g", c->name, ang, it * phi, QF(a), QF(b), t);
        }
    }
}

/* Statuses and the defined outputs: zero input, t outside [0, 1], NULL out. */
/* Statuses and the defined outputs of slerp, slerp_long and nlerp: zero inputs, t outside
 * [0, 1] and at the core's out-of-range value, an out-of-range component, NULL out. */
static void test_slerp_nlerp_errors(void **state)
{
    static const double bad_t[] = { -0.25, -1e-6, -1e-7, -1.0, 1.0 + 1e-6, 1.0000001, 1.5, 2.0 };
    static const char *const names[] = { "slerp", "slerp_long", "nlerp" };
    const core *c = *state;
    dq a, b, ua, out;
    size_t i;
    int which;
    rng_seed(0xE7707ull);
    a = c->q_in(dq_scale(rand_unit(), 1.5));
    b = c->q_in(rand_unit());
    ua = cu(c, a);
    for (which = 0; which < 3; which++) {
        qo_status (*f)(dq, dq, double, dq *) =
            which == 0 ? c->slerp : which == 1 ? c->slerp_long : c->nlerp;
        const char *fn = names[which];
        assert_int_equal(f(a, b, 0.5, NULL), QO_E_NULL);
        CHECK(f(a, ZERO_Q, 0.5, &out) == QO_E_DEGENERATE && dq_equal(out, ID),
              "%s %s(a, 0): DEGENERATE and identity", c->name, fn);
        CHECK(f(ZERO_Q, b, 0.5, &out) == QO_E_DEGENERATE && dq_equal(out, ID),
              "%s %s(0, b): DEGENERATE and identity", c->name, fn);
        CHECK(f(ZERO_Q, ZERO_Q, 0.0, &out) == QO_E_DEGENERATE && dq_equal(out, ID),
              "%s %s(0, 0): DEGENERATE and identity", c->name, fn);
        for (i = 0; i < sizeof bad_t / sizeof bad_t[0]; i++)
            CHECK(f(a, b, bad_t[i], &out) == QO_E_RANGE && dq_equal(out, ua),
                  "%s %s t=%.9g: want QO_E_RANGE and unit a", c->name, fn, bad_t[i]);
        /* t = big: Inf (float32: NONFINITE) / saturated (fixed: RANGE); unit a either way */
        CHECK(f(a, b, c->big, &out) == ST(c, QO_E_NONFINITE, QO_E_RANGE) && dq_equal(out, ua),
              "%s %s t=big: status and unit a", c->name, fn);
        /* a component at big: Inf (float32: NONFINITE, identity) / saturated, a valid input */
        CHECK(f(big_q(c), b, 0.5, &out) == ST(c, QO_E_NONFINITE, QO_OK) &&
              (c->fixed || dq_equal(out, ID)), "%s %s a=big", c->name, fn);
        CHECK(f(a, big_q(c), 0.5, &out) == ST(c, QO_E_NONFINITE, QO_OK) &&
              (c->fixed || dq_equal(out, ID)), "%s %s b=big", c->name, fn);
        /* the bad quaternion is reported before a zero one and before a bad t */
        CHECK(f(ZERO_Q, big_q(c), 0.5, &out) == ST(c, QO_E_NONFINITE, QO_E_DEGENERATE) &&
              dq_equal(out, ID), "%s %s a=0 b=big", c->name, fn);
        CHECK(f(big_q(c), b, 3.0, &out) == ST(c, QO_E_NONFINITE, QO_E_RANGE) &&
              dq_equal(out, c->fixed ? cu(c, big_q(c)) : ID), "%s %s a=big t=3", c->name, fn);
    }
    assert_int_equal(c->unit(ZERO_Q, &out), QO_E_DEGENERATE);
}

/* ---- slerp long, both cores ------------------------------------------------------------- */

/* The long way: against the textbook slerp to -b' (random pairs, and pairs a small angle
 * apart where the plane of the long path is least determined), at the rate of the long
 * angle; edges. */
static void test_slerp_long(void **state)
{
    const core *c = *state;
    double worst = 0, worst_k = 0;
    int n, i, k;
    dq o, a, b;
    rng_seed(101);
    for (n = 0; n < 1000; n++) {
        double t = c->t_in(n < 8 ? n / 7.0 : rng_u()), phi;
        dq bl, want;
        a = c->q_in(rand_unit());
        b = c->q_in(n % 3 ? rand_unit() : rand_axis_rot(rng_range(0.01, 0.1)));
        bl = dq_unit(b);
        if (dq_dot(a, b) > 0) bl = dq_neg(bl);
        phi = dq_angle(a, b);
        if (phi < 0.01) continue;
        want = d_slerp_unit(dq_unit(a), bl, t);
        /* the plane of the long path is known to the inputs' rounding / phi (interp.h) */
        if (c->slerp_long(a, b, t, &o) != QO_OK ||
            rot_err(o, want) > c->tol_long * (1 + 1 / phi) || dq_dot(o, want) < 0 ||
            fabs(dq_norm(o) - 1) > 4 * c->tol_abs)
            fail_msg("%s slerp_long case %d: a " QFMT " b " QFMT " t %.10g: got " QFMT
                     ", error %.3g rad (tol %.3g)", c->name, n, QF(a), QF(b), t, QF(o),
                     rot_err(o, want), c->tol_long * (1 + 1 / phi));
        worst = fmax(worst, rot_err(o, want) * phi);
    }
    print_message("%s slerp_long: worst error * phi = %.3g\n", c->name, worst);
    rng_seed(0x1046ull);
    for (i = 0; i < 300; i++) {
        dq b0;
        double phi, psi;
        a = c->q_in(rand_unit());
        b0 = dq_mul(a, rand_axis_rot(rng_range(0.01, PI)));
        b = c->q_in(i % 2 ? dq_neg(b0) : b0);
        {
            dq ua = dq_unit(a), ub = dq_unit(b);
            phi = rot_err(ua, ub);
            if (dq_dot(ua, ub) > 0) ub = dq_neg(ub);
            psi = 2 * PI - phi; /* the long rotation angle */
            for (k = 0; k <= 16; k++) {
                double t = (double)k / 16.0, it = c->t_in(t), ang, want = it * psi, e4;
                dq ref = d_slerp_raw(ua, ub, it);
                assert_int_equal(c->slerp_long(a, b, t, &o), QO_OK);
                /* documented accuracy of the long way: tol/phi (input rounding / |a + b'|) */
                e4 = dist4(dq_unit(ref), o);
                if (e4 * phi > worst_k) worst_k = e4 * phi;
                CHECK(e4 <= c->tol_rot + c->tol_rot / phi && norm_dev(o) <= c->tol_norm,
                      "%s long: 4-D error %.3g a=" QFMT " b=" QFMT " t=%g", c->name, e4, QF(a),
                      QF(b), t);
                if (want > PI) want = 2 * PI - want;
                ang = rot_err(ua, o);
                CHECK(fabs(ang - want) <= 2 * c->tol_rot + 2 * c->tol_rot / phi,
                      "%s long rate: angle %.9g want %.9g a=" QFMT " b=" QFMT " t=%g", c->name,
                      ang, want, QF(a), QF(b), t);
            }
        }
    }
    print_message("%s slerp_long: worst 4-D error * phi = %.3g\n", c->name, worst_k);
    /* edges: identical and antipodal are the same rotation (no long way): unit a; exact ends */
    a = c->q_in(rand_unit());
    assert_int_equal(c->slerp_long(a, a, 0.5, &o), QO_E_DEGENERATE);
    CHECK(dq_equal(o, cu(c, a)), "%s slerp_long(q, q): unit q exactly", c->name);
    assert_int_equal(c->slerp_long(a, dq_neg(a), 0.5, &o), QO_E_DEGENERATE);
    assert_int_equal(c->slerp_long(ZERO_Q, a, 0.5, &o), QO_E_DEGENERATE);
    assert_true(dq_equal(o, ID));
    assert_int_equal(c->slerp_long(ID, dq_axis_angle(0, 0, 1, 1.0), 1.5, &o), QO_E_RANGE);
    assert_true(dq_equal(o, ID));
    /* 180 deg exactly (dot == 0): b kept, the path through b */
    b = dq_axis_angle(0, 1, 0, PI);
    b.w = 0;
    assert_int_equal(c->slerp_long(ID, b, 1.0, &o), QO_OK);
    assert_true(dq_equal(o, b));
    /* 90 deg about z the long way: 270 deg about -z, the middle is 135 deg about -z */
    assert_int_equal(c->slerp_long(ID, c->q_in(dq_axis_angle(0, 0, 1, PI / 2)), 0.5, &o), QO_OK);
    assert_true(rot_err(o, dq_axis_angle(0, 0, -1, 0.75 * PI)) <= 10 * c->tol_long);
    /* out of range: Inf (float32) / a saturated component (fixed: a valid, large input) */
    assert_int_equal(c->slerp_long(ID, big_q(c), 0.5, &o), ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(fabs(dq_norm(o) - 1) <= 4 * c->tol_abs);
}

/* ---- slerp rate, both cores ------------------------------------------------------------- */

/* The constant angular velocity 2 log(conj(a) b') / T (body frame) against double, over
 * durations 0.1 .. 10 s and 0.01 .. 10 s; edges. */
static void test_slerp_rate(void **state)
{
    const core *c = *state;
    int n;
    ref_vec3 w;
    dq a, b;
    rng_seed(102);
    for (n = 0; n < 1000; n++) {
        double dur = c->s_in(pow(10.0, rng_range(-1.0, 1.0)));
        dq r, l;
        ref_vec3 want;
        a = c->q_in(rand_unit());
        b = c->q_in(n % 2 ? rand_unit() : rand_axis_rot(rng_range(1e-6, 0.1)));
        r = dq_mul(dq_conj(dq_unit(a)), dq_unit(b));
        if (r.w < 0) r = dq_neg(r);
        l = dq_log(r);
        want = v_make(2 * l.x / dur, 2 * l.y / dur, 2 * l.z / dur);
        /* float: relative; fixed: 1 LSB of Q16.16 plus the log's Q3.28 error times 2/dur */
        if (c->slerp_rate(a, b, dur, &w) != QO_OK ||
            v_dist(w, want) > (c->fixed ? 1.5 / Q16 + 2 * c->tol_ang / dur
                                        : c->tol_long * (1 + v_norm(want))))
            fail_msg("%s slerp_rate case %d: a " QFMT " b " QFMT " dur %.10g: (%.9g %.9g %.9g)"
                     " want (%.9g %.9g %.9g)", c->name, n, QF(a), QF(b), dur, w.x, w.y, w.z,
                     want.x, want.y, want.z);
    }
    rng_seed(0x4A7Eull);
    for (n = 0; n < 500; n++) {
        double dur = c->s_in(rng_range(0.01, 10)), tol;
        dq ua, ub, lg;
        ref_vec3 want;
        a = c->q_in(rand_unit());
        b = c->q_in(rand_unit());
        ua = dq_unit(a);
        ub = dq_unit(b);
        if (dq_dot(ua, ub) < 0) ub = dq_neg(ub);
        lg = dq_log(dq_mul(dq_conj(ua), ub));
        want = v_make(2 * lg.x / dur, 2 * lg.y / dur, 2 * lg.z / dur);
        assert_int_equal(c->slerp_rate(a, b, dur, &w), QO_OK);
        /* float: 1e-6 rad of angle over T; fixed as above */
        tol = c->fixed ? 1.5 / Q16 + 2 * c->tol_ang / dur : 1e-6 / dur;
        CHECK(v_dist(w, want) <= tol, "%s rate a=" QFMT " b=" QFMT " T=%g: error %.3g > %.3g",
              c->name, QF(a), QF(b), dur, v_dist(w, want), tol);
    }
    /* identical and antipodal: no motion */
    a = c->q_in(rand_unit());
    assert_int_equal(c->slerp_rate(a, a, 1.0, &w), QO_OK);
    assert_true(v_norm(w) <= c->tol_long);
    assert_int_equal(c->slerp_rate(a, dq_neg(a), 1.0, &w), QO_OK);
    assert_true(v_norm(w) <= c->tol_long);
    assert_true(fabs(w.x) + fabs(w.y) + fabs(w.z) <= (c->fixed ? 1.5 / Q16 : 1e-6));
    /* 90 deg about x in 0.5 s: pi rad/s about x */
    assert_int_equal(c->slerp_rate(ID, c->q_in(dq_axis_angle(1, 0, 0, PI / 2)), 0.5, &w), QO_OK);
    assert_true(fabs(w.x - PI) <= 2e-5 && fabs(w.y) <= 2e-5 && fabs(w.z) <= 2e-5);
    assert_int_equal(c->slerp_rate(a, a, 1.0, NULL), QO_E_NULL);
    w = v_make(9, 9, 9);
    assert_int_equal(c->slerp_rate(ID, ZERO_Q, 1.0, &w), QO_E_DEGENERATE);
    assert_true(v_norm(w) == 0);
    w = v_make(9, 9, 9);
    assert_int_equal(c->slerp_rate(ID, a, 0.0, &w), QO_E_RANGE);
    assert_true(v_norm(w) == 0);
    assert_int_equal(c->slerp_rate(ID, a, -1.0, &w), QO_E_RANGE);
    /* a duration so short the rate overflows the format (float: 1e-39 s is subnormal) */
    w = v_make(9, 9, 9);
    assert_int_equal(c->slerp_rate(ID, dq_axis_angle(0, 1, 0, 3.0), c->fixed ? 1 / Q16 : 1e-39,
                                   &w), QO_E_RANGE);
    assert_true(v_norm(w) == 0);
    /* out of range duration: Inf (float32) / saturated (fixed: 32768 s, a valid slow rate) */
    assert_int_equal(c->slerp_rate(ID, dq_axis_angle(0, 1, 0, 1.0), c->big, &w),
                     ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(v_norm(w) <= 1e-4);
}

/* ---- lerp, both cores ------------------------------------------------------------------- */

/* a + t (b - a) against double on the inputs as received (float32: 1e-6; fixed: rounded once,
 * 1 LSB); exact ends; no flip, no normalisation (q and -q average to zero); statuses. */
static void test_lerp(void **state)
{
    const core *c = *state;
    const dq p0 = { 0.125, 0.5, 0.75, 1.0 }, q0 = { -1.0, 0.5, 0.0, 1.5 };
    dq a = c->q_in(p0), b = c->q_in(q0), out;
    double sc = fmin(3.0, 0.95 * c->max_scale);
    int i;
    rng_seed(0x1E4Bull);
    for (i = 0; i < 500; i++) {
        dq p = c->q_in(dq_scale(rand_unit(), sc)), q = c->q_in(rand_unit());
        double t = rng_u(), it = c->t_in(t);
        dq ref = dq_add(dq_scale(p, 1.0 - it), dq_scale(q, it));
        assert_int_equal(c->lerp(p, q, t, &out), QO_OK);
        CHECK(dist4(ref, out) <= c->tol_lerp, "%s lerp p=" QFMT " q=" QFMT " t=%g: error %.3g",
              c->name, QF(p), QF(q), t, dist4(ref, out));
        assert_int_equal(c->lerp(p, q, 0.0, &out), QO_OK);
        CHECK(dq_equal(out, p), "%s lerp t=0 p=" QFMT, c->name, QF(p));
        assert_int_equal(c->lerp(p, q, 1.0, &out), QO_OK);
        CHECK(dq_equal(out, q), "%s lerp t=1 q=" QFMT, c->name, QF(q));
    }
    assert_int_equal(c->lerp(a, b, 0.0, &out), QO_OK);
    assert_true(dq_equal(out, a));
    assert_int_equal(c->lerp(a, b, 1.0, &out), QO_OK);
    assert_true(dq_equal(out, b));
    /* no normalisation, no flip: the midpoint of q and -q is zero */
    assert_int_equal(c->lerp(a, dq_neg(a), 0.5, &out), QO_OK);
    assert_true(out.w == 0 && out.x == 0 && out.y == 0 && out.z == 0);
    assert_int_equal(c->lerp(ZERO_Q, b, 0.5, &out), QO_OK);
    assert_int_equal(c->lerp(a, b, 1.5, &out), QO_E_RANGE);
    assert_true(dq_equal(out, a));
    assert_int_equal(c->lerp(a, b, -1e-6, &out), QO_E_RANGE);
    assert_true(dq_equal(out, a));
    assert_int_equal(c->lerp(a, b, c->big, &out), ST(c, QO_E_NONFINITE, QO_E_RANGE));
    assert_true(dq_equal(out, a));
    /* a component at big: Inf (float32: NONFINITE, identity) / saturated, plain arithmetic */
    assert_int_equal(c->lerp(big_q(c), b, 0.5, &out), ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(c->fixed || dq_equal(out, ID));
    assert_int_equal(c->lerp(a, b, 0.5, NULL), QO_E_NULL);
}

/* ---- nlerp, both cores ------------------------------------------------------------------ */

static void test_nlerp(void **state)
{
    const core *c = *state;
    int i;
    dq out, out2;
    rng_seed(0x41E4Bull);
    for (i = 0; i < 1000; i++) {
        dq a = c->q_in(dq_scale(rand_unit(), rng_range(0.1, fmin(10.0, c->max_scale))));
        dq b = c->q_in(rand_unit());
        double t = rng_u(), it = c->t_in(t);
        dq ua = dq_unit(a), ub = dq_unit(b), ref;
        if (dq_dot_exact(ua, ub) < 0) ub = dq_neg(ub); /* shortest way */
        ref = dq_unit(dq_add(dq_scale(ua, 1.0 - it), dq_scale(ub, it)));
        assert_int_equal(c->nlerp(a, b, t, &out), QO_OK);
        CHECK(dist4(ref, out) <= c->tol_rot && norm_dev(out) <= c->tol_norm,
              "%s nlerp a=" QFMT " b=" QFMT " t=%g out=" QFMT, c->name, QF(a), QF(b), t, QF(out));
        /* -b: same path */
        assert_int_equal(c->nlerp(a, dq_neg(b), t, &out2), QO_OK);
        CHECK(dist4(out, out2) <= c->tol_rot, "%s nlerp -b a=" QFMT " b=" QFMT " t=%g", c->name,
              QF(a), QF(b), t);
        /* short way: never further from a than b' */
        CHECK(rot_err(ua, out) <= rot_err(ua, ub) + c->tol_rot,
              "%s nlerp not on the short arc a=" QFMT " b=" QFMT " t=%g", c->name, QF(a), QF(b),
              t);
    }
    {   /* q vs -q stays q; ends; errors */
        dq q = c->q_in(rand_unit());
        assert_int_equal(c->nlerp(q, dq_neg(q), 0.5, &out), QO_OK);
        CHECK(dist4(q, out) <= c->tol_rot, "%s nlerp(q, -q, 1/2) must be q", c->name);
        assert_int_equal(c->nlerp(q, dq_neg(q), 1.0, &out), QO_OK);
        CHECK(dq_equal(out, cu(c, q)), "%s nlerp(q, -q, 1) must be unit q exactly", c->name);
        assert_int_equal(c->nlerp(q, ID, 2.0, &out), QO_E_RANGE);
        assert_true(dq_equal(out, cu(c, q)));
        assert_int_equal(c->nlerp(q, ZERO_Q, 0.5, &out), QO_E_DEGENERATE);
        assert_true(dq_equal(out, ID));
        assert_int_equal(c->nlerp(q, ID, 0.5, NULL), QO_E_NULL);
    }
}

/* ---- key alignment, both cores ---------------------------------------------------------- */

/* Signs made continuous, each key normalised (the first one keeps its sign, bit-equal to the
 * core's unit key), in place, errors. Norms from 1/sqrt(max) to max^(3/4) of the core. */
static void test_align_keys(void **state)
{
    const core *c = *state;
    dq k[6], o[6], prev;
    int i;
    rng_seed(0xA11Full);
    prev = rand_unit();
    for (i = 0; i < 6; i++) {
        prev = dq_mul(prev, rand_axis_rot(rng_range(0.1, 3.0)));
        k[i] = c->q_in(dq_scale(i % 2 ? dq_neg(prev) : prev, pow(c->max_scale, (i - 2) / 4.0)));
    }
    assert_int_equal(c->align_keys(k, 6, o), QO_OK);
    CHECK(dq_equal(o[0], cu(c, k[0])), "%s aligned key 0 keeps its sign", c->name);
    for (i = 1; i < 6; i++)
        CHECK(dq_dot_exact(o[i - 1], o[i]) >= 0 && rot_err(o[i], k[i]) <= c->tol_key &&
              norm_dev(o[i]) <= c->tol_norm, "%s aligned key %d: error %.3g", c->name, i,
              rot_err(o[i], k[i]));
    /* in place gives the same */
    assert_int_equal(c->align_keys(k, 6, k), QO_OK);
    for (i = 0; i < 6; i++) CHECK(dq_equal(k[i], o[i]), "%s in-place key %d", c->name, i);
    assert_int_equal(c->align_keys(k, 0, o), QO_E_TOO_FEW);
    assert_int_equal(c->align_keys(NULL, 3, o), QO_E_NULL);
    for (i = 0; i < 3; i++) CHECK(dq_equal(o[i], ID), "%s NULL keys: identity %d", c->name, i);
    k[2] = ZERO_Q;
    assert_int_equal(c->align_keys(k, 6, o), QO_E_DEGENERATE);
    for (i = 0; i < 6; i++) CHECK(dq_equal(o[i], ID), "%s zero key: identity %d", c->name, i);
    k[2] = ID;
    k[4] = big_q(c);
    assert_int_equal(c->align_keys(k, 6, o), ST(c, QO_E_NONFINITE, QO_OK));
}

/* ---- Bezier, both cores ----------------------------------------------------------------- */

/* de Casteljau in double with textbook slerp over sign-aligned, normalised points. */
static dq d_bezier(const dq *c, size_t n, double t)
{
    dq p[16];
    size_t i, lev;
    p[0] = dq_unit(c[0]);
    for (i = 1; i < n; i++) {
        p[i] = dq_unit(c[i]);
        if (dq_dot_exact(p[i - 1], p[i]) < 0) p[i] = dq_neg(p[i]);
    }
    for (lev = n - 1; lev > 0; lev--)
        for (i = 0; i < lev; i++) p[i] = dq_unit(d_slerp_raw(p[i], p[i + 1], t));
    return p[0];
}

static void test_bezier(void **state)
{
    const core *c = *state;
    dq cp[QO_INTERP_BEZIER_MAX_POINTS + 1], out, o2, u0, un;
    int i, k;
    size_t n;
    rng_seed(0xBE21E4ull);
    for (i = 0; i < 400; i++) {
        dq p = rand_unit();
        n = 2 + (size_t)(i % (QO_INTERP_BEZIER_MAX_POINTS - 1));
        for (k = 0; k < (int)n; k++) {
            p = dq_mul(p, rand_axis_rot(rng_range(0, 1.5)));
            cp[k] = c->q_in(dq_scale(rng_u() < 0.3 ? dq_neg(p) : p, rng_range(0.5, 1.9)));
        }
        for (k = 0; k <= 10; k++) {
            double t = (double)k / 10.0;
            dq ref = d_bezier(cp, n, c->t_in(t));
            assert_int_equal(c->bezier(cp, n, t, &out), QO_OK);
            CHECK(dist4(ref, out) <= 2 * c->tol_rot && norm_dev(out) <= c->tol_norm,
                  "%s bezier n=%u t=%g error %.3g", c->name, (unsigned)n, t, dist4(ref, out));
        }
        /* exact end points */
        u0 = cu(c, cp[0]);
        un = cu(c, cp[n - 1]);
        assert_int_equal(c->bezier(cp, n, 0.0, &out), QO_OK);
        CHECK(dq_equal(out, u0), "%s bezier t=0 n=%u", c->name, (unsigned)n);
        assert_int_equal(c->bezier(cp, n, 1.0, &out), QO_OK);
        CHECK(dq_equal(out, un) || dq_equal(out, dq_neg(un)), "%s bezier t=1 n=%u", c->name,
              (unsigned)n);
        if (n == 2) { /* a 2-point Bezier is slerp */
            for (k = 0; k <= 10; k++) {
                double t = (double)k / 10.0;
                assert_int_equal(c->bezier(cp, 2, t, &out), QO_OK);
                assert_int_equal(c->slerp(cp[0], cp[1], t, &o2), QO_OK);
                CHECK(dist4(out, o2) <= c->tol_rot, "%s bezier2 vs slerp t=%g", c->name, t);
            }
        }
        if (n == 4) { /* the cubic shortcut is the same function */
            assert_int_equal(c->bezier3(cp[0], cp[1], cp[2], cp[3], 0.3, &o2), QO_OK);
            assert_int_equal(c->bezier(cp, 4, 0.3, &out), QO_OK);
            CHECK(dq_equal(out, o2), "%s bezier3 vs bezier n=4", c->name);
        }
    }
    /* errors */
    for (k = 0; k <= QO_INTERP_BEZIER_MAX_POINTS; k++) cp[k] = c->q_in(rand_unit());
    assert_int_equal(c->bezier(cp, QO_INTERP_BEZIER_MAX_POINTS + 1, 0.5, &out), QO_E_CAPACITY);
    assert_true(dq_equal(out, ID));
    assert_int_equal(c->bezier(cp, QO_INTERP_BEZIER_MAX_POINTS, 0.5, &out), QO_OK);
    assert_int_equal(c->bezier(cp, 1, 0.5, &out), QO_E_TOO_FEW);
    assert_int_equal(c->bezier(cp, 0, 0.5, &out), QO_E_TOO_FEW);
    assert_true(dq_equal(out, ID));
    assert_int_equal(c->bezier(NULL, 3, 0.5, &out), QO_E_NULL);
    assert_true(dq_equal(out, ID));
    assert_int_equal(c->bezier(cp, 3, 0.5, NULL), QO_E_NULL);
    u0 = cu(c, cp[0]);
    assert_int_equal(c->bezier(cp, 3, -0.5, &out), QO_E_RANGE);
    CHECK(dq_equal(out, u0), "%s bezier t out of range: unit ctrl[0]", c->name);
    assert_int_equal(c->bezier(cp, 3, c->big, &out), ST(c, QO_E_NONFINITE, QO_E_RANGE));
    CHECK(dq_equal(out, u0), "%s bezier t=big: unit ctrl[0]", c->name);
    cp[1] = ZERO_Q;
    assert_int_equal(c->bezier(cp, 3, 0.5, &out), QO_E_DEGENERATE);
    assert_true(dq_equal(out, ID));
    cp[2] = big_q(c);
    cp[1] = c->q_in(rand_unit());
    assert_int_equal(c->bezier3(cp[0], cp[1], cp[2], cp[3], 0.5, &out),
                     ST(c, QO_E_NONFINITE, QO_OK));
}

/* ---- Shoemake spline, both cores -------------------------------------------------------- */

static dq d_spline_eval(const dq *q, const dq *a, const dq *b, size_t n, double s)
{
    size_t i = (size_t)s;
    dq p[4];
    if (i > n - 2) i = n - 2;
    p[0] = q[i]; p[1] = a[i]; p[2] = b[i + 1]; p[3] = q[i + 1];
    return d_bezier(p, 4, s - (double)i);
}
/* A random key sequence: steps of 0.05..maxstep rad, random signs and scales (unaligned),
 * already as the core receives them. */
static void rand_keys(const core *c, dq *k, size_t n, double maxstep)
{
    dq p = rand_unit();
    size_t i;
    for (i = 0; i < n; i++) {
        if (i) p = dq_mul(p, rand_axis_rot(rng_range(0.05, maxstep)));
        k[i] = c->q_in(dq_scale(rng_u() < 0.4 ? dq_neg(p) : p, rng_range(0.5, 1.9)));
    }
}
static void d_align(const dq *k, size_t n, dq *q)
{
    size_t i;
    for (i = 0; i < n; i++) {
        q[i] = dq_unit(k[i]);
        if (i && dq_dot_exact(q[i - 1], q[i]) < 0) q[i] = dq_neg(q[i]);
    }
}

/* ---- the fixture of the spline and Squad bodies: each body states its key count, its step
 * and its seed; the keys, their double alignment and the controls come from here ---------- */

/* Control points against double: float32 2e-6 (the former float-only test's bound); fixed
 * point 10x its slerp tolerance. */
static double ctrl_tol(const core *c) { return c->fixed ? 10 * c->tol_rot : 2e-6; }

/* n random keys as the core receives them (k, steps up to maxstep rad) and the same keys
 * normalised and sign-aligned in double (q). */
static void keys_case(const core *c, size_t n, double maxstep, dq *k, dq *q)
{
    rand_keys(c, k, n, maxstep);
    d_align(k, n, q);
}

/* keys_case, then the double spline controls (da, db) and the core's (a, b), which must
 * succeed. */
static void spline_case(const core *c, size_t n, double maxstep, dq *k, dq *q, dq *da, dq *db,
                        dq *a, dq *b)
{
    keys_case(c, n, maxstep, k, q);
    d_spline_controls(q, n, da, db);
    assert_int_equal(c->spline_controls(k, n, a, b), QO_OK);
}

static void test_spline_vs_double_and_through_keys(void **state)
{
    const core *c = *state;
    dq k[MAXK], a[MAXK], b[MAXK], q[MAXK], da[MAXK], db[MAXK], out;
    int it, j;
    size_t n, i;
    double tol_ctrl = ctrl_tol(c);
    rng_seed(0x5B11E5ull);
    for (it = 0; it < 120; it++) {
        n = 2 + (size_t)(it % (MAXK - 1));
        spline_case(c, n, it % 2 ? 1.5 : 3.0, k, q, da, db, a, b);
        for (i = 0; i < n; i++) {
            if (i + 1 < n)
                CHECK(dist4(da[i], a[i]) <= tol_ctrl, "%s spline a[%u] n=%u error %.3g",
                      c->name, (unsigned)i, (unsigned)n, dist4(da[i], a[i]));
            if (i > 0)
                CHECK(dist4(db[i], b[i]) <= tol_ctrl, "%s spline b[%u] n=%u error %.3g",
                      c->name, (unsigned)i, (unsigned)n, dist4(db[i], b[i]));
        }
        for (i = 0; i < n; i++) { /* through every key, with the aligned sign */
            assert_int_equal(c->spline_eval(k, a, b, n, (double)i, &out), QO_OK);
            CHECK(dist4(q[i], out) <= c->tol_rot && norm_dev(out) <= c->tol_norm,
                  "%s spline through key %u of %u: error %.3g", c->name, (unsigned)i,
                  (unsigned)n, dist4(q[i], out));
        }
        for (j = 0; j < 40; j++) { /* anywhere vs the double construction */
            double s = rng_u() * (double)(n - 1), is = c->s_in(s);
            dq ref = d_spline_eval(q, da, db, n, is);
            assert_int_equal(c->spline_eval(k, a, b, n, s, &out), QO_OK);
            CHECK(dist4(ref, out) <= 1.5 * tol_ctrl && norm_dev(out) <= c->tol_norm,
                  "%s spline n=%u s=%.9g error %.3g", c->name, (unsigned)n, is, dist4(ref, out));
        }
        if (n == 2) { /* two keys: the spline is slerp */
            for (j = 0; j <= 10; j++) {
                dq o2;
                double s = c->s_in((double)j / 10.0); /* exact as t too */
                assert_int_equal(c->spline_eval(k, a, b, n, s, &out), QO_OK);
                assert_int_equal(c->slerp(k[0], k[1], s, &o2), QO_OK);
                CHECK(dist4(out, o2) <= 2 * c->tol_rot, "%s 2-key spline vs slerp s=%g",
                      c->name, s);
            }
        }
    }
}

/* Body-frame rotation vector 2 log(conj(p) x) in double, short way. */
static void rotvec(dq p, dq x, double v[3])
{
    dq d;
    double vn, k;
    p = dq_unit(p);
    x = dq_unit(x);
    if (dq_dot(p, x) < 0) x = dq_neg(x);
    d = dq_mul(dq_conj(p), x);
    vn = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    k = (vn > 0) ? 2 * atan2(vn, d.w) / vn : 2.0;
    v[0] = d.x * k; v[1] = d.y * k; v[2] = d.z * k;
}
/* One-sided second-order angular velocity at s0 from r(s0 + sg h), r(s0 + sg 2h):
 * (4 r(h) - r(2h)) / (2h) = w - r''' h^2 / 3. */
static void omega_side(const double r1[3], const double r2[3], double h, double sg, double w[3])
{
    int i;
    for (i = 0; i < 3; i++) w[i] = sg * (4 * r1[i] - r2[i]) / (2 * h);
}
static double vdist(const double a[3], const double b[3])
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* C1 at every join, as test_interp.c: the angular velocity just left and just right of each
 * inner key agrees within a tolerance derived per join from the measured sample error e
 * (10e/h) and the truncation of the stencil estimated on the double construction; piecewise
 * slerp through the same keys must then show a jump far above it (the check can fail).
 * h = 1/64 is exact in float and in Q16.16. */
static void test_spline_c1(void **state)
{
    const core *c = *state;
    dq k[MAXK], a[MAXK], b[MAXK], q[MAXK], da[MAXK], db[MAXK], f[5], g[5], dref[5];
    const double h = 1.0 / 64;
    double worst_ratio = 0;
    int it, j;
    size_t n, i;
    rng_seed(0xC1C1ull);
    for (it = 0; it < 40; it++) {
        n = 3 + (size_t)(it % (MAXK - 2));
        spline_case(c, n, 1.5, k, q, da, db, a, b);
        for (i = 1; i + 1 < n; i++) {
            double s0 = (double)i, e = 0, trunc, tol, jump;
            double rl1[3], rl2[3], rr1[3], rr2[3], wl[3], wr[3], w1l[3], w1r[3], w2l[3], w2r[3];
            dq m2 = d_spline_eval(q, da, db, n, s0 - 4 * h);
            dq p2 = d_spline_eval(q, da, db, n, s0 + 4 * h);
            for (j = 0; j < 5; j++) { /* s0-2h .. s0+2h */
                double s = s0 + (j - 2) * h;
                size_t seg = (j < 2) ? i - 1 : i;
                assert_int_equal(c->spline_eval(k, a, b, n, s, &f[j]), QO_OK);
                dref[j] = d_spline_eval(q, da, db, n, s);
                if (rot_err(dref[j], f[j]) > e) e = rot_err(dref[j], f[j]);
                assert_int_equal(c->slerp(k[seg], k[seg + 1], s - (double)seg, &g[j]), QO_OK);
            }
            rotvec(f[2], f[1], rl1); rotvec(f[2], f[0], rl2);
            rotvec(f[2], f[3], rr1); rotvec(f[2], f[4], rr2);
            omega_side(rl1, rl2, h, -1, wl);
            omega_side(rr1, rr2, h, 1, wr);
            /* truncation from the double construction: stencil at h vs at 2h */
            rotvec(dref[2], dref[1], rl1); rotvec(dref[2], dref[0], rl2);
            rotvec(dref[2], dref[3], rr1); rotvec(dref[2], dref[4], rr2);
            omega_side(rl1, rl2, h, -1, w1l); omega_side(rr1, rr2, h, 1, w1r);
            rotvec(dref[2], dref[0], rl1); rotvec(dref[2], m2, rl2);
            rotvec(dref[2], dref[4], rr1); rotvec(dref[2], p2, rr2);
            omega_side(rl1, rl2, 2 * h, -1, w2l); omega_side(rr1, rr2, 2 * h, 1, w2r);
            trunc = 2 * (vdist(w1l, w2l) + vdist(w1r, w2r)) / 3;
            tol = 10 * e / h + 2 * trunc + 1e-9;
            jump = vdist(wl, wr);
            if (jump / tol > worst_ratio) worst_ratio = jump / tol;
            CHECK(jump <= tol, "%s C1 at key %u of %u: |w_left - w_right| = %.3g > tol %.3g "
                  "(e=%.3g, trunc=%.3g)", c->name, (unsigned)i, (unsigned)n, jump, tol, e,
                  trunc);
            /* sensitivity: piecewise slerp has a velocity jump at the key */
            rotvec(g[2], g[1], rl1); rotvec(g[2], g[0], rl2);
            rotvec(g[2], g[3], rr1); rotvec(g[2], g[4], rr2);
            omega_side(rl1, rl2, h, -1, wl);
            omega_side(rr1, rr2, h, 1, wr);
            CHECK(vdist(wl, wr) > 10 * tol, "%s C1 check too weak: piecewise slerp jump %.3g vs "
                  "tol %.3g at key %u", c->name, vdist(wl, wr), tol, (unsigned)i);
        }
    }
    print_message("%s spline C1: worst |jump| / tolerance = %.3f\n", c->name, worst_ratio);
}

/* Flipping the sign of any keys (and scaling them) gives the same rotations everywhere. */
static void test_spline_sign_invariance(void **state)
{
    const core *c = *state;
    dq k[MAXK], k2[MAXK], a[MAXK], b[MAXK], a2[MAXK], b2[MAXK], o1, o2, o3;
    int it, j;
    size_t n, i;
    rng_seed(0x516Full);
    for (it = 0; it < 60; it++) {
        n = 2 + (size_t)(it % (MAXK - 1));
        rand_keys(c, k, n, 2.0);
        for (i = 0; i < n; i++) k2[i] = (rng_u() < 0.5) ? dq_neg(k[i]) : k[i];
        k2[0] = dq_neg(k[0]);
        assert_int_equal(c->spline_controls(k, n, a, b), QO_OK);
        assert_int_equal(c->spline_controls(k2, n, a2, b2), QO_OK);
        for (j = 0; j <= 50; j++) {
            double s = (double)j / 50.0 * (double)(n - 1);
            assert_int_equal(c->spline_eval(k, a, b, n, s, &o1), QO_OK);
            assert_int_equal(c->spline_eval(k2, a2, b2, n, s, &o2), QO_OK);
            assert_int_equal(c->spline_eval(k2, a, b, n, s, &o3), QO_OK);
            CHECK(rot_err(o1, o2) <= c->tol_rot && rot_err(o1, o3) <= c->tol_rot,
                  "%s sign-flipped keys n=%u s=%g: %.3g / %.3g", c->name, (unsigned)n, s,
                  rot_err(o1, o2), rot_err(o1, o3));
            CHECK(dist4(o1, o3) <= c->tol_rot, "%s output sign must follow the aligned keys "
                  "n=%u s=%g", c->name, (unsigned)n, s);
        }
    }
}

/* The end rule of the notes: keys at a uniform rate about one axis give a_0 = q_0 and
 * b_{N-1} = q_{N-1}; interior controls at 1/3 of the step. A 180-deg swing out and back has
 * the documented zero tangent at the middle key. */
static void test_spline_end_rule_and_swing_back(void **state)
{
    const core *c = *state;
    const dq swing[3] = { { 1, 0, 0, 0 }, { 0, 0, 1, 0 }, { 1, 0, 0, 0 } };
    dq k[5], a[5], b[5], base, step, out;
    double tol = ctrl_tol(c);
    int i;
    rng_seed(0xE2Dull);
    base = rand_unit();
    step = rand_axis_rot(0.4);
    for (i = 0; i < 5; i++) {
        k[i] = c->q_in(base);
        base = dq_mul(base, step);
    }
    assert_int_equal(c->spline_controls(k, 5, a, b), QO_OK);
    CHECK(rot_err(a[0], k[0]) <= tol, "%s a_0 = q_0 for uniform keys: %.3g", c->name,
          rot_err(a[0], k[0]));
    CHECK(rot_err(b[4], k[4]) <= tol, "%s b_N = q_N for uniform keys: %.3g", c->name,
          rot_err(b[4], k[4]));
    for (i = 1; i < 4; i++) {
        double ang = rot_err(k[i], a[i]);
        CHECK(fabs(ang - 0.4 / 3) <= tol, "%s a_%d at %.9g rad, want %.9g", c->name, i, ang,
              0.4 / 3);
    }
    assert_int_equal(c->spline_controls(swing, 3, a, b), QO_OK);
    CHECK(rot_err(a[1], swing[1]) <= c->tol_rot && rot_err(b[1], swing[1]) <= c->tol_rot,
          "%s swing back: zero tangent at the middle key", c->name);
    for (i = 0; i <= 20; i++) {
        double s = (double)i / 10.0;
        assert_int_equal(c->spline_eval(swing, a, b, 3, s, &out), QO_OK);
        CHECK(norm_dev(out) <= c->tol_norm, "%s swing back s=%g", c->name, s);
    }
}

/* Statuses and the documented outputs of spline_controls and spline_eval. */
static void test_spline_errors(void **state)
{
    const core *c = *state;
    dq k[4], a[4], b[4], out;
    int i;
    rng_seed(0xE44ull);
    rand_keys(c, k, 4, 1.0);
    assert_int_equal(c->spline_controls(k, 1, a, b), QO_E_TOO_FEW);
    assert_true(dq_equal(a[0], ID) && dq_equal(b[0], ID));
    assert_int_equal(c->spline_controls(NULL, 4, a, b), QO_E_NULL);
    for (i = 0; i < 4; i++)
        CHECK(dq_equal(a[i], ID) && dq_equal(b[i], ID), "%s NULL keys: identity %d", c->name, i);
    assert_int_equal(c->spline_controls(k, 4, NULL, b), QO_E_NULL);
    assert_int_equal(c->spline_controls(k, 4, a, b), QO_OK);
    /* s out of range: nearest end key */
    assert_int_equal(c->spline_eval(k, a, b, 4, -0.001, &out), QO_E_RANGE);
    CHECK(dq_equal(out, cu(c, k[0])), "%s s < 0: unit first key", c->name);
    assert_int_equal(c->spline_eval(k, a, b, 4, 3.001, &out), QO_E_RANGE);
    CHECK(dq_equal(out, cu(c, k[3])), "%s s > n-1: unit last key", c->name);
    /* s = big: Inf (float32: NONFINITE) / saturated (fixed: RANGE); the last key either way */
    assert_int_equal(c->spline_eval(k, a, b, 4, c->big, &out), ST(c, QO_E_NONFINITE, QO_E_RANGE));
    CHECK(dq_equal(out, cu(c, k[3])), "%s s = big: unit last key", c->name);
    assert_int_equal(c->spline_eval(k, a, b, 4, 3.0, &out), QO_OK);
    assert_int_equal(c->spline_eval(k, a, b, 1, 0.0, &out), QO_E_TOO_FEW);
    assert_true(dq_equal(out, ID));
    assert_int_equal(c->spline_eval(k, NULL, b, 4, 1.0, &out), QO_E_NULL);
    assert_true(dq_equal(out, ID));
    assert_int_equal(c->spline_eval(k, a, b, 4, 1.0, NULL), QO_E_NULL);
    k[1] = ZERO_Q;
    assert_int_equal(c->spline_eval(k, a, b, 4, 0.5, &out), QO_E_DEGENERATE);
    assert_true(dq_equal(out, ID));
    assert_int_equal(c->spline_eval(k, a, b, 4, 2.5, &out), QO_OK); /* other segment */
    assert_int_equal(c->spline_controls(k, 4, a, b), QO_E_DEGENERATE);
    for (i = 0; i < 4; i++)
        CHECK(dq_equal(a[i], ID) && dq_equal(b[i], ID), "%s zero key: identity %d", c->name, i);
    k[1] = ID;
    k[3] = big_q(c);
    assert_int_equal(c->spline_controls(k, 4, a, b), ST(c, QO_E_NONFINITE, QO_OK));
}

/* ---- Squad, both cores ------------------------------------------------------------------ */

static dq d_squad(dq q0, dq s0, dq s1, dq q1, double t)
{
    dq x = dq_unit(d_slerp_raw(q0, q1, t)), y = dq_unit(d_slerp_raw(s0, s1, t));
    return dq_unit(d_slerp_raw(x, y, 2 * t * (1 - t)));
}

/* Inner points vs the classic formula in double, segments vs double (on the core's own inner
 * points, sign-aligned as documented), exact ends, sign independence, statuses. */
static void test_squad(void **state)
{
    const core *c = *state;
    const dq id = { 1, 0, 0, 0 }, zero = { 0, 0, 0, 0 };
    dq k[MAXK], s[MAXK], q[MAXK], ds[MAXK], out, o2, u;
    double tol_ctrl = ctrl_tol(c);
    int it, j;
    size_t n, i;
    rng_seed(0x50AAull);
    for (it = 0; it < 100; it++) {
        n = 2 + (size_t)(it % (MAXK - 1));
        keys_case(c, n, 1.5, k, q);
        d_squad_controls(q, n, ds);
        assert_int_equal(c->squad_controls(k, n, s), QO_OK);
        for (i = 0; i < n; i++)
            CHECK(dist4(ds[i], s[i]) <= tol_ctrl, "%s squad s[%u] of %u: %.3g", c->name,
                  (unsigned)i, (unsigned)n, dist4(ds[i], s[i]));
        for (i = 0; i + 1 < n; i++) {
            dq s0 = dq_unit(s[i]), s1 = dq_unit(s[i + 1]);
            if (dq_dot_exact(s0, q[i]) < 0) s0 = dq_neg(s0);
            if (dq_dot_exact(s1, q[i + 1]) < 0) s1 = dq_neg(s1);
            assert_int_equal(c->unit(k[i], &u), QO_OK);
            assert_int_equal(c->squad(k[i], s[i], s[i + 1], k[i + 1], 0.0, &out), QO_OK);
            CHECK(dq_equal(out, u), "%s squad t=0 segment %u", c->name, (unsigned)i);
            assert_int_equal(c->squad(k[i], s[i], s[i + 1], k[i + 1], 1.0, &out), QO_OK);
            CHECK(rot_err(out, k[i + 1]) <= c->tol_rot, "%s squad t=1 segment %u", c->name,
                  (unsigned)i);
            for (j = 1; j < 10; j++) {
                double t = (double)j / 10.0;
                dq ref = d_squad(q[i], s0, s1, q[i + 1], c->t_in(t));
                assert_int_equal(c->squad(k[i], s[i], s[i + 1], k[i + 1], t, &out), QO_OK);
                CHECK(rot_err(ref, out) <= 3 * c->tol_rot && norm_dev(out) <= c->tol_norm,
                      "%s squad segment %u t=%g: %.3g", c->name, (unsigned)i, t,
                      rot_err(ref, out));
                /* and on the double inner points: the controls' error carried through */
                ref = d_squad(q[i], ds[i], ds[i + 1], q[i + 1], c->t_in(t));
                CHECK(rot_err(ref, out) <= 1.5 * tol_ctrl, "%s squad segment %u t=%g vs the "
                      "double inner points: %.3g", c->name, (unsigned)i, t, rot_err(ref, out));
                assert_int_equal(c->squad(dq_neg(k[i]), s[i], dq_neg(s[i + 1]), k[i + 1], t,
                                          &o2), QO_OK);
                CHECK(rot_err(o2, out) <= c->tol_rot, "%s squad signs t=%g", c->name, t);
            }
        }
    }
    assert_int_equal(c->unit(k[0], &u), QO_OK);
    assert_int_equal(c->squad(k[0], s[0], s[1], k[1], 1.5, &out), QO_E_RANGE);
    CHECK(dq_equal(out, u), "%s squad t out of range: unit q0", c->name);
    assert_int_equal(c->squad(k[0], s[0], s[1], k[1], c->big, &out),
                     ST(c, QO_E_NONFINITE, QO_E_RANGE));
    CHECK(dq_equal(out, u), "%s squad t = big: unit q0", c->name);
    assert_int_equal(c->squad(k[0], s[0], s[1], k[1], 0.5, NULL), QO_E_NULL);
    assert_int_equal(c->squad(k[0], zero, s[1], k[1], 0.5, &out), QO_E_DEGENERATE);
    CHECK(dq_equal(out, id), "%s squad zero point: identity", c->name);
    assert_int_equal(c->squad_controls(k, 1, s), QO_E_TOO_FEW);
    assert_int_equal(c->squad_controls(NULL, 3, s), QO_E_NULL);
    for (i = 0; i < 3; i++) CHECK(dq_equal(s[i], id), "%s squad controls NULL fill", c->name);
    k[1] = big_q(c);
    assert_int_equal(c->squad_controls(k, 3, s), ST(c, QO_E_NONFINITE, QO_OK));
    k[1] = zero;
    assert_int_equal(c->squad_controls(k, 3, s), QO_E_DEGENERATE);
    for (i = 0; i < 3; i++) CHECK(dq_equal(s[i], id), "%s squad controls error fill", c->name);
}

/* ---- fixed point only ------------------------------------------------------------------- */

static const qo_quat_q30 ID_X = { QO_Q30_ONE, 0, 0, 0 };
static const qo_quat_q30 ZERO_X = { 0, 0, 0, 0 };
static int x_equal(qo_quat_q30 a, qo_quat_q30 b) { return memcmp(&a, &b, sizeof a) == 0; }
static qo_quat_q30 x_neg(qo_quat_q30 q)
{
    qo_quat_q30 r = { -q.w, -q.x, -q.y, -q.z };
    return r;
}
static qo_quat_q30 xu(qo_quat_q30 q)
{
    qo_quat_q30 u;
    assert_int_equal(qo_interp_align_keys_q30(&q, 1, &u), QO_OK);
    return u;
}
static int64_t x_dot(qo_quat_q30 a, qo_quat_q30 b)
{
    return (int64_t)a.w * b.w + (int64_t)a.x * b.x + (int64_t)a.y * b.y + (int64_t)a.z * b.z;
}
#define XF(q) (int)(q).w, (int)(q).x, (int)(q).y, (int)(q).z
#define XFMT "(%d %d %d %d)"

/* The module's normalisation against double: within 1 LSB per component for any non-zero
 * input from 1 LSB up to all components INT32_MIN; exactly representable unit quaternions come
 * back unchanged. */
static void test_fx_normalisation(void **state)
{
    static const qo_quat_q30 edge[] = {
        { 1, 0, 0, 0 }, { 0, 0, 0, -1 }, { 1, 1, 0, 0 }, { 1, -1, 1, -1 },
        { INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN },
        { INT32_MAX, INT32_MAX, INT32_MAX, INT32_MAX },
        { INT32_MIN, 0, 0, 1 }, { INT32_MAX, INT32_MIN, 3, -7 }, { 3, 0, 0, 4 },
        { QO_Q30_ONE / 2, QO_Q30_ONE / 2, QO_Q30_ONE / 2, QO_Q30_ONE / 2 },
    };
    static const qo_quat_q30 exact_units[] = {
        { QO_Q30_ONE, 0, 0, 0 }, { 0, -QO_Q30_ONE, 0, 0 },
        { QO_Q30_ONE / 2, -QO_Q30_ONE / 2, QO_Q30_ONE / 2, QO_Q30_ONE / 2 },
    };
    size_t i;
    int k;
    (void)state;
    rng_seed(0x404Dull);
    for (i = 0; i < sizeof edge / sizeof edge[0] + 3000; i++) {
        qo_quat_q30 q, u;
        dq ref;
        double e;
        if (i < sizeof edge / sizeof edge[0]) {
            q = edge[i];
        } else { /* random direction and magnitude 2^-30 .. 1.99 */
            q = x_from(dq_scale(rand_unit(), pow(2.0, rng_range(-28, 0.99))));
            if (q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0) continue;
        }
        u = xu(q);
        {
            qo_quat_q30 u2;
            assert_int_equal(qo_quat_normalize_q30(q, &u2), QO_OK);
            CHECK(x_equal(u, u2), "unit a is qo_quat_normalize_q30(a): " XFMT, XF(q));
        }
        ref = dq_unit(dq_from_x(q));
        e = fabs(u.w / Q30 - ref.w);
        for (k = 0; k < 3; k++) {
            double d = fabs((k == 0 ? u.x : k == 1 ? u.y : u.z) / Q30 -
                            (k == 0 ? ref.x : k == 1 ? ref.y : ref.z));
            if (d > e) e = d;
        }
        CHECK(e <= 1.0 / Q30, "normalise " XFMT ": component error %.3g LSB", XF(q), e * Q30);
    }
    for (i = 0; i < sizeof exact_units / sizeof exact_units[0]; i++)
        CHECK(x_equal(xu(exact_units[i]), exact_units[i]), "exact unit " XFMT " changed",
              XF(exact_units[i]));
}

/* Extreme magnitudes through slerp (1 LSB inputs, norm-4 inputs) and every t edge value. */
static void test_fx_slerp_extremes(void **state)
{
    static const qo_quat_q30 ex[] = {
        { 1, 0, 0, 0 }, { 0, 1, 1, 0 }, { INT32_MIN, INT32_MIN, INT32_MIN, INT32_MIN },
        { INT32_MAX, 0, INT32_MIN, 0 }, { 0, 0, 0, INT32_MIN }, { -1, 2, -3, 4 },
    };
    static const qo_q30 ts[] = { 0, 1, 2, QO_Q30_ONE / 3, QO_Q30_ONE / 2, QO_Q30_ONE - 1,
                                 QO_Q30_ONE };
    static const qo_q30 bad_t[] = { -1, INT32_MIN, QO_Q30_ONE + 1, INT32_MAX };
    size_t i, j, k;
    (void)state;
    for (i = 0; i < sizeof ex / sizeof ex[0]; i++) {
        for (j = 0; j < sizeof ex / sizeof ex[0]; j++) {
            for (k = 0; k < sizeof ts / sizeof ts[0]; k++) {
                char name[96];
                snprintf(name, sizeof name, "extreme pair %u,%u t=%d", (unsigned)i, (unsigned)j,
                         (int)ts[k]);
                check_slerp_case(&CORE_FX, name, dq_from_x(ex[i]), dq_from_x(ex[j]),
                                 ts[k] / Q30);
            }
            for (k = 0; k < sizeof bad_t / sizeof bad_t[0]; k++) {
                qo_quat_q30 out;
                assert_int_equal(qo_interp_slerp_q30(ex[i], ex[j], bad_t[k], &out), QO_E_RANGE);
                CHECK(x_equal(out, xu(ex[i])), "slerp t=%d: out must be unit a",
                      (int)bad_t[k]);
                assert_int_equal(qo_interp_nlerp_q30(ex[i], ex[j], bad_t[k], &out), QO_E_RANGE);
                assert_int_equal(qo_interp_lerp_q30(ex[i], ex[j], bad_t[k], &out), QO_E_RANGE);
                CHECK(x_equal(out, ex[i]), "lerp t=%d: out must be a", (int)bad_t[k]);
            }
        }
    }
    {
        qo_quat_q30 out;
        assert_int_equal(qo_interp_slerp_q30(ex[0], ex[1], 0, NULL), QO_E_NULL);
        assert_int_equal(qo_interp_nlerp_q30(ex[0], ex[1], 0, NULL), QO_E_NULL);
        assert_int_equal(qo_interp_lerp_q30(ex[0], ex[1], 0, NULL), QO_E_NULL);
        assert_int_equal(qo_interp_slerp_q30(ZERO_X, ZERO_X, -1, &out), QO_E_DEGENERATE);
        assert_true(x_equal(out, ID_X));
    }
}

/* t == 0 / t == 1: bit-exact unit a / unit b' (sign by the exact integer dot product). */
static void test_fx_exact_endpoints(void **state)
{
    int i;
    (void)state;
    rng_seed(0xB17Eull);
    for (i = 0; i < 500; i++) {
        qo_quat_q30 a = x_from(dq_scale(rand_unit(), rng_range(0.01, 1.99)));
        qo_quat_q30 b = x_from(dq_scale(rand_unit(), rng_range(0.01, 1.99)));
        qo_quat_q30 ua = xu(a), ub = xu(b), o;
        if (x_dot(ua, ub) < 0) ub = x_neg(ub);
        assert_int_equal(qo_interp_slerp_q30(a, b, 0, &o), QO_OK);
        CHECK(x_equal(o, ua), "slerp t=0 a=" XFMT, XF(a));
        assert_int_equal(qo_interp_slerp_q30(a, b, QO_Q30_ONE, &o), QO_OK);
        CHECK(x_equal(o, ub), "slerp t=1 a=" XFMT " b=" XFMT, XF(a), XF(b));
        assert_int_equal(qo_interp_nlerp_q30(a, b, 0, &o), QO_OK);
        CHECK(x_equal(o, ua), "nlerp t=0 a=" XFMT, XF(a));
        assert_int_equal(qo_interp_nlerp_q30(a, b, QO_Q30_ONE, &o), QO_OK);
        CHECK(x_equal(o, ub), "nlerp t=1 a=" XFMT " b=" XFMT, XF(a), XF(b));
    }
}

/* lerp: a + t (b - a) rounded once, against long double; exact ends; no overflow for the
 * extreme components (the result lies between the inputs); no flip, no normalisation. */
static void test_fx_lerp(void **state)
{
    static const int32_t ext[] = { INT32_MIN, INT32_MIN + 1, -1, 0, 1, INT32_MAX - 1, INT32_MAX };
    qo_quat_q30 out;
    int i;
    size_t j, k;
    (void)state;
    rng_seed(0x1E4B30ull);
    for (i = 0; i < 2000; i++) {
        qo_quat_q30 a, b;
        qo_q30 t = (qo_q30)(rng_next() % ((uint64_t)QO_Q30_ONE + 1));
        a.w = (int32_t)(uint32_t)rng_next(); a.x = (int32_t)(uint32_t)rng_next();
        a.y = (int32_t)(uint32_t)rng_next(); a.z = (int32_t)(uint32_t)rng_next();
        b.w = (int32_t)(uint32_t)rng_next(); b.x = (int32_t)(uint32_t)rng_next();
        b.y = (int32_t)(uint32_t)rng_next(); b.z = (int32_t)(uint32_t)rng_next();
        if (i < 49) { /* every pair of extreme values in w */
            a.w = ext[i % 7];
            b.w = ext[i / 7];
        }
        assert_int_equal(qo_interp_lerp_q30(a, b, t, &out), QO_OK);
        for (k = 0; k < 4; k++) {
            const int32_t *ca = (k == 0) ? &a.w : (k == 1) ? &a.x : (k == 2) ? &a.y : &a.z;
            const int32_t *cb = (k == 0) ? &b.w : (k == 1) ? &b.x : (k == 2) ? &b.y : &b.z;
            const int32_t *co = (k == 0) ? &out.w : (k == 1) ? &out.x : (k == 2) ? &out.y
                                                                                  : &out.z;
            long double ref = (long double)*ca + (long double)t * ((long double)*cb - *ca) /
                              (long double)Q30;
            int32_t lo = *ca < *cb ? *ca : *cb, hi = *ca < *cb ? *cb : *ca;
            CHECK(fabsl(ref - (long double)*co) <= 0.5L && *co >= lo && *co <= hi,
                  "lerp comp %u a=%d b=%d t=%d: %d want %.3Lf", (unsigned)k, (int)*ca, (int)*cb,
                  (int)t, (int)*co, ref);
        }
        assert_int_equal(qo_interp_lerp_q30(a, b, 0, &out), QO_OK);
        CHECK(x_equal(out, a), "lerp t=0 a=" XFMT, XF(a));
        assert_int_equal(qo_interp_lerp_q30(a, b, QO_Q30_ONE, &out), QO_OK);
        CHECK(x_equal(out, b), "lerp t=1 b=" XFMT, XF(b));
    }
    /* q and -q: no flip, the midpoint is zero; zero inputs are plain arithmetic */
    {
        qo_quat_q30 q = x_from(rand_unit());
        assert_int_equal(qo_interp_lerp_q30(q, x_neg(q), QO_Q30_ONE / 2, &out), QO_OK);
        assert_true(x_equal(out, ZERO_X));
        assert_int_equal(qo_interp_lerp_q30(ZERO_X, q, QO_Q30_ONE / 2, &out), QO_OK);
        for (j = 0; j < 4; j++) {
            int32_t c = (j == 0) ? out.w : (j == 1) ? out.x : (j == 2) ? out.y : out.z;
            int32_t h = (j == 0) ? q.w : (j == 1) ? q.x : (j == 2) ? q.y : q.z;
            CHECK(c == (int32_t)(((int64_t)h + 1) >> 1), "lerp(0, q, 1/2) comp %u", (unsigned)j);
        }
    }
}

/* Fixed vs float32 on the same inputs (the float inputs converted with fxconv.h): both
 * compute the same rotation within the float32 tolerance, with the same sign. */
static void test_fx_vs_f32(void **state)
{
    int i;
    (void)state;
    rng_seed(0xF1F2ull);
    for (i = 0; i < 2000; i++) {
        qo_quat_f32 fa = f_from(rand_unit()), fb, fo, fn;
        qo_quat_q30 xa, xb, xo, xn;
        float t = (float)rng_u();
        double e;
        fb = f_from(dq_scale(i % 2 ? rand_unit() : dq_mul(dq_from_f(fa),
                                                           rand_axis_rot(rng_range(0, 1e-3))),
                             rng_range(0.3, 1.9)));
        xa = qo_q30_quat_from_f32(fa);
        xb = qo_q30_quat_from_f32(fb);
        assert_int_equal(qo_interp_slerp_f32(fa, fb, t, &fo), QO_OK);
        assert_int_equal(qo_interp_slerp_q30(xa, xb, qo_q30_from_f32(t), &xo), QO_OK);
        assert_int_equal(qo_interp_nlerp_f32(fa, fb, t, &fn), QO_OK);
        assert_int_equal(qo_interp_nlerp_q30(xa, xb, qo_q30_from_f32(t), &xn), QO_OK);
        if (fabs(dq_dot(dq_from_f(fa), dq_from_f(fb))) < 1e-5) continue; /* ambiguous 180 */
        e = dist4(dq_from_f(fo), dq_from_x(xo));
        CHECK(e <= 1e-6, "fixed vs float32 slerp %.3g a=" QFMT " b=" QFMT " t=%g", e,
              QF(dq_from_f(fa)), QF(dq_from_f(fb)), (double)t);
        e = dist4(dq_from_f(fn), dq_from_x(xn));
        CHECK(e <= 1e-6, "fixed vs float32 nlerp %.3g t=%g", e, (double)t);
    }
    /* spline through the same keys (float keys converted at the boundary) */
    for (i = 0; i < 100; i++) {
        qo_quat_f32 fk[MAXK], fa[MAXK], fb[MAXK], fo;
        qo_quat_q30 xk[MAXK], xa[MAXK], xb[MAXK], xo;
        dq p = rand_unit();
        size_t n = 2 + (size_t)(i % (MAXK - 1)), j;
        for (j = 0; j < n; j++) {
            if (j) p = dq_mul(p, rand_axis_rot(rng_range(0.05, 2.0)));
            fk[j] = f_from(dq_scale(rng_u() < 0.4 ? dq_neg(p) : p, rng_range(0.5, 1.9)));
            xk[j] = qo_q30_quat_from_f32(fk[j]);
        }
        assert_int_equal(qo_interp_spline_controls_f32(fk, n, fa, fb), QO_OK);
        assert_int_equal(qo_interp_spline_controls_q30(xk, n, xa, xb), QO_OK);
        for (j = 0; j <= 4 * (n - 1); j++) { /* s = j/4: exact in float and Q16.16 */
            double e;
            assert_int_equal(qo_interp_spline_eval_f32(fk, fa, fb, n, (float)j / 4.0f, &fo), QO_OK);
            assert_int_equal(qo_interp_spline_eval_q30(xk, xa, xb, n, (qo_q16)(j << 14), &xo),
                             QO_OK);
            e = dist4(dq_from_f(fo), dq_from_x(xo));
            CHECK(e <= 3e-6, "fixed vs float32 spline n=%u s=%g: %.3g", (unsigned)n,
                  (double)j / 4.0, e);
        }
    }
}

/* Spline in Q16.16: exact keys at s = i << 16 (bit-equal to the aligned keys), range ends,
 * statuses; Bezier errors; bezier3 == bezier with 4 points. */
static void test_fx_spline_bezier_edges(void **state)
{
    qo_quat_q30 k[5], a[5], b[5], al[5], out, o2;
    dq dk[5];
    size_t i;
    (void)state;
    rng_seed(0x5B16ull);
    rand_keys(&CORE_FX, dk, 5, 2.5);
    for (i = 0; i < 5; i++) k[i] = x_from(dk[i]);
    assert_int_equal(qo_interp_align_keys_q30(k, 5, al), QO_OK);
    assert_int_equal(qo_interp_spline_controls_q30(k, 5, a, b), QO_OK);
    assert_true(x_equal(b[0], al[0]) && x_equal(a[4], al[4]));
    for (i = 0; i < 5; i++) {
        assert_int_equal(qo_interp_spline_eval_q30(k, a, b, 5, (qo_q16)(i << 16), &out), QO_OK);
        CHECK(x_equal(out, al[i]), "spline at key %u must be the aligned key exactly",
              (unsigned)i);
    }
    assert_int_equal(qo_interp_spline_eval_q30(k, a, b, 5, -1, &out), QO_E_RANGE);
    assert_true(x_equal(out, xu(k[0])));
    assert_int_equal(qo_interp_spline_eval_q30(k, a, b, 5, (4 << 16) + 1, &out), QO_E_RANGE);
    assert_true(x_equal(out, xu(k[4])));
    assert_int_equal(qo_interp_spline_eval_q30(k, a, b, 5, INT32_MIN, &out), QO_E_RANGE);
    assert_int_equal(qo_interp_spline_eval_q30(k, a, b, 5, INT32_MAX, &out), QO_E_RANGE);
    assert_int_equal(qo_interp_spline_eval_q30(k, a, b, 1, 0, &out), QO_E_TOO_FEW);
    assert_true(x_equal(out, ID_X));
    assert_int_equal(qo_interp_spline_eval_q30(k, NULL, b, 5, 0, &out), QO_E_NULL);
    assert_true(x_equal(out, ID_X));
    assert_int_equal(qo_interp_spline_eval_q30(k, a, b, 5, 0, NULL), QO_E_NULL);
    assert_int_equal(qo_interp_spline_controls_q30(k, 1, a, b), QO_E_TOO_FEW);
    assert_true(x_equal(a[0], ID_X) && x_equal(b[0], ID_X));
    assert_int_equal(qo_interp_spline_controls_q30(NULL, 5, a, b), QO_E_NULL);
    for (i = 0; i < 5; i++) assert_true(x_equal(a[i], ID_X) && x_equal(b[i], ID_X));
    assert_int_equal(qo_interp_spline_controls_q30(k, 5, a, b), QO_OK);
    k[1] = ZERO_X;
    assert_int_equal(qo_interp_spline_eval_q30(k, a, b, 5, 1 << 15, &out), QO_E_DEGENERATE);
    assert_true(x_equal(out, ID_X));
    assert_int_equal(qo_interp_spline_eval_q30(k, a, b, 5, 3 << 16, &out), QO_OK);
    assert_int_equal(qo_interp_spline_controls_q30(k, 5, a, b), QO_E_DEGENERATE);
    for (i = 0; i < 5; i++) assert_true(x_equal(a[i], ID_X) && x_equal(b[i], ID_X));
    /* Bezier */
    k[1] = x_from(rand_unit());
    assert_int_equal(qo_interp_bezier3_q30(k[0], k[1], k[2], k[3], QO_Q30_ONE / 3, &out), QO_OK);
    assert_int_equal(qo_interp_bezier_q30(k, 4, QO_Q30_ONE / 3, &o2), QO_OK);
    assert_true(x_equal(out, o2));
    assert_int_equal(qo_interp_bezier_q30(NULL, 3, 0, &out), QO_E_NULL);
    assert_true(x_equal(out, ID_X));
    assert_int_equal(qo_interp_bezier_q30(k, 3, 0, NULL), QO_E_NULL);
    assert_int_equal(qo_interp_bezier_q30(k, 3, QO_Q30_ONE + 1, &out), QO_E_RANGE);
    assert_true(x_equal(out, xu(k[0])));
    assert_int_equal(qo_interp_bezier_q30(k, 0, 0, &out), QO_E_TOO_FEW);
    assert_true(x_equal(out, ID_X));
}

/* Squad segment vs double (inner points from the classic formula, computed here), exact ends,
 * sign independence, statuses. */
static void test_fx_squad(void **state)
{
    int it, j;
    qo_quat_q30 out, o2;
    (void)state;
    rng_seed(0x50A430ull);
    for (it = 0; it < 200; it++) {
        dq q0 = rand_unit(), q1 = dq_mul(q0, rand_axis_rot(rng_range(0.05, 2.5)));
        dq s0 = dq_mul(q0, rand_axis_rot(rng_range(0, 0.6)));
        dq s1 = dq_mul(q1, rand_axis_rot(rng_range(0, 0.6)));
        qo_quat_q30 x0 = x_from(q0), x1 = x_from(it % 2 ? dq_neg(q1) : q1);
        qo_quat_q30 xs0 = x_from(s0), xs1 = x_from(s1);
        dq u0 = dq_unit(dq_from_x(x0)), u1 = dq_unit(dq_from_x(x1));
        dq v0 = dq_unit(dq_from_x(xs0)), v1 = dq_unit(dq_from_x(xs1));
        if (dq_dot_exact(u0, u1) < 0) u1 = dq_neg(u1);
        if (dq_dot_exact(v0, u0) < 0) v0 = dq_neg(v0);
        if (dq_dot_exact(v1, u1) < 0) v1 = dq_neg(v1);
        assert_int_equal(qo_interp_squad_q30(x0, xs0, xs1, x1, 0, &out), QO_OK);
        assert_true(x_equal(out, xu(x0)));
        assert_int_equal(qo_interp_squad_q30(x0, xs0, xs1, x1, QO_Q30_ONE, &out), QO_OK);
        CHECK(dist4(dq_from_x(out), u1) <= 1e-9, "squad t=1 it=%d", it);
        for (j = 1; j < 10; j++) {
            qo_q30 t = (qo_q30)(QO_Q30_ONE / 10 * j);
            double tt = t / Q30;
            dq x = dq_unit(d_slerp_raw(u0, u1, tt)), y = dq_unit(d_slerp_raw(v0, v1, tt));
            dq ref = dq_unit(d_slerp_raw(x, y, 2 * tt * (1 - tt)));
            assert_int_equal(qo_interp_squad_q30(x0, xs0, xs1, x1, t, &out), QO_OK);
            CHECK(dist4(ref, dq_from_x(out)) <= 2 * CORE_FX.tol_rot &&
                  norm_dev(dq_from_x(out)) <= CORE_FX.tol_norm, "squad it=%d t=%g: %.3g", it,
                  tt, dist4(ref, dq_from_x(out)));
            assert_int_equal(qo_interp_squad_q30(x_neg(x0), x_neg(xs0), xs1, x_neg(x1), t, &o2),
                             QO_OK);
            CHECK(rot_err(dq_from_x(o2), dq_from_x(out)) <= CORE_FX.tol_rot,
                  "squad signs it=%d t=%g", it, tt);
        }
    }
    {
        qo_quat_q30 q = x_from(rand_unit());
        assert_int_equal(qo_interp_squad_q30(q, q, q, q, QO_Q30_ONE + 1, &out), QO_E_RANGE);
        assert_true(x_equal(out, xu(q)));
        assert_int_equal(qo_interp_squad_q30(q, ZERO_X, q, q, QO_Q30_ONE / 2, &out),
                         QO_E_DEGENERATE);
        assert_true(x_equal(out, ID_X));
        assert_int_equal(qo_interp_squad_q30(q, q, q, q, 0, NULL), QO_E_NULL);
    }
}

/* ---- float32 only ----------------------------------------------------------------------- */

static int f_bits_equal(qo_quat_f32 a, qo_quat_f32 b) { return memcmp(&a, &b, sizeof a) == 0; }
static qo_quat_f32 f_unit_of(qo_quat_f32 q)
{
    qo_quat_f32 u;
    assert_int_equal(qo_quat_normalize_f32(q, &u), QO_OK);
    return u;
}

/* NaN, which fixed point cannot hold (Inf goes through the shared bodies as `big`): a NaN
 * quaternion gives QO_E_NONFINITE and identity, also over a zero input or a bad t; a NaN
 * parameter gives QO_E_NONFINITE and the documented end value. */
static void test_f32_nan(void **state)
{
    const qo_quat_f32 a = { 0.0f, 0.0f, 0.0f, 2.0f }, b = { 1.0f, 0.0f, 0.0f, 0.0f };
    const qo_quat_f32 ua = { 0.0f, 0.0f, 0.0f, 1.0f }, id = { 1.0f, 0.0f, 0.0f, 0.0f };
    const qo_quat_f32 nanq = { NAN, 0.0f, 0.0f, 1.0f }, zero = { 0.0f, 0.0f, 0.0f, 0.0f };
    qo_quat_f32 out, k[4], ka[4], kb[4];
    qo_vec3_f32 w;
    int which, i;
    (void)state;
    for (which = 0; which < 2; which++) {
        qo_status (*f)(qo_quat_f32, qo_quat_f32, float, qo_quat_f32 *) =
            which ? qo_interp_slerp_long_f32 : qo_interp_slerp_f32;
        CHECK(f(a, b, NAN, &out) == QO_E_NONFINITE && f_bits_equal(out, ua), "t=NaN %d", which);
        CHECK(f(nanq, b, 0.5f, &out) == QO_E_NONFINITE && f_bits_equal(out, id), "a=NaN %d",
              which);
        CHECK(f(a, nanq, 0.5f, &out) == QO_E_NONFINITE && f_bits_equal(out, id), "b=NaN %d",
              which);
        /* NaN wins over zero, whichever argument holds it */
        CHECK(f(zero, nanq, 0.5f, &out) == QO_E_NONFINITE, "a=0 b=NaN %d", which);
        CHECK(f(nanq, zero, 0.5f, &out) == QO_E_NONFINITE, "a=NaN b=0 %d", which);
        /* bad t with bad quaternion: the quaternion is reported */
        CHECK(f(nanq, b, 3.0f, &out) == QO_E_NONFINITE && f_bits_equal(out, id),
              "a=NaN t=3 %d", which);
    }
    assert_int_equal(qo_interp_nlerp_f32(a, b, NAN, &out), QO_E_NONFINITE);
    assert_true(f_bits_equal(out, ua));
    assert_int_equal(qo_interp_nlerp_f32(nanq, b, 0.5f, &out), QO_E_NONFINITE);
    assert_true(f_bits_equal(out, id));
    assert_int_equal(qo_interp_lerp_f32(a, b, NAN, &out), QO_E_NONFINITE);
    assert_true(f_bits_equal(out, a));
    assert_int_equal(qo_interp_lerp_f32(nanq, b, 0.5f, &out), QO_E_NONFINITE);
    assert_true(f_bits_equal(out, id));
    assert_int_equal(qo_interp_slerp_rate_f32(a, a, NAN, &w), QO_E_NONFINITE);
    assert_true(w.x == 0.0f && w.y == 0.0f && w.z == 0.0f);
    assert_int_equal(qo_interp_slerp_rate_f32(nanq, a, 1.0f, &w), QO_E_NONFINITE);
    /* keyframes */
    rng_seed(0xE44ull);
    for (i = 0; i < 4; i++) k[i] = f_from(dq_mul(rand_unit(), rand_axis_rot(0.1 * i)));
    assert_int_equal(qo_interp_bezier_f32(k, 3, NAN, &out), QO_E_NONFINITE);
    assert_true(f_bits_equal(out, f_unit_of(k[0])));
    assert_int_equal(qo_interp_spline_controls_f32(k, 4, ka, kb), QO_OK);
    assert_int_equal(qo_interp_spline_eval_f32(k, ka, kb, 4, NAN, &out), QO_E_NONFINITE);
    assert_true(f_bits_equal(out, f_unit_of(k[0])));
    assert_int_equal(qo_interp_squad_f32(k[0], k[1], k[2], k[3], NAN, &out), QO_E_NONFINITE);
    k[2].y = NAN;
    assert_int_equal(qo_interp_align_keys_f32(k, 4, ka), QO_E_NONFINITE);
    kb[0] = k[0];
    kb[1] = zero; /* NaN wins over a zero key */
    kb[2] = k[2];
    assert_int_equal(qo_interp_align_keys_f32(kb, 3, ka), QO_E_NONFINITE);
    for (i = 0; i < 4; i++) assert_true(f_bits_equal(ka[i], id));
    assert_int_equal(qo_interp_bezier_f32(k, 3, 0.5f, &out), QO_E_NONFINITE);
    assert_true(f_bits_equal(out, id));
    assert_int_equal(qo_interp_spline_controls_f32(k, 4, ka, kb), QO_E_NONFINITE);
    assert_int_equal(qo_interp_squad_controls_f32(k, 4, ka), QO_E_NONFINITE);
}

/* BOTH, FAST: common/cores.h, one cmocka line per core */
int main(void)
{
    const struct CMUnitTest tests[] = {
        /* both cores */
        BOTH(test_slerp_random_vs_double),
        BOTH(test_slerp_edge_table),
        BOTH(test_slerp_same_rotation_opposite_sign),
        BOTH(test_slerp_exact_180),
        BOTH(test_slerp_nearly_180_ambiguous),
        BOTH(test_slerp_exact_endpoints),
        BOTH(test_slerp_constant_rate),
        BOTH(test_slerp_nlerp_errors),
        BOTH(test_slerp_long),
        BOTH(test_slerp_rate),
        BOTH(test_lerp),
        BOTH(test_nlerp),
        BOTH(test_align_keys),
        BOTH(test_bezier),
        BOTH(test_spline_vs_double_and_through_keys),
        BOTH(test_spline_c1),
        BOTH(test_spline_sign_invariance),
        BOTH(test_spline_end_rule_and_swing_back),
        BOTH(test_spline_errors),
        BOTH(test_squad),
        /* the fixed fast tier through the slerp bodies */
        FAST(test_slerp_random_vs_double),
        FAST(test_slerp_edge_table),
        FAST(test_slerp_same_rotation_opposite_sign),
        FAST(test_slerp_exact_180),
        FAST(test_slerp_nearly_180_ambiguous),
        FAST(test_slerp_exact_endpoints),
        FAST(test_slerp_constant_rate),
        /* fixed point only */
        cmocka_unit_test(test_fx_normalisation),
        cmocka_unit_test(test_fx_slerp_extremes),
        cmocka_unit_test(test_fx_exact_endpoints),
        cmocka_unit_test(test_fx_lerp),
        cmocka_unit_test(test_fx_vs_f32),
        cmocka_unit_test(test_fx_spline_bezier_edges),
        cmocka_unit_test(test_fx_squad),
        /* float32 only */
        cmocka_unit_test(test_f32_nan),
    };
    return cmocka_run_group_tests_name("interp", tests, NULL, NULL);
}
