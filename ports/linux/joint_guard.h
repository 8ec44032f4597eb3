/*
 * ports/linux/joint_guard.h - the joint guard of the Modbus sink: clamp, type range and the
 * max_step window, in register units, so a drive NEVER receives a change bigger than
 * max_step from any value it may hold. Pure (no I/O).
 *
 * Index:
 *   qo_joint_guard               what the sink knows of one joint's drive
 *   qo_joint_guard_init()        from the map's joint (nothing known yet)
 *   qo_joint_guard_limit()       the value to send this tick (packed into the registers)
 *   qo_joint_guard_goal()        the value a final target must read back as
 *   qo_joint_guard_holds()       the drive is known to hold exactly that value
 *   qo_joint_guard_known()       the drive holds this (acknowledged write, read-back, seed)
 *   qo_joint_guard_sent()        a write of the last limited value went out (TCP: outstanding)
 *   qo_joint_guard_answered()    its reply: applied, or refused (exception)
 *   qo_joint_guard_unknown()     its outcome is unknown: the drive may hold old or new
 *
 * The guard remembers the range [lo, hi] of raw values the drive may hold: one value after
 * a confirmed write or a read-back, both the old and the new value after a write whose
 * outcome is unknown. A new value is always within max_step of every value in that range
 * (the window [hi - max_step, lo + max_step]); when the window is empty or rounding cannot
 * land in it, nothing may be sent (QO_E_INFEASIBLE; the joint is marked uncertain so the
 * sink reads it back).
 */
#ifndef QORIENT_JOINT_GUARD_H
#define QORIENT_JOINT_GUARD_H

#include <stdint.h>

#include "linux/regmap.h"
#include "qorient/status.h"

typedef struct qo_joint_guard {
    int have;          /* lo/hi known */
    double lo, hi;     /* raw values the drive may hold */
    double cmd;        /* raw value packed by the last qo_joint_guard_limit */
    double step;       /* max_step in raw units, 0 = unlimited */
    double tlo, thi;   /* the register type's range */
    int uncertain;     /* lo/hi may be stale: read the target back before the next write */
    int pend;          /* a write carrying pcmd is outstanding (TCP) */
    double pcmd;       /* ... the value it carries */
    double plo, phi;   /* ... and the range before it (restored on an exception reply) */
} qo_joint_guard;

/* What qo_joint_guard_limit changed (bits). */
#define QO_JOINT_GUARD_CLAMPED 1u      /* min/max of the map */
#define QO_JOINT_GUARD_SATURATED 2u    /* the register type's range */
#define QO_JOINT_GUARD_RATE_LIMITED 4u /* max_step */

/* Nothing known; step and type range from the joint `j`. */
void qo_joint_guard_init(qo_joint_guard *g, const qo_regmap_joint *j);

/* Limits the finite `target` (joint units) and packs it into regs (the joint's 1 or 2
 * registers); g->cmd is the raw value packed. *changed gets the QO_JOINT_GUARD_* bits. Returns
 * QO_OK, or QO_E_INFEASIBLE (nothing may be sent to this joint's slave; regs unspecified,
 * g->uncertain set). */
qo_status qo_joint_guard_limit(qo_joint_guard *g, const qo_regmap_joint *j, double target,
                               uint16_t *regs, unsigned *changed);

/* The raw value a drive must hold for `target`: clamped, saturated, rounded by packing (the
 * rate limit does not apply to a goal). */
double qo_joint_guard_goal(const qo_joint_guard *g, const qo_regmap_joint *j, double target);

/* 1 when the drive is known to hold exactly `goal` (nothing outstanding or uncertain). */
int qo_joint_guard_holds(const qo_joint_guard *g, double goal);

/* The drive holds `raw`. */
void qo_joint_guard_known(qo_joint_guard *g, double raw);

/* A write of g->cmd was sent and is outstanding until qo_joint_guard_answered (TCP). */
void qo_joint_guard_sent(qo_joint_guard *g);

/* The outstanding write's reply: applied (the drive holds it) or refused (as before). */
void qo_joint_guard_answered(qo_joint_guard *g, int applied);

/* A write of g->cmd had an unknown outcome: the range takes both values. */
void qo_joint_guard_unknown(qo_joint_guard *g);

#endif /* QORIENT_JOINT_GUARD_H */
