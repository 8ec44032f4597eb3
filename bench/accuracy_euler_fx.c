/* accuracy_euler_fx - measured accuracy of the fixed-point Euler conversions (Q1.30
 * quaternions, Q3.28 angles), all 24 conventions: the figures of bench/accuracy_euler.c for
 * the fixed core.
 *
 *   make build/bench/accuracy_euler_fx && build/bench/accuracy_euler_fx [N]
 *
 * For N (default 20000, at least 10000) fixed-seed random cases per convention it measures,
 * against a double-precision reference (products of elementary rotations from the
 * convention's letters, tests/common/ref.c):
 *   - from_euler: angle between the Q1.30 quaternion and the double one of the same Q3.28
 *     angles, and the largest component error (LSB of Q1.30);
 *   - to_euler, generic: uniformly random rotations rounded to Q1.30; the returned Q3.28
 *     angles composed in double vs the Q1.30 input rotation (the "recomposition error");
 *   - to_euler at lock: middle angle exactly singular, built in double and rounded to Q1.30,
 *     and built by qo_euler_to_quat_q30 with the Q3.28 nearest the singular angle;
 *   - singular rotations whose components were then moved by up to 2 LSB each (how much
 *     fixed-point noise the lock band absorbs);
 *   - to_euler near lock: middle angle 1e-9 ... 0.035 rad off singular, both sides;
 *   - the gimbal-lock flag: the largest margin at which it was raised, the largest margin seen
 *     at an exactly singular input, and whether every exactly singular input was flagged;
 *   - the nearest-solution variant with random prev, generic inputs;
 *   - time per call of to_euler / from_euler (host, informative only).
 * Exit status 1 if a goal is missed: generic <= 1e-6 rad (also from_euler and the nearest
 * variant), at/near lock <= 1e-5 rad, the flag never raised more than 2 degrees from the
 * singularity, always raised at an exact singularity (all three ways of building one).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "common/dq.h"
#include "qorient/euler_fx.h"
#include "qorient/fxmath.h"

/* double reference, the 24 convention names and fixed-seed PRNG: tests/common/ref.c */
static ref_rng rng = { 0x5EED0E17ull };

