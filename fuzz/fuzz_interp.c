/*
 * fuzz/fuzz_interp.c - qorient/interp.h fed decoded floats: lerp, nlerp, slerp, slerp_long,
 * slerp_rate, Bezier, the Shoemake spline and Squad, with key counts 0..9 (past the Bezier
 * capacity). Properties from the header: documented statuses; on QO_OK finite outputs, unit
 * (within 1e-5) for all but lerp, endpoints exact where promised; on error the documented
 * value (identity, unit a, nearest end key, zero rate).
 */
#include "fuzz_common.h"
#include "qorient/interp.h"
#include "qorient/quat.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define FUZZ_INTERP_MAXK 10

/* The documented output of a two-point interpolator on error. */
static void fuzz_interp_check_err2(qo_status st, qo_quat_f32 a, qo_quat_f32 b, float t, qo_quat_f32 o,
                                   const char *what)
{
    qo_quat_f32 ua;
    int qbad = !qo_fz_finite_quat(a) || !qo_fz_finite_quat(b);
    qo_status sa = qo_quat_normalize_f32(a, &ua);
    qo_quat_f32 ub;
    qo_status sb = qo_quat_normalize_f32(b, &ub);
    (void)t;
    if (qbad || sa != QO_OK || sb != QO_OK) {
        QO_FUZZ_CHECK(qo_fz_is_identity(o), "%s status %d: output " QO_FZ_QFMT " not identity", what, (int)st,
                      QO_FZ_QARG(o));
    } else if (st == QO_E_NONFINITE || st == QO_E_RANGE) {
        QO_FUZZ_CHECK(qo_fz_same_quat(o, ua), "%s status %d: output " QO_FZ_QFMT " not unit a " QO_FZ_QFMT, what,
                      (int)st, QO_FZ_QARG(o), QO_FZ_QARG(ua));
    }
}

