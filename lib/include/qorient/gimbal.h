/* parity float32 (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   gimbal.track   qo_gimbal_init_f32
 *   gimbal.track   qo_gimbal_reset_f32
 *   gimbal.track   qo_gimbal_step_f32
 *   gimbal.filter  qo_gimbal_track_init_f32
 *   gimbal.filter  qo_gimbal_track_step_f32
 *   gimbal.path    qo_gimbal_path_init_f32
 *   gimbal.path    qo_gimbal_path_sample_f32
 */
/* parity fixed:
 *   gimbal.track   - float32 only: a gimbal controller runs where the IMU fusion runs, in float
 *   gimbal.path    - float32 only: sample its joint angles into a spline and export that to Q16
 *   gimbal.filter  - float32 only: it runs the float32 motion planner; export its output instead
 */
/*
 * qorient/gimbal.h - orientation paths for 2- and 3-axis gimbals and spherical wrists, float32.
 *
 * A path is a list of quaternion keyframes at times, interpolated on the sphere (piecewise
 * slerp, or the Shoemake keyframe spline of qorient/interp.h). A gimbal turns each sampled
 * orientation into the mechanism's own joint angles for an axis sequence (outer to inner, in
 * scipy's naming: intrinsic "ZYX" is a yaw-pitch-roll head; a 2-axis pan-tilt head drives a1
 * and a2 of its sequence, and a3 is then the part of the orientation it cannot produce - about
 * 0 on a pointing path), choosing the solution nearest the
 * previous sample (no jumps, continuous joints keep counting turns), holding the free angle
 * steady inside a band around the singular configuration, and only then position- and
 * rate-limiting each joint. Every sample reports the lock margin and which joints a limit
 * clipped.
 *
 * Index:
 *   qo_gimbal_path_interp      QO_GIMBAL_PATH_SLERP | QO_GIMBAL_PATH_SPLINE
 *   qo_gimbal_path_f32         caller-allocated path over caller arrays
 *   qo_gimbal_path_init_f32    validate keys/times, align signs, spline controls
 *   qo_gimbal_path_sample_f32  unit quaternion at time t
 *   qo_gimbal_settings_f32 / _default_f32 sequence, hold band, rate and position limits
 *   qo_gimbal_f32              the per-mechanism state (previous sample)
 *   qo_gimbal_init_f32         validate settings, start without a previous sample
 *   qo_gimbal_reset_f32        start from known joint angles (e.g. read from encoders)
 *   qo_gimbal_step_f32         one sample: orientation -> joint angles + report
 *   qo_gimbal_track_settings_f32 / _default_f32  opt-in tracking filter: acceleration, jerk limits
 *   qo_gimbal_track_f32        the filter's state (a 3-joint motion planner)
 *   qo_gimbal_track_init_f32   validate settings, start without a previous sample
 *   qo_gimbal_track_step_f32   one sample: the gimbal's joint angles -> smooth joints
 *
 * Units: times in seconds, angles in radians, rates in rad/s, accelerations in rad/s^2, jerk
 * in rad/s^3.
 */
#ifndef QORIENT_GIMBAL_H
#define QORIENT_GIMBAL_H

#include "qorient/euler.h"
#include "qorient/motion.h"
#include "qorient/status.h"
#include "qorient/types.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum qo_gimbal_path_interp {
    QO_GIMBAL_PATH_SLERP = 0,   /* piecewise slerp: constant rate per segment, C0 at the keys */
    QO_GIMBAL_PATH_SPLINE = 1   /* Shoemake spline through the keys (C1 in the segment parameter) */
} qo_gimbal_path_interp;

/* An orientation path. All pointers are caller storage that must outlive the path; fill it
 * with qo_gimbal_path_init_f32, do not write the members yourself. */
typedef struct qo_gimbal_path_f32 {
    const float *t;      /* n key times, s, strictly increasing */
    qo_quat_f32 *keys;   /* n keys: normalised and sign-aligned copies of the caller's keys */
    qo_quat_f32 *a, *b;  /* n spline control points each (QO_GIMBAL_PATH_SPLINE only) */
    size_t n;
    qo_gimbal_path_interp interp;
} qo_gimbal_path_f32;

