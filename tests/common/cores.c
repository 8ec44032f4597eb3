/* tests/common/cores.c - the two rows of the adapter table of common/cores.h: float32 and
 * Q1.30 fixed point. The wrappers of each concept are written ONCE as a macro over the
 * core's prefix P (f: float32, x: Q1.30) and expanded for both, so the two rows cannot
 * drift apart; only the boundary conversions below differ.
 *
 * Each core provides the same conversions under its prefix P:
 *   P##_q / P##_qb     dq <-> quaternion          P##_a    angle (rad; Q3.28)
 *   P##_v / P##_vb     unit-range vector          P##_ab   angle back
 *   P##_av / P##_avb   angle vector (rad; Q3.28)  P##_db   unit-range scalar back (det, dot, norm)
 *   P##_m / P##_mb     matrix
 *   P##_integ          integrate by an increment (rad, body frame)
 * Adding a concept: a DEFINE_<CONCEPT>_ADAPTERS macro, a <CONCEPT>_FIELDS(P) list of
 * designated initialisers, both added to the two tables (cores.h says where its fields go). */
#include <math.h>
#include <stdint.h>

#include "common/cores.h"
#include "qorient/convert.h"
#include "qorient/convert_fx.h"
#include "qorient/quat.h"
#include "qorient/quat_fx.h"

/* ---- quat: exp, log, mul, conj, rotate, normalize, canonical, angle_between, integrate ---- */

#define DEFINE_QUAT_ADAPTERS(P, SFX, QT, VT, AVT)                                             \
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
    static dq P##_identity(void) { return P##_qb(qo_quat_identity_##SFX()); }                 \
    static double P##_dot(dq a, dq b)                                                         \
    {                                                                                         \
        return P##_db(qo_quat_dot_##SFX(P##_q(a), P##_q(b)));                                 \
    }                                                                                         \
    static double P##_norm(dq q) { return P##_db(qo_quat_norm_##SFX(P##_q(q))); }             \
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
    static qo_status P##_integrate(dq q, ref_vec3 dtheta, dq *out)                            \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = P##_integ(P##_q(q), P##_av(dtheta), &o);                               \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }

#define QUAT_FIELDS(P)                                                                        \
    .exp = P##_exp, .log = P##_log, .mul = P##_mul, .conj = P##_conj,                         \
    .identity = P##_identity, .dot = P##_dot, .norm = P##_norm, .rotate = P##_rotate,         \
    .normalize = P##_normalize, .canonical = P##_canonical,                                   \
    .angle_between = P##_angle_between, .integrate = P##_integrate

/* ---- convert: axis-angle, rotation vector, to/from mat3, the mat3 helpers ------------------ */

