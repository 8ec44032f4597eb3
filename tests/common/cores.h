/*
 * tests/common/cores.h - the adapter table that runs ONE test body against both cores
 * (float32 `qo_..._f32` and fixed point `qo_..._q30`), as cglm's TEST_IMPL compiles one body
 * for its two APIs (docs/TESTING.md, "One body for both cores").
 *
 * A body receives a `const core *` through cmocka's prestate (BOTH registers it once per core).
 * The core's wrappers take and return doubles: they round their inputs to what that core takes
 * (float32, or Q1.30 / Q3.28 / Q16.16 rounded to nearest and saturated, common/ref.h), call the
 * library and give the result back exactly. The body forms its inputs in double, passes them
 * through the core's own rounding first (q_in, u_in, a_in, r_in) and computes the reference
 * from those ROUNDED values with the double algebra of tests/common (ref.c, dq.h, dq_interp.h),
 * so each core is judged on exactly what it received, with its own tolerance.
 *
 * Index:
 *   core                         the table: name, tolerances, input rounding, one wrapper per
 *                                operation, grouped by concept (quat, convert)
 *   CORE_F32, CORE_Q30           the two tables (tests/common/cores.c)
 *   ST(c, st_f32, st_fx)         the status a body expects where the cores' documents differ
 *   ON(fn, row)                  one cmocka prestate entry: fn on that row
 *   BOTH(fn)                     two entries: fn on CORE_F32, then CORE_FX (CORE_Q30 here)
 *   FAST(fn), ALL3(fn)           fn on a concept's fixed fast tier CORE_FX_FAST; BOTH then FAST
 *   ID, ZERO_Q, dq_is, q_dist    identity, zero, exact equality, largest component difference
 *   v_make, v_norm, v_dist, v_in, v_rand      vectors (v_in rounds as the core receives)
 *   m_in, m_dist, m_orth_err, m_rand_rot      matrices
 *   clampd, print_m, QFMT, QARG  a clamp, failure printing
 *   EXPECT_OK, qf, vf            for the core-only sections: a status check in a loop, float32
 *                                literals
 *
 * Adding a concept (interp, euler, ...): its fields go in `core` under a comment naming the
 * concept, its wrappers in cores.c in a DEFINE_<CONCEPT>_ADAPTERS(P, SFX, ...) written once for
 * both prefixes, its designated initialisers in a <CONCEPT>_FIELDS(P) macro added to both tables.
 * A body that uses a field must check it is set only if some table leaves it NULL (none does).
 *
 * A concept whose wrappers do not fit this table (Euler angles with their lock band and fast
 * tier, interpolation over key arrays, the spline's plan and Q16.16 samples, the scalar kernels
 * judged in ulp/LSB) keeps a table of its own in its test file, with the same idiom: it defines
 * CORES_OWN_TABLE before including this header, which then gives it only the registration and
 * status macros (ON, BOTH, FAST, ALL3, ST) and the scales; its rows are named CORE_F32 and
 * CORE_FX (and CORE_FX_FAST for a fast tier), and a body reads its row as `const T *c = *state`.
 */
#ifndef QORIENT_TESTS_CORES_H
#define QORIENT_TESTS_CORES_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "common/ref.h"
#include "qorient/status.h"

#define PI REF_PI
#define Q30 REF_Q30
#define Q28 REF_Q28
#define Q16 REF_Q16

/* ---- the idiom of every program of tests/core/, whatever its table ------------------------ */

/* The status a body expects where the cores' documented answers differ. */
#define ST(c, st_f32, st_fx) ((c)->fixed ? (st_fx) : (st_f32))

/* One body, one cmocka entry per row: a failure message starts with the row's name. */
#define ON(fn, row) cmocka_unit_test_prestate(fn, (void *)&(row))
#define BOTH(fn) ON(fn, CORE_F32), ON(fn, CORE_FX)
#define FAST(fn) ON(fn, CORE_FX_FAST)
#define ALL3(fn) BOTH(fn), FAST(fn)

