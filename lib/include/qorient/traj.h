/* parity float32 (tools/parity.sh writes docs/PARITY.md from these blocks):
 *   traj.storage   qo_traj_store_len
 *   traj.plan      qo_traj_init_keys
 *   traj.plan      qo_traj_init_targets
 *   traj.plan      qo_traj_set_timing
 *   traj.plan      qo_traj_set_joint_sync
 *   traj.plan      qo_traj_push
 *   traj.plan      qo_traj_prepare
 *   traj.sample    qo_traj_sample
 *   traj.query     qo_traj_joints
 *   traj.query     qo_traj_end_time
 *   traj.query     qo_traj_done
 *   traj.time      qo_traj_ns_from_s
 */
/* parity fixed:
 *   traj.plan      - float32 only: one object over the spline and the motion planner
 *   traj.sample    - sample the exported Q16 tables (spline_fx.h, motion_fx.h)
 *   traj.storage   - the Q16 tables size themselves (qo_spline_q16_len, QO_MOTION_Q16_SEGS)
 *   traj.query     - the times are in the float32 object that exported the tables
 *   traj.time      - the integer time is the API's own: the Q16 tables take Q16.16 seconds
 */
/*
 * qorient/traj.h - one trajectory object over N joints: keyframes or timed targets, float32.
 *
 * Index:
 *   qo_traj_kind                QO_TRAJ_KEYS (spline profiles) or QO_TRAJ_TARGETS (motion profiles)
 *   qo_traj                     the trajectory (caller-allocated, storage in caller arrays)
 *   qo_traj_store_len()         floats of storage a trajectory of N joints and capacity C needs
 *   qo_traj_init_keys()         set up a keyframe trajectory (qorient/spline.h profiles)
 *   qo_traj_init_targets()      set up a target queue (qorient/motion.h profiles)
 *   qo_traj_set_timing()        TARGETS: minimum move duration, durations in whole control periods
 *   qo_traj_set_joint_sync()    TARGETS: one joint's synchronisation (qo_motion_set_joint_sync_f32)
 *   qo_traj_push()              add a keyframe / a timed target (also between samples: live)
 *   qo_traj_prepare()           plan what the pushes left pending (optional: sample does it)
 *   qo_traj_sample()            position, velocity, acceleration of every joint at a time
 *   qo_traj_joints()            joint count N
 *   qo_traj_end_time()          when the motion known so far ends
 *   qo_traj_done()              1 once nothing more will move at a time
 *   qo_traj_ns_from_s()         seconds (double) to the integer time of this API, rounded
 *
 * This is the one shape every consumer drives (the `qorient plan` and `qorient stream`
 * commands, examples/pi/stream_modbus.c, firmware): push keyframes or targets, then sample at
 * ticks. The planners underneath are qorient/spline.h and qorient/motion.h; their fixed-point
 * samplers stay available (the plan is readable: qo_traj.spline, qo_traj.planner).
 *
 * Time scheme. Absolute times are int64_t nanoseconds (qo_traj_ns) on the caller's own clock
 * (CLOCK_MONOTONIC, a tick counter scaled to ns, or seconds of a file times 1e9): exact for
 * any running time, |t| <= QO_TRAJ_TIME_MAX (about 146 years). The float32 core only ever sees
 * RELATIVE times computed in integers first: keyframe times relative to the first key, target
 * times and sample times relative to the last re-plan. So a motion at t = 1e7 s samples as
 * precisely as one at t = 0: the float32 rounding is that of the time since the first key
 * (keys) or since the last target (targets), ulp(10 s) = 1 us, never that of the absolute time.
 *
 * QO_TRAJ_KEYS. Keyframes (time, N positions, optionally N velocities and N accelerations per
 * key: key_cols 1, 2 or 3) with the profile, end condition, limits and wrap of a
 * qo_spline_settings_f32 (its key_vel / key_acc are ignored: they come with the keys). Key
 * times must increase strictly (also after rounding their offset from the first key to
 * float32). A push only stores the key; the spline is (re)planned over all keys by the next
 * qo_traj_prepare() or qo_traj_sample(): O(K) work. With one key the trajectory holds it at
 * rest (the settings are still checked as a plan would: QO_E_RANGE, QO_E_LIMIT); before the first key the first key is held, after the last the last (see spline.h).
 * Pushing keys while sampling re-plans the whole spline: the local profiles (LINEAR,
 * CUBIC_HERMITE, CATMULL_ROM) keep every segment but the last one unchanged, the global
 * CUBIC_C2 and estimated QUINTIC may move earlier segments slightly; live input is what
 * QO_TRAJ_TARGETS is for.
 *
 * QO_TRAJ_TARGETS. The first push is the start: the joints are at rest at its positions from
 * its time on. Every later push queues a target (times must not decrease; an equal time
 * re-plans again, the later target wins). qo_traj_sample() at time t first applies, in order,
 * every queued target whose time is <= t: the motion planner re-plans from its current state
 * (position, velocity, acceleration: no jump) at max(target time, latest time sampled), so a
 * target that arrives late (live input) starts from where the joints really are. Queued targets
 * take capacity; applied ones free it (a ring of `cap` entries).
 * Target states: given storage for them (qo_traj_store_len with key_cols 2 or 3), a target
 * carries velocities (and accelerations) too, reached with its positions at the end of its
 * move (qo_motion_set_target_state_f32: the joints pass through it moving, and move on at
 * that velocity if no later target comes). A target state the limits cannot reach or hold is
 * refused when it becomes due: the sample says so (QO_E_LIMIT, QO_E_ARG) and the motion
 * planned before goes on unchanged.
 *
 * Concurrency: one trajectory is one object; push, prepare and sample must not overlap (a
 * reader thread pushing while a timer thread samples takes a lock around both). Two
 * trajectories never interfere: no static mutable state, no heap.
 * Resources: sizeof(qo_traj) plus the caller's arrays: cap int64_t times, qo_traj_store_len()
 * floats, and for targets N qo_motion_joint_f32 (236 B each on Cortex-M4F).
 */