/*
 * Builds a path through n keyframes (keys_in[i] reached at t[i]).
 *   keys:  caller storage for n quaternions; receives normalised keys with each one's sign
 *          flipped to the hemisphere of the previous one, so the path takes the short way
 *          between neighbours (may be the same array as keys_in).
 *   a, b:  caller storage for n quaternions each when interp is QO_GIMBAL_PATH_SPLINE (the spline's
 *          control points); ignored (may be NULL) for QO_GIMBAL_PATH_SLERP.
 * The spline is Shoemake's over the segment index, so with unequal key spacing the angular
 * rate jumps at the keys by the ratio of the neighbouring durations (C1 in the parameter, not
 * in time); use evenly spaced keys where rate continuity matters.
 * Returns QO_OK; QO_E_NULL (path, t, keys_in, keys, or a/b for the spline); QO_E_TOO_FEW
 * (n < 2); QO_E_NONFINITE (a NaN/Inf time or key component); QO_E_ORDER (times not strictly
 * increasing); QO_E_DEGENERATE (a zero key); QO_E_ARG (unknown interp). On error the path
 * is left with n = 0, which qo_gimbal_path_sample_f32 rejects.
 */
qo_status qo_gimbal_path_init_f32(qo_gimbal_path_f32 *path, const float *t,
                                  const qo_quat_f32 *keys_in, size_t n, qo_gimbal_path_interp interp,
                                  qo_quat_f32 *keys, qo_quat_f32 *a, qo_quat_f32 *b);

/*
 * Unit quaternion of the path at time t (s). Before the first key the path holds the first
 * key, after the last it holds the last (a path is a motion that starts and ends at rest).
 * Returns QO_OK; QO_E_NULL; QO_E_STATE (path not initialised); QO_E_NONFINITE (t NaN/Inf).
 * On error *out is the identity.
 */
qo_status qo_gimbal_path_sample_f32(const qo_gimbal_path_f32 *path, float t, qo_quat_f32 *out);

/* Gimbal settings. */
typedef struct qo_gimbal_settings_f32 {
    qo_euler_seq seq;   /* the mechanism's axes, outer to inner (scipy naming) */
    float band;         /* rad, [0, pi/2]: inside this margin from the singular configuration
                           the free angle is held where it was (see qo_euler_from_quat_near_f32) */
    float vmax;         /* rad/s, > 0: per-joint rate limit; +INFINITY for none */
    float min[3];       /* rad: joint position limits (may be -INFINITY, not +INFINITY) */
    float max[3];       /* rad: (may be +INFINITY, not -INFINITY); min[i] <= max[i] */
} qo_gimbal_settings_f32;

/* ZYX (yaw-pitch-roll head), band 1 degree, no rate limit, no position limits. */
extern const qo_gimbal_settings_f32 qo_gimbal_settings_default;

/* A gimbal: its settings and the previous sample. */
typedef struct qo_gimbal_f32 {
    qo_gimbal_settings_f32 s;
    qo_euler_f32 prev;   /* joint angles last commanded */
    float t_prev;        /* time of the last sample, s */
    qo_euler_f32 prev2;  /* the commanded angles before that (for the branch prediction) */
    float t_prev2;
    int started;         /* 0 until the first sample or a reset */
    int have2;           /* 1 when prev2 holds a sample */
} qo_gimbal_f32;

/* One commanded sample. */
typedef struct qo_gimbal_sample_f32 {
    qo_euler_f32 angles;  /* commanded joint angles a1 (outer) .. a3 (inner), rad */
    float margin;         /* rad: angle of the requested orientation from the singular
                             configuration (qo_euler_info_f32.margin) */
    int locked;           /* 1 when margin <= band: the free angle was held */
    unsigned clipped;     /* bit i set when joint i+1 was rate- or position-limited, so the
                             commanded angles lag (or stop short of) the requested orientation */
} qo_gimbal_sample_f32;

/*
 * Validates settings and starts the gimbal without a previous sample (the first step then
 * takes the principal decomposition, scipy's ranges, and applies no rate limit).
 * Returns QO_OK; QO_E_NULL; QO_E_ARG (bad seq); QO_E_RANGE (band outside [0, pi/2]);
 * QO_E_LIMIT (vmax not > 0 or NaN, a NaN limit, min > max, min = +Inf or max = -Inf); on error the gimbal is
 * initialised with the default settings and must not be used until a successful init.
 */
