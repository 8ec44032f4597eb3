/*
 * ports/linux/streamer.c - absolute-time periodic loop, best-effort RT, overrun skipping,
 * statistics readable while running. See streamer.h for the timing and locking model.
 */
#include "streamer.h"
#include "mono_clock.h"

#include <errno.h>
#include <math.h>
#include <sched.h>
#include <stdio.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <time.h>

/* ---- histogram ---------------------------------------------------------------------------- */

void qo_streamer_jitter_hist_reset(qo_streamer_jitter_hist *h)
{
    if (h) memset(h, 0, sizeof *h);
}

static size_t hist_bin_of(uint64_t ns)
{
    uint64_t fine_top = (uint64_t)QO_STREAMER_JITTER_FINE_BINS * QO_STREAMER_JITTER_FINE_NS;
    uint64_t b;
    if (ns < fine_top) return (size_t)(ns / QO_STREAMER_JITTER_FINE_NS);
    b = (ns - fine_top) / QO_STREAMER_JITTER_COARSE_NS;
    if (b >= QO_STREAMER_JITTER_COARSE_BINS) b = QO_STREAMER_JITTER_COARSE_BINS - 1u;
    return (size_t)(QO_STREAMER_JITTER_FINE_BINS + b);
}

static uint64_t hist_bin_low(size_t i)
{
    if (i < QO_STREAMER_JITTER_FINE_BINS) return (uint64_t)i * QO_STREAMER_JITTER_FINE_NS;
    return (uint64_t)QO_STREAMER_JITTER_FINE_BINS * QO_STREAMER_JITTER_FINE_NS +
           (uint64_t)(i - QO_STREAMER_JITTER_FINE_BINS) * QO_STREAMER_JITTER_COARSE_NS;
}

void qo_streamer_jitter_hist_add(qo_streamer_jitter_hist *h, uint64_t latency_ns)
{
    size_t i;
    if (!h) return;
    i = hist_bin_of(latency_ns);
    if (h->bin[i] != UINT32_MAX) h->bin[i]++;
    h->count++;
    if (latency_ns > h->max_ns) h->max_ns = latency_ns;
}

qo_status qo_streamer_jitter_hist_percentile(const qo_streamer_jitter_hist *h, double q,
                                             uint64_t *out_ns)
{
    uint64_t rank, seen = 0;
    size_t i;
    if (out_ns) *out_ns = 0;
    if (!h || !out_ns) return QO_E_NULL;
    if (!(q >= 0.0 && q <= 1.0)) return QO_E_RANGE;
    if (h->count == 0) return QO_E_TOO_FEW;
    if (q == 1.0) { *out_ns = h->max_ns; return QO_OK; }
    rank = (uint64_t)ceil(q * (double)h->count);
    if (rank < 1) rank = 1;
    if (rank > h->count) rank = h->count;
    for (i = 0; i < QO_STREAMER_JITTER_BINS; i++) {
        seen += h->bin[i];
        if (seen >= rank) {
            *out_ns = (i == QO_STREAMER_JITTER_BINS - 1u) ? h->max_ns : hist_bin_low(i);
            return QO_OK;
        }
    }
    /* Only reachable when saturated bins undercount: the max is the honest answer. */
    *out_ns = h->max_ns;
    return QO_OK;
}

/* ---- streamer --------------------------------------------------------------------------- */

const qo_streamer_config qo_streamer_config_default = {
    .rate_hz = 500.0, .rt_priority = 80, .lock_memory = 1
};

