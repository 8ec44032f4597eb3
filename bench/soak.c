/*
 * bench/soak.c - soak figures (not part of `make test`; tools/soak.sh runs it).
 *
 * Part 1, stream: an 18-joint keyframe trajectory streamed through qo_streamer_tick to the
 * Modbus sink and the simulated drive bank over loopback TCP, 1e6 ticks at a nominal 500 Hz.
 * The streamer runs on an injected clock that jumps to each deadline, so the ticks run back
 * to back (bus round trips are real, the period is not waited for). Figures: wall time, RSS
 * from /proc/self/statm after warm-up, at the middle and at the end (growth, goal 0), every
 * error counter of the streamer, the sink and the simulator (goal 0), the largest difference
 * between the drive's final targets and the last sample (goal: within the register
 * resolution), and the schedule drift (the sample time of the last tick minus
 * (ticks - 1) * period: goal 0, checked to 1 ns, the rounding of the double sample time).
 *
 * Part 2, compositions: 1e7 products q <- q * r_i with qo_quat_mul_f32, r_i uniform random
 * unit quaternions (splitmix64, fixed seed) rounded to float, against the same product in
 * double (tests/common/ref.c) of the same float r_i. Variants: never renormalised, and
 * renormalised with qo_quat_normalize_f32 every 1e6, 1000 and 1 steps. Figures per variant:
 * |norm - 1| at the end and its maximum (sampled every 1000 steps), and the orientation error
 * (angle between the float and double results, both normalised) at the end and its maximum
 * at the 1e5-step checkpoints. The double product is renormalised every 1000 steps (the float
 * r_i are not exactly unit, so its norm would drift too; that is not the question); its final
 * norm is printed as a check.
 *
 * Usage: soak [--short]    --short: 2e4 ticks and 1e5 compositions (for valgrind).
 * Exit status 1 when an error counter is not 0, memory grew between the middle and the end,
 * or the final targets are off.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "linux/modbus_sink.h"
#include "linux/regmap.h"
#include "linux/sim.h"
#include "linux/streamer.h"
#include "qorient/quat.h"
#include "qorient/spline.h"

#include "common/ref.h"   /* the double reference: tests/common/ref.c, linked */

#define NJ 18
#define NK 5
#define RATE_HZ 500.0
#define T_LOOP 4.0 /* s: the trajectory repeats with this period */

static double wall_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* Resident set size in KiB, from /proc/self/statm (second field, pages). */
static long rss_kib(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    long size = 0, res = 0;
    if (f == NULL) return -1;
    if (fscanf(f, "%ld %ld", &size, &res) != 2) res = -1;
    fclose(f);
    return res < 0 ? -1 : res * (sysconf(_SC_PAGESIZE) / 1024);
}

/* ---- fake clock: sleeping jumps to the deadline ---------------------------------------- */

struct fake_clock {
    uint64_t now;
};

static uint64_t fake_now(void *ctx)
{
    return ((struct fake_clock *)ctx)->now;
}

static int fake_sleep_until(void *ctx, uint64_t abs_ns)
{
    struct fake_clock *c = ctx;
    if (c->now < abs_ns) c->now = abs_ns;
    return 0;
}

/* ---- trajectory: a loop through five keys, repeated every T_LOOP ------------------------ */

struct traj {
    qo_spline_f32 sp;
    float coef[NK + 3 * NJ + 6 * NK * NJ];
    double last_t;
    float last[NJ];
};

static int traj_init(struct traj *tr)
{
    float t[NK], p[NK * NJ];
    size_t k, j;
    for (k = 0; k < NK; k++) t[k] = (float)(T_LOOP * (double)k / (NK - 1));
    for (j = 0; j < NJ; j++) {
        double a = 0.5 + 0.1 * (double)j;
        p[0 * NJ + j] = 0.0f;
        p[1 * NJ + j] = (float)a;
        p[2 * NJ + j] = 0.0f;
        p[3 * NJ + j] = (float)-a;
        p[4 * NJ + j] = 0.0f;
    }
    return qo_spline_init_f32(NJ, NK, t, p, &qo_spline_settings_default, tr->coef,
                              sizeof tr->coef / sizeof tr->coef[0], &tr->sp) == QO_OK;
}

static qo_status traj_sample(void *ctx, double t, float *out, size_t n)
{
    struct traj *tr = ctx;
    qo_status st;
    if (n != NJ) return QO_E_RANGE;
    st = qo_spline_sample_f32(&tr->sp, (float)fmod(t, T_LOOP), out, NULL, NULL, NULL);
    if (st == QO_OK) {
        tr->last_t = t;
        memcpy(tr->last, out, sizeof tr->last);
    }
    return st;
}

