/*
 * Streamer: deadlines, overrun skipping without bursts, sampling at the actual wake time, the
 * final target on stop, and the latency statistics, on a fake clock (deterministic); plus one
 * short real-time run with sane bounds only (timing is never asserted tightly here).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <signal.h>
#include <time.h>
#include <cmocka.h>

#include "common/ref.h"
#include "linux/streamer.h"

/* ---- deterministic PRNG: splitmix64 of tests/common/ref.c -------------------------------- */
static ref_rng sm;
static uint64_t sm_below(uint64_t n) { return ref_rng_next(&sm) % n; }

/* ---- fake clock, sampler and sink ------------------------------------------------------ */
#define MAXT 4096
typedef struct fake {
    uint64_t now;
    uint64_t lat[MAXT];       /* extra lateness of the i-th sleep */
    uint64_t work[MAXT];      /* time the i-th sample call takes */
    size_t n_sleep, n_sample;
    uint64_t deadline[MAXT];  /* deadline passed to the i-th sleep */
    uint64_t wake[MAXT];      /* fake time when the i-th sleep returned */
    double t[MAXT];           /* t_seconds given to the i-th sample call */
    uint64_t end[MAXT];       /* fake time at the end of the i-th sample call (incl. work) */
    int fail_sample_from;     /* sample index from which the sampler fails; -1 never */
    /* sink */
    size_t n_write;
    float written[MAXT][3];
    uint64_t wtick[MAXT];
    uint64_t wdeadline[MAXT]; /* qo_streamer_tick_deadline during the i-th write */
    int stop_after_write;     /* request stop inside write number k (1-based); 0 never */
    qo_streamer *s;
    qo_status sink_status;
    size_t n_service;
} fake;

static uint64_t fk_now(void *ctx) { return ((fake *)ctx)->now; }

static int fk_sleep(void *ctx, uint64_t abs_ns)
{
    fake *f = ctx;
    size_t i = f->n_sleep++;
    assert_true(i < MAXT);
    f->deadline[i] = abs_ns;
    if (f->now < abs_ns) f->now = abs_ns;
    f->now += f->lat[i];
    f->wake[i] = f->now;
    return 0;
}

/* Target of joint j at time t: smooth and distinct per joint, computed in double. */
static double traj(double t, size_t j) { return sin(1.3 * t + (double)j) * (double)(j + 1); }

static qo_status fk_sample(void *ctx, double t, float *targets, size_t n)
{
    fake *f = ctx;
    size_t i = f->n_sample++, j;
    assert_true(i < MAXT);
    f->t[i] = t;
    f->now += f->work[i];
    f->end[i] = f->now;
    if (f->fail_sample_from >= 0 && (int)i >= f->fail_sample_from) {
        for (j = 0; j < n; j++) targets[j] = 12345.0f; /* must never reach the sink */
        return QO_E_NONFINITE;
    }
    for (j = 0; j < n; j++) targets[j] = (float)traj(t, j);
    return QO_OK;
}

static qo_status fk_write(void *ctx, const float *targets, size_t n, uint64_t tick)
{
    fake *f = ctx;
    size_t i = f->n_write++, j;
    assert_true(i < MAXT);
    assert_int_equal(n, 3);
    for (j = 0; j < n; j++) f->written[i][j] = targets[j];
    f->wtick[i] = tick;
    assert_int_equal(qo_streamer_tick_deadline(f->s, &f->wdeadline[i]), QO_OK);
    if (f->stop_after_write && (int)f->n_write == f->stop_after_write) qo_streamer_request_stop(f->s);
    return f->sink_status;
}

static void fk_service(void *ctx) { ((fake *)ctx)->n_service++; }

static fake F;

static void setup_streamer(qo_streamer *s, double rate)
{
    qo_streamer_config c;
    memset(&F, 0, sizeof F);
    F.now = 1000000000ull; /* origin 1 s: the clock is not zero-based */
    F.fail_sample_from = -1;
    F.s = s;
    c = qo_streamer_config_default;
    c.rate_hz = rate;
    c.n_joints = 3;
    c.sample = fk_sample;
    c.sample_ctx = &F;
    c.sink.ctx = &F;
    c.sink.write = fk_write;
    c.sink.service = fk_service;
    c.now = fk_now;
    c.sleep_until = fk_sleep;
    c.clock_ctx = &F;
    assert_int_equal(qo_streamer_init(s, &c), QO_OK);
}

