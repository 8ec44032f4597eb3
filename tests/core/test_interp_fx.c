/* qorient/interp_fx.h (fixed point, Q1.30): lerp, nlerp, slerp, key alignment, Bezier,
 * Shoemake spline and the Squad segment, checked against double-precision references written
 * here from the textbook formulas (not from the code under test), with fixed-seed random inputs
 * and edge tables.
 *
 * The operations the two cores share are tested by ONE body run against both: each body gets
 * a `core` (float32 interp.h or fixed interp_fx.h) through cmocka's prestate, whose adapters
 * take double quaternions, round them to what that core takes (float, or Q1.30 rounded to
 * nearest) and give the result back as double; the reference is always computed from the
 * rounded inputs the core actually received. Fixed-only behaviour (integer ranges, bit-exact
 * ends, Q16.16 spline parameter, saturation-free lerp, extreme magnitudes) and the agreement of
 * the fixed core with the float32 core follow. Every failure names the core, the case and its
 * inputs. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "qorient/fxconv.h"
#include "qorient/interp.h"
#include "qorient/interp_fx.h"
#include "qorient/quat.h"
#include "qorient/quat_fx.h"

#define PI 3.14159265358979323846
#define Q30 1073741824.0

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
static int dq_equal(dq a, dq b) { return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z; }

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
    double tol_rot;    /* slerp / nlerp / Bezier vs double, rad */
    double tol_norm;   /* | |q| - 1 | */
    double max_scale;  /* largest input norm the core can hold (non-unit input tests) */
    dq (*q_in)(dq q);            /* the input as the core receives it */
    double (*t_in)(double t);    /* t as the core receives it */
    double (*s_in)(double s);    /* spline s as the core receives it */
    qo_status (*unit)(dq q, dq *out);   /* the core's own normalisation */
    qo_status (*slerp)(dq a, dq b, double t, dq *out);
    qo_status (*nlerp)(dq a, dq b, double t, dq *out);
    qo_status (*bezier)(const dq *c, size_t n, double t, dq *out);
    qo_status (*spline_controls)(const dq *k, size_t n, dq *a, dq *b);
    qo_status (*spline_eval)(const dq *k, const dq *a, const dq *b, size_t n, double s,
                             dq *out);
    qo_status (*squad_controls)(const dq *k, size_t n, dq *s);
    qo_status (*squad)(dq q0, dq s0, dq s1, dq q1, double t, dq *out);
} core;

/* float32 adapters */
static dq f_q_in(dq q) { return dq_from_f(f_from(q)); }
static double f_t_in(double t) { return (double)(float)t; }
static qo_status f_unit(dq q, dq *out)
{
    qo_quat_f32 o;
    qo_status st = qo_quat_normalize_f32(f_from(q), &o);
    *out = dq_from_f(o);
    return st;
}
static qo_status f_slerp(dq a, dq b, double t, dq *out)
{
    qo_quat_f32 o;
    qo_status st = qo_quat_slerp_f32(f_from(a), f_from(b), (float)t, &o);
    *out = dq_from_f(o);
    return st;
}
static qo_status f_nlerp(dq a, dq b, double t, dq *out)
{
    qo_quat_f32 o;
    qo_status st = qo_quat_nlerp_f32(f_from(a), f_from(b), (float)t, &o);
    *out = dq_from_f(o);
    return st;
}
static qo_status f_bezier(const dq *c, size_t n, double t, dq *out)
{
    qo_quat_f32 fc[QO_BEZIER_MAX_POINTS + 1], o;
    size_t i;
    qo_status st;
    for (i = 0; i < n; i++) fc[i] = f_from(c[i]);
    st = qo_quat_bezier_f32(fc, n, (float)t, &o);
    *out = dq_from_f(o);
    return st;
}
static qo_status f_spline_controls(const dq *k, size_t n, dq *a, dq *b)
{
    qo_quat_f32 fk[MAXK], fa[MAXK], fb[MAXK];
    size_t i;
    qo_status st;
    memset(fk, 0, sizeof fk);
    for (i = 0; i < n; i++) fk[i] = f_from(k[i]);
    st = qo_quat_spline_controls_f32(fk, n, fa, fb);
    for (i = 0; i < n; i++) { a[i] = dq_from_f(fa[i]); b[i] = dq_from_f(fb[i]); }
    return st;
}
static qo_status f_spline_eval(const dq *k, const dq *a, const dq *b, size_t n, double s,
                               dq *out)
{
    qo_quat_f32 fk[MAXK], fa[MAXK], fb[MAXK], o;
    size_t i;
    qo_status st;
    for (i = 0; i < n; i++) { fk[i] = f_from(k[i]); fa[i] = f_from(a[i]); fb[i] = f_from(b[i]); }
    st = qo_quat_spline_eval_f32(fk, fa, fb, n, (float)s, &o);
    *out = dq_from_f(o);
    return st;
}

