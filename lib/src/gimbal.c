/* Orientation paths and gimbal joint angles, float32. Contract: qorient/gimbal.h. */
#include "qorient/gimbal.h"

#include <math.h>

#include "qorient/interp.h"
#include "qorient/quat.h"

const qo_gimbal_settings_f32 qo_gimbal_settings_default = {
    QO_EULER_ZYX,
    0.017453292f, /* 1 degree: wide enough that a path through the singularity never sees the
                     free angle swing, narrow enough that the held split is still within
                     2 * 1 degree of the requested orientation (qo_euler_from_quat_near_f32) */
    INFINITY,
    { -INFINITY, -INFINITY, -INFINITY },
    { INFINITY, INFINITY, INFINITY },
};

qo_status qo_gimbal_path_init_f32(qo_gimbal_path_f32 *path, const float *t,
                                  const qo_quat_f32 *keys_in, size_t n, qo_gimbal_path_interp interp,
                                  qo_quat_f32 *keys, qo_quat_f32 *a, qo_quat_f32 *b)
{
    size_t i;
    qo_status st;
    if (path == NULL) return QO_E_NULL;
    path->t = t; path->keys = keys; path->a = a; path->b = b;
    path->n = 0;
    path->interp = interp;
    if (t == NULL || keys_in == NULL || keys == NULL) return QO_E_NULL;
    if (interp != QO_GIMBAL_PATH_SLERP && interp != QO_GIMBAL_PATH_SPLINE) return QO_E_ARG;
    if (interp == QO_GIMBAL_PATH_SPLINE && (a == NULL || b == NULL)) return QO_E_NULL;
    if (n < 2) return QO_E_TOO_FEW;
    for (i = 0; i < n; i++) {
        if (!isfinite(t[i]) || !qo_quat_is_finite_f32(keys_in[i])) return QO_E_NONFINITE;
        if (i > 0 && !(t[i] > t[i - 1])) return QO_E_ORDER;
    }
    st = qo_interp_align_keys_f32(keys_in, n, keys);
    if (st != QO_OK) return st;
    if (interp == QO_GIMBAL_PATH_SPLINE) {
        st = qo_interp_spline_controls_f32(keys, n, a, b);
        if (st != QO_OK) return st;
    }
    path->n = n;
    return QO_OK;
}

qo_status qo_gimbal_path_sample_f32(const qo_gimbal_path_f32 *path, float t, qo_quat_f32 *out)
{
    size_t lo, hi;
    float u;
    if (out == NULL) return QO_E_NULL;
    *out = qo_quat_identity_f32();
    if (path == NULL) return QO_E_NULL;
    if (path->n < 2 || path->t == NULL || path->keys == NULL) return QO_E_STATE;
    if (!isfinite(t)) return QO_E_NONFINITE;
    if (t <= path->t[0]) { *out = path->keys[0]; return QO_OK; }
    if (t >= path->t[path->n - 1]) { *out = path->keys[path->n - 1]; return QO_OK; }
    /* Binary search for the segment [t[lo], t[lo+1]) holding t: O(log n) per sample so long
     * paths sample at a fixed cost. */
    lo = 0;
    hi = path->n - 1;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (path->t[mid] <= t) lo = mid; else hi = mid;
    }
    u = (t - path->t[lo]) / (path->t[lo + 1] - path->t[lo]);
    if (u > 1.0f) u = 1.0f; /* rounding of the division, never more than 1 ulp */
    if (u < 0.0f) u = 0.0f;
    if (path->interp == QO_GIMBAL_PATH_SPLINE)
        return qo_interp_spline_eval_f32(path->keys, path->a, path->b, path->n, (float)lo + u, out);
    return qo_interp_slerp_f32(path->keys[lo], path->keys[lo + 1], u, out);
}