static qo_streamer S;

/* ---- tests --------------------------------------------------------------------------- */

static void test_init_rejects_bad_config(void **state)
{
    qo_streamer_config c;
    (void)state;
    setup_streamer(&S, 500.0);
    c = S.cfg;
    assert_int_equal(qo_streamer_init(NULL, &c), QO_E_NULL);
    assert_int_equal(qo_streamer_init(&S, NULL), QO_E_NULL);
    assert_int_equal(qo_streamer_tick(&S), QO_E_STATE); /* the failed init left it unusable */
    {
        qo_streamer_config b = c; b.sample = NULL;
        assert_int_equal(qo_streamer_init(&S, &b), QO_E_NULL);
    }
    {
        qo_streamer_config b = c; b.sink.write = NULL;
        assert_int_equal(qo_streamer_init(&S, &b), QO_E_NULL);
    }
    {
        const double bad[] = { 0.0, -1.0, NAN, INFINITY, -INFINITY, 100000.5 };
        size_t i;
        for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
            qo_streamer_config b = c; b.rate_hz = bad[i];
            if (qo_streamer_init(&S, &b) != QO_E_LIMIT) fail_msg("rate %g accepted", bad[i]);
        }
    }
    {
        qo_streamer_config b = c; b.n_joints = 0;
        assert_int_equal(qo_streamer_init(&S, &b), QO_E_TOO_FEW);
        b.n_joints = QO_STREAMER_MAX_JOINTS + 1;
        assert_int_equal(qo_streamer_init(&S, &b), QO_E_CAPACITY);
        b.n_joints = QO_STREAMER_MAX_JOINTS;
        assert_int_equal(qo_streamer_init(&S, &b), QO_OK);
    }
    {
        qo_streamer_config b = c; b.rt_priority = 100;
        assert_int_equal(qo_streamer_init(&S, &b), QO_E_RANGE);
        b.rt_priority = -1;
        assert_int_equal(qo_streamer_init(&S, &b), QO_E_RANGE);
    }
    assert_int_equal(qo_streamer_tick(NULL), QO_E_NULL);
    assert_int_equal(qo_streamer_finish(NULL), QO_E_NULL);
    assert_int_equal(qo_streamer_start(NULL), QO_E_NULL);
    assert_int_equal(qo_streamer_join(NULL), QO_E_NULL);
    {
        qo_streamer_stats st;
        assert_int_equal(qo_streamer_stats_read(NULL, &st), QO_E_NULL);
        assert_int_equal(st.ticks, 0);
        assert_int_equal(qo_streamer_stats_read(&S, NULL), QO_E_NULL);
    }
}

/* Without lateness every tick wakes exactly on its deadline and samples t = k * period. */
static void test_period_accuracy(void **state)
{
    const double rates[] = { 500.0, 3.0, 1000.0 / 7.0, 100000.0 };
    size_t r, k;
    (void)state;
    for (r = 0; r < sizeof rates / sizeof rates[0]; r++) {
        setup_streamer(&S, rates[r]);
        for (k = 0; k < 200; k++) assert_int_equal(qo_streamer_tick(&S), QO_OK);
        for (k = 0; k < 200; k++) {
            /* Ideal time k/rate; the ns-rounded period may drift by at most 0.5 ns per tick. */
            double ideal = (double)k / rates[r];
            double tol = 0.5e-9 * (double)k + 1e-12;
            if (fabs(F.t[k] - ideal) > tol)
                fail_msg("rate %g tick %zu: t %.12f want %.12f", rates[r], k, F.t[k], ideal);
            if (F.wake[k] != F.deadline[k]) fail_msg("rate %g tick %zu woke off-deadline", rates[r], k);
            assert_int_equal(F.wtick[k], k);
        }
        assert_int_equal(F.n_service, 200);
        {
            qo_streamer_stats st;
            assert_int_equal(qo_streamer_stats_read(&S, &st), QO_OK);
            assert_int_equal(st.ticks, 200);
            assert_int_equal(st.overruns, 0);
            assert_int_equal(st.lat_max_ns, 0);
            assert_int_equal(st.period_err_max_ns, 0);
        }
    }
}