static int build_map(qo_regmap *map)
{
    char text[8192], err[256];
    size_t len = 0, j;
    len += (size_t)snprintf(text + len, sizeof text - len, "[slave.1]\nmax_registers = 123\n");
    for (j = 0; j < NJ; j++)
        len += (size_t)snprintf(text + len, sizeof text - len,
                                "[joint.j%zu]\nslave = 1\naddress = %zu\ntype = int32\n"
                                "scale = 1000\nmin = -3.2\nmax = 3.2\nmax_step = 0.05\n"
                                "feedback = %zu\n",
                                j + 1, 2 * j, 100 + 2 * j);
    if (qo_regmap_parse(text, "soak18", map, err, sizeof err) != QO_OK) {
        fprintf(stderr, "soak: map: %s\n", err);
        return 0;
    }
    return 1;
}

static qo_regmap g_map; /* about 20 KiB: not on the stack */

static int soak_stream(unsigned long ticks, int short_mode)
{
    static struct traj tr;
    static qo_streamer str;
    struct fake_clock clk = { 1000000000ull };
    qo_sim *sim = NULL;
    qo_sim_settings ss = qo_sim_settings_default;
    qo_modbus_sink *ms = NULL;
    qo_modbus_sink_settings set = qo_modbus_sink_settings_default;
    qo_streamer_config cfg;
    qo_streamer_stats st;
    qo_modbus_sink_stats mst;
    qo_sim_stats sst;
    char spec[64];
    unsigned long k, warm = ticks / 100u;
    long rss_start = 0, rss_mid = 0, rss_end;
    double w0, w1, worst_final = 0.0, drift;
    uint64_t errors;
    size_t j;
    int ok = 1;

    if (!build_map(&g_map) || !traj_init(&tr)) return 0;
    ss.lag_s = 0.0;
    if (qo_sim_start("tcp://127.0.0.1:0", &g_map, &ss, &sim) != QO_OK) {
        fprintf(stderr, "soak: simulator did not start\n");
        return 0;
    }
    snprintf(spec, sizeof spec, "tcp://127.0.0.1:%d", qo_sim_port(sim));
    set.response_timeout_us = 200000; /* a loaded machine must not turn into errors here */
    set.byte_timeout_us = 50000;
    if (qo_modbus_sink_open(spec, &g_map, &set, &ms) != QO_OK) {
        fprintf(stderr, "soak: sink did not open\n");
        qo_sim_stop(sim);
        return 0;
    }
    cfg = qo_streamer_config_default;
    cfg.rate_hz = RATE_HZ;
    cfg.n_joints = NJ;
    cfg.sample = traj_sample;
    cfg.sample_ctx = &tr;
    (void)qo_modbus_sink_as_sink(ms, &cfg.sink);
    cfg.rt_priority = 0;
    cfg.lock_memory = 0;
    cfg.now = fake_now;
    cfg.sleep_until = fake_sleep_until;
    cfg.clock_ctx = &clk;
    if (qo_streamer_init(&str, &cfg) != QO_OK) return 0;

    w0 = wall_s();
    for (k = 0; k < ticks; k++) {
        (void)qo_streamer_tick(&str);
        if (k + 1 == warm) rss_start = rss_kib();
        if (k + 1 == ticks / 2u) rss_mid = rss_kib();
    }
    w1 = wall_s();
    rss_end = rss_kib();
    (void)qo_streamer_finish(&str);
    (void)qo_streamer_stats_read(&str, &st);
    (void)qo_modbus_sink_get_stats(ms, &mst);
    (void)qo_sim_wait_requests(sim, mst.requests, 1000);
    (void)qo_sim_get_stats(sim, &sst);
    for (j = 0; j < NJ; j++) {
        double tgt, pos;
        (void)qo_sim_get_joint(sim, j, &tgt, &pos);
        if (fabs(tgt - (double)tr.last[j]) > worst_final) worst_final = fabs(tgt - (double)tr.last[j]);
    }
    drift = tr.last_t - (double)(st.ticks - 1u) / RATE_HZ;
    qo_modbus_sink_free(ms);
    qo_sim_stop(sim);

    errors = st.overruns + st.sink_errors + st.sample_errors + mst.requests_failed +
             mst.timeouts + mst.exceptions + mst.protocol_errors + mst.disconnects +
             mst.common.reconnects + mst.rate_limited + mst.clamped + mst.saturated;
    printf("stream: %lu ticks x %d joints (%.0f Hz nominal, injected clock), wall %.1f s "
           "(%.1f us per tick: %u FC16 request(s) for %u registers)\n",
           ticks, NJ, RATE_HZ, w1 - w0, (w1 - w0) / (double)ticks * 1e6, mst.groups,
           2u * NJ);
    printf("stream: RSS after %lu ticks %ld KiB, at %lu %ld KiB, at %lu %ld KiB: growth "
           "warm-up->end %ld KiB, middle->end %ld KiB\n",
           warm, rss_start, ticks / 2u, rss_mid, ticks, rss_end, rss_end - rss_start,
           rss_end - rss_mid);
    printf("stream: streamer ticks %llu overruns %llu sink_errors %llu sample_errors %llu | "
           "sink requests %llu failed %llu timeouts %llu exceptions %llu protocol %llu "
           "disconnects %llu reconnects %llu limited %llu | sim requests %llu target writes "
           "%llu faults %llu\n",
           (unsigned long long)st.ticks, (unsigned long long)st.overruns,
           (unsigned long long)st.sink_errors, (unsigned long long)st.sample_errors,
           (unsigned long long)mst.requests, (unsigned long long)mst.requests_failed,
           (unsigned long long)mst.timeouts, (unsigned long long)mst.exceptions,
           (unsigned long long)mst.protocol_errors, (unsigned long long)mst.disconnects,
           (unsigned long long)mst.common.reconnects, (unsigned long long)mst.common.limited,
           (unsigned long long)sst.requests, (unsigned long long)sst.target_writes,
           (unsigned long long)sst.faults);
    printf("stream: final targets vs last sample max |diff| %.3g (resolution 5e-4); schedule "
           "drift %.3g s after %.1f s of trajectory time\n",
           worst_final, drift, tr.last_t);
    if (errors != 0) { printf("stream: FAIL: error counters not 0\n"); ok = 0; }
    if (st.ticks != ticks) { printf("stream: FAIL: %llu ticks\n", (unsigned long long)st.ticks); ok = 0; }
    if (sst.target_writes != (uint64_t)NJ * (ticks + 1u)) {
        printf("stream: FAIL: the simulator saw %llu target writes\n",
               (unsigned long long)sst.target_writes);
        ok = 0;
    }
    /* --short runs under valgrind, whose own heap grows: there valgrind judges the leaks */
    if (!short_mode && rss_end > rss_mid) {
        printf("stream: FAIL: memory grew after the middle\n");
        ok = 0;
    }
    /* the sample time is (wake - origin) * 1e-9 in double: exact to well under 1 ns */
    if (worst_final > 0.5e-3 + 1e-9 || fabs(drift) > 1e-9) { printf("stream: FAIL: final / drift\n"); ok = 0; }
    return ok;
}

