/*
 * tests/common/linux/sim_log.h - the check the port tests run on the simulated drive bank's
 * CSV log (qo_sim_settings.log: a header line, then "t_s,request,slave,joint_index,joint,value"
 * per joint value received): no joint ever steps by more than its map's max_step.
 *
 * sim_log_steps(log, m, what, last, &r) reads the whole log from the start. Each header line
 * starts a simulator instance (a restarted drive: every joint back at 0); every data line must
 * parse, name a joint of m by index and name, and come after a header (else fail_msg, naming
 * `what` and the line). A step above max_step (beyond 1e-9 relative) is counted in r.over and
 * printed with its joint, values, time and request; the caller asserts r.over == 0 (after
 * printing its own totals, if it wants). last[0..m->n_joints-1] gets the last value of each
 * joint; r.worst is the largest step / max_step ratio seen.
 */
#ifndef QORIENT_TESTS_LINUX_SIM_LOG_H
#define QORIENT_TESTS_LINUX_SIM_LOG_H

#include <stdio.h>

#include "linux/regmap.h"

typedef struct sim_log_result {
    unsigned lines;     /* data lines */
    unsigned instances; /* header lines */
    unsigned over;      /* steps above max_step */
    double worst;       /* largest step / max_step */
} sim_log_result;

void sim_log_steps(FILE *log, const qo_regmap *m, const char *what, double *last,
                   sim_log_result *r);

#endif
