/*
 * ports/linux/streamer.h - periodic streamer: samples a trajectory at a fixed rate and hands
 * the joint targets of each tick to a sink (Modbus, GPIO, mock...).
 *
 * Index:
 *   qo_sink                        the consumer interface (write one tick, optional service)
 *   qo_streamer_sample_fn          the producer callback (targets at a time in seconds)
 *   qo_streamer_clock_now_fn, qo_streamer_clock_sleep_until_fn   an injected clock
 *   qo_streamer_jitter_hist        a wake-latency histogram:
 *   qo_streamer_jitter_hist_reset()       empty it
 *   qo_streamer_jitter_hist_add()         add one latency sample (ns)
 *   qo_streamer_jitter_hist_percentile()  nearest-rank percentile (ns, bin resolution)
 *   qo_streamer_config_default     const defaults: 500 Hz, SCHED_FIFO 80, mlockall, real clock
 *   qo_streamer_init()             check a config and prepare a streamer (no thread, no RT yet)
 *   qo_streamer_tick()             one period: wait for the deadline, sample, write, skip overruns
 *   qo_streamer_run()              the loop in the calling thread until stop, then the final write
 *   qo_streamer_start()            the loop in a new thread (qo_streamer_run in it)
 *   qo_streamer_join()             wait for the thread started by qo_streamer_start
 *   qo_streamer_request_stop()     set the stop flag (async-signal-safe)
 *   qo_streamer_stop_flag()        the flag itself, for an application's own signal handler
 *   qo_streamer_install_stop_signals()  SIGINT/SIGTERM set the flag of one streamer
 *   qo_streamer_finish()           hand the sink the defined final target (last sampled)
 *   qo_streamer_tick_deadline()    the scheduled time of the tick in progress (for a tick log)
 *   qo_streamer_stats_read()       copy of the statistics, safe from any thread while running
 *   qo_streamer_rt_report()        what the real-time setup achieved and why not (text)
 *
 * Timing model. Deadlines are absolute: D_k = D_0 + k * period on the injected clock
 * (CLOCK_MONOTONIC by default), slept to with clock_nanosleep(TIMER_ABSTIME), so the loop
 * never drifts. After waking, the trajectory is sampled at the ACTUAL wake time (seconds since
 * qo_streamer_init, or since the loop started in run/start), not at D_k, so a late tick
 * sends the target that is right for when it is sent. When a tick's work (sample, write,
 * service) ends after the next deadline, every deadline before that end is skipped (counted in
 * `overruns`) and the loop waits for the first deadline at or after it: a missed period is
 * never made up by a burst of back-to-back ticks. The period is 1e9 / rate_hz ns rounded to
 * the nearest ns.
 *
 * Statistics scheme (mutex, the RT thread never blocks). The loop keeps the statistics in a
 * `live` block guarded by a mutex. Each tick it only TRY-locks it: on success it merges the
 * tick; if a reader holds the lock it parks the tick's numbers in a small private `pending`
 * block (counters plus up to QO_STREAMER_PENDING latency samples; more are counted in
 * `stats_dropped`) and merges them on the next successful try-lock. Readers
 * (qo_streamer_stats_read) lock normally and copy; they hold the lock for a copy of a few
 * kilobytes only, so a parked tick is rare. Consequently a reader may see statistics that lag
 * the loop by a few ticks, never torn ones.
 *
 * Stop. The stop flag is a `volatile sig_atomic_t` written with a plain store, so setting it
 * from a SIGINT/SIGTERM handler is async-signal-safe. A signal interrupting clock_nanosleep
 * makes the loop re-check the flag at once (sleeps are never restarted by SA_RESTART).
 * The loop exits before the next sample; qo_streamer_run then calls qo_streamer_finish, which
 * writes the LAST SUCCESSFULLY SAMPLED TARGET to the sink once more, with the next tick number.
 * That is the defined final target: the sink holds where the motion was when it stopped.
 *
 * Failures inside a tick never stop the loop: a sampler error makes the tick send the last
 * good target again (hold; nothing is sent if no sample ever succeeded) and counts
 * `sample_errors`; a sink error counts `sink_errors` and `sink_errors_consecutive`.
 */