qo_status qo_gimbal_init_f32(qo_gimbal_f32 *g, const qo_gimbal_settings_f32 *s);

/*
 * Declares the mechanism's present joint angles (e.g. read from its encoders) at time t: the
 * next step decomposes nearest them and rate-limits from them.
 * Returns QO_OK; QO_E_NULL; QO_E_NONFINITE (an angle or t is not finite). On error the state
 * is unchanged.
 */
qo_status qo_gimbal_reset_f32(qo_gimbal_f32 *g, qo_euler_f32 angles, float t);

/*
 * One sample: the requested orientation q (need not be unit) at time t (s, strictly
 * increasing from step to step) -> commanded joint angles, lock margin and clip flags.
 * The decomposition is taken nearest a PREDICTION of this sample: a1 and a2 extrapolated
 * linearly from the last two commanded samples (the step ratio capped at 4), a3 the last
 * commanded a3. Off lock this picks the branch the joints are moving along; inside the band it
 * is what lets the middle joint carry on through the singular value (a pitch sweep through 90
 * degrees continues to 91, 92...) instead of reflecting back, while the free angle a3 is held
 * exactly where it was.
 * Order of operations: nearest decomposition (hold band) -> position limits -> rate limit
 * (|change| <= vmax*dt per joint, always the last word: no step ever exceeds it, even after a
 * reset outside the position limits). The commanded angles become the next step's reference,
 * so after a clip the joints catch up at the rate limit, never in a jump.
 * Returns QO_OK; QO_E_NULL; QO_E_STATE (not initialised); QO_E_NONFINITE (NaN/Inf in q or
 * t); QO_E_DEGENERATE (q zero); QO_E_ORDER (t not after the previous sample's). On error the
 * joints hold: out->angles = the previous commanded angles ((0,0,0) before the first), margin
 * 0, locked 0, clipped 0, and the state is unchanged.
 */
qo_status qo_gimbal_step_f32(qo_gimbal_f32 *g, float t, qo_quat_f32 q, qo_gimbal_sample_f32 *out);

/*
 * Tracking filter (opt-in). qo_gimbal_step_f32 limits rates only, so its joint rates jump
 * where the path enters and leaves the hold band, and wherever a key or a clip changes the
 * rate. The filter follows the gimbal's commanded angles (the "path" below) with a 3-joint
 * motion planner (qorient/motion.h) re-planned at every step, so that its output has:
 *   - continuous rates and |acceleration| <= amax at every instant (TRAPEZOID profile), and
 *     with jmax finite also continuous accelerations and |jerk| <= jmax (SCURVE profile);
 *     the planner guarantees the limits of each plan and each re-plan starts from the state
 *     the previous one had reached, so the limits hold across steps as well;
 *   - |rate| <= vmax.
 * How it follows: while the path moves, every joint is commanded (velocity interface) to the
 * path's rate over the last step plus a correction of the position error e = path - joint,
 * c(e) = gain*e for |e| <= amax/(2 gain^2), sign(e)*sqrt(amax*(|e| - amax/(4 gain^2))) beyond
 * (the velocity from which half of amax stops the joint at the path: large errors close at
 * about amax/2, without overshoot from braking too late), capped at |e|/(2 dt) so a long step
 * never overshoots, and the sum clamped to +-vmax. While the path holds still (the same angle
 * twice in a row) the joint is instead planned, once, to the path's position at rest and that
 * plan runs to its end: it arrives exactly, in minimum time within the limits. (Re-planning
 * it at every step would chatter forever: a plan for the last ulp of a move, from a state
 * carrying float32 rounding, ends an ulp off and starts again.)
 * What it costs: the output lags the path. While the path's rate changes faster than amax
 * (or its acceleration faster than jmax) the error grows: a rate step of dv leaves an error
 * of about dv^2/(2 amax) (plus dv*amax/(2 jmax) with jerk limiting), closed at gain
 * (1/s, time constant 1/gain) once the path's rate is reachable again; on a path of constant
 * rate the error decays to float32 rounding; after the path stops the joints reach it
 * exactly and at rest, overshooting the path's end (when it stops dead from rate R) by at
 * most R^2/(2 amax) + 2 R amax/jmax + R dt: the filter sees a change of the path's rate one
 * step (dt) late, the rate being the difference of its last two samples. Position limits
 * apply to the path (the gimbal clamps it); an output joint may overshoot a limit by its
 * tracking error. out->err reports the largest error.
 */
