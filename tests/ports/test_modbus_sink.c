/* The Modbus sink against the real simulator: loopback TCP on an ephemeral port and RTU over
 * a pseudo-terminal pair joined by a relay thread (which can inject garbage bytes).
 * For every run: the simulator's log of received targets shows no step above max_step (the
 * bound is checked from the simulator's initial position onward, across every fault), the
 * stream recovers after the fault, and the final targets are reached exactly (to the
 * register resolution). Targets move faster than max_step so the limit is always in play. */
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
#include <termios.h>
#include <time.h>
#include <unistd.h>
#include <cmocka.h>

#include "common/linux/relay.h"
#include "common/linux/sim_log.h"
#include "linux/modbus_sink.h"
#include "linux/sim.h"

#define NJ 6
#define NTICKS 300
#define FINAL_TICKS 100

static qo_regmap map; /* large: keep off the stack */

/* The map from a file (text NULL) or from text (path names it in messages). */
static void load_map(const char *path, const char *text)
{
    char err[256];
    qo_status st = text == NULL ? qo_regmap_load(path, &map, err, sizeof err)
                                : qo_regmap_parse(text, path, &map, err, sizeof err);
    if (st != QO_OK) fail_msg("map %s: %s", path, err);
}

static void load_six(void)
{
    load_map("examples/maps/six_int32.ini", NULL);
}

/* cmocka setup of the tests on the six-joint example map. */
static int six_map(void **state)
{
    (void)state;
    load_six();
    return 0;
}

static qo_modbus_sink_settings test_settings(void)
{
    qo_modbus_sink_settings s = qo_modbus_sink_settings_default;
    /* Generous for loopback (replies take ~0.1 ms) so a loaded CI machine does not turn into
     * spurious timeouts; faults that must time out are longer (delay 150 ms). */
    s.response_timeout_us = 100000;
    s.byte_timeout_us = 20000;
    s.fail_threshold = 3;
    s.reconnect_min_us = 1000;
    s.reconnect_max_us = 20000;
    return s;
}

static double final_target(size_t i)
{
    return 0.3 * (double)(i + 1) - 1.0;
}

/* Targets at tick k: a fast sine (0.25 rad/tick peak, 5x max_step), then the final values. */
static void targets_at(unsigned k, float *t)
{
    size_t i;
    for (i = 0; i < NJ; i++)
        t[i] = k < NTICKS - FINAL_TICKS ? (float)(2.5 * sin(0.1 * k + (double)i))
                                        : (float)final_target(i);
}

struct run_result {
    unsigned ok, failed, last_failed_tick;
};

/* Streams NTICKS ticks, calling service after each write as a streamer does after its
 * deadline work. A service that must wait for its backoff returns at once, so a bounded
 * number of extra service calls at the end lets a pending reconnection finish. */
static struct run_result stream(qo_modbus_sink *s)
{
    struct run_result r = { 0, 0, 0 };
    unsigned k;
    float t[NJ];
    for (k = 0; k < NTICKS; k++) {
        qo_status st;
        targets_at(k, t);
        st = qo_modbus_sink_write(s, t, NJ, k);
        if (st == QO_OK) r.ok++;
        else {
            r.failed++;
            r.last_failed_tick = k;
        }
        (void)qo_modbus_sink_service(s);
    }
    return r;
}

/* Reads the simulator's CSV log: every step per joint within max_step (joint units, checked
 * in double from the decoded register values) starting from the initial position 0; returns
 * the largest step/max_step ratio and the last value per joint. */
static double check_log(FILE *log, const qo_regmap *m, double *last, unsigned *lines)
{
    sim_log_result r;
    sim_log_steps(log, m, "sim log", last, &r); /* tests/common/linux/sim_log.c */
    assert_int_equal(r.instances, 1);
    assert_int_equal(r.over, 0);
    *lines = r.lines;
    return r.worst;
}

static void check_final(qo_sim *sim, const char *what)
{
    size_t i;
    for (i = 0; i < NJ; i++) {
        double tgt, pos;
        assert_int_equal(qo_sim_get_joint(sim, i, &tgt, &pos), QO_OK);
        if (fabs(tgt - final_target(i)) > 0.5e-3 + 1e-12)
            fail_msg("%s: joint %u: simulator target %.9g, want %.9g", what, (unsigned)i, tgt,
                     final_target(i));
    }
}

/* A simulator of `map` with settings ss (NULL: defaults) on an ephemeral loopback port; its
 * address into spec. */
static qo_sim *sim_on_tcp(const qo_sim_settings *ss, char *spec, size_t spec_len)
{
    qo_sim *sim = NULL;
    assert_int_equal(qo_sim_start("tcp://127.0.0.1:0", &map, ss, &sim), QO_OK);
    assert_true(qo_sim_port(sim) > 0);
    snprintf(spec, spec_len, "tcp://127.0.0.1:%d", qo_sim_port(sim));
    return sim;
}

/* The failure pattern of a run of ticks. */
struct tick_log {
    unsigned failed, first_fail, second_fail, last_fail;
    qo_status first_status, second_status;
};

static void note_tick(struct tick_log *tl, unsigned k, qo_status st)
{
    if (st == QO_OK) return;
    if (tl->failed == 0) {
        tl->first_fail = k;
        tl->first_status = st;
    } else if (tl->failed == 1) {
        tl->second_fail = k;
        tl->second_status = st;
    }
    tl->failed++;
    tl->last_fail = k;
}

/* One sink against one simulator, the setup nearly every test starts with and the teardown
 * it ends with. Zeroed by rig_logged or rig_plain before use. */
struct rig {
    qo_sim *sim;
    qo_modbus_sink *s;
    qo_modbus_sink_settings set; /* test_settings(), for the test to adjust before opening */
    qo_modbus_sink_stats st;     /* as of the last rig_stats */
    qo_sim_stats sst;
    struct tick_log tl;          /* the failed ticks, for note_tick */
    double last[NJ];             /* by rig_end, from the log: the last value per joint, */
    double worst;                /* the largest step / max_step */
    unsigned lines;              /* and the line count */
    FILE *log;          /* the simulator's log of received targets, or NULL */
    struct relay relay; /* RTU rigs only */
    int rtu;
    char spec[128];     /* the simulator's address */
};

/* Simulator settings for a rig whose simulator logs into a fresh tmpfile (g->log): lag in s,
 * seed 7, no fault. */
static qo_sim_settings rig_logged(struct rig *g, double lag)
{
    qo_sim_settings ss = qo_sim_settings_default;
    memset(g, 0, sizeof *g);
    g->set = test_settings();
    g->log = tmpfile();
    assert_non_null(g->log);
    ss.log = g->log;
    ss.lag_s = lag;
    ss.seed = 7;
    return ss;
}

/* Simulator settings for a rig without a log: the defaults with lag in s. */
static qo_sim_settings rig_plain(struct rig *g, double lag)
{
    qo_sim_settings ss = qo_sim_settings_default;
    memset(g, 0, sizeof *g);
    g->set = test_settings();
    ss.lag_s = lag;
    return ss;
}

/* The simulator of `map` with ss on an ephemeral loopback port, the sink of g->set opened on
 * it. */
static qo_modbus_sink *rig_tcp(struct rig *g, const qo_sim_settings *ss)
{
    g->sim = sim_on_tcp(ss, g->spec, sizeof g->spec);
    assert_int_equal(qo_modbus_sink_open(g->spec, &map, &g->set, &g->s), QO_OK);
    return g->s;
}

/* The same over RTU: the simulator on the relay's side A, the sink on side B (k_junk is what
 * an injection writes). */
