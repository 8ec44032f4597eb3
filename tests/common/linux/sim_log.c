/* The max_step check on the simulator's log. See sim_log.h. */
#include "common/linux/sim_log.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

void sim_log_steps(FILE *log, const qo_regmap *m, const char *what, double *last,
                   sim_log_result *r)
{
    char line[256];
    size_t i;
    memset(r, 0, sizeof *r);
    for (i = 0; i < m->n_joints; i++) last[i] = 0.0;
    fflush(log);
    rewind(log);
    while (fgets(line, sizeof line, log) != NULL) {
        double t, v, ratio;
        unsigned long long req;
        unsigned slave;
        size_t ji;
        char name[64];
        if (strcmp(line, "t_s,request,slave,joint_index,joint,value\n") == 0) {
            for (i = 0; i < m->n_joints; i++) last[i] = 0.0;
            r->instances++;
            continue;
        }
        if (r->instances == 0) fail_msg("%s: log line before the header: %s", what, line);
        if (sscanf(line, "%lf,%llu,%u,%zu,%63[^,],%lf", &t, &req, &slave, &ji, name, &v) != 6)
            fail_msg("%s: log line not parsed: %s", what, line);
        if (ji >= m->n_joints || strcmp(name, m->joints[ji].name) != 0)
            fail_msg("%s: log line with a wrong joint: %s", what, line);
        ratio = fabs(v - last[ji]) / m->joints[ji].max_step;
        if (ratio > 1.0 + 1e-9) {
            r->over++;
            print_error("%s: joint %s: step %.9g -> %.9g exceeds max_step %.9g (t %.4f s, "
                        "request %llu)\n", what, name, last[ji], v, m->joints[ji].max_step, t,
                        req);
        }
        if (ratio > r->worst) r->worst = ratio;
        last[ji] = v;
        r->lines++;
    }
}
