#include "qorient/traj.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* Relative time a - b in seconds as float32. Split into whole seconds and the ns remainder so
 * the only rounding is the final float32 one (converting the ns count alone to float would
 * round it first to 24 bits of ns). Each time is split before subtracting: a - b itself
 * overflows int64 when a = QO_TRAJ_TIME_MAX and b = -QO_TRAJ_TIME_MAX (2^63). The pair is
 * then normalised to truncating division's (quotient, remainder of the sign of a - b), so the
 * float32 result is bit for bit that of splitting a - b. */
static float rel_s(qo_traj_ns a, qo_traj_ns b)
{
    qo_traj_ns s = a / QO_TRAJ_NS_PER_S - b / QO_TRAJ_NS_PER_S;
    qo_traj_ns r = a % QO_TRAJ_NS_PER_S - b % QO_TRAJ_NS_PER_S;
    if (r >= QO_TRAJ_NS_PER_S) { s++; r -= QO_TRAJ_NS_PER_S; }
    else if (r <= -QO_TRAJ_NS_PER_S) { s--; r += QO_TRAJ_NS_PER_S; }
    if (s > 0 && r < 0) { s--; r += QO_TRAJ_NS_PER_S; }
    else if (s < 0 && r > 0) { s++; r -= QO_TRAJ_NS_PER_S; }
    return (float)s + (float)r * 1e-9f;
}

static int time_ok(qo_traj_ns t)
{
    return t >= -QO_TRAJ_TIME_MAX && t <= QO_TRAJ_TIME_MAX;
}

static int all_finite(const float *v, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!(v[i] - v[i] == 0.0f)) return 0;
    return 1;
}

static void zero_out(size_t n, float *pos, float *vel, float *acc, int8_t *clamped)
{
    size_t i;
    for (i = 0; i < n; i++) {
        if (pos) pos[i] = 0.0f;
        if (vel) vel[i] = 0.0f;
        if (acc) acc[i] = 0.0f;
        if (clamped) clamped[i] = 0;
    }
}

size_t qo_traj_store_len(qo_traj_kind kind, size_t n_joints, size_t cap, unsigned key_cols)
{
    size_t per, coef, keys;
    if (n_joints == 0 || cap == 0) return 0;
    if (n_joints > (size_t)-1 / cap) return 0;
    per = n_joints * cap;
    if (key_cols < 1 || key_cols > 3) return 0;
    if (kind == QO_TRAJ_TARGETS) return per > (size_t)-1 / key_cols ? 0 : per * key_cols;
    if (kind != QO_TRAJ_KEYS || cap < 2) return 0;
    coef = qo_spline_coef_len(n_joints, cap);
    if (coef == 0 || per > ((size_t)-1 - cap) / key_cols) return 0;
    keys = cap + per * key_cols;
    if (coef > (size_t)-1 - keys) return 0;
    return keys + coef;
}

/* What both kinds share (the callers set kind last). */
static void set_common(qo_traj *tr, size_t n_joints, size_t cap, qo_traj_ns *t_ns, float *store)
{
    tr->n = n_joints;
    tr->cap = cap;
    tr->t_ns = t_ns;
    tr->store = store;
}

qo_status qo_traj_init_keys(qo_traj *tr, size_t n_joints, const qo_spline_settings_f32 *set,
                            unsigned key_cols, qo_traj_ns *t_ns, size_t cap, float *store,
                            size_t store_len)
{
    size_t need, per;
    if (tr == NULL) return QO_E_NULL;
    memset(tr, 0, sizeof *tr);
    if (set == NULL) set = &qo_spline_settings_default;
    if (t_ns == NULL || store == NULL) return QO_E_NULL;
    if (n_joints == 0 || cap < 2) return QO_E_TOO_FEW;
    if (key_cols < 1 || key_cols > 3) return QO_E_ARG;
    if ((unsigned)set->profile > (unsigned)QO_SPLINE_QUINTIC ||
        (unsigned)set->end > (unsigned)QO_SPLINE_END_NATURAL ||
        (unsigned)set->derivs > (unsigned)QO_SPLINE_DERIVS_ZERO)
        return QO_E_ARG;
    if (set->profile == QO_SPLINE_CUBIC_HERMITE && key_cols < 2) return QO_E_ARG;
    need = qo_traj_store_len(QO_TRAJ_KEYS, n_joints, cap, key_cols);
    if (need == 0 || store_len < need) return QO_E_CAPACITY;
    per = n_joints * cap;
    set_common(tr, n_joints, cap, t_ns, store);
    tr->key_cols = key_cols;
    tr->t_rel = store;
    tr->key_p = store + cap;
    tr->key_v = key_cols >= 2 ? tr->key_p + per : NULL;
    tr->key_a = key_cols >= 3 ? tr->key_p + 2 * per : NULL;
    tr->coef = tr->key_p + key_cols * per;
    tr->coef_len = store_len - (cap + key_cols * per);
    tr->spline_set = *set;
    tr->spline_set.key_vel = NULL;
    tr->spline_set.key_acc = NULL;
    tr->spline.n_joints = n_joints;
    tr->plan_status = QO_E_TOO_FEW;
    tr->kind = QO_TRAJ_KEYS;
    return QO_OK;
}

