/* Keyframe trajectories, float32 planning and sampling, and the one-time conversion to the
 * fixed-point table. See qorient/spline.h for the contract of each function. */
#include "qorient/spline.h"

#include <math.h>

/* Storage layout inside coef (floats):
 *   [0, K)                 key times
 *   K + 3j + {0,1,2}       joint j: min, max, wrap period (0 = not wrapped)
 *   K + 3N + 6(kN + j) + n segment k, joint j, coefficient b_n (normalised time);
 *                          row K-1 is the end state (p, v, a, 0, 0, 0) in physical units.
 * While planning, rows temporarily hold the unwrapped key position (slot 0), the key velocity
 * (slot 1) and acceleration (slot 2) in physical units, and the tridiagonal solver's
 * c' / d' (slots 3 / 4): this is the "scratch" of the C2 solve, so no extra storage. */
#define COEF_W 6u

const qo_spline_settings_f32 qo_spline_settings_default = {
    QO_SPLINE_CUBIC_C2,        /* profile */
    QO_SPLINE_END_CLAMPED,     /* end */
    NULL,                      /* end_vel: rest */
    NULL,                      /* key_vel */
    NULL,                      /* key_acc */
    QO_SPLINE_DERIVS_ESTIMATED,
    NULL,                      /* pos_min */
    NULL,                      /* pos_max */
    NULL,                      /* wrap */
    6.28318530717958647692f,   /* wrap_period: 2 pi */
    1                          /* wrap_output */
};

size_t qo_spline_coef_len(size_t n_joints, size_t n_keys)
{
    size_t per_key;
    if (n_joints == 0 || n_keys < 2) return 0;
    /* K + 3N + 6KN = K(1 + 6N) + 3N, each step checked against size_t overflow. */
    if (n_joints > (SIZE_MAX - 1) / COEF_W) return 0;
    per_key = 1 + COEF_W * n_joints;
    if (n_keys > SIZE_MAX / per_key) return 0;
    if (n_joints > SIZE_MAX / 3 || n_keys * per_key > SIZE_MAX - 3 * n_joints) return 0;
    return n_keys * per_key + 3 * n_joints;
}

static float *row_of(float *coef, size_t nj, size_t nk, size_t k, size_t j)
{
    return coef + nk + 3 * nj + COEF_W * (k * nj + j);
}

static const float *row_of_c(const float *coef, size_t nj, size_t nk, size_t k, size_t j)
{
    return coef + nk + 3 * nj + COEF_W * (k * nj + j);
}

/* d in (-period/2, period/2]; fmodf is exact, so the only rounding is the final +-period. */
static float wrap_half(float d, float period)
{
    float r = fmodf(d, period);
    if (r > 0.5f * period) r -= period;
    else if (r <= -0.5f * period) r += period;
    return r;
}

static int all_finite(const float *v, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++)
        if (!isfinite(v[i])) return 0;
    return 1;
}

/* Segment k of joint j from key positions (slot 0), velocities (slot 1) and accelerations
 * (slot 2) of rows k and k+1, written over row k as normalised-time coefficients. */
static void segment_from_pva(float *r0, const float *r1, float h, qo_spline_profile prof)
{
    float d = r1[0] - r0[0];
    float v0 = r0[1] * h, v1 = r1[1] * h;           /* velocities in position units per s-unit */
    float a0 = r0[2] * h * h, a1 = r1[2] * h * h;
    if (prof == QO_SPLINE_LINEAR) {
        r0[1] = d;
        r0[2] = r0[3] = r0[4] = r0[5] = 0.0f;
    } else if (prof == QO_SPLINE_QUINTIC) {
        r0[1] = v0;
        r0[2] = 0.5f * a0;
        r0[3] = 10.0f * d - (6.0f * v0 + 4.0f * v1) - 0.5f * (3.0f * a0 - a1);
        r0[4] = -15.0f * d + (8.0f * v0 + 7.0f * v1) + 0.5f * (3.0f * a0 - 2.0f * a1);
        r0[5] = 6.0f * d - 3.0f * (v0 + v1) - 0.5f * (a0 - a1);
    } else { /* cubic Hermite: HERMITE, CATMULL_ROM */
        r0[1] = v0;
        r0[2] = 3.0f * d - 2.0f * v0 - v1;
        r0[3] = -2.0f * d + v0 + v1;
        r0[4] = r0[5] = 0.0f;
    }
}

