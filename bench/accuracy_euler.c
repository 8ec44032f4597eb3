/* accuracy_euler - measured accuracy of the float32 Euler conversions, all 24 conventions.
 *
 *   make build/bench/accuracy_euler && build/bench/accuracy_euler [N]
 *
 * For N (default 20000) fixed-seed random cases per convention it measures, against a
 * double-precision reference (products of elementary rotations from the
 * convention's letters, tests/common/ref.c):
 *   - from_euler: angle between the float quaternion and the double one;
 *   - to_euler, generic: uniformly random rotations; the returned angles composed in double
 *     vs the float input rotation (the "recomposition error");
 *   - to_euler at lock: middle angle exactly singular, built in double and rounded to float,
 *     and built by qo_euler_to_quat_f32 with the float nearest the singular angle;
 *   - singular rotations whose components were then moved by up to 2 ulp each (informative:
 *     how much float noise the lock band absorbs);
 *   - to_euler near lock: middle angle 1e-7 ... 0.035 rad off singular, both sides;
 *   - the gimbal-lock flag: the largest margin at which it was raised, the largest margin seen
 *     at an exactly singular input, and whether every exactly singular input was flagged;
 *   - the nearest-solution variant with random prev, generic inputs (goal 2e-6: its outputs
 *     leave [-pi, pi], where float32's spacing doubles);
 *   - time per call of to_euler / from_euler (host, informative only).
 * Exit status 1 if a goal is missed: generic <= 1e-6 rad (nearest variant 2e-6), at/near lock
 * <= 1e-5 rad, the flag never raised more than 2 degrees from the singularity, always raised at
 * an exact singularity (both ways of building one).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "common/dq.h"
#include "qorient/euler.h"
#include "qorient/quat.h"

/* double reference, the 24 convention names and fixed-seed PRNG: tests/common/ref.c */
static ref_rng rng = { 0x5EED0E17ull };

