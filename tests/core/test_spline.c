/* Keyframe splines (qorient/spline.h, qorient/spline_fx.h): a plan is made in float32
 * (qo_spline_init_f32, the one planner) and sampled by either core, float32
 * (qo_spline_sample_f32) or Q16.16 (qo_spline_sample_q16 on its qo_spline_export_q16 table).
 *
 * One body per behaviour both samplers have (docs/TESTING.md, "One body for both cores"):
 * each body gets a `core` through cmocka's prestate whose adapters take the plan, a time and
 * give back doubles; times and positions are rounded as the core receives them (float32, or
 * Q16.16 rounded to nearest and saturated) and the reference is computed from those rounded
 * values, each core judged with its own tolerance. The out-of-range time of each core goes
 * through one field, `big` (Inf in float32, a saturated time in Q16.16).
 *
 * Sections: the adapter table; the shared bodies (keys reproduced exactly, closed forms,
 * outside the keys and at the end, limits); fixed point only (the Q16.16 sampler against the
 * float32 sampler of the same plan within the bound of spline_fx.h, small-move precision,
 * ends / wrap / limits against float, conversion and sampling errors); float32 only
 * (continuity at joins, C2 / Catmull-Rom / Hermite / quintic against double-precision
 * references written here with dense Gaussian elimination, not the code's own formulas,
 * wrap, init edges, many joints, re-planning, overflow, NaN). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <math.h>
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <cmocka.h>

#define CORES_OWN_TABLE   /* the spline's table below: plans in slots, Q16.16 samples */
#include "common/cores.h"
#include "common/ref.h"
#include "qorient/spline.h"
#include "qorient/spline_fx.h"

#define MAXK 12   /* keys of the random plans (2 + trial % 11 at most) */
#define MAXN 4    /* joints of the random plans */
/* Coefficient storage of one plan, K + 3N + 6KN floats: the largest plan of the tests that use
 * it has 10 keys of 4 joints (262). The program also runs on the Cortex-M0 board (microbit,
 * 16 KB of RAM, stack included), so every buffer is sized to what the tests use. */
#define COEF_CAP 320

/* ---- deterministic PRNG ---- */
static uint64_t rng_state;
static uint64_t splitmix64(void) { return ref_splitmix64(&rng_state); } /* tests/common/ref.c */
static double urand(double lo, double hi)
{
    return lo + (hi - lo) * (double)(splitmix64() >> 11) * (1.0 / 9007199254740992.0);
}

/* ---- double references ---- */

/* Solves A x = b (n <= 16) by Gaussian elimination with partial pivoting. */
static void ref_solve(int n, double a[][MAXK], double *b, double *x)
{
    int i, j, k;
    for (k = 0; k < n; k++) {
        int piv = k;
        for (i = k + 1; i < n; i++)
            if (fabs(a[i][k]) > fabs(a[piv][k])) piv = i;
        if (piv != k) {
            double tmp;
            for (j = 0; j < n; j++) { tmp = a[k][j]; a[k][j] = a[piv][j]; a[piv][j] = tmp; }
            tmp = b[k]; b[k] = b[piv]; b[piv] = tmp;
        }
        for (i = k + 1; i < n; i++) {
            double f = a[i][k] / a[k][k];
            for (j = k; j < n; j++) a[i][j] -= f * a[k][j];
            b[i] -= f * b[k];
        }
    }
    for (i = n - 1; i >= 0; i--) {
        double s = b[i];
        for (j = i + 1; j < n; j++) s -= a[i][j] * x[j];
        x[i] = s / a[i][i];
    }
}

/* Power-basis coefficients c[0..5] in physical local time u of the polynomial of lowest
 * degree (deg = 3: p, v at both ends; deg = 5: p, v, a) matching the end conditions. */
static void ref_segment(int deg, double h, double p0, double v0, double a0, double p1, double v1,
                        double a1, double *c)
{
    double a[MAXK][MAXK], b[MAXK], x[MAXK];
    int n = deg + 1, i, row = 0;
    memset(a, 0, sizeof a);
    /* value, first and second derivative of u^i at u = 0 and u = h */
    for (i = 0; i < n; i++) a[row][i] = (i == 0) ? 1.0 : 0.0;
    b[row++] = p0;
    for (i = 0; i < n; i++) a[row][i] = (i == 1) ? 1.0 : 0.0;
    b[row++] = v0;
    if (deg == 5) {
        for (i = 0; i < n; i++) a[row][i] = (i == 2) ? 2.0 : 0.0;
        b[row++] = a0;
    }
    for (i = 0; i < n; i++) a[row][i] = pow(h, i);
    b[row++] = p1;
    for (i = 0; i < n; i++) a[row][i] = i >= 1 ? i * pow(h, i - 1) : 0.0;
    b[row++] = v1;
    if (deg == 5) {
        for (i = 0; i < n; i++) a[row][i] = i >= 2 ? i * (i - 1) * pow(h, i - 2) : 0.0;
        b[row++] = a1;
    }
    ref_solve(n, a, b, x);
    for (i = 0; i < 6; i++) c[i] = i < n ? x[i] : 0.0;
}

static void ref_eval(const double *c, double u, double *p, double *v, double *a)
{
    int i;
    *p = *v = *a = 0.0;
    for (i = 0; i < 6; i++) {
        *p += c[i] * pow(u, i);
        if (i >= 1) *v += i * c[i] * pow(u, i - 1);
        if (i >= 2) *a += i * (i - 1) * c[i] * pow(u, i - 2);
    }
}

/* Key accelerations of the interpolating C2 cubic spline: the dense K x K system in the
 * second derivatives (natural: zero at the ends; clamped: given end velocities). */
static void ref_c2_moments(int k, const double *t, const double *y, int natural, double v0,
                           double v1, double *m)
{
    double a[MAXK][MAXK], b[MAXK];
    int i;
    memset(a, 0, sizeof a);
    for (i = 1; i < k - 1; i++) {
        double h0 = t[i] - t[i - 1], h1 = t[i + 1] - t[i];
        a[i][i - 1] = h0 / 6.0;
        a[i][i] = (h0 + h1) / 3.0;
        a[i][i + 1] = h1 / 6.0;
        b[i] = (y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0;
    }
    if (natural) {
        a[0][0] = 1.0; b[0] = 0.0;
        a[k - 1][k - 1] = 1.0; b[k - 1] = 0.0;
    } else {
        double h = t[1] - t[0], hl = t[k - 1] - t[k - 2];
        a[0][0] = h / 3.0; a[0][1] = h / 6.0; b[0] = (y[1] - y[0]) / h - v0;
        a[k - 1][k - 2] = hl / 6.0; a[k - 1][k - 1] = hl / 3.0;
        b[k - 1] = v1 - (y[k - 1] - y[k - 2]) / hl;
    }
    ref_solve(k, a, b, m);
}

/* ---- helpers ---- */
typedef struct keys {
    int n, k;
    float t[MAXK], p[MAXK * MAXN], v[MAXK * MAXN], a[MAXK * MAXN];
} keys;

static void random_keys(keys *ks, int n, int k, double hmin, double hmax, double amp)
{
    int i, j;
    ks->n = n;
    ks->k = k;
    ks->t[0] = (float)urand(-1.0, 1.0);
    for (i = 1; i < k; i++) ks->t[i] = ks->t[i - 1] + (float)urand(hmin, hmax);
    for (i = 0; i < k; i++)
        for (j = 0; j < n; j++) {
            ks->p[i * n + j] = (float)urand(-amp, amp);
            ks->v[i * n + j] = (float)urand(-amp, amp);
            ks->a[i * n + j] = (float)urand(-amp, amp);
        }
}

static double keys_scale(const keys *ks)
{
    double m = 1.0;
    int i;
    for (i = 0; i < ks->k * ks->n; i++) {
        if (fabs(ks->p[i]) > m) m = fabs(ks->p[i]);
        if (fabs(ks->v[i]) > m) m = fabs(ks->v[i]);
        if (fabs(ks->a[i]) > m) m = fabs(ks->a[i]);
    }
    return m;
}

static double keys_hmin(const keys *ks)
{
    double h = 1e30;
    int i;
    for (i = 1; i < ks->k; i++)
        if ((double)ks->t[i] - ks->t[i - 1] < h) h = (double)ks->t[i] - ks->t[i - 1];
    return h;
}

/* ---- the fixture of the bodies: each states its key shape, profile and end; the keys, the
 * scales of the rounding budget and the settings come from here ---------------------------- */

/* The random key sets of a float32-only body against double: n joints, k0 + trial % kmod
 * keys, steps of hlo ... hhi s, values within +-amp (random_keys). */
typedef struct key_shape { int n, k0, kmod; double hlo, hhi, amp; } key_shape;
/* One trial of such a body: its number, its keys, the scales of its float32 rounding budget
 * (P: twice the largest key value, positions, velocities and accelerations; hmin: the
 * shortest segment, s) and the body's own state (ctx). */
typedef void (*trial_fn)(int trial, const keys *ks, double P, double hmin, void *ctx);

/* The loop of those bodies: seeds the generator, then draws `count` key sets of the shape and
 * hands each to fn, which draws anything else it needs right after its keys. */
static void run_trials(uint64_t seed, int count, const key_shape *shape, trial_fn fn, void *ctx)
{
    int trial;
    rng_state = seed;
    for (trial = 0; trial < count; trial++) {
        keys ks;
        random_keys(&ks, shape->n, shape->k0 + trial % shape->kmod, shape->hlo, shape->hhi,
                    shape->amp);
        fn(trial, &ks, keys_scale(&ks) * 2.0, keys_hmin(&ks), ctx);
    }
}

/* The default settings but for the profile and the end condition. */
static qo_spline_settings_f32 settings_for(qo_spline_profile prof, qo_spline_end end)
{
    qo_spline_settings_f32 set = qo_spline_settings_default;
    set.profile = prof;
    set.end = end;
    return set;
}

/* The end condition of variant e (0 clamped, 1 natural) of the bodies that run both. */
static qo_spline_end end_of(int e) { return e ? QO_SPLINE_END_NATURAL : QO_SPLINE_END_CLAMPED; }

static const char *prof_name(qo_spline_profile p)
{
    switch (p) {
    case QO_SPLINE_LINEAR: return "linear";
    case QO_SPLINE_CUBIC_HERMITE: return "hermite";
    case QO_SPLINE_CATMULL_ROM: return "catmull";
    case QO_SPLINE_CUBIC_C2: return "c2";
    case QO_SPLINE_QUINTIC: return "quintic";
    }
    return "?";
}

static float coef[COEF_CAP];

static qo_status plan(const keys *ks, qo_spline_settings_f32 *set, qo_spline_f32 *sp)
{
    if (set->profile == QO_SPLINE_CUBIC_HERMITE) set->key_vel = ks->v;
    return qo_spline_init_f32((size_t)ks->n, (size_t)ks->k, ks->t, ks->p, set, coef, COEF_CAP, sp);
}

static void sample(const qo_spline_f32 *sp, float t, float *p, float *v, float *a)
{
    qo_status st = qo_spline_sample_f32(sp, t, p, v, a, NULL);
    if (st != QO_OK) fail_msg("sample at t=%.9g: status %d", (double)t, (int)st);
}

/* sum |b_n| of segment k, joint j, read from the plan's documented storage layout (used
 * only to size a rounding tolerance) */
static double coef_sum(const qo_spline_f32 *sp, int k, int j)
{
    const float *b = sp->coef + sp->n_keys + 3 * sp->n_joints + 6 * ((size_t)k * sp->n_joints + j);
    double s = 0.0;
    int n;
    for (n = 0; n < 6; n++) s += fabs(b[n]);
    return s;
}

/* Tolerances of float32 against the double references: rounding budget in units of eps
 * relative to the key scale P and the shortest segment. */
static void check_close(const char *what, int trial, int j, double t, double got, double want,
                        double tol)
{
    if (!(fabs(got - want) <= tol))
        fail_msg("%s trial %d joint %d t=%.9g: got %.9g want %.9g (|diff| %.3g > tol %.3g)", what,
                 trial, j, t, got, want, fabs(got - want), tol);
}

static int seg_of(const keys *ks, double t)
{
    int i = 0;
    while (i + 2 < ks->k && t >= ks->t[i + 1]) i++;
    return i;
}


/* ---- the two samplers behind one interface ---------------------------------------------- */

/* Two plans at once (slot 0 and 1: a limited plan and its free twin). */
#define SLOTS 2
/* Q16.16 table words of one plan: 5K + 3N + 7KN, at most 375 here (11 keys, 4 joints) */
#define X_CAP 384
static qo_spline_f32 f_plans[SLOTS];
static qo_spline_table_q16 x_plans[SLOTS];
static int32_t x_tables[SLOTS][X_CAP];
/* the Q16.16 table of the fixed-only bodies (they do not use the adapters' slot 0 meanwhile) */
static int32_t *const table = x_tables[0];
/* a second plan's coefficients (limited and free plans; re-planning) */
static float coef2[COEF_CAP];

typedef struct core {
    const char *name;
    int fixed;
    double lsb;                 /* resolution of a value: 0 (float32) / 2^-16 (Q16.16) */
    double big;                 /* a time beyond the core's range (Inf / saturated) */
    double (*in)(double x);     /* a time or a position as the core receives it */
    qo_status (*use)(int slot, const qo_spline_f32 *sp);   /* the core's copy of a plan */
    /* samples the plan of a slot at t; NULL outputs are passed through */
    qo_status (*sample)(int slot, double t, double *p, double *v, double *a, int8_t *cl);
} core;

/* The sampler of one core (prefix P), written once: VT its value type, TO_T its time. */
#define DEFINE_SAMPLER(P, SFX, VT, TO_T, BACK)                                                \
    static qo_status P##_sample(int slot, double t, double *p, double *v, double *a,          \
                                int8_t *cl)                                                   \
    {                                                                                         \
        VT op[MAXN], ov[MAXN], oa[MAXN];                                                      \
        size_t j, n = P##_plans[slot].n_joints;                                               \
        qo_status st = qo_spline_sample_##SFX(&P##_plans[slot], TO_T(t), p ? op : NULL,       \
                                              v ? ov : NULL, a ? oa : NULL, cl);              \
        for (j = 0; j < n && j < MAXN; j++) {                                                 \
            if (p) p[j] = BACK(op[j]);                                                        \
            if (v) v[j] = BACK(ov[j]);                                                        \
            if (a) a[j] = BACK(oa[j]);                                                        \
        }                                                                                     \
        return st;                                                                            \
    }