/* Estimated key values y'_k from y_k (slot `src`) into slot `dst`: weighted chord slope
 * (y_k - y_(k-1))/h0 * h1 + (y_(k+1) - y_k)/h1 * h0, over h0 + h1, for inner keys only. */
static void estimate_inner(float *coef, size_t nj, size_t nk, size_t j, const float *t,
                           unsigned src, unsigned dst)
{
    size_t k;
    float prev = row_of(coef, nj, nk, 0, j)[src];
    for (k = 1; k + 1 < nk; k++) {
        float *r = row_of(coef, nj, nk, k, j);
        float h0 = t[k] - t[k - 1], h1 = t[k + 1] - t[k];
        float s0 = (r[src] - prev) / h0;
        float s1 = (row_of(coef, nj, nk, k + 1, j)[src] - r[src]) / h1;
        prev = r[src]; /* read before writing: src and dst may be different slots only */
        r[dst] = (s0 * h1 + s1 * h0) / (h0 + h1);
    }
}

/* Natural-spline (C2) key accelerations by the Thomas algorithm; c' in slot 3, d' in slot
 * 4, result in slot 2. Equations in terms of the key accelerations M_k:
 *   inner:   h0 M_(k-1) + 2 (h0 + h1) M_k + h1 M_(k+1) = 6 (s1 - s0)
 *   clamped: 2 h M_0 + h M_1 = 6 (s_0 - v_start),  h M_(K-2) + 2 h M_(K-1) = 6 (v_end - s)
 *   natural: M = 0 at the end.  Strictly diagonally dominant, so no pivoting. */
static void solve_c2(float *coef, size_t nj, size_t nk, size_t j, const float *t, int natural,
                     float v_start, float v_end)
{
    size_t k;
    float cprev = 0.0f, dprev = 0.0f;
    for (k = 0; k < nk; k++) {
        float *r = row_of(coef, nj, nk, k, j);
        float a, b, c, rhs, den;
        if (k == 0) {
            float h = t[1] - t[0];
            float s = (row_of(coef, nj, nk, 1, j)[0] - r[0]) / h;
            a = 0.0f;
            if (natural) { b = 1.0f; c = 0.0f; rhs = 0.0f; }
            else { b = 2.0f * h; c = h; rhs = 6.0f * (s - v_start); }
        } else if (k + 1 == nk) {
            float h = t[k] - t[k - 1];
            float s = (r[0] - row_of(coef, nj, nk, k - 1, j)[0]) / h;
            c = 0.0f;
            if (natural) { a = 0.0f; b = 1.0f; rhs = 0.0f; }
            else { a = h; b = 2.0f * h; rhs = 6.0f * (v_end - s); }
        } else {
            float h0 = t[k] - t[k - 1], h1 = t[k + 1] - t[k];
            float s0 = (r[0] - row_of(coef, nj, nk, k - 1, j)[0]) / h0;
            float s1 = (row_of(coef, nj, nk, k + 1, j)[0] - r[0]) / h1;
            a = h0; b = 2.0f * (h0 + h1); c = h1; rhs = 6.0f * (s1 - s0);
        }
        den = b - a * cprev;
        cprev = c / den;
        dprev = (rhs - a * dprev) / den;
        r[3] = cprev;
        r[4] = dprev;
    }
    {
        float mnext = 0.0f;
        for (k = nk; k-- > 0;) {
            float *r = row_of(coef, nj, nk, k, j);
            float m = (k + 1 == nk) ? r[4] : r[4] - r[3] * mnext;
            r[2] = m;
            mnext = m;
        }
    }
}

