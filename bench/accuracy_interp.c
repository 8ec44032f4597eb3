/* Accuracy figures of qorient/interp.h (float32) against double-precision references written
 * here from the textbook formulas. Fixed seeds: the figures are reproducible.
 *
 *   make build/bench/accuracy_interp && ./build/bench/accuracy_interp     (or: make figures)
 *
 * Goals (exit status 1 if one is missed):
 *   slerp rotation error vs double        <= 1e-6 rad   (random pairs and t + the edge table)
 *   |norm - 1| of every result            <= 1e-6
 *   spline: error at the keys             <= 1e-6 rad
 * Other figures (long-way slerp, Bezier, spline between keys, Squad) are reported only. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "qorient/interp.h"
#include "qorient/quat.h"

#define PI 3.14159265358979323846

#include "common/dq_interp.h"
static dq dq_from(qo_quat_f32 q) { dq r = { q.w, q.x, q.y, q.z }; return r; }
static double norm_dev(qo_quat_f32 q) { return fabs(dq_norm(dq_from(q)) - 1.0); }

/* running maxima */
static double slerp_rot, slerp_4d, norm_max, long_k, bez_err, key_err, spl_err, squad_err;
static long n_slerp, n_norm;

static void note_norm(qo_quat_f32 q)
{
    double d = norm_dev(q);
    if (d > norm_max) norm_max = d;
    n_norm++;
}

static void slerp_case(qo_quat_f32 a, qo_quat_f32 b, float t)
{
    qo_quat_f32 out;
    dq ua = dq_unit(dq_from(a)), ub = dq_unit(dq_from(b)), ref;
    double e;
    if (dq_dot(ua, ub) < 0) ub = dq_neg(ub);
    ref = d_slerp_unit(ua, ub, (double)t);
    if (qo_interp_slerp_f32(a, b, t, &out) != QO_OK) {
        printf("slerp failed\n");
        slerp_rot = INFINITY;
        return;
    }
    e = rot_err(ref, dq_from(out));
    if (e > slerp_rot) slerp_rot = e;
    e = dist4(ref, dq_from(out));
    if (e > slerp_4d) slerp_4d = e;
    note_norm(out);
    n_slerp++;
}

#define MAXK 12

static void d_align(const qo_quat_f32 *k, size_t n, dq *q)
{
    size_t i;
    for (i = 0; i < n; i++) {
        q[i] = dq_unit(dq_from(k[i]));
        if (i && dq_dot(q[i - 1], q[i]) < 0) q[i] = dq_neg(q[i]);
    }
}
static void rand_keys(qo_quat_f32 *k, size_t n, double maxstep)
{
    dq p = rand_unit();
    size_t i;
    for (i = 0; i < n; i++) {
        if (i) p = dq_mul(p, rand_axis_rot(rng_range(0.05, maxstep)));
        k[i] = f_from(dq_scale(rng_u() < 0.4 ? dq_neg(p) : p, rng_range(0.5, 2)));
    }
}

