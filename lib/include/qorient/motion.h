/* parity float32 (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   motion.plan    qo_motion_init_f32
 *   motion.plan    qo_motion_set_limits_f32
 *   motion.plan    qo_motion_set_target_f32
 *   motion.plan    qo_motion_set_target_state_f32
 *   motion.plan    qo_motion_set_joint_sync_f32
 *   motion.plan    qo_motion_set_velocity_f32
 *   motion.plan    qo_motion_set_timing_f32
 *   motion.plan    qo_motion_brake_f32
 *   motion.plan    qo_motion_shift_time_f32
 *   motion.query   qo_motion_done_f32
 *   motion.query   qo_motion_duration_f32
 *   motion.query   qo_motion_end_time_f32
 *   motion.query   qo_motion_sync_used
 *   motion.sample  qo_motion_sample_f32
 *   motion.export  qo_motion_export_q16 (float32 code: writes the fixed core's table)
 */
/*
 * qorient/motion.h - online, limit-respecting point-to-point motion for N joints (float32).
 *
 * Index:
 *   qo_motion_settings_default      const default settings (SCURVE, TIME sync)
 *   qo_motion_limits_default        const default limits of one joint (all 1, no range, no wrap)
 *   qo_motion_init_f32              set up a planner over caller arrays, at rest at given positions
 *   qo_motion_set_target_f32        re-plan from the sampled state at t_now to new targets
 *   qo_motion_set_target_state_f32  re-plan to target positions with velocities, accelerations
 *   qo_motion_set_joint_sync_f32    per-joint synchronisation (overrides settings.sync)
 *   qo_motion_set_velocity_f32      velocity interface: every joint to a target velocity, then on
 *   qo_motion_set_limits_f32        change one joint's limits at t_now (bad limits -> brake)
 *   qo_motion_brake_f32             stop every joint as fast as its limits allow, from t_now
 *   qo_motion_sample_f32            position, velocity, acceleration of every joint at time t
 *   qo_motion_duration_f32          seconds from the last re-plan until every joint is at rest
 *   qo_motion_end_time_f32          absolute time at which every joint is at rest
 *   qo_motion_done_f32              1 once t has reached the end time
 *   qo_motion_set_timing_f32        minimum duration, durations rounded up to a control period
 *   qo_motion_sync_used             which synchronisation the last plan really used
 *   qo_motion_shift_time_f32        move the time origin (keep float32 times small in long runs)
 *   qo_motion_export_q16            the current plan as a fixed-point table (see motion_fx.h)
 *
 * What it does. Each joint is a scalar in the user's unit (rad, deg, counts: "u") with limits
 * vmax [u/s], amax [u/s^2], jmax [u/s^3] (optionally asymmetric: vmin, amin), an optional
 * position range [pmin, pmax] and an optional wrap period (continuous joint). A plan takes
 * every joint from its current state (position p0, velocity v0, acceleration a0) to its target
 * position, at rest (v = 0, a = 0) or in a target state (v, a) (qo_motion_set_target_state_f32):
 *   - QO_MOTION_TRAPEZOID: acceleration-limited, the velocity is a trapezoid (or triangle);
 *     the acceleration jumps between -amax, 0 and +amax (jerk unlimited, jmax unused).
 *   - QO_MOTION_SCURVE: jerk-limited seven-phase profile: acceleration ramps at +-jmax, so
 *     position, velocity and acceleration are continuous.
 * Any start state is accepted, including |v0| > vmax or |a0| > amax (the profile first brings
 * them back inside the limits as fast as jmax / amax allow) and motion away from the target.
 *
 * Profile structure and why it is time-optimal. A minimum-time control for a chain of
 * integrators with box bounds is bang-bang (Pontryagin): the highest derivative sits at a bound
 * (+-jmax, or amax / amin for TRAPEZOID) or the path rides a state bound (a = amax or amin,
 * v = vmax or vmin). Below, "vmax" and "amax" stand for the bound on the side of the motion
 * (a rising velocity uses amax, a falling one amin; a positive cruise vmax, a negative vmin).
 * Target states: the stop to rest becomes the fastest transfer from (vc, 0) to (v, a) (the
 * time reversal of a velocity change), the velocity 0 that splits the monotone pieces below
 * becomes v - a|a|/(2 jmax), and a target acceleration adds the shapes without an acceleration
 * zero at either end: three jerk ramps a0 -> am -> peak -> a (the "dips", at the start and, by
 * time reversal, at the end, am over the whole acceleration range) and a0 to one acceleration
 * bound and held, to the other and held, to a. A dip's displacement is not monotone in am:
 * between two of its scan points, where the residual comes closest to zero without changing
 * sign, a golden-section search looks for the pair of roots it may hide (make check-motion
 * case 5781: 2.018 s planned where 0.809 s was possible).
 * With the target at rest, every such profile is: a fastest velocity change from (v0, a0) to a
 * velocity extremum vc with a = 0 (<= 3 phases: ramp, hold amax, ramp), a cruise at vc (only
 * when |vc| = vmax), and a fastest stop from (vc, 0) to (0, 0) (<= 3 phases). The planner finds
 * the vc whose displacement D(vc) equals the distance. D is monotone on [-vmax, min(0, vn)] and
 * on [max(0, vn), vmax], vn being the velocity reached by ramping a0 straight to zero; between
 * 0 and vn the joint stops in two stages and D has one interior extremum. The outer pieces are
 * solved first (a single extremum beyond vn, or a reversal, is the faster way when it exists);
 * the middle piece is split at its extremum (golden section) and solved only when they give no
 * root. Each root is found by the Illinois method (regula falsi that keeps a bracket like
 * bisection), at most QO_MOTION_BISECT_ITERS steps, typically 5-12; the shortest candidate wins,
 * and a cruise at +-vmax is used when even vc = +-vmax falls short. SCURVE starts with a0 != 0
 * also try the "dip" profiles, which have no acceleration zero before the stop: a0 ramps
 * straight to am between 0 and a0, then the fastest pulse from there to rest (e.g. braking is
 * eased first, then raised to amax, held and released: issue 11), solved where the profiles
 * through vn and 0 bracket the distance; and the other orientation, a0 first ramped further
 * away from zero (am between a0 and +-amax), solved where it brackets the distance with the
 * direct stop (velocity extremum checked against vmax). The shortest candidate wins. For TRAPEZOID this family
 * provably contains the minimum-time solution (double integrator, state bound on v). For SCURVE
 * it contains the minimum-time rest-to-rest solution (checked against the closed form in
 * tests/core/test_motion.c). Evidence for moving SCURVE starts within the limits:
 * tests/core/test_motion_oracle.c compares every joint with an independent double-precision
 * reference (tests/common/motion_ref.c: exhaustive search over every two-pulse profile with
 * optional cruise, i.e. every 7-phase bang-bang jerk profile) on 42,000 random joints in
 * `make test` (10,500 per sync mode, with moving starts, asymmetric limits and moving target
 * states; 1,000,000 per mode in `make check-motion`): none more than 0.1 % slower, none over
 * a limit by 1e-5. A general proof is NOT claimed, and starts beyond the limits are only
 * checked against the extremum-velocity family.
 *
 * Synchronisation (settings.sync, or per joint with qo_motion_set_joint_sync_f32):
 *   - QO_MOTION_SYNC_NONE: each joint takes its own minimum time.
 *   - QO_MOTION_SYNC_TIME_IF_NECESSARY: TIME for the joints whose target state moves (nonzero
 *     target velocity or acceleration: arriving early would carry such a joint past its target
 *     before the others arrive), NONE for the joints whose target is at rest.
 *   With per-joint sync the TIME and PHASE joints share one duration (the PHASE joints' straight
 *   line stretched to it when a TIME joint is slower; if the line cannot be, they go as TIME).
 *   - QO_MOTION_SYNC_TIME: every joint arrives at the slowest joint's minimum time T. A faster
 *     joint gets a profile of exactly T by lowering its extremum velocity vc (bracketed root search
 *     on vc in (0, vc*], at most QO_MOTION_BISECT_ITERS steps; any T above the joint's minimum is reachable
 *     because the cruise may then be arbitrarily slow). Known limitation: from a start far
 *     from rest relative to the jerk limit (velocity changes taking seconds), no profile of
 *     the family may have exactly T (the achievable durations have a gap); that joint then
 *     keeps its own minimum-time profile, arrives early (at its target state, at its own
 *     minimum time) and waits at rest there, or, with a moving target state, moves on past it
 *     as after the end of any plan (qo_motion_set_target_state_f32); its bit is set
 *     in planner.unsynced (rare: bench/bench_motion.c counts the plans not TIME-synchronised,
 *     docs/FIGURES.md, motion). The exact-duration search uses the
 *     extremum-velocity family only: a joint whose minimum is a dip or a two-holds shape (target
 *     states) has no profile of that family between its minimum and the family's own shortest,
 *     e.g. check-motion case 5781 joint 5: minimum 0.809 s, none between it and 2.018 s, so at
 *     a common 1.560 s it is reported unsynced (it passes its target state at 0.809 s and moves
 *     on at about -3.05 u/s). That gap is real, not the family's: no jerk
 *     profile of any shape within the limits takes that joint to its target state in 1.560 s
 *     (an LP over piecewise-constant jerk, tests/core/motion_gap_lp.py, finds profiles for
 *     about [0.809, 0.861] s and [2.019 s, inf) only, none between even with the bounds widened;
 *     tests/core/test_motion.c). A reading of it: the joint starts braking at a0 = -11.3 with
 *     jmax 20.7 and a
 *     positive bound amax of only 2.06; releasing the brake alone takes 0.55 s and carries it
 *     through v = 0 to -0.56 u/s, after which only -0.72 u of travel remain until it must leave
 *     at -3.05 u/s. Arriving later means spending the extra time near v = 0, and climbing back
 *     there at amax 2.06 first takes the joint out to the 2.018 s profile. The narrow
 *     [0.809, 0.861] s above its minimum (stretching the dip itself) is not searched either: a
 *     common duration there leaves the joint unsynced at its minimum in the same way
 *     (tests/core/test_motion.c test_issue_case_5781 checks 0.83, 0.85, 1.2 and 1.56 s).
 *   - QO_MOTION_SYNC_PHASE: straight line in joint space: p_i(t) = p0_i + d_i s(t), one scalar
 *     profile s: 0 -> 1 with limits min_i(vmax_i/|d_i|) etc. (vmin_i for a joint moving the
 *     other way). Possible only when every joint's (v0, a0) and target (v, a) are proportional
 *     to its displacement d_i (all at rest is the usual case), within
 *     1e-6 of max(min(vmax, -vmin), |v0|) and max(min(amax, -amin), |a0|) (the tighter bound:
 *     with the larger, check-motion wide case 4862, vmin = -12 vmax, a re-plan jumped by
 *     4e-6 vmax), which bounds the velocity / acceleration step the straight line may
 *     introduce, and when the scalar limits min_i(vmax_i/|d_i|)...
 *     lie in [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX] (a tiny d_i makes them overflow
 *     float32 products), and when the straight line's phase coefficients keep every joint
 *     within its own vmax, amax, jmax (or its start values beyond them) to 1e-6 relative (a
 *     line over them by float32 rounding only, less than 1e-4, is solved again within limits
 *     shrunk by that excess: make check-motion wide PHASE case 87, 3.1e-6):
 *     from a moving start the shared jerk min_i(jmax_i/|d_i|) may brake a joint's initial
 *     acceleration too late (issue 11); otherwise the plan falls back to TIME and
 *     qo_motion_sync_used() says so. The straight line can take longer than TIME sync, because
 *     the binding limit may come from different joints for v, a and j.
 *
 * Re-planning: qo_motion_set_target_f32(pl, t_now, ...) samples the current plan at t_now and
 * plans from that state, so the motion stays continuous in position and velocity (TRAPEZOID) or
 * position, velocity and acceleration (SCURVE). A stream of targets issued faster than the
 * joints arrive never stops at each point.
 *
 * Continuous joints (wrap > 0): the target is taken modulo wrap and the joint moves the short
 * way round (|move| <= wrap/2; exactly wrap/2 goes in the positive direction). Positions are NOT
 * wrapped on output: they stay continuous (an unbounded angle), wrap them yourself if needed.
 *
 * Position range: a target outside [pmin, pmax] is clamped to it and reported in the clamped
 * mask. The range limits the target only: a joint moving fast toward its range end may pass it
 * while braking if its braking distance says so (nothing can prevent that within the limits).
 *
 * A joint already at rest on its target gets no phases (duration 0) and never moves; it does
 * not take part in the synchronisation.
 *
 * Concurrency: re-planning and sampling the SAME planner must not overlap (a sample taken
 * while a re-plan rewrites the phases mixes two plans). An interrupt that samples while the
 * main loop re-plans should use two planners (or two exported Q16.16 tables) and swap a pointer.
 *
 * Safety: a non-finite target, or an attempt to set bad limits, returns a status and switches
 * the planner to a braking profile from the current state at t_now (each joint stops as fast as
 * its valid limits allow, no jump). Sampling after the end returns the final positions at rest
 * (target states and the velocity interface: moving on, see qo_motion_set_target_state_f32).
 *
 * Numerics: float32, -ffp-contract=off. Each phase keeps its exact duration d and the next
 * phase starts from the state integrated over d, so p, v (and a) are continuous at every
 * boundary to a few float32 ulps of the values, and limits hold to float32 rounding (the
 * oracle tests allow 1e-5 relative; the worst overshoot measured by bench/bench_motion.c:
 * docs/FIGURES.md, motion). The phase start times are rounded float32 sums: a sample falling in the
 * <= ulp(T)/2 gap or overlap between two phases sees the boundary state a fraction of an ulp
 * early or late (T = duration; ulp(100 s) = 7.6e-6 s). The end snaps to the exact target at
 * rest; the remaining step is the solver residual (~1e-7 relative in position, float32
 * rounding in v and a).
 * Absolute times are float32 too: keep the caller's time origin recent (ulp(1000 s) = 61 us).
 * Resources: code and stack per module in docs/FIGURES.md (section sizes: motion.o the planner,
 * motion_solver.o the one-joint solver, motion_export.o the Q16.16 export; tools/size-report.sh).
 * The stack of a re-plan does not grow with N: the solver works on small per-call structs, and
 * between its two passes a plan keeps each joint's solve in that joint's own phase storage.
 * sizeof(qo_motion_joint_f32) per joint; no heap, no static mutable state: planners never
 * interfere. A re-plan costs O(N) root searches.
 */
