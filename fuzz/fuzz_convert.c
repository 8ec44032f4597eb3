/*
 * fuzz/fuzz_convert.c - qorient/convert.h fed decoded floats. A mode byte chooses a raw
 * matrix or a rotation matrix (from a fuzzed quaternion) perturbed by fuzzed amounts up to
 * ~1e-3, so both the accepting and the refusing paths of the matrix functions are reached.
 * Properties from the header: documented statuses only; on QO_OK outputs finite, unit
 * quaternions unit, matrices orthonormal with det +1, angles in their ranges; on error the
 * documented value (identity, (1,0,0)/0, zero vector).
 */
#include "fuzz_common.h"
#include "qorient/convert.h"
#include "qorient/quat.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

/* max |M^T M - I| and det: the rotation test of the header, in double. */
static double fuzz_convert_ortho_err(const qo_mat3_f32 *m, double *det)
{
    double e = 0.0;
    int i, j, k;
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) {
            double s = 0.0;
            for (k = 0; k < 3; k++) s += (double)m->m[k][i] * m->m[k][j];
            s -= i == j ? 1.0 : 0.0;
            if (fabs(s) > e) e = fabs(s);
        }
    *det = (double)m->m[0][0] * ((double)m->m[1][1] * m->m[2][2] - (double)m->m[1][2] * m->m[2][1])
         - (double)m->m[0][1] * ((double)m->m[1][0] * m->m[2][2] - (double)m->m[1][2] * m->m[2][0])
         + (double)m->m[0][2] * ((double)m->m[1][0] * m->m[2][1] - (double)m->m[1][1] * m->m[2][0]);
    return e;
}