static void fuzz_interp_two(qo_quat_f32 a, qo_quat_f32 b, float t)
{
    qo_quat_f32 o;
    qo_vec3_f32 w;
    qo_status st;
    int tin = t >= 0.0f && t <= 1.0f;

    st = qo_interp_lerp_f32(a, b, t, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE, "lerp status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(tin, "lerp accepted t %.9g", (double)t);
        if (t == 0.0f) QO_FUZZ_CHECK(qo_fz_same_quat(o, a), "lerp t=0 not a");
        if (t == 1.0f) QO_FUZZ_CHECK(qo_fz_same_quat(o, b), "lerp t=1 not b");
    } else if (!qo_fz_finite_quat(a) || !qo_fz_finite_quat(b)) {
        QO_FUZZ_CHECK(qo_fz_is_identity(o), "lerp error output");
    } else {
        QO_FUZZ_CHECK(qo_fz_same_quat(o, a), "lerp t error output not a");
    }

    st = qo_interp_nlerp_f32(a, b, t, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE || st == QO_E_DEGENERATE,
                  "nlerp status %d", (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(tin && qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "nlerp -> " QO_FZ_QFMT, QO_FZ_QARG(o));
    else fuzz_interp_check_err2(st, a, b, t, o, "nlerp");

    st = qo_interp_slerp_f32(a, b, t, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE || st == QO_E_DEGENERATE,
                  "slerp status %d", (int)st);
    if (st == QO_OK) {
        qo_quat_f32 ua;
        QO_FUZZ_CHECK(tin && qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "slerp " QO_FZ_QFMT " " QO_FZ_QFMT " %.9g -> " QO_FZ_QFMT,
                      QO_FZ_QARG(a), QO_FZ_QARG(b), (double)t, QO_FZ_QARG(o));
        if (t == 0.0f && qo_quat_normalize_f32(a, &ua) == QO_OK)
            QO_FUZZ_CHECK(qo_fz_same_quat(o, ua), "slerp t=0 " QO_FZ_QFMT " not unit a " QO_FZ_QFMT, QO_FZ_QARG(o),
                          QO_FZ_QARG(ua));
    } else {
        fuzz_interp_check_err2(st, a, b, t, o, "slerp");
    }

    st = qo_interp_slerp_long_f32(a, b, t, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE || st == QO_E_DEGENERATE,
                  "slerp_long status %d", (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(tin && qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "slerp_long -> " QO_FZ_QFMT, QO_FZ_QARG(o));
    else if (st != QO_E_DEGENERATE || !qo_fz_finite_quat(a)) fuzz_interp_check_err2(st, a, b, t, o, "slerp_long");

    st = qo_interp_slerp_rate_f32(a, b, t, &w);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE || st == QO_E_DEGENERATE,
                  "slerp_rate status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(t > 0.0f, "slerp_rate accepted duration %.9g", (double)t);
        /* |omega| = angle / duration: finite unless the duration is tiny */
        if (t >= 1e-30f) QO_FUZZ_CHECK(qo_fz_finite_vec3(w), "slerp_rate non-finite omega for duration %.9g", (double)t);
    } else {
        QO_FUZZ_CHECK(w.x == 0.0f && w.y == 0.0f && w.z == 0.0f, "slerp_rate error output");
    }
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    uint8_t hdr = qo_fz_u8(&f);
    size_t n = (size_t)(hdr % FUZZ_INTERP_MAXK), i;
    float t = qo_fz_f32(&f), s;
    qo_quat_f32 k[FUZZ_INTERP_MAXK], al[FUZZ_INTERP_MAXK], ca[FUZZ_INTERP_MAXK], cb[FUZZ_INTERP_MAXK], o;
    qo_status st, sk;
    int keys_ok = 1;

    /* Keys: fuzzed, or (bit 4 of the header) small fuzzed steps from the previous key, which
     * keeps the series and near-antipodal branches busy. */
    for (i = 0; i < FUZZ_INTERP_MAXK; i++) {
        k[i] = qo_fz_quat(&f);
        if ((hdr & 0x10u) && i > 0 && qo_fz_finite_quat(k[i]) && qo_fz_finite_quat(k[i - 1])) {
            k[i].w = k[i - 1].w + k[i].w * 1e-4f; k[i].x = k[i - 1].x + k[i].x * 1e-4f;
            k[i].y = k[i - 1].y + k[i].y * 1e-4f; k[i].z = k[i - 1].z + k[i].z * 1e-4f;
            if (hdr & 0x20u) { k[i].w = -k[i].w; k[i].x = -k[i].x; k[i].y = -k[i].y; k[i].z = -k[i].z; }
        }
    }
    fuzz_interp_two(k[0], k[1], t);

    sk = qo_interp_align_keys_f32(k, n, al);
    QO_FUZZ_CHECK(sk == QO_OK || sk == QO_E_TOO_FEW || sk == QO_E_NONFINITE || sk == QO_E_DEGENERATE,
                  "align_keys status %d", (int)sk);
    for (i = 0; i < n; i++) {
        if (sk == QO_OK) {
            QO_FUZZ_CHECK(qo_fz_unit_quat(al[i], QO_FZ_UNIT_TOL), "align_keys[%zu] -> " QO_FZ_QFMT, i, QO_FZ_QARG(al[i]));
            if (i > 0) QO_FUZZ_CHECK(qo_quat_dot_f32(al[i - 1], al[i]) >= 0.0f, "align_keys[%zu] not aligned", i);
        } else {
            QO_FUZZ_CHECK(qo_fz_is_identity(al[i]), "align_keys error output [%zu]", i);
        }
        if (!qo_fz_finite_quat(k[i]) || qo_quat_normalize_f32(k[i], &o) != QO_OK) keys_ok = 0;
    }
    QO_FUZZ_CHECK(n == 0 || (sk == QO_OK) == keys_ok, "align_keys status %d with keys_ok %d", (int)sk, keys_ok);

    /* Bezier on n control points (n > 8 exceeds its capacity) */
    st = qo_interp_bezier_f32(k, n, t, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_TOO_FEW || st == QO_E_CAPACITY || st == QO_E_NONFINITE
                  || st == QO_E_DEGENERATE || st == QO_E_RANGE, "bezier status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(n >= 2 && n <= QO_INTERP_BEZIER_MAX_POINTS && keys_ok && t >= 0.0f && t <= 1.0f,
                      "bezier accepted n %zu t %.9g", n, (double)t);
        QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "bezier n %zu t %.9g -> " QO_FZ_QFMT, n, (double)t, QO_FZ_QARG(o));
        if (t == 0.0f) QO_FUZZ_CHECK(qo_fz_same_quat(o, al[0]), "bezier t=0 not unit ctrl[0]");
    } else if (st == QO_E_RANGE || (st == QO_E_NONFINITE && keys_ok && n >= 2 && n <= QO_INTERP_BEZIER_MAX_POINTS)) {
        QO_FUZZ_CHECK(qo_fz_same_quat(o, al[0]), "bezier t error output not unit ctrl[0]");
    } else {
        QO_FUZZ_CHECK(qo_fz_is_identity(o), "bezier error output not identity (status %d)", (int)st);
    }

    /* Shoemake spline */
    st = qo_interp_spline_controls_f32(k, n, ca, cb);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_TOO_FEW || st == QO_E_NONFINITE || st == QO_E_DEGENERATE,
                  "spline_controls status %d", (int)st);
    for (i = 0; i < n; i++) {
        if (st == QO_OK)
            QO_FUZZ_CHECK(qo_fz_unit_quat(ca[i], QO_FZ_UNIT_TOL) && qo_fz_unit_quat(cb[i], QO_FZ_UNIT_TOL),
                          "spline_controls [%zu] a " QO_FZ_QFMT " b " QO_FZ_QFMT, i, QO_FZ_QARG(ca[i]), QO_FZ_QARG(cb[i]));
        else
            QO_FUZZ_CHECK(qo_fz_is_identity(ca[i]) && qo_fz_is_identity(cb[i]), "spline_controls error output");
    }
    if (st == QO_OK) {
        s = isfinite(t) ? t * (float)(n - 1) : t;
        st = qo_interp_spline_eval_f32(k, ca, cb, n, s, &o);
        QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE, "spline_eval status %d", (int)st);
        if (st == QO_OK) {
            QO_FUZZ_CHECK(s >= 0.0f && s <= (float)(n - 1), "spline_eval accepted s %.9g", (double)s);
            QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "spline_eval n %zu s %.9g -> " QO_FZ_QFMT, n, (double)s,
                          QO_FZ_QARG(o));
        } else {
            QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "spline_eval error output " QO_FZ_QFMT " not a unit end key",
                          QO_FZ_QARG(o));
        }
    }

    /* Squad */
    st = qo_interp_squad_controls_f32(k, n, ca);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_TOO_FEW || st == QO_E_NONFINITE || st == QO_E_DEGENERATE,
                  "squad_controls status %d", (int)st);
    for (i = 0; i < n; i++) {
        if (st == QO_OK)
            QO_FUZZ_CHECK(qo_fz_unit_quat(ca[i], QO_FZ_UNIT_TOL), "squad_controls [%zu] " QO_FZ_QFMT, i, QO_FZ_QARG(ca[i]));
        else
            QO_FUZZ_CHECK(qo_fz_is_identity(ca[i]), "squad_controls error output");
    }
    if (st == QO_OK) {
        st = qo_interp_squad_f32(k[0], ca[0], ca[1], k[1], t, &o);
        QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE, "squad status %d", (int)st);
        if (st == QO_OK) QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "squad -> " QO_FZ_QFMT, QO_FZ_QARG(o));
        else QO_FUZZ_CHECK(qo_fz_same_quat(o, al[0]), "squad t error output not unit q0");
    }
    st = qo_interp_squad_f32(k[0], k[1], k[2], k[3], t, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE || st == QO_E_RANGE || st == QO_E_DEGENERATE,
                  "squad(raw) status %d", (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(qo_fz_unit_quat(o, QO_FZ_UNIT_TOL), "squad(raw) -> " QO_FZ_QFMT, QO_FZ_QARG(o));
    return 0;
}