static double recomp(int seq, qo_euler_q28 e, dq q)
{
    return dq_angle(ref_quat_from_euler(ref_euler_names[seq], e.a1 / REF_Q28, e.a2 / REF_Q28, e.a3 / REF_Q28), q);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void upd(double *worst, double v, int seq, int *worst_seq)
{
    if (v > *worst) { *worst = v; if (worst_seq) *worst_seq = seq; }
}

int main(int argc, char **argv)
{
    static const double offs[] = { 1e-9, 5e-9, 2e-8, 5e-8, 1e-7, 1.5e-7, 3e-7, 1e-6, 1e-5,
                                   1e-4, 1e-3, 0.01, 0.035 };
    const double two_deg = 2.0 * REF_PI / 180.0;
    long n_per = argc > 1 ? atol(argv[1]) : 20000;
    double w_from = 0, w_from_lsb = 0, w_gen = 0, w_lock = 0, w_near_in = 0, w_near_out = 0;
    double w_nearfn = 0, max_flag_margin = 0, max_exact_margin = 0, max_exact_margin_f = 0;
    double max_noisy_margin = 0;
    long n_exact = 0, n_exact_flagged = 0, n_flagged_total = 0, n_cases = 0;
    long n_noisy = 0, n_noisy_flagged = 0, n_bad_status = 0;
    double w_fast_gen = 0, w_fast_lock = 0, w_fast_near_in = 0, w_fast_near_out = 0;
    long n_fast_unflagged = 0;
    int s_fast_gen = 0;
    int s_from = 0, s_gen = 0, s_lock = 0, s_near = 0, seq;
    int ok = 1;
    long i;
    if (n_per < 10000) n_per = 10000;

    for (seq = 0; seq < 24; seq++) {
        qo_euler_seq sq = (qo_euler_seq)seq;
        for (i = 0; i < n_per; i++) {
            qo_euler_q28 e, o;
            qo_euler_info_q28 info;
            qo_quat_q30 qf;
            dq r, rr;
            double nn, s, a1, a3, a2, d;
            int k, which, side;

            /* from_euler (every tenth case over the whole Q3.28 range, [-8, 8) rad) */
            {
                double span = (i % 10 == 0) ? 7.999 : REF_PI;
                e.a1 = ref_to_fixed(ref_rng_range(&rng, -span, span), REF_Q28); e.a2 = ref_to_fixed(ref_rng_range(&rng, -span, span), REF_Q28);
                e.a3 = ref_to_fixed(ref_rng_range(&rng, -span, span), REF_Q28);
                if (qo_euler_to_quat_q30(sq, e, &qf) != QO_OK) n_bad_status++;
                r = ref_quat_from_euler(ref_euler_names[seq], e.a1 / REF_Q28, e.a2 / REF_Q28, e.a3 / REF_Q28);
                upd(&w_from, dq_angle(ref_quat_normalize(ref_quat_from_q30(qf)), r), seq, &s_from);
                d = fabs(qf.w - r.w * REF_Q30);
                if (fabs(qf.x - r.x * REF_Q30) > d) d = fabs(qf.x - r.x * REF_Q30);
                if (fabs(qf.y - r.y * REF_Q30) > d) d = fabs(qf.y - r.y * REF_Q30);
                if (fabs(qf.z - r.z * REF_Q30) > d) d = fabs(qf.z - r.z * REF_Q30);
                upd(&w_from_lsb, d, 0, NULL);
            }

            /* generic: uniform random rotation */
            do {
                r.w = ref_rng_range(&rng, -1, 1); r.x = ref_rng_range(&rng, -1, 1); r.y = ref_rng_range(&rng, -1, 1); r.z = ref_rng_range(&rng, -1, 1);
                nn = r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z;
            } while (nn > 1.0 || nn < 1e-4);
            nn = sqrt(nn);
            r.w /= nn; r.x /= nn; r.y /= nn; r.z /= nn;
            qf = ref_quat_to_q30(r);
            r = ref_quat_normalize(ref_quat_from_q30(qf));
            if (qo_euler_from_quat_q30(qf, sq, &o, &info) != QO_OK) n_bad_status++;
            n_cases++;
            if (info.locked) { n_flagged_total++; upd(&max_flag_margin, info.margin / REF_Q28, 0, NULL); }
            upd(&w_gen, recomp(seq, o, r), seq, &s_gen);
            if (qo_euler_from_quat_fast_q30(qf, sq, QO_EULER_LOCK_BAND_Q28, &o, &info) != QO_OK) n_bad_status++;
            upd(&w_fast_gen, recomp(seq, o, r), seq, &s_fast_gen);

            /* nearest-solution variant, generic, prev a random nearby-ish triple */
            {
                qo_euler_q28 prev;
                prev.a1 = o.a1 + ref_to_fixed(ref_rng_range(&rng, -2, 2), REF_Q28); prev.a2 = o.a2 + ref_to_fixed(ref_rng_range(&rng, -2, 2), REF_Q28);
                prev.a3 = o.a3 + ref_to_fixed(ref_rng_range(&rng, -2, 2), REF_Q28);
                if (qo_euler_from_quat_near_q30(qf, sq, prev, QO_EULER_LOCK_BAND_Q28, &o, &info) != QO_OK)
                    n_bad_status++;
                upd(&w_nearfn, recomp(seq, o, r), seq, NULL);
            }

            /* exactly singular, built in double and rounded to Q1.30 */
            a1 = ref_rng_range(&rng, -REF_PI, REF_PI); a3 = ref_rng_range(&rng, -REF_PI, REF_PI);
            which = (int)(ref_rng_next(&rng) & 1);
            s = ref_euler_proper(seq) ? (which ? REF_PI : 0.0) : (which ? REF_PI / 2 : -REF_PI / 2);
            qf = ref_quat_to_q30(ref_quat_from_euler(ref_euler_names[seq], a1, s, a3));
            r = ref_quat_normalize(ref_quat_from_q30(qf));
            qo_euler_from_quat_q30(qf, sq, &o, &info);
            n_exact++; n_cases++;
            if (info.locked) { n_exact_flagged++; n_flagged_total++; upd(&max_flag_margin, info.margin / REF_Q28, 0, NULL); }
            upd(&max_exact_margin, info.margin / REF_Q28, 0, NULL);
            upd(&w_lock, recomp(seq, o, r), seq, &s_lock);
            qo_euler_from_quat_fast_q30(qf, sq, QO_EULER_LOCK_BAND_Q28, &o, &info);
            if (!info.locked) n_fast_unflagged++;
            upd(&w_fast_lock, recomp(seq, o, r), seq, NULL);

            /* exactly singular, as a user would build it: from_euler_q30 with the Q3.28
             * nearest the singular middle angle */
            {
                qo_euler_q28 se;
                se.a1 = ref_to_fixed(ref_rng_range(&rng, -REF_PI, REF_PI), REF_Q28); se.a2 = ref_to_fixed(s, REF_Q28); se.a3 = ref_to_fixed(ref_rng_range(&rng, -REF_PI, REF_PI), REF_Q28);
                qo_euler_to_quat_q30(sq, se, &qf);
                rr = ref_quat_from_euler(ref_euler_names[seq], se.a1 / REF_Q28, s, se.a3 / REF_Q28);
                qo_euler_from_quat_q30(qf, sq, &o, &info);
                n_exact++; n_cases++;
                if (info.locked) { n_exact_flagged++; n_flagged_total++; upd(&max_flag_margin, info.margin / REF_Q28, 0, NULL); }
                upd(&max_exact_margin_f, info.margin / REF_Q28, 0, NULL);
                /* against the exactly singular rotation the angles were meant to describe */
                upd(&w_lock, recomp(seq, o, rr), seq, &s_lock);
            }
            /* exactly singular rotation with every component then moved by up to 2 LSB
             * (noise from an upstream fixed-point computation, e.g. a filter's output) */
            {
                qf = ref_quat_to_q30(ref_quat_from_euler(ref_euler_names[seq], ref_rng_range(&rng, -REF_PI, REF_PI), s, ref_rng_range(&rng, -REF_PI, REF_PI)));
                qf.w += (int32_t)(ref_rng_next(&rng) % 5) - 2; qf.x += (int32_t)(ref_rng_next(&rng) % 5) - 2;
                qf.y += (int32_t)(ref_rng_next(&rng) % 5) - 2; qf.z += (int32_t)(ref_rng_next(&rng) % 5) - 2;
                r = ref_quat_normalize(ref_quat_from_q30(qf));
                qo_euler_from_quat_q30(qf, sq, &o, &info);
                n_noisy++; n_exact++; n_cases++;
                if (info.locked) { n_noisy_flagged++; n_exact_flagged++; n_flagged_total++; upd(&max_flag_margin, info.margin / REF_Q28, 0, NULL); }
                upd(&max_noisy_margin, info.margin / REF_Q28, 0, NULL);
                upd(info.locked ? &w_near_in : &w_near_out, recomp(seq, o, r), seq, NULL);
            }

            /* near lock */
            k = (int)(ref_rng_next(&rng) % (sizeof offs / sizeof offs[0]));
            side = (int)(ref_rng_next(&rng) & 1);
            a2 = s + ((s > 0) ? -1.0 : 1.0) * (side ? -offs[k] : offs[k]);
            a1 = ref_rng_range(&rng, -REF_PI, REF_PI); a3 = ref_rng_range(&rng, -REF_PI, REF_PI);
            qf = ref_quat_to_q30(ref_quat_from_euler(ref_euler_names[seq], a1, a2, a3));
            r = ref_quat_normalize(ref_quat_from_q30(qf));
            qo_euler_from_quat_q30(qf, sq, &o, &info);
            n_cases++;
            if (info.locked) {
                n_flagged_total++;
                upd(&max_flag_margin, info.margin / REF_Q28, 0, NULL);
                upd(&w_near_in, recomp(seq, o, r), seq, &s_near);
            } else {
                upd(&w_near_out, recomp(seq, o, r), seq, &s_near);
            }
            qo_euler_from_quat_fast_q30(qf, sq, QO_EULER_LOCK_BAND_Q28, &o, &info);
            upd(info.locked ? &w_fast_near_in : &w_fast_near_out, recomp(seq, o, r), seq, NULL);
        }
    }

    printf("accuracy_euler_fx: %ld cases per convention x 24 conventions (seed 0x5EED0E17)\n", n_per);
    printf("  lock band QO_EULER_LOCK_BAND_Q28      = %d LSB = %.3g rad\n",
           (int)QO_EULER_LOCK_BAND_Q28, QO_EULER_LOCK_BAND_Q28 / REF_Q28);
    printf("  euler_to_quat worst error              = %.3g rad (%s), %.2f LSB per component   goal <= 1e-6\n",
           w_from, ref_euler_names[s_from], w_from_lsb);
    printf("  euler_from_quat generic worst recomp.  = %.3g rad (%s)   goal <= 1e-6\n", w_gen, ref_euler_names[s_gen]);
    printf("  euler_from_quat_near generic recomp.   = %.3g rad         goal <= 1e-6\n", w_nearfn);
    printf("  euler_from_quat at exact lock recomp.  = %.3g rad (%s)   goal <= 1e-5\n", w_lock, ref_euler_names[s_lock]);
    printf("  near lock, flagged, worst recomp.      = %.3g rad         goal <= 1e-5\n", w_near_in);
    printf("  near lock, not flagged, worst recomp.  = %.3g rad (%s)   goal <= 1e-5\n", w_near_out, ref_euler_names[s_near]);
    printf("  exactly singular inputs flagged        = %ld of %ld\n", n_exact_flagged, n_exact);
    printf("  largest margin at an exact singularity = %.3g rad (rounded from double), %.3g rad (via euler_to_quat_q30)\n",
           max_exact_margin, max_exact_margin_f);
    printf("  singular + up to 2 LSB per component   = %ld of %ld flagged, largest margin %.3g rad\n",
           n_noisy_flagged, n_noisy, max_noisy_margin);
    printf("  largest margin at which lock flagged   = %.3g rad (%.3g deg)   goal <= 2 deg\n",
           max_flag_margin, max_flag_margin * 180.0 / REF_PI);
    printf("  flagged in total                       = %ld of %ld decompositions\n", n_flagged_total, n_cases);
    printf("  fast tier (qo_euler_from_quat_fast_q30):\n");
    printf("    generic worst recomposition          = %.3g rad (%s)   goal <= 2e-7\n", w_fast_gen, ref_euler_names[s_fast_gen]);
    printf("    at exact lock worst recomp.          = %.3g rad, %ld not flagged   goal <= 1e-5, 0\n", w_fast_lock, n_fast_unflagged);
    printf("    near lock worst recomp.              = %.3g rad flagged, %.3g rad not   goal <= 1e-5\n", w_fast_near_in, w_fast_near_out);
    printf("  unexpected non-OK statuses             = %ld\n", n_bad_status);

    /* speed (host, informative) */
    {
        const int reps = 2000000;
        volatile int32_t sink = 0;
        qo_quat_q30 q = { 858993459, 107374182, -536870912, 322122547 };
        qo_euler_q28 e = { 80530637, -107374182, 322122547 }, o;
        double t0 = now_s(), t1, t2;
        int rep;
        for (rep = 0; rep < reps; rep++) {
            q.x = 107374182 + (rep & 255) * 1000;
            qo_euler_from_quat_q30(q, QO_EULER_ZYX, &o, NULL);
            sink += o.a1;
        }
        t1 = now_s();
        for (rep = 0; rep < reps; rep++) {
            qo_quat_q30 qq;
            e.a1 = (rep & 255) * 268435;
            qo_euler_to_quat_q30(QO_EULER_ZYX, e, &qq);
            sink += qq.w;
        }
        t2 = now_s();
        printf("  host time per call: euler_from_quat %.1f ns, euler_to_quat %.1f ns (-O2, informative)\n",
               1e9 * (t1 - t0) / reps, 1e9 * (t2 - t1) / reps);
        (void)sink;
    }

    if (w_from > 1e-6 || w_gen > 1e-6 || w_nearfn > 1e-6) ok = 0;
    if (w_lock > 1e-5 || w_near_in > 1e-5 || w_near_out > 1e-5) ok = 0;
    if (w_fast_gen > 2e-7 || w_fast_lock > 1e-5 || w_fast_near_in > 1e-5 || w_fast_near_out > 1e-5 ||
        n_fast_unflagged != 0) ok = 0;
    if (max_flag_margin > two_deg || n_exact_flagged != n_exact || n_bad_status != 0) ok = 0;
    printf("accuracy_euler_fx: %s\n", ok ? "all goals met" : "GOAL MISSED");
    return ok ? 0 : 1;
}
