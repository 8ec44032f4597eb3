/* Keyframe trajectories, fixed-point sampler (integers only). See qorient/spline_fx.h for the
 * table layout, the formats and the error bound. */
#include "qorient/spline_fx.h"

#include "fx_internal.h"

/* Normalised segment time s in Q5.27: with int32 coefficients (|b| < 2^31; the conversion
 * keeps them below 2^30, or 2^31 for f = 0) the Horner sums
 * stay below 20 * 2^31 < 2^35.4, and 2^35.4 * 2^27 < 2^63, so no product can overflow int64. */
#define S_FRAC 27
#define S_ONE ((int64_t)1 << S_FRAC)

size_t qo_spline_q16_len(size_t n_joints, size_t n_keys)
{
    size_t per_key;
    if (n_joints == 0 || n_keys < 2) return 0;
    if (n_joints > (SIZE_MAX - QO_SPLINE_Q16_KEY_WORDS) / QO_SPLINE_Q16_COEF_WORDS) return 0;
    per_key = QO_SPLINE_Q16_KEY_WORDS + QO_SPLINE_Q16_COEF_WORDS * n_joints;
    if (n_keys > SIZE_MAX / per_key) return 0;
    if (n_joints > SIZE_MAX / QO_SPLINE_Q16_JOINT_WORDS ||
        n_keys * per_key > SIZE_MAX - QO_SPLINE_Q16_JOINT_WORDS * n_joints)
        return 0;
    return n_keys * per_key + QO_SPLINE_Q16_JOINT_WORDS * n_joints;
}

/* x * m * 2^-e, rounded; |x| < 2^37, 0 < m < 2^24 so the product fits. For e < 0 the result
 * is scaled up with a bound check: *big is set when it would exceed `lim`. */
static int64_t scale(int64_t x, int32_t m, int32_t e, int64_t lim, int *big)
{
    int64_t p = x * (int64_t)m;
    if (e >= 0) return qo_fx_rshift_round_away_clamped(p, e);
    if (p > (lim >> -e) || p < -(lim >> -e)) {
        *big = 1;
        return p < 0 ? -lim : lim;
    }
    return p * ((int64_t)1 << -e);
}

/* sum over n = lo..5 of w[n] b[n] s^(n-lo), by Horner with a rounding after each product
 * (s in Q5.27). A loop rather than three unrolled chains: it keeps the int64 register
 * pressure, and so the stack of an interrupt on a 32-bit core, small. */
static int64_t horner(const int32_t *b, const int8_t *w, int lo, int64_t s)
{
    int n;
    int64_t acc = (int64_t)w[5] * b[5];
    for (n = 4; n >= lo; n--) acc = (int64_t)w[n] * b[n] + qo_fx_rshift_round_away_clamped(acc * s, S_FRAC);
    return acc;
}

/* Horner weights: p(s); p'(s) = sum n b_n s^(n-1); p''(s)/2 = sum n(n-1)/2 b_n s^(n-2). */
static const int8_t w_pos[6] = { 1, 1, 1, 1, 1, 1 };
static const int8_t w_vel[6] = { 0, 1, 2, 3, 4, 5 };
static const int8_t w_acc[6] = { 0, 0, 1, 3, 6, 10 };

/* x wrapped into (-P/2, P/2], P >= 2. */
static int64_t wrap_half(int64_t x, int64_t period)
{
    int64_t r = x % period; /* C99: truncates toward zero, sign of x */
    if (2 * r > period) r -= period;
    else if (2 * r <= -period) r += period;
    return r;
}

static void zero_out(size_t n, qo_q16 *pos, qo_q16 *vel, qo_q16 *acc, int8_t *clamped)
{
    size_t j;
    for (j = 0; j < n; j++) {
        if (pos) pos[j] = 0;
        if (vel) vel[j] = 0;
        if (acc) acc[j] = 0;
        if (clamped) clamped[j] = 0;
    }
}

