/*
 * fuzz/fuzz_euler.c - qorient/euler.h: the sequence parser fed raw strings, and the three
 * decompositions plus from_euler fed decoded floats and any sequence value (also invalid
 * ones). Properties from the header: documented statuses; on QO_OK finite angles in scipy's
 * ranges, margin in [0, pi/2], locked == (margin <= band), and the angles compose back to q
 * (within 1e-5 rad, plus 2*margin when locked); on error the documented outputs.
 */
#include "fuzz_common.h"
#include "qorient/euler.h"
#include "qorient/quat.h"

#include "common/ref.h"   /* the double reference: tests/common/ref.c, linked */

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define FUZZ_EULER_PI 3.14159274f
#define FUZZ_EULER_HALF_PI 1.57079637f

/* Rotation angle between q (any non-zero finite) and the composition of e in seq: the double
 * reference of tests/common/ref.c (both normalised, 2 atan2(|vec|, |scalar|) of conj(q) c,
 * accurate at small angles). */
static double fuzz_euler_recompose_err(qo_quat_f32 q, qo_euler_seq seq, qo_euler_f32 e)
{
    qo_quat_f32 c;
    if (qo_euler_to_quat_f32(seq, e, &c) != QO_OK) return 1e9;
    return ref_quat_angle_between(ref_quat_from_f32(q), ref_quat_from_f32(c));
}