#ifndef QORIENT_STREAMER_H
#define QORIENT_STREAMER_H

#include <pthread.h>
#include <signal.h>
#include <stddef.h>
#include <stdint.h>

#include "qorient/sink.h"
#include "qorient/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The consumer of joint targets is a qo_sink (qorient/sink.h): write() gets the n targets of
 * one tick and the tick number; service() (optional) is called after the tick's deadline work. */

/*
 * Producer: write the n joint targets for time t_seconds (seconds since the streamer's time
 * origin) into targets. Returns QO_OK, or an error status (the streamer then holds the last
 * good target).
 */
typedef qo_status (*qo_streamer_sample_fn)(void *ctx, double t_seconds, float *targets, size_t n);

/* ---- wake-latency histogram ------------------------------------------------------------ */

/*
 * Fixed-size histogram of wake latencies (actual wake time minus the absolute deadline, ns):
 * bins 0..1023 are 1 us wide (0 to 1.024 ms), bins 1024..2047 are 64 us wide (up to 66.56 ms),
 * the last bin also takes everything above. `max_ns` keeps the exact maximum.
 */
#define QO_STREAMER_JITTER_FINE_BINS 1024u
#define QO_STREAMER_JITTER_COARSE_BINS 1024u
#define QO_STREAMER_JITTER_BINS (QO_STREAMER_JITTER_FINE_BINS + QO_STREAMER_JITTER_COARSE_BINS)
#define QO_STREAMER_JITTER_FINE_NS 1000u    /* width of a fine bin */
#define QO_STREAMER_JITTER_COARSE_NS 64000u /* width of a coarse bin */

typedef struct qo_streamer_jitter_hist {
    uint32_t bin[QO_STREAMER_JITTER_BINS];
    uint64_t count;
    uint64_t max_ns;
} qo_streamer_jitter_hist;

/* Empties h. NULL is ignored. */
void qo_streamer_jitter_hist_reset(qo_streamer_jitter_hist *h);

/* Adds one latency (ns) to h; a bin saturates at UINT32_MAX instead of wrapping. NULL ignored. */
void qo_streamer_jitter_hist_add(qo_streamer_jitter_hist *h, uint64_t latency_ns);

/*
 * Nearest-rank percentile: the q-quantile sample is the one of rank ceil(q * count) (rank 1 for
 * q = 0). *out_ns is the LOWER edge of the bin holding it, so the true value v satisfies
 * *out_ns <= v < *out_ns + bin width (1 us below 1.024 ms, 64 us above); for the overflow bin
 * and for q = 1 the exact max_ns is returned instead.
 * q in [0, 1]. Returns QO_OK; QO_E_NULL (h or out_ns NULL), QO_E_RANGE (q outside [0,1] or
 * NaN), QO_E_TOO_FEW (empty histogram). *out_ns is 0 on every error.
 */
qo_status qo_streamer_jitter_hist_percentile(const qo_streamer_jitter_hist *h, double q,
                                             uint64_t *out_ns);

/* ---- streamer ---------------------------------------------------------------------------- */

#define QO_STREAMER_MAX_JOINTS 64u
#define QO_STREAMER_PENDING 32u

/* Injected time source: monotonic nanoseconds. */
typedef uint64_t (*qo_streamer_clock_now_fn)(void *ctx);
/* Injected sleep to an absolute time of the same clock: 0 when reached, EINTR if interrupted. */
typedef int (*qo_streamer_clock_sleep_until_fn)(void *ctx, uint64_t abs_ns);

typedef struct qo_streamer_config {
    double rate_hz;               /* ticks per second, (0, 100000]; default 500 */
    size_t n_joints;              /* 1..QO_STREAMER_MAX_JOINTS */
    qo_streamer_sample_fn sample; /* required */
    void *sample_ctx;
    qo_sink sink;                 /* sink.write required */
    int rt_priority;              /* SCHED_FIFO priority 1..99 for run/start; 0 = leave the policy alone */
    int lock_memory;              /* nonzero: mlockall(MCL_CURRENT|MCL_FUTURE) in run/start */
    qo_streamer_clock_now_fn now; /* NULL: CLOCK_MONOTONIC */
    qo_streamer_clock_sleep_until_fn sleep_until; /* NULL: clock_nanosleep(CLOCK_MONOTONIC,
                                                     TIMER_ABSTIME) */
    void *clock_ctx;
} qo_streamer_config;

