/* Accuracy figures of the fixed-point core against double libm.
 *
 *   make build/bench/accuracy_fx && build/bench/accuracy_fx      (or: make figures)
 *
 * Part 1: worst error of each primitive in LSB of its output format, over its whole domain
 *         (strided sweeps of the full int32 range plus fixed-seed random inputs and edges).
 * Part 2: worst rotation error in radians of each fixed quaternion operation / conversion over
 *         N fixed-seed random rotations, END TO END: the double rotation is rounded to Q1.30 /
 *         Q3.28 (round to nearest, in this program), run through the fixed core, and compared
 *         with the double result of the ORIGINAL double input. Goal: <= 1e-6 rad.
 * Exits 1 if a primitive exceeds its documented LSB bound or a rotation error misses the goal.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "common/dq.h"
#include "qorient/convert_fx.h"
#include "qorient/fxmath.h"
#include "qorient/quat_fx.h"

#define NROT 100000
#define GOAL_RAD 1e-6

/* double reference and fixed-seed PRNG: tests/common/ref.c (dq.h) */
static ref_rng rng = { 0x5EEDULL };
static int32_t rnd_i32_mag(void)
{
    int32_t v = (int32_t)(uint32_t)ref_rng_next(&rng);
    return (int32_t)(v / ((int64_t)1 << (ref_rng_next(&rng) % 32u)));
}

static int failures;
static void report_lsb(const char *name, double worst, double bound)
{
    printf("  %-34s worst %.3f LSB (bound %.2f)%s\n", name, worst, bound, worst <= bound ? "" : "  MISSED");
    if (worst > bound) failures++;
}
static void report_rad(const char *name, double worst)
{
    printf("  %-34s worst %.3e rad%s\n", name, worst, worst <= GOAL_RAD ? "" : "  MISSED");
    if (worst > GOAL_RAD) failures++;
}
static void upd(double *w, double e) { if (e > *w) *w = e; }

static int32_t q30(double v) { return ref_to_fixed(v, REF_Q30); }
static int32_t q28(double v) { return ref_to_fixed(v, REF_Q28); }
static void drot(dq q, const double v[3], double o[3])
{
    ref_vec3 r = ref_quat_rotate(q, (ref_vec3){ v[0], v[1], v[2] });
    o[0] = r.x; o[1] = r.y; o[2] = r.z;
}

