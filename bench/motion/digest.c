/*
 * bench/motion/digest.c - a digest of the plans the planner makes on fixed-seed random cases
 * (every sync mode, SCURVE and TRAPEZOID, moving starts reached by re-planning mid-motion,
 * target velocities and accelerations, asymmetric and wide limits, and make bench-motion's
 * cases). A speed change to lib/src/motion*.c that claims "the same plans" prints the same
 * digests before and after (`make motion-digest`): every phase's bits, the durations, the
 * status, sync_used and unsynced are hashed (FNV-1a).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/motion.h"
#include "common/ref.h"

#define NJ 7

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *b = (const unsigned char *)p;
    size_t i;
    for (i = 0; i < n; i++) h = (h ^ b[i]) * 1099511628211u;
    return h;
}

static uint64_t digest(uint64_t h, const qo_motion_planner_f32 *pl, qo_status st)
{
    size_t i;
    int s = (int)st, su = (int)pl->sync_used;
    h = fnv(h, &s, sizeof s);
    h = fnv(h, &su, sizeof su);
    h = fnv(h, &pl->unsynced, sizeof pl->unsynced);
    h = fnv(h, &pl->duration, sizeof pl->duration);
    for (i = 0; i < pl->n; i++) {
        const qo_motion_joint_f32 *jt = &pl->joints[i];
        h = fnv(h, &jt->nph, sizeof jt->nph);
        h = fnv(h, &jt->duration, sizeof jt->duration);
        h = fnv(h, &jt->final, sizeof jt->final);
        h = fnv(h, jt->ph, sizeof jt->ph[0] * jt->nph);
    }
    return h;
}

/* log-uniform in [lo, hi] */
static float logu(ref_rng *g, double lo, double hi)
{
    return (float)exp(ref_rng_range(g, log(lo), log(hi)));
}

/* A target state within the limits (state_ok's rule), or at rest. */
static void target_state(ref_rng *g, const qo_motion_limits_f32 *l, float *v, float *a)
{
    float vp = l->vmax, vn = l->vmin != 0.0f ? -l->vmin : l->vmax, ap = l->amax, an = l->amin != 0.0f ? -l->amin : l->amax;
    int k;
    *v = *a = 0.0f;
    for (k = 0; k < 8; k++) {
        float tv = (float)ref_rng_range(g, -vn, vp), ta = (float)ref_rng_range(g, -an, ap);
        float h = ta * fabsf(ta) / (2.0f * l->jmax);
        if (tv + h <= vp && tv + h >= -vn && tv - h <= vp && tv - h >= -vn) {
            *v = tv;
            *a = ta;
            return;
        }
    }
}

/* scenario: 0 ordinary limits, 1 wide limits, 2 asymmetric limits and target states */
static uint64_t run(int scen, qo_motion_profile prof, qo_motion_sync sync, int n, uint32_t seed, int *nok)
{
    ref_rng g;
    uint64_t h = 14695981039346656037u;
    int k, i;
    g.s = seed;
    for (k = 0; k < n; k++) {
        qo_motion_planner_f32 pl;
        qo_motion_joint_f32 jts[NJ];
        qo_motion_limits_f32 l[NJ];
        qo_motion_settings_f32 set;
        float p0[NJ], tg[NJ], tv[NJ], ta[NJ];
        qo_status st;
        int states = scen == 2 || (scen == 0 && (k & 1));
        set.profile = prof;
        set.sync = sync;
        for (i = 0; i < NJ; i++) {
            l[i] = qo_motion_limits_default;
            if (scen == 1) {
                l[i].vmax = logu(&g, 1e-3, 1e9);
                l[i].amax = logu(&g, 1e-3, 1e9);
                l[i].jmax = logu(&g, 1e-3, 1e9);
            } else {
                l[i].vmax = (float)ref_rng_range(&g, 0.5, 5.0);
                l[i].amax = (float)ref_rng_range(&g, 1.0, 20.0);
                l[i].jmax = (float)ref_rng_range(&g, 10.0, 500.0);
            }
            if (scen == 2 || (k % 3 == 0)) {
                l[i].vmin = -l[i].vmax * logu(&g, 1.0 / 20.0, 20.0);
                l[i].amin = -l[i].amax * logu(&g, 1.0 / 20.0, 20.0);
            }
            p0[i] = (float)ref_rng_range(&g, -2.0, 2.0);
        }
        if (qo_motion_init_f32(&pl, jts, NJ, l, p0, 0.0f, &set) != QO_OK) {
            h = fnv(h, &k, sizeof k);
            continue;
        }
        /* a first plan, then a re-plan part-way through it: a moving start */
        for (i = 0; i < NJ; i++) {
            double s = scen == 1 ? (double)l[i].vmax : 1.0;
            tg[i] = (float)(p0[i] + s * ref_rng_range(&g, -3.0, 3.0));
            target_state(&g, &l[i], &tv[i], &ta[i]);
            if (!states) tv[i] = ta[i] = 0.0f;
        }
        st = qo_motion_set_target_state_f32(&pl, 0.0f, tg, tv, ta, NULL);
        *nok += st == QO_OK;
        h = digest(h, &pl, st);
        for (i = 0; i < NJ; i++) {
            double s = scen == 1 ? (double)l[i].vmax : 1.0;
            tg[i] = (float)(tg[i] + s * ref_rng_range(&g, -3.0, 3.0));
            target_state(&g, &l[i], &tv[i], &ta[i]);
            if (!states) tv[i] = ta[i] = 0.0f;
        }
        st = qo_motion_set_target_state_f32(&pl, (float)ref_rng_range(&g, 0.0, 1.0) * pl.duration, tg, tv, ta, NULL);
        *nok += st == QO_OK;
        h = digest(h, &pl, st);
    }
    return h;
}

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 20000, scen, s, prof;
    static const char *const sname[] = { "none", "time", "phase", "time_if_necessary" };
    static const char *const cname[] = { "ordinary", "wide", "states" };
    printf("motion plan digests, %d cases of 2 plans each per line\n", n);
    for (scen = 0; scen < 3; scen++)
        for (prof = 0; prof < 2; prof++)
            for (s = 0; s < 4; s++) {
                int nok = 0;
                uint64_t h;
                if (prof == 1 && scen == 2) continue; /* target states are SCURVE only */
                h = run(scen, prof ? QO_MOTION_TRAPEZOID : QO_MOTION_SCURVE, (qo_motion_sync)s, n,
                        20261202u + (uint32_t)(100 * scen + 10 * prof + s), &nok);
                printf("%-8s %-9s %-17s %016llx  %d plans accepted\n", cname[scen], prof ? "trapezoid" : "scurve",
                       sname[s], (unsigned long long)h, nok);
            }
    return 0;
}
