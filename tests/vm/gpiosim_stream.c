/*
 * gpiosim_stream - runs INSIDE the gpio-sim VM (tests/vm/run-gpiosim.sh): drives the GPIO sink
 * through the real libgpiod backend (v1 or v2, whichever this build uses) against kernel
 * gpio-sim lines. After every set it reads the line back from the kernel (sysfs
 * sim_gpioN/value) and checks the step/dir timing rules, then checks that the steps the kernel
 * saw add up to the sink's positions, that every line is released on close, on an open error
 * and on process exit, and that lookups by name, chip name, path and label all work.
 *
 *   gpiosim_stream <sysfs chip dir 0> <chip name 0> <label 0> <sysfs chip dir 1> <chip name 1> <label 1>
 *
 * Banks (made by tests/vm/init): chip 0, 8 lines, line 0 named "qo-step0"; chip 1 as on a
 * Raspberry Pi 5, label "pinctrl-rp1", 54 lines, lines 17 and 27 named "GPIO17" and "GPIO27".
 *   joint 0: step = line named "qo-step0" (by name),        dir = <label 0>:1 (by chip label)
 *   joint 1: step = <name 0>:2 (by chip name),              dir = /dev/<name 0>:3 (by path), invert_dir
 *   joint 2: step = pinctrl-rp1:17 (by label, as on a Pi 5), dir = line named "GPIO27" (by name)
 * Part A: hand-made ticks with reversals. Part B: the real streamer at 250 Hz for 0.6 s with
 * ramps (joint 2 reverses), then its final write; what is checked does not depend on how many
 * ticks the load lets run. Part C: release on close. Part D: open errors
 * (busy line, offset out of range, unknown chip, name, path) release what was opened. Part E:
 * release when the process exits or is killed holding the lines.
 *
 * Timing. Each set is stamped before and after the call (CLOCK_MONOTONIC, the sink's clock).
 * The sink schedules from times it reads after its own set returns, so these lower bounds hold
 * however late the wake-ups are (TCG wake-ups are milliseconds late; upper bounds are not
 * asserted): consecutive rises of a joint at least 1/max_rate apart, a step at least
 * step_high_us high, the first rise at least dir_setup_us after a dir change, dir never changed
 * while its step line is high. The minima seen are printed.
 *
 * Prints "QOVM: ..." summary lines and "RESULT: PASS" or "RESULT: FAIL (...)"; exit 0/1.
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "linux/gpio_sink.h"
#include "linux/streamer.h"

#define NJ 3
#define NCHIP 2
#define LPC 64 /* line ids: chip * LPC + offset */
#define NID (NCHIP * LPC)

static const char *g_sysdir[NCHIP], *g_chip[NCHIP], *g_label[NCHIP];
static qo_gpio_sink_backend g_inner;
static int g_id_of[QO_GPIO_SINK_MAX_LINES]; /* handle -> line id */
static int g_level[NID];               /* level read back from the kernel */
static int g_role_joint[NID], g_role_step[NID];
static int g_step_id[NJ], g_dir_id[NJ], g_invert[NJ];
static uint64_t g_min_spacing[NJ], g_high[NJ], g_setup[NJ];
static uint64_t g_last_rise_after[NJ], g_rise_after[NJ], g_dir_after[NJ];
static int g_have_rise[NJ];
static long g_net[NJ], g_dir_changes[NJ];
static uint64_t g_seen_spacing = UINT64_MAX, g_seen_high = UINT64_MAX, g_seen_setup = UINT64_MAX;
static long g_mismatch, g_timing, g_sets;

static uint64_t now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

static int read_level(int id)
{
    char path[512], buf[8];
    FILE *f;
    int v = -1;
    snprintf(path, sizeof path, "%s/sim_gpio%d/value", g_sysdir[id / LPC], id % LPC);
    f = fopen(path, "r");
    if (!f) return -1;
    if (fgets(buf, sizeof buf, f)) v = atoi(buf);
    fclose(f);
    return v;
}

