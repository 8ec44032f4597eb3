/* tests/core/test_twins.c - one test body per concept, run against BOTH cores (float32 and
 * Q1.30 fixed point) through an adapter table, as cglm's TEST_IMPL runs one body against its
 * two APIs (see docs/TESTING.md, "One body for both cores").
 *
 * Each body receives a `core` through cmocka's prestate. The core's adapters take double
 * values, round them to what that core takes (float32, or Q1.30 / Q3.28 / Q16.16 rounded to
 * nearest and saturated, common/ref.h), call the library and give the result back as double.
 * The body forms its inputs in double, passes them through the core's own rounding first
 * (q_in, u_in, a_in), and computes the reference from those ROUNDED values with the double
 * algebra of tests/common (ref.c, dq.h, dq_interp.h), so each core is judged on the inputs it
 * actually received. Fixed seeds; every failure names the core, the case and its inputs.
 *
 * Concepts: slerp_long, slerp_rate, exp/log, mul, conj, rotate, normalize, canonical,
 * angle_between, integrate, axis-angle,
 * rotation vector, to/from mat3 (checked, trusted, ortho), mat3 identity, transpose, mul, det,
 * orthonormalize. Edges in every body: identity, identical and antipodal inputs, zero, and the
 * out-of-range value of each core - NaN/Inf for float32, a saturated input for fixed point -
 * whose documented statuses differ by core and are given per core in the body.
 * (slerp, nlerp, Bezier, spline and Squad have their shared bodies in tests/test_interp_fx.c.) */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "qorient/convert.h"
#include "qorient/convert_fx.h"
#include "qorient/interp.h"
#include "qorient/interp_fx.h"
#include "qorient/quat.h"
#include "qorient/quat_fx.h"

#include "common/dq_interp.h"

#define N_RANDOM 1000
#define PI REF_PI
#define Q30 1073741824.0
#define Q28 268435456.0
#define Q16 65536.0

typedef struct core {
    const char *name;
    int fixed;
    double tol_rot;   /* rad: rotation error of a result (from exact, rounded inputs) */
    double tol_abs;   /* absolute error of a unit-range component or matrix entry */
    double tol_ang;   /* rad: angle-format outputs (log, rotation vector, axis-angle angle) */
    double big;       /* an entry beyond the core's range: Inf in float, saturated in fixed */
    double u_min, u_max;   /* the range of a unit-range value (fixed: [-2, 2 - 2^-30]) */
    double (*u_in)(double x);   /* unit-range scalar as the core receives it */
    double (*a_in)(double x);   /* angle / rotation-vector component as received */
    double (*r_in)(double x);   /* duration (s) as received */
    dq (*q_in)(dq q);           /* quaternion as received */
    qo_status (*slerp_long)(dq a, dq b, double t, dq *out);
    qo_status (*slerp_rate)(dq a, dq b, double dur, ref_vec3 *w);
    qo_status (*exp)(ref_vec3 v, dq *out);
    qo_status (*log)(dq q, ref_vec3 *out);
    dq (*mul)(dq a, dq b);
    dq (*conj)(dq q);
    ref_vec3 (*rotate)(dq q, ref_vec3 v);
    qo_status (*normalize)(dq q, dq *out);
    dq (*canonical)(dq q);
    double (*angle_between)(dq a, dq b);
    qo_status (*integrate)(dq q, ref_vec3 dtheta, dq *out);   /* body frame, rad */
    qo_status (*from_axis_angle)(ref_vec3 axis, double ang, dq *out);
    qo_status (*to_axis_angle)(dq q, ref_vec3 *axis, double *ang);
    qo_status (*from_rotvec)(ref_vec3 rv, dq *out);
    qo_status (*to_rotvec)(dq q, ref_vec3 *out);
    qo_status (*to_mat3)(dq q, ref_mat3 *out);
    qo_status (*from_mat3)(const ref_mat3 *m, dq *out);
    qo_status (*from_mat3_trusted)(const ref_mat3 *m, dq *out);
    qo_status (*from_mat3_ortho)(const ref_mat3 *m, dq *out);
    qo_status (*orthonormalize)(const ref_mat3 *m, ref_mat3 *out);
    ref_mat3 (*mat3_mul)(const ref_mat3 *a, const ref_mat3 *b);
    ref_mat3 (*mat3_transpose)(const ref_mat3 *m);
    ref_mat3 (*mat3_identity)(void);
    double (*mat3_det)(const ref_mat3 *m);
} core;

/* The status a body expects where the cores' documented answers differ. */
#define ST(c, st_f32, st_q30) ((c)->fixed ? (st_q30) : (st_f32))

/* ---- the adapters, written once for both cores ----------------------------------------- */

/* Each core provides the same conversions under its prefix P (f: float32, x: Q1.30):
 *   P##_q / P##_qb     dq <-> quaternion          P##_s    unit-range scalar (t, Q1.30)
 *   P##_v / P##_vb     unit-range vector          P##_a    angle (rad; Q3.28)
 *   P##_av / P##_avb   angle vector (rad; Q3.28)  P##_r    duration (s; Q16.16)
 *   P##_rb             rate vector back (rad/s)   P##_ab   angle back
 *   P##_m / P##_mb     matrix                     P##_db   determinant back
 * and DEFINE_ADAPTERS writes every wrapper from them, the same text for both. */