/* A tick whose work takes 2.5 periods skips the two deadlines it overlapped, counts them, and
 * the next tick waits for the first future deadline (no back-to-back catch-up). */
static void test_overrun_skips_and_counts(void **state)
{
    const uint64_t P = 2000000u; /* 500 Hz */
    qo_streamer_stats st;
    size_t k;
    (void)state;
    setup_streamer(&S, 500.0);
    F.work[5] = 5u * P / 2u;
    F.work[9] = P;      /* ends exactly ON the next deadline: not missed */
    F.work[12] = P + 1; /* one ns after it: missed */
    for (k = 0; k < 16; k++) (void)qo_streamer_tick(&S);
    for (k = 0; k < 16; k++) {
        uint64_t skip = (k > 5) + (k > 5) + (k > 12); /* deadlines skipped before tick k */
        uint64_t want = 1000000000ull + (k + skip) * P;
        if (F.deadline[k] != want)
            fail_msg("tick %zu deadline %llu want %llu", k, (unsigned long long)F.deadline[k],
                     (unsigned long long)want);
    }
    assert_int_equal(qo_streamer_stats_read(&S, &st), QO_OK);
    assert_int_equal(st.overruns, 3);
    assert_int_equal(st.overrun_events, 2);
    assert_int_equal(st.ticks, 16);
}

/* Random lateness and work: every tick's deadline is on the grid, is the first grid point at
 * or after the previous tick's end (skip to the next future period, never a burst), the
 * overrun count equals the skipped grid points, and each sample is taken at the wake time. */
static void test_no_catch_up_burst_random(void **state)
{
    const uint64_t P = 2000000u;
    const size_t N = 3000;
    uint64_t skipped = 0, origin, max_lat = 0, max_perr = 0;
    qo_streamer_stats st;
    size_t k;
    (void)state;
    sm.s = 0x5eed1234u;
    setup_streamer(&S, 500.0);
    origin = F.now;
    for (k = 0; k < N; k++) {
        uint64_t r = sm_below(100);
        F.lat[k] = r < 80 ? sm_below(200000) : r < 95 ? sm_below(3 * P) : sm_below(12 * P);
        F.work[k] = sm_below(10) == 0 ? sm_below(4 * P) : sm_below(P / 4);
    }
    for (k = 0; k < N; k++) (void)qo_streamer_tick(&S);
    for (k = 0; k < N; k++) {
        uint64_t d = F.deadline[k];
        double want_t = (double)(F.wake[k] - origin) * 1e-9;
        if ((d - origin) % P != 0) fail_msg("tick %zu: deadline off the grid", k);
        if (F.t[k] != want_t) fail_msg("tick %zu: sampled %.9f, woke at %.9f", k, F.t[k], want_t);
        /* the scheduled time a tick log gets: the deadline the tick slept to, from the origin */
        if (F.wdeadline[k] != d - origin)
            fail_msg("tick %zu: tick_deadline %llu, slept to %llu", k, (unsigned long long)F.wdeadline[k],
                     (unsigned long long)(d - origin));
        if (F.wake[k] - d > max_lat) max_lat = F.wake[k] - d;
        if (k > 0) {
            uint64_t prev_end = F.end[k - 1];
            uint64_t first = F.deadline[k - 1] + P; /* brute force: walk the grid */
            while (first < prev_end) { first += P; skipped++; }
            if (d != first)
                fail_msg("tick %zu: deadline %llu, first future after end %llu is %llu", k,
                         (unsigned long long)d, (unsigned long long)prev_end,
                         (unsigned long long)first);
            if (d == F.deadline[k - 1] + P) { /* consecutive deadlines: a real period */
                double e = fabs((double)(F.wake[k] - F.wake[k - 1]) - (double)P);
                if (e > (double)max_perr) max_perr = (uint64_t)e;
            }
        }
    }
    assert_int_equal(qo_streamer_stats_read(&S, &st), QO_OK);
    /* the last tick's own skips are counted too */
    {
        uint64_t first = F.deadline[N - 1] + P;
        while (first < F.end[N - 1]) { first += P; skipped++; }
    }
    if (st.overruns != skipped)
        fail_msg("overruns %llu, brute force %llu", (unsigned long long)st.overruns,
                 (unsigned long long)skipped);
    assert_int_equal(st.lat_max_ns, max_lat);
    assert_int_equal(st.lat_count, N);
    assert_int_equal(st.period_err_max_ns, max_perr);
    assert_true(max_perr > 0);
}