static double f_in(double x) { return (double)(float)x; }
static float f_t(double t) { return (float)t; }
static double f_back(float x) { return (double)x; }
static qo_status f_use(int slot, const qo_spline_f32 *sp)
{
    f_plans[slot] = *sp;
    return QO_OK;
}
DEFINE_SAMPLER(f, f32, float, f_t, f_back)

static qo_q16 x_t(double t) { return ref_to_fixed(t, Q16); }
static double x_in(double x) { return x_t(x) / Q16; }
static double x_back(qo_q16 x) { return x / Q16; }
static qo_status x_use(int slot, const qo_spline_f32 *sp)
{
    return qo_spline_export_q16(sp, &x_plans[slot], x_tables[slot], X_CAP);
}
DEFINE_SAMPLER(x, q16, qo_q16, x_t, x_back)

static const core CORE_F32 = { "float32", 0, 0.0, 1e39, f_in, f_use, f_sample };
/* the fixed row (CORE_FX of common/cores.h's idiom) samples Q16.16 */
static const core CORE_FX = { "q16", 1, 1.0 / Q16, 1e39, x_in, x_use, x_sample };

/* A tolerance: float32's (its own rounding budget) or a number of Q16.16 LSB. */
static double tol(const core *c, double f32_tol, double lsbs)
{
    return c->fixed ? lsbs * c->lsb : f32_tol;
}

/* ---- both cores ------------------------------------------------------------------------- */

static const qo_spline_profile all_profiles[] = {
    QO_SPLINE_LINEAR, QO_SPLINE_CUBIC_HERMITE, QO_SPLINE_CATMULL_ROM, QO_SPLINE_CUBIC_C2,
    QO_SPLINE_QUINTIC
};
#define NPROF (sizeof all_profiles / sizeof all_profiles[0])

/* Every key is reproduced (the sample at the key time is the key as received: t == t_k gives
 * b0 == p_k), for every profile and both end conditions, including the last key: bit-exact in
 * float32, within 1 LSB in Q16.16 (b0 carries f extra bits, rounded once more: the bound of
 * spline_fx.h at s = 0, 0.5 + 0.5 * 2^-f). */
static void test_keys_interpolated_exactly(void **state)
{
    const core *c = *state;
    size_t pi;
    int trial, i, j, e, checked = 0, refused = 0;
    rng_state = 101;
    for (trial = 0; trial < 20; trial++) {
        keys ks;
        random_keys(&ks, 3, 2 + trial % 9, 0.05, 2.0, 50.0);
        /* key times the core holds exactly (Q16.16: multiples of 2^-16 s; float32 as drawn):
         * a key time moved by rounding moves the sample off the key by |v| 2^-17 */
        for (i = 0; i < ks.k; i++) ks.t[i] = (float)c->in(ks.t[i]);
        for (pi = 0; pi < NPROF; pi++)
            for (e = 0; e < 2; e++) {
                qo_spline_settings_f32 set = settings_for(all_profiles[pi], end_of(e));
                qo_spline_f32 sp;
                qo_status st;
                st = plan(&ks, &set, &sp);
                if (st == QO_OK) st = c->use(0, &sp);
                /* Q16.16 refuses a plan whose values do not fit (documented): counted */
                if (c->fixed && st == QO_E_OVERFLOW) {
                    refused++;
                    continue;
                }
                if (st != QO_OK) fail_msg("%s %s trial %d: init/export status %d", c->name,
                                          prof_name(set.profile), trial, (int)st);
                checked++;
                for (i = 0; i < ks.k; i++) {
                    double p[MAXN], v[MAXN], a[MAXN];
                    st = c->sample(0, c->in(ks.t[i]), p, v, a, NULL);
                    /* Q16.16: a velocity or acceleration beyond the format saturates and says
                     * so; the position is still valid (spline_fx.h) */
                    if (!(st == QO_OK || (c->fixed && st == QO_E_OVERFLOW)))
                        fail_msg("%s %s trial %d key %d: sample status %d", c->name,
                                 prof_name(set.profile), trial, i, (int)st);
                    for (j = 0; j < ks.n; j++)
                        if (!(fabs(p[j] - c->in(ks.p[i * ks.n + j])) <= tol(c, 0.0, 1.0)))
                            fail_msg("%s %s end %d trial %d key %d joint %d: %.9g != key %.9g",
                                     c->name, prof_name(set.profile), e, trial, i, j, p[j],
                                     c->in(ks.p[i * ks.n + j]));
                }
            }
    }
    print_message("%s: %d plans checked, %d refused by the Q16.16 export (overflow)\n",
                  c->name, checked, refused);
    assert_true(checked >= 100);
}

/* Linear: p0 + w (p1 - p0), slope (p1 - p0) / h, zero acceleration, against double on the key
 * times and positions as the core received them. */
static void test_linear_against_double(void **state)
{
    const core *c = *state;
    keys ks;
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    int i, j;
    rng_state = 606;
    random_keys(&ks, 3, 6, 0.1, 1.0, 10.0);
    set.profile = QO_SPLINE_LINEAR;
    assert_int_equal(plan(&ks, &set, &sp), QO_OK);
    assert_int_equal(c->use(0, &sp), QO_OK);
    for (i = 0; i < 100; i++) {
        double t = c->in(urand(ks.t[0], ks.t[ks.k - 1]));
        double p[MAXN], v[MAXN], a[MAXN], t0, h;
        int s = 0;
        while (s + 2 < ks.k && t >= c->in(ks.t[s + 1])) s++;
        t0 = c->in(ks.t[s]);
        h = c->in(ks.t[s + 1]) - t0;
        assert_int_equal(c->sample(0, t, p, v, a, NULL), QO_OK);
        for (j = 0; j < ks.n; j++) {
            double p0 = c->in(ks.p[s * ks.n + j]), p1 = c->in(ks.p[(s + 1) * ks.n + j]);
            double w = (t - t0) / h;
            char what[48];
            snprintf(what, sizeof what, "%s linear pos", c->name);
            check_close(what, i, j, t, p[j], p0 + w * (p1 - p0), tol(c, 32 * FLT_EPSILON * 20, 2));
            snprintf(what, sizeof what, "%s linear vel", c->name);
            check_close(what, i, j, t, v[j], (p1 - p0) / h, tol(c, 32 * FLT_EPSILON * 20 / 0.1, 8));
            assert_true(a[j] == 0.0);
        }
    }
}