static void segment_from_moments(float *r0, const float *r1, float h)
{
    float d = r1[0] - r0[0];
    float m0 = r0[2] * h * h, m1 = r1[2] * h * h;
    r0[1] = d - (2.0f * m0 + m1) / 6.0f;
    r0[2] = 0.5f * m0;
    r0[3] = (m1 - m0) / 6.0f;
    r0[4] = r0[5] = 0.0f;
}

static void empty_plan(qo_spline_f32 *out, size_t n_joints)
{
    out->n_joints = n_joints;
    out->n_keys = 0;
    out->profile = QO_SPLINE_LINEAR;
    out->wrap_output = 0;
    out->coef = NULL;
}

static qo_status check_inputs(size_t nj, size_t nk, const float *t, const float *p,
                              const qo_spline_settings_f32 *set)
{
    size_t k, j;
    int any_wrap = 0;
    if (set->profile != QO_SPLINE_LINEAR && set->profile != QO_SPLINE_CUBIC_HERMITE &&
        set->profile != QO_SPLINE_CATMULL_ROM && set->profile != QO_SPLINE_CUBIC_C2 &&
        set->profile != QO_SPLINE_QUINTIC)
        return QO_E_ARG;
    if (set->end != QO_SPLINE_END_CLAMPED && set->end != QO_SPLINE_END_NATURAL) return QO_E_ARG;
    if (set->derivs != QO_SPLINE_DERIVS_ESTIMATED && set->derivs != QO_SPLINE_DERIVS_ZERO)
        return QO_E_ARG;
    if (!all_finite(t, nk) || !all_finite(p, nk * nj)) return QO_E_NONFINITE;
    if (set->end_vel != NULL && !all_finite(set->end_vel, 2 * nj)) return QO_E_NONFINITE;
    if ((set->profile == QO_SPLINE_CUBIC_HERMITE || set->profile == QO_SPLINE_QUINTIC) &&
        set->key_vel != NULL && !all_finite(set->key_vel, nk * nj))
        return QO_E_NONFINITE;
    if (set->profile == QO_SPLINE_QUINTIC && set->key_acc != NULL &&
        !all_finite(set->key_acc, nk * nj))
        return QO_E_NONFINITE;
    for (k = 1; k < nk; k++)
        if (!(t[k] > t[k - 1])) return QO_E_ORDER;
    for (k = 1; k < nk; k++)
        if (!isfinite(t[k] - t[k - 1])) return QO_E_RANGE;
    if (set->wrap != NULL)
        for (j = 0; j < nj; j++) any_wrap |= set->wrap[j] != 0;
    if (any_wrap && !(isfinite(set->wrap_period) && set->wrap_period > 0.0f)) return QO_E_RANGE;
    for (j = 0; j < nj; j++) {
        float lo = set->pos_min ? set->pos_min[j] : -INFINITY;
        float hi = set->pos_max ? set->pos_max[j] : INFINITY;
        if (isnan(lo) || isnan(hi) || lo == INFINITY || hi == -INFINITY || lo > hi)
            return QO_E_LIMIT;
    }
    return QO_OK;
}

/* Key velocities (slot 1) of joint j for CATMULL_ROM and estimated QUINTIC. */
static void key_velocities(float *coef, size_t nj, size_t nk, size_t j, const float *t,
                           const qo_spline_settings_f32 *set)
{
    float *first = row_of(coef, nj, nk, 0, j), *last = row_of(coef, nj, nk, nk - 1, j);
    size_t k;
    if (set->profile == QO_SPLINE_QUINTIC && set->derivs == QO_SPLINE_DERIVS_ZERO) {
        for (k = 1; k + 1 < nk; k++) row_of(coef, nj, nk, k, j)[1] = 0.0f;
    } else {
        estimate_inner(coef, nj, nk, j, t, 0, 1);
    }
    if (set->end == QO_SPLINE_END_CLAMPED) {
        first[1] = set->end_vel ? set->end_vel[j] : 0.0f;
        last[1] = set->end_vel ? set->end_vel[nj + j] : 0.0f;
    } else {
        float s0 = (row_of(coef, nj, nk, 1, j)[0] - first[0]) / (t[1] - t[0]);
        float s1 = (last[0] - row_of(coef, nj, nk, nk - 2, j)[0]) / (t[nk - 1] - t[nk - 2]);
        if (nk == 2) {
            first[1] = s0; /* both ends natural: the straight line */
            last[1] = s1;
        } else {
            first[1] = 0.5f * (3.0f * s0 - row_of(coef, nj, nk, 1, j)[1]);
            last[1] = 0.5f * (3.0f * s1 - row_of(coef, nj, nk, nk - 2, j)[1]);
        }
    }
}