#ifndef QORIENT_MOTION_H
#define QORIENT_MOTION_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/status.h"
#include "qorient/motion_fx.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Largest number of joints one planner handles (the clamped mask is a uint32_t). */
#define QO_MOTION_MAX_JOINTS 32
/* Phases of one joint's plan: 3 (velocity change) + 1 (cruise) + 3 (stop). */
#define QO_MOTION_MAX_PHASES 7
/* Supported range: what the planner accepts is what tests/core/test_motion_oracle.c verifies
 * against its independent reference (test_oracle_wide: time-optimal to 0.1 %, within the limits
 * to 1e-5, continuous, at the goal), and every other limit gets QO_E_LIMIT:
 *   - vmax, amax, jmax in [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX] = [1e-3, 1e9] (checked
 *     log-uniform over the whole range, in every sync mode, from moving starts and to moving
 *     target states that can stop within a few units). At scale, make check-motion runs
 *     test_oracle_wide in every sync mode (NONE, TIME, PHASE, TIME_IF_NECESSARY) and fails on
 *     any failure (QO_MOTION_ORACLE_FILTER=test_oracle_wide
 *     build/check/test_motion_oracle_1000000, run in chunks with QO_MOTION_ORACLE_FIRST /
 *     _NUM). The cases it found on the way (moving target states at extreme ratios: dips, a
 *     dip tolerance, the reference's ramp grid, a PHASE start step with an asymmetric vmin)
 *     are kept as tests/core/test_motion.c: test_issue_wide_cases, test_phase_step_asym.
 *     Beyond the range the float32 solver is not time-optimal (issue 11); subnormal or tiny
 *     limits would also give durations beyond float, huge ones overflowing products.
 *   - vmin, amin: 0 (symmetric) or within a factor QO_MOTION_LIMIT_RATIO = 20 of -vmax, -amax
 *     (and in [-QO_MOTION_LIMIT_MAX, -QO_MOTION_LIMIT_MIN]): checked with ratios log-uniform
 *     over [1/20, 20] across the whole range (and up to 20 in the ordinary ranges of make
 *     check-motion); beyond that ratio plans were found exceeding a limit (issue 11).
 * Start positions, targets (after clamping to [pmin, pmax]) and wrap periods within
 * +-QO_MOTION_POS_MAX (QO_E_RANGE / QO_E_LIMIT). Every plan is also checked after it is made:
 * each phase's coefficients, its end state, the durations and the final positions must be
 * finite (positions within +-QO_MOTION_POS_MAX); a plan that is not gets QO_E_RANGE and the
 * safe state: a brake from the state at t_now, or, if even that is not finite, every joint
 * held at rest where it is. */
