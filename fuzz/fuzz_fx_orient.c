/*
 * fuzz/fuzz_fx_orient.c - the fixed-point orientation core (qorient/quat_fx.h, convert_fx.h,
 * euler_fx.h) fed int32 components (raw and the edges INT32_MIN/MAX, 0, +-1, QO_Q30_ONE...).
 * A mode byte also makes near-unit quaternions (a fuzzed one normalised) so the accuracy
 * paths are reached, not only the saturating ones. Properties from the headers: documented
 * statuses; on error the documented value; on QO_OK unit quaternions within a few LSB of
 * unit length, angles in their Q3.28 ranges, rotation matrices orthonormal, the Hamilton
 * product equal to the exact sum rounded once (or QO_E_OVERFLOW when it saturated), and Euler
 * angles that compose back to q (1e-6 rad, plus 2*margin when locked).
 */
#include "fuzz_common.h"
#include "qorient/convert_fx.h"
#include "qorient/euler_fx.h"
#include "qorient/fxmath.h"
#include "qorient/quat_fx.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define FUZZ_FXO_ONE 1073741824.0
#define FUZZ_FXO_Q28 268435456.0

static qo_quat_q30 fuzz_fxo_quat(qo_fz *f)
{
    qo_quat_q30 q;
    q.w = qo_fz_i32(f); q.x = qo_fz_i32(f); q.y = qo_fz_i32(f); q.z = qo_fz_i32(f);
    return q;
}

static double fuzz_fxo_norm(qo_quat_q30 q)
{
    return sqrt((double)q.w * q.w + (double)q.x * q.x + (double)q.y * q.y + (double)q.z * q.z) / FUZZ_FXO_ONE;
}

static int fuzz_fxo_is_identity(qo_quat_q30 q)
{
    return q.w == QO_Q30_ONE && q.x == 0 && q.y == 0 && q.z == 0;
}

static int fuzz_fxo_is_zero(qo_quat_q30 q)
{
    return q.w == 0 && q.x == 0 && q.y == 0 && q.z == 0;
}

/* Unit within n LSB (per component rounding adds up to 2n LSB of length). */
static void fuzz_fxo_unit(qo_quat_q30 q, double lsb, const char *what)
{
    double n = fuzz_fxo_norm(q);
    QO_FUZZ_CHECK(fabs(n - 1.0) <= lsb / FUZZ_FXO_ONE, "%s: (%d %d %d %d) has norm 1%+.3g LSB", what, q.w, q.x, q.y,
                  q.z, (n - 1.0) * FUZZ_FXO_ONE);
}

/* Rotation angle between unit(q) and unit(c), in double. */
static double fuzz_fxo_angle(qo_quat_q30 q, qo_quat_q30 c)
{
    double nq = fuzz_fxo_norm(q) * FUZZ_FXO_ONE, nc = fuzz_fxo_norm(c) * FUZZ_FXO_ONE;
    double qw = q.w / nq, qx = q.x / nq, qy = q.y / nq, qz = q.z / nq;
    double cw = c.w / nc, cx = c.x / nc, cy = c.y / nc, cz = c.z / nc;
    double rw = cw * qw + cx * qx + cy * qy + cz * qz;
    double rx = cw * qx - cx * qw - cy * qz + cz * qy;
    double ry = cw * qy + cx * qz - cy * qw - cz * qx;
    double rz = cw * qz - cx * qy + cy * qx - cz * qw;
    return 2.0 * atan2(sqrt(rx * rx + ry * ry + rz * rz), fabs(rw));
}

/* round((p0 + p1 + p2 + p3) / 2^30), ties toward +inf, exactly (|p| <= 2^62 each). */
static int64_t fuzz_fxo_sum4(int64_t p0, int64_t p1, int64_t p2, int64_t p3)
{
    int64_t p[4], hs = 0, ls = 0;
    int i;
    p[0] = p0; p[1] = p1; p[2] = p2; p[3] = p3;
    for (i = 0; i < 4; i++) {
        int64_t h = p[i] >> 30;   /* arithmetic shift: floor */
        hs += h;
        ls += p[i] - h * ((int64_t)1 << 30);
    }
    return hs + ((ls + ((int64_t)1 << 29)) >> 30);
}

