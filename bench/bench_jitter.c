/*
 * bench_jitter - wake-up jitter of the streamer at 500 Hz, with and without SCHED_FIFO, and
 * the CPU cost of one tick (sample + hand-off to a null sink) for 6 and 18 joints.
 *
 *   build/bench/bench_jitter [seconds]     (default 5 s per run; run as root for SCHED_FIFO)
 *
 * Jitter = wake latency: actual wake time minus the absolute deadline (CLOCK_MONOTONIC), in
 * the streamer's histogram (1 us bins below 1.024 ms, 64 us above; max exact).
 * The tick cost runs qo_streamer_tick on a clock that never sleeps, so it measures only the
 * work of a tick; the sampler is a stand-in (a quintic per joint, the shape of a trajectory
 * segment evaluation), since the trajectory modules are separate.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>

#include "linux/streamer.h"

static qo_status sample_quintic(void *ctx, double t, float *out, size_t n)
{
    size_t j;
    (void)ctx;
    for (j = 0; j < n; j++) {
        /* s(u) = 10u^3 - 15u^4 + 6u^5 over a 2 s segment, per-joint amplitude */
        double u = fmod(t, 2.0) * 0.5;
        double s = u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
        out[j] = (float)(0.1 * (double)(j + 1) * s);
    }
    return QO_OK;
}

static volatile float g_sink_sum;
static qo_status null_write(void *ctx, const float *targets, size_t n, uint64_t tick)
{
    (void)ctx;
    (void)tick;
    g_sink_sum = targets[n - 1]; /* a store the compiler cannot drop */
    return QO_OK;
}

static double mono_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static int run_stream(const char *label, int prio, int lock, double seconds)
{
    static qo_streamer s;
    qo_streamer_config c;
    qo_streamer_stats st;
    const char *warn;
    unsigned flags;
    struct timespec d;
    double t0;
    c = qo_streamer_config_default;
    c.rate_hz = 500.0;
    c.n_joints = 6;
    c.sample = sample_quintic;
    c.sink.write = null_write;
    c.rt_priority = prio;
    c.lock_memory = lock;
    if (qo_streamer_init(&s, &c) != QO_OK || qo_streamer_start(&s) != QO_OK) {
        fprintf(stderr, "bench_jitter: cannot start the streamer\n");
        return 1;
    }
    t0 = mono_s();
    d.tv_sec = (time_t)seconds;
    d.tv_nsec = (long)((seconds - (double)d.tv_sec) * 1e9);
    while (nanosleep(&d, &d) != 0) { }
    qo_streamer_request_stop(&s);
    (void)qo_streamer_join(&s);
    qo_streamer_stats_read(&s, &st);
    flags = qo_streamer_rt_report(&s, &warn);
    printf("%-18s %6.2f s  ticks %6llu  overruns %4llu  latency p50 %5.1f us  p99 %7.1f us  "
           "max %8.1f us  max |period err| %8.1f us  [%s%s%s]\n",
           label, mono_s() - t0, (unsigned long long)st.ticks, (unsigned long long)st.overruns,
           (double)st.lat_p50_ns / 1e3, (double)st.lat_p99_ns / 1e3, (double)st.lat_max_ns / 1e3,
           (double)st.period_err_max_ns / 1e3, (flags & QO_STREAMER_RT_FIFO) ? "FIFO " : "",
           (flags & QO_STREAMER_RT_MLOCK) ? "mlock " : "", warn);
    return 0;
}

/* A clock that never waits: each sleep jumps to the deadline. */
static uint64_t g_fake_now;
static uint64_t fake_now(void *ctx) { (void)ctx; return g_fake_now; }
static int fake_sleep(void *ctx, uint64_t t) { (void)ctx; if (g_fake_now < t) g_fake_now = t; return 0; }

static double thread_cpu_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void tick_cost(size_t joints)
{
    static qo_streamer s;
    qo_streamer_config c;
    const long N = 200000;
    double best = 1e9;
    int rep;
    c = qo_streamer_config_default;
    c.rate_hz = 500.0;
    c.n_joints = joints;
    c.sample = sample_quintic;
    c.sink.write = null_write;
    c.now = fake_now;
    c.sleep_until = fake_sleep;
    for (rep = 0; rep < 5; rep++) {
        long i;
        double t0, t1;
        g_fake_now = 1000000000u;
        if (qo_streamer_init(&s, &c) != QO_OK) { fprintf(stderr, "init failed\n"); exit(1); }
        t0 = thread_cpu_s();
        for (i = 0; i < N; i++) (void)qo_streamer_tick(&s);
        t1 = thread_cpu_s();
        if ((t1 - t0) / (double)N < best) best = (t1 - t0) / (double)N;
    }
    printf("tick cost, %2zu joints: %.3f us CPU per tick (best of 5 x %ld ticks; sample + "
           "null sink + statistics)\n", joints, best * 1e6, N);
}

int main(int argc, char **argv)
{
    double seconds = 5.0;
    if (argc > 1) {
        char *end;
        seconds = strtod(argv[1], &end);
        if (*end != '\0' || !(seconds > 0.0) || seconds > 3600.0) {
            fprintf(stderr, "usage: %s [seconds, default 5]\n", argv[0]);
            return 2;
        }
    }
    printf("streamer at 500 Hz, %g s per run, 6 joints, null sink\n", seconds);
    if (run_stream("SCHED_FIFO 80", 80, 1, seconds)) return 1;
    munlockall();
    if (run_stream("SCHED_OTHER", 0, 0, seconds)) return 1;
    tick_cost(6);
    tick_cost(18);
    return 0;
}
