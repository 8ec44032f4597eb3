/*
 * fuzz/fuzz_spline.c - keyframe trajectories (qorient/spline.h, spline_fx.h): 1..4 joints,
 * 0..8 keys, every profile / end / derivs value (and one past the end of each enum), optional
 * key velocities, accelerations, end velocities, position limits and wrapped joints with a
 * fuzzed period, coef storage exactly the size asked for (or one short), then samples at the
 * key times and at fuzzed times, and the Q16.16 table and its sampler.
 * Properties from the headers: documented statuses; a failed init leaves n_keys == 0 and
 * sampling it gives QO_E_STATE; on QO_OK every sampled position, velocity and acceleration is
 * finite, clamped[] is -1/0/+1 and the position lies within the limits; an unwrapped,
 * unclamped joint at a key time is at that key; the fixed table converts with a documented
 * status and samples with QO_OK or QO_E_OVERFLOW.
 */
#include "fuzz_common.h"
#include "qorient/spline.h"
#include "qorient/fxconv.h"
#include "qorient/spline_fx.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

#define FUZZ_SP_MAXN 4
#define FUZZ_SP_MAXK 8

static void fuzz_spline_check_sample(const qo_spline_f32 *sp, const qo_spline_settings_f32 *set, float t,
                                     const float *p, int at_key)
{
    float pos[FUZZ_SP_MAXN], vel[FUZZ_SP_MAXN], acc[FUZZ_SP_MAXN];
    int8_t cl[FUZZ_SP_MAXN];
    size_t j, n = sp->n_joints;
    qo_status st = qo_spline_sample_f32(sp, t, pos, vel, acc, cl);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NONFINITE, "spline_sample status %d", (int)st);
    QO_FUZZ_CHECK((st == QO_E_NONFINITE) == !isfinite(t), "spline_sample t %g status %d", (double)t, (int)st);
    for (j = 0; j < n; j++) {
        QO_FUZZ_CHECK(isfinite(pos[j]) && isfinite(vel[j]) && isfinite(acc[j]),
                      "spline profile %d joint %zu at t %.9g: pos %g vel %g acc %g", (int)sp->profile, j, (double)t,
                      (double)pos[j], (double)vel[j], (double)acc[j]);
        QO_FUZZ_CHECK(cl[j] >= -1 && cl[j] <= 1, "clamped %d", (int)cl[j]);
        if (set->pos_min != NULL)
            QO_FUZZ_CHECK(pos[j] >= set->pos_min[j] && pos[j] <= set->pos_max[j], "joint %zu pos %g outside [%g, %g]",
                          j, (double)pos[j], (double)set->pos_min[j], (double)set->pos_max[j]);
        if (at_key && cl[j] == 0 && (set->wrap == NULL || !set->wrap[j]))
            QO_FUZZ_CHECK(pos[j] == p[j], "profile %d joint %zu at key time %.9g: pos %.9g, key %.9g", (int)sp->profile,
                          j, (double)t, (double)pos[j], (double)p[j]);
    }
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    uint8_t h0 = qo_fz_u8(&f), h1 = qo_fz_u8(&f);
    size_t n = 1u + (h0 & 3u), k = (size_t)((h0 >> 2) % (FUZZ_SP_MAXK + 1u)), i, len, tl;
    float t[FUZZ_SP_MAXK], p[FUZZ_SP_MAXK * FUZZ_SP_MAXN], kv[FUZZ_SP_MAXK * FUZZ_SP_MAXN];
    float ka[FUZZ_SP_MAXK * FUZZ_SP_MAXN], ev[2 * FUZZ_SP_MAXN], lo[FUZZ_SP_MAXN], hi[FUZZ_SP_MAXN];
    unsigned char wr[FUZZ_SP_MAXN];
    qo_spline_settings_f32 set = qo_spline_settings_default;
    qo_spline_f32 sp;
    qo_spline_table_q16 fx;
    float *coef;
    int32_t *table;
    qo_status st;

    set.profile = (qo_spline_profile)(h1 % 6u);
    set.end = (qo_spline_end)((h1 >> 3) % 3u);
    set.derivs = (qo_spline_derivs)((h1 >> 5) % 3u);
    for (i = 0; i < k; i++) {
        float d = qo_fz_f32(&f);
        t[i] = i == 0 ? d : t[i - 1] + d;
    }
    for (i = 0; i < k * n; i++) p[i] = qo_fz_f32(&f);
    if (h0 & 0x40u) { for (i = 0; i < k * n; i++) kv[i] = qo_fz_f32(&f); set.key_vel = kv; }
    if (h0 & 0x80u) { for (i = 0; i < k * n; i++) ka[i] = qo_fz_f32(&f); set.key_acc = ka; }
    if (h1 & 0x80u) { for (i = 0; i < 2 * n; i++) ev[i] = qo_fz_f32(&f); set.end_vel = ev; }
    if (h1 & 0x04u) {
        for (i = 0; i < n; i++) { lo[i] = qo_fz_f32(&f); hi[i] = qo_fz_f32(&f); }
        set.pos_min = lo;
        set.pos_max = hi;
    }
    if (h1 & 0x02u) {
        uint8_t w = qo_fz_u8(&f);
        for (i = 0; i < n; i++) wr[i] = (unsigned char)((w >> i) & 1u);
        set.wrap = wr;
        set.wrap_period = (w & 0x10u) ? qo_fz_f32(&f) : 6.28318548f;
        set.wrap_output = (w & 0x20u) != 0;
    }

    len = qo_spline_coef_len(n, k);
    if (len > 0 && (h1 & 1u) && (h0 & 0x20u)) len--;   /* one short: QO_E_CAPACITY */
    coef = malloc((len ? len : 1) * sizeof *coef);
    if (coef == NULL) abort();
    st = qo_spline_init_f32(n, k, t, p, &set, coef, len, &sp);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_NULL || st == QO_E_TOO_FEW || st == QO_E_CAPACITY || st == QO_E_ARG
                  || st == QO_E_NONFINITE || st == QO_E_ORDER || st == QO_E_RANGE || st == QO_E_LIMIT,
                  "spline_init status %d", (int)st);
    if (st != QO_OK) {
        float pos[FUZZ_SP_MAXN];
        QO_FUZZ_CHECK(sp.n_keys == 0 && sp.coef == NULL, "spline_init error %d left a plan", (int)st);
        QO_FUZZ_CHECK(qo_spline_sample_f32(&sp, 0.0f, pos, NULL, NULL, NULL) == QO_E_STATE, "sample of a failed plan");
        free(coef);
        return 0;
    }
    QO_FUZZ_CHECK(set.profile <= QO_SPLINE_QUINTIC && k >= 2, "spline_init accepted profile %d k %zu", (int)set.profile, k);
    for (i = 0; i < k; i++) fuzz_spline_check_sample(&sp, &set, t[i], p + i * n, 1);
    while (f.n > 0 && f.n % 7u != 0u) fuzz_spline_check_sample(&sp, &set, qo_fz_f32(&f), p, 0);
    fuzz_spline_check_sample(&sp, &set, qo_fz_f32(&f), p, 0);

    /* the fixed-point table */
    tl = qo_spline_q16_len(n, k);
    table = malloc((tl ? tl : 1) * sizeof *table);
    if (table == NULL) abort();
    st = qo_spline_export_q16(&sp, &fx, table, tl);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_OVERFLOW || st == QO_E_ORDER, "spline_export_q16 status %d", (int)st);
    if (st == QO_OK) {
        qo_q16 pos[FUZZ_SP_MAXN], vel[FUZZ_SP_MAXN], acc[FUZZ_SP_MAXN];
        int8_t cl[FUZZ_SP_MAXN];
        int r;
        for (r = 0; r < 8; r++) {
            qo_q16 tq = r < (int)k ? qo_q16_from_f32(t[r]) : qo_fz_i32(&f);
            st = qo_spline_sample_q16(&fx, tq, pos, vel, acc, cl);
            QO_FUZZ_CHECK(st == QO_OK || st == QO_E_OVERFLOW, "spline_sample_q16 status %d", (int)st);
            for (i = 0; i < n; i++) QO_FUZZ_CHECK(cl[i] >= -1 && cl[i] <= 1, "q16 clamped %d", (int)cl[i]);
        }
    } else {
        QO_FUZZ_CHECK(fx.n_keys == 0, "spline_export_q16 error left a table");
    }
    free(table);
    free(coef);
    return 0;
}
