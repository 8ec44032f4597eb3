/*
 * fuzz/fuzz_quat.c - qorient/quat.h fed decoded floats (raw bit patterns and the edge values
 * of fuzz_common.h: NaN, +-Inf, +-0, denormals, FLT_MAX...). Properties from the header:
 * every status is a qo_status the function documents; on QO_OK every output is finite (and
 * unit where promised); on error the output is the documented error value.
 */
#include "fuzz_common.h"
#include "qorient/quat.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    qo_quat_f32 a = qo_fz_quat(&f), b = qo_fz_quat(&f), o, un;
    qo_vec3_f32 v = qo_fz_vec3(&f), rv, av;
    float dt = qo_fz_f32(&f);
    int fin = qo_fz_finite_quat(a);
    double na = qo_fz_norm_quat(a);
    float n;
    qo_status st, stn;

    /* norm: overflow-safe; agrees with the double norm to float rounding */
    n = qo_quat_norm_f32(a);
    if (fin) {
        if (na <= (double)FLT_MAX * 0.999999)
            QO_FUZZ_CHECK(isfinite(n) && fabs((double)n - na) <= 2e-7 * na + 1e-45,
                          "norm " QO_FZ_QFMT " = %.9g, double %.17g", QO_FZ_QARG(a), (double)n, na);
    } else {
        QO_FUZZ_CHECK(!isfinite(n) || n != n, "norm of non-finite " QO_FZ_QFMT " = %.9g", QO_FZ_QARG(a), (double)n);
    }

    /* normalize */
    stn = qo_quat_normalize_f32(a, &un);
    QO_FUZZ_CHECK(stn == QO_OK || stn == QO_E_NONFINITE || stn == QO_E_DEGENERATE,
                  "normalize status %d", (int)stn);
    QO_FUZZ_CHECK((stn == QO_E_NONFINITE) == !fin, "normalize " QO_FZ_QFMT " status %d", QO_FZ_QARG(a), (int)stn);
    if (stn == QO_OK) {
        QO_FUZZ_CHECK(qo_fz_unit_quat(un, QO_FZ_UNIT_TOL), "normalize " QO_FZ_QFMT " -> " QO_FZ_QFMT,
                      QO_FZ_QARG(a), QO_FZ_QARG(un));
    } else {
        QO_FUZZ_CHECK(qo_fz_is_identity(un), "normalize error output not identity");
    }
    if (fin && na > 0.0 && stn == QO_E_DEGENERATE)
        QO_FUZZ_CHECK(na < 1e-37, "normalize " QO_FZ_QFMT " refused a norm of %g", QO_FZ_QARG(a), na);
    QO_FUZZ_CHECK(qo_quat_normalize_f32(a, NULL) == QO_E_NULL, "normalize NULL");

    /* inverse */
    st = qo_quat_inverse_f32(a, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_DEGENERATE, "inverse status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(qo_fz_finite_quat(o), "inverse " QO_FZ_QFMT " -> " QO_FZ_QFMT, QO_FZ_QARG(a), QO_FZ_QARG(o));
        if (stn == QO_OK && na > 1e-18 && na < 1e18) {
            /* q * q^-1 == identity to float rounding */
            qo_quat_f32 p = qo_quat_mul_f32(un, o);
            double s = na;
            QO_FUZZ_CHECK(fabs(p.w * s - 1.0) < 1e-5 && fabs(p.x * s) < 1e-5 && fabs(p.y * s) < 1e-5
                          && fabs(p.z * s) < 1e-5,
                          "inverse " QO_FZ_QFMT " -> " QO_FZ_QFMT, QO_FZ_QARG(a), QO_FZ_QARG(o));
        }
    } else {
        QO_FUZZ_CHECK(qo_fz_is_identity(o), "inverse error output not identity");
    }

    /* canonical: w >= 0 for finite q, same magnitude */
    o = qo_quat_canonical_f32(a);
    if (fin) {
        QO_FUZZ_CHECK(o.w >= 0.0f && fabsf(o.x) == fabsf(a.x) && fabsf(o.w) == fabsf(a.w),
                      "canonical " QO_FZ_QFMT " -> " QO_FZ_QFMT, QO_FZ_QARG(a), QO_FZ_QARG(o));
    }

    /* exp (of the vector part) */
    av.x = a.x; av.y = a.y; av.z = a.z;
    st = qo_quat_exp_f32(av, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE, "exp status %d", (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "exp " QO_FZ_QFMT " -> " QO_FZ_QFMT, QO_FZ_QARG(a), QO_FZ_QARG(o));
    else QO_FUZZ_CHECK(qo_fz_is_identity(o), "exp error output not identity");
    if (fin && fabsf(a.x) < 1e6f && fabsf(a.y) < 1e6f && fabsf(a.z) < 1e6f)
        QO_FUZZ_CHECK(st == QO_OK, "exp of " QO_FZ_QFMT " st %d", QO_FZ_QARG(a), (int)st);

    /* log */
    st = qo_quat_log_f32(a, &av);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_DEGENERATE, "log status %d", (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(isfinite(av.x) && isfinite(av.y) && isfinite(av.z) && fabsf(av.x) <= 3.1416f && fabsf(av.y) <= 3.1416f && fabsf(av.z) <= 3.1416f, "log " QO_FZ_QFMT " not finite or beyond pi", QO_FZ_QARG(a));
    else QO_FUZZ_CHECK(av.x == 0.0f && av.y == 0.0f && av.z == 0.0f, "log error output not zero");

    /* integrate: unit on success; on error q normalised, or identity when that fails */
    st = qo_quat_integrate_f32(a, v, dt, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_DEGENERATE, "integrate status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "integrate " QO_FZ_QFMT " -> " QO_FZ_QFMT,
                      QO_FZ_QARG(a), QO_FZ_QARG(o));
    } else {
        QO_FUZZ_CHECK(qo_fz_same_quat(o, un), "integrate error output " QO_FZ_QFMT " is not normalise(q) " QO_FZ_QFMT,
                      QO_FZ_QARG(o), QO_FZ_QARG(un));
    }

    /* rotate by a unit quaternion keeps the length of a moderate vector */
    if (stn == QO_OK && qo_fz_finite_vec3(v) && fabsf(v.x) < 1e18f && fabsf(v.y) < 1e18f && fabsf(v.z) < 1e18f) {
        double lv = sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z);
        double lr;
        rv = qo_quat_rotate_f32(un, v);
        lr = sqrt((double)rv.x * rv.x + (double)rv.y * rv.y + (double)rv.z * rv.z);
        QO_FUZZ_CHECK(qo_fz_finite_vec3(rv) && fabs(lr - lv) <= 1e-5 * lv + 1e-30,
                      "rotate by " QO_FZ_QFMT " changed |v| %.9g -> %.9g", QO_FZ_QARG(un), lv, lr);
    }

    /* angle between two unit quaternions is in [0, pi] */
    if (stn == QO_OK) {
        qo_quat_f32 ub;
        if (qo_quat_normalize_f32(b, &ub) == QO_OK) {
            float ang = qo_quat_angle_between_f32(un, ub);
            QO_FUZZ_CHECK(ang >= 0.0f && ang <= 3.14159274f, "angle_between " QO_FZ_QFMT " " QO_FZ_QFMT " = %.9g",
                          QO_FZ_QARG(un), QO_FZ_QARG(ub), (double)ang);
        }
    }
    QO_FUZZ_CHECK(qo_quat_is_finite_f32(a) == fin, "is_finite");
    return 0;
}