/* ---- compositions ----------------------------------------------------------------------- */

static void compose(unsigned long n, unsigned long renorm_every)
{
    ref_rng rng = { 0x5eed50a4ull };
    qo_quat_f32 q = qo_quat_identity_f32();
    ref_quat d = { 1.0, 0.0, 0.0, 0.0 };
    double max_norm_dev = 0.0, max_angle = 0.0, norm_f, norm_d, angle, w0 = wall_s();
    unsigned long i;
    for (i = 0; i < n; i++) {
        qo_quat_f32 rf = ref_quat_to_f32(ref_rng_quat(&rng));
        ref_quat rd = ref_quat_from_f32(rf);
        q = qo_quat_mul_f32(q, rf);
        d = ref_quat_mul(d, rd);
        if (renorm_every != 0 && (i + 1u) % renorm_every == 0) {
            (void)qo_quat_normalize_f32(q, &q);
        }
        if ((i + 1u) % 1000u == 0) {
            double dev = fabs((double)qo_quat_norm_f32(q) - 1.0);
            if (dev > max_norm_dev) max_norm_dev = dev;
            /* keep the double reference at unit length: its own drift is not the question */
            d = ref_quat_normalize(d);
        }
        if ((i + 1u) % 100000u == 0) {
            angle = ref_quat_angle_between(ref_quat_from_f32(q), d);
            if (angle > max_angle) max_angle = angle;
        }
    }
    norm_f = (double)qo_quat_norm_f32(q);
    norm_d = ref_quat_norm(d);
    angle = ref_quat_angle_between(ref_quat_from_f32(q), d);
    if (angle > max_angle) max_angle = angle;
    if (renorm_every == 0)
        printf("compose: %lu products, never renormalised:", n);
    else
        printf("compose: %lu products, renormalised every %lu:", n, renorm_every);
    printf(" |norm-1| end %.3g max %.3g; double ref norm %.17g; angle to double end %.3g rad "
           "max %.3g rad; %.2f s\n",
           fabs(norm_f - 1.0), max_norm_dev, norm_d, angle, max_angle, wall_s() - w0);
}

int main(int argc, char **argv)
{
    int short_mode = argc > 1 && strcmp(argv[1], "--short") == 0;
    unsigned long ticks = short_mode ? 20000ul : 1000000ul;
    unsigned long n = short_mode ? 100000ul : 10000000ul;
    double w0 = wall_s();
    int ok;
    if (argc > 1 && !short_mode) {
        fprintf(stderr, "usage: soak [--short]\n");
        return 2;
    }
    ok = soak_stream(ticks, short_mode);
    compose(n, 0);
    compose(n, 1000000ul);
    compose(n, 1000ul);
    compose(n, 1ul);
    printf("soak: %s, total wall %.1f s\n", ok ? "ok" : "FAIL", wall_s() - w0);
    return ok ? 0 : 1;
}
