/* Modbus sink throughput and CPU cost against the simulator on loopback TCP.
 *
 *   make build/bench/bench_modbus && build/bench/bench_modbus [N]
 *
 * For 6 and 18 int32 joints (one slave, contiguous: one FC16 of 12 / 36 registers per tick):
 *   - updates/s through qo_modbus_sink_write (limit + pack + FC16 + reply),
 *   - updates/s of a bare libmodbus modbus_write_registers loop on the same simulator, same run,
 *   - CPU time of the calling thread per update (CLOCK_THREAD_CPUTIME_ID) for both,
 *   - CPU time of packing alone (qo_modbus_reg_pack of every joint, no I/O).
 * Rounds alternate sink and bare loops; the best of 3 rounds is printed (the machine is shared).
 * Loopback timing says nothing about a real RS-485 bus: see the research notes' bus budget. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include <modbus.h>

#include "linux/modbus_reg.h"
#include "linux/modbus_sink.h"
#include "linux/regmap.h"
#include "linux/sim.h"

static qo_regmap map;

static double now_s(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

static int make_map(int nj)
{
    static char text[8192];
    char err[256];
    size_t len = 0;
    int i;
    for (i = 0; i < nj; i++)
        len += (size_t)snprintf(text + len, sizeof text - len,
                                "[joint.j%d]\nslave = 1\naddress = %d\ntype = int32\nscale = 1000\n"
                                "max_step = 0.05\n", i, 2 * i);
    if (qo_regmap_parse(text, "bench", &map, err, sizeof err) != QO_OK) {
        fprintf(stderr, "map: %s\n", err);
        return -1;
    }
    return 0;
}

struct figures {
    double ups, cpu_us;
    int failed;
};

/* One tick of a loop under measurement: returns 0, or nonzero for a failed write. */
typedef int (*tick_fn)(void *ctx, int nj, int k);

static int tick_sink(void *ctx, int nj, int k)
{
    qo_modbus_sink *s = ctx;
    float t[64];
    int j;
    for (j = 0; j < nj; j++) t[j] = 0.5f * sinf(0.01f * (float)k + (float)j);
    if (qo_modbus_sink_write(s, t, (size_t)nj, (uint64_t)k) == QO_OK) return 0;
    (void)qo_modbus_sink_service(s);
    return 1;
}

static int tick_bare(void *ctx, int nj, int k)
{
    uint16_t regs[128];
    int j;
    for (j = 0; j < nj; j++) {
        int32_t v = (int32_t)lrint(500.0 * sin(0.01 * k + j));
        regs[2 * j] = (uint16_t)((uint32_t)v >> 16);
        regs[2 * j + 1] = (uint16_t)((uint32_t)v & 0xFFFFu);
    }
    if (modbus_write_registers(ctx, 0, 2 * nj, regs) == 2 * nj) return 0;
    modbus_flush(ctx);
    return 1;
}

/* Updates per second (wall) and CPU us per update of n ticks. */
static struct figures run(tick_fn tick, void *ctx, int nj, int n)
{
    double w0, c0;
    struct figures f = { 0, 0, 0 };
    int k;
    w0 = now_s(CLOCK_MONOTONIC);
    c0 = now_s(CLOCK_THREAD_CPUTIME_ID);
    for (k = 0; k < n; k++) f.failed += tick(ctx, nj, k);
    f.cpu_us = (now_s(CLOCK_THREAD_CPUTIME_ID) - c0) / n * 1e6;
    f.ups = n / (now_s(CLOCK_MONOTONIC) - w0);
    return f;
}

static double pack_ns(int nj, int n)
{
    uint16_t regs[2];
    volatile uint16_t sink = 0;
    double c0 = now_s(CLOCK_THREAD_CPUTIME_ID);
    int k, j;
    for (k = 0; k < n; k++)
        for (j = 0; j < nj; j++) {
            (void)qo_modbus_reg_pack(&map.joints[j].fmt, 0.5 * sin(0.01 * k + j), regs);
            sink ^= regs[1];
        }
    (void)sink;
    return (now_s(CLOCK_THREAD_CPUTIME_ID) - c0) / n * 1e9;
}

int main(int argc, char **argv)
{
    int n = argc > 1 ? atoi(argv[1]) : 3000;
    int sizes[2] = { 6, 18 }, si;
    if (n <= 0) n = 3000;
    printf("bench_modbus: loopback TCP, simulator in-process (own thread), %d updates per loop, "
           "best of 3 rounds\n", n);
    printf("%-7s %-24s %12s %14s %8s\n", "joints", "path", "updates/s", "cpu us/update",
           "failed");
    for (si = 0; si < 2; si++) {
        int nj = sizes[si], r;
        qo_sim *sim = NULL;
        qo_sim_settings ss = qo_sim_settings_default;
        qo_modbus_sink *s = NULL;
        modbus_t *ctx;
        char spec[64];
        struct figures bs = { 0, 1e9, 0 }, bb = { 0, 1e9, 0 };
        qo_modbus_sink_settings set = qo_modbus_sink_settings_default;
        double pk = 1e9;
        if (make_map(nj) != 0) return 1;
        ss.lag_s = 0.0;
        if (qo_sim_start("tcp://127.0.0.1:0", &map, &ss, &sim) != QO_OK) return 1;
        snprintf(spec, sizeof spec, "tcp://127.0.0.1:%d", qo_sim_port(sim));
        for (r = 0; r < 3; r++) {
            struct figures f;
            double p;
            /* the simulator serves one master at a time: connect each path in turn */
            /* 200 ms: a shared, loaded machine must not turn scheduling delays into errors */
            set.response_timeout_us = 200000;
            if (qo_modbus_sink_open(spec, &map, &set, &s) != QO_OK) return 1;
            f = run(tick_sink, s, nj, n);
            qo_modbus_sink_free(s);
            if (f.ups > bs.ups) bs.ups = f.ups;
            if (f.cpu_us < bs.cpu_us) bs.cpu_us = f.cpu_us;
            bs.failed += f.failed;
            ctx = modbus_new_tcp("127.0.0.1", qo_sim_port(sim));
            if (ctx == NULL || modbus_connect(ctx) != 0) return 1;
            modbus_set_slave(ctx, 1);
            modbus_set_response_timeout(ctx, 0, 200000);
            f = run(tick_bare, ctx, nj, n);
            modbus_close(ctx);
            modbus_free(ctx);
            if (f.ups > bb.ups) bb.ups = f.ups;
            if (f.cpu_us < bb.cpu_us) bb.cpu_us = f.cpu_us;
            bb.failed += f.failed;
            p = pack_ns(nj, 200000);
            if (p < pk) pk = p;
        }
        qo_sim_stop(sim);
        printf("%-7d %-24s %12.0f %14.2f %8d\n", nj, "qo_modbus_sink_write", bs.ups, bs.cpu_us,
               bs.failed);
        printf("%-7d %-24s %12.0f %14.2f %8d\n", nj, "bare FC16 loop", bb.ups, bb.cpu_us, bb.failed);
        printf("%-7d %-24s %12s %14.3f\n", nj, "qo_modbus_reg_pack only", "-", pk / 1000.0);
    }
    return 0;
}