/* The line id a description names in the VM's layout; -1 when it names none of ours. */
static int line_id(const qo_gpio_sink_line *l)
{
    const char *c = l->chip;
    int k;
    if (l->name) {
        if (strcmp(l->name, "qo-step0") == 0) return 0;
        if (strcmp(l->name, "GPIO17") == 0) return LPC + 17;
        if (strcmp(l->name, "GPIO27") == 0) return LPC + 27;
        return -1;
    }
    if (!c || l->offset >= LPC) return -1;
    if (strncmp(c, "/dev/", 5) == 0) c += 5;
    for (k = 0; k < NCHIP; k++)
        if (strcmp(c, g_chip[k]) == 0 || strcmp(c, g_label[k]) == 0) return k * LPC + (int)l->offset;
    return -1;
}

static void timing_fail(const char *what, int j, uint64_t seen, uint64_t want)
{
    if (g_timing < 10)
        printf("TIMING joint %d: %s %llu ns < %llu ns\n", j, what, (unsigned long long)seen,
               (unsigned long long)want);
    g_timing++;
}

static qo_status chk_open(void *ctx, const qo_gpio_sink_line *line, int initial, int *h)
{
    qo_status st = g_inner.open(ctx, line, initial, h);
    int id = line_id(line);
    if (st != QO_OK) return st;
    if (id < 0) { printf("MISMATCH open of a line not in the layout\n"); g_mismatch++; return st; }
    g_id_of[*h] = id;
    g_level[id] = read_level(id);
    if (g_level[id] != initial) {
        printf("MISMATCH open line %d: kernel %d want %d\n", id, g_level[id], initial);
        g_mismatch++;
    }
    return st;
}

static qo_status chk_set(void *ctx, int h, int v)
{
    uint64_t before = now_ns(), after;
    qo_status st = g_inner.set_value(ctx, h, v);
    int id = g_id_of[h], j = g_role_joint[id], now;
    after = now_ns();
    if (st != QO_OK) return st;
    g_sets++;
    now = read_level(id);
    if (now != v) {
        if (g_mismatch < 10) printf("MISMATCH set line %d: kernel %d want %d\n", id, now, v);
        g_mismatch++;
    }
    if (j >= 0 && g_role_step[id]) {
        if (g_level[id] == 0 && now == 1) {
            int up = g_level[g_dir_id[j]] == (g_invert[j] ? 0 : 1);
            g_net[j] += up ? 1 : -1;
            if (g_have_rise[j]) {
                uint64_t d = before - g_last_rise_after[j];
                if (d < g_seen_spacing) g_seen_spacing = d;
                if (d < g_min_spacing[j]) timing_fail("rise to rise", j, d, g_min_spacing[j]);
            }
            if (before - g_dir_after[j] < g_seen_setup) g_seen_setup = before - g_dir_after[j];
            if (before - g_dir_after[j] < g_setup[j])
                timing_fail("dir change to rise", j, before - g_dir_after[j], g_setup[j]);
            g_last_rise_after[j] = after;
            g_rise_after[j] = after;
            g_have_rise[j] = 1;
        } else if (g_level[id] == 1 && now == 0) {
            uint64_t d = before - g_rise_after[j];
            if (d < g_seen_high) g_seen_high = d;
            if (d < g_high[j]) timing_fail("step high", j, d, g_high[j]);
        }
    } else if (j >= 0) {
        if (g_level[g_step_id[j]] == 1) timing_fail("dir changed while step high", j, 0, 1);
        if (g_level[id] != now) g_dir_changes[j]++;
        g_dir_after[j] = after;
    }
    g_level[id] = now;
    return st;
}

static void chk_close(void *ctx, int h) { g_inner.close(ctx, h); }

/* Ramps for part B (joint units; 100 steps per unit); joint 2 starts at -10 steps and
 * reverses through zero. */
static qo_status ramp(void *ctx, double t, float *out, size_t n)
{
    (void)ctx;
    (void)n;
    out[0] = (float)(0.5 * t);
    out[1] = (float)(-0.3 * t + 0.02);
    out[2] = (float)(0.4 * t - 0.1);
    return QO_OK;
}

static int fail(const char *why)
{
    printf("RESULT: FAIL (%s)\n", why);
    return 1;
}

static qo_gpio_sink_config g_cfg;