static qo_modbus_sink *rig_rtu(struct rig *g, const qo_sim_settings *ss)
{
    static const uint8_t k_junk[3] = { 0x5A, 0xA5, 0x11 };
    relay_open(&g->relay, k_junk, sizeof k_junk);
    g->rtu = 1;
    snprintf(g->spec, sizeof g->spec, "rtu:%s,115200,8N1", g->relay.path_a);
    assert_int_equal(qo_sim_start(g->spec, &map, ss, &g->sim), QO_OK);
    assert_int_equal(qo_sim_port(g->sim), 0);
    snprintf(g->spec, sizeof g->spec, "rtu:%s,115200,8N1", g->relay.path_b);
    assert_int_equal(qo_modbus_sink_open(g->spec, &map, &g->set, &g->s), QO_OK);
    return g->s;
}

/* Sets fault on the simulator (counted from the sink's next request), then streams n ticks
 * of targets_at(k) up to tick `hold`, the final targets after it, servicing the sink after
 * each write as a streamer does; the failed ticks go to g->tl. */
static void rig_run_fault(struct rig *g, const qo_sim_fault *fault, unsigned n, unsigned hold)
{
    unsigned k;
    assert_int_equal(qo_sim_set_fault(g->sim, fault), QO_OK);
    for (k = 0; k < n; k++) {
        float t[NJ];
        targets_at(k < hold ? k : NTICKS - 1, t);
        note_tick(&g->tl, k, qo_modbus_sink_write(g->s, t, NJ, k));
        (void)qo_modbus_sink_service(g->s);
    }
}

/* Both sides' counters into g->st and g->sst. */
static void rig_stats(struct rig *g)
{
    assert_int_equal(qo_modbus_sink_get_stats(g->s, &g->st), QO_OK);
    assert_int_equal(qo_sim_get_stats(g->sim, &g->sst), QO_OK);
}

/* Frees the sink and stops the simulator (and the RTU relay); then, for a logged rig, checks
 * the log (check_log: no step above max_step), closes it and keeps the worst step ratio, the
 * last value per joint and the line count in g. The counters (st, sst, tl) stay too, for the
 * checks after it. */
static void rig_end(struct rig *g)
{
    qo_modbus_sink_free(g->s);
    qo_sim_stop(g->sim);
    if (g->rtu) relay_close(&g->relay);
    if (g->log != NULL) {
        g->worst = check_log(g->log, &map, g->last, &g->lines);
        fclose(g->log);
    }
    g->s = NULL;
    g->sim = NULL;
    g->log = NULL;
    g->rtu = 0;
}

/* The simulator's log ends on the final targets (after rig_end). */
static void check_last(const double *last, const char *what)
{
    size_t i;
    for (i = 0; i < NJ; i++)
        if (fabs(last[i] - final_target(i)) > 0.5e-3 + 1e-12)
            fail_msg("%s: joint %u last logged %g want %g", what, (unsigned)i, last[i],
                     final_target(i));
}

static void test_tcp_clean_stream(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_logged(&g, 0.0);
    qo_modbus_sink *s;
    qo_sink generic;
    qo_sink_stats gs;
    struct run_result r;
    float fb[NJ];
    size_t i;
    (void)state;
    s = rig_tcp(&g, &ss);
    assert_int_equal(qo_modbus_sink_as_sink(s, &generic), QO_OK);
    r = stream(s);
    assert_int_equal(r.failed, 0);
    assert_int_equal(r.ok, NTICKS);
    rig_stats(&g);
    assert_int_equal(g.st.groups, 1); /* six contiguous int32 = one FC16 of 12 registers */
    assert_true(g.st.rate_limited > 0);
    assert_int_equal(g.st.requests, NTICKS + NJ); /* + six feedback reads at open */
    assert_int_equal(qo_sink_get_stats(&generic, &gs), QO_OK);
    assert_int_equal(gs.writes_ok, NTICKS);
    assert_int_equal(gs.connected, 1);
    /* lag 0: the feedback registers hold the target */
    assert_int_equal(qo_modbus_sink_read_feedback(s, fb, NJ), QO_OK);
    for (i = 0; i < NJ; i++)
        if (fabs((double)fb[i] - final_target(i)) > 0.5e-3 + 1e-6)
            fail_msg("feedback %u: %g want %g", (unsigned)i, (double)fb[i], final_target(i));
    qo_sink_close(&generic);
    qo_sink_close(&generic);
    assert_int_equal(qo_modbus_sink_write(s, fb, NJ, 0), QO_E_STATE);
    assert_int_equal(qo_modbus_sink_service(s), QO_E_STATE);
    rig_end(&g);
    assert_int_equal(g.lines, NTICKS * NJ);
    assert_true(g.worst > 0.99); /* the limit was reached, and never passed */
    /* with the sink closed and the sim stopped the final targets are in the log */
    check_last(g.last, "clean stream");
}

struct fault_case {
    const char *name;
    qo_sim_fault fault;
};

static void test_tcp_faults(void **state)
{
    static const struct fault_case cases[] = {
        { "delay 150 ms x2 (timeouts, late replies)", { QO_SIM_FAULT_DELAY, 150, 0.0, 60, 2 } },
        { "drop x4 (applied, no reply)", { QO_SIM_FAULT_DROP, 0, 0.0, 60, 4 } },
        { "exception x4 (not applied)", { QO_SIM_FAULT_EXCEPTION, 0, 0.0, 60, 4 } },
        { "close x1 (disconnect mid-stream)", { QO_SIM_FAULT_CLOSE, 0, 0.0, 60, 1 } },
        { "close x3 (reconnects fail too)", { QO_SIM_FAULT_CLOSE, 0, 0.0, 60, 3 } },
        { "drop 3% of requests", { QO_SIM_FAULT_DROP, 0, 0.03, 0, 0 } },
        { "exception 10% of requests", { QO_SIM_FAULT_EXCEPTION, 0, 0.10, 0, 0 } },
    };
    size_t c;
    (void)state;
    for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        struct rig g;
        qo_sim_settings ss = rig_logged(&g, 0.02);
        qo_sim *sim;
        qo_modbus_sink *s;
        struct run_result r;
        int tries;
        s = rig_tcp(&g, &ss);
        sim = g.sim;
        /* faults start after open: `after` counts requests from here */
        assert_int_equal(qo_sim_set_fault(sim, &cases[c].fault), QO_OK);
        r = stream(s);
        /* a share-based fault may hit the last ticks: finish with fault-free ticks */
        {
            qo_sim_fault none = { QO_SIM_FAULT_NONE, 0, 0.0, 0, 0 };
            float t[NJ];
            unsigned k;
            assert_int_equal(qo_sim_set_fault(sim, &none), QO_OK);
            targets_at(NTICKS - 1, t);
            for (tries = 0, k = 0; tries < 200 && k < 3; tries++) {
                if (qo_modbus_sink_service(s) != QO_OK) continue;
                if (qo_modbus_sink_write(s, t, NJ, NTICKS + (unsigned)tries) == QO_OK) k++;
            }
            if (k < 3) fail_msg("%s: stream did not recover", cases[c].name);
        }
        rig_stats(&g);
        if (g.sst.faults == 0 || r.failed == 0)
            fail_msg("%s: no fault seen (sim faults %llu, failed ticks %u)", cases[c].name,
                     (unsigned long long)g.sst.faults, r.failed);
        if (cases[c].fault.share == 0.0 && r.last_failed_tick > NTICKS - FINAL_TICKS)
            fail_msg("%s: failures lasted until tick %u", cases[c].name, r.last_failed_tick);
        if (cases[c].fault.kind == QO_SIM_FAULT_CLOSE && g.st.common.reconnects == 0)
            fail_msg("%s: no reconnection", cases[c].name);
        if (getenv("QO_DEBUG")) printf("%s: failed %u timeouts %llu proto %llu exc %llu disc %llu reconn %llu\n", cases[c].name, r.failed, (unsigned long long)g.st.timeouts, (unsigned long long)g.st.protocol_errors, (unsigned long long)g.st.exceptions, (unsigned long long)g.st.disconnects, (unsigned long long)g.st.common.reconnects);
        if (cases[c].fault.kind == QO_SIM_FAULT_DELAY && g.st.timeouts == 0)
            fail_msg("%s: no timeout counted", cases[c].name);
        if (cases[c].fault.kind == QO_SIM_FAULT_EXCEPTION && g.st.exceptions == 0)
            fail_msg("%s: no exception counted", cases[c].name);
        check_final(sim, cases[c].name);
        rig_end(&g);
        check_last(g.last, cases[c].name);
    }
}