#ifndef QORIENT_TRAJ_H
#define QORIENT_TRAJ_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/motion.h"
#include "qorient/spline.h"
#include "qorient/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Absolute time in nanoseconds. */
typedef int64_t qo_traj_ns;

/* Largest |time| accepted anywhere (ns): 2^62. The difference of two can reach 2^63, one more
 * than int64 holds: the library splits times into seconds and ns before subtracting. */
#define QO_TRAJ_TIME_MAX ((qo_traj_ns)4611686018427387904LL)
#define QO_TRAJ_NS_PER_S ((qo_traj_ns)1000000000LL)

typedef enum qo_traj_kind {
    QO_TRAJ_NONE = 0,    /* not initialised */
    QO_TRAJ_KEYS = 1,    /* keyframes, qorient/spline.h profiles */
    QO_TRAJ_TARGETS = 2  /* queue of timed targets, qorient/motion.h profiles */
} qo_traj_kind;

/* The trajectory. Fields are readable (e.g. the spline for qo_spline_export_q16, the planner
 * for qo_motion_export_q16 after a re-plan); change them only through the functions. */
typedef struct qo_traj {
    qo_traj_kind kind;
    size_t n;                      /* joints */
    size_t cap;                    /* keys (KEYS) or queued targets (TARGETS) the storage holds */
    qo_traj_ns *t_ns;              /* caller array of cap times */
    float *store;                  /* caller array of qo_traj_store_len() floats */
    /* KEYS */
    unsigned key_cols;             /* 1 positions, 2 + velocities, 3 + accelerations */
    size_t n_keys;
    float *t_rel;                  /* key times after the first, seconds */
    float *key_p, *key_v, *key_a;  /* cap*N each (v, a only for key_cols 2, 3) */
    float *coef;
    size_t coef_len;
    qo_spline_settings_f32 spline_set;
    qo_spline_f32 spline;          /* the plan; n_keys == 0 while none */
    int dirty;                     /* keys pushed since the last plan */
    qo_status plan_status;         /* result of the last plan */
    /* TARGETS */
    qo_motion_planner_f32 planner; /* planner time 0 == origin */
    qo_motion_joint_f32 *joints;
    const qo_motion_limits_f32 *limits; /* read by the first push */
    qo_motion_settings_f32 motion_set;
    float min_duration, period;    /* qo_traj_set_timing's rules (0 = off), re-applied at the start */
    float *queue_p;                /* cap*N queued target positions */
    float *queue_v, *queue_a;      /* cap*N queued target velocities, accelerations (NULL: none) */
    unsigned target_cols;          /* 1 positions, 2 + velocities, 3 + accelerations */
    signed char joint_sync[QO_MOTION_MAX_JOINTS]; /* qo_traj_set_joint_sync's values, -1 = none,
                                                   * re-applied at the start */
    size_t head, count;            /* ring of queued targets */
    int started;                   /* the start (first push) is in */
    qo_traj_ns start_ns;           /* time of the start */
    qo_traj_ns origin;             /* absolute time of the last re-plan (planner time 0) */
    qo_traj_ns last_push;          /* time of the latest push */
    qo_traj_ns last_sample;        /* latest time sampled */
    unsigned long replans;         /* targets applied so far (a counter to watch for re-plans) */
    uint32_t clamped;              /* mask of the last applied target's clamped joints */
    qo_status replan_status;       /* result of the last applied target (QO_OK, or why the
                                    * planner brakes: see qo_motion_set_target_f32) */
} qo_traj;