qo_status qo_traj_init_targets(qo_traj *tr, size_t n_joints, const qo_motion_limits_f32 *limits,
                               const qo_motion_settings_f32 *set, qo_motion_joint_f32 *joints,
                               qo_traj_ns *t_ns, size_t cap, float *store, size_t store_len)
{
    size_t need, i;
    qo_status st;
    if (tr == NULL) return QO_E_NULL;
    memset(tr, 0, sizeof *tr);
    if (set == NULL) set = &qo_motion_settings_default;
    if (joints == NULL || limits == NULL || t_ns == NULL || store == NULL) return QO_E_NULL;
    if (n_joints == 0 || cap == 0) return QO_E_TOO_FEW;
    if (n_joints > QO_MOTION_MAX_JOINTS) return QO_E_CAPACITY;
    need = qo_traj_store_len(QO_TRAJ_TARGETS, n_joints, cap, 1);
    if (need == 0 || store_len < need) return QO_E_CAPACITY;
    /* Validate limits and settings now (the planner is set up for real by the first push, at
     * the start positions): a bad limit is an init error, not a surprise at the start. The
     * queue storage is free yet, so zeros there serve as the trial start. */
    for (i = 0; i < n_joints; i++) store[i] = 0.0f;
    st = qo_motion_init_f32(&tr->planner, joints, n_joints, limits, store, 0.0f, set);
    if (st != QO_OK) {
        memset(tr, 0, sizeof *tr);
        return st;
    }
    set_common(tr, n_joints, cap, t_ns, store);
    tr->queue_p = store;
    /* Room for target velocities (and accelerations) when the storage has it. */
    tr->target_cols = 1;
    if (store_len >= qo_traj_store_len(QO_TRAJ_TARGETS, n_joints, cap, 2) && qo_traj_store_len(QO_TRAJ_TARGETS, n_joints, cap, 2))
        tr->target_cols = 2;
    if (store_len >= qo_traj_store_len(QO_TRAJ_TARGETS, n_joints, cap, 3) && qo_traj_store_len(QO_TRAJ_TARGETS, n_joints, cap, 3))
        tr->target_cols = 3;
    tr->queue_v = tr->target_cols >= 2 ? store + n_joints * cap : NULL;
    tr->queue_a = tr->target_cols >= 3 ? store + 2 * n_joints * cap : NULL;
    for (i = 0; i < n_joints; i++) tr->joint_sync[i] = -1;
    tr->joints = joints;
    tr->limits = limits;
    tr->motion_set = *set;
    tr->replan_status = QO_OK;
    tr->kind = QO_TRAJ_TARGETS;
    return QO_OK;
}