typedef struct qo_gimbal_track_settings_f32 {
    float amax;  /* rad/s^2, in [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX]: acceleration limit */
    float jmax;  /* rad/s^3, in [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX], or +INFINITY for no
                    jerk limit (accelerations may then step) */
    float vmax;  /* rad/s, in [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX], or +INFINITY; a vmax
                    above 1000 s * amax (and +INFINITY) acts as 1000 s * amax, which the
                    joints would need 1000 s at amax to reach */
    float gain;  /* 1/s, in [QO_MOTION_LIMIT_MIN, QO_MOTION_LIMIT_MAX]: how fast a small position
                    error is closed; keep it below jmax/(4 amax) with a jerk limit, or the joints
                    ring around the path before settling */
} qo_gimbal_track_settings_f32;

/* amax 10 rad/s^2, jmax +INFINITY, vmax +INFINITY, gain 10 /s. */
extern const qo_gimbal_track_settings_f32 qo_gimbal_track_settings_default;

/* One filtered sample. */
typedef struct qo_gimbal_track_sample_f32 {
    qo_euler_f32 angles;  /* filtered joint angles, rad */
    float rate[3];        /* joint rates, rad/s */
    float acc[3];         /* joint accelerations, rad/s^2 */
    float err;            /* rad: largest |path - angles| over the joints at this step */
    int settled;          /* 1 when the path holds still and every joint is on it at rest */
} qo_gimbal_track_sample_f32;

/* The filter's state: caller storage (three planner joints: sizeof(qo_gimbal_track_f32)),
 * written only by the functions. */
typedef struct qo_gimbal_track_f32 {
    qo_gimbal_track_settings_f32 s;
    qo_motion_planner_f32 pl;         /* time origin moved to the last step (shift_time) */
    qo_motion_joint_f32 joints[3];
    float path_prev[3];               /* the path's angles at the last step, rad */
    float t_prev;                     /* time of the last step, s */
    qo_gimbal_track_sample_f32 last;  /* the last step's output (what an error repeats) */
    int started;                      /* 0 until the first step */
    int holding;                      /* 1 while the plan runs to path_prev at rest: not re-planned */
} qo_gimbal_track_f32;

/*
 * Validates settings and starts the filter without a previous sample (the first step puts
 * the joints on the path at rest).
 * Returns QO_OK; QO_E_NULL; QO_E_LIMIT (amax, vmax, gain or jmax NaN or outside their ranges
 * above). On error the filter keeps the default settings and is not started; every step then
 * returns QO_E_STATE until a successful init.
 */
qo_status qo_gimbal_track_init_f32(qo_gimbal_track_f32 *tr, const qo_gimbal_track_settings_f32 *s);

/*
 * One step at time t (s, strictly increasing; steps of any length, e.g. the control period):
 * path = the gimbal's commanded angles at t (qo_gimbal_sample_f32.angles) -> the filtered
 * joint state at t, then a re-plan from that state toward the path (see above). The output
 * at t comes from the plan made at the previous step, so it never jumps.
 * Returns QO_OK; QO_E_NULL; QO_E_STATE (not initialised, or an earlier init failed);
 * QO_E_NONFINITE (t or an angle NaN/Inf); QO_E_ORDER (t not after the previous step's);
 * QO_E_RANGE (an angle beyond +-QO_MOTION_POS_MAX, or t - previous t above
 * QO_MOTION_DURATION_MAX or overflowing float32: state unchanged; or a joint would be beyond
 * +-QO_MOTION_POS_MAX, or the re-plan would not be finite: the planner's safety stop, every
 * joint brakes to rest from its state at t as fast as its limits allow, or is held where
 * the planner can hold it if even that is not finite, and out is the state the stop starts
 * from). On the other errors the state is unchanged and out holds the joints' state at
 * the previous step (all 0 before the first), err 0, settled 0.
 */
qo_status qo_gimbal_track_step_f32(qo_gimbal_track_f32 *tr, float t, qo_euler_f32 path,
                                   qo_gimbal_track_sample_f32 *out);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_GIMBAL_H */