qo_status qo_streamer_init(qo_streamer *s, const qo_streamer_config *cfg)
{
    pthread_mutexattr_t ma;
    int ok;
    if (!s) return QO_E_NULL;
    memset(s, 0, sizeof *s);
    if (!cfg || !cfg->sample || !cfg->sink.write) return QO_E_NULL;
    if (!isfinite(cfg->rate_hz) || !(cfg->rate_hz > 0.0) || cfg->rate_hz > 100000.0)
        return QO_E_LIMIT;
    if (cfg->n_joints == 0) return QO_E_TOO_FEW;
    if (cfg->n_joints > QO_STREAMER_MAX_JOINTS) return QO_E_CAPACITY;
    if (cfg->rt_priority < 0 || cfg->rt_priority > 99) return QO_E_RANGE;
    s->cfg = *cfg;
    if (!s->cfg.now) { s->cfg.now = qo_mono_clock_now_ns; }
    if (!s->cfg.sleep_until) { s->cfg.sleep_until = qo_mono_clock_sleep_until_ns; }
    s->period_ns = (uint64_t)llround(1e9 / cfg->rate_hz);
    /* Priority inheritance: a low-priority reader holding the lock cannot be preempted for
     * long by mid-priority work while the RT thread wants the lock (it only try-locks anyway). */
    ok = pthread_mutexattr_init(&ma) == 0;
    if (ok) {
        (void)pthread_mutexattr_setprotocol(&ma, PTHREAD_PRIO_INHERIT);
        ok = pthread_mutex_init(&s->lock, &ma) == 0;
        pthread_mutexattr_destroy(&ma);
    }
    if (!ok) return QO_E_IO;
    qo_streamer_jitter_hist_reset(&s->hist);
    s->origin_ns = s->cfg.now(s->cfg.clock_ctx);
    s->next_ns = s->origin_ns;
    s->run_status = QO_OK;
    s->initialised = 1;
    return QO_OK;
}

/* Folds the parked tick numbers into the live block; caller holds the lock. */
static void merge_pending(qo_streamer *s)
{
    qo_streamer_stats *l = &s->live, *p = &s->pend;
    uint32_t i;
    l->ticks += p->ticks;
    l->overruns += p->overruns;
    l->overrun_events += p->overrun_events;
    l->sink_errors += p->sink_errors;
    l->sample_errors += p->sample_errors;
    l->stats_dropped += p->stats_dropped;
    l->sink_errors_consecutive = p->sink_errors_consecutive;
    if (p->period_err_max_ns > l->period_err_max_ns) l->period_err_max_ns = p->period_err_max_ns;
    l->origin_ns = s->origin_ns;
    l->span_ns = s->next_ns - s->origin_ns; /* consistent with the counts merged here */
    for (i = 0; i < s->pend_n; i++) qo_streamer_jitter_hist_add(&s->hist, s->pend_lat[i]);
    s->pend_n = 0;
    {
        uint64_t keep = p->sink_errors_consecutive;
        memset(p, 0, sizeof *p);
        p->sink_errors_consecutive = keep;
    }
}

qo_status qo_streamer_tick(qo_streamer *s)
{
    qo_status st = QO_OK, st_w = QO_OK;
    uint64_t wake, end, lat, skipped = 0;
    double t;
    if (!s) return QO_E_NULL;
    if (!s->initialised || s->stop) return QO_E_STATE;
    for (;;) {
        int r = s->cfg.sleep_until(s->cfg.clock_ctx, s->next_ns);
        if (s->stop) return QO_E_STATE;
        if (r != EINTR) break; /* 0, or an error we cannot fix by sleeping again: run the tick */
    }
    wake = s->cfg.now(s->cfg.clock_ctx);
    lat = wake > s->next_ns ? wake - s->next_ns : 0;
    t = wake > s->origin_ns ? (double)(wake - s->origin_ns) * 1e-9 : 0.0;

    st = s->cfg.sample(s->cfg.sample_ctx, t, s->scratch, s->cfg.n_joints);
    if (st == QO_OK) {
        memcpy(s->target, s->scratch, s->cfg.n_joints * sizeof s->target[0]);
        s->have_target = 1;
    } else {
        s->pend.sample_errors++;
    }
    if (s->have_target) {
        st_w = s->cfg.sink.write(s->cfg.sink.ctx, s->target, s->cfg.n_joints, s->tick_no);
        if (st_w != QO_OK) {
            s->pend.sink_errors++;
            s->pend.sink_errors_consecutive++;
        } else {
            s->pend.sink_errors_consecutive = 0;
        }
    }
    s->tick_no++;
    if (s->cfg.sink.service) s->cfg.sink.service(s->cfg.sink.ctx);

    end = s->cfg.now(s->cfg.clock_ctx);
    s->next_ns += s->period_ns;
    if (end > s->next_ns) {
        /* Every deadline before `end` has passed: skip them all and wait for the first one at
         * or after `end` (one that is exactly now is still on time, not missed). */
        skipped = (end - s->next_ns + s->period_ns - 1u) / s->period_ns;
        s->next_ns += skipped * s->period_ns;
        s->pend.overruns += skipped;
        s->pend.overrun_events++;
    }
    if (s->have_last_wake) {
        uint64_t iv = wake - s->last_wake_ns;
        uint64_t err = iv > s->period_ns ? iv - s->period_ns : s->period_ns - iv;
        if (err > s->pend.period_err_max_ns) s->pend.period_err_max_ns = err;
    }
    /* An interval that spans skipped deadlines is not a period: do not measure it. */
    s->have_last_wake = skipped == 0;
    s->last_wake_ns = wake;

    s->pend.ticks++;
    if (pthread_mutex_trylock(&s->lock) == 0) {
        merge_pending(s);
        qo_streamer_jitter_hist_add(&s->hist, lat);
        pthread_mutex_unlock(&s->lock);
    } else if (s->pend_n < QO_STREAMER_PENDING) {
        s->pend_lat[s->pend_n++] = lat;
    } else {
        s->pend.stats_dropped++;
    }
    return st != QO_OK ? st : st_w;
}