static qo_status f_squad_controls(const dq *k, size_t n, dq *s)
{
    qo_quat_f32 fk[MAXK], fs[MAXK];
    size_t i;
    qo_status st;
    memset(fk, 0, sizeof fk);
    for (i = 0; i < n; i++) fk[i] = f_from(k[i]);
    st = qo_quat_squad_controls_f32(fk, n, fs);
    for (i = 0; i < n; i++) s[i] = dq_from_f(fs[i]);
    return st;
}
static qo_status f_squad(dq q0, dq s0, dq s1, dq q1, double t, dq *out)
{
    qo_quat_f32 o;
    qo_status st = qo_quat_squad_f32(f_from(q0), f_from(s0), f_from(s1), f_from(q1), (float)t,
                                     &o);
    *out = dq_from_f(o);
    return st;
}

/* fixed-point adapters */
static dq x_q_in(dq q) { return dq_from_x(x_from(q)); }
static double x_t_in(double t) { return fx_from_d(t, Q30) / Q30; }
static double x_s_in(double s) { return fx_from_d(s, 65536.0) / 65536.0; }
static qo_status x_unit(dq q, dq *out)
{
    qo_quat_q30 k = x_from(q), o;
    qo_status st = qo_quat_align_keys_q30(&k, 1, &o);
    *out = dq_from_x(o);
    return st;
}
/* A two-point Q1.30 interpolation (slerp and its fast tier) on double inputs. */
typedef qo_status (*x_interp_fn)(qo_quat_q30, qo_quat_q30, qo_q30, qo_quat_q30 *);
static qo_status x_interp(x_interp_fn f, dq a, dq b, double t, dq *out)
{
    qo_quat_q30 o;
    qo_status st = f(x_from(a), x_from(b), fx_from_d(t, Q30), &o);
    *out = dq_from_x(o);
    return st;
}
static qo_status x_slerp(dq a, dq b, double t, dq *out)
{
    return x_interp(qo_quat_slerp_q30, a, b, t, out);
}
/* The fast tier: its own normalisation (qo_quat_normalize_fast_q30) and slerp. */
static qo_status x_unit_fast(dq q, dq *out)
{
    qo_quat_q30 o;
    qo_status st = qo_quat_normalize_fast_q30(x_from(q), &o);
    *out = dq_from_x(o);
    return st;
}
static qo_status x_slerp_fast(dq a, dq b, double t, dq *out)
{
    return x_interp(qo_quat_slerp_fast_q30, a, b, t, out);
}
static qo_status x_nlerp(dq a, dq b, double t, dq *out)
{
    qo_quat_q30 o;
    qo_status st = qo_quat_nlerp_q30(x_from(a), x_from(b), fx_from_d(t, Q30), &o);
    *out = dq_from_x(o);
    return st;
}
static qo_status x_bezier(const dq *c, size_t n, double t, dq *out)
{
    qo_quat_q30 xc[QO_BEZIER_MAX_POINTS + 1], o;
    size_t i;
    qo_status st;
    for (i = 0; i < n; i++) xc[i] = x_from(c[i]);
    st = qo_quat_bezier_q30(xc, n, fx_from_d(t, Q30), &o);
    *out = dq_from_x(o);
    return st;
}
static qo_status x_spline_controls(const dq *k, size_t n, dq *a, dq *b)
{
    qo_quat_q30 xk[MAXK], xa[MAXK], xb[MAXK];
    size_t i;
    qo_status st;
    memset(xk, 0, sizeof xk);
    for (i = 0; i < n; i++) xk[i] = x_from(k[i]);
    st = qo_quat_spline_controls_q30(xk, n, xa, xb);
    for (i = 0; i < n; i++) { a[i] = dq_from_x(xa[i]); b[i] = dq_from_x(xb[i]); }
    return st;
}
static qo_status x_spline_eval(const dq *k, const dq *a, const dq *b, size_t n, double s,
                               dq *out)
{
    qo_quat_q30 xk[MAXK], xa[MAXK], xb[MAXK], o;
    size_t i;
    qo_status st;
    for (i = 0; i < n; i++) { xk[i] = x_from(k[i]); xa[i] = x_from(a[i]); xb[i] = x_from(b[i]); }
    st = qo_quat_spline_eval_q30(xk, xa, xb, n, fx_from_d(s, 65536.0), &o);
    *out = dq_from_x(o);
    return st;
}

