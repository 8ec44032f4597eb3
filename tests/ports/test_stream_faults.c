/*
 * Fault injection end to end: the streamer (real time, its own thread, 200 Hz on TCP) samples
 * a keyframe trajectory of six joints (a C2 spline, qorient/spline.h) and hands it to the
 * Modbus sink, which drives the simulated drive bank (lag 0) over loopback TCP or RTU over a
 * pseudo-terminal pair. Each scenario injects one kind of fault while the trajectory moves:
 *   clean       no fault (the noise floor of a loaded machine);
 *   absent      no drive at start: the simulator appears 0.6 s after the stream began;
 *   restart     the simulator is stopped mid-stream and a new one (fresh registers, position
 *               0) starts on the SAME port 0.3 s later;
 *   delay       4 replies delayed 20 ms, past the 3 ms response timeout (late replies);
 *   exception   6 requests answered with exception 0x04 (nothing applied);
 *   pulled      a TCP proxy between sink and drive black-holes every byte for 2 s (a pulled
 *               cable: no RST, only silence; the drive keeps its state);
 *   rtu garbage junk bytes before two replies and before two requests on an RTU line
 *               (200 Hz, 3 ms timeout, as on TCP: late replies are frequent there);
 *   SIGINT      SIGINT through qo_streamer_install_stop_signals at 0.8 s, mid-motion.
 * For every scenario the test checks:
 *   period   every deadline is either a tick or a counted overrun: ticks + overruns equals
 *            the span the streamer accounted for / period, and that span ends after the stop
 *            was requested and before the join returned (nothing made up in a burst, nothing
 *            lost uncounted). Checked against the streamer's own account, so a loaded machine
 *            cannot fail it; how many deadlines were overruns is timing, printed, not asserted
 *            (bench/bench_jitter.c measures it);
 *   reported the failures are in the streamer's statistics (sink_errors, one per failed
 *            tick) and in the sink's own counter for that fault (timeouts, exceptions,
 *            silences, failed opens, bad frames);
 *   recovery the simulator holds the final targets (to the register resolution, 0.5e-3
 *            rad) at the end, which only writes after the fault can have put there; for
 *            SIGINT it holds the last sampled target (the streamer's defined final target);
 *   steps    the simulator's CSV log of every target it received shows no step above the
 *            joint's max_step, for every joint, from each simulator instance's initial
 *            position (0) on, across the whole run.
 * "Ticks lost" = ticks whose write failed or was held back + deadlines skipped as overruns;
 * printed per scenario and per fault, with the totals at the end.
 *
 * Application recipe exercised here (struct app below). qo_modbus_sink_open fails at once
 * when no drive answers, so the application opens lazily from the sink's service hook and
 * retries. After that the sink is kept for the whole run: after its own reconnection it reads
 * every joint's target registers back before writing (modbus_sink.h), so a drive that
 * restarted and lost its target is walked from what it holds at max_step per tick.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <pty.h>
#include <signal.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <arpa/inet.h>
#include <sys/socket.h>
#include <cmocka.h>

#include "common/linux/relay.h"
#include "common/linux/sim_log.h"
#include "linux/modbus_sink.h"
#include "linux/sim.h"
#include "linux/streamer.h"
#include "qorient/spline.h"

#define NJ 6
#define NKEYS 4
#define RATE_HZ 200.0       /* TCP scenarios */
#define T_TRAJ 1.5          /* s: the trajectory ends (and holds the final targets) here */
#define T_FAULT 0.6         /* s: faults start here */
#define RESOLUTION 0.5e-3   /* half a register unit (scale 1000) */

static qo_regmap map; /* large: keep off the stack */

/* Totals over every scenario, printed by main. */
static uint64_t g_faults, g_survived_faults, g_lost, g_steps_over, g_scenarios;