/* Closed forms in double: linear interpolation, and the rest-to-rest quintic
 * p0 + d (10 s^3 - 15 s^4 + 6 s^5) with its derivatives (times and keys exact in both
 * formats). */
static void test_closed_form(void **state)
{
    const core *c = *state;
    const float t[2] = { 0.5f, 2.5f };
    const float p[2] = { -3.0f, 7.0f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    int prof, i;
    for (prof = 0; prof < 2; prof++) {
        set.profile = prof ? QO_SPLINE_QUINTIC : QO_SPLINE_LINEAR;
        assert_int_equal(qo_spline_init_f32(1, 2, t, p, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(c->use(0, &sp), QO_OK);
        for (i = 0; i <= 2000; i++) {
            double tt = (32768 + i * 65) / Q16, s = (tt - 0.5) / 2.0, d = 10.0, rp, rv, ra;
            double pq, vq, aq;
            if (prof) {
                rp = -3.0 + d * (10 * s * s * s - 15 * s * s * s * s + 6 * pow(s, 5));
                rv = d * (30 * s * s - 60 * s * s * s + 30 * pow(s, 4)) / 2.0;
                ra = d * (60 * s - 180 * s * s + 120 * s * s * s) / 4.0;
            } else {
                rp = -3.0 + d * s;
                rv = d / 2.0;
                ra = 0.0;
            }
            assert_int_equal(c->sample(0, tt, &pq, &vq, &aq, NULL), QO_OK);
            /* float32: a few ulp of the largest coefficient (d) and its derivative factors */
            if (fabs(pq - rp) > tol(c, 32 * FLT_EPSILON * d, 8) ||
                fabs(vq - rv) > tol(c, 32 * FLT_EPSILON * d * 5, 8) ||
                fabs(aq - ra) > tol(c, 32 * FLT_EPSILON * d * 20, 8))
                fail_msg("%s %s t=%.9g: (%.9g %.9g %.9g) vs double (%.9g %.9g %.9g)", c->name,
                         prof ? "quintic" : "linear", tt, pq, vq, aq, rp, rv, ra);
        }
    }
}

/* Before the first key: first key at rest; after the last: last key at rest; at the last
 * key: the end state of the last segment (a natural spline's non-zero end velocity). The
 * out-of-range times: -big / +big (float32 -Inf / +Inf: QO_E_NONFINITE; Q16.16 INT32_MIN /
 * INT32_MAX: before the start / after the end). */
static void test_outside_and_end(void **state)
{
    const core *c = *state;
    const float t[3] = { 1.0f, 2.0f, 4.0f };
    const float p[6] = { 0.0f, 5.0f, 1.0f, -2.0f, 3.0f, 3.0f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    double pos[2], vel[2], acc[2];
    set.end = QO_SPLINE_END_NATURAL;
    assert_int_equal(qo_spline_init_f32(2, 3, t, p, &set, coef, COEF_CAP, &sp), QO_OK);
    assert_int_equal(c->use(0, &sp), QO_OK);
    assert_int_equal(c->sample(0, 0.5, pos, vel, acc, NULL), QO_OK);
    assert_true(pos[0] == 0.0 && pos[1] == 5.0 && vel[0] == 0.0 && acc[1] == 0.0);
    assert_int_equal(c->sample(0, 9.0, pos, vel, acc, NULL), QO_OK);
    assert_true(pos[0] == 3.0 && pos[1] == 3.0 && vel[0] == 0.0 && acc[0] == 0.0);
    assert_int_equal(c->sample(0, 4.0, pos, vel, acc, NULL), QO_OK);
    assert_true(pos[0] == 3.0 && pos[1] == 3.0);
    assert_true(fabs(vel[0]) > 0.1); /* natural end: moving */
    assert_true(fabs(acc[0]) < tol(c, 1e-5, 4));
    /* optional outputs may be NULL */
    assert_int_equal(c->sample(0, 2.5, pos, NULL, NULL, NULL), QO_OK);
    /* -big: the first key held at rest in both cores */
    vel[0] = 7.0;
    assert_int_equal(c->sample(0, -c->big, pos, vel, acc, NULL), ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(pos[0] == 0.0 && pos[1] == 5.0 && vel[0] == 0.0);
    /* +big: float32 NONFINITE; Q16.16 after the end, the last key at rest */
    assert_int_equal(c->sample(0, c->big, pos, vel, acc, NULL), ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(!c->fixed || (pos[0] == 3.0 && pos[1] == 3.0 && vel[1] == 0.0 && acc[1] == 0.0));
}

/* Limits: samples stay inside, clamped[] is -1/+1 exactly when the core's own unlimited
 * sample is outside, and a clamped joint reports zero velocity and acceleration; an
 * unclamped joint is the unlimited sample. */
static void test_limits_clamp_and_report(void **state)
{
    const core *c = *state;
    keys ks;
    float lo[3] = { -4.0f, -INFINITY, -1.0f }, hi[3] = { 4.0f, 2.0f, INFINITY };
    int i, j, seen_lo = 0, seen_hi = 0;
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 lim, free_sp;
    rng_state = 707;
    random_keys(&ks, 3, 8, 0.1, 1.0, 10.0);
    set.profile = QO_SPLINE_QUINTIC;
    assert_int_equal(plan(&ks, &set, &free_sp), QO_OK);
    set.pos_min = lo;
    set.pos_max = hi;
    assert_int_equal(qo_spline_init_f32(3, (size_t)ks.k, ks.t, ks.p, &set, coef2, COEF_CAP, &lim),
                     QO_OK);
    assert_int_equal(c->use(0, &free_sp), QO_OK);
    assert_int_equal(c->use(1, &lim), QO_OK);
    for (i = 0; i < 400; i++) {
        double t = c->in(urand(ks.t[0] - 0.5, ks.t[ks.k - 1] + 0.5));
        double p[3], v[3], a[3], pf[3], vf[3], af[3];
        int8_t cl[3];
        assert_int_equal(c->sample(1, t, p, v, a, cl), QO_OK);
        assert_int_equal(c->sample(0, t, pf, vf, af, NULL), QO_OK);
        for (j = 0; j < 3; j++) {
            int8_t want = pf[j] < lo[j] ? -1 : pf[j] > hi[j] ? 1 : 0;
            if (cl[j] != want)
                fail_msg("%s t=%.9g joint %d: clamped %d, want %d (free %.9g in [%g, %g])",
                         c->name, t, j, cl[j], want, pf[j], (double)lo[j], (double)hi[j]);
            if (want) {
                assert_true(p[j] == (want < 0 ? lo[j] : hi[j]));
                assert_true(v[j] == 0.0 && a[j] == 0.0);
                if (want < 0) seen_lo = 1; else seen_hi = 1;
            } else {
                assert_true(p[j] == pf[j] && v[j] == vf[j] && a[j] == af[j]);
            }
        }
    }
    assert_true(seen_lo && seen_hi);
}

/* ---- fixed point only (Q16.16 sampler) ------------------------------------------------- */

static double lsb(double x) { return x * 65536.0; }

/* Fixed against float for every profile over random plans. exact_times: key times are
 * multiples of 2^-10 s (exact in Q16.16), else arbitrary floats (the key-time rounding term
 * of the bound applies, and samples within 2 LSB of a key skip the derivative orders the
 * profile does not keep continuous). Prints the worst differences in LSB. */
static void fixed_vs_float(int exact_times, uint64_t seed)
{
    size_t pi;
    int trial, i, j;
    double worst_p = 0, worst_v = 0, worst_a = 0;
    rng_state = seed;
    for (trial = 0; trial < 12; trial++) {
        float t[MAXK], p[MAXK * MAXN], v[MAXK * MAXN];
        int K = 2 + trial % 10, N = 4;
        t[0] = (float)urand(-2.0, 2.0);
        if (exact_times) t[0] = floorf(t[0] * 1024.0f) / 1024.0f;
        for (i = 1; i < K; i++) {
            t[i] = t[i - 1] + (float)urand(0.2, 1.0);
            if (exact_times) t[i] = floorf(t[i] * 1024.0f) / 1024.0f;
        }
        for (i = 0; i < K * N; i++) {
            p[i] = (float)urand(-20.0, 20.0);
            v[i] = (float)urand(-20.0, 20.0);
        }
        for (pi = 0; pi < NPROF; pi++) {
            qo_spline_settings_f32 set = settings_for(all_profiles[pi], end_of(trial & 1));
            qo_spline_f32 sp;
            qo_spline_table_q16 fx;
            int order;
            set.key_vel = v;
            assert_int_equal(qo_spline_init_f32((size_t)N, (size_t)K, t, p, &set, coef, COEF_CAP,
                                                &sp), QO_OK);
            assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_OK);
            order = set.profile == QO_SPLINE_LINEAR ? 0
                  : (set.profile == QO_SPLINE_CUBIC_C2 || set.profile == QO_SPLINE_QUINTIC) ? 2 : 1;
            for (i = 0; i < 300; i++) {
                qo_q16 tq = (qo_q16)lrint(urand(t[0] - 0.1, t[K - 1] + 0.1) * 65536.0);
                float tf = (float)tq / 65536.0f; /* exact: |tq| < 2^24 */
                float pf[MAXN], vf[MAXN], af[MAXN];
                qo_q16 pq[MAXN], vq[MAXN], aq[MAXN];
                size_t seg = 0;
                double h, near = 1e30;
                int k;
                assert_int_equal(qo_spline_sample_f32(&sp, tf, pf, vf, af, NULL), QO_OK);
                assert_int_equal(qo_spline_sample_q16(&fx, tq, pq, vq, aq, NULL), QO_OK);
                for (k = 0; k < K; k++) {
                    if (fabs((double)tf - t[k]) < near) near = fabs((double)tf - t[k]);
                    if (k + 1 < K && tf >= t[k]) seg = (size_t)k;
                }
                h = (double)t[seg + 1] - t[seg];
                for (j = 0; j < N; j++) {
                    double S = coef_sum(&sp, (int)seg, j);
                    double fb = 8 * FLT_EPSILON * S; /* float32's own rounding, units */
                    double dp = fabs((double)pq[j] - lsb(pf[j]));
                    double dv = fabs((double)vq[j] - lsb(vf[j]));
                    double da = fabs((double)aq[j] - lsb(af[j]));
                    double shift = exact_times ? 0.0 : 1.0 / 131072.0; /* key-time rounding, s */
                    /* the row's extra fractional bits f, from the documented table layout */
                    int32_t f = table[5 * K + 3 * N + 7 * ((int)seg * N + j) + 6];
                    double g = ldexp(1.0, -f);
                    /* bound of spline_fx.h + float32's own rounding + 1 LSB for the
                     * float-to-LSB comparison itself */
                    double tol_p = 0.5 + 5.5 * g + lsb(fb) + lsb(fabs(vf[j]) * shift) + 1;
                    /* key-time rounding moves the sample by <= shift and changes h by
                     * <= 2 shift (relative 2 shift / h, once for v, twice for a) */
                    double tol_v = 10 * g / h + 0.5 + fabs(lsb(vf[j])) * 0x1p-22 + lsb(5 * fb / h) +
                                   lsb(fabs(af[j]) * shift + fabs(vf[j]) * 2 * shift / h) + 1;
                    double tol_a = 23 * g / (h * h) + 0.5 + fabs(lsb(af[j])) * 0x1p-22 +
                                   lsb(20 * fb / (h * h)) + lsb(4 * 60 * S / (h * h * h) * shift +
                                   fabs(af[j]) * 4 * shift / h) + 1;
                    int skip_v = !exact_times && order < 1 && near < 2.0 / 65536.0;
                    int skip_a = !exact_times && order < 2 && near < 2.0 / 65536.0;
                    if (dp > worst_p) worst_p = dp;
                    if (!skip_v && dv > worst_v) worst_v = dv;
                    if (!skip_a && da > worst_a) worst_a = da;
                    if (dp > tol_p)
                        fail_msg("profile %d trial %d t=%.9g joint %d: pos fixed %.9g float %.9g, "
                                 "%.1f LSB > %.1f", (int)set.profile, trial, (double)tf, j,
                                 pq[j] / 65536.0, (double)pf[j], dp, tol_p);
                    if (!skip_v && dv > tol_v)
                        fail_msg("profile %d trial %d t=%.9g joint %d: vel fixed %.9g float %.9g, "
                                 "%.1f LSB > %.1f", (int)set.profile, trial, (double)tf, j,
                                 vq[j] / 65536.0, (double)vf[j], dv, tol_v);
                    if (!skip_a && da > tol_a)
                        fail_msg("profile %d trial %d t=%.9g joint %d: acc fixed %.9g float %.9g, "
                                 "%.1f LSB > %.1f", (int)set.profile, trial, (double)tf, j,
                                 aq[j] / 65536.0, (double)af[j], da, tol_a);
                }
            }
        }
    }
    print_message("fixed vs float (%s key times): worst |diff| pos %.1f, vel %.1f, acc %.1f LSB\n",
                  exact_times ? "Q16-exact" : "arbitrary", worst_p, worst_v, worst_a);
}

static void test_fixed_vs_float_exact_times(void **state)
{
    (void)state;
    fixed_vs_float(1, 1001);
}

static void test_fixed_vs_float_arbitrary_times(void **state)
{
    (void)state;
    fixed_vs_float(0, 2002);
}

/* A small move keeps extra fractional bits (f = 12 here: max |b| = 15 * 0.25): the fixed
 * sample is then within 1 LSB of the double closed form in position and velocity. */
static void test_fixed_small_move_precision(void **state)
{
    const float t[2] = { 0.0f, 0.5f };
    const float p[2] = { 0.125f, 0.375f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    qo_spline_table_q16 fx;
    int i;
    double worst_p = 0, worst_v = 0;
    (void)state;
    set.profile = QO_SPLINE_QUINTIC;
    assert_int_equal(qo_spline_init_f32(1, 2, t, p, &set, coef, COEF_CAP, &sp), QO_OK);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_OK);
    assert_int_equal(table[5 * 2 + 3 * 1 + 6], 12); /* f of the only segment */
    for (i = 0; i <= 32768; i += 7) {
        double s = i / 32768.0, d = 0.25, rp, rv;
        qo_q16 pq, vq;
        rp = 0.125 + d * (10 * pow(s, 3) - 15 * pow(s, 4) + 6 * pow(s, 5));
        rv = d * (30 * s * s - 60 * pow(s, 3) + 30 * pow(s, 4)) / 0.5;
        assert_int_equal(qo_spline_sample_q16(&fx, (qo_q16)i, &pq, &vq, NULL, NULL), QO_OK);
        if (fabs(pq - lsb(rp)) > worst_p) worst_p = fabs(pq - lsb(rp));
        if (fabs(vq - lsb(rv)) > worst_v) worst_v = fabs(vq - lsb(rv));
        if (fabs(pq - lsb(rp)) > 1.0 || fabs(vq - lsb(rv)) > 1.0)
            fail_msg("t=%.9g: fixed (%.9g, %.9g) vs double (%.9g, %.9g)", i / 65536.0, pq / 65536.0,
                     vq / 65536.0, rp, rv);
    }
    print_message("small move vs double: worst pos %.2f, vel %.2f LSB\n", worst_p, worst_v);
}

/* Ends, wrap and limits in the fixed sampler. */
static void test_fixed_ends_wrap_limits(void **state)
{
    const float t[3] = { 0.0f, 1.0f, 2.0f };
    const float p[6] = { 3.0f, 0.0f, -3.0f, 5.0f, -2.5f, 1.0f };
    const unsigned char wrap[2] = { 1, 0 };
    const float lo[2] = { -10.0f, -1.0f }, hi[2] = { 10.0f, 4.0f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    qo_spline_table_q16 fx;
    qo_q16 pos[2], vel[2], acc[2];
    int8_t cl[2];
    int i, seen_clamp = 0;
    (void)state;
    set.wrap = wrap;
    set.pos_min = lo;
    set.pos_max = hi;
    assert_int_equal(qo_spline_init_f32(2, 3, t, p, &set, coef, COEF_CAP, &sp), QO_OK);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_OK);
    /* before / after: keys at rest; exact end: last key */
    assert_int_equal(qo_spline_sample_q16(&fx, INT32_MIN, pos, vel, acc, cl), QO_OK);
    assert_int_equal(pos[0], (qo_q16)lrint(3.0 * 65536));
    assert_int_equal(vel[0], 0);
    assert_int_equal(qo_spline_sample_q16(&fx, INT32_MAX, pos, vel, acc, cl), QO_OK);
    assert_int_equal(pos[1], 65536);
    assert_int_equal(vel[1], 0);
    assert_int_equal(acc[1], 0);
    assert_int_equal(qo_spline_sample_q16(&fx, 2 * 65536, pos, vel, acc, cl), QO_OK);
    assert_true(abs(pos[0] - (qo_q16)lrint(-2.5 * 65536)) <= 1);
    for (i = 0; i <= 200; i++) {
        qo_q16 tq = (qo_q16)(i * 65536 / 100);
        float pf[2], vf[2];
        int8_t cf[2];
        assert_int_equal(qo_spline_sample_q16(&fx, tq, pos, vel, acc, cl), QO_OK);
        assert_int_equal(qo_spline_sample_f32(&sp, (float)tq / 65536.0f, pf, vf, NULL, cf), QO_OK);
        /* wrapped joint: in (-pi, pi], near +-pi (the short way), same as float */
        if (!(pos[0] > -205888 && pos[0] <= 205888) || fabs(fabs(pos[0] / 65536.0) - REF_PI) > 0.7)
            fail_msg("t=%g: wrapped joint %.9g", tq / 65536.0, pos[0] / 65536.0);
        /* equal, or one period apart when the two land on either side of +-pi */
        if (fabs(pos[0] - lsb(pf[0])) > 16 && fabs(fabs(pos[0] - lsb(pf[0])) - lsb(2 * REF_PI)) > 16)
            fail_msg("t=%g: wrapped fixed %.9g float %.9g", tq / 65536.0, pos[0] / 65536.0,
                     (double)pf[0]);
        /* limited joint: the same clamp decision as float (away from the limit itself) */
        if (cl[1] != cf[1] && fabs(pf[1] - hi[1]) > 1e-3 && fabs(pf[1] - lo[1]) > 1e-3)
            fail_msg("t=%g: clamp fixed %d float %d (float pos %.9g)", tq / 65536.0, cl[1], cf[1],
                     (double)pf[1]);
        if (cl[1]) {
            seen_clamp = 1;
            assert_true(pos[1] == (cl[1] > 0 ? 4 * 65536 : -65536));
            assert_int_equal(vel[1], 0);
            assert_int_equal(acc[1], 0);
        }
    }
    assert_true(seen_clamp);
}

/* Conversion and sampling errors. */
static void test_fixed_edges(void **state)
{
    const float t[2] = { 0.0f, 1.0f }, p[2] = { 0.0f, 1.0f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp, empty;
    qo_spline_table_q16 fx;
    qo_q16 pos = 5, vel = 5, acc = 5;
    int8_t cl = 3;
    size_t need = qo_spline_q16_len(1, 2);
    (void)state;
    set.profile = QO_SPLINE_LINEAR;
    assert_int_equal(need, 10 + 3 + 14);
    assert_int_equal(qo_spline_q16_len(0, 2), 0);
    assert_int_equal(qo_spline_q16_len(1, 1), 0);
    assert_int_equal(qo_spline_q16_len(SIZE_MAX / 4, 4), 0);
    assert_int_equal(qo_spline_init_f32(1, 2, t, p, &set, coef, COEF_CAP, &sp), QO_OK);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, need - 1), QO_E_CAPACITY);
    assert_int_equal(fx.n_keys, 0);
    assert_int_equal(qo_spline_sample_q16(&fx, 0, &pos, &vel, &acc, &cl), QO_E_NULL); /* no table */
    assert_true(pos == 0 && vel == 0 && acc == 0 && cl == 0);
    assert_int_equal(qo_spline_export_q16(NULL, &fx, table, X_CAP), QO_E_NULL);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, NULL, COEF_CAP), QO_E_NULL);
    assert_int_equal(qo_spline_export_q16(&sp, NULL, table, X_CAP), QO_E_NULL);
    assert_int_equal(qo_spline_init_f32(1, 1, t, p, &set, coef, COEF_CAP, &empty), QO_E_TOO_FEW);
    assert_int_equal(qo_spline_export_q16(&empty, &fx, table, X_CAP), QO_E_STATE);
    /* a usable table, then a fake failed one: STATE with zeroed outputs */
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, need), QO_OK);
    assert_int_equal(qo_spline_sample_q16(&fx, 32768, &pos, &vel, &acc, &cl), QO_OK);
    assert_int_equal(pos, 32768);
    assert_int_equal(vel, 65536);
    fx.n_keys = 0;
    assert_int_equal(qo_spline_sample_q16(&fx, 32768, &pos, &vel, &acc, &cl), QO_E_STATE);
    assert_true(pos == 0 && vel == 0 && acc == 0 && cl == 0);
    assert_int_equal(qo_spline_sample_q16(NULL, 0, &pos, &vel, &acc, &cl), QO_E_NULL);
    assert_int_equal(qo_spline_export_q16(&sp, &fx, table, need), QO_OK);
    vel = 5;
    assert_int_equal(qo_spline_sample_q16(&fx, 0, NULL, &vel, NULL, NULL), QO_E_NULL);
    assert_int_equal(vel, 0);
    /* out of Q16.16: a position, a time; key times that round to the same Q16.16 value */
    {
        const float pbig[2] = { 0.0f, 40000.0f }, tbig[2] = { 0.0f, 40000.0f };
        const float tclose[2] = { 0.0f, 1e-6f };
        assert_int_equal(qo_spline_init_f32(1, 2, t, pbig, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_E_OVERFLOW);
        assert_int_equal(fx.n_keys, 0);
        assert_int_equal(qo_spline_init_f32(1, 2, tbig, p, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_E_OVERFLOW);
        assert_int_equal(qo_spline_init_f32(1, 2, tclose, p, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_E_ORDER);
    }
    /* a velocity beyond Q16.16 (rest-to-rest quintic over 2000 units in 10 ms: peak 3.75e5
     * units/s) saturates and says so; the position is still right */
    {
        const float tf[2] = { 0.0f, 0.01f }, pf[2] = { 0.0f, 2000.0f }, pn[2] = { 0.0f, -2000.0f };
        qo_q16 half = (qo_q16)lrint(0.01 * 65536) / 2; /* s = 0.5 of the rounded segment */
        set.profile = QO_SPLINE_QUINTIC;
        assert_int_equal(qo_spline_init_f32(1, 2, tf, pf, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_OK);
        assert_int_equal(qo_spline_sample_q16(&fx, half, &pos, &vel, &acc, NULL), QO_E_OVERFLOW);
        assert_int_equal(vel, INT32_MAX);
        {
            double sd = (double)half / (double)lrint(0.01 * 65536);
            double want = 2000.0 * (10 * pow(sd, 3) - 15 * pow(sd, 4) + 6 * pow(sd, 5));
            if (fabs(pos - lsb(want)) > 8)
                fail_msg("saturated-velocity sample: pos %.9g, want %.9g", pos / 65536.0, want);
        }
        assert_int_equal(qo_spline_init_f32(1, 2, tf, pn, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_OK);
        assert_int_equal(qo_spline_sample_q16(&fx, half, &pos, &vel, NULL, NULL), QO_E_OVERFLOW);
        assert_int_equal(vel, INT32_MIN);
        /* linear: the end state holds the same slope, so the conversion already refuses */
        set.profile = QO_SPLINE_LINEAR;
        assert_int_equal(qo_spline_init_f32(1, 2, tf, pf, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_E_OVERFLOW);
    }
    /* the shortest segment Q16.16 can hold (1 LSB of time) and a long one (hours) */
    {
        const float ts[3] = { 0.0f, 1.0f / 65536.0f, 20000.0f }, ps[3] = { 0.0f, 0.0f, 1.0f };
        set.profile = QO_SPLINE_CUBIC_C2;
        assert_int_equal(qo_spline_init_f32(1, 3, ts, ps, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_export_q16(&sp, &fx, table, X_CAP), QO_OK);
        assert_int_equal(qo_spline_sample_q16(&fx, 10000 * 65536, &pos, &vel, &acc, NULL), QO_OK);
        assert_true(abs(pos - 32768) <= 8);
    }
}

/* ---- float32 only ----------------------------------------------------------------------- */

/* Continuity at every inner key: the sample just before t_k (the float below t_k) against
 * the sample at t_k. Tolerance: a float32 rounding budget from eps and the key scale P,
 * plus the Taylor term f' * dt measured from the samples themselves. Position for all
 * profiles, velocity for C1 ones, acceleration for CUBIC_C2 and QUINTIC. The same
 * measurement must SEE the acceleration jumps of Catmull-Rom and the velocity jumps of
 * linear (so it is able to fail). */
/* the jumps the measurement must see over all trials (ctx of continuity_trial) */
typedef struct seen_jumps { int acc, vel; } seen_jumps;

static void continuity_trial(int trial, const keys *ks, double P, double hmin, void *ctx)
{
    seen_jumps *seen = ctx;
    size_t pi;
    int i, j;
    const double eps = FLT_EPSILON;
    (void)P;
    for (pi = 0; pi < NPROF; pi++) {
        qo_spline_settings_f32 set = settings_for(all_profiles[pi], end_of(trial & 1));
        qo_spline_f32 sp;
        int order; /* continuity order expected */
        assert_int_equal(plan(ks, &set, &sp), QO_OK);
        order = set.profile == QO_SPLINE_LINEAR ? 0
              : (set.profile == QO_SPLINE_CUBIC_C2 || set.profile == QO_SPLINE_QUINTIC) ? 2 : 1;
        for (i = 1; i + 1 < ks->k; i++) {
            float tr = ks->t[i], tl = nextafterf(tr, -INFINITY);
            float tl2 = tr - (float)(0.01 * hmin);
            float pl[MAXN], vl[MAXN], al[MAXN], pr[MAXN], vr[MAXN], ar[MAXN];
            float p2[MAXN], v2[MAXN], a2[MAXN];
            double dt = (double)tr - tl, d2 = (double)tl - tl2;
            sample(&sp, tl, pl, vl, al);
            sample(&sp, tr, pr, vr, ar);
            sample(&sp, tl2, p2, v2, a2);
            for (j = 0; j < ks->n; j++) {
                /* rounding budget: eps times the coefficient magnitude S of the two
                 * segments meeting here (sum |b_n|; derivatives bring factors up to 5
                 * and 20 and 1/h, 1/h^2 of the shorter segment) */
                double S = fmax(coef_sum(&sp, i - 1, j), coef_sum(&sp, i, j));
                double h = fmin((double)ks->t[i] - ks->t[i - 1], (double)ks->t[i + 1] - ks->t[i]);
                double jerk = fabs((double)al[j] - a2[j]) / d2;
                double tol_p = 8 * eps * S + 2 * fabs(vl[j]) * dt;
                double tol_v = 8 * eps * 5 * S / h + 2 * fabs(al[j]) * dt;
                double tol_a = 8 * eps * 20 * S / (h * h) + 4 * jerk * dt;
                double jp = fabs((double)pr[j] - pl[j]);
                double jv = fabs((double)vr[j] - vl[j]);
                double ja = fabs((double)ar[j] - al[j]);
                if (jp > tol_p)
                    fail_msg("%s trial %d key %d joint %d: position jump %.3g > %.3g",
                             prof_name(set.profile), trial, i, j, jp, tol_p);
                if (order >= 1 && jv > tol_v)
                    fail_msg("%s trial %d key %d joint %d: velocity jump %.3g > %.3g",
                             prof_name(set.profile), trial, i, j, jv, tol_v);
                if (order >= 2 && ja > tol_a)
                    fail_msg("%s trial %d key %d joint %d: acceleration jump %.3g > %.3g",
                             prof_name(set.profile), trial, i, j, ja, tol_a);
                if (set.profile == QO_SPLINE_CATMULL_ROM && ja > 100 * tol_a) seen->acc = 1;
                if (set.profile == QO_SPLINE_LINEAR && jv > 100 * tol_v) seen->vel = 1;
            }
        }
    }
}

static void test_continuity_at_joins(void **state)
{
    static const key_shape shape = { 4, 3, 8, 0.1, 1.5, 10.0 };
    seen_jumps seen = { 0, 0 };
    (void)state;
    run_trials(202, 25, &shape, continuity_trial, &seen);
    assert_true(seen.acc);
    assert_true(seen.vel);
}

/* Interpolating C2 cubic (natural and clamped ends) against the dense double solve. */
static void c2_trial(int trial, const keys *ks, double P, double hmin, void *ctx)
{
    int j, nat, i;
    float ev[2 * MAXN];
    const double eps = FLT_EPSILON;
    (void)ctx;
    for (j = 0; j < 2 * ks->n; j++) ev[j] = (float)urand(-5.0, 5.0);
    for (nat = 0; nat < 2; nat++) {
        qo_spline_settings_f32 set = settings_for(QO_SPLINE_CUBIC_C2, end_of(nat));
        qo_spline_f32 sp;
        set.end_vel = ev;
        assert_int_equal(plan(ks, &set, &sp), QO_OK);
        for (j = 0; j < ks->n; j++) {
            double td[MAXK], yd[MAXK], m[MAXK];
            for (i = 0; i < ks->k; i++) { td[i] = ks->t[i]; yd[i] = ks->p[i * ks->n + j]; }
            ref_c2_moments(ks->k, td, yd, nat, ev[j], ev[ks->n + j], m);
            for (i = 0; i < 40; i++) {
                float t = (float)urand(td[0], td[ks->k - 1]);
                float p[MAXN], v[MAXN], a[MAXN];
                int s = seg_of(ks, t);
                double h = td[s + 1] - td[s], A = (td[s + 1] - t) / h, B = 1.0 - A;
                double rp = A * yd[s] + B * yd[s + 1] +
                            ((A * A * A - A) * m[s] + (B * B * B - B) * m[s + 1]) * h * h / 6.0;
                double rv = (yd[s + 1] - yd[s]) / h - (3 * A * A - 1) / 6.0 * h * m[s] +
                            (3 * B * B - 1) / 6.0 * h * m[s + 1];
                double ra = A * m[s] + B * m[s + 1];
                sample(&sp, t, p, v, a);
                check_close(nat ? "c2 natural pos" : "c2 clamped pos", trial, j, t, p[j], rp,
                            64 * eps * P * ks->k);
                check_close(nat ? "c2 natural vel" : "c2 clamped vel", trial, j, t, v[j], rv,
                            64 * eps * P * ks->k / hmin);
                check_close(nat ? "c2 natural acc" : "c2 clamped acc", trial, j, t, a[j], ra,
                            256 * eps * P * ks->k / (hmin * hmin));
            }
            /* natural: zero acceleration at both ends; clamped: the given end velocities */
            {
                float p[MAXN], v[MAXN], a[MAXN];
                sample(&sp, ks->t[0], p, v, a);
                if (nat) check_close("c2 natural start acc", trial, j, td[0], a[j], 0.0,
                                     256 * eps * P * ks->k / (hmin * hmin));
                else check_close("c2 clamped start vel", trial, j, td[0], v[j], ev[j],
                                 64 * eps * P * ks->k / hmin);
                sample(&sp, ks->t[ks->k - 1], p, v, a);
                if (nat) check_close("c2 natural end acc", trial, j, td[ks->k - 1], a[j], 0.0,
                                     256 * eps * P * ks->k / (hmin * hmin));
                else check_close("c2 clamped end vel", trial, j, td[ks->k - 1], v[j],
                                 ev[ks->n + j],
                                 64 * eps * P * ks->k / hmin);
            }
        }
    }
}

static void test_c2_against_double(void **state)
{
    static const key_shape shape = { 3, 2, 11, 0.1, 1.0, 10.0 };
    (void)state;
    run_trials(303, 30, &shape, c2_trial, NULL);
}

/* Double Catmull-Rom (time-weighted) tangents of key i of joint j; ends per condition. */
static double ref_tangent(const keys *ks, int j, int i, int natural, const float *ev)
{
    int n = ks->n, k = ks->k;
    double s0, s1, h0, h1;
    if (i > 0 && i < k - 1) {
        h0 = (double)ks->t[i] - ks->t[i - 1];
        h1 = (double)ks->t[i + 1] - ks->t[i];
        s0 = ((double)ks->p[i * n + j] - ks->p[(i - 1) * n + j]) / h0;
        s1 = ((double)ks->p[(i + 1) * n + j] - ks->p[i * n + j]) / h1;
        /* Barry-Goldman with uniform-in-time knots: s0 - (p_(i+1) - p_(i-1))/(h0+h1) + s1 */
        return s0 - ((double)ks->p[(i + 1) * n + j] - ks->p[(i - 1) * n + j]) / (h0 + h1) + s1;
    }
    if (!natural) return i == 0 ? (ev ? ev[j] : 0.0) : (ev ? ev[n + j] : 0.0);
    if (k == 2) return ((double)ks->p[n + j] - ks->p[j]) / ((double)ks->t[1] - ks->t[0]);
    if (i == 0) {
        s0 = ((double)ks->p[n + j] - ks->p[j]) / ((double)ks->t[1] - ks->t[0]);
        return 1.5 * s0 - 0.5 * ref_tangent(ks, j, 1, natural, ev);
    }
    s1 = ((double)ks->p[(k - 1) * n + j] - ks->p[(k - 2) * n + j]) /
         ((double)ks->t[k - 1] - ks->t[k - 2]);
    return 1.5 * s1 - 0.5 * ref_tangent(ks, j, k - 2, natural, ev);
}

/* Catmull-Rom: velocities at the keys equal the double tangents, and samples between keys
 * match the double cubic Hermite through them; natural ends have zero end acceleration. */
static void catmull_trial(int trial, const keys *ks, double P, double hmin, void *ctx)
{
    int j, i, nat;
    const double eps = FLT_EPSILON;
    (void)ctx;
    for (nat = 0; nat < 2; nat++) {
        qo_spline_settings_f32 set = settings_for(QO_SPLINE_CATMULL_ROM, end_of(nat));
        qo_spline_f32 sp;
        assert_int_equal(plan(ks, &set, &sp), QO_OK);
        for (i = 0; i < ks->k; i++) {
            float p[MAXN], v[MAXN], a[MAXN];
            sample(&sp, ks->t[i], p, v, a);
            for (j = 0; j < ks->n; j++)
                check_close("catmull tangent", trial, j, ks->t[i], v[j],
                            ref_tangent(ks, j, i, nat, NULL), 16 * eps * P / hmin);
        }
        for (i = 0; i < 60; i++) {
            float t = (float)urand(ks->t[0], ks->t[ks->k - 1]);
            float p[MAXN], v[MAXN], a[MAXN];
            int s = seg_of(ks, t);
            sample(&sp, t, p, v, a);
            for (j = 0; j < ks->n; j++) {
                double c[6], rp, rv, ra;
                ref_segment(3, (double)ks->t[s + 1] - ks->t[s], ks->p[s * ks->n + j],
                            ref_tangent(ks, j, s, nat, NULL), 0.0, ks->p[(s + 1) * ks->n + j],
                            ref_tangent(ks, j, s + 1, nat, NULL), 0.0, c);
                ref_eval(c, (double)t - ks->t[s], &rp, &rv, &ra);
                check_close("catmull pos", trial, j, t, p[j], rp, 32 * eps * P);
                check_close("catmull vel", trial, j, t, v[j], rv, 64 * eps * P / hmin);
                check_close("catmull acc", trial, j, t, a[j], ra,
                            256 * eps * P / (hmin * hmin));
            }
        }
        if (nat && ks->k > 2) {
            float p[MAXN], v[MAXN], a[MAXN];
            sample(&sp, ks->t[0], p, v, a);
            for (j = 0; j < ks->n; j++)
                check_close("catmull natural start acc", trial, j, ks->t[0], a[j], 0.0,
                            256 * eps * P / (hmin * hmin));
        }
    }
}

static void test_catmull_rom_against_double(void **state)
{
    static const key_shape shape = { 3, 2, 10, 0.05, 1.0, 10.0 };
    (void)state;
    run_trials(404, 30, &shape, catmull_trial, NULL);
}

/* Hermite with given velocities and quintic with given / estimated / zero derivatives
 * against the double solve of each segment's end conditions. */
static void hermite_quintic_trial(int trial, const keys *ks, double P, double hmin, void *ctx)
{
    int j, i, mode;
    const double eps = FLT_EPSILON;
    (void)ctx;
    for (mode = 0; mode < 5; mode++) {
        /* 0 hermite, 1 quintic given v+a, 2 quintic estimated, 3 quintic zero,
         * 4 quintic given v, estimated a */
        qo_spline_settings_f32 set = settings_for(mode == 0 ? QO_SPLINE_CUBIC_HERMITE
                                                            : QO_SPLINE_QUINTIC,
                                                  QO_SPLINE_END_CLAMPED);
        qo_spline_f32 sp;
        double kv[MAXK * MAXN], ka[MAXK * MAXN];
        if (mode == 1 || mode == 4) set.key_vel = ks->v;
        if (mode == 1) set.key_acc = ks->a;
        if (mode == 3) set.derivs = QO_SPLINE_DERIVS_ZERO;
        assert_int_equal(plan(ks, &set, &sp), QO_OK);
        for (j = 0; j < ks->n; j++)
            for (i = 0; i < ks->k; i++) {
                int x = i * ks->n + j;
                if (mode == 0 || mode == 1 || mode == 4) kv[x] = ks->v[x];
                else if (mode == 3 && i > 0 && i < ks->k - 1) kv[x] = 0.0;
                else kv[x] = ref_tangent(ks, j, i, 0, NULL);
                ka[x] = mode == 1 ? ks->a[x] : 0.0;
            }
        if (mode == 2 || mode == 4)
            for (j = 0; j < ks->n; j++)
                for (i = 1; i + 1 < ks->k; i++) {
                    double h0 = (double)ks->t[i] - ks->t[i - 1];
                    double h1 = (double)ks->t[i + 1] - ks->t[i];
                    double g0 = (kv[i * ks->n + j] - kv[(i - 1) * ks->n + j]) / h0;
                    double g1 = (kv[(i + 1) * ks->n + j] - kv[i * ks->n + j]) / h1;
                    ka[i * ks->n + j] = (g0 * h1 + g1 * h0) / (h0 + h1);
                }
        for (i = 0; i < 60; i++) {
            float t = (float)urand(ks->t[0], ks->t[ks->k - 1]);
            float p[MAXN], v[MAXN], a[MAXN];
            int s = seg_of(ks, t);
            double h = (double)ks->t[s + 1] - ks->t[s];
            sample(&sp, t, p, v, a);
            for (j = 0; j < ks->n; j++) {
                double c[6], rp, rv, ra, Ps = P * (1 + h) * (1 + h); /* v h, a h^2 terms */
                int x0 = s * ks->n + j, x1 = (s + 1) * ks->n + j;
                ref_segment(mode == 0 ? 3 : 5, h, ks->p[x0], kv[x0], ka[x0], ks->p[x1], kv[x1],
                            ka[x1], c);
                ref_eval(c, (double)t - ks->t[s], &rp, &rv, &ra);
                check_close(mode == 0 ? "hermite pos" : "quintic pos", trial * 10 + mode, j, t,
                            p[j], rp, 64 * eps * Ps);
                check_close(mode == 0 ? "hermite vel" : "quintic vel", trial * 10 + mode, j, t,
                            v[j], rv, 256 * eps * Ps / hmin);
                check_close(mode == 0 ? "hermite acc" : "quintic acc", trial * 10 + mode, j, t,
                            a[j], ra, 1024 * eps * Ps / (hmin * hmin));
            }
        }
    }
}

static void test_hermite_quintic_against_double(void **state)
{
    static const key_shape shape = { 2, 2, 8, 0.1, 1.0, 5.0 };
    (void)state;
    run_trials(505, 24, &shape, hermite_quintic_trial, NULL);
}

/* Continuous joints: 3.0 -> -3.0 rad goes through +pi (0.283 rad), not through 0 (6 rad);
 * output wrapped into (-pi, pi] or unwrapped (monotonic from 3.0 to 2 pi - 3.0); degrees. */
static void test_wrap_short_way(void **state)
{
    const float t[3] = { 0.0f, 1.0f, 2.0f };
    const float p[6] = { 3.0f, 0.5f, -3.0f, 0.7f, -2.5f, 0.9f }; /* joint 0 wraps, joint 1 not */
    const unsigned char wrap[2] = { 1, 0 };
    const double twopi = 6.283185307179586;
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    float prev = 3.0f;
    int i, wrapped_out;
    (void)state;
    set.profile = QO_SPLINE_CUBIC_C2;
    set.wrap = wrap;
    for (wrapped_out = 0; wrapped_out < 2; wrapped_out++) {
        set.wrap_output = wrapped_out;
        assert_int_equal(qo_spline_init_f32(2, 3, t, p, &set, coef, COEF_CAP, &sp), QO_OK);
        for (i = 0; i <= 200; i++) {
            float tt = (float)i / 100.0f, pos[2], vel[2];
            double ref_unwrapped;
            assert_int_equal(qo_spline_sample_f32(&sp, tt, pos, vel, NULL, NULL), QO_OK);
            if (wrapped_out) {
                if (!(pos[0] > -3.14159275f && pos[0] <= 3.14159275f))
                    fail_msg("t=%g: wrapped output %.9g outside (-pi, pi]", (double)tt,
                             (double)pos[0]);
                /* never through 0: keys are within 0.65 rad of +-pi */
                if (fabs(fabs(pos[0]) - 3.14159265) > 0.7)
                    fail_msg("t=%g: %.9g went the long way", (double)tt, (double)pos[0]);
            } else {
                if (i <= 100 && pos[0] < prev - 1e-6f)
                    fail_msg("t=%g: unwrapped output %.9g decreases", (double)tt, (double)pos[0]);
                prev = pos[0];
            }
            if (i == 100) {
                ref_unwrapped = twopi - 3.0;
                if (wrapped_out) check_close("wrap key1", 0, 0, tt, pos[0], -3.0, 4e-6);
                else check_close("unwrap key1", 0, 0, tt, pos[0], ref_unwrapped, 4e-6);
            }
            if (i == 200) {
                double want = twopi - 3.0 + (-2.5 - -3.0);
                if (wrapped_out) check_close("wrap key2", 0, 0, tt, pos[0], -2.5, 4e-6);
                else check_close("unwrap key2", 0, 0, tt, pos[0], want, 4e-6);
            }
        }
    }
    /* degrees: 170 -> -170 through 180; exactly half a turn goes + */
    {
        const float td[3] = { 0.0f, 1.0f, 2.0f };
        const float pd[3] = { 170.0f, -170.0f, 10.0f };
        float pos, vel;
        set.wrap_period = 360.0f;
        set.wrap_output = 0;
        set.profile = QO_SPLINE_LINEAR;
        assert_int_equal(qo_spline_init_f32(1, 3, td, pd, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_sample_f32(&sp, 0.5f, &pos, &vel, NULL, NULL), QO_OK);
        check_close("deg mid", 0, 0, 0.5, pos, 180.0, 1e-4);
        check_close("deg vel", 0, 0, 0.5, vel, 20.0, 1e-4);
        assert_int_equal(qo_spline_sample_f32(&sp, 1.5f, &pos, &vel, NULL, NULL), QO_OK);
        check_close("deg half turn goes +", 0, 0, 1.5, vel, 180.0, 1e-3); /* 190 -> 370 */
    }
}

/* Edges: K = 2 for every profile, too few keys, equal / decreasing times, NaN / Inf inputs,
 * NULL pointers, storage one float short, bad enums, impossible limits, bad wrap period,
 * coefficient overflow, sampling a failed plan. */
static void test_edges(void **state)
{
    const float t2[2] = { 0.0f, 2.0f }, p2[2] = { 1.0f, 3.0f };
    float tb[3] = { 0.0f, 1.0f, 1.0f }, pb[3] = { 0.0f, 1.0f, 2.0f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    size_t pi;
    float pos[2] = { 9, 9 }, vel[2] = { 9, 9 }, acc[2] = { 9, 9 };
    int8_t cl[2] = { 5, 5 };
    size_t need = qo_spline_coef_len(1, 3);
    (void)state;
    /* K = 2: every profile interpolates; natural C2 / Catmull-Rom is the straight line */
    for (pi = 0; pi < NPROF; pi++) {
        const float v2[2] = { 0.0f, 0.0f };
        set = qo_spline_settings_default;
        set.profile = all_profiles[pi];
        set.key_vel = v2;
        set.end = QO_SPLINE_END_NATURAL;
        assert_int_equal(qo_spline_init_f32(1, 2, t2, p2, &set, coef, COEF_CAP, &sp), QO_OK);
        assert_int_equal(qo_spline_sample_f32(&sp, 1.0f, pos, vel, acc, NULL), QO_OK);
        if (set.profile != QO_SPLINE_CUBIC_HERMITE && set.profile != QO_SPLINE_QUINTIC) {
            check_close(prof_name(set.profile), 2, 0, 1.0, pos[0], 2.0, 1e-6);
            check_close(prof_name(set.profile), 2, 0, 1.0, vel[0], 1.0, 1e-6);
        } else {
            check_close(prof_name(set.profile), 2, 0, 1.0, pos[0], 2.0, 1e-6); /* symmetric */
        }
    }
    set = qo_spline_settings_default;
    assert_int_equal(qo_spline_init_f32(1, 1, t2, p2, &set, coef, COEF_CAP, &sp), QO_E_TOO_FEW);
    assert_int_equal(sp.n_keys, 0);
    assert_int_equal(qo_spline_init_f32(0, 2, t2, p2, &set, coef, COEF_CAP, &sp), QO_E_TOO_FEW);
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_ORDER);
    tb[2] = 0.5f;
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_ORDER);
    tb[2] = NAN;
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_NONFINITE);
    tb[2] = 2.0f;
    pb[1] = INFINITY;
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_NONFINITE);
    pb[1] = NAN;
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_NONFINITE);
    pb[1] = 1.0f;
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_OK);
    /* NULLs */
    assert_int_equal(qo_spline_init_f32(1, 3, NULL, pb, &set, coef, COEF_CAP, &sp), QO_E_NULL);
    assert_int_equal(sp.n_keys, 0);
    assert_int_equal(qo_spline_init_f32(1, 3, tb, NULL, &set, coef, COEF_CAP, &sp), QO_E_NULL);
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, NULL, coef, COEF_CAP, &sp), QO_E_NULL);
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, NULL, COEF_CAP, &sp), QO_E_NULL);
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, NULL), QO_E_NULL);
    set.profile = QO_SPLINE_CUBIC_HERMITE; /* needs key_vel */
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_NULL);
    set = qo_spline_settings_default;
    /* storage */
    assert_int_equal(need, 3 + 3 + 18);
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, need - 1, &sp), QO_E_CAPACITY);
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, need, &sp), QO_OK);
    assert_int_equal(qo_spline_coef_len(0, 3), 0);
    assert_int_equal(qo_spline_coef_len(2, 1), 0);
    assert_int_equal(qo_spline_coef_len(SIZE_MAX / 4, 4), 0);
    assert_int_equal(qo_spline_coef_len(4, SIZE_MAX / 4), 0);
    /* bad enums */
    set.profile = (qo_spline_profile)99;
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_ARG);
    set = qo_spline_settings_default;
    set.end = (qo_spline_end)7;
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_ARG);
    set = qo_spline_settings_default;
    set.derivs = (qo_spline_derivs)-1;
    assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_ARG);
    /* limits */
    {
        float lo = 2.0f, hi = 1.0f, nan = NAN;
        set = qo_spline_settings_default;
        set.pos_min = &lo;
        set.pos_max = &hi;
        assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_LIMIT);
        set.pos_max = &nan;
        assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_LIMIT);
        hi = 2.0f; /* min == max is allowed: a held joint */
        set.pos_max = &hi;
        assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_OK);
    }
    /* wrap period */
    {
        const unsigned char w = 1;
        set = qo_spline_settings_default;
        set.wrap = &w;
        set.wrap_period = 0.0f;
        assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_RANGE);
        set.wrap_period = NAN;
        assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp), QO_E_RANGE);
    }
    /* non-finite end velocity; coefficient overflow; huge time span */
    {
        float ev[2] = { 0.0f, INFINITY };
        const float th[2] = { 0.0f, 1e-30f }, ph[2] = { -3e38f, 3e38f };
        const float tw[2] = { -3e38f, 3e38f };
        set = qo_spline_settings_default;
        set.end_vel = ev;
        assert_int_equal(qo_spline_init_f32(1, 3, tb, pb, &set, coef, COEF_CAP, &sp),
                         QO_E_NONFINITE);
        set.end_vel = NULL;
        assert_int_equal(qo_spline_init_f32(1, 2, th, ph, &set, coef, COEF_CAP, &sp), QO_E_RANGE);
        assert_int_equal(qo_spline_init_f32(1, 2, tw, p2, &set, coef, COEF_CAP, &sp), QO_E_RANGE);
    }
    /* sampling a failed plan writes zeros and says so; NULL output */
    assert_int_equal(qo_spline_init_f32(2, 1, t2, p2, &set, coef, COEF_CAP, &sp), QO_E_TOO_FEW);
    assert_int_equal(qo_spline_sample_f32(&sp, 1.0f, pos, vel, acc, cl), QO_E_STATE);
    assert_true(pos[0] == 0.0f && pos[1] == 0.0f && vel[1] == 0.0f && acc[0] == 0.0f && cl[1] == 0);
    assert_int_equal(qo_spline_sample_f32(NULL, 1.0f, pos, vel, acc, cl), QO_E_NULL);
    set = qo_spline_settings_default;
    assert_int_equal(qo_spline_init_f32(1, 2, t2, p2, &set, coef, COEF_CAP, &sp), QO_OK);
    vel[0] = 9.0f;
    assert_int_equal(qo_spline_sample_f32(&sp, 1.0f, NULL, vel, acc, cl), QO_E_NULL);
    assert_true(vel[0] == 0.0f);
}