#define QO_MOTION_LIMIT_MIN 1e-3f
#define QO_MOTION_LIMIT_MAX 1e9f
#define QO_MOTION_LIMIT_RATIO 20.0f
#define QO_MOTION_POS_MAX 1e18f
/* Range of qo_motion_set_timing_f32's durations [s]: a period below QO_MOTION_PERIOD_MIN
 * (1 us) would make T / period lose float32 resolution; the upper bound keeps every plan's
 * float32 time axis at sub-millisecond resolution. */
#define QO_MOTION_DURATION_MAX 1e4f
#define QO_MOTION_PERIOD_MIN 1e-6f
/* A synchronised joint (TIME, PHASE, and the rounded durations of qo_motion_set_timing_f32)
 * ends within QO_MOTION_SYNC_END_ULPS float32 ulps of the common duration T (ulp(4.4 s) =
 * 4.8e-7 s): its profile is solved for T, but each phase duration is a float32 value and the
 * plan's end is their float32 sum (up to 11 phases, each addition rounding by up to ulp(T)/2),
 * and the durations themselves carry the rounding of the solve (T minus the ramps' times).
 * The phases are not forced to sum to T bit for bit: that would move the end position by the
 * velocity times the correction, and the position is what the end snaps to. make check-motion
 * (test_timing) asserts this bound on every synchronised joint and prints the largest seen. */