static const char *disable_map =
    "[slave.1]\n"
    "init = 200=1\n"
    "disable = 200=0, 201=0x40\n"
    "constant = 4=0x10\n"
    "[joint.a]\nslave = 1\naddress = 0\ntype = int32\nscale = 1000\nmax_step = 0.05\n"
    "feedback = 100\n"
    "[joint.b]\nslave = 1\naddress = 2\ntype = int16\nscale = 100\nmax_step = 0.05\n"
    "feedback = 102\n";

static void test_disable_action_and_enable(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_plain(&g, 0.0);
    qo_modbus_sink *s;
    qo_sim_fault exc = { QO_SIM_FAULT_EXCEPTION, 0, 0.0, 0, 3 };
    uint16_t reg;
    float t[2] = { 1.0f, -1.0f };
    unsigned k;
    int tries;
    (void)state;
    load_map("disable.ini", disable_map);
    g.set.on_fail = QO_MODBUS_SINK_ON_FAIL_DISABLE;
    s = rig_tcp(&g, &ss);
    assert_int_equal(qo_sim_get_register(g.sim, 1, 200, &reg), QO_OK);
    assert_int_equal(reg, 1); /* init write */
    for (k = 0; k < 5; k++) assert_int_equal(qo_modbus_sink_write(s, t, 2, k), QO_OK);
    assert_int_equal(qo_sim_get_register(g.sim, 1, 4, &reg), QO_OK);
    assert_int_equal(reg, 0x10); /* constant register written with the targets */
    /* the next three requests get exceptions: three failed ticks = the threshold */
    exc.after = 0;
    exc.share = 1.0;
    assert_int_equal(qo_sim_set_fault(g.sim, &exc), QO_OK);
    for (k = 0; k < 3; k++) assert_int_equal(qo_modbus_sink_write(s, t, 2, 10 + k), QO_E_PROTOCOL);
    exc.kind = QO_SIM_FAULT_NONE;
    exc.share = 0.0;
    assert_int_equal(qo_sim_set_fault(g.sim, &exc), QO_OK);
    rig_stats(&g);
    assert_int_equal(g.st.disabled, 1);
    assert_int_equal(g.st.actions, 1);
    assert_int_equal(g.st.common.connected, 0);
    assert_int_equal(qo_modbus_sink_write(s, t, 2, 20), QO_E_STATE);
    /* reconnection sends the disable writes again; still disabled */
    for (tries = 0; tries < 100 && qo_modbus_sink_service(s) != QO_OK; tries++) {
    }
    assert_int_equal(qo_modbus_sink_service(s), QO_OK);
    assert_int_equal(qo_sim_get_register(g.sim, 1, 201, &reg), QO_OK);
    assert_int_equal(reg, 0x40);
    assert_int_equal(qo_sim_get_register(g.sim, 1, 200, &reg), QO_OK);
    assert_int_equal(reg, 0);
    assert_int_equal(qo_modbus_sink_write(s, t, 2, 21), QO_E_STATE);
    assert_int_equal(qo_modbus_sink_enable(s), QO_OK);
    assert_int_equal(qo_sim_get_register(g.sim, 1, 200, &reg), QO_OK);
    assert_int_equal(reg, 1);
    for (k = 0; k < 40; k++) assert_int_equal(qo_modbus_sink_write(s, t, 2, 30 + k), QO_OK);
    {
        double tgt, pos;
        assert_int_equal(qo_sim_get_joint(g.sim, 0, &tgt, &pos), QO_OK);
        assert_true(fabs(tgt - 1.0) < 1e-9);
        assert_int_equal(qo_sim_get_joint(g.sim, 1, &tgt, &pos), QO_OK);
        assert_true(fabs(tgt + 1.0) < 1e-9);
    }
    rig_end(&g);
}

/* Grouping: contiguous registers of one slave in one FC16, split at max_registers (never
 * inside a 32-bit value), gaps never filled, one request per run. */
static const char *group_map =
    "[slave.1]\nmax_registers = 4\nconstant = 5=77\n"
    "[slave.2]\n"
    "[joint.a]\nslave = 1\naddress = 0\ntype = int32\n"
    "[joint.b]\nslave = 1\naddress = 2\ntype = int16\n"
    "[joint.c]\nslave = 1\naddress = 3\ntype = float32\n"
    "[joint.d]\nslave = 2\naddress = 10\ntype = uint16\n"
    "[joint.e]\nslave = 2\naddress = 12\ntype = int16\n";

static void test_grouping(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_plain(&g, qo_sim_settings_default.lag_s);
    qo_modbus_sink *s;
    qo_sim_stats a, b;
    uint16_t reg;
    float t[5] = { 1000.0f, -5.0f, 2.5f, 65535.0f, -32768.0f };
    size_t i;
    (void)state;
    load_map("group.ini", group_map);
    s = rig_tcp(&g, &ss);
    assert_int_equal(qo_sim_get_stats(g.sim, &a), QO_OK);
    assert_int_equal(qo_modbus_sink_write(s, t, 5, 0), QO_OK);
    assert_int_equal(qo_sim_get_stats(g.sim, &b), QO_OK);
    /* slave 1: [a(2) b(1)] then [c(2) const(1)] (4 would split c); slave 2: d, e (gap at 11) */
    rig_stats(&g);
    assert_int_equal(g.st.groups, 4);
    assert_int_equal(b.requests - a.requests, 4);
    assert_int_equal(qo_sim_get_register(g.sim, 1, 5, &reg), QO_OK);
    assert_int_equal(reg, 77);
    assert_int_equal(qo_sim_get_register(g.sim, 2, 11, &reg), QO_OK);
    assert_int_equal(reg, 0); /* the gap is never written */
    for (i = 0; i < 5; i++) {
        double tgt, pos;
        assert_int_equal(qo_sim_get_joint(g.sim, i, &tgt, &pos), QO_OK);
        if (tgt != (double)t[i]) fail_msg("joint %u: %g want %g", (unsigned)i, tgt, (double)t[i]);
    }
    rig_end(&g);
}