/*
 * Floats of `store` a trajectory needs: KEYS: C + C*N*key_cols + qo_spline_coef_len(N, C)
 * (C >= 2); TARGETS: C*N*key_cols (key_cols 1: target positions; 2: and velocities; 3: and
 * accelerations). Returns 0 for kind unknown, n_joints == 0, cap == 0, key_cols not 1..3 or
 * a size that overflows.
 */
size_t qo_traj_store_len(qo_traj_kind kind, size_t n_joints, size_t cap, unsigned key_cols);

/*
 * Sets up a keyframe trajectory of n_joints joints holding up to cap keys.
 *   set:      spline settings (profile, end, end_vel, derivs, limits, wrap); its arrays must
 *             stay valid while the trajectory is used (every plan reads them); key_vel and
 *             key_acc are ignored. NULL = qo_spline_settings_default.
 *   key_cols: 1 (positions), 2 (+ velocities: needed by CUBIC_HERMITE) or 3 (+ accelerations).
 *   t_ns:     cap times; store: store_len >= qo_traj_store_len(QO_TRAJ_KEYS, N, cap, key_cols).
 * Returns QO_OK; QO_E_NULL (tr, t_ns or store NULL); QO_E_TOO_FEW (n_joints == 0 or cap < 2);
 * QO_E_ARG (key_cols not 1..3, unknown profile/end/derivs, CUBIC_HERMITE with key_cols 1);
 * QO_E_CAPACITY (store_len too small). On error *tr is not initialised (kind NONE): every
 * later call returns QO_E_STATE.
 */
qo_status qo_traj_init_keys(qo_traj *tr, size_t n_joints, const qo_spline_settings_f32 *set,
                            unsigned key_cols, qo_traj_ns *t_ns, size_t cap, float *store,
                            size_t store_len);

/*
 * Sets up a target queue of n_joints joints (1..QO_MOTION_MAX_JOINTS) holding up to cap
 * queued targets, with the per-joint limits (n entries, checked now, read again by the first
 * push: keep them valid until then) and settings (NULL = qo_motion_settings_default).
 * joints: n planner joints (caller storage); t_ns: cap times; store: store_len >=
 * qo_traj_store_len(QO_TRAJ_TARGETS, N, cap, 1), or with key_cols 2 (3) for targets that carry
 * velocities (and accelerations): the storage given decides (tr->target_cols).
 * Returns QO_OK; QO_E_NULL (tr, joints, limits, t_ns or store NULL); QO_E_TOO_FEW (n_joints
 * == 0 or cap == 0); QO_E_CAPACITY (n_joints > QO_MOTION_MAX_JOINTS or store_len too small);
 * QO_E_ARG and QO_E_LIMIT as qo_motion_init_f32 (bad settings or limits). On error *tr is
 * not initialised (kind NONE).
 */
qo_status qo_traj_init_targets(qo_traj *tr, size_t n_joints, const qo_motion_limits_f32 *limits,
                               const qo_motion_settings_f32 *set, qo_motion_joint_f32 *joints,
                               qo_traj_ns *t_ns, size_t cap, float *store, size_t store_len);

/*
 * TARGETS: duration rules of every re-plan from now on (qo_motion_set_timing_f32): a move lasts
 * at least min_duration seconds, and with period > 0 (the caller's control or sample period, s)
 * its duration is rounded up to a whole number of periods, so a move issued on a tick ends on a
 * tick. 0 = off (the default). Callable before or after the first push (the rules survive the
 * planner's set-up at the start); a plan already running keeps its duration until the next
 * re-plan. Braking (a refused target) still stops as fast as possible.
 * Returns QO_OK; QO_E_NULL (tr NULL); QO_E_STATE (not initialised, or a KEYS trajectory);
 * QO_E_ARG (either value negative, NaN or above QO_MOTION_DURATION_MAX, or a period in
 * (0, QO_MOTION_PERIOD_MIN)): nothing changed.
 */
qo_status qo_traj_set_timing(qo_traj *tr, float min_duration, float period);

/*
 * TARGETS: joint i (0-based) takes synchronisation `sync` instead of the settings' from the
 * next re-plan on (qo_motion_set_joint_sync_f32: NONE, TIME, PHASE, TIME_IF_NECESSARY).
 * Callable before or after the first push (kept across the start's set-up, like the timing).
 * Returns QO_OK; QO_E_NULL; QO_E_STATE (not initialised, or KEYS); QO_E_RANGE (i >= N);
 * QO_E_ARG (unknown sync): nothing changed.
 */
qo_status qo_traj_set_joint_sync(qo_traj *tr, size_t i, qo_motion_sync sync);

