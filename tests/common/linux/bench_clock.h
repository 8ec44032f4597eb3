/*
 * tests/common/linux/bench_clock.h - the clocks and the sort comparison the bench programs
 * share (bench/bench_spline.c, bench/motion/compare.c). Linux (POSIX clocks).
 *
 *   bench_now_ns()   CLOCK_MONOTONIC in ns (wall time: includes time descheduled)
 *   bench_cpu_ns()   CLOCK_THREAD_CPUTIME_ID in ns (this thread's CPU time: a shared machine's
 *                    other load does not count, its cache effects still do)
 *   bench_cmp_d()    qsort comparison of doubles, ascending (for medians and percentiles)
 */
#ifndef QORIENT_TESTS_LINUX_BENCH_CLOCK_H
#define QORIENT_TESTS_LINUX_BENCH_CLOCK_H

double bench_now_ns(void);
double bench_cpu_ns(void);
int bench_cmp_d(const void *a, const void *b);

#endif