static void test_arguments_and_specs(void **state)
{
    qo_modbus_link_spec sp;
    qo_modbus_sink *s = (qo_modbus_sink *)&sp;
    qo_modbus_sink_settings set = test_settings();
    qo_sim *sim = NULL;
    struct rig g;
    qo_sim_settings ss = rig_plain(&g, 0.0);
    float t[NJ] = { 0, 0, 0, 0, 0, 0 };
    qo_sim_stats a, b;
    (void)state;
    assert_int_equal(qo_modbus_link_parse_spec("tcp://10.0.0.2:1502", &sp), QO_OK);
    assert_int_equal(sp.transport, QO_MODBUS_LINK_TCP);
    assert_string_equal(sp.host, "10.0.0.2");
    assert_int_equal(sp.port, 1502);
    assert_int_equal(qo_modbus_link_parse_spec("tcp://:7", &sp), QO_OK);
    assert_string_equal(sp.host, "127.0.0.1");
    assert_int_equal(qo_modbus_link_parse_spec("tcp://host", &sp), QO_OK);
    assert_int_equal(sp.port, 502);
    assert_int_equal(qo_modbus_link_parse_spec("rtu:/dev/ttyUSB0,115200,8N1", &sp), QO_OK);
    assert_int_equal(sp.transport, QO_MODBUS_LINK_RTU);
    assert_string_equal(sp.device, "/dev/ttyUSB0");
    assert_int_equal(sp.baud, 115200);
    assert_int_equal(sp.parity, 'N');
    assert_int_equal(sp.data_bits, 8);
    assert_int_equal(sp.stop_bits, 1);
    assert_int_equal(qo_modbus_link_parse_spec("rtu:/dev/ttyS1,9600,7O2", &sp), QO_OK);
    assert_int_equal(sp.parity, 'O');
    assert_int_equal(sp.data_bits, 7);
    assert_int_equal(sp.stop_bits, 2);
    assert_int_equal(qo_modbus_link_parse_spec("rtu:/dev/ttyS1", &sp), QO_OK);
    assert_int_equal(sp.baud, 19200);
    assert_int_equal(sp.parity, 'E');
    {
        static const char *bad[] = { "udp://x:1", "tcp://x:70000", "tcp://x:", "tcp://x:1a",
                                     "rtu:", "rtu:/dev/x,0", "rtu:/dev/x,9600,8X1",
                                     "rtu:/dev/x,9600,9N1", "rtu:/dev/x,9600,8N3",
                                     "rtu:/dev/x,96k", "" };
        size_t i;
        for (i = 0; i < sizeof bad / sizeof bad[0]; i++)
            if (qo_modbus_link_parse_spec(bad[i], &sp) != QO_E_CONFIG || sp.port != 0)
                fail_msg("spec '%s' accepted", bad[i]);
    }
    assert_int_equal(qo_modbus_link_parse_spec(NULL, &sp), QO_E_NULL);
    load_six();
    /* open errors leave *out NULL */
    assert_int_equal(qo_modbus_sink_open("tcp://127.0.0.1:0", &map, &set, &s), QO_E_CONFIG);
    assert_null(s);
    set.response_timeout_us = 0;
    assert_int_equal(qo_modbus_sink_open("tcp://127.0.0.1:1", &map, &set, &s), QO_E_LIMIT);
    set = test_settings();
    set.reconnect_max_us = 10;
    assert_int_equal(qo_modbus_sink_open("tcp://127.0.0.1:1", &map, &set, &s), QO_E_CONFIG);
    set = test_settings();
    /* a host name goes through modbus_new_tcp_pi; the simulator listens on literals and
     * localhost only */
    assert_int_equal(qo_modbus_link_parse_spec("tcp://localhost:1", &sp), QO_OK);
    {
        modbus_t *ctx = qo_modbus_link_new_ctx(&sp);
        assert_non_null(ctx);
        modbus_free(ctx);
        assert_int_equal(qo_sim_start("tcp://no-such-host.invalid:0", &map, NULL, &sim), QO_E_CONFIG);
        assert_null(sim);
    }
    /* IPv6 in brackets */
    assert_int_equal(qo_modbus_link_parse_spec("tcp://[::1]:1502", &sp), QO_OK);
    assert_string_equal(sp.host, "::1");
    assert_int_equal(sp.port, 1502);
    assert_int_equal(qo_modbus_link_parse_spec("tcp://[fe80::1]", &sp), QO_OK);
    assert_string_equal(sp.host, "fe80::1");
    assert_int_equal(sp.port, 502);
    assert_int_equal(qo_modbus_link_parse_spec("tcp://[::1", &sp), QO_E_CONFIG);
    assert_int_equal(qo_modbus_link_parse_spec("tcp://[]:1", &sp), QO_E_CONFIG);
    assert_int_equal(qo_modbus_link_parse_spec("tcp://[::1]x", &sp), QO_E_CONFIG);
    assert_int_equal(qo_modbus_link_parse_spec("tcp://[::1]:", &sp), QO_E_CONFIG);
    /* port 1 on loopback: nobody listens */
    assert_int_equal(qo_modbus_sink_open("tcp://127.0.0.1:1", &map, &set, &s), QO_E_DISCONNECTED);
    assert_null(s);
    assert_int_equal(qo_modbus_sink_open(NULL, &map, &set, &s), QO_E_NULL);
    /* hand-made maps are checked: bad type, zero scale, NaN max_step, too few registers */
    map.joints[2].fmt.type = QO_MODBUS_REG_TYPE_COUNT_;
    assert_int_equal(qo_modbus_sink_open("tcp://127.0.0.1:1", &map, &set, &s), QO_E_CONFIG);
    load_six();
    map.joints[2].fmt.scale = 0.0;
    assert_int_equal(qo_modbus_sink_open("tcp://127.0.0.1:1", &map, &set, &s), QO_E_CONFIG);
    load_six();
    map.joints[2].max_step = NAN;
    assert_int_equal(qo_modbus_sink_open("tcp://127.0.0.1:1", &map, &set, &s), QO_E_CONFIG);
    load_six();
    map.slaves[0].max_registers = 1; /* an int32 cannot be split */
    assert_int_equal(qo_modbus_sink_open("tcp://127.0.0.1:1", &map, &set, &s), QO_E_CONFIG);
    assert_null(s);
    load_six();
    /* bad ticks send nothing */
    ss.seed = 7;
    s = rig_tcp(&g, &ss);
    sim = g.sim;
    assert_int_equal(qo_sim_get_stats(sim, &a), QO_OK);
    t[3] = NAN;
    assert_int_equal(qo_modbus_sink_write(s, t, NJ, 0), QO_E_NONFINITE);
    t[3] = INFINITY;
    assert_int_equal(qo_modbus_sink_write(s, t, NJ, 0), QO_E_NONFINITE);
    t[3] = 0.0f;
    assert_int_equal(qo_modbus_sink_write(s, t, NJ - 1, 0), QO_E_RANGE);
    assert_int_equal(qo_modbus_sink_write(s, NULL, NJ, 0), QO_E_NULL);
    assert_int_equal(qo_modbus_sink_write(NULL, t, NJ, 0), QO_E_NULL);
    assert_int_equal(qo_modbus_sink_write(s, t, NJ, 0), QO_OK);
    assert_int_equal(qo_sim_get_stats(sim, &b), QO_OK);
    assert_int_equal(b.requests - a.requests, 1);
    /* clamping to [min, max]: 10 rad -> 3.2 (walked there at max_step), seed from a value */
    {
        float far[NJ] = { 10, 10, 10, 10, 10, 10 }, seed[NJ] = { 3.2f, 3.2f, 3.2f, 3.2f, 3.2f, 3.2f };
        double tgt, pos;
        assert_int_equal(qo_modbus_sink_seed(s, seed, NJ), QO_OK);
        assert_int_equal(qo_modbus_sink_write(s, far, NJ, 1), QO_OK);
        assert_int_equal(qo_sim_get_joint(sim, 2, &tgt, &pos), QO_OK);
        assert_true(fabs(tgt - 3.2) < 1e-9);
        rig_stats(&g);
        assert_int_equal(g.st.clamped, NJ);
        seed[1] = NAN;
        assert_int_equal(qo_modbus_sink_seed(s, seed, NJ), QO_E_NONFINITE);
        assert_int_equal(qo_modbus_sink_seed(s, seed, 2), QO_E_RANGE);
    }
    rig_end(&g);
    qo_modbus_sink_free(NULL);
    qo_modbus_sink_close(NULL);
}

/* The worked Leadshine example map end to end: init writes, the PR0 block of 8 registers in
 * one FC16 per drive (constants around the high-first int32 target), invert on the tilt
 * drive. Expected registers are computed here from the manual's layout. */
