/* The max_step window of one joint. Contract: joint_guard.h. */
#include "linux/joint_guard.h"

#include <math.h>
#include <string.h>

void qo_joint_guard_init(qo_joint_guard *g, const qo_regmap_joint *j)
{
    memset(g, 0, sizeof *g);
    g->step = j->max_step * fabs(j->fmt.scale);
    (void)qo_modbus_reg_type_range(j->fmt.type, &g->tlo, &g->thi);
}

/* A value inside the window cannot be sent: hold the slave and read the joint back. */
static qo_status blocked(qo_joint_guard *g)
{
    g->cmd = g->lo;
    g->uncertain = 1;
    return QO_E_INFEASIBLE;
}

qo_status qo_joint_guard_limit(qo_joint_guard *g, const qo_regmap_joint *j, double target,
                               uint16_t *regs, unsigned *changed)
{
    double v = target, raw, packed;
    *changed = 0;
    if (v < j->min) v = j->min;
    if (v > j->max) v = j->max;
    if (v != target) *changed |= QO_JOINT_GUARD_CLAMPED;
    (void)qo_modbus_reg_raw_from_value(&j->fmt, v, &raw); /* finite: checked by the caller */
    if (raw < g->tlo || raw > g->thi) {
        raw = raw < g->tlo ? g->tlo : g->thi;
        *changed |= QO_JOINT_GUARD_SATURATED;
    }
    if (g->have && g->step > 0.0) {
        double a = g->hi - g->step, b = g->lo + g->step;
        int tries;
        /* Some value the drive may hold is more than max_step from any value: send nothing
         * rather than guess; a read-back may narrow the range next tick. */
        if (!(a <= b)) return blocked(g);
        if (raw < a || raw > b) {
            raw = raw < a ? a : b;
            *changed |= QO_JOINT_GUARD_RATE_LIMITED;
        }
        (void)qo_modbus_reg_pack_raw(j->fmt.type, j->fmt.order, raw, regs, &packed);
        /* Rounding to the register's resolution must not push the step past max_step. */
        for (tries = 0; tries < 4 && (packed > b || packed < a); tries++) {
            if (j->fmt.type == QO_MODBUS_REG_FLOAT32)
                raw = (double)nextafterf((float)packed, packed > b ? -INFINITY : INFINITY);
            else
                raw = packed > b ? floor(b) : ceil(a);
            (void)qo_modbus_reg_pack_raw(j->fmt.type, j->fmt.order, raw, regs, &packed);
        }
        if (packed > b || packed < a) return blocked(g);
    } else {
        (void)qo_modbus_reg_pack_raw(j->fmt.type, j->fmt.order, raw, regs, &packed);
    }
    g->cmd = packed;
    return QO_OK;
}

double qo_joint_guard_goal(const qo_joint_guard *g, const qo_regmap_joint *j, double target)
{
    uint16_t regs[2];
    double v = target, raw, packed;
    if (v < j->min) v = j->min;
    if (v > j->max) v = j->max;
    (void)qo_modbus_reg_raw_from_value(&j->fmt, v, &raw);
    if (raw < g->tlo) raw = g->tlo;
    if (raw > g->thi) raw = g->thi;
    (void)qo_modbus_reg_pack_raw(j->fmt.type, j->fmt.order, raw, regs, &packed);
    return packed;
}

int qo_joint_guard_holds(const qo_joint_guard *g, double goal)
{
    return g->have && !g->uncertain && !g->pend && g->lo == goal && g->hi == goal;
}

void qo_joint_guard_known(qo_joint_guard *g, double raw)
{
    g->have = 1;
    g->lo = g->hi = raw;
    g->uncertain = 0;
}

void qo_joint_guard_sent(qo_joint_guard *g)
{
    g->pend = 1;
    g->pcmd = g->cmd;
    g->plo = g->lo;
    g->phi = g->hi;
}

void qo_joint_guard_answered(qo_joint_guard *g, int applied)
{
    if (!g->pend) return;
    if (applied) {
        g->have = 1;
        g->lo = g->hi = g->pcmd;
    } else {
        g->lo = g->plo;
        g->hi = g->phi;
    }
    g->pend = 0;
}

void qo_joint_guard_unknown(qo_joint_guard *g)
{
    if (!g->have) return;
    if (g->cmd < g->lo) g->lo = g->cmd;
    if (g->cmd > g->hi) g->hi = g->cmd;
}
