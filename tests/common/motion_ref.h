/*
 * tests/common/motion_ref.h - an independent double-precision minimum-time reference for one
 * jerk-limited joint (written apart from lib/src/motion*.c, sharing none of its code).
 *
 * Index:
 *   mref_lim            limits of one joint (asymmetric velocity and acceleration allowed)
 *   mref_min_time       minimum time from (p0, v0, a0) to (pf, vf, af), or -1 if none found
 *   mref_vel_time       minimum time of a velocity change (v0, a0) -> (v1, a1)
 *   mref_rest_time      closed-form rest-to-rest minimum time (symmetric limits), the oracle's
 *                       own check
 *   mref_exact_time     a profile of exactly a given duration within the limits, if the
 *                       two-cruise family has one (time synchronisation's feasibility)
 *   mref_vchange        one fastest velocity change to a = 0 (symmetric limits): its displacement
 *                       and duration (the family references of test_motion.c and bench_motion.c)
 *
 * Method (exhaustive search over switching times, not the library's root search on one
 * velocity): any time-optimal profile of a triple integrator with |j| <= J, a in [amin, amax],
 * v in [vmin, vmax] is bang-bang in jerk with holds on the acceleration bounds and cruises on the
 * velocity bounds (Pontryagin); every such profile with at most 7 phases is "fastest (v, a)
 * transfer to a junction state (vm, am), optional cruise (am = 0, vm on a velocity bound),
 * fastest (v, a) transfer to (vf, af)". Each (v, a) transfer is closed-form (one pulse, its peak
 * from the velocity balance, clipped to a hold). The reference scans am on a grid (plus the
 * bounds, 0, a0 and af), finds every vm root of the position equation by a dense scan and
 * bisection, keeps the fastest profile whose velocity stays within the bounds (checked at every
 * acceleration zero crossing), then refines am around the best on finer grids.
 * Start and target states must be feasible (within the bounds, and |v + a|a|/(2J)| within the
 * velocity bounds for the start).
 */
#ifndef QORIENT_TESTS_MOTION_REF_H
#define QORIENT_TESTS_MOTION_REF_H

typedef struct mref_lim {
    double vmin, vmax, amin, amax, jmax; /* vmin < 0 < vmax, amin < 0 < amax, jmax > 0 */
} mref_lim;

/* Minimum time [s] from (p0, v0, a0) to (pf, vf, af) within `l`; -1 if no profile was found. */
double mref_min_time(const mref_lim *l, double p0, double v0, double a0, double pf, double vf, double af);

/* Minimum time [s] of the velocity change (v0, a0) -> (v1, a1) within `l` (position free: the
 * fastest single pulse); -1 if none. */
double mref_vel_time(const mref_lim *l, double v0, double a0, double v1, double a1);

/* Closed form: rest-to-rest minimum time over distance D (any sign), symmetric limits V, A, J. */
double mref_rest_time(double D, double V, double A, double J);

/* A jerk profile as phases of duration d[k] [s] and constant jerk j[k] [u/s^3]. */
#define MREF_PROF_MAX 11
typedef struct mref_prof {
    int n;
    double d[MREF_PROF_MAX], j[MREF_PROF_MAX];
} mref_prof;

/* Looks for a profile of exactly T seconds from (p0, v0, a0) to (pf, vf, af) within `l`, in the
 * "two cruises" family: fastest transfer to (v1, 0), cruise t1 at v1, fastest transfer to
 * (v2, 0), cruise t2 at v2, fastest transfer to (vf, af) (<= 11 phases). For each (v1, v2) on a
 * grid over [vmin, vmax] (with 0 and the states' own zero-acceleration velocities) the transfers
 * fix the rest R = T - their durations and the distance S left to the cruises; t1 + t2 = R,
 * v1 t1 + v2 t2 = S has a solution t1, t2 >= 0 exactly when R >= 0 and S lies between v1 R and
 * v2 R: no root search, the profile found ends on the target to rounding. The pair with the
 * largest margin is returned in *out (may be NULL). Returns 1 if found, 0 if not (which does not
 * prove that no profile of T exists: the family is not every profile). */
int mref_exact_time(const mref_lim *l, double p0, double v0, double a0, double pf, double vf, double af, double T,
                    mref_prof *out);

/* Fastest change from (v0, a0) to (v1, 0) with |a| <= A, |jerk| <= J (one pulse toward v1,
 * held at +-A when it would exceed it; an a0 beyond A is ramped back first): its displacement
 * *dp [u] and duration *dt [s]. Integrated in double from its three phases. */
void mref_vchange(double v0, double a0, double v1, double A, double J, double *dp, double *dt);

#endif