static double mono_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static void sleep_until_s(double t)
{
    for (;;) {
        double d = t - mono_s();
        struct timespec ts;
        if (d <= 0.0) return;
        ts.tv_sec = (time_t)d;
        ts.tv_nsec = (long)((d - (double)ts.tv_sec) * 1e9);
        nanosleep(&ts, NULL);
    }
}

static void load_six(void)
{
    char err[256];
    qo_status st = qo_regmap_load("examples/maps/six_int32.ini", &map, err, sizeof err);
    if (st != QO_OK) fail_msg("map: %s", err);
}

static double final_target(size_t i)
{
    return 0.3 * (double)(i + 1) - 1.0;
}

/* ---- trajectory: a C2 spline through four keys, from 0 (the drives' start) to the final
 * targets at T_TRAJ. Peak step ~0.04 rad per 5 ms tick, under max_step (0.05), so the rate
 * limit only acts when the stream catches up after a fault. ---------------------------- */

struct traj {
    qo_spline_f32 sp;
    float coef[NKEYS + 3 * NJ + 6 * NKEYS * NJ];
};

static void traj_init(struct traj *tr)
{
    float t[NKEYS] = { 0.0f, (float)(T_TRAJ / 3.0), (float)(2.0 * T_TRAJ / 3.0), (float)T_TRAJ };
    float p[NKEYS * NJ];
    size_t j;
    for (j = 0; j < NJ; j++) {
        double a = 0.9 + 0.1 * (double)j;
        p[0 * NJ + j] = 0.0f;
        p[1 * NJ + j] = (float)a;
        p[2 * NJ + j] = (float)-a;
        p[3 * NJ + j] = (float)final_target(j);
    }
    assert_true(qo_spline_coef_len(NJ, NKEYS) <= sizeof tr->coef / sizeof tr->coef[0]);
    assert_int_equal(qo_spline_init_f32(NJ, NKEYS, t, p, &qo_spline_settings_default, tr->coef,
                                        sizeof tr->coef / sizeof tr->coef[0], &tr->sp),
                     QO_OK);
}

static qo_status traj_sample(void *ctx, double t, float *out, size_t n)
{
    const struct traj *tr = ctx;
    if (n != NJ) return QO_E_RANGE;
    return qo_spline_sample_f32(&tr->sp, (float)t, out, NULL, NULL, NULL);
}

/* ---- the application's sink: lazy open, re-seed after every (re)connection -------------- */

struct app {
    char spec[128];
    qo_modbus_sink_settings set;
    qo_modbus_sink *ms;
    double next_open_s;
    uint64_t open_failures;
    qo_status open_error;       /* what the first failed open returned */
    /* the sink's counters, copied at the end */
    uint64_t opens, reconnects, timeouts, exceptions, protocol_errors, disconnects, actions;
    uint64_t silences;
    uint64_t requests_failed, rate_limited, readbacks;
    /* per-tick record, written by the streamer thread, read after the join */
    uint64_t writes, fails, held;
    uint64_t last_fail_tick;
    qo_status last_status;
    float last_written[NJ];
};

static void app_init(struct app *a, const char *spec)
{
    memset(a, 0, sizeof *a);
    snprintf(a->spec, sizeof a->spec, "%s", spec);
    a->set = qo_modbus_sink_settings_default;
    /* Below the 5 ms period: a tick that times out still ends before the next deadline
     * (a stale reply can cost a second bounded receive, see modbus_sink.h). */
    a->set.response_timeout_us = 3000;
    a->set.byte_timeout_us = 2000;
    a->set.fail_threshold = 3;
    a->set.reconnect_min_us = 5000;
    a->set.reconnect_max_us = 40000;
    a->open_error = QO_OK;
    a->last_status = QO_OK;
}

static qo_status app_write(void *ctx, const float *targets, size_t n, uint64_t tick)
{
    struct app *a = ctx;
    qo_status st;
    a->writes++;
    if (n == NJ) memcpy(a->last_written, targets, sizeof a->last_written);
    if (a->ms == NULL) {
        st = QO_E_DISCONNECTED; /* nothing sent: the drive holds what it has */
        a->held++;
    } else {
        st = qo_modbus_sink_write(a->ms, targets, n, tick);
    }
    if (st != QO_OK) {
        a->fails++;
        a->last_fail_tick = tick;
    }
    a->last_status = st;
    return st;
}

