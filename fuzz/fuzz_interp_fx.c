/*
 * fuzz/fuzz_interp_fx.c - fixed-point orientation interpolation (qorient/interp_fx.h) fed
 * int32 components (raw and the edges INT32_MIN/MAX, 0, +-1, QO_Q30_ONE...) and parameters
 * (also outside their range), 0..9 keys. Properties from the header: documented statuses;
 * on error the documented value (identity or unit a / unit ctrl[0] / the nearest end key);
 * lerp between its inputs component-wise with exact endpoints; every other QO_OK result unit
 * within 2 LSB of length (the header: 1.1e-9) with exact endpoints where promised.
 */
#include "fuzz_common.h"
#include "qorient/interp_fx.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define FUZZ_IFX_MAXK 10

static int fuzz_ifx_zero(qo_quat_q30 q)
{
    return q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0;
}

static int fuzz_ifx_ident(qo_quat_q30 q)
{
    return q.w == QO_Q30_ONE && q.x == 0 && q.y == 0 && q.z == 0;
}

static int fuzz_ifx_same(qo_quat_q30 a, qo_quat_q30 b)
{
    return a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z;
}

static void fuzz_ifx_unit(qo_quat_q30 q, const char *what)
{
    double n = sqrt((double)q.w * q.w + (double)q.x * q.x + (double)q.y * q.y + (double)q.z * q.z) / 1073741824.0;
    QO_FUZZ_CHECK(fabs(n - 1.0) <= 2.5 / 1073741824.0, "%s: (%d %d %d %d) norm 1%+.3g LSB", what, q.w, q.x, q.y, q.z,
                  (n - 1.0) * 1073741824.0);
}

/* This module's "unit a": the one-key alignment of a. */
static qo_quat_q30 fuzz_ifx_unit_of(qo_quat_q30 a)
{
    qo_quat_q30 u;
    (void)qo_interp_align_keys_q30(&a, 1, &u);
    return u;
}