#define QO_MOTION_SYNC_END_ULPS 8
/* Upper bound of root-search steps in one solve (a solve usually stops far earlier; bounded anyway). */
#define QO_MOTION_BISECT_ITERS 48

typedef enum qo_motion_profile {
    QO_MOTION_TRAPEZOID = 0, /* acceleration-limited, velocity trapezoid */
    QO_MOTION_SCURVE = 1     /* jerk-limited, seven phases */
} qo_motion_profile;

typedef enum qo_motion_sync {
    QO_MOTION_SYNC_NONE = 0,  /* each joint at its own minimum time */
    QO_MOTION_SYNC_TIME = 1,  /* all joints arrive together */
    QO_MOTION_SYNC_PHASE = 2, /* straight line in joint space (falls back to TIME) */
    /* Time sync only where a joint would otherwise arrive early: a joint whose target state is
     * moving (target velocity or acceleration nonzero) is synchronised like TIME, because
     * arriving at its own minimum time would carry it past its target before the others
     * arrive; a joint whose target is at rest keeps its own minimum time (like NONE). */
    QO_MOTION_SYNC_TIME_IF_NECESSARY = 3
} qo_motion_sync;

typedef struct qo_motion_settings_f32 {
    qo_motion_profile profile;
    qo_motion_sync sync;
} qo_motion_settings_f32;