qo_status qo_spline_sample_q16(const qo_spline_table_q16 *s, qo_q16 t, qo_q16 *pos, qo_q16 *vel,
                               qo_q16 *acc, int8_t *clamped)
{
    size_t nj, nk, j, k = 0;
    const int32_t *kt, *jt, *ct;
    int mode; /* 0 hold first at rest, 1 segment k, 2 end state, 3 hold last at rest */
    int64_t sn = 0;
    int ovf = 0;
    if (s == NULL) return QO_E_NULL;
    if (pos == NULL || s->table == NULL || s->n_keys < 2) {
        zero_out(s->n_joints, pos, vel, acc, clamped);
        return (pos == NULL || s->table == NULL) ? QO_E_NULL : QO_E_STATE;
    }
    nj = s->n_joints;
    nk = s->n_keys;
    kt = s->table;
    jt = kt + QO_SPLINE_Q16_KEY_WORDS * nk;
    ct = jt + QO_SPLINE_Q16_JOINT_WORDS * nj;
    if (t < kt[0]) {
        mode = 0;
    } else if (t > kt[QO_SPLINE_Q16_KEY_WORDS * (nk - 1)]) {
        mode = 3;
        k = nk - 1;
    } else if (t == kt[QO_SPLINE_Q16_KEY_WORDS * (nk - 1)]) {
        mode = 2;
        k = nk - 1;
    } else {
        size_t lo = 0, hi = nk - 1; /* invariant t_lo <= t < t_hi */
        const int32_t *kr;
        int big = 0;
        while (hi - lo > 1) {
            size_t mid = lo + (hi - lo) / 2;
            if (kt[QO_SPLINE_Q16_KEY_WORDS * mid] <= t) lo = mid;
            else hi = mid;
        }
        k = lo;
        mode = 1;
        kr = kt + QO_SPLINE_Q16_KEY_WORDS * k;
        /* s = u / h in Q5.27 = u(Q16.16) * m1 * 2^-e1 * 2^(27-16) */
        sn = scale((int64_t)t - kr[0], kr[1], kr[2] - (S_FRAC - 16), S_ONE, &big);
        if (sn > S_ONE) sn = S_ONE;
        if (sn < 0) sn = 0;
    }
    for (j = 0; j < nj; j++) {
        const int32_t *b = ct + QO_SPLINE_Q16_COEF_WORDS * (k * nj + j);
        const int32_t *jr = jt + QO_SPLINE_Q16_JOINT_WORDS * j;
        int64_t x, v, a;
        int8_t c = 0;
        if (mode == 1) {
            const int32_t *kr = kt + QO_SPLINE_Q16_KEY_WORDS * k;
            int32_t f = b[6]; /* extra fractional bits of this row, [0, 14] */
            int64_t dv, dh;
            int big = 0;
            /* keeps the shifts defined; tables not made by qo_spline_export_q16() are not
             * supported */
            if (f < 0 || f > QO_SPLINE_Q16_MAX_FRAC) f = 0;
            x = qo_fx_rshift_round_away_clamped(horner(b, w_pos, 0, sn), f);
            v = a = 0; /* derivatives only when asked for: position-only ticks are cheaper */
            if (vel) {
                dv = horner(b, w_vel, 1, sn);
                v = scale(dv, kr[1], kr[2] + f, (int64_t)INT32_MAX + 1, &big);
            }
            if (acc) {
                /* p'' / h^2 = 2 (p''/2) m2 2^-e2 = (p''/2) m2 2^-(e2 - 1) */
                dh = horner(b, w_acc, 2, sn);
                a = scale(dh, kr[3], kr[4] - 1 + f, (int64_t)INT32_MAX + 1, &big);
            }
            if (big) ovf = 1;
        } else {
            /* the first row (hold before the start) carries its f; the end row has f = 0 */
            int32_t f = b[6];
            if (f < 0 || f > QO_SPLINE_Q16_MAX_FRAC) f = 0;
            x = qo_fx_rshift_round_away_clamped(b[0], f);
            v = (mode == 2) ? b[1] : 0;
            a = (mode == 2) ? b[2] : 0;
        }
        if (jr[2] > 0 && s->wrap_output) x = wrap_half(x, jr[2]);
        if (x < jr[0]) { x = jr[0]; c = -1; }
        else if (x > jr[1]) { x = jr[1]; c = 1; }
        if (c) v = a = 0;
        pos[j] = qo_fx_sat_i32_flag(x, &ovf);
        if (vel) vel[j] = qo_fx_sat_i32_flag(v, &ovf);
        if (acc) acc[j] = qo_fx_sat_i32_flag(a, &ovf);
        if (clamped) clamped[j] = c;
    }
    return ovf ? QO_E_OVERFLOW : QO_OK;
}