static void fuzz_fxo_euler_ok(qo_quat_q30 q, qo_euler_seq seq, qo_euler_q28 e, qo_euler_info_q28 info,
                              qo_q28 band, int principal, const char *what)
{
    qo_quat_q30 c;
    double err, tol;
    QO_FUZZ_CHECK(info.margin >= 0 && info.margin <= QO_Q28_HALF_PI, "%s: margin %d", what, info.margin);
    QO_FUZZ_CHECK(info.locked == (info.margin <= band), "%s: locked %d margin %d band %d", what, info.locked,
                  info.margin, band);
    if (principal) {
        QO_FUZZ_CHECK(e.a1 >= -QO_Q28_PI && e.a1 <= QO_Q28_PI && e.a3 >= -QO_Q28_PI && e.a3 <= QO_Q28_PI,
                      "%s: a1 %d a3 %d out of range", what, e.a1, e.a3);
        if (qo_euler_seq_is_proper(seq))
            QO_FUZZ_CHECK(e.a2 >= 0 && e.a2 <= QO_Q28_PI, "%s: a2 %d out of [0, pi]", what, e.a2);
        else
            QO_FUZZ_CHECK(e.a2 >= -QO_Q28_HALF_PI && e.a2 <= QO_Q28_HALF_PI, "%s: a2 %d out of [-pi/2, pi/2]", what, e.a2);
    }
    QO_FUZZ_CHECK(qo_euler_to_quat_q30(seq, e, &c) == QO_OK, "%s: from_euler failed", what);
    /* Quaternions a few LSB long carry only a few bits of direction. */
    tol = 1e-6 + 64.0 / (fuzz_fxo_norm(q) * FUZZ_FXO_ONE);
    if (info.locked) tol += 2.0 * info.margin / FUZZ_FXO_Q28 * 1.01;
    err = fuzz_fxo_angle(q, c);
    QO_FUZZ_CHECK(err <= tol, "%s %s: (%d %d %d %d) -> (%d %d %d) recomposes %g rad off (tol %g)", what,
                  qo_euler_seq_name(seq), q.w, q.x, q.y, q.z, e.a1, e.a2, e.a3, err, tol);
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    uint8_t mode = qo_fz_u8(&f);
    qo_quat_q30 a = fuzz_fxo_quat(&f), b = fuzz_fxo_quat(&f), o, un, un2;
    qo_vec3_q30 v, ax;
    qo_vec3_q28 rv, lv;
    qo_q28 ang, band = qo_fz_i32(&f);
    qo_mat3_q30 m;
    qo_euler_q28 e, prev;
    qo_euler_info_q28 info;
    qo_euler_seq seq = (qo_euler_seq)(qo_fz_u8(&f) % 26u);
    qo_status st;
    int i, j, k;

    v.x = qo_fz_i32(&f); v.y = qo_fz_i32(&f); v.z = qo_fz_i32(&f);
    rv.x = qo_fz_i32(&f); rv.y = qo_fz_i32(&f); rv.z = qo_fz_i32(&f);
    prev.a1 = qo_fz_i32(&f); prev.a2 = qo_fz_i32(&f); prev.a3 = qo_fz_i32(&f);
    if ((mode & 1u) && qo_quat_normalize_q30(a, &o) == QO_OK) a = o;
    if ((mode & 2u) && qo_quat_normalize_q30(b, &o) == QO_OK) b = o;

    /* normalize */
    st = qo_quat_normalize_q30(a, &un);
    if (fuzz_fxo_is_zero(a)) {
        QO_FUZZ_CHECK(st == QO_E_DEGENERATE && fuzz_fxo_is_identity(un), "normalize zero: %d", (int)st);
    } else {
        double n = fuzz_fxo_norm(a) * FUZZ_FXO_ONE;
        QO_FUZZ_CHECK(st == QO_OK, "normalize status %d", (int)st);
        QO_FUZZ_CHECK(fabs(un.w - a.w / n * FUZZ_FXO_ONE) <= 1.01 && fabs(un.x - a.x / n * FUZZ_FXO_ONE) <= 1.01
                      && fabs(un.y - a.y / n * FUZZ_FXO_ONE) <= 1.01 && fabs(un.z - a.z / n * FUZZ_FXO_ONE) <= 1.01,
                      "normalize (%d %d %d %d) -> (%d %d %d %d) not within 1 LSB", a.w, a.x, a.y, a.z, un.w, un.x,
                      un.y, un.z);
    }

    /* Hamilton product: each component the exact sum rounded once, or saturated with a status */
    st = qo_quat_mul_checked_q30(a, b, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_OVERFLOW, "mul_checked status %d", (int)st);
    {
        /* exact: round(sum / 2^30), ties toward +inf, from a split of each product */
        int64_t ex[4];
        int sat = 0;
        ex[0] = fuzz_fxo_sum4((int64_t)a.w * b.w, -(int64_t)a.x * b.x, -(int64_t)a.y * b.y, -(int64_t)a.z * b.z);
        ex[1] = fuzz_fxo_sum4((int64_t)a.w * b.x, (int64_t)a.x * b.w, (int64_t)a.y * b.z, -(int64_t)a.z * b.y);
        ex[2] = fuzz_fxo_sum4((int64_t)a.w * b.y, -(int64_t)a.x * b.z, (int64_t)a.y * b.w, (int64_t)a.z * b.x);
        ex[3] = fuzz_fxo_sum4((int64_t)a.w * b.z, (int64_t)a.x * b.y, -(int64_t)a.y * b.x, (int64_t)a.z * b.w);
        for (k = 0; k < 4; k++) {
            int32_t got = k == 0 ? o.w : k == 1 ? o.x : k == 2 ? o.y : o.z;
            if (ex[k] > INT32_MAX) { sat = 1; QO_FUZZ_CHECK(got == INT32_MAX, "mul component %d not saturated", k); }
            else if (ex[k] < INT32_MIN) { sat = 1; QO_FUZZ_CHECK(got == INT32_MIN, "mul component %d not saturated", k); }
            else QO_FUZZ_CHECK(got == ex[k], "mul component %d = %d, exact %lld", k, got, (long long)ex[k]);
        }
        if (!sat) QO_FUZZ_CHECK(st == QO_OK, "mul_checked reported overflow without saturation");
        un2 = qo_quat_mul_q30(a, b);
        QO_FUZZ_CHECK(memcmp(&un2, &o, sizeof o) == 0, "mul and mul_checked differ");
    }

    /* canonical, angle between, rotate */
    o = qo_quat_canonical_q30(a);
    QO_FUZZ_CHECK(o.w >= 0, "canonical w %d", o.w);
    ang = qo_quat_angle_between_q30(un, b);
    QO_FUZZ_CHECK(ang >= 0 && ang <= QO_Q28_PI, "angle_between = %d", ang);
    ax = qo_quat_rotate_q30(un, v);   /* saturating by contract; UBSan watches the arithmetic */
    (void)ax;

    /* exp / log / integrate */
    st = qo_quat_exp_q30(rv, &o);
    if (rv.x >= (4 << 28) || rv.x <= -(4 << 28) || rv.y >= (4 << 28) || rv.y <= -(4 << 28) || rv.z >= (4 << 28)
        || rv.z <= -(4 << 28)) {
        QO_FUZZ_CHECK(st == QO_E_RANGE && fuzz_fxo_is_identity(o), "exp (%d %d %d): status %d", rv.x, rv.y, rv.z, (int)st);
    } else {
        QO_FUZZ_CHECK(st == QO_OK, "exp status %d", (int)st);
        fuzz_fxo_unit(o, 6.0, "exp");
    }
    st = qo_quat_log_q30(a, &lv);
    if (fuzz_fxo_is_zero(a)) QO_FUZZ_CHECK(st == QO_E_DEGENERATE && lv.x == 0 && lv.y == 0 && lv.z == 0, "log zero");
    else QO_FUZZ_CHECK(st == QO_OK, "log status %d", (int)st);
    st = qo_quat_integrate_q30(a, rv, &o);
    if (fuzz_fxo_is_zero(a)) QO_FUZZ_CHECK(st == QO_E_DEGENERATE && fuzz_fxo_is_identity(o), "integrate zero");
    else { QO_FUZZ_CHECK(st == QO_OK, "integrate status %d", (int)st); fuzz_fxo_unit(o, 6.0, "integrate"); }

    /* conversions */
    st = qo_axis_angle_to_quat_q30(v, band, &o);
    if (v.x == 0 && v.y == 0 && v.z == 0) QO_FUZZ_CHECK(st == QO_E_DEGENERATE && fuzz_fxo_is_identity(o), "from_axis_angle zero");
    else { QO_FUZZ_CHECK(st == QO_OK, "from_axis_angle status %d", (int)st); fuzz_fxo_unit(o, 6.0, "from_axis_angle"); }
    st = qo_axis_angle_from_quat_q30(a, &ax, &ang);
    if (fuzz_fxo_is_zero(a)) {
        QO_FUZZ_CHECK(st == QO_E_DEGENERATE && ax.x == QO_Q30_ONE && ax.y == 0 && ax.z == 0 && ang == 0, "to_axis_angle zero");
    } else {
        double la = sqrt((double)ax.x * ax.x + (double)ax.y * ax.y + (double)ax.z * ax.z) / FUZZ_FXO_ONE;
        QO_FUZZ_CHECK(st == QO_OK && ang >= 0 && ang <= QO_Q28_PI && fabs(la - 1.0) <= 6.0 / FUZZ_FXO_ONE,
                      "to_axis_angle (%d %d %d %d): status %d angle %d |axis| 1%+.3g LSB", a.w, a.x, a.y, a.z, (int)st,
                      ang, (la - 1.0) * FUZZ_FXO_ONE);
    }
    st = qo_rotvec_to_quat_q30(rv, &o);
    QO_FUZZ_CHECK(st == QO_OK, "from_rotvec status %d", (int)st);
    fuzz_fxo_unit(o, 6.0, "from_rotvec");
    st = qo_rotvec_from_quat_q30(a, &lv);
    if (fuzz_fxo_is_zero(a)) {
        QO_FUZZ_CHECK(st == QO_E_DEGENERATE && lv.x == 0 && lv.y == 0 && lv.z == 0, "to_rotvec zero");
    } else {
        double l = sqrt((double)lv.x * lv.x + (double)lv.y * lv.y + (double)lv.z * lv.z);
        QO_FUZZ_CHECK(st == QO_OK && l <= QO_Q28_PI + 6.0, "to_rotvec status %d |rv| %.1f", (int)st, l);
    }
    st = qo_mat3_from_quat_q30(a, &m);
    if (fuzz_fxo_is_zero(a)) {
        QO_FUZZ_CHECK(st == QO_E_DEGENERATE && m.m[0][0] == QO_Q30_ONE && m.m[0][1] == 0 && m.m[1][1] == QO_Q30_ONE,
                      "to_mat3 zero");
    } else {
        QO_FUZZ_CHECK(st == QO_OK, "to_mat3 status %d", (int)st);
        for (i = 0; i < 3; i++)
            for (j = 0; j < 3; j++) {
                double s = 0.0;
                for (k = 0; k < 3; k++) s += (double)m.m[k][i] * m.m[k][j];
                s = s / (FUZZ_FXO_ONE * FUZZ_FXO_ONE) - (i == j ? 1.0 : 0.0);
                QO_FUZZ_CHECK(fabs(s) <= 2e-8, "to_mat3 (%d %d %d %d): (M^T M - I)[%d][%d] = %g", a.w, a.x, a.y, a.z, i, j, s);
            }
        st = qo_mat3_to_quat_q30(&m, &o);
        QO_FUZZ_CHECK(st == QO_OK && o.w >= 0, "from_mat3(to_mat3(q)) status %d", (int)st);
        fuzz_fxo_unit(o, 6.0, "from_mat3");
        QO_FUZZ_CHECK(fuzz_fxo_angle(a, o) <= 1e-7 + 64.0 / (fuzz_fxo_norm(a) * FUZZ_FXO_ONE),
                      "from_mat3(to_mat3(q)) is %g rad from q", fuzz_fxo_angle(a, o));
    }
    /* a raw matrix: refused or a unit canonical quaternion */
    for (i = 0; i < 3; i++)
        for (j = 0; j < 3; j++) m.m[i][j] = (mode & 4u) ? m.m[i][j] + (qo_fz_i32(&f) >> 16) : qo_fz_i32(&f);
    st = qo_mat3_to_quat_q30(&m, &o);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NOT_ROTATION, "from_mat3 status %d", (int)st);
    if (st == QO_OK) { QO_FUZZ_CHECK(o.w >= 0, "from_mat3 w %d", o.w); fuzz_fxo_unit(o, 6.0, "from_mat3 raw"); }
    else QO_FUZZ_CHECK(fuzz_fxo_is_identity(o), "from_mat3 error output");

    /* Euler */
    e.a1 = rv.x; e.a2 = rv.y; e.a3 = rv.z;
    st = qo_euler_to_quat_q30(seq, e, &o);
    if ((int)seq >= (int)QO_EULER_SEQ_COUNT_) QO_FUZZ_CHECK(st == QO_E_ARG && fuzz_fxo_is_identity(o), "from_euler bad seq");
    else { QO_FUZZ_CHECK(st == QO_OK, "from_euler status %d", (int)st); fuzz_fxo_unit(o, 8.0, "from_euler"); }

    st = qo_euler_from_quat_q30(a, seq, &e, &info);
    if ((int)seq >= (int)QO_EULER_SEQ_COUNT_ || fuzz_fxo_is_zero(a)) {
        QO_FUZZ_CHECK((st == QO_E_ARG || st == QO_E_DEGENERATE) && e.a1 == 0 && e.a2 == 0 && e.a3 == 0 && info.locked == 0
                      && info.margin == 0, "to_euler error %d output", (int)st);
    } else {
        QO_FUZZ_CHECK(st == QO_OK, "to_euler status %d", (int)st);
        fuzz_fxo_euler_ok(a, seq, e, info, QO_EULER_LOCK_BAND_Q28, 1, "to_euler");
    }
    st = qo_euler_from_quat_band_q30(a, seq, band, &e, &info);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_DEGENERATE || st == QO_E_RANGE, "to_euler_band status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(band >= 0 && band <= QO_Q28_HALF_PI, "to_euler_band accepted band %d", band);
        fuzz_fxo_euler_ok(a, seq, e, info, band, 1, "to_euler_band");
    } else {
        QO_FUZZ_CHECK(e.a1 == 0 && e.a2 == 0 && e.a3 == 0 && info.locked == 0 && info.margin == 0, "to_euler_band error output");
    }
    st = qo_euler_from_quat_near_q30(a, seq, prev, band, &e, &info);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_DEGENERATE || st == QO_E_RANGE || st == QO_E_OVERFLOW,
                  "to_euler_near status %d", (int)st);
    if (st == QO_OK || st == QO_E_OVERFLOW) {
        fuzz_fxo_euler_ok(a, seq, e, info, band, 0, "to_euler_near");
    } else {
        QO_FUZZ_CHECK(e.a1 == prev.a1 && e.a2 == prev.a2 && e.a3 == prev.a3 && info.locked == 0 && info.margin == 0,
                      "to_euler_near error output is not prev");
    }
    return 0;
}