static qo_status check_settings(const qo_gimbal_settings_f32 *s)
{
    int i;
    if ((unsigned)s->seq >= (unsigned)QO_EULER_SEQ_COUNT_) return QO_E_ARG;
    if (isnan(s->band) || s->band < 0.0f || s->band > 1.57079633f) return QO_E_RANGE;
    if (!(s->vmax > 0.0f)) return QO_E_LIMIT; /* also rejects NaN */
    for (i = 0; i < 3; i++) {
        if (isnan(s->min[i]) || isnan(s->max[i]) || s->min[i] > s->max[i]) return QO_E_LIMIT;
        /* min = +Inf (or max = -Inf) would clamp the joint to an infinite command. */
        if (s->min[i] == INFINITY || s->max[i] == -INFINITY) return QO_E_LIMIT;
    }
    return QO_OK;
}

qo_status qo_gimbal_init_f32(qo_gimbal_f32 *g, const qo_gimbal_settings_f32 *s)
{
    qo_status st;
    if (g == NULL) return QO_E_NULL;
    g->s = qo_gimbal_settings_default;
    g->prev.a1 = g->prev.a2 = g->prev.a3 = 0.0f;
    g->t_prev = 0.0f;
    g->prev2 = g->prev;
    g->t_prev2 = 0.0f;
    g->started = 0;
    g->have2 = 0;
    if (s == NULL) return QO_E_NULL;
    st = check_settings(s);
    if (st != QO_OK) return st;
    g->s = *s;
    return QO_OK;
}

qo_status qo_gimbal_reset_f32(qo_gimbal_f32 *g, qo_euler_f32 angles, float t)
{
    if (g == NULL) return QO_E_NULL;
    if (!isfinite(angles.a1) || !isfinite(angles.a2) || !isfinite(angles.a3) || !isfinite(t))
        return QO_E_NONFINITE;
    g->prev = angles;
    g->t_prev = t;
    g->started = 1;
    g->have2 = 0;
    return QO_OK;
}

/* Moves *v toward want by at most step; returns 1 if it had to stop short. */
static int limit_step(float *v, float from, float want, float step)
{
    float d = want - from;
    if (d > step) { *v = from + step; return 1; }
    if (d < -step) { *v = from - step; return 1; }
    *v = want;
    return 0;
}

static int clamp_pos(float *v, float lo, float hi)
{
    if (*v < lo) { *v = lo; return 1; }
    if (*v > hi) { *v = hi; return 1; }
    return 0;
}

qo_status qo_gimbal_step_f32(qo_gimbal_f32 *g, float t, qo_quat_f32 q, qo_gimbal_sample_f32 *out)
{
    qo_euler_f32 e;
    qo_euler_info_f32 info;
    qo_status st;
    unsigned clipped = 0;
    float *ang[3];
    float prev[3];
    int i;
    if (out == NULL) return QO_E_NULL;
    out->angles.a1 = out->angles.a2 = out->angles.a3 = 0.0f;
    out->margin = 0.0f;
    out->locked = 0;
    out->clipped = 0;
    if (g == NULL) return QO_E_NULL;
    if (check_settings(&g->s) != QO_OK) return QO_E_STATE;
    if (g->started) out->angles = g->prev;
    if (!isfinite(t)) return QO_E_NONFINITE;
    if (g->started && !(t > g->t_prev)) return QO_E_ORDER;

    if (g->started) {
        qo_euler_f32 pred = g->prev;
        if (g->have2) {
            /* Linear prediction of a1, a2 from the last two commanded samples; a3 held. A
             * nearest-to-previous choice alone cannot tell "carry on through 90 degrees" from
             * "bounce back", the two branches being equally near at the singularity. */
            float r = (t - g->t_prev) / (g->t_prev - g->t_prev2);
            if (!(r <= 4.0f)) r = 4.0f; /* a long pause must not extrapolate wildly */
            pred.a1 = g->prev.a1 + r * (g->prev.a1 - g->prev2.a1);
            pred.a2 = g->prev.a2 + r * (g->prev.a2 - g->prev2.a2);
        }
        st = qo_euler_from_quat_near_f32(q, g->s.seq, pred, g->s.band, &e, &info);
    } else
        st = qo_euler_from_quat_band_f32(q, g->s.seq, g->s.band, &e, &info);
    if (st != QO_OK) {
        if (g->started) out->angles = g->prev;
        return st;
    }

    ang[0] = &e.a1; ang[1] = &e.a2; ang[2] = &e.a3;
    prev[0] = g->prev.a1; prev[1] = g->prev.a2; prev[2] = g->prev.a3;
    /* Position limits first, then the rate limit: the rate limit is the last word, so even a
     * reset outside the limits walks back inside at vmax instead of jumping. */
    for (i = 0; i < 3; i++)
        if (clamp_pos(ang[i], g->s.min[i], g->s.max[i])) clipped |= 1u << i;
    if (g->started && isfinite(g->s.vmax)) {
        float step = g->s.vmax * (t - g->t_prev);
        for (i = 0; i < 3; i++)
            if (limit_step(ang[i], prev[i], *ang[i], step)) clipped |= 1u << i;
    }

    if (g->started) {
        g->prev2 = g->prev;
        g->t_prev2 = g->t_prev;
        g->have2 = 1;
    }
    g->prev = e;
    g->t_prev = t;
    g->started = 1;
    out->angles = e;
    out->margin = info.margin;
    out->locked = info.locked;
    out->clipped = clipped;
    return QO_OK;
}