#define DEFINE_CONVERT_ADAPTERS(P, SFX, QT, VT, AVT, MT, AT)                                  \
    static qo_status P##_from_axis_angle(ref_vec3 axis, double ang, dq *out)                  \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = qo_axis_angle_to_quat_##SFX(P##_v(axis), P##_a(ang), &o);            \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_to_axis_angle(dq q, ref_vec3 *axis, double *ang)                     \
    {                                                                                         \
        VT ax;                                                                                \
        AT an;                                                                                \
        qo_status st = qo_axis_angle_from_quat_##SFX(P##_q(q), &ax, &an);                       \
        *axis = P##_vb(ax);                                                                   \
        *ang = P##_ab(an);                                                                    \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_from_rotvec(ref_vec3 rv, dq *out)                                    \
    {                                                                                         \
        QT o;                                                                                 \
        qo_status st = qo_rotvec_to_quat_##SFX(P##_av(rv), &o);                             \
        *out = P##_qb(o);                                                                     \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_to_rotvec(dq q, ref_vec3 *out)                                       \
    {                                                                                         \
        AVT o;                                                                                \
        qo_status st = qo_rotvec_from_quat_##SFX(P##_q(q), &o);                                 \
        *out = P##_avb(o);                                                                    \
        return st;                                                                            \
    }                                                                                         \
    static qo_status P##_to_mat3(dq q, ref_mat3 *out)                                         \
    {                                                                                         \
        MT o;                                                                                 \
        qo_status st = qo_mat3_from_quat_##SFX(P##_q(q), &o);                                   \
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
        return P##_from_m(qo_mat3_to_quat_##SFX, m, out);                                   \
    }                                                                                         \
    static qo_status P##_from_mat3_trusted(const ref_mat3 *m, dq *out)                        \
    {                                                                                         \
        return P##_from_m(qo_mat3_to_quat_trusted_##SFX, m, out);                           \
    }                                                                                         \
    static qo_status P##_from_mat3_ortho(const ref_mat3 *m, dq *out)                          \
    {                                                                                         \
        return P##_from_m(qo_mat3_to_quat_ortho_##SFX, m, out);                             \
    }                                                                                         \
    static qo_status P##_orthonormalize(const ref_mat3 *m, ref_mat3 *out)                     \
    {                                                                                         \
        MT cm = P##_m(m), o;                                                                  \
        qo_status st = qo_mat3_orthonormalize_##SFX(&cm, &o);                                 \
        *out = P##_mb(&o);                                                                    \
        return st;                                                                            \
    }                                                                                         \
    static ref_vec3 P##_mat3_mul_vec3(const ref_mat3 *m, ref_vec3 v)                          \
    {                                                                                         \
        MT cm = P##_m(m);                                                                     \
        return P##_vb(qo_mat3_mul_vec3_##SFX(&cm, P##_v(v)));                                 \
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


#define CONVERT_FIELDS(P)                                                                     \
    .from_axis_angle = P##_from_axis_angle, .to_axis_angle = P##_to_axis_angle,               \
    .from_rotvec = P##_from_rotvec, .to_rotvec = P##_to_rotvec, .to_mat3 = P##_to_mat3,       \
    .from_mat3 = P##_from_mat3, .from_mat3_trusted = P##_from_mat3_trusted,                   \
    .from_mat3_ortho = P##_from_mat3_ortho, .orthonormalize = P##_orthonormalize,             \
    .mat3_mul_vec3 = P##_mat3_mul_vec3, .mat3_mul = P##_mat3_mul,                             \
    .mat3_transpose = P##_mat3_transpose, .mat3_identity = P##_mat3_identity,                 \
    .mat3_det = P##_mat3_det

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
#define f_ab f_db
#define f_av f_v
#define f_avb f_vb
/* qo_quat_integrate_f32 takes omega (rad/s) and dt (s): the increment is omega with dt = 1 */
static qo_status f_integ(qo_quat_f32 q, qo_vec3_f32 dtheta, qo_quat_f32 *out)
{
    return qo_quat_integrate_f32(q, dtheta, 1.0f, out);
}
DEFINE_QUAT_ADAPTERS(f, f32, qo_quat_f32, qo_vec3_f32, qo_vec3_f32)
DEFINE_CONVERT_ADAPTERS(f, f32, qo_quat_f32, qo_vec3_f32, qo_vec3_f32, qo_mat3_f32, float)

const core CORE_F32 = {
    .name = "float32", .fixed = 0, .tol_rot = 2e-6, .tol_abs = 1e-6, .tol_ang = 2e-6,
    .big = 1e39, .u_min = -HUGE_VAL, .u_max = HUGE_VAL,
    .u_in = f_u_in, .a_in = f_u_in, .r_in = f_u_in, .q_in = f_q_in,
    QUAT_FIELDS(f), CONVERT_FIELDS(f)
};

/* Q1.30: the boundary rounds to nearest and saturates (ref_to_fixed), the exact value back */
static double x_u_in(double x) { return ref_to_fixed(x, Q30) / Q30; }
static double x_a_in(double x) { return ref_to_fixed(x, Q28) / Q28; }
static double x_r_in(double x) { return ref_to_fixed(x, Q16) / Q16; }
static dq x_q_in(dq q) { return dq_from_x(x_from(q)); }
static qo_quat_q30 x_q(dq q) { return x_from(q); }
static dq x_qb(qo_quat_q30 q) { return dq_from_x(q); }
static qo_q28 x_a(double x) { return ref_to_fixed(x, Q28); }
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
DEFINE_QUAT_ADAPTERS(x, q30, qo_quat_q30, qo_vec3_q30, qo_vec3_q28)
DEFINE_CONVERT_ADAPTERS(x, q30, qo_quat_q30, qo_vec3_q30, qo_vec3_q28, qo_mat3_q30, qo_q28)

const core CORE_Q30 = {
    .name = "Q1.30", .fixed = 1, .tol_rot = 2e-8, .tol_abs = 5e-9, .tol_ang = 2e-8,
    .big = 1e39, .u_min = -2.0, .u_max = 2147483647.0 / Q30,
    .u_in = x_u_in, .a_in = x_a_in, .r_in = x_r_in, .q_in = x_q_in,
    QUAT_FIELDS(x), CONVERT_FIELDS(x)
};

