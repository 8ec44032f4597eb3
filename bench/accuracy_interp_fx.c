/* Accuracy figures of qorient/interp_fx.h (fixed point, Q1.30) against double-precision
 * references written here from the textbook formulas, side by side with the float32 core on
 * the same inputs. Fixed seeds: the figures are reproducible. Each reference is computed from
 * the exact value of the Q1.30 input the fixed core was given (raw / 2^30), so the figures are
 * the error of the computation, not of the input rounding.
 *
 *   make build/bench/accuracy_interp_fx && ./build/bench/accuracy_interp_fx  (or: make figures)
 *
 * Goals (exit status 1 if one is missed):
 *   slerp rotation error vs double        <= 1e-6 rad and <= the float32 core's worst on the
 *                                         same cases (random pairs and t + the edge table)
 *   the same for qo_interp_slerp_fast_q30   <= 2e-7 rad (issue 14's bound for the fast tier)
 *   |norm - 1| of every result            <= 1e-6
 *   spline: error at the keys             <= 1e-6 rad
 * Other figures (nlerp, Bezier, spline between keys, Squad) are reported only. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "qorient/interp.h"
#include "qorient/interp_fx.h"

#define PI 3.14159265358979323846
#define Q30 1073741824.0

#include "common/dq_interp.h"

static double norm_dev_x(qo_quat_q30 q) { return fabs(dq_norm(dq_from_x(q)) - 1.0); }

/* running maxima */
static double slerp_rot_fast, slerp_rot, slerp_4d, slerp_rot_f, norm_max, bez_err, key_err, spl_err, squad_err;
static double nlerp_err, agree_fx_f, squadc_err;
static long n_slerp, n_norm, n_fail;

static void note_norm(qo_quat_q30 q)
{
    double d = norm_dev_x(q);
    if (d > norm_max) norm_max = d;
    n_norm++;
}

/* One pair: fixed core on the Q1.30 rounding of a, b, t and float32 core on the float
 * rounding, each against the double slerp of the inputs it actually received. */
static void slerp_case(dq a, dq b, double t)
{
    qo_quat_q30 xa = x_from(a), xb = x_from(b), out;
    qo_q30 xt = fx_from_d(t, Q30);
    qo_quat_f32 fa = f_from(a), fb = f_from(b), fo;
    float ft = (float)t;
    dq ua = dq_unit(dq_from_x(xa)), ub = dq_unit(dq_from_x(xb)), ref;
    double e;
    if (xt > QO_Q30_ONE) xt = QO_Q30_ONE;
    if (dq_dot(ua, ub) < 0) ub = dq_neg(ub);
    ref = d_slerp_unit(ua, ub, xt / Q30);
    if (qo_interp_slerp_q30(xa, xb, xt, &out) != QO_OK) {
        n_fail++;
        return;
    }
    e = rot_err(ref, dq_from_x(out));
    if (e > slerp_rot) slerp_rot = e;
    e = dist4(ref, dq_from_x(out));
    if (e > slerp_4d) slerp_4d = e;
    note_norm(out);
    n_slerp++;
    /* the fast tier on the same inputs, against the same reference */
    if (qo_interp_slerp_fast_q30(xa, xb, xt, &out) != QO_OK) {
        n_fail++;
        return;
    }
    e = rot_err(ref, dq_from_x(out));
    if (e > slerp_rot_fast) slerp_rot_fast = e;
    /* float32 core, same case */
    ua = dq_unit(dq_from_f(fa));
    ub = dq_unit(dq_from_f(fb));
    if (dq_dot(ua, ub) < 0) ub = dq_neg(ub);
    if (qo_interp_slerp_f32(fa, fb, ft, &fo) != QO_OK) {
        n_fail++;
        return;
    }
    e = rot_err(d_slerp_unit(ua, ub, (double)ft), dq_from_f(fo));
    if (e > slerp_rot_f) slerp_rot_f = e;
    /* fixed vs float: only meaningful away from the ambiguous exact 180 (dot ~ 0) */
    if (fabs(dq_dot(ua, ub)) > 1e-5) {
        e = rot_err(dq_from_x(out), dq_from_f(fo));
        if (e > agree_fx_f) agree_fx_f = e;
    }
}

#define MAXK 12

static void x_align(const qo_quat_q30 *k, size_t n, dq *q)
{
    size_t i;
    for (i = 0; i < n; i++) {
        q[i] = dq_unit(dq_from_x(k[i]));
        if (i && dq_dot(q[i - 1], q[i]) < 0) q[i] = dq_neg(q[i]);
    }
}
static void rand_keys(qo_quat_q30 *k, size_t n, double maxstep)
{
    dq p = rand_unit();
    size_t i;
    for (i = 0; i < n; i++) {
        if (i) p = dq_mul(p, rand_axis_rot(rng_range(0.05, maxstep)));
        k[i] = x_from(dq_scale(rng_u() < 0.4 ? dq_neg(p) : p, rng_range(0.5, 1.9)));
    }
}