static qo_status push_key(qo_traj *tr, qo_traj_ns t, const float *pos, const float *vel,
                          const float *acc)
{
    size_t n = tr->n, k = tr->n_keys;
    float rel = 0.0f;
    if ((tr->key_cols >= 2 && vel == NULL) || (tr->key_cols >= 3 && acc == NULL)) return QO_E_NULL;
    if (!all_finite(pos, n) || (tr->key_cols >= 2 && !all_finite(vel, n)) ||
        (tr->key_cols >= 3 && !all_finite(acc, n)))
        return QO_E_NONFINITE;
    if (k > 0) {
        if (t <= tr->t_ns[k - 1]) return QO_E_ORDER;
        rel = rel_s(t, tr->t_ns[0]);
        /* The spline sees float32 offsets: they too must increase strictly. */
        if (!(rel > tr->t_rel[k - 1])) return QO_E_ORDER;
    }
    if (k >= tr->cap) return QO_E_CAPACITY;
    tr->t_ns[k] = t;
    tr->t_rel[k] = rel;
    memcpy(tr->key_p + k * n, pos, n * sizeof *pos);
    if (tr->key_v) memcpy(tr->key_v + k * n, vel, n * sizeof *vel);
    if (tr->key_a) memcpy(tr->key_a + k * n, acc, n * sizeof *acc);
    tr->n_keys = k + 1;
    tr->dirty = 1;
    return QO_OK;
}

static int any_nonzero(const float *v, size_t n)
{
    size_t i;
    for (i = 0; v != NULL && i < n; i++)
        if (v[i] != 0.0f) return 1;
    return 0;
}

static qo_status push_target(qo_traj *tr, qo_traj_ns t, const float *pos, const float *vel,
                             const float *acc)
{
    size_t n = tr->n, i, slot;
    if ((vel != NULL && tr->target_cols < 2) || (acc != NULL && tr->target_cols < 3)) return QO_E_CAPACITY;
    if (!all_finite(pos, n) || (vel != NULL && !all_finite(vel, n)) || (acc != NULL && !all_finite(acc, n)))
        return QO_E_NONFINITE;
    for (i = 0; i < n; i++)
        if (pos[i] > QO_MOTION_POS_MAX || pos[i] < -QO_MOTION_POS_MAX) return QO_E_RANGE;
    if (!tr->started) {
        qo_status st;
        if (any_nonzero(vel, n) || any_nonzero(acc, n)) return QO_E_ARG; /* the start is at rest */
        st = qo_motion_init_f32(&tr->planner, tr->joints, n, tr->limits, pos, 0.0f, &tr->motion_set);
        if (st != QO_OK) return st;
        /* The init reset the planner's duration rules and per-joint sync: the caller's come
         * back. */
        (void)qo_motion_set_timing_f32(&tr->planner, tr->min_duration, tr->period);
        for (i = 0; i < n; i++)
            if (tr->joint_sync[i] >= 0)
                (void)qo_motion_set_joint_sync_f32(&tr->planner, i, (qo_motion_sync)tr->joint_sync[i]);
        tr->started = 1;
        tr->start_ns = tr->origin = tr->last_push = tr->last_sample = t;
        return QO_OK;
    }
    if (t < tr->last_push) return QO_E_ORDER;
    if (tr->count >= tr->cap) return QO_E_CAPACITY;
    slot = (tr->head + tr->count) % tr->cap;
    tr->t_ns[slot] = t;
    memcpy(tr->queue_p + slot * n, pos, n * sizeof *pos);
    for (i = 0; tr->queue_v != NULL && i < n; i++) tr->queue_v[slot * n + i] = vel != NULL ? vel[i] : 0.0f;
    for (i = 0; tr->queue_a != NULL && i < n; i++) tr->queue_a[slot * n + i] = acc != NULL ? acc[i] : 0.0f;
    tr->count++;
    tr->last_push = t;
    return QO_OK;
}

qo_status qo_traj_set_timing(qo_traj *tr, float min_duration, float period)
{
    qo_status st;
    if (tr == NULL) return QO_E_NULL;
    if (tr->kind != QO_TRAJ_TARGETS || tr->n == 0) return QO_E_STATE;
    /* The planner is initialised from qo_traj_init_targets on (a trial start before the first
     * push), so its own checks decide; stored too for the start's re-init. */
    st = qo_motion_set_timing_f32(&tr->planner, min_duration, period);
    if (st != QO_OK) return st;
    tr->min_duration = min_duration;
    tr->period = period;
    return QO_OK;
}