static qo_status x_squad_controls(const dq *k, size_t n, dq *s)
{
    qo_quat_q30 xk[MAXK], xs[MAXK];
    size_t i;
    qo_status st;
    memset(xk, 0, sizeof xk);
    for (i = 0; i < n; i++) xk[i] = x_from(k[i]);
    st = qo_quat_squad_controls_q30(xk, n, xs);
    for (i = 0; i < n; i++) s[i] = dq_from_x(xs[i]);
    return st;
}
static qo_status x_squad(dq q0, dq s0, dq s1, dq q1, double t, dq *out)
{
    qo_quat_q30 o;
    qo_status st = qo_quat_squad_q30(x_from(q0), x_from(s0), x_from(s1), x_from(q1),
                                     fx_from_d(t, Q30), &o);
    *out = dq_from_x(o);
    return st;
}

/* Tolerances: float32 as test_interp.c; fixed point measured by bench/accuracy_interp_fx.c at
 * 5e-9 rad (slerp) and 1e-9 (norm), checked here with a margin. */
static const core CORE_F32 = {
    "float32", 1e-6, 1e-6, 1e3, f_q_in, f_t_in, f_t_in, f_unit, f_slerp, f_nlerp, f_bezier,
    f_spline_controls, f_spline_eval, f_squad_controls, f_squad
};
static const core CORE_Q30 = {
    "q30", 3e-8, 3e-9, 1.99, x_q_in, x_t_in, x_s_in, x_unit, x_slerp, x_nlerp, x_bezier,
    x_spline_controls, x_spline_eval, x_squad_controls, x_squad
};
/* The fast tier (slerp tests only): documented 5e-8 rad; its unit is normalize_fast's
 * (16 LSB, 1.5e-8 of norm). */
static const core CORE_Q30_FAST = {
    "q30 fast", 5e-8, 3e-8, 1.99, x_q_in, x_t_in, x_s_in, x_unit_fast, x_slerp_fast, x_nlerp,
    x_bezier, x_spline_controls, x_spline_eval, x_squad_controls, x_squad
};

/* ---- check helper ----------------------------------------------------------------------- */
#define CHECK(cond, ...) do { if (!(cond)) { fail_msg(__VA_ARGS__); } } while (0)
#define QF(q) (q).w, (q).x, (q).y, (q).z
#define QFMT "(%.12g %.12g %.12g %.12g)"
#define CORE(state) ((const core *)*(state))

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
    const core *c = CORE(state);
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
    const core *c = CORE(state);
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
    const core *c = CORE(state);
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
    const core *c = CORE(state);
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
    const core *c = CORE(state);
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
    const core *c = CORE(state);
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
    const core *c = CORE(state);
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
static void test_slerp_nlerp_errors(void **state)
{
    const core *c = CORE(state);
    const dq id = { 1, 0, 0, 0 }, zero = { 0, 0, 0, 0 };
    const double bad_t[] = { -0.25, -1e-6, 1.0 + 1e-6, 1.5 };
    dq a, b, ua, out;
    size_t i;
    rng_seed(0xE7707ull);
    a = c->q_in(dq_scale(rand_unit(), 1.5));
    b = c->q_in(rand_unit());
    assert_int_equal(c->unit(a, &ua), QO_OK);
    assert_int_equal(c->slerp(a, zero, 0.5, &out), QO_E_DEGENERATE);
    CHECK(dq_equal(out, id), "%s slerp(a, 0): identity", c->name);
    assert_int_equal(c->slerp(zero, b, 0.5, &out), QO_E_DEGENERATE);
    CHECK(dq_equal(out, id), "%s slerp(0, b): identity", c->name);
    assert_int_equal(c->nlerp(zero, zero, 0.0, &out), QO_E_DEGENERATE);
    CHECK(dq_equal(out, id), "%s nlerp(0, 0): identity", c->name);
    assert_int_equal(c->unit(zero, &out), QO_E_DEGENERATE);
    for (i = 0; i < sizeof bad_t / sizeof bad_t[0]; i++) {
        assert_int_equal(c->slerp(a, b, bad_t[i], &out), QO_E_RANGE);
        CHECK(dq_equal(out, ua), "%s slerp t=%g: out must be unit a", c->name, bad_t[i]);
        assert_int_equal(c->nlerp(a, b, bad_t[i], &out), QO_E_RANGE);
        CHECK(dq_equal(out, ua), "%s nlerp t=%g: out must be unit a", c->name, bad_t[i]);
    }
}