static void prefault_stack(void)
{
    /* Touch the stack the loop may use so page faults happen now, not in the first ticks. */
    volatile unsigned char buf[64 * 1024];
    size_t i;
    for (i = 0; i < sizeof buf; i += 4096) buf[i] = 0;
}

static void rt_setup(qo_streamer *s, int *restore_policy, struct sched_param *restore_param)
{
    size_t len = 0;
    s->rt_flags = 0;
    s->rt_warning[0] = '\0';
    *restore_policy = -1;
    if (s->cfg.lock_memory) {
        if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) s->rt_flags |= QO_STREAMER_RT_MLOCK;
        else {
            int n = snprintf(s->rt_warning, sizeof s->rt_warning, "mlockall: %s; ", strerror(errno));
            if (n > 0) len = (size_t)n < sizeof s->rt_warning ? (size_t)n : sizeof s->rt_warning - 1u;
        }
    }
    if (s->cfg.rt_priority > 0) {
        struct sched_param sp;
        int old, r;
        if (pthread_getschedparam(pthread_self(), &old, restore_param) == 0) *restore_policy = old;
        memset(&sp, 0, sizeof sp);
        sp.sched_priority = s->cfg.rt_priority;
        r = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
        if (r == 0) s->rt_flags |= QO_STREAMER_RT_FIFO;
        else {
            *restore_policy = -1;
            snprintf(s->rt_warning + len, sizeof s->rt_warning - len,
                     "SCHED_FIFO %d: %s; running SCHED_OTHER", s->cfg.rt_priority, strerror(r));
        }
    }
#ifdef PR_SET_TIMERSLACK
    /* A SCHED_OTHER thread's absolute sleeps are rounded up by the timer slack (50 us by
     * default): at high rates that slack, not the work, would set the period. 1 ns asks for
     * the deadline itself (SCHED_FIFO threads get that anyway). Best effort, never fatal. */
    (void)prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
#endif
    prefault_stack();
}

/* At the stop, the deadlines that passed since the last tick (a loaded machine may have kept the
 * thread off the CPU) are overruns too: every deadline up to the stop is accounted for. */
static void account_passed_deadlines(qo_streamer *s)
{
    uint64_t now = s->cfg.now(s->cfg.clock_ctx);
    if (now >= s->next_ns) {
        uint64_t passed = (now - s->next_ns) / s->period_ns + 1u;
        s->next_ns += passed * s->period_ns;
        s->pend.overruns += passed;
        s->pend.overrun_events++;
    }
}