/* A reader holding the statistics lock never blocks the tick: ticks park their numbers
 * (QO_STREAMER_PENDING latencies, the rest counted as dropped) and publish them at the first
 * tick after the lock is free. */
static void test_stats_reader_never_blocks_tick(void **state)
{
    const size_t held = QO_STREAMER_PENDING + 8u;
    qo_streamer_stats st;
    size_t k;
    (void)state;
    setup_streamer(&S, 500.0);
    for (k = 0; k < 5; k++) (void)qo_streamer_tick(&S);
    F.work[7] = 3u * 2000000u + 1u; /* 3 deadlines missed while the lock is held */
    assert_int_equal(pthread_mutex_lock(&S.lock), 0); /* plays the reader */
    for (k = 0; k < held; k++) (void)qo_streamer_tick(&S);
    assert_int_equal(S.live.ticks, 5); /* nothing published while held */
    assert_int_equal(pthread_mutex_unlock(&S.lock), 0);
    (void)qo_streamer_tick(&S);
    assert_int_equal(qo_streamer_stats_read(&S, &st), QO_OK);
    assert_int_equal(st.ticks, 5u + held + 1u);
    assert_int_equal(st.overruns, 3);
    assert_int_equal(st.stats_dropped, held - QO_STREAMER_PENDING);
    assert_int_equal(st.lat_count, st.ticks - st.stats_dropped);
}

/* Nearest-rank percentile from a sorted copy, in the test's own terms. */
static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}
static uint64_t brute_pct(const uint64_t *sorted, size_t n, double q)
{
    size_t rank = (size_t)ceil(q * (double)n);
    if (rank < 1) rank = 1;
    return sorted[rank - 1];
}
static uint64_t width_at(uint64_t v) { return v < 1024000u ? 1000u : 64000u; }

static void check_pct(const qo_streamer_jitter_hist *h, const uint64_t *sorted, size_t n, double q,
                      const char *label)
{
    uint64_t got, want = brute_pct(sorted, n, q);
    assert_int_equal(qo_streamer_jitter_hist_percentile(h, q, &got), QO_OK);
    if (want >= 1024000u + 1023u * 64000u || q == 1.0) {
        if (got != (q == 1.0 ? sorted[n - 1] : h->max_ns))
            fail_msg("%s q=%g overflow/max: got %llu", label, q, (unsigned long long)got);
        return;
    }
    if (!(got <= want && want < got + width_at(got)))
        fail_msg("%s q=%g n=%zu: got bin %llu, true %llu", label, q, n,
                 (unsigned long long)got, (unsigned long long)want);
}

