/*
 * The --fixed paths of `qorient convert` and `qorient slerp`: the numbers read are converted
 * once, at the boundary, to the fixed-point formats (Q1.30 for quaternion, axis and matrix
 * components, Q3.28 for angles in radians), every computation is done by the fixed-point core
 * (quat_fx, convert_fx, euler_fx, interp_fx), and the results are converted back to print.
 * A value that does not fit its format is an error (QO_E_OVERFLOW), never silently clipped -
 * except for directions (a quaternion to normalise, an axis), whose length carries no
 * information: those are first scaled by an exact power of two so their largest component is
 * in [0.5, 1).
 */
#include "cli.h"

#include <math.h>

#include "qorient/convert_fx.h"
#include "qorient/euler_fx.h"
#include "qorient/interp_fx.h"
#include "qorient/quat_fx.h"

#define Q30 1073741824.0
#define Q28 268435456.0

static const double DEG = 3.14159265358979323846 / 180.0;

/* Rounds v * scale to the nearest int32 (ties away from zero). */
static qo_status to_fx(double v, double scale, int32_t *out)
{
    double x;
    *out = 0;
    if (!isfinite(v)) return QO_E_NONFINITE;
    x = round(v * scale);
    if (x < -2147483648.0 || x > 2147483647.0) return QO_E_OVERFLOW;
    *out = (int32_t)x;
    return QO_OK;
}

/* Scales the n numbers of a direction by a power of two so the largest magnitude lies in
 * [0.5, 1) (exact in binary floating point), then converts them to Q1.30. An all-zero vector
 * stays zero (the fixed core then reports it). */
static qo_status dir_to_q30(const double *v, size_t n, int32_t *out)
{
    double m = 0;
    int e;
    size_t i;
    for (i = 0; i < n; i++) {
        if (!isfinite(v[i])) return QO_E_NONFINITE;
        if (fabs(v[i]) > m) m = fabs(v[i]);
    }
    if (m > 0) (void)frexp(m, &e); else e = 0;
    for (i = 0; i < n; i++) {
        qo_status st = to_fx(ldexp(v[i], -e), Q30, &out[i]);
        if (st != QO_OK) return st;
    }
    return QO_OK;
}

static qo_status angle_to_q28(double v, int degrees, qo_q28 *out)
{
    return to_fx(degrees ? v * DEG : v, Q28, out);
}

static qo_status quat_in(const struct rep_spec *r, const double *v, int degrees, qo_quat_q30 *q)
{
    qo_status st;
    *q = qo_quat_identity_q30();
    switch (r->kind) {
    case REP_QUAT: {
        int32_t c[4];
        st = dir_to_q30(v, 4, c);
        if (st != QO_OK) return st;
        q->w = c[0]; q->x = c[1]; q->y = c[2]; q->z = c[3];
        return qo_quat_normalize_q30(*q, q);
    }
    case REP_MATRIX: {
        qo_mat3_q30 m;
        int i;
        for (i = 0; i < 9; i++) {
            /* An entry beyond 1 cannot belong to a rotation: the same answer as the float
             * core's, instead of a format overflow. */
            if (isfinite(v[i]) && fabs(v[i]) > 1.0 + 1e-4) return QO_E_NOT_ROTATION;
            st = to_fx(v[i], Q30, &m.m[i / 3][i % 3]);
            if (st != QO_OK) return st;
        }
        return qo_mat3_to_quat_q30(&m, q);
    }
    case REP_ROTVEC: {
        qo_vec3_q28 rv;
        if ((st = angle_to_q28(v[0], degrees, &rv.x)) != QO_OK) return st;
        if ((st = angle_to_q28(v[1], degrees, &rv.y)) != QO_OK) return st;
        if ((st = angle_to_q28(v[2], degrees, &rv.z)) != QO_OK) return st;
        return qo_rotvec_to_quat_q30(rv, q);
    }
    case REP_AXISANGLE: {
        int32_t c[3];
        qo_vec3_q30 ax;
        qo_q28 a;
        if ((st = dir_to_q30(v, 3, c)) != QO_OK) return st;
        if ((st = angle_to_q28(v[3], degrees, &a)) != QO_OK) return st;
        ax.x = c[0]; ax.y = c[1]; ax.z = c[2];
        return qo_axis_angle_to_quat_q30(ax, a, q);
    }
    case REP_EULER: {
        qo_euler_q28 e;
        if ((st = angle_to_q28(v[0], degrees, &e.a1)) != QO_OK) return st;
        if ((st = angle_to_q28(v[1], degrees, &e.a2)) != QO_OK) return st;
        if ((st = angle_to_q28(v[2], degrees, &e.a3)) != QO_OK) return st;
        return qo_euler_to_quat_q30(r->seq, e, q);
    }
    }
    return QO_E_ARG;
}