/* Every sampled value stays finite: for s in [0, 1] each Horner partial sum of p, p' and p''
 * is at most the sum of |b_n| weighted by n^0, n, n(n-1), so bounding those sums (divided by
 * h, h^2 as the sampler does) below QO_SPLINE_MAX_VALUE bounds every intermediate of
 * qo_spline_sample_f32 with a margin for its rounding. */
static int segments_bounded(const float *coef, size_t nj, size_t nk)
{
    size_t k, j, n;
    for (k = 0; k + 1 < nk; k++) {
        float h = coef[k + 1] - coef[k];
        for (j = 0; j < nj; j++) {
            const float *b = row_of_c(coef, nj, nk, k, j);
            float s0 = 0.0f, s1 = 0.0f, s2 = 0.0f;
            for (n = 0; n < COEF_W; n++) {
                float m = fabsf(b[n]);
                s0 += m;
                s1 += (float)n * m;
                s2 += (float)(n * (n - (n > 0))) * m;
            }
            if (!(s0 <= QO_SPLINE_MAX_VALUE && s1 / h <= QO_SPLINE_MAX_VALUE &&
                  (s2 / h) / h <= QO_SPLINE_MAX_VALUE))
                return 0;
        }
    }
    return 1;
}

qo_status qo_spline_init_f32(size_t n_joints, size_t n_keys, const float *t, const float *p,
                             const qo_spline_settings_f32 *set, float *coef, size_t coef_len,
                             qo_spline_f32 *out)
{
    size_t need, j, k;
    qo_status st;
    float *tt;
    if (out == NULL) return QO_E_NULL;
    empty_plan(out, n_joints);
    if (t == NULL || p == NULL || set == NULL || coef == NULL) return QO_E_NULL;
    if (set->profile == QO_SPLINE_CUBIC_HERMITE && set->key_vel == NULL) return QO_E_NULL;
    if (n_joints == 0 || n_keys < 2) return QO_E_TOO_FEW;
    need = qo_spline_coef_len(n_joints, n_keys);
    if (need == 0 || coef_len < need) return QO_E_CAPACITY;
    st = check_inputs(n_joints, n_keys, t, p, set);
    if (st != QO_OK) return st;

    tt = coef;
    for (k = 0; k < n_keys; k++) tt[k] = t[k];
    for (j = 0; j < n_joints; j++) {
        float *jr = coef + n_keys + 3 * j;
        jr[0] = set->pos_min ? set->pos_min[j] : -INFINITY;
        jr[1] = set->pos_max ? set->pos_max[j] : INFINITY;
        jr[2] = (set->wrap != NULL && set->wrap[j]) ? set->wrap_period : 0.0f;
    }

    for (j = 0; j < n_joints; j++) {
        float period = coef[n_keys + 3 * j + 2];
        float *last = row_of(coef, n_joints, n_keys, n_keys - 1, j);
        int known_v = 1, known_a = 0;
        /* 1. unwrapped key positions (short way round for continuous joints) */
        for (k = 0; k < n_keys; k++) {
            float *r = row_of(coef, n_joints, n_keys, k, j);
            if (k == 0 || period == 0.0f) r[0] = p[k * n_joints + j];
            else r[0] = row_of(coef, n_joints, n_keys, k - 1, j)[0] +
                        wrap_half(p[k * n_joints + j] - p[(k - 1) * n_joints + j], period);
            r[1] = r[2] = r[3] = r[4] = r[5] = 0.0f;
        }
        /* 2. key derivatives, 3. segments (ascending: segment k reads row k+1 intact) */
        switch (set->profile) {
        case QO_SPLINE_LINEAR:
            known_v = 0;
            break;
        case QO_SPLINE_CUBIC_HERMITE:
            for (k = 0; k < n_keys; k++)
                row_of(coef, n_joints, n_keys, k, j)[1] = set->key_vel[k * n_joints + j];
            break;
        case QO_SPLINE_CATMULL_ROM:
            key_velocities(coef, n_joints, n_keys, j, tt, set);
            known_a = set->end == QO_SPLINE_END_NATURAL; /* slot 2 is 0: exactly natural */
            break;
        case QO_SPLINE_QUINTIC:
            known_a = 1;
            if (set->key_vel != NULL) {
                for (k = 0; k < n_keys; k++)
                    row_of(coef, n_joints, n_keys, k, j)[1] = set->key_vel[k * n_joints + j];
            } else {
                key_velocities(coef, n_joints, n_keys, j, tt, set);
            }
            if (set->key_acc != NULL) {
                for (k = 0; k < n_keys; k++)
                    row_of(coef, n_joints, n_keys, k, j)[2] = set->key_acc[k * n_joints + j];
            } else if (set->derivs == QO_SPLINE_DERIVS_ESTIMATED) {
                estimate_inner(coef, n_joints, n_keys, j, tt, 1, 2); /* ends stay 0 */
            }
            break;
        case QO_SPLINE_CUBIC_C2:
            /* the end state is exact where the end condition fixes it */
            known_v = set->end == QO_SPLINE_END_CLAMPED;
            known_a = !known_v;
            solve_c2(coef, n_joints, n_keys, j, tt, set->end == QO_SPLINE_END_NATURAL,
                     set->end_vel ? set->end_vel[j] : 0.0f,
                     set->end_vel ? set->end_vel[n_joints + j] : 0.0f);
            break;
        }
        if (set->profile == QO_SPLINE_CUBIC_C2) {
            /* the end row keeps exact end values; solve_c2 left M in slot 2 and scratch in
             * 3, 4, which the end-state step below clears */
            last[1] = set->end_vel ? set->end_vel[n_joints + j] : 0.0f;
            if (known_a) last[2] = 0.0f;
        }
        for (k = 0; k + 1 < n_keys; k++) {
            float *r0 = row_of(coef, n_joints, n_keys, k, j);
            const float *r1 = row_of(coef, n_joints, n_keys, k + 1, j);
            float h = tt[k + 1] - tt[k];
            if (set->profile == QO_SPLINE_CUBIC_C2) segment_from_moments(r0, r1, h);
            else segment_from_pva(r0, r1, h, set->profile);
        }
        /* 4. end state: exact given values where the profile has them, else the derivatives
         * of the last segment at s = 1 */
        {
            const float *b = row_of(coef, n_joints, n_keys, n_keys - 2, j);
            float h = tt[n_keys - 1] - tt[n_keys - 2];
            if (!known_v)
                last[1] = (b[1] + 2.0f * b[2] + 3.0f * b[3] + 4.0f * b[4] + 5.0f * b[5]) / h;
            if (!known_a)
                last[2] = (set->profile == QO_SPLINE_LINEAR) ? 0.0f :
                          ((2.0f * b[2] + 6.0f * b[3] + 12.0f * b[4] + 20.0f * b[5]) / h) / h;
            last[3] = last[4] = last[5] = 0.0f;
        }
    }
    if (!all_finite(coef + n_keys + 3 * n_joints, COEF_W * n_keys * n_joints) ||
        !segments_bounded(coef, n_joints, n_keys))
        return QO_E_RANGE;
    out->n_joints = n_joints;
    out->n_keys = n_keys;
    out->profile = set->profile;
    out->wrap_output = set->wrap_output != 0;
    out->coef = coef;
    return QO_OK;
}