qo_status qo_streamer_finish(qo_streamer *s)
{
    qo_status st;
    if (!s) return QO_E_NULL;
    if (!s->initialised || !s->have_target) return QO_E_STATE;
    st = s->cfg.sink.write(s->cfg.sink.ctx, s->target, s->cfg.n_joints, s->tick_no);
    s->tick_no++;
    return st;
}

qo_status qo_streamer_run(qo_streamer *s)
{
    int policy;
    struct sched_param param;
    qo_status st;
    if (!s) return QO_E_NULL;
    if (!s->initialised) return QO_E_STATE;
    rt_setup(s, &policy, &param);
    s->origin_ns = s->cfg.now(s->cfg.clock_ctx);
    s->next_ns = s->origin_ns;
    s->have_last_wake = 0;
    while (!s->stop) (void)qo_streamer_tick(s);
    account_passed_deadlines(s);
    st = qo_streamer_finish(s);
    /* Publish what is still parked (the reader may have held the lock at the last tick). */
    pthread_mutex_lock(&s->lock);
    merge_pending(s);
    pthread_mutex_unlock(&s->lock);
    if (policy >= 0) (void)pthread_setschedparam(pthread_self(), policy, &param);
    return st;
}

static void *thread_main(void *arg)
{
    qo_streamer *s = arg;
    s->run_status = qo_streamer_run(s);
    return NULL;
}

qo_status qo_streamer_start(qo_streamer *s)
{
    if (!s) return QO_E_NULL;
    if (!s->initialised || s->thread_started) return QO_E_STATE;
    if (pthread_create(&s->thread, NULL, thread_main, s) != 0) return QO_E_IO;
    s->thread_started = 1;
    return QO_OK;
}

qo_status qo_streamer_join(qo_streamer *s)
{
    if (!s) return QO_E_NULL;
    if (!s->thread_started) return QO_E_STATE;
    pthread_join(s->thread, NULL);
    s->thread_started = 0;
    return s->run_status;
}

void qo_streamer_request_stop(qo_streamer *s)
{
    if (s) s->stop = 1;
}

volatile sig_atomic_t *qo_streamer_stop_flag(qo_streamer *s)
{
    return s ? &s->stop : NULL;
}

/* The handler's target. Set before the handler is installed, only read inside it. */
static volatile sig_atomic_t *g_stop_target;

static void on_stop_signal(int sig)
{
    (void)sig;
    if (g_stop_target) *g_stop_target = 1;
}

qo_status qo_streamer_install_stop_signals(qo_streamer *s)
{
    struct sigaction sa;
    if (!s) return QO_E_NULL;
    g_stop_target = &s->stop;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0; /* no SA_RESTART: let blocking calls return EINTR so the loop notices */
    if (sigaction(SIGINT, &sa, NULL) != 0 || sigaction(SIGTERM, &sa, NULL) != 0) return QO_E_IO;
    return QO_OK;
}

qo_status qo_streamer_tick_deadline(const qo_streamer *s, uint64_t *deadline_ns)
{
    if (!deadline_ns) return QO_E_NULL;
    *deadline_ns = 0;
    if (!s) return QO_E_NULL;
    if (!s->initialised) return QO_E_STATE;
    *deadline_ns = s->next_ns - s->origin_ns;
    return QO_OK;
}

qo_status qo_streamer_stats_read(qo_streamer *s, qo_streamer_stats *out)
{
    if (!out) return QO_E_NULL;
    memset(out, 0, sizeof *out);
    if (!s) return QO_E_NULL;
    if (!s->initialised) return QO_E_STATE;
    pthread_mutex_lock(&s->lock);
    *out = s->live;
    out->lat_count = s->hist.count;
    out->lat_max_ns = s->hist.max_ns;
    (void)qo_streamer_jitter_hist_percentile(&s->hist, 0.50, &out->lat_p50_ns);
    (void)qo_streamer_jitter_hist_percentile(&s->hist, 0.99, &out->lat_p99_ns);
    pthread_mutex_unlock(&s->lock);
    return QO_OK;
}

unsigned qo_streamer_rt_report(const qo_streamer *s, const char **warning)
{
    if (warning) *warning = s ? s->rt_warning : "";
    return s ? s->rt_flags : 0u;
}