/* ---- nlerp, both cores ------------------------------------------------------------------ */

static void test_nlerp(void **state)
{
    const core *c = CORE(state);
    int i;
    rng_seed(0x41E4Bull);
    for (i = 0; i < 1000; i++) {
        dq a = c->q_in(dq_scale(rand_unit(), rng_range(0.1, 1.9))), b = c->q_in(rand_unit());
        double t = rng_u(), it = c->t_in(t);
        dq ua = dq_unit(a), ub = dq_unit(b), ref, out, out2;
        if (dq_dot_exact(ua, ub) < 0) ub = dq_neg(ub); /* shortest way */
        ref = dq_unit(dq_add(dq_scale(ua, 1.0 - it), dq_scale(ub, it)));
        assert_int_equal(c->nlerp(a, b, t, &out), QO_OK);
        CHECK(dist4(ref, out) <= c->tol_rot && norm_dev(out) <= c->tol_norm,
              "%s nlerp a=" QFMT " b=" QFMT " t=%g out=" QFMT, c->name, QF(a), QF(b), t, QF(out));
        assert_int_equal(c->nlerp(a, dq_neg(b), t, &out2), QO_OK);
        CHECK(dist4(out, out2) <= c->tol_rot, "%s nlerp -b a=" QFMT " b=" QFMT " t=%g", c->name,
              QF(a), QF(b), t);
    }
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
    const core *c = CORE(state);
    dq cp[QO_BEZIER_MAX_POINTS + 1], out, o2, u0, un;
    int i, k;
    size_t n;
    rng_seed(0xBE21E4ull);
    for (i = 0; i < 300; i++) {
        dq p = rand_unit();
        n = 2 + (size_t)(i % (QO_BEZIER_MAX_POINTS - 1));
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
        assert_int_equal(c->unit(cp[0], &u0), QO_OK);
        assert_int_equal(c->unit(cp[n - 1], &un), QO_OK);
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
    }
    /* errors */
    for (k = 0; k <= QO_BEZIER_MAX_POINTS; k++) cp[k] = c->q_in(rand_unit());
    assert_int_equal(c->bezier(cp, QO_BEZIER_MAX_POINTS + 1, 0.5, &out), QO_E_CAPACITY);
    assert_int_equal(c->bezier(cp, QO_BEZIER_MAX_POINTS, 0.5, &out), QO_OK);
    assert_int_equal(c->bezier(cp, 1, 0.5, &out), QO_E_TOO_FEW);
    assert_int_equal(c->bezier(cp, 3, -0.5, &out), QO_E_RANGE);
    assert_int_equal(c->unit(cp[0], &u0), QO_OK);
    CHECK(dq_equal(out, u0), "%s bezier t out of range: unit ctrl[0]", c->name);
    cp[1].w = cp[1].x = cp[1].y = cp[1].z = 0.0;
    assert_int_equal(c->bezier(cp, 3, 0.5, &out), QO_E_DEGENERATE);
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

static void test_spline_vs_double_and_through_keys(void **state)
{
    const core *c = CORE(state);
    dq k[MAXK], a[MAXK], b[MAXK], q[MAXK], da[MAXK], db[MAXK], out;
    int it, j;
    size_t n, i;
    /* control points: float32 2e-6 as test_interp.c; fixed 10x its slerp tolerance */
    double tol_ctrl = (c == &CORE_F32) ? 2e-6 : 10 * c->tol_rot;
    rng_seed(0x5B11E5ull);
    for (it = 0; it < 120; it++) {
        n = 2 + (size_t)(it % (MAXK - 1));
        rand_keys(c, k, n, it % 2 ? 1.5 : 3.0);
        d_align(k, n, q);
        d_spline_controls(q, n, da, db);
        assert_int_equal(c->spline_controls(k, n, a, b), QO_OK);
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
    const core *c = CORE(state);
    dq k[MAXK], a[MAXK], b[MAXK], q[MAXK], da[MAXK], db[MAXK], f[5], g[5], dref[5];
    const double h = 1.0 / 64;
    int it, j;
    size_t n, i;
    rng_seed(0xC1C1ull);
    for (it = 0; it < 30; it++) {
        n = 3 + (size_t)(it % (MAXK - 2));
        rand_keys(c, k, n, 1.5);
        d_align(k, n, q);
        d_spline_controls(q, n, da, db);
        assert_int_equal(c->spline_controls(k, n, a, b), QO_OK);
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
}

/* Flipping the sign of any keys (and scaling them) gives the same rotations everywhere. */
static void test_spline_sign_invariance(void **state)
{
    const core *c = CORE(state);
    dq k[MAXK], k2[MAXK], a[MAXK], b[MAXK], a2[MAXK], b2[MAXK], o1, o2, o3;
    int it, j;
    size_t n, i;
    rng_seed(0x516Full);
    for (it = 0; it < 40; it++) {
        n = 2 + (size_t)(it % (MAXK - 1));
        rand_keys(c, k, n, 2.0);
        for (i = 0; i < n; i++) k2[i] = (rng_u() < 0.5) ? dq_neg(k[i]) : k[i];
        k2[0] = dq_neg(k[0]);
        assert_int_equal(c->spline_controls(k, n, a, b), QO_OK);
        assert_int_equal(c->spline_controls(k2, n, a2, b2), QO_OK);
        for (j = 0; j <= 30; j++) {
            double s = (double)j / 30.0 * (double)(n - 1);
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
    const core *c = CORE(state);
    const dq swing[3] = { { 1, 0, 0, 0 }, { 0, 0, 1, 0 }, { 1, 0, 0, 0 } };
    dq k[5], a[5], b[5], base, step, out;
    double tol = (c == &CORE_F32) ? 2e-6 : 10 * c->tol_rot;
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
    const core *c = CORE(state);
    const dq id = { 1, 0, 0, 0 }, zero = { 0, 0, 0, 0 };
    dq k[MAXK], s[MAXK], q[MAXK], ds[MAXK], out, o2, u;
    /* inner points: float32 2e-6 as test_interp.c; fixed 10x its slerp tolerance */
    double tol_ctrl = (c == &CORE_F32) ? 2e-6 : 10 * c->tol_rot;
    int it, j;
    size_t n, i;
    rng_seed(0x50AAull);
    for (it = 0; it < 100; it++) {
        n = 2 + (size_t)(it % (MAXK - 1));
        rand_keys(c, k, n, 1.5);
        d_align(k, n, q);
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
                assert_int_equal(c->squad(dq_neg(k[i]), s[i], dq_neg(s[i + 1]), k[i + 1], t,
                                          &o2), QO_OK);
                CHECK(rot_err(o2, out) <= c->tol_rot, "%s squad signs t=%g", c->name, t);
            }
        }
    }
    assert_int_equal(c->unit(k[0], &u), QO_OK);
    assert_int_equal(c->squad(k[0], s[0], s[1], k[1], 1.5, &out), QO_E_RANGE);
    CHECK(dq_equal(out, u), "%s squad t out of range: unit q0", c->name);
    assert_int_equal(c->squad(k[0], zero, s[1], k[1], 0.5, &out), QO_E_DEGENERATE);
    CHECK(dq_equal(out, id), "%s squad zero point: identity", c->name);
    assert_int_equal(c->squad_controls(k, 1, s), QO_E_TOO_FEW);
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
    assert_int_equal(qo_quat_align_keys_q30(&q, 1, &u), QO_OK);
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
                check_slerp_case(&CORE_Q30, name, dq_from_x(ex[i]), dq_from_x(ex[j]),
                                 ts[k] / Q30);
            }
            for (k = 0; k < sizeof bad_t / sizeof bad_t[0]; k++) {
                qo_quat_q30 out;
                assert_int_equal(qo_quat_slerp_q30(ex[i], ex[j], bad_t[k], &out), QO_E_RANGE);
                CHECK(x_equal(out, xu(ex[i])), "slerp t=%d: out must be unit a",
                      (int)bad_t[k]);
                assert_int_equal(qo_quat_nlerp_q30(ex[i], ex[j], bad_t[k], &out), QO_E_RANGE);
                assert_int_equal(qo_quat_lerp_q30(ex[i], ex[j], bad_t[k], &out), QO_E_RANGE);
                CHECK(x_equal(out, ex[i]), "lerp t=%d: out must be a", (int)bad_t[k]);
            }
        }
    }
    {
        qo_quat_q30 out;
        assert_int_equal(qo_quat_slerp_q30(ex[0], ex[1], 0, NULL), QO_E_NULL);
        assert_int_equal(qo_quat_nlerp_q30(ex[0], ex[1], 0, NULL), QO_E_NULL);
        assert_int_equal(qo_quat_lerp_q30(ex[0], ex[1], 0, NULL), QO_E_NULL);
        assert_int_equal(qo_quat_slerp_q30(ZERO_X, ZERO_X, -1, &out), QO_E_DEGENERATE);
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
        assert_int_equal(qo_quat_slerp_q30(a, b, 0, &o), QO_OK);
        CHECK(x_equal(o, ua), "slerp t=0 a=" XFMT, XF(a));
        assert_int_equal(qo_quat_slerp_q30(a, b, QO_Q30_ONE, &o), QO_OK);
        CHECK(x_equal(o, ub), "slerp t=1 a=" XFMT " b=" XFMT, XF(a), XF(b));
        assert_int_equal(qo_quat_nlerp_q30(a, b, 0, &o), QO_OK);
        CHECK(x_equal(o, ua), "nlerp t=0 a=" XFMT, XF(a));
        assert_int_equal(qo_quat_nlerp_q30(a, b, QO_Q30_ONE, &o), QO_OK);
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
        assert_int_equal(qo_quat_lerp_q30(a, b, t, &out), QO_OK);
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
        assert_int_equal(qo_quat_lerp_q30(a, b, 0, &out), QO_OK);
        CHECK(x_equal(out, a), "lerp t=0 a=" XFMT, XF(a));
        assert_int_equal(qo_quat_lerp_q30(a, b, QO_Q30_ONE, &out), QO_OK);
        CHECK(x_equal(out, b), "lerp t=1 b=" XFMT, XF(b));
    }
    /* q and -q: no flip, the midpoint is zero; zero inputs are plain arithmetic */
    {
        qo_quat_q30 q = x_from(rand_unit());
        assert_int_equal(qo_quat_lerp_q30(q, x_neg(q), QO_Q30_ONE / 2, &out), QO_OK);
        assert_true(x_equal(out, ZERO_X));
        assert_int_equal(qo_quat_lerp_q30(ZERO_X, q, QO_Q30_ONE / 2, &out), QO_OK);
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
        xa = qo_quat_q30_from_f32(fa);
        xb = qo_quat_q30_from_f32(fb);
        assert_int_equal(qo_quat_slerp_f32(fa, fb, t, &fo), QO_OK);
        assert_int_equal(qo_quat_slerp_q30(xa, xb, qo_q30_from_f32(t), &xo), QO_OK);
        assert_int_equal(qo_quat_nlerp_f32(fa, fb, t, &fn), QO_OK);
        assert_int_equal(qo_quat_nlerp_q30(xa, xb, qo_q30_from_f32(t), &xn), QO_OK);
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
            xk[j] = qo_quat_q30_from_f32(fk[j]);
        }
        assert_int_equal(qo_quat_spline_controls_f32(fk, n, fa, fb), QO_OK);
        assert_int_equal(qo_quat_spline_controls_q30(xk, n, xa, xb), QO_OK);
        for (j = 0; j <= 4 * (n - 1); j++) { /* s = j/4: exact in float and Q16.16 */
            double e;
            assert_int_equal(qo_quat_spline_eval_f32(fk, fa, fb, n, (float)j / 4.0f, &fo), QO_OK);
            assert_int_equal(qo_quat_spline_eval_q30(xk, xa, xb, n, (qo_q16)(j << 14), &xo),
                             QO_OK);
            e = dist4(dq_from_f(fo), dq_from_x(xo));
            CHECK(e <= 3e-6, "fixed vs float32 spline n=%u s=%g: %.3g", (unsigned)n,
                  (double)j / 4.0, e);
        }
    }
}

