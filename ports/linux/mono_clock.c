/* The Linux ports' real clock. See mono_clock.h. */
#include "linux/mono_clock.h"

#include <time.h>

uint64_t qo_mono_clock_now_ns(void *ctx)
{
    struct timespec ts;
    (void)ctx;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

int qo_mono_clock_sleep_until_ns(void *ctx, uint64_t abs_ns)
{
    struct timespec ts;
    (void)ctx;
    ts.tv_sec = (time_t)(abs_ns / 1000000000u);
    ts.tv_nsec = (long)(abs_ns % 1000000000u);
    return clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL);
}