static void test_hist_percentiles_vs_brute_force(void **state)
{
    static uint64_t v[20000];
    static qo_streamer_jitter_hist h;
    const double qs[] = { 0.0, 0.001, 0.25, 0.5, 0.9, 0.99, 0.999, 1.0 };
    const size_t sizes[] = { 1, 2, 3, 99, 100, 101, 20000 };
    size_t si, i, qi;
    uint64_t out;
    (void)state;
    sm.s = 42;
    for (si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
        size_t n = sizes[si];
        qo_streamer_jitter_hist_reset(&h);
        for (i = 0; i < n; i++) {
            uint64_t r = sm_below(100);
            /* mostly fine bins, some coarse, a few past the overflow edge, and bin edges */
            v[i] = r < 70 ? sm_below(1024000) : r < 95 ? sm_below(66560000) :
                   r < 98 ? 66560000u + sm_below(1000000000) : (uint64_t)(sm_below(4) * 1000u);
            qo_streamer_jitter_hist_add(&h, v[i]);
        }
        qsort(v, n, sizeof v[0], cmp_u64);
        for (qi = 0; qi < sizeof qs / sizeof qs[0]; qi++) check_pct(&h, v, n, qs[qi], "random");
    }
    /* exact bin edges */
    qo_streamer_jitter_hist_reset(&h);
    qo_streamer_jitter_hist_add(&h, 1023999u);
    qo_streamer_jitter_hist_add(&h, 1024000u);
    assert_int_equal(qo_streamer_jitter_hist_percentile(&h, 0.5, &out), QO_OK);
    assert_int_equal(out, 1023000u);
    assert_int_equal(qo_streamer_jitter_hist_percentile(&h, 0.51, &out), QO_OK);
    assert_int_equal(out, 1024000u);
    /* errors */
    assert_int_equal(qo_streamer_jitter_hist_percentile(&h, -0.1, &out), QO_E_RANGE);
    assert_int_equal(out, 0);
    assert_int_equal(qo_streamer_jitter_hist_percentile(&h, 1.01, &out), QO_E_RANGE);
    assert_int_equal(qo_streamer_jitter_hist_percentile(&h, NAN, &out), QO_E_RANGE);
    assert_int_equal(qo_streamer_jitter_hist_percentile(NULL, 0.5, &out), QO_E_NULL);
    assert_int_equal(qo_streamer_jitter_hist_percentile(&h, 0.5, NULL), QO_E_NULL);
    qo_streamer_jitter_hist_reset(&h);
    assert_int_equal(qo_streamer_jitter_hist_percentile(&h, 0.5, &out), QO_E_TOO_FEW);
}

/* The streamer's own p50/p99/max equal the brute-force percentiles of the injected lateness. */
static void test_streamer_stats_vs_brute_force(void **state)
{
    static uint64_t lat[1500];
    const size_t N = 1500;
    qo_streamer_stats st;
    size_t k;
    (void)state;
    sm.s = 7;
    setup_streamer(&S, 500.0);
    for (k = 0; k < N; k++) F.lat[k] = sm_below(10) ? sm_below(300000) : sm_below(1500000);
    for (k = 0; k < N; k++) (void)qo_streamer_tick(&S);
    for (k = 0; k < N; k++) lat[k] = F.wake[k] - F.deadline[k];
    qsort(lat, N, sizeof lat[0], cmp_u64);
    assert_int_equal(qo_streamer_stats_read(&S, &st), QO_OK);
    assert_int_equal(st.lat_count, N);
    assert_int_equal(st.lat_max_ns, lat[N - 1]);
    if (!(st.lat_p50_ns <= brute_pct(lat, N, 0.5) && brute_pct(lat, N, 0.5) < st.lat_p50_ns + 1000u))
        fail_msg("p50 %llu vs %llu", (unsigned long long)st.lat_p50_ns,
                 (unsigned long long)brute_pct(lat, N, 0.5));
    {
        uint64_t w = brute_pct(lat, N, 0.99);
        if (!(st.lat_p99_ns <= w && w < st.lat_p99_ns + width_at(st.lat_p99_ns)))
            fail_msg("p99 %llu vs %llu", (unsigned long long)st.lat_p99_ns, (unsigned long long)w);
    }
}

/* Stop requested inside tick 7's write: the next tick does nothing, finish hands the sink the
 * last sampled target with the next tick number. */
static void test_stop_leaves_defined_target(void **state)
{
    size_t k;
    (void)state;
    setup_streamer(&S, 250.0);
    F.stop_after_write = 7;
    for (k = 0; k < 7; k++) assert_int_equal(qo_streamer_tick(&S), QO_OK);
    assert_int_equal(qo_streamer_tick(&S), QO_E_STATE);
    assert_int_equal(F.n_sample, 7);
    assert_int_equal(F.n_write, 7);
    assert_int_equal(qo_streamer_finish(&S), QO_OK);
    assert_int_equal(F.n_write, 8);
    assert_int_equal(F.wtick[7], 7);
    for (k = 0; k < 3; k++) {
        double want = traj(F.t[6], k);
        if (fabs((double)F.written[7][k] - want) > 1e-6 * (1.0 + fabs(want)))
            fail_msg("final joint %zu: %g want %g", k, (double)F.written[7][k], want);
    }
}

/* The sampler fails from tick 4 on: those ticks and the final write hold the tick-3 target;
 * the sink errors are counted, consecutively too. */