#define DEFINE_ADAPTERS(P, SFX, QT, VT, AVT, RVT, MT, AT)                                     \
    static qo_status P##_slerp_long(dq a, dq b, double t, dq *out)                           \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = qo_quat_slerp_long_##SFX(P##_q(a), P##_q(b), P##_s(t), &o);           \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_slerp_rate(dq a, dq b, double dur, ref_vec3 *w)                     \
    {                                                                                         \
        RVT o;                                                                                \
        qo_status st = qo_quat_slerp_rate_##SFX(P##_q(a), P##_q(b), P##_r(dur), &o);         \
        *w = P##_rb(o);                                                                       \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_exp(ref_vec3 v, dq *out)                                             \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = qo_quat_exp_##SFX(P##_av(v), &o);                                      \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_log(dq q, ref_vec3 *out)                                             \
    {                                                                                         \
        AVT o;                                                                                \
        qo_status st = qo_quat_log_##SFX(P##_q(q), &o);                                       \
        *out = P##_avb(o);                                                                    \
        return st;                                                                            \
    }                                                                                         \
    static dq P##_mul(dq a, dq b) { return P##_qb(qo_quat_mul_##SFX(P##_q(a), P##_q(b))); }   \
    static dq P##_conj(dq q) { return P##_qb(qo_quat_conj_##SFX(P##_q(q))); }                 \
    static ref_vec3 P##_rotate(dq q, ref_vec3 v)                                              \
    {                                                                                         \
        return P##_vb(qo_quat_rotate_##SFX(P##_q(q), P##_v(v)));                              \
    }                                                                                         \
    static qo_status P##_normalize(dq q, dq *out)                                             \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = qo_quat_normalize_##SFX(P##_q(q), &o);                                 \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static dq P##_canonical(dq q) { return P##_qb(qo_quat_canonical_##SFX(P##_q(q))); }       \
    static double P##_angle_between(dq a, dq b)                                               \
    {                                                                                         \
        return P##_ab(qo_quat_angle_between_##SFX(P##_q(a), P##_q(b)));                       \
    }                                                                                         \
    static qo_status P##_integrate(dq q, ref_vec3 dtheta, dq *out)                          \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = P##_integ(P##_q(q), P##_av(dtheta), &o);                               \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_from_axis_angle(ref_vec3 axis, double ang, dq *out)                  \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = qo_quat_from_axis_angle_##SFX(P##_v(axis), P##_a(ang), &o);            \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_to_axis_angle(dq q, ref_vec3 *axis, double *ang)                     \
    {                                                                                         \
        VT ax;                                                                                \
        AT an;                                                                                \
        qo_status st = qo_quat_to_axis_angle_##SFX(P##_q(q), &ax, &an);                       \
        *axis = P##_vb(ax);                                                                   \
        *ang = P##_ab(an);                                                                    \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_from_rotvec(ref_vec3 rv, dq *out)                                    \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = qo_quat_from_rotvec_##SFX(P##_av(rv), &o);                             \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_to_rotvec(dq q, ref_vec3 *out)                                       \
    {                                                                                         \
        AVT o;                                                                                \
        qo_status st = qo_quat_to_rotvec_##SFX(P##_q(q), &o);                                 \
        *out = P##_avb(o);                                                                    \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_to_mat3(dq q, ref_mat3 *out)                                         \
    {                                                                                         \
        MT o;                                                                                 \
        qo_status st = qo_quat_to_mat3_##SFX(P##_q(q), &o);                                   \
        *out = P##_mb(&o);                                                                    \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_from_m(qo_status (*fn)(const MT *, QT *), const ref_mat3 *m, dq *out) \
    {                                                                                         \
        MT cm = P##_m(m);                                                                     \
        QT o;                                                                                 \
        qo_status st = fn(&cm, &o);                                                           \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_from_mat3(const ref_mat3 *m, dq *out)                                \
    {                                                                                         \
        return P##_from_m(qo_quat_from_mat3_##SFX, m, out);                                   \
    }                                                                                         \
    static qo_status P##_from_mat3_trusted(const ref_mat3 *m, dq *out)                        \
    {                                                                                         \
        return P##_from_m(qo_quat_from_mat3_trusted_##SFX, m, out);                           \
    }                                                                                         \
    static qo_status P##_from_mat3_ortho(const ref_mat3 *m, dq *out)                          \
    {                                                                                         \
        return P##_from_m(qo_quat_from_mat3_ortho_##SFX, m, out);                             \
    }                                                                                         \
    static qo_status P##_orthonormalize(const ref_mat3 *m, ref_mat3 *out)                     \
    {                                                                                         \
        MT cm = P##_m(m), o;                                                                  \
        qo_status st = qo_mat3_orthonormalize_##SFX(&cm, &o);                                 \
        *out = P##_mb(&o);                                                                    \
        return st;                                                                            \
    }                                                                                         \
    static ref_mat3 P##_mat3_mul(const ref_mat3 *a, const ref_mat3 *b)                        \
    {                                                                                         \
        MT ca = P##_m(a), cb = P##_m(b), o = qo_mat3_mul_##SFX(&ca, &cb);                     \
        return P##_mb(&o);                                                                    \
    }                                                                                         \
    static ref_mat3 P##_mat3_transpose(const ref_mat3 *m)                                     \
    {                                                                                         \
        MT cm = P##_m(m), o = qo_mat3_transpose_##SFX(&cm);                                   \
        return P##_mb(&o);                                                                    \
    }                                                                                         \
    static ref_mat3 P##_mat3_identity(void)                                                   \
    {                                                                                         \
        MT o = qo_mat3_identity_##SFX();                                                      \
        return P##_mb(&o);                                                                    \
    }                                                                                         \
    static double P##_mat3_det(const ref_mat3 *m)                                             \
    {                                                                                         \
        MT cm = P##_m(m);                                                                     \
        return P##_db(qo_mat3_det_##SFX(&cm));                                                \
    }

/* The table entries of one core, in the order of `core`, after its header fields. */
#define CORE_FUNCS(P)                                                                         \
    P##_slerp_long, P##_slerp_rate, P##_exp, P##_log, P##_mul, P##_conj, P##_rotate,          \
    P##_normalize, P##_canonical, P##_angle_between, P##_integrate, P##_from_axis_angle, P##_to_axis_angle, P##_from_rotvec, P##_to_rotvec,    \
    P##_to_mat3, P##_from_mat3, P##_from_mat3_trusted, P##_from_mat3_ortho,                   \
    P##_orthonormalize, P##_mat3_mul, P##_mat3_transpose, P##_mat3_identity, P##_mat3_det

/* float32: a double rounded to float, the exact value back */
static double f_u_in(double x) { return (double)(float)x; }
static dq f_q_in(dq q) { return dq_from_f(f_from(q)); }
static qo_quat_f32 f_q(dq q) { return f_from(q); }
static dq f_qb(qo_quat_f32 q) { return dq_from_f(q); }
static float f_s(double x) { return (float)x; }
static qo_vec3_f32 f_v(ref_vec3 v) { return ref_vec3_to_f32(v); }
static ref_vec3 f_vb(qo_vec3_f32 v) { return ref_vec3_from_f32(v); }
static qo_mat3_f32 f_m(const ref_mat3 *m) { return ref_mat3_to_f32(m); }
static ref_mat3 f_mb(const qo_mat3_f32 *m) { return ref_mat3_from_f32(m); }
static double f_db(float d) { return d; }
#define f_a f_s
#define f_r f_s
#define f_ab f_db
#define f_av f_v
#define f_avb f_vb
#define f_rb f_vb
/* qo_quat_integrate_f32 takes omega (rad/s) and dt (s): the increment is omega with dt = 1 */
static qo_status f_integ(qo_quat_f32 q, qo_vec3_f32 dtheta, qo_quat_f32 *out)
{
    return qo_quat_integrate_f32(q, dtheta, 1.0f, out);
}
DEFINE_ADAPTERS(f, f32, qo_quat_f32, qo_vec3_f32, qo_vec3_f32, qo_vec3_f32, qo_mat3_f32, float)

static const core CORE_F32 = {
    "float32", 0, 2e-6, 1e-6, 2e-6, 1e39, -HUGE_VAL, HUGE_VAL,
    f_u_in, f_u_in, f_u_in, f_q_in, CORE_FUNCS(f)
};

/* Q1.30: the boundary rounds to nearest and saturates (ref_to_fixed), the exact value back */
static double x_u_in(double x) { return ref_to_fixed(x, Q30) / Q30; }
static double x_a_in(double x) { return ref_to_fixed(x, Q28) / Q28; }
static double x_r_in(double x) { return ref_to_fixed(x, Q16) / Q16; }
static dq x_q_in(dq q) { return dq_from_x(x_from(q)); }
static qo_quat_q30 x_q(dq q) { return x_from(q); }
static dq x_qb(qo_quat_q30 q) { return dq_from_x(q); }
static qo_q30 x_s(double x) { return ref_to_fixed(x, Q30); }
static qo_q28 x_a(double x) { return ref_to_fixed(x, Q28); }
static qo_q16 x_r(double x) { return ref_to_fixed(x, Q16); }
static double x_ab(qo_q28 a) { return a / Q28; }
static double x_db(qo_q30 d) { return d / Q30; }
static qo_vec3_q30 x_v(ref_vec3 v)
{
    qo_vec3_q30 r = { ref_to_fixed(v.x, Q30), ref_to_fixed(v.y, Q30), ref_to_fixed(v.z, Q30) };
    return r;
}
static qo_vec3_q28 x_av(ref_vec3 v)
{
    qo_vec3_q28 r = { ref_to_fixed(v.x, Q28), ref_to_fixed(v.y, Q28), ref_to_fixed(v.z, Q28) };
    return r;
}
static ref_vec3 x_back(int32_t x, int32_t y, int32_t z, double scale)
{
    ref_vec3 r = { x / scale, y / scale, z / scale };
    return r;
}
static ref_vec3 x_vb(qo_vec3_q30 v) { return x_back(v.x, v.y, v.z, Q30); }
static ref_vec3 x_avb(qo_vec3_q28 v) { return x_back(v.x, v.y, v.z, Q28); }
static ref_vec3 x_rb(qo_vec3_q16 v) { return x_back(v.x, v.y, v.z, Q16); }
static qo_mat3_q30 x_m(const ref_mat3 *m)
{
    qo_mat3_q30 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = ref_to_fixed(m->m[i][j], Q30);
    return r;
}
static ref_mat3 x_mb(const qo_mat3_q30 *m)
{
    ref_mat3 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = m->m[i][j] / Q30;
    return r;
}
#define x_integ qo_quat_integrate_q30
DEFINE_ADAPTERS(x, q30, qo_quat_q30, qo_vec3_q30, qo_vec3_q28, qo_vec3_q16, qo_mat3_q30, qo_q28)

static const core CORE_Q30 = {
    "Q1.30", 1, 2e-8, 5e-9, 2e-8, 1e39, -2.0, 2147483647.0 / Q30,
    x_u_in, x_a_in, x_r_in, x_q_in, CORE_FUNCS(x)
};

/* ---- shared helpers --------------------------------------------------------------------- */

static const dq ID = { 1, 0, 0, 0 };
static const dq ZERO_Q = { 0, 0, 0, 0 };

static int dq_is(dq a, dq b) { return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z; }
static double v_norm(ref_vec3 v) { return sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
static double v_dist(ref_vec3 a, ref_vec3 b)
{
    return fmax(fabs(a.x - b.x), fmax(fabs(a.y - b.y), fabs(a.z - b.z)));
}
static ref_vec3 v_make(double x, double y, double z)
{
    ref_vec3 r = { x, y, z };
    return r;
}
static ref_vec3 v_in(const core *c, ref_vec3 v, int angle)
{
    double (*f)(double) = angle ? c->a_in : c->u_in;
    return v_make(f(v.x), f(v.y), f(v.z));
}
static ref_vec3 v_rand(double lo, double hi)
{
    return v_make(rng_range(lo, hi), rng_range(lo, hi), rng_range(lo, hi));
}
static ref_mat3 m_in(const core *c, const ref_mat3 *m)
{
    ref_mat3 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = c->u_in(m->m[i][j]);
    return r;
}
static double m_dist(const ref_mat3 *a, const ref_mat3 *b)
{
    double d = 0;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) d = fmax(d, fabs(a->m[i][j] - b->m[i][j]));
    return d;
}
/* max |M^T M - I| */
static double m_orth_err(const ref_mat3 *m)
{
    double e = 0;
    int i, j, k;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            double s = 0;
            for (k = 0; k < 3; k++) s += m->m[k][i] * m->m[k][j];
            e = fmax(e, fabs(s - (i == j)));
        }
    }
    return e;
}
/* a random rotation matrix as the core holds it */
static ref_mat3 m_rand_rot(const core *c)
{
    ref_mat3 r = ref_quat_to_mat3(rand_unit());
    return m_in(c, &r);
}
static double clampd(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }
static void print_m(const char *what, const ref_mat3 *m)
{
    print_message("%s: [%.10g %.10g %.10g; %.10g %.10g %.10g; %.10g %.10g %.10g]\n", what,
                  m->m[0][0], m->m[0][1], m->m[0][2], m->m[1][0], m->m[1][1], m->m[1][2],
                  m->m[2][0], m->m[2][1], m->m[2][2]);
}
#define QFMT "(%.10g %.10g %.10g %.10g)"
#define QARG(q) (q).w, (q).x, (q).y, (q).z

/* ---- interpolation: slerp_long, slerp_rate ---------------------------------------------- */

static void test_slerp_long(void **state)
{
    const core *c = *state;
    double worst = 0;
    int n;
    dq o, a, b;
    rng_seed(101);
    for (n = 0; n < N_RANDOM; n++) {
        double t = c->u_in(n < 8 ? n / 7.0 : rng_u()), phi;
        dq bl, want;
        a = c->q_in(rand_unit());
        b = c->q_in(n % 3 ? rand_unit() : rand_axis_rot(rng_range(0.01, 0.1)));
        bl = dq_unit(b);
        if (dq_dot(a, b) > 0) bl = dq_neg(bl);
        phi = dq_angle(a, b);
        if (phi < 0.01) continue;
        want = d_slerp_unit(dq_unit(a), bl, t);
        /* the plane of the long path is known to the inputs' rounding / phi (interp.h) */
        if (c->slerp_long(a, b, t, &o) != QO_OK || rot_err(o, want) > c->tol_rot * (1 + 1 / phi) ||
            dq_dot(o, want) < 0 || fabs(dq_norm(o) - 1) > 4 * c->tol_abs)
            fail_msg("%s slerp_long case %d: a " QFMT " b " QFMT " t %.10g: got " QFMT
                     ", error %.3g rad (tol %.3g)", c->name, n, QARG(a), QARG(b), t, QARG(o),
                     rot_err(o, want), c->tol_rot * (1 + 1 / phi));
        worst = fmax(worst, rot_err(o, want) * phi);
    }
    print_message("%s slerp_long: worst error * phi = %.3g\n", c->name, worst);
    /* edges: identical and antipodal are the same rotation (no long way); exact ends */
    a = c->q_in(rand_unit());
    assert_int_equal(c->slerp_long(a, a, 0.5, &o), QO_E_DEGENERATE);
    assert_true(rot_err(o, a) <= c->tol_rot);
    assert_int_equal(c->slerp_long(a, dq_neg(a), 0.5, &o), QO_E_DEGENERATE);
    assert_int_equal(c->slerp_long(ZERO_Q, a, 0.5, &o), QO_E_DEGENERATE);
    assert_true(dq_is(o, ID));
    assert_int_equal(c->slerp_long(ID, dq_axis_angle(0, 0, 1, 1.0), 1.5, &o), QO_E_RANGE);
    assert_true(dq_is(o, ID));
    /* 180 deg exactly (dot == 0): b kept, the path through b */
    b = dq_axis_angle(0, 1, 0, PI);
    b.w = 0;
    assert_int_equal(c->slerp_long(ID, b, 1.0, &o), QO_OK);
    assert_true(dq_is(o, b));
    /* 90 deg about z the long way: 270 deg about -z, the middle is 135 deg about -z */
    assert_int_equal(c->slerp_long(ID, c->q_in(dq_axis_angle(0, 0, 1, PI / 2)), 0.5, &o), QO_OK);
    assert_true(rot_err(o, dq_axis_angle(0, 0, -1, 0.75 * PI)) <= 10 * c->tol_rot);
    /* out of range: NaN (float32) / a saturated component (fixed: a valid, large input) */
    b = ID;
    b.x = c->big;
    assert_int_equal(c->slerp_long(ID, b, 0.5, &o), ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(fabs(dq_norm(o) - 1) <= 4 * c->tol_abs);
}

static void test_slerp_rate(void **state)
{
    const core *c = *state;
    int n;
    ref_vec3 w;
    dq a, b;
    rng_seed(102);
    for (n = 0; n < N_RANDOM; n++) {
        double dur = c->r_in(pow(10.0, rng_range(-1.0, 1.0)));
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
                                        : c->tol_rot * (1 + v_norm(want))))
            fail_msg("%s slerp_rate case %d: a " QFMT " b " QFMT " dur %.10g: (%.9g %.9g %.9g)"
                     " want (%.9g %.9g %.9g)", c->name, n, QARG(a), QARG(b), dur, w.x, w.y, w.z,
                     want.x, want.y, want.z);
    }
    /* identical and antipodal: no motion, exactly */
    a = c->q_in(rand_unit());
    assert_int_equal(c->slerp_rate(a, a, 1.0, &w), QO_OK);
    assert_true(v_norm(w) <= c->tol_rot);
    assert_int_equal(c->slerp_rate(a, dq_neg(a), 1.0, &w), QO_OK);
    assert_true(v_norm(w) <= c->tol_rot);
    /* 90 deg about x in 0.5 s: pi rad/s about x */
    assert_int_equal(c->slerp_rate(ID, c->q_in(dq_axis_angle(1, 0, 0, PI / 2)), 0.5, &w), QO_OK);
    assert_true(fabs(w.x - PI) <= 2e-5 && fabs(w.y) <= 2e-5 && fabs(w.z) <= 2e-5);
    w = v_make(9, 9, 9);
    assert_int_equal(c->slerp_rate(ID, ZERO_Q, 1.0, &w), QO_E_DEGENERATE);
    assert_true(v_norm(w) == 0);
    w = v_make(9, 9, 9);
    assert_int_equal(c->slerp_rate(ID, a, 0.0, &w), QO_E_RANGE);
    assert_true(v_norm(w) == 0);
    assert_int_equal(c->slerp_rate(ID, a, -1.0, &w), QO_E_RANGE);
    /* a duration so short the rate overflows the format (float: 1e-39 s is subnormal) */
    w = v_make(9, 9, 9);
    assert_int_equal(c->slerp_rate(ID, dq_axis_angle(0, 1, 0, 3.0), c->fixed ? 1 / Q16 : 1e-39, &w),
                     QO_E_RANGE);
    assert_true(v_norm(w) == 0);
    /* out of range duration: Inf (float32) / saturated (fixed: 32768 s, a valid slow rate) */
    assert_int_equal(c->slerp_rate(ID, dq_axis_angle(0, 1, 0, 1.0), c->big, &w),
                     ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(v_norm(w) <= 1e-4);
}

/* ---- quaternion algebra: exp/log, mul, conj, rotate, normalize -------------------------- */

static void test_exp_log(void **state)
{
    const core *c = *state;
    int n;
    dq o;
    ref_vec3 v, l;
    rng_seed(103);
    for (n = 0; n < N_RANDOM; n++) {
        /* |v| up to pi (every rotation), down to 1e-7 */
        ref_vec3 d = v_rand(-1, 1);
        double s = (n % 4 ? rng_range(0, PI) : pow(10.0, rng_range(-7, -2))) / v_norm(d);
        dq p, want, q;
        v = v_in(c, v_make(d.x * s, d.y * s, d.z * s), 1);
        p.w = 0; p.x = v.x; p.y = v.y; p.z = v.z;
        want = dq_exp(p);
        if (c->exp(v, &o) != QO_OK || dist4(o, want) > 2 * c->tol_abs)
            fail_msg("%s exp case %d: v (%.10g %.10g %.10g) got " QFMT " error %.3g", c->name,
                     n, v.x, v.y, v.z, QARG(o), dist4(o, want));
        q = c->q_in(dq_scale(rand_unit(), rng_range(0.3, 1.9)));
        want = dq_log(dq_unit(q));
        if (c->log(q, &l) != QO_OK || v_dist(l, v_make(want.x, want.y, want.z)) > c->tol_ang)
            fail_msg("%s log case %d: q " QFMT " got (%.10g %.10g %.10g) want (%.10g %.10g %.10g)",
                     c->name, n, QARG(q), l.x, l.y, l.z, want.x, want.y, want.z);
    }
    assert_int_equal(c->exp(v_make(0, 0, 0), &o), QO_OK);
    assert_true(dq_is(o, ID));
    assert_int_equal(c->log(ID, &l), QO_OK);
    assert_true(v_norm(l) == 0);
    /* -1: 2 pi about the documented axis x */
    assert_int_equal(c->log(dq_neg(ID), &l), QO_OK);
    assert_true(fabs(l.x - PI) <= c->tol_ang && l.y == 0 && l.z == 0);
    /* antipodal inputs give the same rotation: logs pi/2 apart in length, opposite axes */
    o = c->q_in(dq_axis_angle(1, 2, 3, 1.0));
    assert_int_equal(c->log(o, &v), QO_OK);
    assert_int_equal(c->log(dq_neg(o), &l), QO_OK);
    assert_true(fabs(v_norm(v) + v_norm(l) - PI) <= 2 * c->tol_ang);
    l = v_make(9, 9, 9);
    assert_int_equal(c->log(ZERO_Q, &l), QO_E_DEGENERATE);
    assert_true(v_norm(l) == 0);
    /* out of range: Inf (float32) / saturated Q3.28 component (~8 rad, fixed: QO_E_RANGE) */
    assert_int_equal(c->exp(v_make(c->big, 0, 0), &o), ST(c, QO_E_NONFINITE, QO_E_RANGE));
    assert_true(dq_is(o, ID));
}

static void test_mul_conj_normalize(void **state)
{
    const core *c = *state;
    int n;
    dq o;
    rng_seed(104);
    for (n = 0; n < N_RANDOM; n++) {
        dq a = c->q_in(rand_unit()), b = c->q_in(rand_unit());
        dq s = c->q_in(dq_scale(rand_unit(), pow(10.0, rng_range(-6, 0.2))));
        dq want = dq_mul(a, b);
        o = c->mul(a, b);
        if (dist4(o, want) > 2 * c->tol_abs)
            fail_msg("%s mul case %d: a " QFMT " b " QFMT " error %.3g", c->name, n, QARG(a),
                     QARG(b), dist4(o, want));
        if (!dq_is(c->conj(a), dq_conj(a)))
            fail_msg("%s conj case %d: a " QFMT, c->name, n, QARG(a));
        want = dq_unit(s);
        if (c->normalize(s, &o) != QO_OK || dist4(o, want) > 2 * c->tol_abs)
            fail_msg("%s normalize case %d: q " QFMT " got " QFMT, c->name, n, QARG(s), QARG(o));
    }
    /* identity is neutral; q (-q) is the identity rotation with w = -1 */
    o = c->q_in(rand_unit());
    assert_true(dist4(c->mul(ID, o), o) <= c->tol_abs);
    assert_true(rot_err(c->mul(o, dq_neg(dq_conj(o))), ID) <= 4 * c->tol_rot);
    assert_int_equal(c->normalize(ZERO_Q, &o), QO_E_DEGENERATE);
    assert_true(dq_is(o, ID));
    /* out of range: Inf (float32) / every component saturated (fixed: normalises) */
    o.w = o.x = o.y = o.z = c->big;
    assert_int_equal(c->normalize(o, &o), ST(c, QO_E_NONFINITE, QO_OK));
    if (c->fixed) {
        dq half = { 0.5, 0.5, 0.5, 0.5 };
        assert_true(dist4(o, half) <= 2 * c->tol_abs);
    }
    /* a product beyond the format saturates in fixed point (float: exact, 4) */
    o.w = o.x = o.y = o.z = c->u_in(1.0);
    o = c->mul(o, dq_conj(o));
    assert_true(fabs(o.w - fmin(4.0, c->u_max)) <= c->tol_abs);
}

static void test_canonical_angle_integrate(void **state)
{
    const core *c = *state;
    int n;
    dq o;
    rng_seed(111);
    for (n = 0; n < N_RANDOM; n++) {
        dq a = c->q_in(rand_unit()), b = c->q_in(n % 4 ? rand_unit() : rand_axis_rot(1e-5));
        ref_vec3 d = v_in(c, v_rand(-0.5, 0.5), 1);
        dq p = { 0, d.x / 2, d.y / 2, d.z / 2 }, want;
        double ang = ref_quat_angle_between(a, b);
        o = c->canonical(a);
        if (!dq_is(o, ref_quat_canonical(a)))
            fail_msg("%s canonical case %d: " QFMT " got " QFMT, c->name, n, QARG(a), QARG(o));
        if (fabs(c->angle_between(a, b) - ang) > 2 * c->tol_ang ||
            c->angle_between(a, dq_neg(b)) != c->angle_between(a, b))
            fail_msg("%s angle_between case %d: a " QFMT " b " QFMT " got %.12g want %.12g",
                     c->name, n, QARG(a), QARG(b), c->angle_between(a, b), ang);
        want = dq_unit(dq_mul(a, dq_exp(p)));
        if (c->integrate(a, d, &o) != QO_OK || dist4(o, want) > 4 * c->tol_abs)
            fail_msg("%s integrate case %d: q " QFMT " dtheta (%.10g %.10g %.10g) error %.3g",
                     c->name, n, QARG(a), d.x, d.y, d.z, dist4(o, want));
    }
    /* identical: 0 (exactly in fixed point, as quat_fx.h says; float32 to rounding);
     * antipodal: the same rotation, 0 too; -1 canonicalises to 1 */
    o = c->q_in(rand_unit());
    assert_true(c->angle_between(o, o) <= (c->fixed ? 0.0 : c->tol_ang));
    assert_true(c->angle_between(o, dq_neg(o)) <= c->tol_ang);
    assert_true(dq_is(c->canonical(dq_neg(ID)), ID));
    /* w == 0: the first non-zero of x, y, z made positive */
    {
        dq h = { 0, 0, -0.5, 0.5 }, hc = { 0, 0, 0.5, -0.5 };
        assert_true(dq_is(c->canonical(h), hc));
    }
    assert_int_equal(c->integrate(ID, v_make(0, 0, 0), &o), QO_OK);
    assert_true(dq_is(o, ID));
    assert_int_equal(c->integrate(ZERO_Q, v_make(0.1, 0, 0), &o), QO_E_DEGENERATE);
    assert_true(dq_is(o, ID));
    /* out of range: Inf (float32) / a saturated Q3.28 increment (fixed: ~8 rad, a valid turn) */
    assert_int_equal(c->integrate(ID, v_make(c->big, 0, 0), &o), ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(fabs(dq_norm(o) - 1) <= 4 * c->tol_abs);
}

static void test_rotate(void **state)
{
    const core *c = *state;
    int n;
    ref_vec3 o;
    rng_seed(105);
    for (n = 0; n < N_RANDOM; n++) {
        dq q = c->q_in(rand_unit());
        ref_vec3 v = v_in(c, v_rand(-0.577, 0.577), 0), want = ref_quat_rotate(q, v);
        o = c->rotate(q, v);
        if (v_dist(o, want) > 4 * c->tol_abs)
            fail_msg("%s rotate case %d: q " QFMT " v (%.10g %.10g %.10g) error %.3g", c->name,
                     n, QARG(q), v.x, v.y, v.z, v_dist(o, want));
        /* q and -q are the same rotation */
        if (v_dist(c->rotate(dq_neg(q), v), o) > 2 * c->tol_abs)
            fail_msg("%s rotate case %d: -q differs", c->name, n);
    }
    o = c->rotate(ID, v_make(0.5, -0.25, 0.125));
    assert_true(o.x == 0.5 && o.y == -0.25 && o.z == 0.125);
    /* 90 deg about z takes x to y */
    o = c->rotate(c->q_in(dq_axis_angle(0, 0, 1, PI / 2)), v_make(1, 0, 0));
    assert_true(fabs(o.x) <= 4 * c->tol_abs && fabs(o.y - 1) <= 4 * c->tol_abs);
}

/* ---- conversions: axis-angle, rotation vector --------------------------------------------- */

static void test_axis_angle(void **state)
{
    const core *c = *state;
    int n;
    dq o;
    ref_vec3 ax;
    double ang;
    rng_seed(106);
    for (n = 0; n < N_RANDOM; n++) {
        ref_vec3 axis = v_in(c, v_rand(-1, 1), 0);
        double a = c->a_in(rng_range(-PI, PI));
        dq want = ref_quat_from_axis_angle(axis, a), q, back;
        if (v_norm(axis) < 1e-3) continue;
        if (c->from_axis_angle(axis, a, &o) != QO_OK || dist4(o, want) > 4 * c->tol_abs)
            fail_msg("%s from_axis_angle case %d: axis (%.10g %.10g %.10g) angle %.10g error %.3g",
                     c->name, n, axis.x, axis.y, axis.z, a, dist4(o, want));
        q = c->q_in(dq_scale(rand_unit(), rng_range(0.5, 1.5)));
        if (c->to_axis_angle(q, &ax, &ang) != QO_OK || ang < 0 || ang > PI + c->tol_ang)
            fail_msg("%s to_axis_angle case %d: q " QFMT " angle %.10g", c->name, n, QARG(q), ang);
        back = ref_quat_from_axis_angle(ax, ang);
        if (rot_err(back, q) > 4 * c->tol_ang || fabs(v_norm(ax) - 1) > 4 * c->tol_abs)
            fail_msg("%s to_axis_angle case %d: q " QFMT " gives a rotation %.3g rad off",
                     c->name, n, QARG(q), rot_err(back, q));
    }
    /* identity: axis (1, 0, 0), angle 0; -identity the same */
    assert_int_equal(c->to_axis_angle(ID, &ax, &ang), QO_OK);
    assert_true(ang == 0 && ax.x == 1 && ax.y == 0 && ax.z == 0);
    assert_int_equal(c->to_axis_angle(dq_neg(ID), &ax, &ang), QO_OK);
    assert_true(ang == 0 && ax.x == 1);
    assert_int_equal(c->to_axis_angle(ZERO_Q, &ax, &ang), QO_E_DEGENERATE);
    assert_true(ang == 0 && ax.x == 1 && ax.y == 0 && ax.z == 0);
    assert_int_equal(c->from_axis_angle(v_make(0, 0, 0), 1.0, &o), QO_E_DEGENERATE);
    assert_true(dq_is(o, ID));
    /* out of range axis: Inf (float32) / saturated (fixed: a valid long axis) */
    assert_int_equal(c->from_axis_angle(v_make(c->big, 0, 0), 1.0, &o),
                     ST(c, QO_E_NONFINITE, QO_OK));
    if (c->fixed) assert_true(rot_err(o, dq_axis_angle(1, 0, 0, 1.0)) <= 4 * c->tol_ang);
}

static void test_rotvec(void **state)
{
    const core *c = *state;
    int n;
    dq o;
    ref_vec3 rv;
    rng_seed(107);
    for (n = 0; n < N_RANDOM; n++) {
        ref_vec3 d = v_rand(-1, 1);
        double s = (n % 4 ? rng_range(0, PI) : pow(10.0, rng_range(-7, -2))) / v_norm(d);
        ref_vec3 r = v_in(c, v_make(d.x * s, d.y * s, d.z * s), 1);
        dq want = ref_quat_from_axis_angle(r, v_norm(r)), q, back;
        if (c->from_rotvec(r, &o) != QO_OK || dist4(o, want) > 4 * c->tol_abs)
            fail_msg("%s from_rotvec case %d: rv (%.10g %.10g %.10g) error %.3g", c->name, n,
                     r.x, r.y, r.z, dist4(o, want));
        q = c->q_in(rand_unit());
        if (c->to_rotvec(q, &rv) != QO_OK || v_norm(rv) > PI + 2 * c->tol_ang)
            fail_msg("%s to_rotvec case %d: q " QFMT, c->name, n, QARG(q));
        back = v_norm(rv) > 0 ? ref_quat_from_axis_angle(rv, v_norm(rv)) : ID;
        if (rot_err(back, q) > 4 * c->tol_ang)
            fail_msg("%s to_rotvec case %d: q " QFMT " gives a rotation %.3g rad off", c->name,
                     n, QARG(q), rot_err(back, q));
    }
    assert_int_equal(c->from_rotvec(v_make(0, 0, 0), &o), QO_OK);
    assert_true(dq_is(o, ID));
    /* q and -q: the same rotation vector (canonical sign) */
    o = c->q_in(dq_axis_angle(1, -2, 0.5, 2.0));
    assert_int_equal(c->to_rotvec(o, &rv), QO_OK);
    {
        ref_vec3 rn;
        assert_int_equal(c->to_rotvec(dq_neg(o), &rn), QO_OK);
        assert_true(v_dist(rv, rn) <= 2 * c->tol_ang);
    }
    rv = v_make(9, 9, 9);
    assert_int_equal(c->to_rotvec(ZERO_Q, &rv), QO_E_DEGENERATE);
    assert_true(v_norm(rv) == 0);
    /* out of range: Inf (float32) / saturated Q3.28 (fixed: |rv| ~ 8 rad, a valid turn) */
    assert_int_equal(c->from_rotvec(v_make(c->big, 0, 0), &o), ST(c, QO_E_NONFINITE, QO_OK));
    assert_true(fabs(dq_norm(o) - 1) <= 4 * c->tol_abs);
}

/* ---- conversions: to/from mat3 ------------------------------------------------------------ */

static void test_mat3_quat(void **state)
{
    const core *c = *state;
    int n;
    dq o;
    ref_mat3 m;
    rng_seed(108);
    for (n = 0; n < N_RANDOM; n++) {
        dq q = c->q_in(n % 5 ? rand_unit() : rand_axis_rot(rng_range(PI - 1e-3, PI)));
        ref_mat3 want = ref_quat_to_mat3(q), mr;
        dq wq;
        if (c->to_mat3(q, &m) != QO_OK || m_dist(&m, &want) > 4 * c->tol_abs)
            fail_msg("%s to_mat3 case %d: q " QFMT " error %.3g", c->name, n, QARG(q),
                     m_dist(&m, &want));
        mr = m_in(c, &want);
        wq = ref_mat3_to_quat(&mr);
        if (c->from_mat3(&mr, &o) != QO_OK || rot_err(o, wq) > 4 * c->tol_rot || o.w < 0)
            fail_msg("%s from_mat3 case %d: q " QFMT " got " QFMT, c->name, n, QARG(q), QARG(o));
        if (c->from_mat3_trusted(&mr, &o) != QO_OK || rot_err(o, wq) > 4 * c->tol_rot || o.w < 0)
            fail_msg("%s from_mat3_trusted case %d: q " QFMT " got " QFMT, c->name, n, QARG(q),
                     QARG(o));
        if (c->from_mat3_ortho(&mr, &o) != QO_OK || rot_err(o, wq) > 4 * c->tol_rot || o.w < 0)
            fail_msg("%s from_mat3_ortho case %d: q " QFMT " got " QFMT, c->name, n, QARG(q),
                     QARG(o));
    }
    /* identity both ways; q and -q give the same matrix */
    assert_int_equal(c->to_mat3(ID, &m), QO_OK);
    assert_true(m_dist(&m, (const ref_mat3[]){ c->mat3_identity() }) == 0);
    assert_int_equal(c->from_mat3(&m, &o), QO_OK);
    assert_true(dq_is(o, ID));
    {
        ref_mat3 mn;
        o = c->q_in(rand_unit());
        assert_int_equal(c->to_mat3(o, &m), QO_OK);
        assert_int_equal(c->to_mat3(dq_neg(o), &mn), QO_OK);
        assert_true(m_dist(&m, &mn) <= c->tol_abs);
    }
    assert_int_equal(c->to_mat3(ZERO_Q, &m), QO_E_DEGENERATE);
    assert_true(m_dist(&m, (const ref_mat3[]){ c->mat3_identity() }) == 0);
    /* not rotations: scaled by 1.01, a reflection, zero */
    m = c->mat3_identity();
    m.m[1][1] = c->u_in(1.01);
    assert_int_equal(c->from_mat3(&m, &o), QO_E_NOT_ROTATION);
    assert_true(dq_is(o, ID));
    m.m[1][1] = -1;
    assert_int_equal(c->from_mat3(&m, &o), QO_E_NOT_ROTATION);
    memset(&m, 0, sizeof m);
    assert_int_equal(c->from_mat3(&m, &o), QO_E_NOT_ROTATION);
    /* out of range entries: Inf (float32) / saturated (fixed: scaled, not a rotation) */
    m = c->mat3_identity();
    m.m[0][0] = c->big;
    assert_int_equal(c->from_mat3(&m, &o), ST(c, QO_E_NONFINITE, QO_E_NOT_ROTATION));
    assert_true(dq_is(o, ID));
}

/* ---- mat3 helpers: identity, transpose, mul, det, orthonormalize -------------------------- */

static void test_mat3_ops(void **state)
{
    const core *c = *state;
    int n, i, j;
    ref_mat3 o, id = c->mat3_identity();
    rng_seed(109);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) assert_true(id.m[i][j] == (i == j));
    for (n = 0; n < N_RANDOM; n++) {
        ref_mat3 a = m_rand_rot(c), b = m_rand_rot(c), want = ref_mat3_mul(&a, &b), g, t;
        /* general matrices, entries up to 1.9: products saturate in fixed point */
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) g.m[i][j] = c->u_in(rng_range(-1.9, 1.9));
        o = c->mat3_mul(&a, &b);
        if (m_dist(&o, &want) > 2 * c->tol_abs)
            fail_msg("%s mat3_mul case %d: error %.3g", c->name, n, m_dist(&o, &want));
        want = ref_mat3_mul(&g, &a);
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) want.m[i][j] = clampd(want.m[i][j], c->u_min, c->u_max);
        o = c->mat3_mul(&g, &a);
        if (m_dist(&o, &want) > 4 * c->tol_abs * (1 + 3 * 1.9)) {
            print_m("g", &g);
            fail_msg("%s mat3_mul (general) case %d: error %.3g", c->name, n, m_dist(&o, &want));
        }
        t = c->mat3_transpose(&g);
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) assert_true(t.m[i][j] == g.m[j][i]);
        /* det: 1 for a rotation, -1 for a reflection, the general value (clamped) */
        if (fabs(c->mat3_det(&a) - 1) > 4 * c->tol_abs)
            fail_msg("%s mat3_det rotation case %d: %.12g", c->name, n, c->mat3_det(&a));
        for (j = 0; j < 3; j++) a.m[1][j] = -a.m[1][j];
        if (fabs(c->mat3_det(&a) + 1) > 4 * c->tol_abs)
            fail_msg("%s mat3_det reflection case %d: %.12g", c->name, n, c->mat3_det(&a));
        {
            double wd = clampd(ref_mat3_det(&g), c->u_min, c->u_max), gd = c->mat3_det(&g);
            /* float32: the cofactor expansion cancels (|terms| up to ~7 x 6e-8);
             * fixed: Q3.28 cofactors for entries beyond 1 + 1/16 (<= ~8 LSB) */
            if (fabs(gd - wd) > (c->fixed ? 16 / Q30 : 1e-5)) {
                print_m("g", &g);
                fail_msg("%s mat3_det case %d: %.12g want %.12g", c->name, n, gd, wd);
            }
        }
    }
    /* edges: det of I, of zero, of the largest entries */
    assert_true(c->mat3_det(&id) == 1);
    memset(&o, 0, sizeof o);
    assert_true(c->mat3_det(&o) == 0);
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) o.m[i][j] = c->u_in(i == j ? c->big : 0);
    /* fixed: 8 saturates; float32: Inf * 0 in the cofactors, not finite */
    if (c->fixed) assert_true(c->mat3_det(&o) == c->u_max);
    else assert_true(!isfinite(c->mat3_det(&o)));
}