static void fuzz_euler_check_ok(qo_quat_f32 q, qo_euler_seq seq, qo_euler_f32 e, qo_euler_info_f32 info,
                                float band, int principal, const char *what)
{
    double err, tol;
    QO_FUZZ_CHECK(isfinite(e.a1) && isfinite(e.a2) && isfinite(e.a3), "%s: non-finite angles", what);
    QO_FUZZ_CHECK(info.margin >= 0.0f && info.margin <= FUZZ_EULER_HALF_PI, "%s: margin %.9g", what, (double)info.margin);
    QO_FUZZ_CHECK(info.locked == (info.margin <= band), "%s: locked %d margin %.9g band %.9g", what, info.locked,
                  (double)info.margin, (double)band);
    if (principal) {
        QO_FUZZ_CHECK(e.a1 >= -FUZZ_EULER_PI && e.a1 <= FUZZ_EULER_PI && e.a3 >= -FUZZ_EULER_PI && e.a3 <= FUZZ_EULER_PI,
                      "%s: a1 %.9g a3 %.9g out of [-pi, pi]", what, (double)e.a1, (double)e.a3);
        if (qo_euler_seq_is_proper(seq))
            QO_FUZZ_CHECK(e.a2 >= 0.0f && e.a2 <= FUZZ_EULER_PI, "%s: a2 %.9g out of [0, pi]", what, (double)e.a2);
        else
            QO_FUZZ_CHECK(e.a2 >= -FUZZ_EULER_HALF_PI && e.a2 <= FUZZ_EULER_HALF_PI, "%s: a2 %.9g out of [-pi/2, pi/2]",
                          what, (double)e.a2);
    }
    /* Angles far from [-pi, pi] carry ulp(|angle|) of error each. */
    tol = 1e-5 + 4.0 * 1.2e-7 * (fabs(e.a1) + fabs(e.a2) + fabs(e.a3));
    if (info.locked) tol += 2.0 * (double)info.margin * 1.01;
    err = fuzz_euler_recompose_err(q, seq, e);
    QO_FUZZ_CHECK(err <= tol, "%s %s: " QO_FZ_QFMT " -> (%.9g %.9g %.9g) recomposes %g rad off (tol %g, margin %g)",
                  what, qo_euler_seq_name(seq), QO_FZ_QARG(q), (double)e.a1, (double)e.a2, (double)e.a3, err, tol,
                  (double)info.margin);
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    char s[6];
    size_t i;
    qo_euler_seq seq, ps;
    qo_quat_f32 q, o;
    qo_euler_f32 e, prev;
    qo_euler_info_f32 info;
    float band;
    qo_status st;
    int qfin, seq_ok;

    /* the parser: up to 5 raw characters */
    for (i = 0; i < 5; i++) s[i] = (char)qo_fz_u8(&f);
    s[5] = '\0';
    st = qo_euler_seq_parse(s, &ps);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG, "seq_parse status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK((int)ps >= 0 && ps < QO_EULER_SEQ_COUNT_ && strcmp(qo_euler_seq_name(ps), s) == 0,
                      "seq_parse '%s' -> %d", s, (int)ps);
    } else {
        QO_FUZZ_CHECK(ps == QO_EULER_SEQ_COUNT_, "seq_parse error output %d", (int)ps);
    }

    seq = (qo_euler_seq)(qo_fz_u8(&f) % 26u);   /* 24 and 25 are invalid */
    seq_ok = (int)seq < (int)QO_EULER_SEQ_COUNT_;
    q = qo_fz_quat(&f);
    qfin = qo_fz_finite_quat(q);
    e.a1 = qo_fz_f32(&f); e.a2 = qo_fz_f32(&f); e.a3 = qo_fz_f32(&f);
    prev.a1 = qo_fz_f32(&f); prev.a2 = qo_fz_f32(&f); prev.a3 = qo_fz_f32(&f);
    band = qo_fz_f32(&f);

    /* angles -> quaternion */
    st = qo_euler_to_quat_f32(seq, e, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_NONFINITE, "from_euler status %d", (int)st);
    QO_FUZZ_CHECK((st == QO_E_ARG) == !seq_ok, "from_euler seq %d status %d", (int)seq, (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "from_euler -> " QO_FZ_QFMT, QO_FZ_QARG(o));
    else QO_FUZZ_CHECK(qo_fz_is_identity(o), "from_euler error output");

    /* quaternion -> angles, default band */
    st = qo_euler_from_quat_f32(q, seq, &e, &info);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_NONFINITE || st == QO_E_DEGENERATE,
                  "to_euler status %d", (int)st);
    if (st == QO_OK) {
        fuzz_euler_check_ok(q, seq, e, info, QO_EULER_LOCK_BAND_F32, 1, "to_euler");
    } else {
        QO_FUZZ_CHECK(e.a1 == 0.0f && e.a2 == 0.0f && e.a3 == 0.0f && info.locked == 0 && info.margin == 0.0f,
                      "to_euler error output");
    }
    if (seq_ok && qfin && (q.w != 0.0f || q.x != 0.0f || q.y != 0.0f || q.z != 0.0f))
        QO_FUZZ_CHECK(st == QO_OK, "to_euler refused finite non-zero " QO_FZ_QFMT ": %d", QO_FZ_QARG(q), (int)st);

    /* caller's band */
    st = qo_euler_from_quat_band_f32(q, seq, band, &e, &info);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_NONFINITE || st == QO_E_DEGENERATE || st == QO_E_RANGE,
                  "to_euler_band status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(band >= 0.0f && band <= FUZZ_EULER_HALF_PI, "to_euler_band accepted band %.9g", (double)band);
        fuzz_euler_check_ok(q, seq, e, info, band, 1, "to_euler_band");
    } else {
        QO_FUZZ_CHECK(e.a1 == 0.0f && e.a2 == 0.0f && e.a3 == 0.0f && info.locked == 0 && info.margin == 0.0f,
                      "to_euler_band error output");
    }

    /* nearest previous joint angles */
    st = qo_euler_from_quat_near_f32(q, seq, prev, band, &e, &info);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_NONFINITE || st == QO_E_DEGENERATE || st == QO_E_RANGE,
                  "to_euler_near status %d", (int)st);
    if (st == QO_OK) {
        fuzz_euler_check_ok(q, seq, e, info, band, 0, "to_euler_near");
    } else {
        int pfin = isfinite(prev.a1) && isfinite(prev.a2) && isfinite(prev.a3);
        if (pfin)
            QO_FUZZ_CHECK(memcmp(&e, &prev, sizeof e) == 0, "to_euler_near error output is not prev");
        else
            QO_FUZZ_CHECK(e.a1 == 0.0f && e.a2 == 0.0f && e.a3 == 0.0f, "to_euler_near error output not zero");
        QO_FUZZ_CHECK(info.locked == 0 && info.margin == 0.0f, "to_euler_near error info");
    }
    QO_FUZZ_CHECK(qo_euler_from_quat_f32(q, seq, NULL, &info) == QO_E_NULL, "to_euler NULL");
    QO_FUZZ_CHECK(qo_euler_seq_parse(NULL, &ps) == QO_E_NULL, "seq_parse NULL");
    return 0;
}