#ifndef CORES_OWN_TABLE
/* ---- the shared table: quat and convert ---------------------------------------------------- */
#include "common/dq_interp.h"

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

    /* quat: quat.h / quat_fx.h */
    qo_status (*exp)(ref_vec3 v, dq *out);
    qo_status (*log)(dq q, ref_vec3 *out);
    dq (*mul)(dq a, dq b);
    dq (*conj)(dq q);
    dq (*identity)(void);
    double (*dot)(dq a, dq b);
    double (*norm)(dq q);
    ref_vec3 (*rotate)(dq q, ref_vec3 v);
    qo_status (*normalize)(dq q, dq *out);
    dq (*canonical)(dq q);
    double (*angle_between)(dq a, dq b);
    qo_status (*integrate)(dq q, ref_vec3 dtheta, dq *out);   /* body frame, rad */

    /* convert: convert.h / convert_fx.h */
    qo_status (*from_axis_angle)(ref_vec3 axis, double ang, dq *out);
    qo_status (*to_axis_angle)(dq q, ref_vec3 *axis, double *ang);
    qo_status (*from_rotvec)(ref_vec3 rv, dq *out);
    qo_status (*to_rotvec)(dq q, ref_vec3 *out);
    qo_status (*to_mat3)(dq q, ref_mat3 *out);
    qo_status (*from_mat3)(const ref_mat3 *m, dq *out);
    qo_status (*from_mat3_trusted)(const ref_mat3 *m, dq *out);
    qo_status (*from_mat3_ortho)(const ref_mat3 *m, dq *out);
    qo_status (*orthonormalize)(const ref_mat3 *m, ref_mat3 *out);
    ref_vec3 (*mat3_mul_vec3)(const ref_mat3 *m, ref_vec3 v);   /* v: unit range */
    ref_mat3 (*mat3_mul)(const ref_mat3 *a, const ref_mat3 *b);
    ref_mat3 (*mat3_transpose)(const ref_mat3 *m);
    ref_mat3 (*mat3_identity)(void);
    double (*mat3_det)(const ref_mat3 *m);
} core;

extern const core CORE_F32;
extern const core CORE_Q30;
#define CORE_FX CORE_Q30

/* ---- helpers of the shared bodies (the PRNG is dq_interp.h's, one state per test file) ---- */

static const dq ID = { 1, 0, 0, 0 };
static const dq ZERO_Q = { 0, 0, 0, 0 };

static inline int dq_is(dq a, dq b) { return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z; }
/* largest component difference */
static inline double q_dist(dq a, dq b)
{
    return fmax(fmax(fabs(a.w - b.w), fabs(a.x - b.x)), fmax(fabs(a.y - b.y), fabs(a.z - b.z)));
}
static inline double v_norm(ref_vec3 v) { return sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
static inline double v_dist(ref_vec3 a, ref_vec3 b)
{
    return fmax(fabs(a.x - b.x), fmax(fabs(a.y - b.y), fabs(a.z - b.z)));
}
static inline ref_vec3 v_make(double x, double y, double z)
{
    ref_vec3 r = { x, y, z };
    return r;
}
/* v as the core receives it: unit-range components (u_in) or angles (a_in) */
static inline ref_vec3 v_in(const core *c, ref_vec3 v, int angle)
{
    double (*f)(double) = angle ? c->a_in : c->u_in;
    return v_make(f(v.x), f(v.y), f(v.z));
}
static inline ref_vec3 v_rand(double lo, double hi)
{
    return v_make(rng_range(lo, hi), rng_range(lo, hi), rng_range(lo, hi));
}
static inline ref_mat3 m_in(const core *c, const ref_mat3 *m)
{
    ref_mat3 r;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) r.m[i][j] = c->u_in(m->m[i][j]);
    return r;
}
static inline double m_dist(const ref_mat3 *a, const ref_mat3 *b)
{
    double d = 0;
    int i, j;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) d = fmax(d, fabs(a->m[i][j] - b->m[i][j]));
    return d;
}
/* max |M^T M - I| */
static inline double m_orth_err(const ref_mat3 *m)
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
static inline ref_mat3 m_rand_rot(const core *c)
{
    ref_mat3 r = ref_quat_to_mat3(rand_unit());
    return m_in(c, &r);
}
static inline double clampd(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }
static inline void print_m(const char *what, const ref_mat3 *m)
{
    print_message("%s: [%.10g %.10g %.10g; %.10g %.10g %.10g; %.10g %.10g %.10g]\n", what,
                  m->m[0][0], m->m[0][1], m->m[0][2], m->m[1][0], m->m[1][1], m->m[1][2],
                  m->m[2][0], m->m[2][1], m->m[2][2]);
}
/* for the core-only sections: a status check inside a loop over cases (names the call and the
 * case on failure), float32 literals */
#define EXPECT_OK(call, n) do { \
        qo_status st_ = (call); \
        if (st_ != QO_OK) fail_msg("%s: status %d in case %d", #call, (int)st_, (int)(n)); \
    } while (0)
static inline qo_quat_f32 qf(float w, float x, float y, float z)
{
    qo_quat_f32 q;
    q.w = w; q.x = x; q.y = y; q.z = z;
    return q;
}
static inline qo_vec3_f32 vf(float x, float y, float z)
{
    qo_vec3_f32 v;
    v.x = x; v.y = y; v.z = z;
    return v;
}
#define QFMT "(%.10g %.10g %.10g %.10g)"
#define QARG(q) (q).w, (q).x, (q).y, (q).z

#endif /* CORES_OWN_TABLE */

#endif
