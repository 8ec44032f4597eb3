/*
 * gpiosim_stream - runs INSIDE the gpio-sim VM (tests/vm/run-gpiosim.sh): drives the GPIO sink
 * through the real libgpiod backend against kernel gpio-sim lines and checks, after every
 * set, that the kernel line took the value (sysfs sim_gpioN/value), then that the steps the
 * kernel saw add up to the sink's positions.
 *
 *   gpiosim_stream <sysfs chip dir> <chip name> <chip label>
 *
 * Bank layout (made by tests/vm/init): 8 lines; line 0 is named "qo-step0".
 *   joint 0: step = line named "qo-step0" (lookup by name), dir = <label>:1 (by chip label)
 *   joint 1: step = <name>:2 (by chip name), dir = /dev/<name>:3 (by path), invert_dir
 * Part A: hand-made ticks with reversals. Part B: the real streamer at 250 Hz for 0.6 s
 * with ramps, then its final write. Prints "RESULT: PASS" or "RESULT: FAIL (...)"; exit 0/1.
 * Timing is not asserted (TCG wake-ups are milliseconds late); logic and order are.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "linux/gpio_sink.h"
#include "linux/streamer.h"

static const char *g_sysdir;
static qo_gpio_backend g_inner;
static int g_offset_of[QO_GPIO_MAX_LINES];
static int g_level[8];       /* level read back from the kernel, per offset */
static long g_rises[8];      /* 0->1 transitions read back, per offset */
static long g_net[2];        /* signed steps the kernel saw, per joint (dir read back) */
static long g_mismatch, g_sets;

static int read_level(int offset)
{
    char path[512], buf[8];
    FILE *f;
    int v = -1;
    snprintf(path, sizeof path, "%s/sim_gpio%d/value", g_sysdir, offset);
    f = fopen(path, "r");
    if (!f) return -1;
    if (fgets(buf, sizeof buf, f)) v = atoi(buf);
    fclose(f);
    return v;
}

static int offset_for(const qo_gpio_line *l)
{
    if (l->name) return strcmp(l->name, "qo-step0") == 0 ? 0 : -1;
    return (int)l->offset;
}

static qo_status chk_open(void *ctx, const qo_gpio_line *line, int initial, int *h)
{
    qo_status st = g_inner.open(ctx, line, initial, h);
    int off = offset_for(line);
    if (st != QO_OK) return st;
    g_offset_of[*h] = off;
    g_level[off] = read_level(off);
    if (g_level[off] != initial) {
        printf("MISMATCH open offset %d: kernel %d want %d\n", off, g_level[off], initial);
        g_mismatch++;
    }
    return st;
}

static qo_status chk_set(void *ctx, int h, int v)
{
    qo_status st = g_inner.set_value(ctx, h, v);
    int off = g_offset_of[h], now;
    if (st != QO_OK) return st;
    g_sets++;
    now = read_level(off);
    if (now != v) {
        if (g_mismatch < 10) printf("MISMATCH set offset %d: kernel %d want %d\n", off, now, v);
        g_mismatch++;
    }
    if (g_level[off] == 0 && now == 1) {
        g_rises[off]++;
        /* step lines 0 and 2; dir of joint 0 is line 1 (1 = positive), joint 1 line 3 inverted */
        if (off == 0) g_net[0] += g_level[1] == 1 ? 1 : -1;
        if (off == 2) g_net[1] += g_level[3] == 0 ? 1 : -1;
    }
    g_level[off] = now;
    return st;
}

static void chk_close(void *ctx, int h) { g_inner.close(ctx, h); }

/* Ramps for part B (joint units; 100 steps per unit). */
static qo_status ramp(void *ctx, double t, float *out, size_t n)
{
    (void)ctx;
    (void)n;
    out[0] = (float)(0.5 * t);
    out[1] = (float)(-0.3 * t + 0.02);
    return QO_OK;
}

static int fail(const char *why)
{
    printf("RESULT: FAIL (%s)\n", why);
    return 1;
}

