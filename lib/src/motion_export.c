/* The current float32 plan as a Q16.16 fixed-point table for qo_motion_sample_q16. See
 * qorient/motion.h (qo_motion_export_q16) and qorient/motion_fx.h. */
#include "motion_internal.h"

#include <math.h>

/* float -> Q31.32 with saturation at +-2^31. */
static int64_t to_q32(float x, int *ovf)
{
    const float lim = 2147483648.0f;
    if (!(x < lim)) {
        *ovf = 1;
        return INT64_MAX;
    }
    if (!(x > -lim)) {
        *ovf = 1;
        return -INT64_MAX;
    }
    return (int64_t)llrintf(x * 4294967296.0f);
}

/* float seconds -> Q16.16 with saturation. */
static qo_q16 to_q16(float x, int *ovf)
{
    const float lim = 32767.0f;
    if (!(x <= lim)) {
        *ovf = 1;
        return INT32_MAX;
    }
    if (!(x >= -lim)) {
        *ovf = 1;
        return -INT32_MAX;
    }
    return (qo_q16)lrintf(x * 65536.0f);
}

qo_status qo_motion_export_q16(const qo_motion_planner_f32 *pl, qo_motion_table_q16 *table,
                               qo_motion_seg_q16 *segs, size_t cap)
{
    size_t i;
    int ovf = 0;
    if (table == NULL) return QO_E_NULL;
    table->segs = segs;
    table->n = 0;
    if (pl == NULL || segs == NULL) return QO_E_NULL;
    if (pl->n == 0 || pl->joints == NULL) return QO_E_STATE;
    if (cap < pl->n * QO_MOTION_Q16_SEGS) return QO_E_CAPACITY;
    for (i = 0; i < pl->n; i++) {
        const qo_motion_joint_f32 *jt = &pl->joints[i];
        qo_motion_seg_q16 *sg = &segs[i * QO_MOTION_Q16_SEGS];
        unsigned k;
        for (k = 0; k < jt->nph; k++) {
            const qo_motion_phase_f32 *ph = &jt->ph[k];
            qo_q16 tq = to_q16(ph->t, &ovf);
            /* Coefficients at the rounded boundary: the same polynomial, re-centred. */
            float tau = (float)tq * (1.0f / 65536.0f) - ph->t;
            float p = ph->p + tau * (ph->v + tau * (0.5f * ph->a + tau * ph->j * (1.0f / 6.0f)));
            float v = ph->v + tau * (ph->a + 0.5f * tau * ph->j);
            float a = ph->a + tau * ph->j;
            if (k == 0) tq = 0;
            sg[k].t = tq;
            sg[k].c0 = to_q32(p, &ovf);
            sg[k].c1 = to_q32(v, &ovf);
            sg[k].c2 = to_q32(0.5f * a, &ovf);
            sg[k].c3 = to_q32(ph->j * (1.0f / 6.0f), &ovf);
            if (fabsf(p) >= 32767.0f) ovf = 1;
        }
        {
            /* After the end: a target acceleration first ramps to zero (one segment), then the
             * last segment: at rest, or on at the end velocity (velocity interface, target
             * states). Coefficients at the rounded boundaries, as for the phases. */
            float te = jt->nph ? jt->duration : 0.0f, ta = 0.0f, tau;
            qo_q16 tq;
            mstate e1;
            if (jt->aend != 0.0f && k < QO_MOTION_Q16_SEGS) {
                float a = jt->aend, v = jt->vend, jr = a > 0.0f ? -jt->lim.jmax : jt->lim.jmax;
                ta = fabsf(a) / jt->lim.jmax;
                tq = to_q16(te, &ovf);
                tau = (float)tq * (1.0f / 65536.0f) - te;
                sg[k].t = tq;
                sg[k].c0 = to_q32(jt->final + tau * (v + tau * (0.5f * a + tau * jr * (1.0f / 6.0f))), &ovf);
                sg[k].c1 = to_q32(v + tau * (a + 0.5f * tau * jr), &ovf);
                sg[k].c2 = to_q32(0.5f * (a + tau * jr), &ovf);
                sg[k].c3 = to_q32(jr * (1.0f / 6.0f), &ovf);
                k++;
            }
            e1 = qo_motion_after_end(jt, ta);
            tq = to_q16(te + ta, &ovf);
            tau = (float)tq * (1.0f / 65536.0f) - (te + ta);
            e1.p += jt->final + e1.v * tau;
            for (; k < QO_MOTION_Q16_SEGS; k++) {
                sg[k].t = jt->nph || ta > 0.0f ? tq : 0;
                sg[k].c0 = to_q32(e1.p, &ovf);
                sg[k].c1 = to_q32(e1.v, &ovf); /* 0 at rest; the velocity interface's cruise */
                sg[k].c2 = sg[k].c3 = 0;
                if (fabsf(e1.p) >= 32767.0f) ovf = 1;
            }
        }
    }
    table->n = pl->n;
    return ovf ? QO_E_OVERFLOW : QO_OK;
}