static void test_leadshine_example_map(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_plain(&g, qo_sim_settings_default.lag_s);
    qo_modbus_sink *s;
    qo_sim_stats a, b;
    float t[2] = { 0.0f, 0.0f };
    const double scale = 10000.0 / (2.0 * 3.14159265358979323846);
    unsigned k;
    uint16_t reg;
    (void)state;
    load_map("examples/maps/leadshine_cs2rs_pr.ini", NULL);
    s = rig_tcp(&g, &ss);
    assert_int_equal(qo_sim_get_register(g.sim, 1, 0x0405, &reg), QO_OK);
    assert_int_equal(reg, 1);
    assert_int_equal(qo_sim_get_register(g.sim, 2, 0x0405, &reg), QO_OK);
    assert_int_equal(reg, 1);
    /* walk to pan 0.5 rad, tilt 0.3 rad at 0.02 rad per tick: 25 and 15 ticks */
    t[0] = 0.5f;
    t[1] = 0.3f;
    assert_int_equal(qo_sim_get_stats(g.sim, &a), QO_OK);
    for (k = 0; k < 30; k++) assert_int_equal(qo_modbus_sink_write(s, t, 2, k), QO_OK);
    assert_int_equal(qo_sim_get_stats(g.sim, &b), QO_OK);
    rig_stats(&g);
    assert_int_equal(g.st.groups, 2);
    assert_int_equal(b.requests - a.requests, 60);
    {
        static const uint16_t consts[][2] = { { 0x6200, 1 }, { 0x6203, 1500 }, { 0x6204, 20 },
                                              { 0x6205, 20 }, { 0x6206, 0 }, { 0x6207, 0x10 } };
        unsigned sl;
        size_t i;
        for (sl = 1; sl <= 2; sl++) {
            int32_t want = (int32_t)lround((sl == 1 ? 1.0 : -1.0) * (double)t[sl - 1] * scale);
            uint16_t hi, lo;
            for (i = 0; i < 6; i++) {
                assert_int_equal(qo_sim_get_register(g.sim, sl, consts[i][0], &reg), QO_OK);
                if (reg != consts[i][1])
                    fail_msg("slave %u register 0x%04X = %u want %u", sl, consts[i][0], reg,
                             consts[i][1]);
            }
            assert_int_equal(qo_sim_get_register(g.sim, sl, 0x6201, &hi), QO_OK);
            assert_int_equal(qo_sim_get_register(g.sim, sl, 0x6202, &lo), QO_OK);
            if ((int32_t)(((uint32_t)hi << 16) | lo) != want)
                fail_msg("slave %u target %d want %d", sl, (int32_t)(((uint32_t)hi << 16) | lo),
                         want);
        }
    }
    rig_end(&g);
}

static double mono_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* The simulator's first-order lag against exp(-t/tau) computed here: the position read at
 * a time known to within [before, after] of a write known to within [wa, wb] must lie
 * between the two bounds of 1 - exp(-dt/tau). The feedback registers carry it (FC03). */
static void test_sim_first_order_lag(void **state)
{
    const double tau = 0.05;
    struct rig g;
    qo_sim_settings ss = rig_plain(&g, tau);
    qo_modbus_sink *s;
    float t[NJ] = { 0.05f, 0.05f, 0.05f, 0.05f, 0.05f, 0.05f }, fb[NJ];
    double wa, wb, elapsed = 0.0;
    int reads = 0;
    (void)state;
    s = rig_tcp(&g, &ss);
    wa = mono_s();
    assert_int_equal(qo_modbus_sink_write(s, t, NJ, 0), QO_OK); /* step 0 -> 0.05 (= max_step) */
    wb = mono_s();
    while (elapsed < 0.15 && reads < 100000) {
        double tgt, pos, b0, b1, lo, hi;
        b0 = mono_s();
        assert_int_equal(qo_sim_get_joint(g.sim, 3, &tgt, &pos), QO_OK);
        b1 = mono_s();
        lo = 0.05 * (1.0 - exp(-fmax(b0 - wb, 0.0) / tau));
        hi = 0.05 * (1.0 - exp(-(b1 - wa) / tau));
        if (tgt != 0.05 || pos < lo - 1e-12 || pos > hi + 1e-12)
            fail_msg("lag: at %.4f s target %.9g position %.9g outside [%.9g, %.9g]", b0 - wa,
                     tgt, pos, lo, hi);
        elapsed = b1 - wa;
        reads++;
    }
    /* after 3 tau the feedback register shows ~95 % of the step (0.5e-3 resolution) */
    {
        double r0 = mono_s(), r1, lo, hi;
        assert_int_equal(qo_modbus_sink_read_feedback(s, fb, NJ), QO_OK);
        r1 = mono_s();
        lo = 0.05 * (1.0 - exp(-(r0 - wb) / tau)) - 0.5e-3; /* register resolution 1e-3 */
        hi = 0.05 * (1.0 - exp(-(r1 - wa) / tau)) + 0.5e-3;
        if ((double)fb[3] < lo - 1e-7 || (double)fb[3] > hi + 1e-7)
            fail_msg("feedback %.9g outside [%.9g, %.9g]", (double)fb[3], lo, hi);
    }
    rig_end(&g);
}

/* ---- RTU over two pty pairs joined by a relay thread (tests/common/linux/relay.c) ------ */

static void test_rtu_pty_with_garbage(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_logged(&g, 0.02);
    qo_modbus_sink *s;
    unsigned k, failed = 0, last_fail = 0;
    (void)state;
    ss.seed = qo_sim_settings_default.seed;
    g.set.rs485 = 1; /* refused by a pty (ENOTTY): must be harmless */
    s = rig_rtu(&g, &ss);
    for (k = 0; k < NTICKS; k++) {
        float t[NJ];
        if (k == 50 || k == 51) {
            relay_junk(&g.relay, 1); /* garbage before the next reply */
        }
        if (k == 100 || k == 130) {
            relay_junk(&g.relay, 0); /* garbage before the next request */
        }
        targets_at(k, t);
        if (qo_modbus_sink_write(s, t, NJ, k) != QO_OK) {
            failed++;
            last_fail = k;
        }
        (void)qo_modbus_sink_service(s);
    }
    rig_stats(&g);
    if (failed == 0 || failed > 20 || last_fail > NTICKS - FINAL_TICKS)
        fail_msg("garbage: %u failed ticks, last at %u (protocol errors %llu, timeouts %llu, "
                 "sim bad frames %llu)", failed, last_fail,
                 (unsigned long long)g.st.protocol_errors, (unsigned long long)g.st.timeouts,
                 (unsigned long long)g.sst.bad_frames);
    assert_true(g.sst.bad_frames >= 1);
    check_final(g.sim, "rtu garbage");
    rig_end(&g);
    assert_true(g.lines >= (NTICKS - 20) * NJ);
}

/* ---- read-back after an unknown outcome, a late RTU reply, a restarted drive ------------ */

static void test_two_timeouts_then_recovery(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_logged(&g, 0.0);
    /* request 21 = the FC16 of tick 20: applied, never answered; on TCP it stays
     * outstanding (the slave's ticks are skipped) until silence_us passes with nothing
     * received: the link is dead, reconnected, and the targets read back: request 22, the
     * read-back, is not answered either (a second silence), request 23 is. */
    qo_sim_fault drop2 = { QO_SIM_FAULT_DROP, 0, 0.0, 20, 2 };
    (void)state;
    g.set.response_timeout_us = 30000;
    g.set.silence_us = 100000;
    g.set.fail_threshold = 10; /* no failure action: the sink recovers on its own */
    (void)rig_tcp(&g, &ss);
    rig_run_fault(&g, &drop2, NTICKS, NTICKS);
    rig_stats(&g);
    /* each silence costs at most silence / timeout + 2 ticks (30 ms each, or less) */
    if (g.tl.first_fail != 20 || g.tl.first_status != QO_E_TIMEOUT || g.tl.second_fail != 21 ||
        g.tl.last_fail > 20 + 2 * (100 / 30 + 3) || g.st.timeouts != 2 || g.st.silences != 2 ||
        g.st.common.reconnects != 2 || g.st.readbacks != 2 || g.st.skipped == 0 || g.st.late_replies != 0)
        fail_msg("two lost replies: failed %u (first at %u, %s; last at %u), timeouts %llu, "
                 "silences %llu, reconnects %llu, read-backs %llu, skipped %llu, late %llu",
                 g.tl.failed, g.tl.first_fail, qo_status_str(g.tl.first_status), g.tl.last_fail,
                 (unsigned long long)g.st.timeouts, (unsigned long long)g.st.silences,
                 (unsigned long long)g.st.common.reconnects, (unsigned long long)g.st.readbacks,
                 (unsigned long long)g.st.skipped, (unsigned long long)g.st.late_replies);
    check_final(g.sim, "two timeouts");
    rig_end(&g); /* fails on any step above max_step */
    assert_int_equal(g.lines, (NTICKS - g.tl.failed + 1) * NJ); /* tick 20 arrived, unanswered */
    assert_true(g.worst > 0.99);
}