/*
 * Adds a keyframe (KEYS) or a target (TARGETS; the first one is the start) at absolute time
 * t (ns). pos: N positions; vel, acc: N key velocities / accelerations, required when
 * key_cols >= 2 / 3, else ignored (pass NULL). TARGETS: vel, acc: N target velocities [u/s]
 * and accelerations [u/s^2] or NULL (= 0: at rest), each only with storage for it (else
 * QO_E_CAPACITY); the start is at rest (nonzero ones: QO_E_ARG). Whether a state is
 * reachable is decided when it becomes due (qo_traj_sample).
 * Nothing is stored on error. Returns QO_OK; QO_E_NULL (tr or pos NULL, or vel/acc missing for
 * key_cols); QO_E_STATE (not initialised); QO_E_RANGE (|t| > QO_TRAJ_TIME_MAX; TARGETS: a
 * position beyond +-QO_MOTION_POS_MAX); QO_E_NONFINITE (a position, velocity or acceleration
 * NaN/Inf); QO_E_ORDER (KEYS: t not after the previous key, also when their offsets from the
 * first key round to the same float32; TARGETS: t before the previous push); QO_E_CAPACITY
 * (cap keys stored, or cap targets queued and not yet due; TARGETS: vel/acc given without
 * storage for them); TARGETS start: QO_E_ARG (nonzero velocity or acceleration), QO_E_LIMIT /
 * QO_E_RANGE from qo_motion_init_f32.
 */
qo_status qo_traj_push(qo_traj *tr, qo_traj_ns t, const float *pos, const float *vel,
                       const float *acc);

/*
 * KEYS: plans the spline over the keys pushed so far if a push left it pending (sample does
 * this itself; call it to get the planning cost and its errors outside a timer interrupt).
 * TARGETS: nothing to do. Returns QO_OK; QO_E_NULL; QO_E_STATE (not initialised); QO_E_TOO_FEW
 * (no key yet); the error of qo_spline_init_f32 (e.g. QO_E_RANGE: keys too far apart for
 * their time step; the trajectory then has no plan and samples hold the first key).
 */
qo_status qo_traj_prepare(qo_traj *tr);

/*
 * Samples every joint at absolute time t (ns): pos, vel [unit/s], acc [unit/s^2], N values
 * each; vel, acc, clamped (N flags: -1 held at the lower limit, +1 at the upper, 0 free; KEYS
 * only, TARGETS write 0) may be NULL. TARGETS: applies the due targets first (see above).
 * Outputs are always written. Returns QO_OK; QO_E_NULL (tr or pos NULL: the given outputs
 * zeroed when N is known); QO_E_STATE (not initialised: zeroed); QO_E_TOO_FEW (nothing pushed:
 * zeroed); QO_E_RANGE (|t| > QO_TRAJ_TIME_MAX: the state at the start / first key, at rest);
 * QO_E_ORDER (TARGETS: t before the last re-plan: the state at the re-plan); the error of a
 * failed plan (KEYS: as qo_traj_prepare, first key held at rest) or of a target applied by
 * this call (TARGETS: as qo_motion_set_target_f32; the planner then brakes, the sample is of
 * the braking motion; a refused target state, QO_E_LIMIT or QO_E_ARG of
 * qo_motion_set_target_state_f32, leaves the motion planned before going on: tr->replan_status
 * says which of the two).
 */
qo_status qo_traj_sample(qo_traj *tr, qo_traj_ns t, float *pos, float *vel, float *acc,
                         int8_t *clamped);

/* N, or 0 for NULL or a trajectory not initialised. */
size_t qo_traj_joints(const qo_traj *tr);

/*
 * *end = when the motion known so far ends (ns): KEYS the last key's time; TARGETS, with no
 * target queued, the end of the current plan (every joint at rest at its last target; rounded
 * up to whole ns), and with targets queued the later of that and the last queued time (a lower
 * bound: their motion is planned when they become due). Returns QO_OK; QO_E_NULL (end NULL:
 * nothing written; tr NULL: *end = 0); QO_E_STATE (not initialised: *end = 0); QO_E_TOO_FEW
 * (nothing pushed: *end = 0).
 */
qo_status qo_traj_end_time(const qo_traj *tr, qo_traj_ns *end);

/* 1 if at time t nothing moves any more and nothing is queued (t >= qo_traj_end_time with no
 * target queued), else 0; 1 for NULL, a trajectory not initialised or with nothing pushed
 * (nothing can move). */
int qo_traj_done(const qo_traj *tr, qo_traj_ns t);

/*
 * *t = seconds s as ns, rounded to nearest. Returns QO_OK; QO_E_NULL (t NULL); QO_E_NONFINITE
 * (s NaN/Inf: *t = 0); QO_E_RANGE (|s * 1e9| > QO_TRAJ_TIME_MAX: *t = 0). Double precision:
 * for host callers that read seconds; firmware counts ticks in integers and scales them.
 */
qo_status qo_traj_ns_from_s(double s, qo_traj_ns *t);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_TRAJ_H */