int main(int argc, char **argv)
{
    static qo_gpio_libgpiod store;
    static qo_gpio_sink sink;
    static qo_streamer str;
    static char path3[64], name2[64];
    qo_gpio_sink_config cfg;
    qo_gpio_joint j;
    qo_gpio_backend be;
    qo_streamer_config sc;
    qo_streamer_stats st;
    int64_t p0, p1;
    size_t k;
    if (argc != 4) return fail("usage");
    g_sysdir = argv[1];
    snprintf(name2, sizeof name2, "%s", argv[2]);
    snprintf(path3, sizeof path3, "/dev/%s", argv[2]);
    printf("libgpiod %s API\n", qo_gpio_libgpiod_api());

    if (qo_gpio_libgpiod_backend(&store, "qorient-vm", &g_inner) != QO_OK) return fail("backend");
    be = g_inner;
    be.open = chk_open;
    be.set_value = chk_set;
    be.close = chk_close;

    qo_gpio_sink_config_default(&cfg, &j);
    cfg.period_s = 0.004;
    cfg.window = 0.75;
    cfg.step_high_us = 20.0;
    cfg.n_joints = 2;
    j.steps_per_unit = 100.0;
    j.max_rate_hz = 2000.0;
    j.dir_setup_us = 50.0;
    cfg.joint[0] = j;
    cfg.joint[0].step.name = "qo-step0";
    cfg.joint[0].dir.chip = argv[3];
    cfg.joint[0].dir.offset = 1;
    cfg.joint[1] = j;
    cfg.joint[1].step.chip = name2;
    cfg.joint[1].step.offset = 2;
    cfg.joint[1].dir.chip = path3;
    cfg.joint[1].dir.offset = 3;
    cfg.joint[1].invert_dir = 1;
    if (qo_gpio_sink_open(&sink, &cfg, &be) != QO_OK) return fail("open");

    /* Part A: reversals, 3 steps each way; generous ticks (the window is 3 ms here). */
    for (k = 0; k < 10; k++) {
        float x[2];
        x[0] = (k & 1) ? -0.01f : 0.02f;
        x[1] = (k & 1) ? 0.02f : -0.01f;
        (void)qo_gpio_sink_write(&sink, x, 2, k);
    }
    /* Late wake-ups (TCG) may leave steps owed: repeat the last target until settled. */
    for (k = 0; k < 200; k++) {
        float x[2];
        x[0] = -0.01f;
        x[1] = 0.02f;
        qo_gpio_sink_position(&sink, 0, &p0);
        qo_gpio_sink_position(&sink, 1, &p1);
        if (p0 == -1 && p1 == 2) break;
        (void)qo_gpio_sink_write(&sink, x, 2, 10 + k);
    }
    printf("part A: positions %lld %lld, kernel saw %ld %ld, %ld sets\n", (long long)p0,
           (long long)p1, g_net[0], g_net[1], g_sets);
    if (p0 != -1 || p1 != 2) return fail("part A positions");
    if (g_net[0] != p0 || g_net[1] != p1) return fail("part A kernel steps");

    /* Part B: the real streamer drives the sink. */
    qo_streamer_config_default(&sc);
    sc.rate_hz = 250.0;
    sc.n_joints = 2;
    sc.sample = ramp;
    sc.sink = qo_gpio_sink_as_sink(&sink);
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
    qo_gpio_sink_position(&sink, 0, &p0);
    qo_gpio_sink_position(&sink, 1, &p1);
    printf("part B: ticks %llu overruns %llu latency max %llu us; positions %lld %lld, kernel "
           "saw %ld %ld; rises %ld %ld; %ld sets\n", (unsigned long long)st.ticks,
           (unsigned long long)st.overruns, (unsigned long long)st.lat_max_ns / 1000u,
           (long long)p0, (long long)p1, g_net[0], g_net[1], g_rises[0], g_rises[2], g_sets);
    qo_gpio_sink_close(&sink);
    if (st.ticks < 10) return fail("too few ticks");
    if (g_net[0] != p0 || g_net[1] != p1) return fail("part B kernel steps");
    if (p0 < 10 || p1 > -5) return fail("part B did not move");
    if (read_level(0) != 0 || read_level(2) != 0) return fail("step left high after close");
    if (g_mismatch) return fail("kernel line values differ from what was set");
    printf("RESULT: PASS\n");
    return 0;
}