/* Many joints and keys, the ordinary size classes of a hexapod (18 joints): every key exact
 * and samples finite, with a binary-searched segment at every t. */
#if defined(__ARM_ARCH_6M__)
#define MANY_KEYS 4   /* Cortex-M0 board: 16 KB of RAM; 200 keys need 87 KB */
#else
#define MANY_KEYS 200
#endif
static void test_many_joints_keys(void **state)
{
    static float t[MANY_KEYS], p[MANY_KEYS * 18], buf[MANY_KEYS + 3 * 18 + 6 * MANY_KEYS * 18];
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    int i, j;
    (void)state;
    rng_state = 808;
    t[0] = 0.0f;
    for (i = 1; i < MANY_KEYS; i++) t[i] = t[i - 1] + (float)urand(0.01, 0.1);
    for (i = 0; i < MANY_KEYS * 18; i++) p[i] = (float)urand(-3.0, 3.0);
    set.profile = QO_SPLINE_QUINTIC;
    assert_int_equal(qo_spline_coef_len(18, MANY_KEYS), sizeof buf / sizeof buf[0]);
    assert_int_equal(qo_spline_init_f32(18, MANY_KEYS, t, p, &set, buf, sizeof buf / sizeof buf[0],
                                        &sp), QO_OK);
    for (i = 0; i < MANY_KEYS; i++) {
        float pos[18];
        assert_int_equal(qo_spline_sample_f32(&sp, t[i], pos, NULL, NULL, NULL), QO_OK);
        for (j = 0; j < 18; j++)
            if (pos[j] != p[i * 18 + j]) fail_msg("key %d joint %d not exact", i, j);
    }
}