static void test_sampler_failure_holds_last_good(void **state)
{
    qo_streamer_stats st;
    size_t k;
    (void)state;
    setup_streamer(&S, 500.0);
    F.fail_sample_from = 4;
    for (k = 0; k < 4; k++) assert_int_equal(qo_streamer_tick(&S), QO_OK);
    F.sink_status = QO_E_TIMEOUT;
    for (k = 4; k < 9; k++) assert_int_equal(qo_streamer_tick(&S), QO_E_NONFINITE);
    F.sink_status = QO_E_IO;
    qo_streamer_request_stop(&S);
    assert_int_equal(qo_streamer_finish(&S), QO_E_IO);
    assert_int_equal(F.n_write, 10);
    for (k = 4; k < 10; k++) {
        size_t j;
        for (j = 0; j < 3; j++)
            if (F.written[k][j] != F.written[3][j]) fail_msg("write %zu joint %zu not held", k, j);
    }
    assert_int_equal(qo_streamer_stats_read(&S, &st), QO_OK);
    assert_int_equal(st.sample_errors, 5);
    assert_int_equal(st.sink_errors, 5);
    assert_int_equal(st.sink_errors_consecutive, 5);
}

/* A sampler that never succeeds: nothing reaches the sink, and finish says so. */
static void test_no_sample_no_write(void **state)
{
    (void)state;
    setup_streamer(&S, 500.0);
    F.fail_sample_from = 0;
    assert_int_equal(qo_streamer_tick(&S), QO_E_NONFINITE);
    assert_int_equal(qo_streamer_finish(&S), QO_E_STATE);
    assert_int_equal(F.n_write, 0);
}

/* qo_streamer_tick_deadline: its errors write 0; before the first tick it is the origin. */
static void test_tick_deadline_errors(void **state)
{
    qo_streamer fresh;
    uint64_t d = 77;
    (void)state;
    memset(&fresh, 0, sizeof fresh);
    assert_int_equal(qo_streamer_tick_deadline(NULL, &d), QO_E_NULL);
    assert_int_equal(d, 0);
    assert_int_equal(qo_streamer_tick_deadline(&S, NULL), QO_E_NULL);
    d = 77;
    assert_int_equal(qo_streamer_tick_deadline(&fresh, &d), QO_E_STATE);
    assert_int_equal(d, 0);
    setup_streamer(&S, 500.0);
    d = 77;
    assert_int_equal(qo_streamer_tick_deadline(&S, &d), QO_OK);
    assert_int_equal(d, 0);
}

/* SIGINT through the installed handler sets the flag. */
static void test_signal_sets_stop(void **state)
{
    struct sigaction dfl;
    (void)state;
    setup_streamer(&S, 500.0);
    assert_int_equal(qo_streamer_install_stop_signals(NULL), QO_E_NULL);
    assert_int_equal(qo_streamer_install_stop_signals(&S), QO_OK);
    assert_int_equal(*qo_streamer_stop_flag(&S), 0);
    raise(SIGINT);
    assert_int_equal(*qo_streamer_stop_flag(&S), 1);
    assert_int_equal(qo_streamer_tick(&S), QO_E_STATE);
    memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    sigaction(SIGINT, &dfl, NULL);
    sigaction(SIGTERM, &dfl, NULL);
    assert_null(qo_streamer_stop_flag(NULL));
}

/* ---- real clock: ~0.3 s at 500 Hz in a thread, statistics read while it runs ------------ */
typedef struct rt_sink { size_t n; float last[3]; uint64_t last_tick; } rt_sink;
static qo_status rt_write(void *ctx, const float *t, size_t n, uint64_t tick)
{
    rt_sink *r = ctx;
    memcpy(r->last, t, n * sizeof *t);
    r->last_tick = tick;
    r->n++;
    return QO_OK;
}
static qo_status rt_sample(void *ctx, double t, float *out, size_t n)
{
    size_t j;
    (void)ctx;
    for (j = 0; j < n; j++) out[j] = (float)traj(t, j);
    return QO_OK;
}
static double mono_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