qo_status qo_traj_set_joint_sync(qo_traj *tr, size_t i, qo_motion_sync sync)
{
    qo_status st;
    if (tr == NULL) return QO_E_NULL;
    if (tr->kind != QO_TRAJ_TARGETS || tr->n == 0) return QO_E_STATE;
    /* As set_timing: the planner (a trial one before the first push) checks, the value is
     * kept for the start's re-init. */
    st = qo_motion_set_joint_sync_f32(&tr->planner, i, sync);
    if (st != QO_OK) return st;
    tr->joint_sync[i] = (signed char)sync;
    return QO_OK;
}

qo_status qo_traj_push(qo_traj *tr, qo_traj_ns t, const float *pos, const float *vel,
                       const float *acc)
{
    if (tr == NULL || pos == NULL) return QO_E_NULL;
    if (tr->kind == QO_TRAJ_NONE || tr->n == 0) return QO_E_STATE;
    if (!time_ok(t)) return QO_E_RANGE;
    if (tr->kind == QO_TRAJ_KEYS) return push_key(tr, t, pos, vel, acc);
    if (tr->kind == QO_TRAJ_TARGETS) return push_target(tr, t, pos, vel, acc);
    return QO_E_STATE;
}

/* The settings checks qo_spline_init_f32 makes that also concern a single key held at rest
 * (which plans nothing): a wrapped joint needs a finite period > 0 (QO_E_RANGE), position
 * limits must not be NaN, min = +Inf, max = -Inf nor min > max (QO_E_LIMIT). */
static qo_status one_key_settings(const qo_traj *tr)
{
    const qo_spline_settings_f32 *s = &tr->spline_set;
    size_t j;
    for (j = 0; j < tr->n; j++)
        if (s->wrap && s->wrap[j] && !(s->wrap_period > 0.0f && s->wrap_period <= FLT_MAX)) return QO_E_RANGE;
    for (j = 0; j < tr->n; j++) {
        float lo = s->pos_min ? s->pos_min[j] : -INFINITY, hi = s->pos_max ? s->pos_max[j] : INFINITY;
        if (isnan(lo) || isnan(hi) || lo == INFINITY || hi == -INFINITY || lo > hi) return QO_E_LIMIT;
    }
    return QO_OK;
}

static qo_status plan_keys(qo_traj *tr)
{
    if (!tr->dirty) return tr->plan_status;
    tr->dirty = 0;
    if (tr->n_keys < 2) {
        /* One key: held at rest, nothing to plan. */
        tr->spline.n_keys = 0;
        tr->plan_status = tr->n_keys == 1 ? one_key_settings(tr) : QO_E_TOO_FEW;
        return tr->plan_status;
    }
    tr->spline_set.key_vel = tr->key_v;
    tr->spline_set.key_acc = tr->key_a;
    tr->plan_status = qo_spline_init_f32(tr->n, tr->n_keys, tr->t_rel, tr->key_p, &tr->spline_set,
                                         tr->coef, tr->coef_len, &tr->spline);
    tr->spline_set.key_vel = NULL;
    tr->spline_set.key_acc = NULL;
    return tr->plan_status;
}

qo_status qo_traj_prepare(qo_traj *tr)
{
    if (tr == NULL) return QO_E_NULL;
    if (tr->kind == QO_TRAJ_NONE || tr->n == 0) return QO_E_STATE;
    if (tr->kind == QO_TRAJ_TARGETS) return tr->started ? QO_OK : QO_E_TOO_FEW;
    return plan_keys(tr);
}

/* The first key held at rest, with the position limits and wrap of the settings applied as
 * the spline sampler would (so a failed plan still gives the documented safe output), when
 * the settings are valid: a limit of -Inf above the key (refused by the plan) would make the
 * held position infinite. */
static void hold_first_key(const qo_traj *tr, float *pos, float *vel, float *acc, int8_t *clamped)
{
    size_t j, n = tr->n;
    const qo_spline_settings_f32 *s = &tr->spline_set;
    zero_out(n, pos, vel, acc, clamped);
    if (one_key_settings(tr) != QO_OK) {
        memcpy(pos, tr->key_p, n * sizeof *pos);
        return;
    }
    for (j = 0; j < n; j++) {
        float p = tr->key_p[j];
        int8_t c = 0;
        if (s->wrap && s->wrap[j] && s->wrap_output && s->wrap_period > 0.0f && s->wrap_period <= FLT_MAX) {
            /* as the spline sampler wraps: fmodf is exact and takes one step whatever the
             * ratio (a loop of p -= P never ends once P is below ulp(p)) */
            float P = s->wrap_period;
            p = fmodf(p, P);
            if (p > 0.5f * P) p -= P;
            else if (p <= -0.5f * P) p += P;
        }
        if (s->pos_min && p < s->pos_min[j]) { p = s->pos_min[j]; c = -1; }
        if (s->pos_max && p > s->pos_max[j]) { p = s->pos_max[j]; c = 1; }
        pos[j] = p;
        if (clamped) clamped[j] = c;
    }
}