/* The documented re-planning recipe: sample plan A at the switch time, plan B from that
 * sample (first key = position, CLAMPED start velocity = velocity): at the switch B gives the
 * same position bit for bit and the same velocity up to rounding; B then reaches its keys. */
static void test_replan_continues(void **state)
{
    keys ks;
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 a, b;
    int trial, j;
    (void)state;
    rng_state = 909;
    for (trial = 0; trial < 20; trial++) {
        float ts, pa[MAXN], va[MAXN], pb[MAXN], vb[MAXN], ev[2 * MAXN];
        float tb[3], keyb[3 * MAXN];
        random_keys(&ks, 3, 5, 0.2, 1.0, 5.0);
        set.profile = (trial & 1) ? QO_SPLINE_CATMULL_ROM : QO_SPLINE_CUBIC_C2;
        assert_int_equal(plan(&ks, &set, &a), QO_OK);
        ts = (float)urand(ks.t[1], ks.t[3]);
        sample(&a, ts, pa, va, NULL);
        tb[0] = ts;
        tb[1] = ts + 0.5f;
        tb[2] = ts + 1.5f;
        for (j = 0; j < 3; j++) {
            keyb[j] = pa[j];
            keyb[3 + j] = (float)urand(-5.0, 5.0);
            keyb[6 + j] = (float)urand(-5.0, 5.0);
            ev[j] = va[j];
            ev[3 + j] = 0.0f;
        }
        set.end = QO_SPLINE_END_CLAMPED;
        set.end_vel = ev;
        assert_int_equal(qo_spline_init_f32(3, 3, tb, keyb, &set, coef2, COEF_CAP, &b), QO_OK);
        set.end_vel = NULL;
        sample(&b, ts, pb, vb, NULL);
        for (j = 0; j < 3; j++) {
            if (pb[j] != pa[j]) fail_msg("trial %d joint %d: position %.9g != %.9g at the switch",
                                         trial, j, (double)pb[j], (double)pa[j]);
            check_close("replan velocity", trial, j, ts, vb[j], va[j],
                        8 * FLT_EPSILON * (1 + fabs(va[j])));
        }
        sample(&b, tb[2], pb, vb, NULL);
        for (j = 0; j < 3; j++) assert_true(pb[j] == keyb[6 + j] && vb[j] == 0.0f);
    }
}