static void zero_out(size_t n, float *pos, float *vel, float *acc, int8_t *clamped)
{
    size_t j;
    for (j = 0; j < n; j++) {
        if (pos) pos[j] = 0.0f;
        if (vel) vel[j] = 0.0f;
        if (acc) acc[j] = 0.0f;
        if (clamped) clamped[j] = 0;
    }
}

qo_status qo_spline_sample_f32(const qo_spline_f32 *s, float t, float *pos, float *vel,
                               float *acc, int8_t *clamped)
{
    size_t nj, nk, j, k;
    const float *tt;
    float sn = 0.0f, h = 1.0f;
    int mode; /* 0 hold first at rest, 1 segment k, 2 end state, 3 hold last at rest */
    qo_status st = QO_OK;
    if (s == NULL) return QO_E_NULL;
    if (pos == NULL || s->n_keys < 2 || s->coef == NULL) {
        zero_out(s->n_joints, pos, vel, acc, clamped);
        return pos == NULL ? QO_E_NULL : QO_E_STATE;
    }
    nj = s->n_joints;
    nk = s->n_keys;
    tt = s->coef;
    k = 0;
    if (isnan(t) || isinf(t)) {
        st = QO_E_NONFINITE;
        mode = 0;
    } else if (t < tt[0]) {
        mode = 0;
    } else if (t > tt[nk - 1]) {
        mode = 3;
        k = nk - 1;
    } else if (t == tt[nk - 1]) {
        mode = 2;
        k = nk - 1;
    } else {
        size_t lo = 0, hi = nk - 1; /* invariant tt[lo] <= t < tt[hi] */
        while (hi - lo > 1) {
            size_t mid = lo + (hi - lo) / 2;
            if (tt[mid] <= t) lo = mid;
            else hi = mid;
        }
        k = lo;
        mode = 1;
        h = tt[k + 1] - tt[k];
        sn = (t - tt[k]) / h;
        if (sn > 1.0f) sn = 1.0f; /* rounding only */
    }
    for (j = 0; j < nj; j++) {
        const float *b = row_of_c(s->coef, nj, nk, k, j);
        const float *jr = s->coef + nk + 3 * j;
        float x, v, a;
        int8_t c = 0;
        if (mode == 1) {
            x = b[0] + sn * (b[1] + sn * (b[2] + sn * (b[3] + sn * (b[4] + sn * b[5]))));
            v = a = 0.0f; /* derivatives only when asked for */
            if (vel)
                v = (b[1] + sn * (2.0f * b[2] + sn * (3.0f * b[3] +
                     sn * (4.0f * b[4] + sn * 5.0f * b[5])))) / h;
            if (acc)
                a = ((2.0f * b[2] + sn * (6.0f * b[3] + sn * (12.0f * b[4] +
                      sn * 20.0f * b[5]))) / h) / h;
        } else {
            x = b[0];
            v = (mode == 2) ? b[1] : 0.0f;
            a = (mode == 2) ? b[2] : 0.0f;
        }
        if (!(isfinite(x) && isfinite(v) && isfinite(a))) {
            /* last line of defence (init bounds the segments, so not expected): the key
             * the segment started from, held at rest */
            x = b[0];
            v = a = 0.0f;
            st = QO_E_RANGE;
        }
        if (jr[2] > 0.0f && s->wrap_output) x = wrap_half(x, jr[2]);
        if (x < jr[0]) { x = jr[0]; c = -1; }
        else if (x > jr[1]) { x = jr[1]; c = 1; }
        if (c) v = a = 0.0f;
        pos[j] = x;
        if (vel) vel[j] = v;
        if (acc) acc[j] = a;
        if (clamped) clamped[j] = c;
    }
    return st;
}