static void app_service(void *ctx)
{
    struct app *a = ctx;
    if (a->ms == NULL) {
        double now = mono_s();
        qo_status os;
        if (now < a->next_open_s) return;
        os = qo_modbus_sink_open(a->spec, &map, &a->set, &a->ms);
        if (os != QO_OK) {
            if (a->open_failures++ == 0) a->open_error = os;
            a->next_open_s = now + 0.02;
            return;
        }
        a->opens++; /* open seeded every joint's rate limit from its feedback registers */
        return;
    }
    (void)qo_modbus_sink_service(a->ms);
}

/* ---- a TCP proxy that can black-hole the link (the pulled cable) ------------------------ */

struct proxy {
    int lfd, cfd, ufd;
    int port, up_port;
    int pulled, stop;
    uint64_t dropped;
    pthread_t th;
    pthread_mutex_t mu;
};

static void proxy_drop_pair(struct proxy *p)
{
    if (p->cfd >= 0) close(p->cfd);
    if (p->ufd >= 0) close(p->ufd);
    p->cfd = p->ufd = -1;
}

static void *proxy_main(void *arg)
{
    struct proxy *p = arg;
    for (;;) {
        struct pollfd pf[3];
        uint8_t buf[512];
        int i, np = 1, stop, pulled, one = 1;
        pthread_mutex_lock(&p->mu);
        stop = p->stop;
        pulled = p->pulled;
        pthread_mutex_unlock(&p->mu);
        if (stop) break;
        pf[0].fd = p->lfd;
        pf[0].events = POLLIN;
        pf[0].revents = 0;
        if (p->cfd >= 0) {
            pf[1].fd = p->cfd;
            pf[2].fd = p->ufd;
            pf[1].events = pf[2].events = POLLIN;
            pf[1].revents = pf[2].revents = 0;
            np = 3;
        }
        if (poll(pf, (nfds_t)np, 10) <= 0) continue;
        if (pf[0].revents & POLLIN) {
            int fd = accept(p->lfd, NULL, NULL);
            struct sockaddr_in up;
            if (fd < 0) continue;
            proxy_drop_pair(p); /* one master at a time, like the simulator */
            p->cfd = fd;
            (void)setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
            p->ufd = socket(AF_INET, SOCK_STREAM, 0);
            if (p->ufd >= 0)
                (void)setsockopt(p->ufd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
            memset(&up, 0, sizeof up);
            up.sin_family = AF_INET;
            up.sin_port = htons((uint16_t)p->up_port);
            up.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
            if (p->ufd < 0 || connect(p->ufd, (struct sockaddr *)&up, sizeof up) != 0)
                proxy_drop_pair(p);
            continue;
        }
        for (i = 1; i < np; i++) {
            ssize_t n;
            int to;
            if (!(pf[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            n = read(pf[i].fd, buf, sizeof buf);
            if (n <= 0) {
                proxy_drop_pair(p);
                break;
            }
            if (pulled) {
                pthread_mutex_lock(&p->mu);
                p->dropped += (uint64_t)n;
                pthread_mutex_unlock(&p->mu);
                continue;
            }
            to = i == 1 ? p->ufd : p->cfd;
            if (write(to, buf, (size_t)n) != n) {
                proxy_drop_pair(p);
                break;
            }
        }
    }
    proxy_drop_pair(p);
    return NULL;
}

static void proxy_open(struct proxy *p, int up_port)
{
    struct sockaddr_in a;
    socklen_t al = sizeof a;
    int one = 1;
    memset(p, 0, sizeof *p);
    p->cfd = p->ufd = -1;
    p->up_port = up_port;
    pthread_mutex_init(&p->mu, NULL);
    p->lfd = socket(AF_INET, SOCK_STREAM, 0);
    assert_true(p->lfd >= 0);
    (void)setsockopt(p->lfd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    assert_int_equal(bind(p->lfd, (struct sockaddr *)&a, sizeof a), 0);
    assert_int_equal(listen(p->lfd, 4), 0);
    assert_int_equal(getsockname(p->lfd, (struct sockaddr *)&a, &al), 0);
    p->port = ntohs(a.sin_port);
    assert_int_equal(pthread_create(&p->th, NULL, proxy_main, p), 0);
}

static void proxy_set_pulled(struct proxy *p, int pulled)
{
    pthread_mutex_lock(&p->mu);
    p->pulled = pulled;
    pthread_mutex_unlock(&p->mu);
}

static void proxy_close(struct proxy *p)
{
    pthread_mutex_lock(&p->mu);
    p->stop = 1;
    pthread_mutex_unlock(&p->mu);
    pthread_join(p->th, NULL);
    close(p->lfd);
    pthread_mutex_destroy(&p->mu);
}

/* ---- RTU over two pty pairs joined by a relay that can inject garbage
 * (tests/common/linux/relay.c, shared with test_modbus_sink.c) ----------------------------- */

static const uint8_t k_junk[5] = { 0x5A, 0xA5, 0x11, 0xFF, 0x00 };

/* ---- simulator and its log -------------------------------------------------------------- */

static qo_sim *sim_start(const char *spec, FILE *log)
{
    qo_sim *sim = NULL;
    qo_sim_settings ss = qo_sim_settings_default;
    ss.log = log;
    ss.lag_s = 0.0; /* feedback = the target the drive holds (see the header) */
    ss.seed = 11;
    if (qo_sim_start(spec, &map, &ss, &sim) != QO_OK) fail_msg("simulator on %s", spec);
    return sim;
}

/* Every step in the simulator's log, per joint, within max_step; each header line starts a
 * new simulator instance, whose joints start at 0. Returns the worst step/max_step ratio and
 * counts the steps above the limit (each one also fails the test, after counting). */
static double check_log(FILE *log, const char *what, unsigned *lines, unsigned *instances,
                        unsigned *over)
{
    double last[NJ];
    sim_log_result r;
    assert_true(map.n_joints <= NJ);
    sim_log_steps(log, &map, what, last, &r); /* tests/common/linux/sim_log.c */
    *lines = r.lines;
    *instances = r.instances;
    *over = r.over;
    return r.worst;
}

/* ---- one scenario ----------------------------------------------------------------------- */

enum scen { S_CLEAN, S_ABSENT, S_RESTART, S_DELAY, S_EXCEPTION, S_PULLED, S_RTU_GARBAGE,
            S_SIGINT };

static const char *scen_name[] = { "clean", "absent at start", "restart mid-stream",
                                   "delay past timeout", "exceptions", "pulled 2 s",
                                   "rtu garbage", "SIGINT mid-motion" };

static void run_scenario(enum scen sc)
{
    const char *what = scen_name[sc];
    FILE *log = tmpfile();
    struct traj tr;
    struct app app;
    struct proxy px;
    struct relay rl;
    qo_sim *sim = NULL;
    qo_streamer str;
    qo_streamer_config cfg;
    qo_streamer_stats ss;
    qo_modbus_sink_stats ms;
    qo_sim_stats sst;
    char spec[128], sim_spec[128];
    double t0, t_stop, t_req = 0.0, elapsed, worst;
    uint64_t faults = 0, deadlines, lost;
    unsigned lines, instances, over;
    qo_status run_st;
    size_t i;
    int port = 0, mid_motion = 0;
    double rate = RATE_HZ;

    assert_non_null(log);
    load_six();
    traj_init(&tr);
    memset(&ms, 0, sizeof ms);
    memset(&sst, 0, sizeof sst);
    t_stop = T_TRAJ + 1.0;

    /* the drive side */
    if (sc == S_RTU_GARBAGE) {
        relay_open(&rl, k_junk, sizeof k_junk);
        snprintf(sim_spec, sizeof sim_spec, "rtu:%s,115200,8N1", rl.path_a);
        sim = sim_start(sim_spec, log);
        snprintf(spec, sizeof spec, "rtu:%s,115200,8N1", rl.path_b);
    } else {
        sim = sim_start("tcp://127.0.0.1:0", sc == S_ABSENT ? NULL : log);
        port = qo_sim_port(sim);
        assert_true(port > 0);
        snprintf(sim_spec, sizeof sim_spec, "tcp://127.0.0.1:%d", port);
        snprintf(spec, sizeof spec, "tcp://127.0.0.1:%d", port);
        if (sc == S_PULLED) {
            proxy_open(&px, port);
            snprintf(spec, sizeof spec, "tcp://127.0.0.1:%d", px.port);
            t_stop = T_FAULT + 2.0 + 1.0;
        }
        if (sc == S_ABSENT) {
            /* keep the port number, free the port: nobody answers at start */
            qo_sim_stop(sim);
            sim = NULL;
        }
    }

    /* the application opens the sink from the first tick's service hook (and retries) */
    app_init(&app, spec);
    /* RTU runs at the TCP settings (200 Hz, 3 ms): through two ptys and a relay thread (three
     * threads per request) on a loaded machine, replies after the timeout are frequent. That
     * is the case the sink's read-back is for: before it, a late reply taken for the answer to
     * a lost request sent steps of 2 x max_step to the drive in most runs (RTU replies carry
     * no transaction id). It was a stress option (QO_STRESS_RTU) then; it is the default now. */
    if (sc == S_SIGINT) app.set.response_timeout_us = 20000; /* the final write must land */

    cfg = qo_streamer_config_default;
    cfg.rate_hz = rate;
    cfg.n_joints = NJ;
    cfg.sample = traj_sample;
    cfg.sample_ctx = &tr;
    cfg.sink.ctx = &app;
    cfg.sink.write = app_write;
    cfg.sink.service = app_service;
    cfg.rt_priority = 0;
    cfg.lock_memory = 0;
    assert_int_equal(qo_streamer_init(&str, &cfg), QO_OK);
    if (sc == S_SIGINT) assert_int_equal(qo_streamer_install_stop_signals(&str), QO_OK);
    t0 = mono_s();
    assert_int_equal(qo_streamer_start(&str), QO_OK);

    /* the fault timeline (seconds after the start) */
    sleep_until_s(t0 + T_FAULT);
    switch (sc) {
    case S_CLEAN:
        break;
    case S_ABSENT:
        sim = sim_start(sim_spec, log);
        assert_int_equal(qo_sim_port(sim), port);
        faults = 1;
        break;
    case S_RESTART:
        qo_sim_stop(sim);
        sleep_until_s(t0 + T_FAULT + 0.3);
        sim = sim_start(sim_spec, log);
        assert_int_equal(qo_sim_port(sim), port);
        faults = 1;
        break;
    case S_DELAY: {
        qo_sim_fault f = { QO_SIM_FAULT_DELAY, 20, 0.0, 1, 4 };
        assert_int_equal(qo_sim_set_fault(sim, &f), QO_OK);
        break;
    }
    case S_EXCEPTION: {
        qo_sim_fault f = { QO_SIM_FAULT_EXCEPTION, 0, 0.0, 1, 6 };
        assert_int_equal(qo_sim_set_fault(sim, &f), QO_OK);
        break;
    }
    case S_PULLED:
        proxy_set_pulled(&px, 1);
        sleep_until_s(t0 + T_FAULT + 2.0);
        proxy_set_pulled(&px, 0);
        faults = 1;
        break;
    case S_SIGINT:
        sleep_until_s(t0 + 0.8); /* mid-motion: the targets are far from the final ones */
        t_req = mono_s() - t0;
        raise(SIGINT);
        faults = 1;
        break;
    case S_RTU_GARBAGE:
        relay_junk(&rl, 1);
        sleep_until_s(t0 + T_FAULT + 0.2);
        relay_junk(&rl, 1);
        sleep_until_s(t0 + T_FAULT + 0.4);
        relay_junk(&rl, 0);
        sleep_until_s(t0 + T_FAULT + 0.6);
        relay_junk(&rl, 0);
        break;
    }

    if (sc != S_SIGINT) {
        sleep_until_s(t0 + t_stop);
        t_req = mono_s() - t0;
        qo_streamer_request_stop(&str);
    }
    run_st = qo_streamer_join(&str);
    elapsed = mono_s() - t0;
    if (sc == S_SIGINT) {
        struct sigaction dfl;
        memset(&dfl, 0, sizeof dfl);
        dfl.sa_handler = SIG_DFL;
        sigaction(SIGINT, &dfl, NULL);
        sigaction(SIGTERM, &dfl, NULL);
    }
    assert_int_equal(qo_streamer_stats_read(&str, &ss), QO_OK);
    if (app.ms != NULL) {
        assert_int_equal(qo_modbus_sink_get_stats(app.ms, &ms), QO_OK);
        app.timeouts += ms.timeouts;
        app.exceptions += ms.exceptions;
        app.protocol_errors += ms.protocol_errors;
        app.disconnects += ms.disconnects;
        app.actions += ms.actions;
        app.silences += ms.silences;
        app.requests_failed += ms.requests_failed;
        app.rate_limited += ms.rate_limited;
        app.reconnects += ms.common.reconnects;
        app.readbacks += ms.readbacks;
    }
    assert_non_null(sim);
    assert_int_equal(qo_sim_get_stats(sim, &sst), QO_OK);
    if (sc == S_DELAY || sc == S_EXCEPTION) faults = sst.faults;
    if (sc == S_RTU_GARBAGE) {
        pthread_mutex_lock(&rl.mu);
        faults = rl.injected;
        pthread_mutex_unlock(&rl.mu);
    }

    /* recovery: after the fault the stream reached the drive again and brought it to the
     * final targets (the trajectory ends at T_TRAJ; only writes after the fault can have put
     * them there). The last tick's and the final write's status are printed, not asserted:
     * on a loaded machine any single request may time out. */
    for (i = 0; i < NJ; i++) {
        double tgt, pos;
        assert_int_equal(qo_sim_get_joint(sim, i, &tgt, &pos), QO_OK);
        if (sc == S_SIGINT) {
            /* the defined final target: the last sampled one, written once more by
             * qo_streamer_run after the signal, and held by the drive */
            double d = fabs(tgt - (double)app.last_written[i]);
            /* exactly (to the resolution); when a spurious failure on a loaded machine put
             * the rate limit in play, the drive is still on its way there and only the
             * final write's status is checked */
            if (run_st != QO_OK || (app.rate_limited == 0 && d > RESOLUTION + 1e-7))
                fail_msg("%s: final write %s; joint %zu holds %.9g, last sampled %.9g (rate "
                         "limited %llu)", what, qo_status_str(run_st), i, tgt,
                         (double)app.last_written[i], (unsigned long long)app.rate_limited);
            if (fabs(tgt - final_target(i)) > 0.1) mid_motion = 1;
        } else if (fabs(tgt - final_target(i)) > RESOLUTION + 1e-12) {
            fail_msg("%s: joint %zu holds %.9g, final target %.9g (final write %s, last tick "
                     "%s; timeouts %llu, disconnects %llu, reconnections %llu, opens %llu, "
                     "failed opens %llu (first %s), failed requests %llu)",
                     what, i, tgt, final_target(i), qo_status_str(run_st),
                     qo_status_str(app.last_status), (unsigned long long)app.timeouts,
                     (unsigned long long)app.disconnects, (unsigned long long)app.reconnects,
                     (unsigned long long)app.opens, (unsigned long long)app.open_failures,
                     qo_status_str(app.open_error), (unsigned long long)app.requests_failed);
        }
    }
    if (sc == S_SIGINT && !mid_motion) fail_msg("%s: stopped too late to tell", what);

    /* reported */
    /* the streamer counts the ticks' failed writes; the app also saw the final write */
    if (sc != S_CLEAN && sc != S_SIGINT &&
        (ss.sink_errors == 0 || app.fails != ss.sink_errors + (app.last_status != QO_OK)))
        fail_msg("%s: %llu sink errors in the streamer's statistics, %llu failed writes", what,
                 (unsigned long long)ss.sink_errors, (unsigned long long)app.fails);
    switch (sc) {
    case S_ABSENT:
        if (app.open_failures == 0 || app.open_error != QO_E_DISCONNECTED)
            fail_msg("%s: %llu failed opens, last %s", what,
                     (unsigned long long)app.open_failures, qo_status_str(app.open_error));
        break;
    case S_RESTART:
        /* One open: the sink itself reconnects and reads the restarted drive's targets
         * back (no application-level re-open). */
        if (app.disconnects == 0 || app.reconnects == 0 || app.opens != 1 || app.readbacks == 0)
            fail_msg("%s: disconnects %llu reconnections %llu opens %llu read-backs %llu", what,
                     (unsigned long long)app.disconnects, (unsigned long long)app.reconnects,
                     (unsigned long long)app.opens, (unsigned long long)app.readbacks);
        break;
    case S_DELAY:
        if (faults < 4 || app.timeouts == 0) fail_msg("%s: faults %llu, timeouts %llu", what,
                                                     (unsigned long long)faults,
                                                     (unsigned long long)app.timeouts);
        break;
    case S_EXCEPTION:
        if (faults < 6 || app.exceptions == 0) fail_msg("%s: faults %llu, exceptions %llu", what,
                                                       (unsigned long long)faults,
                                                       (unsigned long long)app.exceptions);
        break;
    case S_PULLED:
        /* TCP: the request stays outstanding (ticks skipped) until silence_us (1 s) passes
         * with nothing received: then the link is dropped and reconnected */
        if (app.timeouts == 0 || app.silences == 0 || app.reconnects == 0 || px.dropped == 0)
            fail_msg("%s: timeouts %llu, silences %llu, reconnects %llu, bytes black-holed %llu",
                     what, (unsigned long long)app.timeouts, (unsigned long long)app.silences,
                     (unsigned long long)app.reconnects,
                     (unsigned long long)px.dropped);
        break;
    case S_RTU_GARBAGE:
        if (faults != 4 || sst.bad_frames == 0 ||
            app.protocol_errors + app.timeouts == 0)
            fail_msg("%s: injected %llu, sim bad frames %llu, protocol errors %llu, timeouts "
                     "%llu, failed requests %llu (last %s), failed writes %llu", what,
                     (unsigned long long)faults, (unsigned long long)sst.bad_frames,
                     (unsigned long long)app.protocol_errors, (unsigned long long)app.timeouts,
                     (unsigned long long)app.requests_failed, qo_status_str(ms.last_error),
                     (unsigned long long)app.fails);
        break;
    default:
        break;
    }

    /* period: every deadline is a tick or a counted overrun (none made up, none invented).
     * Judged against the streamer's own account of the span it covered, and that span against
     * this thread's clock, so that a loaded machine (threads kept off the CPU) cannot fail it:
     * the span ends after the stop was requested and before the join returned. */
    deadlines = ss.ticks + ss.overruns;
    {
        const uint64_t period_ns = (uint64_t)(1e9 / rate + 0.5);
        const double span_end = (double)(ss.origin_ns + ss.span_ns) * 1e-9;
        if (deadlines != ss.span_ns / period_ns || ss.span_ns % period_ns != 0u)
            fail_msg("%s: %llu ticks + %llu overruns, but the span covered is %llu ns at %.0f Hz",
                     what, (unsigned long long)ss.ticks, (unsigned long long)ss.overruns,
                     (unsigned long long)ss.span_ns, rate);
        if (span_end < t0 + t_req || span_end > t0 + elapsed + 1.0 / rate)
            fail_msg("%s: deadlines accounted up to %.4f s, stop requested at %.4f s, joined at "
                     "%.4f s", what, span_end - t0, t_req, elapsed);
    }
    /* one write per tick, plus the final write of qo_streamer_run */
    if (app.writes != ss.ticks + 1u) fail_msg("%s: %llu writes for %llu ticks", what,
                                         (unsigned long long)app.writes,
                                         (unsigned long long)ss.ticks);

    /* no step above the limit, over the whole run and every simulator instance */
    if (app.ms != NULL) qo_modbus_sink_free(app.ms);
    qo_sim_stop(sim);
    if (sc == S_PULLED) proxy_close(&px);
    if (sc == S_RTU_GARBAGE) relay_close(&rl);
    worst = check_log(log, what, &lines, &instances, &over);
    g_steps_over += over;
    if (over != 0) fail_msg("%s: %u steps above max_step", what, over);
    if (lines < NJ * 50u || instances != (sc == S_RESTART ? 2u : 1u))
        fail_msg("%s: %u log lines from %u simulator instances", what, lines, instances);

    lost = ss.sink_errors + ss.overruns;
    printf("stream_faults: %-19s faults %2llu | ticks %4llu lost %3llu (failed %3llu held %3llu "
           "overruns %3llu) = %5.1f per fault | worst step %.3f x max_step | period err max "
           "%.2f ms | final write %s\n",
           what, (unsigned long long)faults, (unsigned long long)ss.ticks,
           (unsigned long long)lost, (unsigned long long)ss.sink_errors,
           (unsigned long long)app.held, (unsigned long long)ss.overruns,
           faults ? (double)lost / (double)faults : 0.0, worst,
           (double)ss.period_err_max_ns * 1e-6, qo_status_str(run_st));
    g_faults += faults;
    g_survived_faults += faults;
    g_lost += lost;
    g_scenarios++;
    fclose(log);
}

static void test_clean(void **state) { (void)state; run_scenario(S_CLEAN); }
static void test_drive_absent_at_start(void **state) { (void)state; run_scenario(S_ABSENT); }
static void test_drive_restart(void **state) { (void)state; run_scenario(S_RESTART); }
static void test_delay_past_timeout(void **state) { (void)state; run_scenario(S_DELAY); }
static void test_exceptions(void **state) { (void)state; run_scenario(S_EXCEPTION); }
static void test_pulled_connection(void **state) { (void)state; run_scenario(S_PULLED); }
static void test_rtu_garbage(void **state) { (void)state; run_scenario(S_RTU_GARBAGE); }
static void test_sigint_mid_motion(void **state) { (void)state; run_scenario(S_SIGINT); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_clean),
        cmocka_unit_test(test_drive_absent_at_start),
        cmocka_unit_test(test_drive_restart),
        cmocka_unit_test(test_delay_past_timeout),
        cmocka_unit_test(test_exceptions),
        cmocka_unit_test(test_pulled_connection),
        cmocka_unit_test(test_rtu_garbage),
        cmocka_unit_test(test_sigint_mid_motion),
    };
    int rc = cmocka_run_group_tests_name("stream_faults", tests, NULL, NULL);
    printf("stream_faults: %llu scenarios passed, faults injected %llu, survived %llu, steps "
           "above the limit %llu, ticks lost %llu\n",
           (unsigned long long)g_scenarios, (unsigned long long)g_faults,
           (unsigned long long)g_survived_faults, (unsigned long long)g_steps_over,
           (unsigned long long)g_lost);
    return rc;
}