/* SCURVE, SYNC_TIME. */
extern const qo_motion_settings_f32 qo_motion_settings_default;

/* Limits of one joint. vmax, amax, jmax: in [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX] (jmax
 * also for TRAPEZOID, where it is unused). pmin <= pmax, each finite or -INFINITY / +INFINITY
 * (= no range; the default). wrap: 0 = ordinary joint, in (0, QO_MOTION_POS_MAX] = continuous
 * joint with that period (2*pi rad, 360 deg).
 * vmin, amin: asymmetric limits, the most negative velocity [u/s] and acceleration [u/s^2]
 * allowed (e.g. vmin = -2 with vmax = 3). 0 (the default, and what an initializer of the first
 * six fields gives) means symmetric: vmin = -vmax, amin = -amax. Otherwise each must lie in
 * [-QO_MOTION_LIMIT_MAX, -QO_MOTION_LIMIT_MIN] and within a factor QO_MOTION_LIMIT_RATIO of
 * -vmax / -amax (-vmin/vmax in [1/20, 20]; else QO_E_LIMIT, see above). Every plan (all profiles and
 * sync modes, braking, the velocity interface, target states) keeps v in [vmin, vmax] and a
 * in [amin, amax] (starts beyond them are first brought back, as for the symmetric limits). */
typedef struct qo_motion_limits_f32 {
    float vmax, amax, jmax;
    float pmin, pmax;
    float wrap;
    float vmin, amin;
} qo_motion_limits_f32;

/* vmax = amax = jmax = 1, pmin = -INFINITY, pmax = +INFINITY, wrap = 0, vmin = amin = 0
 * (symmetric). */
extern const qo_motion_limits_f32 qo_motion_limits_default;

/* One phase of a joint's plan: from time t (seconds after the plan start) the joint follows
 * p + v*tau + a*tau^2/2 + j*tau^3/6, tau = min(time - t, d), until the next phase's t.
 * d is the phase's exact duration; t is the rounded float32 sum of the earlier d. */
typedef struct qo_motion_phase_f32 {
    float t, d, p, v, a, j;
} qo_motion_phase_f32;

/* Per-joint storage, caller-allocated (an array of N), owned by the planner after init. */
typedef struct qo_motion_joint_f32 {
    qo_motion_limits_f32 lim;                      /* validated limits in force */
    float goal;                                    /* last accepted target after clamping */
    float final;                                   /* where the plan ends (unwrapped), at rest */
    float duration;                                /* seconds after the plan start */
    unsigned nph;                                  /* phases in use, 0 = at rest at `final` */
    qo_motion_phase_f32 ph[QO_MOTION_MAX_PHASES];
    float p0, v0, a0;  /* start state of the current plan (at the planner's t0) [u, u/s, u/s^2] */
    float vend;  /* velocity after the last phase [u/s]: 0 = at rest at `final`; the velocity
                  * interface's target (the joint then moves on at vend from `final`) */
    float aend;  /* acceleration at the end of the last phase [u/s^2] (target states; see
                  * qo_motion_set_target_state_f32 for the motion after the end) */
    float goal_v, goal_a;                          /* last accepted target velocity, acceleration */
    int sync;    /* per-joint sync (qo_motion_set_joint_sync_f32), -1 = settings.sync */
} qo_motion_joint_f32;