/* Statistics, as copied out by qo_streamer_stats_read. Latencies in ns. */
typedef struct qo_streamer_stats {
    uint64_t ticks;                /* ticks executed (each one sampled and wrote, or tried to) */
    uint64_t overruns;             /* deadlines skipped because they had passed */
    uint64_t overrun_events;       /* ticks whose work ended after the next deadline */
    uint64_t sink_errors;          /* sink writes that returned an error */
    uint64_t sink_errors_consecutive; /* current run of failed writes (0 after a good one) */
    uint64_t sample_errors;        /* sampler calls that returned an error */
    uint64_t stats_dropped;        /* latency samples lost because a reader held the lock long */
    uint64_t lat_count;            /* latency samples in the histogram */
    uint64_t lat_p50_ns, lat_p99_ns, lat_max_ns; /* wake latency: nearest-rank, bin resolution */
    uint64_t period_err_max_ns;    /* max |interval between consecutive ticks - period|, skips excluded */
    uint64_t span_ns;              /* every deadline in [origin, origin + span_ns) was a tick or an
                                    * overrun: ticks + overruns == span_ns / period (qo_streamer_run
                                    * also counts the deadlines that passed before it saw the stop) */
    uint64_t origin_ns;            /* the clock's time of trajectory time 0 (cfg.now's clock) */
} qo_streamer_stats;

/* RT setup outcome flags (qo_streamer_rt_report). */
#define QO_STREAMER_RT_FIFO 1u     /* SCHED_FIFO was set */
#define QO_STREAMER_RT_MLOCK 2u    /* mlockall succeeded */

/* Everything is inside (no allocation); treat the members as private. */
typedef struct qo_streamer {
    qo_streamer_config cfg;
    uint64_t period_ns;
    uint64_t origin_ns;            /* trajectory time 0 */
    uint64_t next_ns;              /* next absolute deadline */
    uint64_t last_wake_ns;
    int have_last_wake;
    uint64_t tick_no;
    int have_target;
    float target[QO_STREAMER_MAX_JOINTS];
    float scratch[QO_STREAMER_MAX_JOINTS];
    volatile sig_atomic_t stop;
    int initialised;
    /* statistics: live under `lock`, pending private to the loop thread */
    pthread_mutex_t lock;
    qo_streamer_stats live;
    qo_streamer_jitter_hist hist;
    qo_streamer_stats pend;
    uint64_t pend_lat[QO_STREAMER_PENDING];
    uint32_t pend_n;
    /* RT setup */
    unsigned rt_flags;
    char rt_warning[160];
    pthread_t thread;
    int thread_started;
    qo_status run_status;
} qo_streamer;

/*
 * Defaults, copied by value (cfg = qo_streamer_config_default): 500 Hz, SCHED_FIFO priority
 * 80, mlockall on, real clock, no sampler or sink (the caller sets sample, sink and n_joints).
 * The ports' one defaults idiom, as qo_modbus_sink_settings_default and the core's
 * qo_motion_settings_default.
 */
extern const qo_streamer_config qo_streamer_config_default;

/*
 * Checks cfg and prepares s: the time origin and the first deadline are set to now (the
 * first tick runs at once), statistics zeroed, stop flag clear. No thread, no RT change.
 * Returns QO_OK; QO_E_NULL (s, cfg, cfg->sample or cfg->sink.write NULL), QO_E_LIMIT
 * (rate_hz not finite or outside (0, 100000]), QO_E_TOO_FEW (n_joints 0), QO_E_CAPACITY
 * (n_joints > QO_STREAMER_MAX_JOINTS), QO_E_RANGE (rt_priority outside 0..99), QO_E_IO
 * (the mutex could not be created). On error s is left not initialised (qo_streamer_tick
 * then returns QO_E_STATE). s must not be initialised twice without qo_streamer_join.
 */
qo_status qo_streamer_init(qo_streamer *s, const qo_streamer_config *cfg);