int main(void)
{
    static const double deltas[] = { 0.0, 1e-7, 3e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1.9e-3, 2e-3,
                                     2.1e-3, 1e-2, 0.5, 2.0, PI - 1e-2, PI - 1e-3, PI - 1e-4,
                                     PI - 1e-5 };
    static const float ts[] = { 0.0f, 1e-7f, 1e-3f, 0.25f, 0.5f, 0.75f, 0.999f, 0.9999999f,
                                1.0f };
    static const qo_quat_f32 p180[][2] = {
        { { 1.0f, 0.0f, 0.0f, 0.0f }, { 0.0f, 1.0f, 0.0f, 0.0f } },
        { { 0.5f, 0.5f, 0.5f, 0.5f }, { 0.5f, -0.5f, 0.5f, -0.5f } },
        { { 0.0f, 0.6f, 0.8f, 0.0f }, { 0.0f, -0.8f, 0.6f, 0.0f } },
    };
    const int n_random = 20000, n_edge_bases = 40, n_long = 5000, n_bez = 2000, n_spl = 2000;
    int i, k, sgn, fail = 0;
    size_t di, ti, n, j;
    long n_edge = 0;

    /* ---- slerp: random pairs and t (a third of them non-unit) ---- */
    rng_state = 0x5EEDA11ull;
    for (i = 0; i < n_random; i++) {
        dq a = rand_unit(), b = rand_unit();
        if (i % 3 == 1) {
            a = dq_scale(a, pow(10.0, rng_range(-3, 3)));
            b = dq_scale(b, pow(10.0, rng_range(-3, 3)));
        }
        slerp_case(f_from(a), f_from(b), (float)rng_u());
    }
    /* ---- slerp: edge table (delta x sign of b x t), exact 180 pairs ---- */
    for (k = 0; k < n_edge_bases; k++) {
        dq a = rand_unit();
        for (di = 0; di < sizeof deltas / sizeof deltas[0]; di++) {
            dq b = dq_mul(a, rand_axis_rot(deltas[di]));
            for (sgn = 0; sgn < 2; sgn++)
                for (ti = 0; ti < sizeof ts / sizeof ts[0]; ti++, n_edge++)
                    slerp_case(f_from(a), f_from(sgn ? dq_neg(b) : b), ts[ti]);
        }
    }
    for (di = 0; di < sizeof p180 / sizeof p180[0]; di++)
        for (ti = 0; ti < sizeof ts / sizeof ts[0]; ti++, n_edge++)
            slerp_case(p180[di][0], p180[di][1], ts[ti]);

    /* ---- long way: error * phi (conditioning ~ 1/phi near phi = 0) ---- */
    for (i = 0; i < n_long; i++) {
        dq a = rand_unit(), b = dq_mul(a, rand_axis_rot(pow(10.0, rng_range(-2.5, 0.5))));
        qo_quat_f32 fa = f_from(a), fb = f_from(b), out;
        dq ua = dq_unit(dq_from(fa)), ub = dq_unit(dq_from(fb));
        double phi = rot_err(ua, ub), e;
        float t = (float)rng_u();
        if (dq_dot(ua, ub) > 0) ub = dq_neg(ub);
        if (qo_interp_slerp_long_f32(fa, fb, t, &out) != QO_OK) continue; /* phi < 0.002 refused */
        e = dist4(d_slerp_unit(ua, ub, (double)t), dq_from(out)) * phi;
        if (e > long_k) long_k = e;
        note_norm(out);
    }

    /* ---- Bezier, n = 2..8 ---- */
    for (i = 0; i < n_bez; i++) {
        qo_quat_f32 c[QO_INTERP_BEZIER_MAX_POINTS], out;
        dq p[QO_INTERP_BEZIER_MAX_POINTS];
        float t = (float)rng_u();
        double e;
        n = 2 + (size_t)(i % (QO_INTERP_BEZIER_MAX_POINTS - 1));
        rand_keys(c, n, 1.5);
        d_align(c, n, p);
        qo_interp_bezier_f32(c, n, t, &out);
        e = dist4(d_bez(p, n, (double)t), dq_from(out));
        if (e > bez_err) bez_err = e;
        note_norm(out);
    }

    /* ---- Shoemake spline: at the keys and between them ---- */
    for (i = 0; i < n_spl; i++) {
        qo_quat_f32 kf[MAXK], a[MAXK], b[MAXK], out;
        dq q[MAXK], da[MAXK], db[MAXK];
        n = 2 + (size_t)(i % (MAXK - 1));
        rand_keys(kf, n, (i % 2) ? 1.5 : 3.0);
        d_align(kf, n, q);
        d_spline_controls(q, n, da, db);
        qo_interp_spline_controls_f32(kf, n, a, b);
        for (j = 0; j < n; j++) {
            double e;
            qo_interp_spline_eval_f32(kf, a, b, n, (float)j, &out);
            e = rot_err(q[j], dq_from(out));
            if (e > key_err) key_err = e;
            note_norm(out);
        }
        for (k = 0; k < 10; k++) {
            float s = (float)(rng_u() * (double)(n - 1));
            size_t seg = (size_t)s;
            dq p[4];
            double e;
            if (seg > n - 2) seg = n - 2;
            p[0] = q[seg]; p[1] = da[seg]; p[2] = db[seg + 1]; p[3] = q[seg + 1];
            qo_interp_spline_eval_f32(kf, a, b, n, s, &out);
            e = rot_err(d_bez(p, 4, (double)s - (double)seg), dq_from(out));
            if (e > spl_err) spl_err = e;
            note_norm(out);
        }
        /* Squad through the same keys (controls computed in float; segment vs double) */
        {
            qo_quat_f32 sq[MAXK];
            qo_interp_squad_controls_f32(kf, n, sq);
            for (k = 0; k < 5; k++) {
                float t = (float)rng_u();
                size_t seg = (size_t)(rng_u() * (double)(n - 1));
                dq x, y, s0 = dq_unit(dq_from(sq[seg])), s1 = dq_unit(dq_from(sq[seg + 1]));
                double e;
                if (dq_dot(s0, q[seg]) < 0) s0 = dq_neg(s0);
                if (dq_dot(s1, q[seg + 1]) < 0) s1 = dq_neg(s1);
                x = d_slerp_unit(q[seg], q[seg + 1], (double)t);
                y = d_slerp_unit(s0, s1, (double)t);
                qo_interp_squad_f32(kf[seg], sq[seg], sq[seg + 1], kf[seg + 1], t, &out);
                e = rot_err(d_slerp_unit(x, y, 2.0 * (double)t * (1.0 - (double)t)),
                            dq_from(out));
                if (e > squad_err) squad_err = e;
                note_norm(out);
            }
        }
    }

    printf("qorient interp accuracy (float32 vs double references, fixed seeds)\n");
    printf("slerp: %ld cases (%d random pairs/t, %ld edge-table cases)\n", n_slerp, n_random,
           n_edge);
    printf("  worst rotation error        %.3g rad   (goal <= 1e-6) %s\n", slerp_rot,
           slerp_rot <= 1e-6 ? "ok" : "MISSED");
    printf("  worst 4-D error (signed)    %.3g\n", slerp_4d);
    printf("|norm - 1|, all %ld results   %.3g       (goal <= 1e-6) %s\n", n_norm, norm_max,
           norm_max <= 1e-6 ? "ok" : "MISSED");
    printf("slerp_long: worst 4-D error x phi   %.3g rad^2 (error ~ this / phi)\n", long_k);
    printf("bezier n=2..8: worst 4-D error      %.3g\n", bez_err);
    printf("spline: worst error at the keys     %.3g rad   (goal <= 1e-6) %s\n", key_err,
           key_err <= 1e-6 ? "ok" : "MISSED");
    printf("spline: worst error between keys    %.3g rad   (vs double construction)\n", spl_err);
    printf("squad: worst error                  %.3g rad   (vs double, float controls)\n",
           squad_err);
    if (slerp_rot > 1e-6 || norm_max > 1e-6 || key_err > 1e-6) fail = 1;
    return fail;
}