static void test_rtu_late_reply(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_logged(&g, 0.0);
    /* the FC16 of tick 20 is applied at once and answered 80 ms later, after the sink's
     * 30 ms timeout: an RTU reply carries no transaction id, and an FC16 echo is the same
     * every tick, so only the FC03 read-back (another function code) can tell it apart */
    qo_sim_fault late = { QO_SIM_FAULT_DELAY, 80, 0.0, 20, 1 };
    (void)state;
    ss.seed = qo_sim_settings_default.seed;
    g.set.response_timeout_us = 30000;
    g.set.byte_timeout_us = 10000;
    g.set.fail_threshold = 10;
    (void)rig_rtu(&g, &ss);
    rig_run_fault(&g, &late, 120, 40); /* short (RTU ticks are slow): final at 40 */
    rig_stats(&g);
    check_final(g.sim, "rtu late reply");
    rig_end(&g); /* fails on any step above max_step */
    assert_true(g.worst > 0.99);
    /* the late echo was dropped by the drain or rejected by the read-back, never taken as
     * the confirmation of a later FC16 */
    if (g.tl.failed == 0 || g.tl.first_fail != 20 || g.tl.first_status != QO_E_TIMEOUT ||
        g.tl.last_fail > 60 || g.st.readbacks == 0 || g.st.drains == 0 ||
        g.st.drained_bytes + g.st.protocol_errors == 0)
        fail_msg("late RTU reply: failed %u (first at %u, %s, last at %u), read-backs %llu, "
                 "drains %llu, drained bytes %llu, protocol errors %llu", g.tl.failed,
                 g.tl.first_fail, qo_status_str(g.tl.first_status), g.tl.last_fail,
                 (unsigned long long)g.st.readbacks, (unsigned long long)g.st.drains,
                 (unsigned long long)g.st.drained_bytes, (unsigned long long)g.st.protocol_errors);
}

static void test_drive_restart_target_zero(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_logged(&g, 0.0);
    qo_modbus_sink *s;
    float t[NJ];
    unsigned k, ok_after = 0;
    size_t i;
    (void)state;
    for (i = 0; i < NJ; i++) t[i] = 2.0f;
    g.set.response_timeout_us = 30000; /* the old link may time out before it is found down */
    s = rig_tcp(&g, &ss);
    for (k = 0; k < 60; k++) assert_int_equal(qo_modbus_sink_write(s, t, NJ, k), QO_OK);
    /* the drive restarts: same address, every register 0 (its target too), a new log */
    qo_sim_stop(g.sim);
    (void)check_log(g.log, &map, g.last, &g.lines); /* read once its writer has stopped */
    for (i = 0; i < NJ; i++)
        if (fabs(g.last[i] - 2.0) > 0.5e-3)
            fail_msg("before restart: joint %u at %g, want 2", (unsigned)i, g.last[i]);
    fclose(g.log);
    g.log = ss.log = tmpfile();
    assert_non_null(g.log);
    ss.seed = qo_sim_settings_default.seed;
    assert_int_equal(qo_sim_start(g.spec, &map, &ss, &g.sim), QO_OK);
    for (k = 60; k < 60 + 400 && ok_after < 60; k++) {
        if (qo_modbus_sink_write(s, t, NJ, k) == QO_OK) ok_after++;
        if (qo_modbus_sink_service(s) == QO_E_DISCONNECTED) {
            struct timespec d = { 0, 2000000L };
            nanosleep(&d, NULL); /* backoff */
        }
    }
    rig_stats(&g);
    /* the restarted drive (target 0) was walked at max_step: 2.0 / 0.05 = 40 ticks */
    rig_end(&g);
    assert_true(g.worst > 0.99);
    assert_true(g.lines >= 40 * NJ);
    if (ok_after < 60 || g.st.common.reconnects == 0 || g.st.readbacks == 0)
        fail_msg("restart: %u good ticks after, reconnects %llu, read-backs %llu", ok_after,
                 (unsigned long long)g.st.common.reconnects, (unsigned long long)g.st.readbacks);
    for (i = 0; i < NJ; i++) {
        double tg;
        tg = g.last[i];
        if (fabs(tg - 2.0) > 0.5e-3) fail_msg("restart: joint %u holds %g, want 2", (unsigned)i, tg);
    }
}

static const char *unreadable_map =
    "[slave.1]\n"
    "[joint.a]\nslave = 1\naddress = 0\ntype = int32\nscale = 1000\nmax_step = 0.05\n"
    "min = -3\nmax = 3\nfeedback = 100\n"
    "[joint.b]\nslave = 1\naddress = 2\ntype = int32\nscale = 1000\nmax_step = 0.05\n"
    "min = -3\nmax = 3\n";

static void test_readback_exception_fallback(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_logged(&g, 0.0); /* feedback = target: the fallback is then exact */
    qo_modbus_sink *s;
    qo_sim_fault drop1 = { QO_SIM_FAULT_DROP, 0, 0.0, 20, 1 };
    const float zero[2] = { 0.0f, 0.0f };
    unsigned k;
    (void)state;
    load_map("unreadable.ini", unreadable_map);
    ss.seed = qo_sim_settings_default.seed;
    ss.targets_unreadable = 1;
    g.set.response_timeout_us = 30000;
    g.set.silence_us = 100000;
    g.set.fail_threshold = 10;
    s = rig_tcp(&g, &ss);
    assert_int_equal(qo_modbus_sink_seed(s, zero, 2), QO_OK); /* b has no feedback */
    assert_int_equal(qo_sim_set_fault(g.sim, &drop1), QO_OK);
    for (k = 0; k < NTICKS; k++) {
        float t[2];
        t[0] = (float)(2.5 * sin(0.1 * k));
        t[1] = (float)(2.5 * sin(0.1 * k + 1.0));
        note_tick(&g.tl, k, qo_modbus_sink_write(s, t, 2, k));
        (void)qo_modbus_sink_service(s);
    }
    rig_stats(&g);
    /* tick 20 is never answered: after the silence the link is reconnected; the next tick
     * reads back, gets 0x02, takes a's feedback, keeps b's range (old and new value) and
     * writes; no read-back after that */
    if (g.tl.first_fail != 20 || g.tl.last_fail > 20 + 100 / 30 + 3 || g.st.silences != 1 ||
        g.st.readbacks != 1 || g.st.readback_fallbacks != 1 || g.st.exceptions != 1)
        fail_msg("fallback: failed %u (first at %u, last at %u), silences %llu, read-backs %llu, "
                 "fallbacks %llu, exceptions %llu; want first at 20, 1, 1, 1, 1", g.tl.failed,
                 g.tl.first_fail, g.tl.last_fail, (unsigned long long)g.st.silences,
                 (unsigned long long)g.st.readbacks, (unsigned long long)g.st.readback_fallbacks,
                 (unsigned long long)g.st.exceptions);
    /* FC16 per tick sent, a's feedback at open, the read-back and a's feedback after it */
    assert_int_equal(g.st.requests, NTICKS - g.tl.failed + 1 + 3);
    rig_end(&g); /* fails on any step above max_step */
    assert_int_equal(g.lines, (NTICKS - g.tl.failed + 1) * 2);
}

/* "Done" is the drive holding the final target: a move far beyond max_step per tick ends
 * only when the catch-up arrived and reads back (the case: j1 to 3.0 with max_step
 * 0.05 after one tick of the plan). Checked against the simulator's own target registers. */