static void primitives(void)
{
    double w;
    int64_t k;
    int32_t o;
    printf("Part 1: primitives, worst error in LSB of the output format\n");
    /* mul (Q1.30 x Q1.30): reference in long double (products are exact in 64 bits). */
    w = 0;
    for (k = 0; k < 4000000; k++) {
        int32_t a = rnd_i32_mag(), b = rnd_i32_mag();
        long double ref = (long double)a * b / REF_Q30;
        if (ref < 2147483647.0L && ref > -2147483648.0L) upd(&w, (double)fabsl(qo_fx_mul_q30(a, b) - ref));
    }
    report_lsb("qo_fx_mul_q30", w, 0.5);
    w = 0;
    for (k = 0; k < 4000000; k++) {
        int32_t a = rnd_i32_mag(), b = rnd_i32_mag();
        long double ref;
        if (b == 0) continue;
        ref = (long double)a * REF_Q30 / b;
        if (qo_fx_div_q30(a, b, &o) == QO_OK) upd(&w, (double)fabsl(o - ref));
    }
    report_lsb("qo_fx_div_q30", w, 0.5);
    w = 0;
    for (k = 0; k <= INT32_MAX; k += 211) {
        (void)qo_fx_sqrt_q30((int32_t)k, &o);
        upd(&w, fabs(o - sqrt((double)k / REF_Q30) * REF_Q30));
    }
    report_lsb("qo_fx_sqrt_q30 (all x >= 0 / 211)", w, 0.5);
    w = 0;
    for (k = QO_Q30_ONE / 4 + 1; k <= INT32_MAX; k += 157) {
        (void)qo_fx_rsqrt_q30((int32_t)k, &o);
        upd(&w, fabs(o - REF_Q30 / sqrt((double)k / REF_Q30)));
    }
    report_lsb("qo_fx_rsqrt_q30 (x > 0.25 / 157)", w, 1.0);
    w = 0;
    {
        double wh = 0;
        for (k = INT32_MIN; k <= INT32_MAX; k += 257) {
            qo_q30 s, c;
            double a = (double)k / REF_Q28;
            (void)qo_fx_sincos_q28((int32_t)k, &s, &c);
            upd(&w, fabs(s - sin(a) * REF_Q30));
            upd(&w, fabs(c - cos(a) * REF_Q30));
            (void)qo_fx_sincos_half_q28((int32_t)k, &s, &c);
            upd(&wh, fabs(s - sin(a / 2) * REF_Q30));
            upd(&wh, fabs(c - cos(a / 2) * REF_Q30));
        }
        report_lsb("qo_fx_sincos_q28 (all int32 / 257)", w, 1.0);
        report_lsb("qo_fx_sincos_half_q28 (same)", wh, 1.0);
    }
    w = 0;
    for (k = 0; k < 4000000; k++) {
        int32_t y = rnd_i32_mag(), x = rnd_i32_mag();
        double ref = atan2((double)y, (double)x) * REF_Q28;
        if (y == 0 && x < 0) ref = REF_PI * REF_Q28;
        upd(&w, fabs(qo_fx_atan2_q28(y, x) - ref));
    }
    report_lsb("qo_fx_atan2_q28 (4M random)", w, 1.0);
    w = 0;
    {
        double wc = 0;
        for (k = -QO_Q30_ONE; k <= QO_Q30_ONE; k += (k > QO_Q30_ONE - 100000 || k < -QO_Q30_ONE + 100000) ? 1 : 251) {
            double x = (double)k / REF_Q30;
            upd(&w, fabs(qo_fx_asin_q28((int32_t)k) - asin(x) * REF_Q28));
            upd(&wc, fabs(qo_fx_acos_q28((int32_t)k) - acos(x) * REF_Q28));
        }
        report_lsb("qo_fx_asin_q28 ([-1,1], ends dense)", w, 1.0);
        report_lsb("qo_fx_acos_q28 ([-1,1], ends dense)", wc, 1.0);
    }
    w = 0;
    for (k = 0; k < 2000000; k++) {
        int32_t a = (int32_t)(uint32_t)ref_rng_next(&rng);
        upd(&w, fabs(qo_fx_wrap_pi_q28(a) - remainder((double)a / REF_Q28, 2 * REF_PI) * REF_Q28));
    }
    report_lsb("qo_fx_wrap_pi_q28", w, 0.5 + 1e-3);
    w = 0;
    for (k = 0; k < 2000000; k++) {
        int32_t a = rnd_i32_mag() / 2, b = rnd_i32_mag() / 2, c = rnd_i32_mag() / 2;
        long double ref = sqrtl((long double)a * a + (long double)b * b + (long double)c * c);
        upd(&w, (double)fabsl(qo_fx_norm3_q30(a, b, c) - ref));
    }
    report_lsb("qo_fx_norm3_q30", w, 0.5);
}