static void fuzz_convert_check_rotation(const qo_mat3_f32 *m, const char *what)
{
    double det, e;
    QO_FUZZ_CHECK(qo_fz_finite_mat3(m), "%s: non-finite matrix", what);
    e = fuzz_convert_ortho_err(m, &det);
    QO_FUZZ_CHECK(e <= 1e-5 && fabs(det - 1.0) <= 1e-5, "%s: not a rotation (|MtM-I| %g, det %.9g)", what, e, det);
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    uint8_t mode = qo_fz_u8(&f);
    qo_quat_f32 q = qo_fz_quat(&f), o;
    qo_vec3_f32 axis = qo_fz_vec3(&f), ax;
    float angle = qo_fz_f32(&f), an;
    qo_mat3_f32 m, r;
    qo_status st;
    int fin_axis = qo_fz_finite_vec3(axis) && isfinite(angle);
    int i, j;

    if (mode & 1u) {
        qo_mat3_f32 base;
        float scale = (mode & 2u) ? 1e-3f : 1e-6f;
        if (qo_mat3_from_quat_f32(q, &base) != QO_OK) base = qo_mat3_identity_f32();
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) {
                float d = qo_fz_f32(&f);
                m.m[i][j] = base.m[i][j] + (isfinite(d) && fabsf(d) <= 1.0f ? d * scale : 0.0f);
            }
    } else {
        m = qo_fz_mat3(&f);
    }

    /* axis-angle -> quaternion */
    st = qo_axis_angle_to_quat_f32(axis, angle, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_DEGENERATE, "from_axis_angle status %d", (int)st);
    QO_FUZZ_CHECK((st == QO_E_NONFINITE) == !fin_axis, "from_axis_angle status %d for finiteness %d", (int)st, fin_axis);
    if (st == QO_OK) QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "from_axis_angle -> " QO_FZ_QFMT, QO_FZ_QARG(o));
    else QO_FUZZ_CHECK(qo_fz_is_identity(o), "from_axis_angle error output");

    /* quaternion -> axis-angle */
    st = qo_axis_angle_from_quat_f32(q, &ax, &an);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_DEGENERATE, "to_axis_angle status %d", (int)st);
    if (st == QO_OK) {
        double la = sqrt((double)ax.x * ax.x + (double)ax.y * ax.y + (double)ax.z * ax.z);
        QO_FUZZ_CHECK(qo_fz_finite_vec3(ax) && fabs(la - 1.0) <= QO_FZ_UNIT_TOL && an >= 0.0f && an <= 3.14159274f,
                      "to_axis_angle " QO_FZ_QFMT " -> (%g %g %g) %.9g", QO_FZ_QARG(q),
                      (double)ax.x, (double)ax.y, (double)ax.z, (double)an);
    } else {
        QO_FUZZ_CHECK(ax.x == 1.0f && ax.y == 0.0f && ax.z == 0.0f && an == 0.0f, "to_axis_angle error output");
    }

    /* rotation vector -> quaternion */
    st = qo_rotvec_to_quat_f32(axis, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE, "from_rotvec status %d", (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "from_rotvec (%g %g %g) -> " QO_FZ_QFMT,
                                   (double)axis.x, (double)axis.y, (double)axis.z, QO_FZ_QARG(o));
    else QO_FUZZ_CHECK(qo_fz_is_identity(o), "from_rotvec error output");

    /* quaternion -> rotation vector, |rv| <= pi */
    st = qo_rotvec_from_quat_f32(q, &ax);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_DEGENERATE, "to_rotvec status %d", (int)st);
    if (st == QO_OK) {
        double l = sqrt((double)ax.x * ax.x + (double)ax.y * ax.y + (double)ax.z * ax.z);
        QO_FUZZ_CHECK(qo_fz_finite_vec3(ax) && l <= 3.14159274 * (1.0 + 4e-7), "to_rotvec " QO_FZ_QFMT " -> |rv| %.9g", QO_FZ_QARG(q), l);
    } else {
        QO_FUZZ_CHECK(ax.x == 0.0f && ax.y == 0.0f && ax.z == 0.0f, "to_rotvec error output");
    }

    /* quaternion -> matrix */
    st = qo_mat3_from_quat_f32(q, &r);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_DEGENERATE, "to_mat3 status %d", (int)st);
    if (st == QO_OK) fuzz_convert_check_rotation(&r, "to_mat3");
    else QO_FUZZ_CHECK(qo_fz_is_identity_mat3(&r), "to_mat3 error output");

    /* matrix -> quaternion, strict: accepted only near a rotation, result reproduces m */
    st = qo_mat3_to_quat_f32(&m, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_NOT_ROTATION, "from_mat3 status %d", (int)st);
    QO_FUZZ_CHECK((st == QO_E_NONFINITE) == !qo_fz_finite_mat3(&m), "from_mat3 status %d", (int)st);
    if (st == QO_OK) {
        double det, e = fuzz_convert_ortho_err(&m, &det), d = 0.0;
        QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL) && o.w >= 0.0f, "from_mat3 -> " QO_FZ_QFMT, QO_FZ_QARG(o));
        QO_FUZZ_CHECK(e <= 1.01e-4 + 1e-6 && det > 0.0, "from_mat3 accepted |MtM-I| %g det %g", e, det);
        if (qo_mat3_from_quat_f32(o, &r) == QO_OK)
            for (i = 0; i < 3; i++)
                for (j = 0; j < 3; j++)
                    if (fabs((double)r.m[i][j] - m.m[i][j]) > d) d = fabs((double)r.m[i][j] - m.m[i][j]);
        QO_FUZZ_CHECK(d <= 2e-4, "from_mat3 result is %g away from the accepted matrix", d);
    } else {
        QO_FUZZ_CHECK(qo_fz_is_identity(o), "from_mat3 error output");
    }

    /* nearest rotation */
    st = qo_mat3_orthonormalize_f32(&m, &r);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_NOT_ROTATION, "orthonormalize status %d", (int)st);
    if (st == QO_OK) fuzz_convert_check_rotation(&r, "orthonormalize");
    else QO_FUZZ_CHECK(qo_fz_is_identity_mat3(&r), "orthonormalize error output");

    st = qo_mat3_to_quat_ortho_f32(&m, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_NOT_ROTATION, "from_mat3_ortho status %d", (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL) && o.w >= 0.0f, "from_mat3_ortho -> " QO_FZ_QFMT, QO_FZ_QARG(o));
    else QO_FUZZ_CHECK(qo_fz_is_identity(o), "from_mat3_ortho error output");

    QO_FUZZ_CHECK(qo_mat3_to_quat_f32(NULL, &o) == QO_E_NULL && qo_fz_is_identity(o), "from_mat3 NULL");
    return 0;
}