static void test_orthonormalize(void **state)
{
    const core *c = *state;
    int n, i, j;
    ref_mat3 o;
    dq q;
    double worst = 0;
    rng_seed(110);
    for (n = 0; n < N_RANDOM; n++) {
        /* a rotation, drifted (noise 1e-6 .. 0.1) and uniformly scaled (0.3 .. 1.7) */
        ref_mat3 m = ref_quat_to_mat3(rand_unit()), want;
        double noise = pow(10.0, rng_range(-6, -1)), k = rng_range(0.3, 1.7), e;
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) m.m[i][j] = k * m.m[i][j] + rng_range(-noise, noise);
        m = m_in(c, &m);
        want = ref_mat3_nearest_rotation(&m);
        if (c->orthonormalize(&m, &o) != QO_OK) {
            print_m("m", &m);
            fail_msg("%s orthonormalize case %d: refused", c->name, n);
        }
        e = ref_mat3_rotation_distance(&o, &want);
        worst = fmax(worst, e);
        if (e > 4 * c->tol_rot || m_orth_err(&o) > 8 * c->tol_abs) {
            print_m("m", &m);
            fail_msg("%s orthonormalize case %d: %.3g rad from the nearest rotation, "
                     "orthogonality error %.3g", c->name, n, e, m_orth_err(&o));
        }
        if (c->from_mat3_ortho(&m, &q) != QO_OK ||
            rot_err(q, ref_mat3_to_quat(&want)) > 4 * c->tol_rot || q.w < 0)
            fail_msg("%s from_mat3_ortho case %d: " QFMT, c->name, n, QARG(q));
    }
    print_message("%s orthonormalize: worst %.3g rad from the nearest rotation\n", c->name, worst);
    /* a rotation comes back (within rounding); m and out may alias */
    o = m_rand_rot(c);
    {
        ref_mat3 r;
        assert_int_equal(c->orthonormalize(&o, &r), QO_OK);
        assert_true(m_dist(&o, &r) <= 4 * c->tol_abs);
        assert_int_equal(c->orthonormalize(&o, &o), QO_OK);
        assert_true(m_dist(&o, &r) == 0);
    }
    /* refused: zero, rank 2, a reflection; the output is the identity */
    {
        ref_mat3 r;
        memset(&o, 0, sizeof o);
        assert_int_equal(c->orthonormalize(&o, &r), QO_E_NOT_ROTATION);
        assert_true(m_dist(&r, (const ref_mat3[]){ c->mat3_identity() }) == 0);
        o = c->mat3_identity();
        o.m[2][2] = 0;
        assert_int_equal(c->orthonormalize(&o, &r), QO_E_NOT_ROTATION);
        o.m[2][2] = -1;
        assert_int_equal(c->orthonormalize(&o, &r), QO_E_NOT_ROTATION);
        assert_int_equal(c->from_mat3_ortho(&o, &q), QO_E_NOT_ROTATION);
        assert_true(dq_is(q, ID));
    }
    /* out of range: Inf (float32) / every entry saturated (fixed: rank 1, refused) */
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) o.m[i][j] = c->u_in(c->big);
    assert_int_equal(c->orthonormalize(&o, &o), ST(c, QO_E_NONFINITE, QO_E_NOT_ROTATION));
    /* a saturated diagonal (fixed: 2 - 2^-30 times the identity, a scaled rotation) */
    o = c->mat3_identity();
    for (i = 0; i < 3; i++) o.m[i][i] = c->u_in(fmin(c->u_max, 1.9));
    assert_int_equal(c->orthonormalize(&o, &o), QO_OK);
    assert_true(m_dist(&o, (const ref_mat3[]){ c->mat3_identity() }) <= 4 * c->tol_abs);
}

#define BOTH(fn) cmocka_unit_test_prestate(fn, (void *)&CORE_F32), \
                 cmocka_unit_test_prestate(fn, (void *)&CORE_Q30)

int main(void)
{
    const struct CMUnitTest tests[] = {
        BOTH(test_slerp_long),
        BOTH(test_slerp_rate),
        BOTH(test_exp_log),
        BOTH(test_mul_conj_normalize),
        BOTH(test_canonical_angle_integrate),
        BOTH(test_rotate),
        BOTH(test_axis_angle),
        BOTH(test_rotvec),
        BOTH(test_mat3_quat),
        BOTH(test_mat3_ops),
        BOTH(test_orthonormalize),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