/* Plans whose float32 samples would overflow (fuzz findings): refused with QO_E_RANGE and the
 * empty plan, or, where the bound lets them through, every sample finite. */
static void expect_range_or_finite(const char *name, qo_spline_profile prof, size_t nk, const float *t,
                                   const float *p, const unsigned char *wrap, int must_fail)
{
    float cf[COEF_CAP], pos[1], vel[1], acc[1];
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    qo_status st;
    size_t k;
    int i;
    set.profile = prof;
    set.wrap = wrap;
    st = qo_spline_init_f32(1, nk, t, p, &set, cf, COEF_CAP, &sp);
    if (st != QO_OK) {
        if (st != QO_E_RANGE || sp.n_keys != 0 || sp.coef != NULL)
            fail_msg("%s: init status %d n_keys %zu, want QO_E_RANGE and the empty plan", name, (int)st, sp.n_keys);
        if (qo_spline_sample_f32(&sp, t[0], pos, vel, acc, NULL) != QO_E_STATE) fail_msg("%s: sample of empty plan", name);
        return;
    }
    if (must_fail) fail_msg("%s: init accepted a plan whose samples overflow", name);
    for (k = 0; k + 1 < nk; k++)
        for (i = 0; i <= 8; i++) {
            float tt = (float)((double)t[k] + ((double)t[k + 1] - (double)t[k]) * i / 8.0);
            st = qo_spline_sample_f32(&sp, tt, pos, vel, acc, NULL);
            if (st != QO_OK || !isfinite(pos[0]) || !isfinite(vel[0]) || !isfinite(acc[0]))
                fail_msg("%s: t %.9g status %d pos %g vel %g acc %g", name, (double)tt, (int)st, (double)pos[0],
                         (double)vel[0], (double)acc[0]);
        }
}