/* The planner. Fields are readable; change them only through the functions. */
typedef struct qo_motion_planner_f32 {
    qo_motion_joint_f32 *joints;   /* caller array of n */
    size_t n;
    qo_motion_settings_f32 settings;
    float t0;                      /* absolute time of the last (re-)plan, seconds */
    float duration;                /* max joint duration of the current plan */
    qo_motion_sync sync_used;      /* what the current plan used: PHASE if its PHASE joints got the
                                    * straight line, else TIME if any joint was synchronised,
                                    * else NONE */
    uint32_t unsynced;             /* bit i: joint i could not be given the common duration
                                    * (it arrives earlier, at its own minimum time, and
                                    * waits there or moves on from a moving target state;
                                    * see above) */
    int braking;                   /* 1 if the current plan is a safety stop */
    float min_duration, period;    /* duration rules (qo_motion_set_timing_f32), 0 = off */
    int vel_mode;                  /* 1 if the current plan came from qo_motion_set_velocity_f32 */
} qo_motion_planner_f32;

/*
 * Sets up `pl` over `joints` (n entries, 1..QO_MOTION_MAX_JOINTS) with per-joint `limits`
 * (n entries) and `settings` (NULL = qo_motion_settings_default), at rest at `start` (n
 * positions) from time `t0` (seconds, any finite origin the caller uses for later calls).
 * Start positions are not clamped to the range (the first target will be).
 * Returns QO_OK; QO_E_NULL (pl, joints, limits or start NULL); QO_E_TOO_FEW (n == 0);
 * QO_E_CAPACITY (n > QO_MOTION_MAX_JOINTS); QO_E_ARG (unknown profile or sync);
 * QO_E_LIMIT (a vmax/amax/jmax outside [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX] or NaN, a
 * vmin/amin neither 0 nor in [-QO_MOTION_LIMIT_MAX, -QO_MOTION_LIMIT_MIN], or farther than a
 * factor QO_MOTION_LIMIT_RATIO from -vmax/-amax, pmin > pmax or NaN,
 * wrap < 0, NaN or above QO_MOTION_POS_MAX); QO_E_NONFINITE (a start
 * position or t0 not finite); QO_E_RANGE (a start position beyond +-QO_MOTION_POS_MAX).
 * On any error (pl non-NULL) the planner is left with n = 0, so every later call returns
 * QO_E_STATE: it never moves anything.
 */
qo_status qo_motion_init_f32(qo_motion_planner_f32 *pl, qo_motion_joint_f32 *joints, size_t n,
                             const qo_motion_limits_f32 *limits, const float *start, float t0,
                             const qo_motion_settings_f32 *settings);

/*
 * Re-plans every joint from its state sampled at `t_now` (seconds, >= the last plan's t0) to
 * `targets` (n positions, user unit), using the planner's settings.
 * Targets outside [pmin, pmax] are clamped; bit i of *clamped is set for joint i (clamped may be
 * NULL). Continuous joints go the short way round.
 * Returns QO_OK; QO_E_NULL (pl or targets NULL); QO_E_STATE (planner not initialised);
 * QO_E_NONFINITE (t_now or a target NaN/Inf: the planner then brakes every joint to rest from
 * its state at t_now, if t_now is finite, else the plan is unchanged); QO_E_ORDER (t_now
 * earlier than the last plan's t0: plan unchanged); QO_E_RANGE (a target, after clamping,
 * beyond +-QO_MOTION_POS_MAX, or the plan would not be finite: every joint brakes from its
 * state at t_now, or is held at rest there if even the stop would not be finite).
 * *clamped is 0 on every error.
 */
qo_status qo_motion_set_target_f32(qo_motion_planner_f32 *pl, float t_now, const float *targets,
                                   uint32_t *clamped);

/*
 * Full target states (streams of setpoints passing through without stopping): re-plans every
 * joint from its state sampled at `t_now` to position pos[i] [u] with velocity vel[i] [u/s] and
 * acceleration acc[i] [u/s^2] at the plan's end (n entries each; vel and acc may be NULL = all
 * 0). qo_motion_set_target_f32(pl, t, p, c) is qo_motion_set_target_state_f32(pl, t, p, NULL,
 * NULL, c). Positions are clamped to [pmin, pmax] and wrapped as for set_target.
 * A target state must be reachable and then holdable within the limits: vmin <= v <= vmax,
 * amin <= a <= amax, and, because after the end the acceleration ramps to 0 at jmax (below),
 * v + a|a|/(2 jmax) within [vmin, vmax] (the velocity the ramp reaches). TRAPEZOID (jerk
 * unlimited) requires acc = 0. A joint whose velocity is nonzero but whose position stays the
 * same still moves (it arrives at its target moving).
 * After the end (what a teleoperation stream needs if its next setpoint is late: keep moving
 * as commanded, continuously, within the limits): the acceleration ramps from acc[i] to 0 at
 * jmax (duration |acc|/jmax), then the joint moves on at constant velocity, like the velocity
 * interface; qo_motion_done_f32 is 1 from the end. Nothing stops it but a later call, and the
 * position range is NOT applied after the end (a moving target near a range end leaves the
 * range unless the caller re-plans or brakes in time).
 * Synchronisation works with target states: TIME gives every joint the common duration,
 * PHASE is used only where the straight line is feasible (all target velocities and
 * accelerations zero, or proportional like the start), else TIME, reported by sync_used;
 * TIME_IF_NECESSARY synchronises only the joints with a moving target.
 * Returns as qo_motion_set_target_f32, and QO_E_NULL (pl or pos NULL); QO_E_NONFINITE (a
 * velocity or acceleration NaN/Inf: brake, as for a non-finite target); QO_E_LIMIT (a target
 * state outside the limits or not holdable as above: refused, the plan is unchanged and
 * nothing moves differently); QO_E_ARG (acc nonzero with TRAPEZOID: refused, unchanged).
 * *clamped is 0 on every error.
 */