const qo_gimbal_track_settings_f32 qo_gimbal_track_settings_default = {
    10.0f,    /* rad/s^2: a small camera head; the caller sets its mechanism's figure */
    INFINITY, /* acceleration-limited (TRAPEZOID) unless a jerk limit is asked for */
    INFINITY,
    10.0f,    /* 1/s: a 0.1 s time constant for small errors, well below amax/vmax scales */
};

static int track_limit_ok(float v, int inf_ok)
{
    if (inf_ok && v == INFINITY) return 1;
    return v >= QO_MOTION_LIMIT_MIN && v <= QO_MOTION_LIMIT_MAX; /* false for NaN */
}

static qo_status track_check(const qo_gimbal_track_settings_f32 *s)
{
    if (!track_limit_ok(s->amax, 0) || !track_limit_ok(s->jmax, 1) || !track_limit_ok(s->vmax, 1)
        || !track_limit_ok(s->gain, 0))
        return QO_E_LIMIT;
    return QO_OK;
}

qo_status qo_gimbal_track_init_f32(qo_gimbal_track_f32 *tr, const qo_gimbal_track_settings_f32 *s)
{
    int i;
    if (tr == NULL) return QO_E_NULL;
    tr->s = qo_gimbal_track_settings_default;
    tr->pl.joints = NULL;
    tr->pl.n = 0; /* the planner is set up at the first step, at the path's angles */
    for (i = 0; i < 3; i++) tr->path_prev[i] = 0.0f;
    tr->t_prev = 0.0f;
    tr->started = 0;
    tr->holding = 0;
    tr->last.angles.a1 = tr->last.angles.a2 = tr->last.angles.a3 = 0.0f;
    for (i = 0; i < 3; i++) tr->last.rate[i] = tr->last.acc[i] = 0.0f;
    tr->last.err = 0.0f;
    tr->last.settled = 0;
    if (s == NULL) return QO_E_NULL;
    if (track_check(s) != QO_OK) {
        tr->s.amax = 0.0f; /* marks the failed init: steps return QO_E_STATE */
        return QO_E_LIMIT;
    }
    tr->s = *s;
    return QO_OK;
}

/* Velocity that closes position error e: linear (gain) for small errors, and beyond
 * amax/(2 gain^2) the speed from which amax/2 brakes to zero exactly at the path (the two
 * pieces meet with equal value and slope); half of amax is left for following the path's own
 * rate changes. Capped at |e|/(2 dt): a joint commanded at that speed for one step closes at
 * most half the error, so a long step (a slow control loop) cannot overshoot and ring. */