static double recomp(int seq, qo_euler_f32 e, dq q)
{
    return dq_angle(ref_quat_from_euler(ref_euler_names[seq], e.a1, e.a2, e.a3), q);
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
    static const double offs[] = { 1e-7, 5e-7, 1e-6, 1.5e-6, 3e-6, 1e-5, 1e-4, 1e-3, 0.01, 0.035 };
    const double two_deg = 2.0 * REF_PI / 180.0;
    long n_per = argc > 1 ? atol(argv[1]) : 20000;
    double w_from = 0, w_gen = 0, w_lock = 0, w_near_in = 0, w_near_out = 0, w_nearfn = 0;
    double max_flag_margin = 0, max_exact_margin = 0, min_unflagged_nonexact = 1e9;
    long n_exact = 0, n_exact_flagged = 0, n_flagged_total = 0, n_cases = 0;
    long n_noisy = 0, n_noisy_flagged = 0;
    double max_exact_margin_f = 0, max_noisy_margin = 0;
    int s_from = 0, s_gen = 0, s_lock = 0, s_near = 0, seq;
    int ok = 1;
    long i;
    if (n_per < 10000) n_per = 10000;

    for (seq = 0; seq < 24; seq++) {
        for (i = 0; i < n_per; i++) {
            qo_euler_f32 e, o;
            qo_euler_info_f32 info;
            qo_quat_f32 qf;
            dq r;
            double nn, s, a1, a3, a2;
            int k, which, side;

            /* from_euler */
            e.a1 = (float)ref_rng_range(&rng, -REF_PI, REF_PI); e.a2 = (float)ref_rng_range(&rng, -REF_PI, REF_PI); e.a3 = (float)ref_rng_range(&rng, -REF_PI, REF_PI);
            qo_euler_to_quat_f32((qo_euler_seq)seq, e, &qf);
            upd(&w_from, dq_angle(dq_unit_from_f(qf), ref_quat_from_euler(ref_euler_names[seq], e.a1, e.a2, e.a3)), seq, &s_from);

            /* generic: uniform random rotation */
            do {
                r.w = ref_rng_range(&rng, -1, 1); r.x = ref_rng_range(&rng, -1, 1); r.y = ref_rng_range(&rng, -1, 1); r.z = ref_rng_range(&rng, -1, 1);
                nn = r.w * r.w + r.x * r.x + r.y * r.y + r.z * r.z;
            } while (nn > 1.0 || nn < 1e-4);
            qf = f_from(r);
            r = dq_unit_from_f(qf);
            qo_euler_from_quat_f32(qf, (qo_euler_seq)seq, &o, &info);
            n_cases++;
            if (info.locked) { n_flagged_total++; upd(&max_flag_margin, info.margin, 0, NULL); }
            upd(&w_gen, recomp(seq, o, r), seq, &s_gen);

            /* nearest-solution variant, generic, prev a random nearby-ish triple */
            {
                qo_euler_f32 prev;
                prev.a1 = o.a1 + (float)ref_rng_range(&rng, -2, 2); prev.a2 = o.a2 + (float)ref_rng_range(&rng, -2, 2);
                prev.a3 = o.a3 + (float)ref_rng_range(&rng, -2, 2);
                qo_euler_from_quat_near_f32(qf, (qo_euler_seq)seq, prev, QO_EULER_LOCK_BAND_F32, &o, &info);
                upd(&w_nearfn, recomp(seq, o, r), seq, NULL);
            }

            /* exactly singular */
            a1 = ref_rng_range(&rng, -REF_PI, REF_PI); a3 = ref_rng_range(&rng, -REF_PI, REF_PI);
            which = (int)(ref_rng_next(&rng) & 1);
            s = ref_euler_proper(seq) ? (which ? REF_PI : 0.0) : (which ? REF_PI / 2 : -REF_PI / 2);
            qf = f_from(ref_quat_from_euler(ref_euler_names[seq], a1, s, a3));
            r = dq_unit_from_f(qf);
            qo_euler_from_quat_f32(qf, (qo_euler_seq)seq, &o, &info);
            n_exact++; n_cases++;
            if (info.locked) { n_exact_flagged++; n_flagged_total++; upd(&max_flag_margin, info.margin, 0, NULL); }
            upd(&max_exact_margin, info.margin, 0, NULL);
            upd(&w_lock, recomp(seq, o, r), seq, &s_lock);

            /* exactly singular, as a user would build it: our own from_euler with the float
             * nearest the singular middle angle (pi/2 itself is not a float) */
            {
                qo_euler_f32 se;
                se.a1 = (float)ref_rng_range(&rng, -REF_PI, REF_PI); se.a2 = (float)s; se.a3 = (float)ref_rng_range(&rng, -REF_PI, REF_PI);
                qo_euler_to_quat_f32((qo_euler_seq)seq, se, &qf);
                r = ref_quat_from_euler(ref_euler_names[seq], se.a1, s, se.a3);
                qo_euler_from_quat_f32(qf, (qo_euler_seq)seq, &o, &info);
                n_exact++; n_cases++;
                if (info.locked) { n_exact_flagged++; n_flagged_total++; upd(&max_flag_margin, info.margin, 0, NULL); }
                upd(&max_exact_margin_f, info.margin, 0, NULL);
                /* against the exactly singular rotation the angles were meant to describe */
                upd(&w_lock, recomp(seq, o, r), seq, &s_lock);
            }
            /* exactly singular rotation with every component then moved by up to 2 ulp
             * (noise from an upstream float computation, e.g. a filter's output) */
            {
                int c;
                float *comp[4];
                qf = f_from(ref_quat_from_euler(ref_euler_names[seq], ref_rng_range(&rng, -REF_PI, REF_PI), s, ref_rng_range(&rng, -REF_PI, REF_PI)));
                comp[0] = &qf.w; comp[1] = &qf.x; comp[2] = &qf.y; comp[3] = &qf.z;
                for (c = 0; c < 4; c++) {
                    int u = (int)(ref_rng_next(&rng) % 5) - 2;
                    while (u > 0) { *comp[c] = nextafterf(*comp[c], INFINITY); u--; }
                    while (u < 0) { *comp[c] = nextafterf(*comp[c], -INFINITY); u++; }
                }
                r = dq_unit_from_f(qf);
                qo_euler_from_quat_f32(qf, (qo_euler_seq)seq, &o, &info);
                n_noisy++; n_cases++;
                if (info.locked) { n_noisy_flagged++; n_flagged_total++; upd(&max_flag_margin, info.margin, 0, NULL); }
                upd(&max_noisy_margin, info.margin, 0, NULL);
                upd(info.locked ? &w_near_in : &w_near_out, recomp(seq, o, r), seq, NULL);
            }

            /* near lock */
            k = (int)(ref_rng_next(&rng) % (sizeof offs / sizeof offs[0]));
            side = (int)(ref_rng_next(&rng) & 1);
            a2 = s + ((s > 0) ? -1.0 : 1.0) * (side ? -offs[k] : offs[k]);
            a1 = ref_rng_range(&rng, -REF_PI, REF_PI); a3 = ref_rng_range(&rng, -REF_PI, REF_PI);
            qf = f_from(ref_quat_from_euler(ref_euler_names[seq], a1, a2, a3));
            r = dq_unit_from_f(qf);
            qo_euler_from_quat_f32(qf, (qo_euler_seq)seq, &o, &info);
            n_cases++;
            if (info.locked) {
                n_flagged_total++;
                upd(&max_flag_margin, info.margin, 0, NULL);
                upd(&w_near_in, recomp(seq, o, r), seq, &s_near);
            } else {
                if (offs[k] < min_unflagged_nonexact) min_unflagged_nonexact = offs[k];
                upd(&w_near_out, recomp(seq, o, r), seq, &s_near);
            }
        }
    }

    printf("accuracy_euler: %ld cases per convention x 24 conventions (seed 0x5EED0E17)\n", n_per);
    printf("  lock band QO_EULER_LOCK_BAND_F32      = %.3g rad\n", (double)QO_EULER_LOCK_BAND_F32);
    printf("  euler_to_quat worst error              = %.3g rad (%s)   goal <= 1e-6\n", w_from, ref_euler_names[s_from]);
    printf("  euler_from_quat generic worst recomp.  = %.3g rad (%s)   goal <= 1e-6\n", w_gen, ref_euler_names[s_gen]);
    printf("  euler_from_quat_near generic recomp.   = %.3g rad         goal <= 2e-6 (outputs beyond +-pi)\n", w_nearfn);
    printf("  euler_from_quat at exact lock recomp.  = %.3g rad (%s)   goal <= 1e-5\n", w_lock, ref_euler_names[s_lock]);
    printf("  near lock, flagged, worst recomp.      = %.3g rad         goal <= 1e-5\n", w_near_in);
    printf("  near lock, not flagged, worst recomp.  = %.3g rad (%s)   goal <= 1e-5\n", w_near_out, ref_euler_names[s_near]);
    printf("  exactly singular inputs flagged        = %ld of %ld\n", n_exact_flagged, n_exact);
    printf("  largest margin at an exact singularity = %.3g rad (rounded from double), %.3g rad (via euler_to_quat_f32)\n",
           max_exact_margin, max_exact_margin_f);
    printf("  singular + up to 2 ulp per component    = %ld of %ld flagged, largest margin %.3g rad\n",
           n_noisy_flagged, n_noisy, max_noisy_margin);
    printf("  largest margin at which lock flagged   = %.3g rad (%.3g deg)   goal <= 2 deg\n",
           max_flag_margin, max_flag_margin * 180.0 / REF_PI);
    printf("  flagged in total                       = %ld of %ld decompositions\n", n_flagged_total, n_cases);

    /* speed (host, informative) */
    {
        const int reps = 2000000;
        volatile float sink = 0.0f;
        qo_quat_f32 q = { 0.8f, 0.1f, -0.5f, 0.3f };
        qo_euler_f32 e = { 0.3f, -0.4f, 1.2f }, o;
        double t0 = now_s(), t1, t2;
        int r;
        for (r = 0; r < reps; r++) {
            q.x = 0.1f + (float)(r & 255) * 1e-4f;
            qo_euler_from_quat_f32(q, QO_EULER_ZYX, &o, NULL);
            sink += o.a1;
        }
        t1 = now_s();
        for (r = 0; r < reps; r++) {
            qo_quat_f32 qq;
            e.a1 = (float)(r & 255) * 1e-3f;
            qo_euler_to_quat_f32(QO_EULER_ZYX, e, &qq);
            sink += qq.w;
        }
        t2 = now_s();
        printf("  host time per call: euler_from_quat %.1f ns, euler_to_quat %.1f ns (-O2, informative)\n",
               1e9 * (t1 - t0) / reps, 1e9 * (t2 - t1) / reps);
        (void)sink;
    }

    /* The near variant's outputs leave [-pi, pi] (a + pi, unwrapped toward prev): float32's
     * spacing there is 4.8e-7, so rounding the three outputs alone can cost ~7e-7. */
    if (w_from > 1e-6 || w_gen > 1e-6 || w_nearfn > 2e-6) ok = 0;
    if (w_lock > 1e-5 || w_near_in > 1e-5 || w_near_out > 1e-5) ok = 0;
    if (max_flag_margin > two_deg || n_exact_flagged != n_exact) ok = 0;
    printf("accuracy_euler: %s\n", ok ? "all goals met" : "GOAL MISSED");
    (void)min_unflagged_nonexact;
    return ok ? 0 : 1;
}