/* Key alignment: signs, in place, errors. */
static void test_fx_align_keys(void **state)
{
    qo_quat_q30 k[6], o[6];
    dq prev;
    int i;
    (void)state;
    rng_seed(0xA11F30ull);
    prev = rand_unit();
    for (i = 0; i < 6; i++) {
        prev = dq_mul(prev, rand_axis_rot(rng_range(0.1, 3.0)));
        k[i] = x_from(dq_scale(i % 2 ? dq_neg(prev) : prev, 0.3 + 0.3 * i));
    }
    assert_int_equal(qo_quat_align_keys_q30(k, 6, o), QO_OK);
    for (i = 1; i < 6; i++)
        CHECK(x_dot(o[i - 1], o[i]) >= 0 && rot_err(dq_from_x(o[i]), dq_from_x(k[i])) <= 1e-8 &&
              norm_dev(dq_from_x(o[i])) <= CORE_Q30.tol_norm, "aligned key %d", i);
    assert_int_equal(qo_quat_align_keys_q30(k, 6, k), QO_OK);
    for (i = 0; i < 6; i++) CHECK(x_equal(k[i], o[i]), "in-place key %d", i);
    assert_int_equal(qo_quat_align_keys_q30(k, 0, o), QO_E_TOO_FEW);
    assert_int_equal(qo_quat_align_keys_q30(NULL, 3, o), QO_E_NULL);
    for (i = 0; i < 3; i++) assert_true(x_equal(o[i], ID_X));
    k[2] = ZERO_X;
    assert_int_equal(qo_quat_align_keys_q30(k, 6, o), QO_E_DEGENERATE);
    for (i = 0; i < 6; i++) assert_true(x_equal(o[i], ID_X));
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
    rand_keys(&CORE_Q30, dk, 5, 2.5);
    for (i = 0; i < 5; i++) k[i] = x_from(dk[i]);
    assert_int_equal(qo_quat_align_keys_q30(k, 5, al), QO_OK);
    assert_int_equal(qo_quat_spline_controls_q30(k, 5, a, b), QO_OK);
    assert_true(x_equal(b[0], al[0]) && x_equal(a[4], al[4]));
    for (i = 0; i < 5; i++) {
        assert_int_equal(qo_quat_spline_eval_q30(k, a, b, 5, (qo_q16)(i << 16), &out), QO_OK);
        CHECK(x_equal(out, al[i]), "spline at key %u must be the aligned key exactly",
              (unsigned)i);
    }
    assert_int_equal(qo_quat_spline_eval_q30(k, a, b, 5, -1, &out), QO_E_RANGE);
    assert_true(x_equal(out, xu(k[0])));
    assert_int_equal(qo_quat_spline_eval_q30(k, a, b, 5, (4 << 16) + 1, &out), QO_E_RANGE);
    assert_true(x_equal(out, xu(k[4])));
    assert_int_equal(qo_quat_spline_eval_q30(k, a, b, 5, INT32_MIN, &out), QO_E_RANGE);
    assert_int_equal(qo_quat_spline_eval_q30(k, a, b, 5, INT32_MAX, &out), QO_E_RANGE);
    assert_int_equal(qo_quat_spline_eval_q30(k, a, b, 1, 0, &out), QO_E_TOO_FEW);
    assert_true(x_equal(out, ID_X));
    assert_int_equal(qo_quat_spline_eval_q30(k, NULL, b, 5, 0, &out), QO_E_NULL);
    assert_true(x_equal(out, ID_X));
    assert_int_equal(qo_quat_spline_eval_q30(k, a, b, 5, 0, NULL), QO_E_NULL);
    assert_int_equal(qo_quat_spline_controls_q30(k, 1, a, b), QO_E_TOO_FEW);
    assert_true(x_equal(a[0], ID_X) && x_equal(b[0], ID_X));
    assert_int_equal(qo_quat_spline_controls_q30(NULL, 5, a, b), QO_E_NULL);
    for (i = 0; i < 5; i++) assert_true(x_equal(a[i], ID_X) && x_equal(b[i], ID_X));
    assert_int_equal(qo_quat_spline_controls_q30(k, 5, a, b), QO_OK);
    k[1] = ZERO_X;
    assert_int_equal(qo_quat_spline_eval_q30(k, a, b, 5, 1 << 15, &out), QO_E_DEGENERATE);
    assert_true(x_equal(out, ID_X));
    assert_int_equal(qo_quat_spline_eval_q30(k, a, b, 5, 3 << 16, &out), QO_OK);
    assert_int_equal(qo_quat_spline_controls_q30(k, 5, a, b), QO_E_DEGENERATE);
    for (i = 0; i < 5; i++) assert_true(x_equal(a[i], ID_X) && x_equal(b[i], ID_X));
    /* Bezier */
    k[1] = x_from(rand_unit());
    assert_int_equal(qo_quat_bezier3_q30(k[0], k[1], k[2], k[3], QO_Q30_ONE / 3, &out), QO_OK);
    assert_int_equal(qo_quat_bezier_q30(k, 4, QO_Q30_ONE / 3, &o2), QO_OK);
    assert_true(x_equal(out, o2));
    assert_int_equal(qo_quat_bezier_q30(NULL, 3, 0, &out), QO_E_NULL);
    assert_true(x_equal(out, ID_X));
    assert_int_equal(qo_quat_bezier_q30(k, 3, 0, NULL), QO_E_NULL);
    assert_int_equal(qo_quat_bezier_q30(k, 3, QO_Q30_ONE + 1, &out), QO_E_RANGE);
    assert_true(x_equal(out, xu(k[0])));
    assert_int_equal(qo_quat_bezier_q30(k, 0, 0, &out), QO_E_TOO_FEW);
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
        assert_int_equal(qo_quat_squad_q30(x0, xs0, xs1, x1, 0, &out), QO_OK);
        assert_true(x_equal(out, xu(x0)));
        assert_int_equal(qo_quat_squad_q30(x0, xs0, xs1, x1, QO_Q30_ONE, &out), QO_OK);
        CHECK(dist4(dq_from_x(out), u1) <= 1e-9, "squad t=1 it=%d", it);
        for (j = 1; j < 10; j++) {
            qo_q30 t = (qo_q30)(QO_Q30_ONE / 10 * j);
            double tt = t / Q30;
            dq x = dq_unit(d_slerp_raw(u0, u1, tt)), y = dq_unit(d_slerp_raw(v0, v1, tt));
            dq ref = dq_unit(d_slerp_raw(x, y, 2 * tt * (1 - tt)));
            assert_int_equal(qo_quat_squad_q30(x0, xs0, xs1, x1, t, &out), QO_OK);
            CHECK(dist4(ref, dq_from_x(out)) <= 2 * CORE_Q30.tol_rot &&
                  norm_dev(dq_from_x(out)) <= CORE_Q30.tol_norm, "squad it=%d t=%g: %.3g", it,
                  tt, dist4(ref, dq_from_x(out)));
            assert_int_equal(qo_quat_squad_q30(x_neg(x0), x_neg(xs0), xs1, x_neg(x1), t, &o2),
                             QO_OK);
            CHECK(rot_err(dq_from_x(o2), dq_from_x(out)) <= CORE_Q30.tol_rot,
                  "squad signs it=%d t=%g", it, tt);
        }
    }
    {
        qo_quat_q30 q = x_from(rand_unit());
        assert_int_equal(qo_quat_squad_q30(q, q, q, q, QO_Q30_ONE + 1, &out), QO_E_RANGE);
        assert_true(x_equal(out, xu(q)));
        assert_int_equal(qo_quat_squad_q30(q, ZERO_X, q, q, QO_Q30_ONE / 2, &out),
                         QO_E_DEGENERATE);
        assert_true(x_equal(out, ID_X));
        assert_int_equal(qo_quat_squad_q30(q, q, q, q, 0, NULL), QO_E_NULL);
    }
}