static float track_correction(float e, float amax, float gain, float dt)
{
    float ae = fabsf(e), lin = amax / (2.0f * gain * gain), c, cap;
    c = ae <= lin ? gain * ae : sqrtf(amax * (ae - 0.5f * lin));
    cap = ae / (2.0f * dt);
    if (c > cap) c = cap;
    return e < 0.0f ? -c : c;
}

static float clampf(float v, float lim)
{
    if (v > lim) return lim;
    if (v < -lim) return -lim;
    return v;
}

/* Output of a step that did not move the filter: the last step's joints, err 0, settled 0. */
static void track_hold(const qo_gimbal_track_f32 *tr, qo_gimbal_track_sample_f32 *out)
{
    if (!tr->started) return;
    *out = tr->last;
    out->err = 0.0f;
    out->settled = 0;
}

qo_status qo_gimbal_track_step_f32(qo_gimbal_track_f32 *tr, float t, qo_euler_f32 path,
                                   qo_gimbal_track_sample_f32 *out)
{
    float in[3], p[3], v[3], a[3], cmd[3], dt = 0.0f, vm;
    int i, still = 1, settled = 1;
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    out->angles.a1 = out->angles.a2 = out->angles.a3 = 0.0f;
    for (i = 0; i < 3; i++) out->rate[i] = out->acc[i] = 0.0f;
    out->err = 0.0f;
    out->settled = 0;
    if (tr == NULL) return QO_E_NULL;
    if (track_check(&tr->s) != QO_OK) return QO_E_STATE;
    track_hold(tr, out);
    in[0] = path.a1; in[1] = path.a2; in[2] = path.a3;
    if (!isfinite(t)) return QO_E_NONFINITE;
    for (i = 0; i < 3; i++) {
        if (!isfinite(in[i])) return QO_E_NONFINITE;
        if (fabsf(in[i]) > QO_MOTION_POS_MAX) return QO_E_RANGE;
    }
    if (tr->started) {
        if (!(t > tr->t_prev)) return QO_E_ORDER;
        dt = t - tr->t_prev;
        /* A step longer than any plan the planner makes (1e4 s) would extrapolate a moving
         * joint beyond the planner's position range: refused like an overflowing one. */
        if (!(dt <= QO_MOTION_DURATION_MAX)) return QO_E_RANGE;
    }
    /* The planner's rate limit: vmax, but at most the speed amax reaches in 1000 s (no real
     * path asks for more). The float32 planner loses a re-planned target when vmax/amax is
     * near 1e5 s or more (its plan then ends short and snaps: a jump), so "no limit" must
     * not be handed to it as QO_MOTION_LIMIT_MAX. */
    vm = tr->s.amax * 1000.0f;
    if (tr->s.vmax < vm) vm = tr->s.vmax;
    if (vm > QO_MOTION_LIMIT_MAX) vm = QO_MOTION_LIMIT_MAX;

    if (!tr->started) {
        /* The planner's time is kept relative to the last step (0 = now), so float32 times
         * never grow with the run. */
        qo_motion_limits_f32 lim[3];
        qo_motion_settings_f32 ms;
        ms.profile = isfinite(tr->s.jmax) ? QO_MOTION_SCURVE : QO_MOTION_TRAPEZOID;
        ms.sync = QO_MOTION_SYNC_NONE;
        for (i = 0; i < 3; i++) {
            lim[i] = qo_motion_limits_default;
            lim[i].vmax = vm;
            lim[i].amax = tr->s.amax;
            lim[i].jmax = isfinite(tr->s.jmax) ? tr->s.jmax : tr->s.amax; /* unused by TRAPEZOID */
        }
        st = qo_motion_init_f32(&tr->pl, tr->joints, 3, lim, in, 0.0f, &ms);
        if (st != QO_OK) return st; /* not reachable for the inputs checked above */
        for (i = 0; i < 3; i++) tr->path_prev[i] = in[i];
        tr->t_prev = t;
        tr->started = 1;
        tr->holding = 0;
        out->angles = path;
        for (i = 0; i < 3; i++) out->rate[i] = out->acc[i] = 0.0f;
        out->settled = 1;
        tr->last = *out;
        return QO_OK;
    }

    st = qo_motion_sample_f32(&tr->pl, dt, p, v, a);
    if (st != QO_OK) return st; /* not reachable: dt > 0 is finite */
    for (i = 0; i < 3; i++) {
        float e = in[i] - p[i], rate;
        if (fabsf(e) > out->err) out->err = fabsf(e);
        if (in[i] != tr->path_prev[i]) still = 0;
        if (e != 0.0f || v[i] != 0.0f || a[i] != 0.0f) settled = 0;
        /* The path's rate over the last step, and the correction, each clamped first so that
         * their sum is finite (a huge jump over a tiny step gives an infinite quotient). */
        rate = clampf((in[i] - tr->path_prev[i]) / dt, vm);
        cmd[i] = clampf(rate + clampf(track_correction(e, tr->s.amax, tr->s.gain, dt), vm), vm);
    }
    (void)qo_motion_shift_time_f32(&tr->pl, dt); /* finite dt, started planner: cannot fail */
    /* A path holding still is a position target: the joints arrive on it exactly, at rest,
     * instead of approaching it forever. It is planned once and that plan runs to its end,
     * where the planner snaps to the target at rest. Re-planning it at every step would be
     * a limit cycle: sampled mid-plan the state carries float32 rounding, and the plan for
     * the last ulp or so of a move (jerk-limited: longer than a step) from it ends an ulp
     * off, so the next step re-plans again, forever (seen on targets whose libm rounds the
     * path an ulp differently). The one exception is a plan that has ended off the path:
     * the planner ends at p0 + (target - p0), which float32 rounds an ulp of |p0| away from
     * the target after a long move; planned again from rest that near, the difference is
     * exact (Sterbenz) and the next plan ends on the target. A joint state beyond the
     * planner's position range (a fast joint over a long step) cannot be planned from: stop. */
    if (!(fabsf(p[0]) <= QO_MOTION_POS_MAX && fabsf(p[1]) <= QO_MOTION_POS_MAX && fabsf(p[2]) <= QO_MOTION_POS_MAX)) {
        (void)qo_motion_brake_f32(&tr->pl, 0.0f);
        st = QO_E_RANGE;
    } else if (still) {
        if (!tr->holding || (!settled && qo_motion_done_f32(&tr->pl, 0.0f)))
            st = qo_motion_set_target_f32(&tr->pl, 0.0f, in, NULL);
        else
            st = QO_OK;
    } else
        st = qo_motion_set_velocity_f32(&tr->pl, 0.0f, cmd);
    tr->holding = still && st == QO_OK;
    for (i = 0; i < 3; i++) tr->path_prev[i] = in[i];
    tr->t_prev = t;
    out->angles.a1 = p[0]; out->angles.a2 = p[1]; out->angles.a3 = p[2];
    for (i = 0; i < 3; i++) { out->rate[i] = v[i]; out->acc[i] = a[i]; }
    out->settled = still && settled;
    if (st != QO_OK) {
        /* The safety stop starts where the planner could put it (a state beyond its range,
         * after a huge step, is not one): report that, the state the next step starts from. */
        (void)qo_motion_sample_f32(&tr->pl, 0.0f, p, v, a);
        out->angles.a1 = p[0]; out->angles.a2 = p[1]; out->angles.a3 = p[2];
        for (i = 0; i < 3; i++) { out->rate[i] = v[i]; out->acc[i] = a[i]; }
        out->settled = 0;
    }
    tr->last = *out;
    return st;
}