static void make_config(void)
{
    qo_gpio_sink_joint j;
    static char path1[80];
    int k;
    g_cfg = qo_gpio_sink_config_default;
    j = qo_gpio_sink_joint_default;
    g_cfg.period_s = 0.004;
    g_cfg.window = 0.75;
    g_cfg.step_high_us = 20.0;
    g_cfg.n_joints = NJ;
    j.steps_per_unit = 100.0;
    j.max_rate_hz = 2000.0;
    j.dir_setup_us = 50.0;
    for (k = 0; k < NJ; k++) g_cfg.joint[k] = j;
    snprintf(path1, sizeof path1, "/dev/%s", g_chip[0]);
    g_cfg.joint[0].step.name = "qo-step0";
    g_cfg.joint[0].dir.chip = g_label[0];
    g_cfg.joint[0].dir.offset = 1;
    g_cfg.joint[1].step.chip = g_chip[0];
    g_cfg.joint[1].step.offset = 2;
    g_cfg.joint[1].dir.chip = path1;
    g_cfg.joint[1].dir.offset = 3;
    g_cfg.joint[1].invert_dir = 1;
    g_cfg.joint[2].step.chip = g_label[1];
    g_cfg.joint[2].step.offset = 17;
    g_cfg.joint[2].dir.name = "GPIO27";
    for (k = 0; k < NJ; k++) {
        g_step_id[k] = line_id(&g_cfg.joint[k].step);
        g_dir_id[k] = line_id(&g_cfg.joint[k].dir);
        g_role_joint[g_step_id[k]] = k;
        g_role_step[g_step_id[k]] = 1;
        g_role_joint[g_dir_id[k]] = k;
        g_invert[k] = g_cfg.joint[k].invert_dir;
        g_min_spacing[k] = 500000u; /* 1 / 2000 Hz */
        g_high[k] = 20000u;
        g_setup[k] = 50000u;
    }
}

/*
 * Requests each line of cfg's first n joints through a separate backend instance. Returns how
 * many of them could be requested (all of them are released again): every one when the lines
 * are free, none while a sink holds them (the kernel says busy).
 */
static int count_free(const qo_gpio_sink_config *cfg, size_t n)
{
    static qo_gpio_sink_libgpiod store;
    qo_gpio_sink_backend be;
    int h, free_n = 0;
    size_t k;
    if (qo_gpio_sink_libgpiod_backend(&store, "qorient-vm-probe", &be) != QO_OK) return -1;
    for (k = 0; k < n; k++) {
        if (be.open(be.ctx, &cfg->joint[k].step, 0, &h) == QO_OK) { free_n++; be.close(be.ctx, h); }
        if (be.open(be.ctx, &cfg->joint[k].dir, 0, &h) == QO_OK) { free_n++; be.close(be.ctx, h); }
    }
    return free_n;
}

/* Part D: an open that fails on joint 1's dir line must release joint 0's and joint 1's step. */
static int open_error(const char *what, qo_gpio_sink_line bad, qo_status want,
                      const qo_gpio_sink_backend *be)
{
    qo_gpio_sink *sink = NULL;
    qo_gpio_sink_config c = g_cfg;
    qo_status st;
    int n;
    c.n_joints = 2;
    c.joint[1].dir = bad;
    st = qo_gpio_sink_open(&c, be, &sink);
    if (sink != NULL) return fail("a failed open handed out a sink");
    c.joint[1].dir = g_cfg.joint[1].dir;
    n = count_free(&c, 2);
    printf("QOVM: part D %s: open %s (want %s), %d of 4 lines free after\n", what,
           qo_status_str(st), qo_status_str(want), n);
    if (st != want) return fail(what);
    if (n != 4) return fail("lines held after a failed open");
    return 0;
}

/* Part E: a child opens the sink, moves, and exits (or is killed) without closing. */
static int exit_release(int kill_it, const qo_gpio_sink_backend *be)
{
    qo_gpio_sink *sink = NULL;
    int status, n;
    pid_t pid;
    fflush(stdout);
    pid = fork();
    if (pid < 0) return fail("fork");
    if (pid == 0) {
        float x[NJ] = { 0.03f, -0.03f, 0.03f };
        if (qo_gpio_sink_open(&g_cfg, be, &sink) != QO_OK) _exit(3);
        (void)qo_gpio_sink_write(sink, x, NJ, 0);
        if (count_free(&g_cfg, NJ) != 0) _exit(4); /* held while the child lives */
        if (kill_it) raise(SIGKILL);
        _exit(0);
    }
    if (waitpid(pid, &status, 0) != pid) return fail("waitpid");
    n = count_free(&g_cfg, NJ);
    printf("QOVM: part E child %s (status %d), %d of %d lines free after\n",
           kill_it ? "killed" : "exited", status, n, 2 * NJ);
    if (kill_it ? !(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL)
                : !(WIFEXITED(status) && WEXITSTATUS(status) == 0))
        return fail("child did not hold all the lines or did not end as planned");
    if (n != 2 * NJ) return fail("lines held after the process ended");
    return 0;
}