static qo_status sample_keys(qo_traj *tr, qo_traj_ns t, float *pos, float *vel, float *acc,
                             int8_t *clamped)
{
    qo_status st = plan_keys(tr);
    if (tr->n_keys == 0) {
        zero_out(tr->n, pos, vel, acc, clamped);
        return QO_E_TOO_FEW;
    }
    if (st != QO_OK || tr->n_keys == 1 || !time_ok(t)) {
        hold_first_key(tr, pos, vel, acc, clamped);
        return st != QO_OK ? st : time_ok(t) ? QO_OK : QO_E_RANGE;
    }
    return qo_spline_sample_f32(&tr->spline, rel_s(t, tr->t_ns[0]), pos, vel, acc, clamped);
}

/* Applies every queued target due at t, each re-planned from the state at its time (or the
 * latest sampled time if later). Returns the first re-plan error, else QO_OK. */
static qo_status apply_due(qo_traj *tr, qo_traj_ns t)
{
    qo_status first = QO_OK;
    while (tr->count > 0 && tr->t_ns[tr->head] <= t) {
        qo_traj_ns at = tr->t_ns[tr->head];
        qo_status st;
        uint32_t mask = 0;
        if (at < tr->last_sample) at = tr->last_sample;
        if (at < tr->origin) at = tr->origin;
        /* Planner time 0 follows the last re-plan: the float32 times stay small. */
        (void)qo_motion_shift_time_f32(&tr->planner, rel_s(at, tr->origin));
        tr->origin = at;
        if (tr->queue_v != NULL)
            st = qo_motion_set_target_state_f32(&tr->planner, 0.0f, tr->queue_p + tr->head * tr->n,
                                                tr->queue_v + tr->head * tr->n,
                                                tr->queue_a != NULL ? tr->queue_a + tr->head * tr->n : NULL, &mask);
        else
            st = qo_motion_set_target_f32(&tr->planner, 0.0f, tr->queue_p + tr->head * tr->n, &mask);
        tr->clamped = mask;
        tr->replan_status = st;
        tr->replans++;
        if (st != QO_OK && first == QO_OK) first = st;
        tr->head = (tr->head + 1) % tr->cap;
        tr->count--;
    }
    return first;
}

static qo_status sample_targets(qo_traj *tr, qo_traj_ns t, float *pos, float *vel, float *acc,
                                int8_t *clamped)
{
    qo_status st, ap;
    size_t j;
    if (!tr->started) {
        zero_out(tr->n, pos, vel, acc, clamped);
        return QO_E_TOO_FEW;
    }
    if (clamped)
        for (j = 0; j < tr->n; j++) clamped[j] = 0;
    if (!time_ok(t)) {
        /* The state at the last re-plan (before any, the start at rest). */
        (void)qo_motion_sample_f32(&tr->planner, tr->planner.t0, pos, vel, acc);
        return QO_E_RANGE;
    }
    if (t < tr->start_ns && tr->replans == 0) {
        /* Before the start, nothing re-planned yet: at rest where it starts. (After a
         * re-plan the start state is gone: the QO_E_ORDER case below.) */
        st = qo_motion_sample_f32(&tr->planner, tr->planner.t0, pos, vel, acc);
        return st;
    }
    ap = apply_due(tr, t);
    if (t < tr->origin) {
        (void)qo_motion_sample_f32(&tr->planner, tr->planner.t0, pos, vel, acc);
        return ap != QO_OK ? ap : QO_E_ORDER;
    }
    if (t > tr->last_sample) tr->last_sample = t;
    st = qo_motion_sample_f32(&tr->planner, rel_s(t, tr->origin), pos, vel, acc);
    return ap != QO_OK ? ap : st;
}