static void test_range_overflow(void **state)
{
    static const float t_lin[2] = {0.0f, 1e-4f}, p_lin[2] = {FLT_MAX, 2.0f};
    static const float t_cr[3] = {0.0f, 1e-10f, 2e-10f}, p_cr[3] = {6e19f, -6e19f, 6e19f};
    static const float t_big[3] = {0.0f, 1.0f, FLT_MAX}, p_big[3] = {0.0f, 1.0f, -3.0f};
    static const float t_wide[3] = {-FLT_MAX, 0.0f, FLT_MAX}, p_wide[3] = {1.0f, 5e30f, -1.0f};
    static const float t_w[4] = {0.0f, 1e-20f, 2e-20f, 3e-20f}, p_w[4] = {0.0f, 3.0f, -3.0f, 3.0f};
    static const float t_ok[2] = {0.0f, 1.0f}, p_ok[2] = {0.0f, 1e28f};
    static const unsigned char wr[1] = {1};
    float cf[COEF_CAP], pos[1], vel[1], acc[1];
    qo_spline_f32 sp;
    (void)state;
    expect_range_or_finite("LINEAR FLT_MAX -> 2 in 1e-4 s", QO_SPLINE_LINEAR, 2, t_lin, p_lin, NULL, 1);
    expect_range_or_finite("CATMULL_ROM +-6e19 in 1e-10 s", QO_SPLINE_CATMULL_ROM, 3, t_cr, p_cr, NULL, 1);
    expect_range_or_finite("QUINTIC wrapped steps in 1e-20 s", QO_SPLINE_QUINTIC, 4, t_w, p_w, wr, 1);
    expect_range_or_finite("QUINTIC key at t = FLT_MAX", QO_SPLINE_QUINTIC, 3, t_big, p_big, NULL, 0);
    expect_range_or_finite("QUINTIC keys at -+FLT_MAX", QO_SPLINE_QUINTIC, 3, t_wide, p_wide, NULL, 1);
    expect_range_or_finite("CUBIC_C2 keys at -+FLT_MAX", QO_SPLINE_CUBIC_C2, 3, t_wide, p_wide, NULL, 1);
    /* inside the supported range (C2 at rest: acc bound 1.8e29): accepted */
    assert_int_equal(qo_spline_init_f32(1, 2, t_ok, p_ok, &qo_spline_settings_default, cf, COEF_CAP, &sp), QO_OK);
    expect_range_or_finite("LINEAR 0 -> 1e28 in 1 s", QO_SPLINE_LINEAR, 2, t_ok, p_ok, NULL, 0);
    /* last line of defence: a hand-made plan whose segment overflows gives QO_E_RANGE and the
     * segment's start key at rest (layout of spline.c: K times, min/max/period, rows) */
    memset(cf, 0, sizeof cf);
    cf[0] = 0.0f; cf[1] = 1.0f;
    cf[2] = -INFINITY; cf[3] = INFINITY; cf[4] = 0.0f;
    cf[5] = 7.0f; cf[6] = FLT_MAX; cf[7] = FLT_MAX;
    cf[11] = 7.0f;
    sp.n_joints = 1; sp.n_keys = 2; sp.profile = QO_SPLINE_QUINTIC; sp.wrap_output = 0; sp.coef = cf;
    pos[0] = vel[0] = acc[0] = 99.0f;
    assert_int_equal(qo_spline_sample_f32(&sp, 0.75f, pos, vel, acc, NULL), QO_E_RANGE);
    if (pos[0] != 7.0f || vel[0] != 0.0f || acc[0] != 0.0f)
        fail_msg("defence: pos %g vel %g acc %g, want 7 at rest", (double)pos[0], (double)vel[0], (double)acc[0]);
    assert_int_equal(qo_spline_sample_f32(&sp, 2.0f, pos, vel, acc, NULL), QO_OK);
}