int main(void)
{
    static const double deltas[] = { 0.0, 1e-9, 1e-8, 1e-7, 3e-7, 1e-6, 1e-5, 1e-4, 1e-3,
                                     1.9e-3, 2e-3, 2.1e-3, 1e-2, 0.5, 2.0, PI - 1e-2,
                                     PI - 1e-3, PI - 1e-4, PI - 1e-5 };
    static const double ts[] = { 0.0, 1e-9, 1e-7, 1e-3, 0.25, 1.0 / 3, 0.5, 0.75, 0.999,
                                 0.9999999, 1.0 - 1e-9, 1.0 };
    static const double p180[][2][4] = {
        { { 1, 0, 0, 0 }, { 0, 1, 0, 0 } },
        { { 0.5, 0.5, 0.5, 0.5 }, { 0.5, -0.5, 0.5, -0.5 } },
        { { 0, 0.6, 0.8, 0 }, { 0, -0.8, 0.6, 0 } },
    };
    const int n_random = 20000, n_edge_bases = 40, n_bez = 2000, n_spl = 2000;
    int i, k, sgn, fail = 0;
    size_t di, ti, n, j;
    long n_edge = 0;

    /* ---- slerp: random pairs and t (a third of them non-unit: 0.01 .. 1.99) ---- */
    rng_state = 0x5EEDA11ull;
    for (i = 0; i < n_random; i++) {
        dq a = rand_unit(), b = rand_unit();
        if (i % 3 == 1) {
            a = dq_scale(a, rng_range(0.01, 1.99));
            b = dq_scale(b, rng_range(0.01, 1.99));
        }
        slerp_case(a, b, rng_u());
    }
    /* ---- slerp: edge table (delta x sign of b x t), exact 180 pairs ---- */
    for (k = 0; k < n_edge_bases; k++) {
        dq a = rand_unit();
        for (di = 0; di < sizeof deltas / sizeof deltas[0]; di++) {
            dq b = dq_mul(a, rand_axis_rot(deltas[di]));
            for (sgn = 0; sgn < 2; sgn++)
                for (ti = 0; ti < sizeof ts / sizeof ts[0]; ti++, n_edge++)
                    slerp_case(a, sgn ? dq_neg(b) : b, ts[ti]);
        }
    }
    for (di = 0; di < sizeof p180 / sizeof p180[0]; di++) {
        dq a = { p180[di][0][0], p180[di][0][1], p180[di][0][2], p180[di][0][3] };
        dq b = { p180[di][1][0], p180[di][1][1], p180[di][1][2], p180[di][1][3] };
        for (ti = 0; ti < sizeof ts / sizeof ts[0]; ti++, n_edge++) slerp_case(a, b, ts[ti]);
    }

    /* ---- nlerp ---- */
    for (i = 0; i < 5000; i++) {
        qo_quat_q30 xa = x_from(rand_unit()), xb = x_from(rand_unit()), out;
        qo_q30 xt = fx_from_d(rng_u(), Q30);
        dq ua = dq_unit(dq_from_x(xa)), ub = dq_unit(dq_from_x(xb));
        double e;
        if (dq_dot(ua, ub) < 0) ub = dq_neg(ub);
        qo_interp_nlerp_q30(xa, xb, xt, &out);
        e = dist4(dq_unit(dq_add(dq_scale(ua, 1 - xt / Q30), dq_scale(ub, xt / Q30))),
                  dq_from_x(out));
        if (e > nlerp_err) nlerp_err = e;
        note_norm(out);
    }

    /* ---- Bezier, n = 2..8 ---- */
    for (i = 0; i < n_bez; i++) {
        qo_quat_q30 c[QO_INTERP_BEZIER_MAX_POINTS], out;
        dq p[QO_INTERP_BEZIER_MAX_POINTS];
        qo_q30 t = fx_from_d(rng_u(), Q30);
        double e;
        n = 2 + (size_t)(i % (QO_INTERP_BEZIER_MAX_POINTS - 1));
        rand_keys(c, n, 1.5);
        x_align(c, n, p);
        qo_interp_bezier_q30(c, n, t, &out);
        e = dist4(d_bez(p, n, t / Q30), dq_from_x(out));
        if (e > bez_err) bez_err = e;
        note_norm(out);
    }

    /* ---- Shoemake spline: at the keys and between them; Squad on the same keys ---- */
    for (i = 0; i < n_spl; i++) {
        qo_quat_q30 kf[MAXK], a[MAXK], b[MAXK], out;
        dq q[MAXK], da[MAXK], db[MAXK];
        n = 2 + (size_t)(i % (MAXK - 1));
        rand_keys(kf, n, (i % 2) ? 1.5 : 3.0);
        x_align(kf, n, q);
        d_spline_controls(q, n, da, db);
        qo_interp_spline_controls_q30(kf, n, a, b);
        for (j = 0; j < n; j++) {
            double e;
            qo_interp_spline_eval_q30(kf, a, b, n, (qo_q16)(j * 65536u), &out);
            e = rot_err(q[j], dq_from_x(out));
            if (e > key_err) key_err = e;
            note_norm(out);
        }
        for (k = 0; k < 10; k++) {
            qo_q16 s = (qo_q16)(rng_u() * (double)(n - 1) * 65536.0);
            size_t seg = (size_t)s >> 16;
            dq p[4];
            double e;
            if (seg > n - 2) seg = n - 2;
            p[0] = q[seg]; p[1] = da[seg]; p[2] = db[seg + 1]; p[3] = q[seg + 1];
            qo_interp_spline_eval_q30(kf, a, b, n, s, &out);
            e = rot_err(d_bez(p, 4, s / 65536.0 - (double)seg), dq_from_x(out));
            if (e > spl_err) spl_err = e;
            note_norm(out);
        }
        {   /* Squad: inner points by the fixed core vs the classic formula in double, then
             * segments vs double on those inner points */
            qo_quat_q30 sq[MAXK];
            dq ds[MAXK];
            d_squad_controls(q, n, ds);
            qo_interp_squad_controls_q30(kf, n, sq);
            for (j = 0; j < n; j++) {
                double e = rot_err(ds[j], dq_from_x(sq[j]));
                if (e > squadc_err) squadc_err = e;
            }
            for (k = 0; k < 5; k++) {
                qo_q30 t = fx_from_d(rng_u(), Q30);
                size_t seg = (size_t)(rng_u() * (double)(n - 1));
                dq x, y, s0 = dq_unit(dq_from_x(sq[seg])), s1 = dq_unit(dq_from_x(sq[seg + 1]));
                double tt = t / Q30, e;
                if (dq_dot(s0, q[seg]) < 0) s0 = dq_neg(s0);
                if (dq_dot(s1, q[seg + 1]) < 0) s1 = dq_neg(s1);
                x = d_slerp_unit(q[seg], q[seg + 1], tt);
                y = d_slerp_unit(s0, s1, tt);
                qo_interp_squad_q30(kf[seg], sq[seg], sq[seg + 1], kf[seg + 1], t, &out);
                e = rot_err(d_slerp_unit(x, y, 2.0 * tt * (1.0 - tt)), dq_from_x(out));
                if (e > squad_err) squad_err = e;
                note_norm(out);
            }
        }
    }

    printf("qorient interp_fx accuracy (Q1.30 fixed point vs double references, fixed seeds)\n");
    printf("slerp: %ld cases (%d random pairs/t, %ld edge-table cases), %ld failed calls\n",
           n_slerp, n_random, n_edge, n_fail);
    printf("  worst rotation error, fixed   %.3g rad   (goal <= 1e-6 and <= float32) %s\n",
           slerp_rot, (slerp_rot <= 1e-6 && slerp_rot <= slerp_rot_f) ? "ok" : "MISSED");
    printf("  worst rotation error, fast    %.3g rad   (qo_interp_slerp_fast_q30; goal <= 2e-7) %s\n",
           slerp_rot_fast, slerp_rot_fast <= 2e-7 ? "ok" : "MISSED");
    printf("  worst rotation error, float32 %.3g rad   (same cases, float32 inputs)\n",
           slerp_rot_f);
    printf("  worst 4-D error (signed)      %.3g\n", slerp_4d);
    printf("  fixed vs float32 (dot > 1e-5) %.3g rad\n", agree_fx_f);
    printf("|norm - 1|, all %ld results    %.3g       (goal <= 1e-6) %s\n", n_norm, norm_max,
           norm_max <= 1e-6 ? "ok" : "MISSED");
    printf("nlerp: worst 4-D error              %.3g\n", nlerp_err);
    printf("bezier n=2..8: worst 4-D error      %.3g\n", bez_err);
    printf("spline: worst error at the keys     %.3g rad   (goal <= 1e-6) %s\n", key_err,
           key_err <= 1e-6 ? "ok" : "MISSED");
    printf("spline: worst error between keys    %.3g rad   (vs double construction)\n", spl_err);
    printf("squad: worst inner-point error      %.3g rad   (vs double formula)\n", squadc_err);
    printf("squad: worst segment error          %.3g rad   (vs double, same inner points)\n",
           squad_err);
    if (slerp_rot > 1e-6 || slerp_rot > slerp_rot_f || slerp_rot_fast > 2e-7 || norm_max > 1e-6 || key_err > 1e-6 ||
        n_fail != 0)
        fail = 1;
    return fail;
}