qo_status qo_motion_set_target_state_f32(qo_motion_planner_f32 *pl, float t_now, const float *pos,
                                         const float *vel, const float *acc, uint32_t *clamped);

/*
 * Per-joint synchronisation: joint i uses `sync` instead of settings.sync from the next re-plan
 * (does not re-plan). NONE: its own minimum time; TIME: the common duration of all TIME and
 * PHASE joints (and of TIME_IF_NECESSARY joints with a moving target); PHASE: on the straight
 * line with the other PHASE joints when that is feasible, else TIME (sync_used reports the
 * plan's overall mode: PHASE only if every PHASE joint got it); TIME_IF_NECESSARY: as in
 * qo_motion_sync. Returns QO_OK; QO_E_NULL; QO_E_STATE (not initialised); QO_E_RANGE (i >= n);
 * QO_E_ARG (unknown sync value: unchanged).
 */
qo_status qo_motion_set_joint_sync_f32(qo_motion_planner_f32 *pl, size_t i, qo_motion_sync sync);

/*
 * Velocity interface (jogging, teleoperation): from its state sampled at `t_now` every joint
 * changes to velocity vel[i] [u/s] (n entries) as fast as its limits allow (jerk-limited for
 * SCURVE, at +-amax for TRAPEZOID; no synchronisation, no position target) and then keeps
 * moving at vel[i] without end: the plan's duration is the time to reach the velocities, after
 * which qo_motion_done_f32 is 1 and samples continue the straight line p = final + vend*(t - end)
 * (joint field vend). The position range is NOT applied (nothing stops the joint but a later
 * call): set_target and brake leave velocity mode, and set_limits re-plans toward the same
 * velocities (clamped into the new [vmin, vmax]). Positions stay float32: re-plan or shift time before a
 * long run loses resolution (ulp(1000 s) = 61 us, ulp(1e4 u) = 1e-3 u). The Q16.16 export
 * carries the end velocity in its rest segment.
 * Returns QO_OK; QO_E_NULL (pl or vel NULL); QO_E_STATE; QO_E_ORDER (t_now < t0: unchanged);
 * QO_E_NONFINITE (t_now non-finite: unchanged; a velocity NaN/Inf: every joint brakes to rest
 * from t_now); QO_E_RANGE (some vel[i] outside [vmin, vmax]: refused, the plan is unchanged; or the plan
 * would not be finite: brake, as for set_target).
 */
qo_status qo_motion_set_velocity_f32(qo_motion_planner_f32 *pl, float t_now, const float *vel);

/*
 * Replaces joint `i`'s limits at `t_now` and re-plans all joints toward their goals from their
 * state at t_now (so lowering vmax on the fly first brakes into the new limits).
 * Returns QO_OK; QO_E_NULL; QO_E_STATE; QO_E_RANGE (i >= n); QO_E_NONFINITE (t_now);
 * QO_E_ORDER (t_now < t0); QO_E_LIMIT (bad limits as in init: the old limits stay and every
 * joint brakes to rest from t_now); QO_E_RANGE (a goal clamped into a range end beyond
 * +-QO_MOTION_POS_MAX, or the plan would not be finite: the new limits stay and every joint
 * brakes, or is held, as for set_target). A goal outside a new, narrower range is clamped
 * again; a target velocity outside the new [vmin, vmax] is clamped into it, and a target
 * acceleration the new limits cannot hold (see qo_motion_set_target_state_f32) becomes 0.
 */
qo_status qo_motion_set_limits_f32(qo_motion_planner_f32 *pl, float t_now, size_t i,
                                   const qo_motion_limits_f32 *limits);

/*
 * Safety stop: every joint brakes from its state at t_now to rest as fast as its limits allow
 * (no synchronisation). The rest positions become the new goals.
 * Returns QO_OK; QO_E_NULL; QO_E_STATE; QO_E_NONFINITE (t_now); QO_E_ORDER (t_now < t0);
 * QO_E_RANGE (the stop would not be finite: every joint is held at rest where it is).
 */
qo_status qo_motion_brake_f32(qo_motion_planner_f32 *pl, float t_now);