/* NaN and Inf times, which Q16.16 cannot hold: QO_E_NONFINITE, the first key held at rest. */
static void test_f32_nonfinite_time(void **state)
{
    const float t[3] = { 1.0f, 2.0f, 4.0f };
    const float p[6] = { 0.0f, 5.0f, 1.0f, -2.0f, 3.0f, 3.0f };
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    float pos[2], vel[2], acc[2];
    (void)state;
    set.end = QO_SPLINE_END_NATURAL;
    assert_int_equal(qo_spline_init_f32(2, 3, t, p, &set, coef, COEF_CAP, &sp), QO_OK);
    vel[0] = 7.0f;
    assert_int_equal(qo_spline_sample_f32(&sp, NAN, pos, vel, acc, NULL), QO_E_NONFINITE);
    assert_true(pos[0] == 0.0f && pos[1] == 5.0f && vel[0] == 0.0f);
    assert_int_equal(qo_spline_sample_f32(&sp, INFINITY, pos, vel, acc, NULL), QO_E_NONFINITE);
}

/* BOTH: common/cores.h, one cmocka line per core */
int main(void)
{
    const struct CMUnitTest tests[] = {
        /* both cores */
        BOTH(test_keys_interpolated_exactly),
        BOTH(test_linear_against_double),
        BOTH(test_closed_form),
        BOTH(test_outside_and_end),
        BOTH(test_limits_clamp_and_report),
        /* fixed point only */
        cmocka_unit_test(test_fixed_vs_float_exact_times),
        cmocka_unit_test(test_fixed_vs_float_arbitrary_times),
        cmocka_unit_test(test_fixed_small_move_precision),
        cmocka_unit_test(test_fixed_ends_wrap_limits),
        cmocka_unit_test(test_fixed_edges),
        /* float32 only */
        cmocka_unit_test(test_continuity_at_joins),
        cmocka_unit_test(test_c2_against_double),
        cmocka_unit_test(test_catmull_rom_against_double),
        cmocka_unit_test(test_hermite_quintic_against_double),
        cmocka_unit_test(test_wrap_short_way),
        cmocka_unit_test(test_edges),
        cmocka_unit_test(test_many_joints_keys),
        cmocka_unit_test(test_replan_continues),
        cmocka_unit_test(test_range_overflow),
        cmocka_unit_test(test_f32_nonfinite_time),
    };
    return cmocka_run_group_tests_name("spline", tests, NULL, NULL);
}