qo_status qo_cli_convert_fixed(const struct rep_spec *from, const struct rep_spec *to,
                               const double *v, int degrees, double *o, size_t *n)
{
    double s = degrees ? 1.0 / DEG : 1.0;
    qo_quat_q30 q;
    qo_status st = quat_in(from, v, degrees, &q);
    *n = 0;
    if (st != QO_OK) return st;
    switch (to->kind) {
    case REP_QUAT:
        q = qo_quat_canonical_q30(q);
        o[0] = q.w / Q30; o[1] = q.x / Q30; o[2] = q.y / Q30; o[3] = q.z / Q30;
        *n = 4;
        return QO_OK;
    case REP_MATRIX: {
        qo_mat3_q30 m;
        int i;
        st = qo_mat3_from_quat_q30(q, &m);
        for (i = 0; i < 9; i++) o[i] = m.m[i / 3][i % 3] / Q30;
        *n = 9;
        return st;
    }
    case REP_ROTVEC: {
        qo_vec3_q28 rv;
        st = qo_rotvec_from_quat_q30(q, &rv);
        o[0] = rv.x / Q28 * s; o[1] = rv.y / Q28 * s; o[2] = rv.z / Q28 * s;
        *n = 3;
        return st;
    }
    case REP_AXISANGLE: {
        qo_vec3_q30 ax;
        qo_q28 a;
        st = qo_axis_angle_from_quat_q30(q, &ax, &a);
        o[0] = ax.x / Q30; o[1] = ax.y / Q30; o[2] = ax.z / Q30; o[3] = a / Q28 * s;
        *n = 4;
        return st;
    }
    case REP_EULER: {
        qo_euler_q28 e;
        qo_euler_info_q28 info;
        st = qo_euler_from_quat_q30(q, to->seq, &e, &info);
        o[0] = e.a1 / Q28 * s; o[1] = e.a2 / Q28 * s; o[2] = e.a3 / Q28 * s;
        o[3] = info.locked ? 1.0 : 0.0;
        *n = 4;
        return st;
    }
    }
    return QO_E_ARG;
}

qo_status qo_cli_slerp_fixed(const double *v, double *o)
{
    int32_t a[4], b[4];
    qo_quat_q30 qa, qb, q;
    qo_q30 t;
    qo_status st;
    o[0] = 1; o[1] = o[2] = o[3] = 0;
    if ((st = dir_to_q30(v, 4, a)) != QO_OK) return st;
    if ((st = dir_to_q30(v + 4, 4, b)) != QO_OK) return st;
    if (!isfinite(v[8])) return QO_E_NONFINITE;
    if (v[8] < 0.0 || v[8] > 1.0) return QO_E_RANGE;
    if ((st = to_fx(v[8], Q30, &t)) != QO_OK) return st;
    qa.w = a[0]; qa.x = a[1]; qa.y = a[2]; qa.z = a[3];
    qb.w = b[0]; qb.x = b[1]; qb.y = b[2]; qb.z = b[3];
    st = qo_interp_slerp_q30(qa, qb, t, &q);
    if (st != QO_OK) return st;
    o[0] = q.w / Q30; o[1] = q.x / Q30; o[2] = q.y / Q30; o[3] = q.z / Q30;
    return QO_OK;
}