/*
 * Samples every joint at absolute time t (seconds): positions, velocities [u/s] and
 * accelerations [u/s^2] into n-element arrays; vel and acc may be NULL. Before the plan's t0
 * the state at t0 is given (QO_E_RANGE); after the end the final positions at rest (velocity
 * interface: moving on from them at the target velocities).
 * Returns QO_OK; QO_E_NULL (pl or pos NULL); QO_E_STATE; QO_E_NONFINITE (t NaN/Inf: outputs are
 * the state at t0); QO_E_RANGE (t < t0; or, as a last line of defence not reachable for the
 * checked plans, a joint's sample would not be finite: that joint gets its final position at
 * rest).
 */
qo_status qo_motion_sample_f32(const qo_motion_planner_f32 *pl, float t, float *pos, float *vel,
                               float *acc);

/* Seconds from the last (re-)plan's t0 until every joint is at rest; 0 for NULL or an
 * uninitialised planner. */
float qo_motion_duration_f32(const qo_motion_planner_f32 *pl);

/* t0 + duration: absolute end time; 0 for NULL or an uninitialised planner. */
float qo_motion_end_time_f32(const qo_motion_planner_f32 *pl);

/* 1 if t >= the end time (every joint at rest at its final position), else 0; 1 for NULL or an
 * uninitialised planner (nothing moves). NaN t gives 0. */
int qo_motion_done_f32(const qo_motion_planner_f32 *pl, float t);

/*
 * Duration rules for the plans made from now on (set_target, set_limits; not the safety stops
 * of brake and of bad input, which stop as fast as possible). A plan that moves lasts at least
 * `min_duration` seconds, and with `period` > 0 its duration is rounded up to a whole number of
 * periods, so that it ends on a control tick (within QO_MOTION_SYNC_END_ULPS float32 ulps of
 * the tick: the phase sums). With SYNC_TIME the common duration obeys the rules; with
 * SYNC_NONE each joint's own; SYNC_PHASE is used only if its straight line already obeys
 * them, else the plan falls back to TIME (sync_used says so). A joint that cannot be given
 * the longer duration (the sync gap described above) keeps its own minimum time, arrives
 * early and waits at rest (or moves on from a moving target state), and its bit in
 * `unsynced` is set (e.g. make check-motion
 * test_timing case 645: minimum 0.20722 s, period 0.041511 s; no profile of the family has
 * 5 ticks, so it waits 0.34 ms for the 5th instead of taking 6). 0 = off (the
 * default after init). Does not re-plan: the rules apply from the next re-plan.
 * Returns QO_OK; QO_E_NULL; QO_E_STATE (not initialised); QO_E_ARG (either value negative, NaN,
 * above QO_MOTION_DURATION_MAX, or a period in (0, QO_MOTION_PERIOD_MIN): rules unchanged).
 */
qo_status qo_motion_set_timing_f32(qo_motion_planner_f32 *pl, float min_duration, float period);

/* The synchronisation the current plan really used (PHASE may have fallen back to TIME; a
 * safety stop reports NONE). NONE for NULL. */
qo_motion_sync qo_motion_sync_used(const qo_motion_planner_f32 *pl);

/*
 * Moves the planner's time origin by dt seconds: afterwards the instant that was time t is
 * time t - dt (only the stored plan start moves; the motion is unchanged). Long-running callers
 * use it to keep their float32 times small (ulp(1000 s) = 61 us), e.g. shifting by the current
 * time at each re-plan and then re-planning at time 0.
 * Returns QO_OK; QO_E_NULL; QO_E_STATE (not initialised); QO_E_NONFINITE (dt NaN/Inf, nothing
 * changed).
 */
qo_status qo_motion_shift_time_f32(qo_motion_planner_f32 *pl, float dt);

/*
 * Exports the current plan to a fixed-point table for qo_motion_sample_q16 (motion_fx.h):
 * `segs` is caller storage of cap entries, needing n * QO_MOTION_Q16_SEGS. Each joint's phase
 * boundaries are rounded to Q16.16 seconds after t0, and each phase's coefficients are taken
 * from the float plan AT the rounded time, so the table follows the float plan exactly except
 * for the coefficient rounding (2^-32) documented in motion_fx.h.
 * Returns QO_OK; QO_E_NULL; QO_E_STATE; QO_E_CAPACITY (cap too small: table->n = 0);
 * QO_E_OVERFLOW (a time beyond 32767 s, a position beyond +-32767 u or a coefficient beyond
 * 2^31: saturated, the table is still filled). On NULL/STATE/CAPACITY the table has n = 0.
 */
qo_status qo_motion_export_q16(const qo_motion_planner_f32 *pl, qo_motion_table_q16 *table,
                               qo_motion_seg_q16 *segs, size_t cap);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_MOTION_H */