qo_status qo_traj_sample(qo_traj *tr, qo_traj_ns t, float *pos, float *vel, float *acc,
                         int8_t *clamped)
{
    if (tr == NULL) return QO_E_NULL;
    if (pos == NULL) {
        if (tr->kind != QO_TRAJ_NONE) zero_out(tr->n, NULL, vel, acc, clamped);
        return QO_E_NULL;
    }
    if (tr->kind == QO_TRAJ_KEYS) return sample_keys(tr, t, pos, vel, acc, clamped);
    if (tr->kind == QO_TRAJ_TARGETS) return sample_targets(tr, t, pos, vel, acc, clamped);
    zero_out(tr->n, pos, vel, acc, clamped);
    return QO_E_STATE;
}

size_t qo_traj_joints(const qo_traj *tr)
{
    return (tr == NULL || tr->kind == QO_TRAJ_NONE) ? 0 : tr->n;
}

/* Seconds (finite, >= 0, float32) to ns, rounded up exactly (from the float's bits: s =
 * m * 2^e, so s * 1e9 = m * 1e9 * 2^e with m * 1e9 < 2^54), so "done at end" holds at the end
 * and a duration of whole ns (a plan ending on a control tick) gets no extra ns. */
static qo_traj_ns ns_up(float s)
{
    uint32_t bits;
    int e;
    qo_traj_ns m;
    if (!(s > 0.0f)) return 0;
    if (s > 4.0e9f) return QO_TRAJ_TIME_MAX; /* not reachable for checked plans */
    memcpy(&bits, &s, sizeof bits);
    e = (int)((bits >> 23) & 0xffu);
    m = (qo_traj_ns)(bits & 0x7fffffu);
    if (e == 0) return 1; /* subnormal: below 1 ns */
    m = (m | 0x800000) * QO_TRAJ_NS_PER_S;
    e -= 150;
    if (e >= 0) return m << e;
    if (-e > 54) return 1;
    return (m + (((qo_traj_ns)1 << -e) - 1)) >> -e;
}

qo_status qo_traj_end_time(const qo_traj *tr, qo_traj_ns *end)
{
    qo_traj_ns e;
    if (end == NULL) return QO_E_NULL;
    *end = 0;
    if (tr == NULL) return QO_E_NULL;
    if (tr->kind == QO_TRAJ_KEYS) {
        if (tr->n_keys == 0) return QO_E_TOO_FEW;
        *end = tr->t_ns[tr->n_keys - 1];
        return QO_OK;
    }
    if (tr->kind != QO_TRAJ_TARGETS) return QO_E_STATE;
    if (!tr->started) return QO_E_TOO_FEW;
    e = ns_up(qo_motion_end_time_f32(&tr->planner));
    /* compared before adding: origin + e can reach 2^63 (e is in [0, QO_TRAJ_TIME_MAX]) */
    e = tr->origin > 0 && e > QO_TRAJ_TIME_MAX - tr->origin ? QO_TRAJ_TIME_MAX : tr->origin + e;
    if (tr->count > 0 && tr->last_push > e) e = tr->last_push;
    *end = e;
    return QO_OK;
}

int qo_traj_done(const qo_traj *tr, qo_traj_ns t)
{
    qo_traj_ns e;
    if (tr == NULL || tr->kind == QO_TRAJ_NONE) return 1;
    if (qo_traj_end_time(tr, &e) != QO_OK) return 1;
    if (tr->kind == QO_TRAJ_TARGETS && tr->count > 0) return 0;
    return t >= e;
}

qo_status qo_traj_ns_from_s(double s, qo_traj_ns *t)
{
    double ns;
    if (t == NULL) return QO_E_NULL;
    *t = 0;
    if (!(s - s == 0.0)) return QO_E_NONFINITE;
    ns = s * 1e9;
    if (ns > (double)QO_TRAJ_TIME_MAX || ns < -(double)QO_TRAJ_TIME_MAX) return QO_E_RANGE;
    *t = (qo_traj_ns)(ns < 0.0 ? ns - 0.5 : ns + 0.5);
    return QO_OK;
}
