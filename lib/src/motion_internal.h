/*
 * motion_internal.h - shared between the one-joint solver (motion_solver.c), the N-joint
 * planner (motion.c) and the Q16.16 export (motion_export.c). Not installed.
 *
 * The solver works on one joint at a time with small value structs (limits, problem, solution),
 * so a re-plan needs O(1) stack per joint and none proportional to N.
 */
#ifndef QORIENT_MOTION_INTERNAL_H
#define QORIENT_MOTION_INTERNAL_H

#include "qorient/motion.h"

/* One piece of a profile under construction: duration d, jerk j; with seta the acceleration
 * is set to a at its start (TRAPEZOID: acceleration jumps), else it carries on continuously;
 * with setv the velocity is set to v (the cruise starts from exactly its velocity). */
typedef struct mseg {
    float d, j, a, v;
    int seta, setv;
} mseg;

typedef struct mstate {
    float p, v, a;
} mstate;

/* Limits as positive magnitudes: v in [-vn, vp], a in [-an, ap], |jerk| <= j (asymmetric limits
 * resolved: vmin = 0 means vn = vmax, amin = 0 means an = amax). */
typedef struct mlim {
    float vp, vn, ap, an, j;
} mlim;

/* One joint's problem: from velocity v0, acceleration a0 over displacement dp to the end state
 * (vf, af), within l; scurve 0 = TRAPEZOID (af must be 0). */
typedef struct mprob {
    mlim l;
    float v0, a0, dp, vf, af;
    int scurve;
} mprob;

/* A solved profile: family 0 = extremum velocity x with cruise tc (qo_motion_build), family
 * 1 = "dip" to acceleration x; t = its duration. f0, t0: what qo_motion_solve_min found for
 * the zero-cruise profile through vc = 0 (residual, duration; NaN if it did not evaluate it),
 * for qo_motion_solve_time's first bracket. */
typedef struct msol {
    float x, tc, t;
    int fam;
    float f0, t0;
} msol;

/* Integrates one segment exactly (the solver's inner loop: inline in both users). */
static inline void mseg_integ(mstate *s, const mseg *g)
{
    float d = g->d;
    if (g->seta) s->a = g->a;
    if (g->setv) s->v = g->v;
    s->p += d * (s->v + d * (0.5f * s->a + d * g->j * (1.0f / 6.0f)));
    s->v += d * (s->a + 0.5f * d * g->j);
    s->a += d * g->j;
}

/* Segments of one plan: velocity change (<= 3) + cruise (1) + end transfer (<= 3). */
#define MSEGS 7

mlim qo_motion_mlim(const qo_motion_limits_f32 *l);
unsigned qo_motion_vchange(int scurve, float v0, float a0, float v1, const mlim *l, mseg *out);
unsigned qo_motion_build(const mprob *p, const msol *s, mseg *out);
void qo_motion_solve_min(const mprob *p, msol *s);
int qo_motion_solve_time(const mprob *p, const msol *min, float vcs, float T, msol *s);

/* State of a loaded joint plan at local time tau (seconds after t0), including the motion after
 * the end (target velocity and acceleration ramp, see motion.h). */
mstate qo_motion_joint_state(const qo_motion_joint_f32 *jt, float tau);
/* Velocity, acceleration and position offset after the end of a plan, tau seconds after it. */
mstate qo_motion_after_end(const qo_motion_joint_f32 *jt, float tau);

#endif /* QORIENT_MOTION_INTERNAL_H */