#define BOTH(fn) cmocka_unit_test_prestate(fn, (void *)&CORE_F32), \
                 cmocka_unit_test_prestate(fn, (void *)&CORE_Q30)
#define FAST(fn) cmocka_unit_test_prestate(fn, (void *)&CORE_Q30_FAST)

int main(void)
{
    const struct CMUnitTest tests[] = {
        BOTH(test_slerp_random_vs_double),
        BOTH(test_slerp_edge_table),
        BOTH(test_slerp_same_rotation_opposite_sign),
        BOTH(test_slerp_exact_180),
        BOTH(test_slerp_nearly_180_ambiguous),
        BOTH(test_slerp_exact_endpoints),
        BOTH(test_slerp_constant_rate),
        FAST(test_slerp_random_vs_double),
        FAST(test_slerp_edge_table),
        FAST(test_slerp_same_rotation_opposite_sign),
        FAST(test_slerp_exact_180),
        FAST(test_slerp_nearly_180_ambiguous),
        FAST(test_slerp_exact_endpoints),
        FAST(test_slerp_constant_rate),
        BOTH(test_slerp_nlerp_errors),
        BOTH(test_nlerp),
        BOTH(test_bezier),
        BOTH(test_spline_vs_double_and_through_keys),
        BOTH(test_spline_c1),
        BOTH(test_spline_sign_invariance),
        BOTH(test_spline_end_rule_and_swing_back),
        BOTH(test_squad),
        cmocka_unit_test(test_fx_normalisation),
        cmocka_unit_test(test_fx_slerp_extremes),
        cmocka_unit_test(test_fx_exact_endpoints),
        cmocka_unit_test(test_fx_lerp),
        cmocka_unit_test(test_fx_vs_f32),
        cmocka_unit_test(test_fx_align_keys),
        cmocka_unit_test(test_fx_spline_bezier_edges),
        cmocka_unit_test(test_fx_squad),
    };
    return cmocka_run_group_tests_name("interp_fx", tests, NULL, NULL);
}