static void rotations(void)
{
    double wmul = 0, wrot = 0, wnorm = 0, wnormf = 0, waa_from = 0, waa_to = 0, wrv_from = 0, wrv_to = 0;
    double wm_to = 0, wm_from = 0, wexp = 0, wlog = 0, wint = 0, wang = 0;
    int k, i, j;
    printf("Part 2: rotation error vs double over %d fixed-seed random rotations (end to end)\n", NROT);
    for (k = 0; k < NROT; k++) {
        dq a = ref_rng_quat(&rng), b = ref_rng_quat(&rng), r;
        qo_quat_q30 fa = ref_quat_to_q30(a), fb = ref_quat_to_q30(b), fr;
        double v[3], vr[3], e;
        qo_vec3_q30 fv, fo;
        qo_vec3_q28 rv;
        qo_vec3_q30 ax;
        qo_q28 an;
        qo_mat3_q30 m;
        double dm[3][3];

        /* multiply */
        fr = qo_quat_mul_q30(fa, fb);
        upd(&wmul, dq_angle(ref_quat_normalize(ref_quat_from_q30(fr)), dq_mul(a, b)));
        /* rotate a unit vector: angle between the rotated vectors */
        v[0] = ref_rng_range(&rng, -1.0, 1.0); v[1] = ref_rng_range(&rng, -1.0, 1.0); v[2] = ref_rng_range(&rng, -1.0, 1.0);
        e = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        for (i = 0; i < 3; i++) v[i] /= e;
        fv.x = q30(v[0]); fv.y = q30(v[1]); fv.z = q30(v[2]);
        fo = qo_quat_rotate_q30(fa, fv);
        drot(a, v, vr);
        upd(&wrot, sqrt(pow(fo.x / REF_Q30 - vr[0], 2) + pow(fo.y / REF_Q30 - vr[1], 2) + pow(fo.z / REF_Q30 - vr[2], 2)));
        /* normalise a scaled copy (scale 2^-20 .. 1.9): direction and |1 - |out|| */
        {
            double s = ldexp(1.0, -(int)(ref_rng_next(&rng) % 21u)) * (1.0 + 0.9 * ref_rng_unit(&rng));
            dq sa = { a.w * s, a.x * s, a.y * s, a.z * s };
            qo_quat_q30 in = ref_quat_to_q30(sa);
            (void)qo_quat_normalize_q30(in, &fr);
            /* Against the double normalisation of the exact fixed input: a short quaternion
             * has only a few significant bits, which no normalisation can restore. */
            upd(&wnorm, dq_angle(ref_quat_from_q30(fr), ref_quat_normalize(ref_quat_from_q30(in))));
            /* and the unit-ness of the output */
            upd(&wnorm, fabs(sqrt(ref_quat_from_q30(fr).w * ref_quat_from_q30(fr).w + ref_quat_from_q30(fr).x * ref_quat_from_q30(fr).x + ref_quat_from_q30(fr).y * ref_quat_from_q30(fr).y + ref_quat_from_q30(fr).z * ref_quat_from_q30(fr).z) - 1.0));
            /* the fast tier, same input, same two measures */
            (void)qo_quat_normalize_fast_q30(in, &fr);
            upd(&wnormf, dq_angle(ref_quat_from_q30(fr), ref_quat_normalize(ref_quat_from_q30(in))));
            upd(&wnormf, fabs(sqrt(ref_quat_from_q30(fr).w * ref_quat_from_q30(fr).w + ref_quat_from_q30(fr).x * ref_quat_from_q30(fr).x + ref_quat_from_q30(fr).y * ref_quat_from_q30(fr).y + ref_quat_from_q30(fr).z * ref_quat_from_q30(fr).z) - 1.0));
        }
        /* axis-angle from / to */
        {
            double ang = 2 * REF_PI * ref_rng_range(&rng, -1.0, 1.0), s = sin(ang / 2);
            dq ref = { cos(ang / 2), s * v[0], s * v[1], s * v[2] };
            (void)qo_axis_angle_to_quat_q30(fv, q28(ang), &fr);
            upd(&waa_from, dq_angle(ref_quat_normalize(ref_quat_from_q30(fr)), ref));
            (void)qo_axis_angle_from_quat_q30(fa, &ax, &an);
            /* rebuild in double and compare rotations */
            s = sin(an / REF_Q28 / 2);
            ref.w = cos(an / REF_Q28 / 2); ref.x = s * ax.x / REF_Q30; ref.y = s * ax.y / REF_Q30; ref.z = s * ax.z / REF_Q30;
            upd(&waa_to, dq_angle(ref, a));
        }
        /* rotation vector from / to */
        {
            double ang = REF_PI * ref_rng_unit(&rng), s;
            dq ref;
            rv.x = q28(v[0] * ang); rv.y = q28(v[1] * ang); rv.z = q28(v[2] * ang);
            (void)qo_rotvec_to_quat_q30(rv, &fr);
            s = sin(ang / 2);
            ref.w = cos(ang / 2); ref.x = s * v[0]; ref.y = s * v[1]; ref.z = s * v[2];
            upd(&wrv_from, dq_angle(ref_quat_normalize(ref_quat_from_q30(fr)), ref));
            (void)qo_rotvec_from_quat_q30(fr, &rv);
            r = a.w < 0 ? (dq){ -a.w, -a.x, -a.y, -a.z } : a;
            (void)qo_rotvec_from_quat_q30(fa, &rv);
            e = sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
            e = e > 0 ? 2 * atan2(e, r.w) / e : 2.0;
            upd(&wrv_to, sqrt(pow(rv.x / REF_Q28 - e * r.x, 2) + pow(rv.y / REF_Q28 - e * r.y, 2) + pow(rv.z / REF_Q28 - e * r.z, 2)));
        }
        /* matrix to / from (to: largest entry error, which bounds the rotation error) */
        (void)qo_mat3_from_quat_q30(fa, &m);
        dq_to_mat(a, dm);
        for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) upd(&wm_to, fabs(m.m[i][j] / REF_Q30 - dm[i][j]));
        dq_to_mat(b, dm);
        for (i = 0; i < 3; i++) for (j = 0; j < 3; j++) m.m[i][j] = q30(dm[i][j]);
        (void)qo_mat3_to_quat_q30(&m, &fr);
        upd(&wm_from, dq_angle(ref_quat_from_q30(fr), b));
        /* exp / log of the half-angle vector */
        {
            double ang = REF_PI * ref_rng_unit(&rng), s;
            dq ref;
            rv.x = q28(v[0] * ang / 2); rv.y = q28(v[1] * ang / 2); rv.z = q28(v[2] * ang / 2);
            (void)qo_quat_exp_q30(rv, &fr);
            s = sin(ang / 2);
            ref.w = cos(ang / 2); ref.x = s * v[0]; ref.y = s * v[1]; ref.z = s * v[2];
            upd(&wexp, dq_angle(ref_quat_normalize(ref_quat_from_q30(fr)), ref));
            (void)qo_quat_log_q30(ref_quat_to_q30(ref), &rv);
            upd(&wlog, 2 * sqrt(pow(rv.x / REF_Q28 - v[0] * ang / 2, 2) + pow(rv.y / REF_Q28 - v[1] * ang / 2, 2) + pow(rv.z / REF_Q28 - v[2] * ang / 2, 2)));
        }
        /* integrate one step of a body rate: q * exp(dtheta/2) */
        {
            double step = 0.1 * ref_rng_unit(&rng), s;
            dq inc;
            rv.x = q28(v[0] * step); rv.y = q28(v[1] * step); rv.z = q28(v[2] * step);
            (void)qo_quat_integrate_q30(fa, rv, &fr);
            s = sin(step / 2);
            inc.w = cos(step / 2); inc.x = s * v[0]; inc.y = s * v[1]; inc.z = s * v[2];
            upd(&wint, dq_angle(ref_quat_from_q30(fr), dq_mul(a, inc)));
        }
        /* angle between */
        upd(&wang, fabs(qo_quat_angle_between_q30(fa, fb) / REF_Q28 - dq_angle(a, b)));
    }
    report_rad("qo_quat_mul_q30", wmul);
    report_rad("qo_quat_rotate_q30 (|v| = 1)", wrot);
    report_rad("qo_quat_normalize_q30 (|q| 1e-6..1.9)", wnorm);
    report_rad("qo_quat_normalize_fast_q30 (same)", wnormf);
    report_rad("qo_axis_angle_to_quat_q30", waa_from);
    report_rad("qo_axis_angle_from_quat_q30", waa_to);
    report_rad("qo_rotvec_to_quat_q30", wrv_from);
    report_rad("qo_rotvec_from_quat_q30", wrv_to);
    report_rad("qo_mat3_from_quat_q30 (max entry)", wm_to);
    report_rad("qo_mat3_to_quat_q30", wm_from);
    report_rad("qo_quat_exp_q30", wexp);
    report_rad("qo_quat_log_q30 (x2 = rotation)", wlog);
    report_rad("qo_quat_integrate_q30", wint);
    report_rad("qo_quat_angle_between_q30", wang);
}

int main(void)
{
    primitives();
    rotations();
    printf("%s\n", failures ? "accuracy_fx: goal MISSED" : "accuracy_fx: all goals met");
    return failures ? 1 : 0;
}