static int fuzz_ifx_between(int32_t v, int32_t a, int32_t b)
{
    return (v >= a && v <= b) || (v >= b && v <= a);
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    uint8_t hdr = qo_fz_u8(&f);
    size_t n = (size_t)(hdr % FUZZ_IFX_MAXK), i;
    qo_q30 t = qo_fz_i32(&f);
    qo_q16 s = qo_fz_i32(&f);
    qo_quat_q30 k[FUZZ_IFX_MAXK], al[FUZZ_IFX_MAXK], ca[FUZZ_IFX_MAXK], cb[FUZZ_IFX_MAXK], o, ua;
    qo_status st, sk;
    int tin, any_zero = 0;

    if (hdr & 0x80u) t = (qo_q30)((uint32_t)t % (uint32_t)(QO_Q30_ONE + 1));   /* mostly in range */
    tin = t >= 0 && t <= QO_Q30_ONE;
    for (i = 0; i < FUZZ_IFX_MAXK; i++) {
        k[i].w = qo_fz_i32(&f); k[i].x = qo_fz_i32(&f); k[i].y = qo_fz_i32(&f); k[i].z = qo_fz_i32(&f);
        if ((hdr & 0x40u) && i > 0) {   /* small steps from the previous key */
            k[i].w = k[i - 1].w / 2 + (k[i].w >> 12); k[i].x = k[i - 1].x / 2 + (k[i].x >> 12);
            k[i].y = k[i - 1].y / 2 + (k[i].y >> 12); k[i].z = k[i - 1].z / 2 + (k[i].z >> 12);
        }
        if (i < n && fuzz_ifx_zero(k[i])) any_zero = 1;
    }
    ua = fuzz_ifx_unit_of(k[0]);

    /* lerp */
    st = qo_interp_lerp_q30(k[0], k[1], t, &o);
    QO_FUZZ_CHECK(st == (tin ? QO_OK : QO_E_RANGE), "lerp t %d status %d", t, (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(fuzz_ifx_between(o.w, k[0].w, k[1].w) && fuzz_ifx_between(o.x, k[0].x, k[1].x)
                      && fuzz_ifx_between(o.y, k[0].y, k[1].y) && fuzz_ifx_between(o.z, k[0].z, k[1].z),
                      "lerp t %d left the box of its inputs", t);
        if (t == 0) QO_FUZZ_CHECK(fuzz_ifx_same(o, k[0]), "lerp t=0");
        if (t == QO_Q30_ONE) QO_FUZZ_CHECK(fuzz_ifx_same(o, k[1]), "lerp t=1");
    } else {
        QO_FUZZ_CHECK(fuzz_ifx_same(o, k[0]), "lerp range error output");
    }

    /* nlerp, slerp */
    st = qo_interp_nlerp_q30(k[0], k[1], t, &o);
    if (fuzz_ifx_zero(k[0]) || fuzz_ifx_zero(k[1])) QO_FUZZ_CHECK(st == QO_E_DEGENERATE && fuzz_ifx_ident(o), "nlerp zero");
    else if (!tin) QO_FUZZ_CHECK(st == QO_E_RANGE && fuzz_ifx_same(o, ua), "nlerp range");
    else { QO_FUZZ_CHECK(st == QO_OK, "nlerp status %d", (int)st); fuzz_ifx_unit(o, "nlerp"); }
    st = qo_interp_slerp_q30(k[0], k[1], t, &o);
    if (fuzz_ifx_zero(k[0]) || fuzz_ifx_zero(k[1])) {
        QO_FUZZ_CHECK(st == QO_E_DEGENERATE && fuzz_ifx_ident(o), "slerp zero");
    } else if (!tin) {
        QO_FUZZ_CHECK(st == QO_E_RANGE && fuzz_ifx_same(o, ua), "slerp range");
    } else {
        QO_FUZZ_CHECK(st == QO_OK, "slerp status %d", (int)st);
        fuzz_ifx_unit(o, "slerp");
        if (t == 0) QO_FUZZ_CHECK(fuzz_ifx_same(o, ua), "slerp t=0 (%d %d %d %d) not unit a (%d %d %d %d)", o.w, o.x,
                                  o.y, o.z, ua.w, ua.x, ua.y, ua.z);
    }

    /* keys */
    sk = qo_interp_align_keys_q30(k, n, al);
    if (n == 0) QO_FUZZ_CHECK(sk == QO_E_TOO_FEW, "align_keys n 0 status %d", (int)sk);
    else if (any_zero) QO_FUZZ_CHECK(sk == QO_E_DEGENERATE, "align_keys zero key status %d", (int)sk);
    else QO_FUZZ_CHECK(sk == QO_OK, "align_keys status %d", (int)sk);
    for (i = 0; i < n; i++) {
        if (sk == QO_OK) fuzz_ifx_unit(al[i], "align_keys");
        else QO_FUZZ_CHECK(fuzz_ifx_ident(al[i]), "align_keys error output");
    }

    st = qo_interp_bezier_q30(k, n, t, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_TOO_FEW || st == QO_E_CAPACITY || st == QO_E_DEGENERATE || st == QO_E_RANGE,
                  "bezier status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(n >= 2 && n <= QO_INTERP_BEZIER_MAX_POINTS && !any_zero && tin, "bezier accepted n %zu t %d", n, t);
        fuzz_ifx_unit(o, "bezier");
        if (t == 0) QO_FUZZ_CHECK(fuzz_ifx_same(o, al[0]), "bezier t=0");
        if (t == QO_Q30_ONE) QO_FUZZ_CHECK(fuzz_ifx_same(o, al[n - 1]), "bezier t=1 not the last aligned point");
    } else if (st == QO_E_RANGE) {
        QO_FUZZ_CHECK(fuzz_ifx_same(o, ua), "bezier range error output");
    } else {
        QO_FUZZ_CHECK(fuzz_ifx_ident(o), "bezier error %d output", (int)st);
    }

    st = qo_interp_spline_controls_q30(k, n, ca, cb);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_TOO_FEW || st == QO_E_DEGENERATE, "spline_controls status %d", (int)st);
    for (i = 0; i < n; i++) {
        if (st == QO_OK) { fuzz_ifx_unit(ca[i], "spline_controls a"); fuzz_ifx_unit(cb[i], "spline_controls b"); }
        else QO_FUZZ_CHECK(fuzz_ifx_ident(ca[i]) && fuzz_ifx_ident(cb[i]), "spline_controls error output");
    }
    if (st == QO_OK) {
        if (hdr & 0x20u) s = (qo_q16)((uint32_t)s % (uint32_t)((n - 1) * 65536u + 1u));
        st = qo_interp_spline_eval_q30(k, ca, cb, n, s, &o);
        if (s < 0 || (int64_t)s > (int64_t)(n - 1) * 65536) {
            QO_FUZZ_CHECK(st == QO_E_RANGE, "spline_eval s %d status %d", s, (int)st);
            QO_FUZZ_CHECK(fuzz_ifx_same(o, fuzz_ifx_unit_of(s < 0 ? k[0] : k[n - 1])), "spline_eval range output");
        } else {
            QO_FUZZ_CHECK(st == QO_OK, "spline_eval s %d status %d", s, (int)st);
            fuzz_ifx_unit(o, "spline_eval");
            if ((s & 0xFFFF) == 0) QO_FUZZ_CHECK(fuzz_ifx_same(o, al[s >> 16]), "spline_eval at key %d not the aligned key", s >> 16);
        }
    }

    st = qo_interp_squad_q30(k[0], k[1], k[2], k[3], t, &o);
    if (fuzz_ifx_zero(k[0]) || fuzz_ifx_zero(k[1]) || fuzz_ifx_zero(k[2]) || fuzz_ifx_zero(k[3]))
        QO_FUZZ_CHECK(st == QO_E_DEGENERATE && fuzz_ifx_ident(o), "squad zero");
    else if (!tin) QO_FUZZ_CHECK(st == QO_E_RANGE && fuzz_ifx_same(o, ua), "squad range");
    else { QO_FUZZ_CHECK(st == QO_OK, "squad status %d", (int)st); fuzz_ifx_unit(o, "squad"); if (t == 0) QO_FUZZ_CHECK(fuzz_ifx_same(o, ua), "squad t=0"); }
    return 0;
}