static void test_settle_until_held(void **state)
{
    static const struct {
        const char *name;
        qo_sim_fault fault;
        int unreadable;
    } cases[] = {
        { "clean", { QO_SIM_FAULT_NONE, 0, 0.0, 0, 0 }, 0 },
        { "drop 20%", { QO_SIM_FAULT_DROP, 0, 0.2, 0, 0 }, 0 },
        { "exception 20%", { QO_SIM_FAULT_EXCEPTION, 0, 0.2, 0, 0 }, 0 },
        { "targets unreadable (feedback confirms)", { QO_SIM_FAULT_NONE, 0, 0.0, 0, 0 }, 1 },
    };
    /* 5.0 is clamped to max 3.2; -0.0004 rounds to 0 counts (scale 1000) */
    const float final[NJ] = { 3.0f, -2.0f, 5.0f, -0.0004f, 0.001f, 0.0f };
    const double goal[NJ] = { 3.0, -2.0, 3.2, 0.0, 0.001, 0.0 };
    size_t c, i;
    (void)state;
    for (c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        struct rig g;
        qo_sim_settings ss = rig_plain(&g, 0.0);
        qo_modbus_sink *s;
        qo_modbus_sink_settle_report rep;
        float zero[NJ] = { 0 };
        double dl;
        qo_status st;
        ss.seed = 11;
        ss.targets_unreadable = cases[c].unreadable;
        g.set.fail_threshold = 1000; /* faults must not end the link: settle retries */
        g.set.silence_us = 100000;   /* a dropped reply: reconnect soon */
        s = rig_tcp(&g, &ss);
        assert_int_equal(qo_modbus_sink_write(s, zero, NJ, 0), QO_OK);
        assert_int_equal(qo_sim_set_fault(g.sim, &cases[c].fault), QO_OK);
        /* the plan's last tick: one write, far short of 3.0 (max_step 0.05) */
        (void)qo_modbus_sink_write(s, final, NJ, 1);
        /* 3.2 / 0.05 = 64 ticks for the slowest joint: 2 x 65 ticks of 2 ms + 0.5 s */
        dl = qo_modbus_sink_settle_time(s, final, NJ, 0.002);
        if (fabs(dl - (2.0 * 65 * 0.002 + QO_MODBUS_SINK_SETTLE_SLACK_S)) > 2 * 0.002 + 1e-9)
            fail_msg("%s: default deadline %.6f s", cases[c].name, dl);
        /* a deadline of 0 writes nothing and names the joints that are short */
        st = qo_modbus_sink_settle(s, final, NJ, 0.002, 0.0, &rep);
        assert_int_equal(st, QO_E_TIMEOUT);
        assert_int_equal(rep.reached, 0);
        assert_int_equal(rep.ticks, 0);
        if (cases[c].fault.kind == QO_SIM_FAULT_NONE && (!rep.short_of[0] || !rep.short_of[2] || rep.short_of[5]))
            fail_msg("%s: short joints %d %d %d", cases[c].name, rep.short_of[0], rep.short_of[2], rep.short_of[5]);
        st = qo_modbus_sink_settle(s, final, NJ, 0.002, 10.0, &rep);
        qo_sim_stop(g.sim); /* before the checks: the registers are read after the last request */
        g.sim = NULL;
        if (st != QO_OK) fail_msg("%s: settle %s after %.3f s", cases[c].name, qo_status_str(st), rep.elapsed_s);
        assert_int_equal(rep.reached, 1);
        assert_true(rep.ticks >= 63); /* 3.15 left at 0.05 per tick */
        for (i = 0; i < NJ; i++) {
            if (rep.short_of[i] || fabs(rep.goal[i] - goal[i]) > 1e-12 || rep.held[i] != rep.goal[i])
                fail_msg("%s: joint %u goal %.9g held %.9g short %d, want goal %.9g", cases[c].name,
                         (unsigned)i, rep.goal[i], rep.held[i], rep.short_of[i], goal[i]);
        }
        rig_end(&g);
    }
}

/* The same, against the simulator's registers (an independent reading of what it holds). */
static void test_settle_matches_drive(void **state)
{
    const float final[NJ] = { 3.0f, -2.0f, 1.0f, 0.5f, 0.25f, -3.0f };
    struct rig g;
    qo_sim_settings ss = rig_plain(&g, 0.0);
    qo_modbus_sink *s;
    qo_modbus_sink_settle_report rep;
    size_t i;
    (void)state;
    ss.seed = 7;
    s = rig_tcp(&g, &ss);
    assert_int_equal(qo_modbus_sink_settle(s, final, NJ, 0.001,
                                           qo_modbus_sink_settle_time(s, final, NJ, 0.001), &rep),
                     QO_OK);
    for (i = 0; i < NJ; i++) {
        double tgt, pos;
        assert_int_equal(qo_sim_get_joint(g.sim, i, &tgt, &pos), QO_OK);
        if (tgt != (double)lround((double)final[i] * 1000.0) / 1000.0)
            fail_msg("joint %u: drive holds %.9g, want %.9g", (unsigned)i, tgt, (double)final[i]);
    }
    /* bad arguments: report written, nothing sent */
    assert_int_equal(qo_modbus_sink_settle(s, final, NJ - 1, 0.001, 1.0, &rep), QO_E_RANGE);
    assert_int_equal(rep.reached, 0);
    assert_int_equal(qo_modbus_sink_settle(s, final, NJ, 0.0, 1.0, &rep), QO_E_LIMIT);
    assert_int_equal(qo_modbus_sink_settle(s, final, NJ, 0.001, NAN, &rep), QO_E_LIMIT);
    assert_int_equal(qo_modbus_sink_settle(NULL, final, NJ, 0.001, 1.0, &rep), QO_E_NULL);
    assert_int_equal(qo_modbus_sink_settle(s, final, NJ, 0.001, 1.0, NULL), QO_E_NULL);
    {
        float bad[NJ] = { 0, 0, NAN, 0, 0, 0 };
        assert_int_equal(qo_modbus_sink_settle(s, bad, NJ, 0.001, 1.0, &rep), QO_E_NONFINITE);
        assert_true(isnan(rep.held[0]));
    }
    qo_modbus_sink_close(s);
    assert_int_equal(qo_modbus_sink_settle(s, final, NJ, 0.001, 1.0, &rep), QO_E_STATE);
    rig_end(&g);
}

/* TCP: replies later than the response timeout cost no connection. 5% of the replies come
 * 200 ms late (timeout 100 ms): each is matched by its transaction id in a later tick and
 * accepted; that slave's ticks in between are skipped (never queued); no reconnection, no
 * protocol error, no step above max_step, final targets exact. */