/* ---- conversion to the fixed-point table ---------------------------------------------- */

/* round(x * 2^16) into *q; 0 when it does not fit int32. */
static int to_q16(float x, int32_t *q)
{
    float r = roundf(x * 65536.0f);
    if (!(r >= -2147483648.0f && r < 2147483648.0f)) {
        *q = 0;
        return 0;
    }
    *q = (int32_t)r;
    return 1;
}

/* x > 0 as m * 2^-e with m in [2^23, 2^24). */
static void to_mant(float x, int32_t *m, int32_t *e)
{
    int ex;
    float f = frexpf(x, &ex); /* x = f 2^ex, f in [0.5, 1) */
    *m = (int32_t)ldexpf(f, 24); /* exact: f has 24 significant bits */
    *e = (int32_t)(24 - ex);
}

static int32_t limit_q16(float x, int32_t sat)
{
    int32_t q;
    if (to_q16(x, &q)) return q;
    return sat;
}

qo_status qo_spline_export_q16(const qo_spline_f32 *s, qo_spline_table_q16 *table, int32_t *words,
                               size_t cap)
{
    size_t nj, nk, need, j, k, n;
    int32_t *jt, *ct;
    if (table == NULL) return QO_E_NULL;
    table->n_joints = s ? s->n_joints : 0;
    table->n_keys = 0;
    table->wrap_output = 0;
    table->table = NULL;
    if (s == NULL || words == NULL) return QO_E_NULL;
    if (s->n_keys < 2 || s->coef == NULL) return QO_E_STATE;
    nj = s->n_joints;
    nk = s->n_keys;
    need = qo_spline_q16_len(nj, nk);
    if (need == 0 || cap < need) return QO_E_CAPACITY;
    jt = words + QO_SPLINE_Q16_KEY_WORDS * nk;
    ct = jt + QO_SPLINE_Q16_JOINT_WORDS * nj;
    for (k = 0; k < nk; k++) {
        int32_t *kr = words + QO_SPLINE_Q16_KEY_WORDS * k;
        if (!to_q16(s->coef[k], &kr[0])) return QO_E_OVERFLOW;
        kr[1] = kr[2] = kr[3] = kr[4] = 0;
        if (k > 0) {
            int32_t *pr = kr - QO_SPLINE_Q16_KEY_WORDS;
            int64_t hq = (int64_t)kr[0] - pr[0];
            float inv;
            if (hq <= 0) return QO_E_ORDER;
            inv = 65536.0f / (float)hq; /* seconds^-1 from the rounded times */
            to_mant(inv, &pr[1], &pr[2]);
            to_mant(inv * inv, &pr[3], &pr[4]);
        }
    }
    for (j = 0; j < nj; j++) {
        const float *jr = s->coef + nk + 3 * j;
        jt[3 * j + 0] = limit_q16(jr[0], INT32_MIN);
        jt[3 * j + 1] = limit_q16(jr[1], INT32_MAX);
        jt[3 * j + 2] = 0;
        if (jr[2] > 0.0f && (!to_q16(jr[2], &jt[3 * j + 2]) || jt[3 * j + 2] < 2))
            return QO_E_OVERFLOW;
    }
    for (k = 0; k < nk; k++) {
        for (j = 0; j < nj; j++) {
            const float *b = row_of_c(s->coef, nj, nk, k, j);
            int32_t *q = ct + QO_SPLINE_Q16_COEF_WORDS * (k * nj + j);
            int32_t f = 0;
            float mag = 0.0f, sc;
            /* Extra fractional bits for this row: the most (up to QO_SPLINE_Q16_MAX_FRAC)
             * that keep every |b_n| below 2^14 units after scaling, i.e. raw < 2^30. The
             * end-state row (physical p, v, a) keeps f = 0. */
            if (k + 1 < nk) {
                for (n = 0; n < COEF_W; n++)
                    if (fabsf(b[n]) > mag) mag = fabsf(b[n]);
                while (f < QO_SPLINE_Q16_MAX_FRAC && ldexpf(mag, (int)f + 1) < 16384.0f) f++;
            }
            sc = ldexpf(1.0f, (int)f);
            for (n = 0; n < COEF_W; n++)
                if (!to_q16(b[n] * sc, &q[n])) return QO_E_OVERFLOW;
            q[COEF_W] = f;
        }
    }
    table->n_keys = nk;
    table->wrap_output = s->wrap_output;
    table->table = words;
    return QO_OK;
}