static void test_real_time_run_sane(void **state)
{
    static qo_streamer rs;
    static rt_sink sink;
    qo_streamer_config c;
    qo_streamer_stats st, mid;
    const char *warn;
    unsigned flags;
    double t0, t1;
    int i;
    (void)state;
    memset(&sink, 0, sizeof sink);
    c = qo_streamer_config_default;
    c.rate_hz = 500.0;
    c.n_joints = 3;
    c.sample = rt_sample;
    c.sink.write = rt_write;
    c.sink.ctx = &sink;
    c.rt_priority = 10;
    c.lock_memory = 0; /* mlockall under ASan would try to pin the shadow memory */
    assert_int_equal(qo_streamer_init(&rs, &c), QO_OK);
    t0 = mono_s();
    assert_int_equal(qo_streamer_start(&rs), QO_OK);
    assert_int_equal(qo_streamer_start(&rs), QO_E_STATE);
    for (i = 0; i < 6; i++) {
        struct timespec d = { 0, 50000000 };
        nanosleep(&d, NULL);
        assert_int_equal(qo_streamer_stats_read(&rs, &mid), QO_OK);
    }
    qo_streamer_request_stop(&rs);
    assert_int_equal(qo_streamer_join(&rs), QO_OK);
    t1 = mono_s();
    assert_int_equal(qo_streamer_stats_read(&rs, &st), QO_OK);
    flags = qo_streamer_rt_report(&rs, &warn);
    print_message("      real run: %.3f s, ticks %llu, overruns %llu, p50 %llu us, p99 %llu us, "
                  "max %llu us, rt flags %u %s\n", t1 - t0, (unsigned long long)st.ticks,
                  (unsigned long long)st.overruns, (unsigned long long)st.lat_p50_ns / 1000u,
                  (unsigned long long)st.lat_p99_ns / 1000u,
                  (unsigned long long)st.lat_max_ns / 1000u, flags, warn);
    /* sane bounds only */
    assert_true(st.ticks >= 20);
    if (!((double)(st.ticks + st.overruns) <= (t1 - t0) * 500.0 + 2.0))
        fail_msg("ticks %llu + overruns %llu exceed %.1f periods", (unsigned long long)st.ticks,
                 (unsigned long long)st.overruns, (t1 - t0) * 500.0);
    assert_true(mid.ticks <= st.ticks);
    assert_int_equal(st.lat_count, st.ticks);
    assert_true(st.lat_p50_ns <= st.lat_p99_ns && st.lat_p99_ns <= st.lat_max_ns);
    assert_true((double)st.lat_max_ns * 1e-9 < t1 - t0);
    assert_int_equal(sink.n, st.ticks + 1); /* every tick plus the final write */
    assert_int_equal(sink.last_tick, st.ticks);
    assert_true((flags & QO_STREAMER_RT_FIFO) ? warn[0] == '\0' : warn[0] != '\0');
    assert_int_equal(qo_streamer_join(&rs), QO_E_STATE);
}

/* The defaults are a constant (the ports' one idiom): the documented values, nothing else set. */
static void test_default_constant(void **state)
{
    const qo_streamer_config *c = &qo_streamer_config_default;
    (void)state;
    assert_true(c->rate_hz == 500.0);
    assert_int_equal(c->rt_priority, 80);
    assert_int_equal(c->lock_memory, 1);
    assert_int_equal(c->n_joints, 0);
    assert_null(c->sample);
    assert_null(c->sink.write);
    assert_null(c->now);
    assert_null(c->sleep_until);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_default_constant),
        cmocka_unit_test(test_init_rejects_bad_config),
        cmocka_unit_test(test_period_accuracy),
        cmocka_unit_test(test_overrun_skips_and_counts),
        cmocka_unit_test(test_no_catch_up_burst_random),
        cmocka_unit_test(test_stats_reader_never_blocks_tick),
        cmocka_unit_test(test_hist_percentiles_vs_brute_force),
        cmocka_unit_test(test_streamer_stats_vs_brute_force),
        cmocka_unit_test(test_stop_leaves_defined_target),
        cmocka_unit_test(test_sampler_failure_holds_last_good),
        cmocka_unit_test(test_no_sample_no_write),
        cmocka_unit_test(test_tick_deadline_errors),
        cmocka_unit_test(test_signal_sets_stop),
        cmocka_unit_test(test_real_time_run_sane),
    };
    return cmocka_run_group_tests_name("streamer", tests, NULL, NULL);
}