static void test_tcp_late_replies_accepted(void **state)
{
    struct rig g;
    qo_sim_settings ss = rig_logged(&g, 0.0);
    qo_modbus_sink *s;
    qo_sim_fault late = { QO_SIM_FAULT_DELAY, 200, 0.05, 0, 0 };
    qo_sim_fault none = { QO_SIM_FAULT_NONE, 0, 0.0, 0, 0 };
    unsigned k, ok = 0;
    (void)state;
    /* Every timeout must be a delayed reply (timeouts == faults below), so an undelayed reply
     * must never take the timeout: 100 ms, not 20 ms, because under qemu-user with ASan, on a
     * machine shared with another emulator, a plain reply once took over 20 ms (the first
     * run of a code path is translated then). The delay keeps its 2:1 ratio to the timeout;
     * the silence (automatic, >= 1 s) stays far above both. */
    g.set.response_timeout_us = 100000;
    g.set.fail_threshold = 3; /* would end the link at once if late replies counted as failures */
    s = rig_tcp(&g, &ss);
    assert_int_equal(qo_sim_set_fault(g.sim, &late), QO_OK);
    for (k = 0; k < NTICKS; k++) {
        float t[NJ];
        qo_status r;
        targets_at(k, t);
        r = qo_modbus_sink_write(s, t, NJ, k);
        note_tick(&g.tl, k, r);
        if (r != QO_OK && r != QO_E_TIMEOUT) fail_msg("tick %u: %s", k, qo_status_str(r));
        (void)qo_modbus_sink_service(s);
    }
    assert_int_equal(qo_sim_set_fault(g.sim, &none), QO_OK);
    for (k = 0; k < 100 && ok < 3; k++) {
        float t[NJ];
        targets_at(NTICKS - 1, t);
        if (qo_modbus_sink_write(s, t, NJ, NTICKS + k) == QO_OK) ok++;
    }
    assert_int_equal(ok, 3);
    rig_stats(&g);
    if (g.sst.faults == 0 || g.st.timeouts != g.sst.faults || g.st.late_replies != g.st.timeouts ||
        g.st.common.reconnects != 0 || g.st.disconnects != 0 || g.st.protocol_errors != 0 ||
        g.st.stale_replies != 0 || g.st.readbacks != 0 || g.st.silences != 0 ||
        g.st.skipped > 2 * g.st.timeouts)
        fail_msg("late replies: sim faults %llu, timeouts %llu, late %llu, skipped %llu, "
                 "reconnects %llu, disconnects %llu, protocol %llu, stale %llu, read-backs %llu",
                 (unsigned long long)g.sst.faults, (unsigned long long)g.st.timeouts,
                 (unsigned long long)g.st.late_replies, (unsigned long long)g.st.skipped,
                 (unsigned long long)g.st.common.reconnects, (unsigned long long)g.st.disconnects,
                 (unsigned long long)g.st.protocol_errors, (unsigned long long)g.st.stale_replies,
                 (unsigned long long)g.st.readbacks);
    check_final(g.sim, "late replies");
    rig_end(&g); /* fails on any step above max_step */
}

/* The simulator's reply latency model: parsing, and replies held back by it are late
 * replies for the sink (a 40 ms sleep always exceeds a 10 ms timeout: no timing assert). */
static void test_sim_lag_dist(void **state)
{
    static const char *bad[] = { "", "0.5", "0.5:", "0:1ms", "-1:1ms", "0.5:1", "0.5:2-1ms",
                                 "0.5:1ms,", "0.5:1ms,x", "1:70000ms", "a:1ms", "0.5:-1ms",
                                 "1:1ms,1:1ms,1:1ms,1:1ms,1:1ms,1:1ms,1:1ms,1:1ms,1:1ms" };
    struct rig g;
    qo_sim_settings ss = rig_plain(&g, qo_sim_settings_default.lag_s);
    qo_sim *sim = NULL;
    qo_modbus_sink *s;
    size_t i;
    unsigned k;
    (void)state;
    assert_int_equal(qo_sim_parse_lag_dist("0.97:0-0.2ms,0.03:5-12ms", &ss), QO_OK);
    assert_int_equal(ss.n_lag, 2);
    assert_true(ss.lag[0].share == 0.97 && ss.lag[0].lo_ms == 0.0 && ss.lag[0].hi_ms == 0.2);
    assert_true(ss.lag[1].share == 0.03 && ss.lag[1].lo_ms == 5.0 && ss.lag[1].hi_ms == 12.0);
    assert_int_equal(qo_sim_parse_lag_dist("2:150us,1:3ms", &ss), QO_OK);
    assert_true(ss.n_lag == 2 && ss.lag[0].lo_ms == 0.15 && ss.lag[0].hi_ms == 0.15 && ss.lag[1].lo_ms == 3.0);
    for (i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ss.n_lag = 5;
        if (qo_sim_parse_lag_dist(bad[i], &ss) != QO_E_CONFIG || ss.n_lag != 0)
            fail_msg("lag-dist '%s' accepted", bad[i]);
    }
    assert_int_equal(qo_sim_parse_lag_dist(NULL, &ss), QO_E_NULL);
    assert_int_equal(qo_sim_parse_lag_dist("1:1ms", NULL), QO_E_NULL);
    /* a bucket out of range is refused by start as well */
    load_six();
    ss = qo_sim_settings_default;
    ss.n_lag = 1;
    ss.lag[0].share = 1.0;
    ss.lag[0].lo_ms = 2.0;
    ss.lag[0].hi_ms = 1.0;
    assert_int_equal(qo_sim_start("tcp://127.0.0.1:0", &map, &ss, &sim), QO_E_CONFIG);
    assert_null(sim);
    assert_int_equal(qo_sim_parse_lag_dist("0.8:0ms,0.2:40ms", &ss), QO_OK);
    ss.lag_s = 0.0;
    g.set.response_timeout_us = 10000;
    g.set.open_timeout_us = 500000; /* the open is not what is tested here */
    s = rig_tcp(&g, &ss);
    for (k = 0; k < 60; k++) {
        float t[NJ];
        targets_at(k, t);
        (void)qo_modbus_sink_write(s, t, NJ, k);
    }
    rig_stats(&g);
    if (g.st.timeouts == 0 || g.st.late_replies + 1 < g.st.timeouts || g.st.common.reconnects != 0 ||
        g.st.protocol_errors != 0)
        fail_msg("lag-dist replies: timeouts %llu late %llu reconnects %llu protocol %llu",
                 (unsigned long long)g.st.timeouts, (unsigned long long)g.st.late_replies,
                 (unsigned long long)g.st.common.reconnects, (unsigned long long)g.st.protocol_errors);
    rig_end(&g);
}

/* The link's reconnection backoff: min first, doubling, capped, reset by a success. */
static void test_link_backoff(void **state)
{
    static const uint32_t want[] = { 1000, 2000, 4000, 5000, 5000 };
    qo_modbus_link_backoff b;
    size_t i;
    (void)state;
    qo_modbus_link_backoff_init(&b, 1000, 5000);
    assert_true(qo_modbus_link_backoff_due(&b));
    for (i = 0; i < sizeof want / sizeof want[0]; i++) assert_int_equal(qo_modbus_link_backoff_failed(&b), want[i]);
    assert_false(qo_modbus_link_backoff_due(&b)); /* 5 ms ahead */
    qo_modbus_link_backoff_now(&b);
    assert_true(qo_modbus_link_backoff_due(&b));
    qo_modbus_link_backoff_reset(&b);
    assert_int_equal(qo_modbus_link_backoff_failed(&b), 1000);
    qo_modbus_link_backoff_init(&b, 1500000, 2500000); /* carries into the seconds */
    assert_int_equal(qo_modbus_link_backoff_failed(&b), 1500000);
    assert_int_equal(qo_modbus_link_backoff_failed(&b), 2500000);
    assert_true(b.next.tv_nsec >= 0 && b.next.tv_nsec < 1000000000L);
    assert_int_equal(qo_modbus_link_connect(NULL, NULL, 0, NULL), QO_E_NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_tcp_clean_stream, six_map),
        cmocka_unit_test_setup(test_tcp_faults, six_map),
        cmocka_unit_test(test_disable_action_and_enable),
        cmocka_unit_test(test_grouping),
        cmocka_unit_test(test_arguments_and_specs),
        cmocka_unit_test_setup(test_sim_first_order_lag, six_map),
        cmocka_unit_test(test_leadshine_example_map),
        cmocka_unit_test_setup(test_rtu_pty_with_garbage, six_map),
        cmocka_unit_test_setup(test_two_timeouts_then_recovery, six_map),
        cmocka_unit_test_setup(test_rtu_late_reply, six_map),
        cmocka_unit_test_setup(test_drive_restart_target_zero, six_map),
        cmocka_unit_test(test_readback_exception_fallback),
        cmocka_unit_test_setup(test_settle_until_held, six_map),
        cmocka_unit_test_setup(test_tcp_late_replies_accepted, six_map),
        cmocka_unit_test(test_sim_lag_dist),
        cmocka_unit_test(test_link_backoff),
        cmocka_unit_test_setup(test_settle_matches_drive, six_map),
    };
    return cmocka_run_group_tests_name("modbus_sink", tests, NULL, NULL);
}
