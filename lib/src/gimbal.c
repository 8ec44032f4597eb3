/* Orientation paths and gimbal joint angles, float32. Contract: qorient/gimbal.h. */
#include "qorient/gimbal.h"

#include <math.h>

#include "qorient/interp.h"
#include "qorient/quat.h"

const qo_gimbal_settings_f32 qo_gimbal_settings_default_f32 = {
    QO_EULER_ZYX,
    0.017453292f, /* 1 degree: wide enough that a path through the singularity never sees the
                     free angle swing, narrow enough that the held split is still within
                     2 * 1 degree of the requested orientation (qo_quat_to_euler_near_f32) */
    INFINITY,
    { -INFINITY, -INFINITY, -INFINITY },
    { INFINITY, INFINITY, INFINITY },
};

qo_status qo_orient_path_init_f32(qo_orient_path_f32 *path, const float *t,
                                  const qo_quat_f32 *keys_in, size_t n, qo_path_interp interp,
                                  qo_quat_f32 *keys, qo_quat_f32 *a, qo_quat_f32 *b)
{
    size_t i;
    qo_status st;
    if (path == NULL) return QO_E_NULL;
    path->t = t; path->keys = keys; path->a = a; path->b = b;
    path->n = 0;
    path->interp = interp;
    if (t == NULL || keys_in == NULL || keys == NULL) return QO_E_NULL;
    if (interp != QO_PATH_SLERP && interp != QO_PATH_SPLINE) return QO_E_ARG;
    if (interp == QO_PATH_SPLINE && (a == NULL || b == NULL)) return QO_E_NULL;
    if (n < 2) return QO_E_TOO_FEW;
    for (i = 0; i < n; i++) {
        if (!isfinite(t[i]) || !qo_quat_is_finite_f32(keys_in[i])) return QO_E_NONFINITE;
        if (i > 0 && !(t[i] > t[i - 1])) return QO_E_ORDER;
    }
    st = qo_quat_align_keys_f32(keys_in, n, keys);
    if (st != QO_OK) return st;
    if (interp == QO_PATH_SPLINE) {
        st = qo_quat_spline_controls_f32(keys, n, a, b);
        if (st != QO_OK) return st;
    }
    path->n = n;
    return QO_OK;
}

qo_status qo_orient_path_sample_f32(const qo_orient_path_f32 *path, float t, qo_quat_f32 *out)
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
    if (path->interp == QO_PATH_SPLINE)
        return qo_quat_spline_eval_f32(path->keys, path->a, path->b, path->n, (float)lo + u, out);
    return qo_quat_slerp_f32(path->keys[lo], path->keys[lo + 1], u, out);
}

static qo_status check_settings(const qo_gimbal_settings_f32 *s)
{
    int i;
    if ((unsigned)s->seq >= (unsigned)QO_EULER_SEQ_COUNT_) return QO_E_ARG;
    if (isnan(s->band) || s->band < 0.0f || s->band > 1.57079633f) return QO_E_RANGE;
    if (!(s->vmax > 0.0f)) return QO_E_LIMIT; /* also rejects NaN */
    for (i = 0; i < 3; i++) {
        if (isnan(s->min[i]) || isnan(s->max[i]) || s->min[i] > s->max[i]) return QO_E_LIMIT;
    }
    return QO_OK;
}

qo_status qo_gimbal_init_f32(qo_gimbal_f32 *g, const qo_gimbal_settings_f32 *s)
{
    qo_status st;
    if (g == NULL) return QO_E_NULL;
    g->s = qo_gimbal_settings_default_f32;
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
        st = qo_quat_to_euler_near_f32(q, g->s.seq, pred, g->s.band, &e, &info);
    } else
        st = qo_quat_to_euler_band_f32(q, g->s.seq, g->s.band, &e, &info);
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
