/*
 * ports/linux/mono_clock.h - the real clock of the Linux ports: CLOCK_MONOTONIC in
 * nanoseconds and an absolute sleep on it, in the (ctx, ...) shape the streamer's and the
 * GPIO sink's clock hooks take (ctx is ignored). The streamer and the GPIO sink default to it.
 *
 * Index:
 *   qo_mono_clock_now_ns()          CLOCK_MONOTONIC now, ns
 *   qo_mono_clock_sleep_until_ns()  clock_nanosleep(TIMER_ABSTIME) until abs_ns; 0 or an errno
 *                                   value (EINTR included: the callers retry)
 */
#ifndef QORIENT_MONO_CLOCK_H
#define QORIENT_MONO_CLOCK_H

#include <stdint.h>

uint64_t qo_mono_clock_now_ns(void *ctx);
int qo_mono_clock_sleep_until_ns(void *ctx, uint64_t abs_ns);

#endif