/*
 * One period: sleeps until the next deadline (returning early if the stop flag is set),
 * samples at the actual wake time, writes to the sink, calls sink.service, then advances the
 * deadline, skipping (and counting) every deadline already in the past.
 * Returns QO_OK when the tick ran and both sample and write succeeded; the sampler's or the
 * sink's status when one failed (the tick still counts; see the header comment for the hold);
 * QO_E_STATE if s is not initialised or the stop flag is set (nothing sampled or written);
 * QO_E_NULL if s is NULL.
 */
qo_status qo_streamer_tick(qo_streamer *s);

/*
 * The loop in the calling thread: best-effort RT setup (SCHED_FIFO at cfg.rt_priority,
 * mlockall, stack prefault; failures only leave a warning, see qo_streamer_rt_report), resets
 * the time origin and deadline to now, ticks until the stop flag is set, then
 * qo_streamer_finish. Returns the status of the final write (QO_OK normally; QO_E_STATE if no
 * sample ever succeeded so nothing was sent); QO_E_NULL / QO_E_STATE for a NULL or
 * uninitialised s.
 */
qo_status qo_streamer_run(qo_streamer *s);

/*
 * qo_streamer_run in a new thread. Returns QO_OK; QO_E_NULL; QO_E_STATE (not initialised or
 * already started); QO_E_IO (pthread_create failed).
 */
qo_status qo_streamer_start(qo_streamer *s);

/*
 * Waits for the thread of qo_streamer_start (set the stop flag first) and returns what its
 * qo_streamer_run returned; QO_E_NULL; QO_E_STATE if no thread was started.
 */
qo_status qo_streamer_join(qo_streamer *s);

/* Sets the stop flag. Async-signal-safe (one sig_atomic_t store). NULL ignored. */
void qo_streamer_request_stop(qo_streamer *s);

/* The stop flag, for a signal handler of the application's own: `*flag = 1` stops. NULL for NULL. */
volatile sig_atomic_t *qo_streamer_stop_flag(qo_streamer *s);

/*
 * Installs SIGINT and SIGTERM handlers (sigaction, no SA_RESTART) that set s's stop flag.
 * One streamer per process can be the target (a later call replaces it). Returns QO_OK,
 * QO_E_NULL, or QO_E_IO if sigaction failed.
 */
qo_status qo_streamer_install_stop_signals(qo_streamer *s);

/*
 * Writes the defined final target (the last successfully sampled one) to the sink with the
 * next tick number. Returns the sink's status; QO_E_STATE if nothing was ever sampled (no
 * write happens) or s is not initialised; QO_E_NULL.
 */
qo_status qo_streamer_finish(qo_streamer *s);

/*
 * The scheduled time of the tick in progress: its absolute deadline minus the time origin, in
 * ns (k * period for a tick on the k-th deadline; the sampler is given the actual wake time,
 * this is when the tick was due). Meant for the sampler and the sink's write, called from
 * them in the streamer's thread; during the final write of qo_streamer_finish it is the first
 * deadline after the stop. Returns QO_OK; QO_E_NULL (s or deadline_ns NULL); QO_E_STATE (not
 * initialised). *deadline_ns is 0 on every error (when not NULL).
 */
qo_status qo_streamer_tick_deadline(const qo_streamer *s, uint64_t *deadline_ns);

/*
 * Copies the statistics into *out (percentiles computed from the histogram). Safe from any
 * thread while the loop runs (it takes the statistics mutex). Returns QO_OK; QO_E_NULL (out
 * is then untouched if NULL, zeroed if s is NULL); QO_E_STATE (not initialised; *out zeroed).
 */
qo_status qo_streamer_stats_read(qo_streamer *s, qo_streamer_stats *out);

/*
 * What the last RT setup achieved: returns the QO_STREAMER_RT_* flags and, if warning is not
 * NULL, points it at a constant-until-next-run text ("" when everything succeeded, else e.g.
 * "SCHED_FIFO 80: Operation not permitted; running SCHED_OTHER"). 0 for NULL s.
 */
unsigned qo_streamer_rt_report(const qo_streamer *s, const char **warning);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_STREAMER_H */