int main(int argc, char **argv)
{
    static qo_gpio_sink_libgpiod store, hold_store;
    qo_gpio_sink *sink = NULL;
    static qo_streamer str;
    qo_gpio_sink_backend be, hold;
    qo_streamer_config sc;
    qo_streamer_stats st;
    qo_gpio_sink_line bad;
    int64_t p[NJ], pa[NJ];
    long neta[NJ], dca2;
    size_t k;
    int i, hold_h;
    if (argc != 7) return fail("usage");
    for (i = 0; i < NCHIP; i++) {
        g_sysdir[i] = argv[1 + 3 * i];
        g_chip[i] = argv[2 + 3 * i];
        g_label[i] = argv[3 + 3 * i];
    }
    for (i = 0; i < NID; i++) g_role_joint[i] = -1;
    printf("QOVM: libgpiod %s API; chips %s (%s), %s (%s)\n", qo_gpio_sink_libgpiod_api(),
           g_chip[0], g_label[0], g_chip[1], g_label[1]);
    make_config();

    if (qo_gpio_sink_libgpiod_backend(&store, "qorient-vm", &g_inner) != QO_OK)
        return fail("backend");
    be = g_inner;
    be.open = chk_open;
    be.set_value = chk_set;
    be.close = chk_close;
    if (count_free(&g_cfg, NJ) != 2 * NJ) return fail("lines not free at start");
    if (qo_gpio_sink_open(&g_cfg, &be, &sink) != QO_OK) return fail("open");
    /* The probe must see the lines busy now, or part C-E could not detect a leak. */
    if (count_free(&g_cfg, NJ) != 0) return fail("probe could request lines the sink holds");

    /* Part A: reversals, 3 steps each way; generous ticks (the window is 3 ms here). */
    for (k = 0; k < 10; k++) {
        float x[NJ];
        x[0] = (k & 1) ? -0.01f : 0.02f;
        x[1] = (k & 1) ? 0.02f : -0.01f;
        x[2] = (k & 1) ? 0.02f : -0.01f;
        (void)qo_gpio_sink_write(sink, x, NJ, k);
    }
    /* Late wake-ups (TCG) may leave steps owed: repeat the last target until settled. */
    for (k = 0; k < 200; k++) {
        float x[NJ] = { -0.01f, 0.02f, 0.02f };
        for (i = 0; i < NJ; i++) qo_gpio_sink_position(sink, (size_t)i, &pa[i]);
        if (pa[0] == -1 && pa[1] == 2 && pa[2] == 2) break;
        (void)qo_gpio_sink_write(sink, x, NJ, 10 + k);
    }
    for (i = 0; i < NJ; i++) neta[i] = g_net[i];
    dca2 = g_dir_changes[2];
    printf("QOVM: part A: positions %lld %lld %lld, kernel saw %ld %ld %ld; dir changes %ld %ld "
           "%ld; %ld sets\n", (long long)pa[0], (long long)pa[1], (long long)pa[2], neta[0], neta[1],
           neta[2], g_dir_changes[0], g_dir_changes[1], g_dir_changes[2], g_sets);
    if (pa[0] != -1 || pa[1] != 2 || pa[2] != 2) return fail("part A positions");
    for (i = 0; i < NJ; i++)
        if (neta[i] != pa[i]) return fail("part A kernel steps");

    /* Part B: the real streamer drives the sink. */
    sc = qo_streamer_config_default;
    sc.rate_hz = 250.0;
    sc.n_joints = NJ;
    sc.sample = ramp;
    if (qo_gpio_sink_as_sink(sink, &sc.sink) != QO_OK) return fail("as_sink");
    sc.lock_memory = 0;
    if (qo_streamer_init(&str, &sc) != QO_OK || qo_streamer_start(&str) != QO_OK)
        return fail("streamer start");
    {
        struct timespec d = { 0, 600000000 };
        nanosleep(&d, NULL);
    }
    qo_streamer_request_stop(&str);
    if (qo_streamer_join(&str) != QO_OK) return fail("streamer final write");
    qo_streamer_stats_read(&str, &st);
    for (i = 0; i < NJ; i++) qo_gpio_sink_position(sink, (size_t)i, &p[i]);
    printf("QOVM: part B: ticks %llu overruns %llu latency max %llu us; positions %lld %lld "
           "%lld, kernel saw %ld %ld %ld; dir changes %ld %ld %ld; %ld sets\n",
           (unsigned long long)st.ticks, (unsigned long long)st.overruns,
           (unsigned long long)st.lat_max_ns / 1000u, (long long)p[0], (long long)p[1],
           (long long)p[2], g_net[0], g_net[1], g_net[2], g_dir_changes[0], g_dir_changes[1],
           g_dir_changes[2], g_sets);
    printf("QOVM: timing: min rise to rise %llu us (>= 500), min step high %llu us (>= 20), "
           "min dir change to rise %llu us (>= 50); %ld violations\n",
           (unsigned long long)g_seen_spacing / 1000u, (unsigned long long)g_seen_high / 1000u,
           (unsigned long long)g_seen_setup / 1000u, g_timing);
    qo_gpio_sink_free(sink); /* closes: part C checks the lines */
    /* Every deadline of the 0.6 s is a tick or an overrun (stats span_ns): however slow the
     * emulated CPU, there are about 150 of them; how many were ticks depends on the load. */
    if (st.ticks < 1 || st.ticks + st.overruns < 100) return fail("too few deadlines");
    for (i = 0; i < NJ; i++)
        if (g_net[i] != p[i]) return fail("part B kernel steps");
    /* How far the joints got depends on how many ticks ran (the load); the direction does not.
     * Joint 2 stood at +2 after part A and the ramp starts it at -10: it reverses. */
    if (p[0] <= 0 || p[1] >= 0) return fail("part B did not move");
    if (g_dir_changes[2] - dca2 < 1) return fail("joint 2 did not reverse in part B");
    if (g_timing) return fail("step/dir timing");
    if (g_mismatch) return fail("kernel line values differ from what was set");

    /* Part C: close drives the step lines low and releases every line. */
    for (i = 0; i < NJ; i++)
        if (read_level(g_step_id[i]) != 0) return fail("step left high after close");
    i = count_free(&g_cfg, NJ);
    printf("QOVM: part C: %d of %d lines free after close\n", i, 2 * NJ);
    if (i != 2 * NJ) return fail("lines held after close");

    /* Part D: failed opens release what they opened. A line held by another request is busy. */
    if (qo_gpio_sink_libgpiod_backend(&hold_store, "qorient-vm-holder", &hold) != QO_OK ||
        hold.open(hold.ctx, &g_cfg.joint[1].dir, 0, &hold_h) != QO_OK)
        return fail("cannot hold a line");
    {
        qo_gpio_sink *s2 = NULL;
        qo_status so = qo_gpio_sink_open(&g_cfg, &be, &s2);
        qo_gpio_sink_free(s2); /* NULL after a failed open; frees one that wrongly opened */
        hold.close(hold.ctx, hold_h);
        i = count_free(&g_cfg, NJ);
        printf("QOVM: part D busy line: open %s (want %s), %d of %d lines free after\n",
               qo_status_str(so), qo_status_str(QO_E_IO), i, 2 * NJ);
        if (so != QO_E_IO) return fail("busy line");
        if (i != 2 * NJ) return fail("lines held after a failed open");
    }
    memset(&bad, 0, sizeof bad);
    bad.chip = g_chip[0];
    bad.offset = 8; /* the bank has 8 lines */
    if (open_error("offset out of range", bad, QO_E_CONFIG, &be)) return 1;
    bad.chip = "no-such-chip";
    bad.offset = 0;
    if (open_error("unknown chip", bad, QO_E_CONFIG, &be)) return 1;
    bad.chip = "/dev/gpiochip99";
    if (open_error("unknown path", bad, QO_E_CONFIG, &be)) return 1;
    bad.chip = NULL;
    bad.name = "no-such-line";
    if (open_error("unknown line name", bad, QO_E_CONFIG, &be)) return 1;

    /* Part E: the kernel releases the lines of a process that ends holding them. */
    if (exit_release(0, &g_inner) || exit_release(1, &g_inner)) return 1;

    printf("RESULT: PASS\n");
    return 0;
}
