/* Fixed-point per-tick sampling of a motion plan (integer only). See qorient/motion_fx.h. */
#include "qorient/motion_fx.h"

#include "fx_internal.h"

/* round(a * b / 2^16): a in Q31.32, b in Q16.16, result Q31.32, int64 only (a split in 32-bit
 * halves so that no partial product exceeds 63 bits). */
static int64_t mul_q16(int64_t a, int32_t b, int *ovf)
{
    uint64_t ua = (uint64_t)a;
    int64_t lo = (int64_t)(ua & 0xffffffffu);
    uint32_t hu = (uint32_t)(ua >> 32);
    int64_t hi = hu >= 0x80000000u ? (int64_t)hu - (int64_t)4294967296 : (int64_t)hu;
    int64_t ph = hi * (int64_t)b;              /* |.| <= 2^62 */
    int64_t pl = qo_fx_rshift_floor(lo * (int64_t)b + 32768, 16); /* |lo * b| < 2^63 */
    if (ph >= ((int64_t)1 << 46) || ph <= -((int64_t)1 << 46)) {
        *ovf = 1;
        return ph > 0 ? INT64_MAX : -INT64_MAX;
    }
    return ph * 65536 + pl;
}

/* c[0] tau^(n-1) + ... + c[n-1] by Horner's rule in Q31.32, saturating; one call site of
 * mul_q16 keeps the sampler small on Cortex-M0 (gcc inlines a helper called once). */
static int64_t horner_q16(const int64_t *c, unsigned n, int32_t tau, int *ovf)
{
    int64_t r = c[0];
    unsigned j;
    for (j = 1; j < n; j++) r = qo_fx_add_sat_sym_i64(mul_q16(r, tau, ovf), c[j], ovf);
    return r;
}

/* Q31.32 -> Q16.16, rounded, saturated. */
static qo_q16 out_q16(int64_t r, int *ovf)
{
    int64_t q;
    if (r >= INT64_MAX - 32768) {
        *ovf = 1;
        return INT32_MAX;
    }
    q = qo_fx_rshift_floor(r + 32768, 16);
    if (q > INT32_MAX) {
        *ovf = 1;
        return INT32_MAX;
    }
    if (q < INT32_MIN) {
        *ovf = 1;
        return INT32_MIN;
    }
    return (qo_q16)q;
}

qo_status qo_motion_sample_q16(const qo_motion_table_q16 *table, qo_q16 t, qo_q16 *pos, qo_q16 *vel,
                               qo_q16 *acc)
{
    size_t i;
    int ovf = 0;
    qo_status st = QO_OK;
    if (table == NULL || pos == NULL) return QO_E_NULL;
    if (table->n == 0) return QO_E_STATE;
    if (table->segs == NULL) {
        for (i = 0; i < table->n; i++) {
            pos[i] = 0;
            if (vel) vel[i] = 0;
            if (acc) acc[i] = 0;
        }
        return QO_E_NULL;
    }
    if (t < 0) {
        t = 0;
        st = QO_E_RANGE;
    }
    for (i = 0; i < table->n; i++) {
        const qo_motion_seg_q16 *sg = &table->segs[i * QO_MOTION_Q16_SEGS];
        unsigned k = QO_MOTION_Q16_SEGS - 1;
        int32_t tau;
        int64_t c[4];
        while (k > 0 && sg[k].t > t) k--;
        sg += k;
        tau = t - sg->t;
        c[0] = sg->c3;
        c[1] = sg->c2;
        c[2] = sg->c1;
        c[3] = sg->c0;
        pos[i] = out_q16(horner_q16(c, 4, tau, &ovf), &ovf);
        c[1] = qo_fx_mul_sat_sym_i64(sg->c2, 2, &ovf);
        if (vel) {
            c[0] = qo_fx_mul_sat_sym_i64(sg->c3, 3, &ovf);
            c[2] = sg->c1;
            vel[i] = out_q16(horner_q16(c, 3, tau, &ovf), &ovf);
        }
        if (acc) {
            c[0] = qo_fx_mul_sat_sym_i64(sg->c3, 6, &ovf);
            acc[i] = out_q16(horner_q16(c, 2, tau, &ovf), &ovf);
        }
    }
    if (ovf) return QO_E_OVERFLOW;
    return st;
}
