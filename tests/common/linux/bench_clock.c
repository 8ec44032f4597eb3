/* Clocks and a sort comparison for the bench programs. See bench_clock.h. */
#include "common/linux/bench_clock.h"

#include <time.h>

static double clock_ns(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

double bench_now_ns(void) { return clock_ns(CLOCK_MONOTONIC); }

double bench_cpu_ns(void) { return clock_ns(CLOCK_THREAD_CPUTIME_ID); }

int bench_cmp_d(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}
