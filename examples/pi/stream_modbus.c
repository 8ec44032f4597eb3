/*
 * examples/pi/stream_modbus.c - stream a smooth multi-joint move to Modbus servo drives from
 * a Raspberry Pi (or any Linux box): RS-485 Modbus RTU or Modbus TCP.
 *
 *   stream_modbus MAP SPEC [TARGET...]
 *     MAP     register map of the drive bank (INI; the files in examples/maps, format in
 *             ports/linux/regmap.h): slaves, registers, types, scale, limits, max_step
 *     SPEC    tcp://HOST:PORT or rtu:DEVICE,BAUD,8N1 (e.g. rtu:/dev/ttyAMA0,115200,8N1)
 *     TARGET  one final position per joint of the map, in joint units. Without targets a
 *             demo runs: joint j heads for -0.2 (j + 1) (-1)^j and, 0.5 s later, is re-planned
 *             mid-move to its final target 0.1 (j + 1) (-1)^j.
 *
 * What it does, and which part of qorient does it:
 *   1. qo_regmap_load reads the map; on RTU, qo_wire_budget_compute says how long one tick's
 *      requests take on the serial line (linux/wire_budget.h): a rate the line cannot carry
 *      is refused, and the reply timeout covers the longest request; qo_modbus_sink_open
 *      connects, sends the drives' init writes and seeds its rate limit from the feedback
 *      registers (linux/modbus_sink.h);
 *   2. qo_modbus_sink_read_feedback gives the joints' actual positions (0 where the map has no
 *      feedback register): the motion starts where the drives are, not where we think they are;
 *   3. a jerk-limited, time-synchronised move of all joints in a trajectory object
 *      (qorient/traj.h over qorient/motion.h, S-curve: every joint arrives together, position,
 *      velocity and acceleration continuous): the start and the targets are pushed with their
 *      times (integer ns), and each target is re-planned from the current state when it
 *      becomes due (the demo's second target);
 *   4. the periodic streamer (linux/streamer.h) samples the move at 100 Hz on an absolute
 *      CLOCK_MONOTONIC schedule (SCHED_FIFO and mlockall when allowed) and hands every tick's
 *      targets to the Modbus sink, which clamps, rate-limits (max_step), packs and sends one
 *      FC16 per contiguous register block; on a drive timeout it holds and resumes smoothly;
 *   5. once every joint is at rest on its target (plus 0.2 s), or on Ctrl-C, the streamer
 *      sends the last target once more and the program prints its statistics.
 * Exit status: 0 when the final target reached the drives; 1 on a runtime error (map, link,
 * drive); 2 on a usage error.
 *
 * Build on the Pi (Debian/Raspberry Pi OS: apt install libmodbus-dev libgpiod-dev libinih-dev):
 *   make examples                      (build/examples/stream_modbus), or after `make install`:
 *   cc -std=c99 -O2 -D_POSIX_C_SOURCE=200809L stream_modbus.c \
 *       $(pkg-config --cflags --libs qorient-ports) -o stream_modbus
 * Try it without drives against the simulated bank:
 *   qorient sim --map examples/maps/six_int32.ini --listen tcp://127.0.0.1:1502 &
 *   build/examples/stream_modbus examples/maps/six_int32.ini tcp://127.0.0.1:1502
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "qorient/traj.h"
#include "linux/modbus_sink.h"
#include "linux/regmap.h"
#include "linux/streamer.h"
#include "linux/wire_budget.h"

#define EX_RATE_HZ 100.0         /* streaming rate */
#define EX_HOLD_S 0.2            /* keep sending the final target this long after arriving */
#define EX_REPLAN_NS 500000000LL /* demo: when the second target is issued (0.5 s) */
#define EX_QUEUE 4               /* targets the trajectory can hold before they are due */

/* Per-joint limits of the demo move, in joint units (rad for the example maps). Keep vmax
 * below the map's max_step * rate, or the sink's rate limit will hold joints back. */
#define EX_VMAX 1.5f
#define EX_AMAX 4.0f
#define EX_JMAX 30.0f

struct move {
    qo_traj tr;
    qo_motion_joint_f32 joints[QO_REGMAP_MAX_JOINTS];
    qo_traj_ns t[EX_QUEUE];
    float store[EX_QUEUE * QO_REGMAP_MAX_JOINTS];
    qo_motion_limits_f32 lim[QO_REGMAP_MAX_JOINTS];
    float final[QO_REGMAP_MAX_JOINTS];
    qo_streamer *st;
    volatile int ended; /* the move ran to its end (not stopped by Ctrl-C) */
};

/* The streamer's producer: runs in the streaming thread; every push happened before the
 * streaming started, so no lock is needed. t is seconds since the streaming started, which
 * is trajectory time 0. */
static qo_status sample_move(void *ctx, double t, float *targets, size_t n)
{
    struct move *m = ctx;
    qo_traj_ns tn = (qo_traj_ns)llround(t * 1e9);
    qo_status st = qo_traj_sample(&m->tr, tn, targets, NULL, NULL, NULL);
    (void)n;
    if (st != QO_OK) return st; /* a refused target: the planner brakes; the streamer holds */
    if (qo_traj_done(&m->tr, tn - (qo_traj_ns)(EX_HOLD_S * 1e9))) {
        m->ended = 1;
        qo_streamer_request_stop(m->st);
    }
    return QO_OK;
}

static int usage(void)
{
    fputs("usage: stream_modbus MAP SPEC [TARGET...]\n"
          "  MAP     register map (INI, see examples/maps)\n"
          "  SPEC    tcp://HOST:PORT or rtu:DEVICE,BAUD,8N1\n"
          "  TARGET  final position of each joint of the map (default: a demo move)\n", stderr);
    return 2;
}

int main(int argc, char **argv)
{
    static qo_regmap map;        /* ~20 KiB: not on the stack */
    static struct move mv;
    static qo_streamer st;
    static qo_wire_budget wb;    /* ~10 KiB */
    qo_modbus_link_spec spec;
    double longest_us = 0.0;
    float start[QO_REGMAP_MAX_JOINTS], first[QO_REGMAP_MAX_JOINTS];
    qo_modbus_sink_settings ss = qo_modbus_sink_settings_default;
    qo_modbus_sink *sink = NULL;
    qo_modbus_sink_stats ms;
    qo_streamer_config cfg;
    qo_streamer_stats sst;
    const char *warn = NULL;
    char err[256];
    size_t n, j;
    qo_status s;
    int rc = 1;

    if (argc < 3) return usage();
    if (qo_regmap_load(argv[1], &map, err, sizeof err) != QO_OK) {
        fprintf(stderr, "stream_modbus: %s\n", err);
        return 1;
    }
    n = map.n_joints;
    if (argc != 3 && (size_t)(argc - 3) != n) {
        fprintf(stderr, "stream_modbus: %s has %zu joints but %d targets were given\n", argv[1], n,
                argc - 3);
        return usage();
    }
    for (j = 0; j < n; j++) {
        const double sign = (j % 2u) ? -1.0 : 1.0;
        if (argc > 3) {
            char *end;
            double v = strtod(argv[3 + j], &end);
            if (end == argv[3 + j] || *end != '\0' || !isfinite(v)) {
                fprintf(stderr, "stream_modbus: target '%s' is not a number\n", argv[3 + j]);
                return usage();
            }
            mv.final[j] = (float)v;
        } else {
            mv.final[j] = (float)(0.1 * (double)(j + 1) * sign);
        }
        first[j] = argc > 3 ? mv.final[j] : -2.0f * mv.final[j];
        mv.lim[j] = qo_motion_limits_default;
        mv.lim[j].vmax = EX_VMAX;
        mv.lim[j].amax = EX_AMAX;
        mv.lim[j].jmax = EX_JMAX;
        mv.lim[j].pmin = (float)map.joints[j].min; /* -INFINITY / INFINITY when the map has none */
        mv.lim[j].pmax = (float)map.joints[j].max;
    }

    /* What one tick costs on a serial line (TCP has no such bound). */
    if (qo_modbus_link_parse_spec(argv[2], &spec) != QO_OK) {
        fprintf(stderr, "stream_modbus: '%s' is not tcp://HOST:PORT or rtu:DEVICE,BAUD,8N1\n",
                argv[2]);
        return usage();
    }
    if (qo_wire_budget_compute(&map, &spec, 0.0, &wb) != QO_OK) {
        fprintf(stderr, "stream_modbus: %s: cannot group the registers into requests\n", argv[1]);
        return 1;
    }
    if (spec.transport == QO_MODBUS_LINK_RTU && EX_RATE_HZ > wb.max_rate_hz) {
        fprintf(stderr, "stream_modbus: %.0f Hz needs more than %s carries (%.0f us per tick, "
                "at most %.1f Hz): raise the baud rate or lower EX_RATE_HZ\n", EX_RATE_HZ,
                argv[2], wb.tick_us, wb.max_rate_hz);
        return 1;
    }
    for (j = 0; j < wb.n_requests; j++)
        if (wb.req[j].time_us > longest_us) longest_us = wb.req[j].time_us;

    /* Replies must come within the period, so one slow drive cannot eat the next tick - but
     * on RTU the timeout also runs while the request itself is on the wire. Connecting
     * happens before the loop and may take longer. */
    ss.response_timeout_us = (uint32_t)fmax(0.8 * 1e6 / EX_RATE_HZ, longest_us + 1000.0);
    ss.byte_timeout_us = ss.response_timeout_us;
    ss.open_timeout_us = 500000u;
    s = qo_modbus_sink_open(argv[2], &map, &ss, &sink);
    if (s != QO_OK) {
        fprintf(stderr, "stream_modbus: cannot reach the drives at %s: %s\n", argv[2],
                qo_status_str(s));
        return s == QO_E_CONFIG ? usage() : 1;
    }

    /* Start where the drives are. */
    s = qo_modbus_sink_read_feedback(sink, start, n);
    for (j = 0; j < n; j++)
        if (s != QO_OK || !isfinite(start[j])) start[j] = 0.0f;
    if (s == QO_OK) (void)qo_modbus_sink_seed(sink, start, n);

    /* The start (at rest where the drives are), the first target at once, and for the demo
     * the final target 0.5 s later, re-planned mid-move from wherever the joints are then. */
    if (qo_traj_init_targets(&mv.tr, n, mv.lim, NULL, mv.joints, mv.t, EX_QUEUE, mv.store,
                             sizeof mv.store / sizeof mv.store[0]) != QO_OK ||
        qo_traj_push(&mv.tr, 0, start, NULL, NULL) != QO_OK ||
        qo_traj_push(&mv.tr, 0, first, NULL, NULL) != QO_OK ||
        (argc == 3 && qo_traj_push(&mv.tr, EX_REPLAN_NS, mv.final, NULL, NULL) != QO_OK) ||
        qo_traj_sample(&mv.tr, 0, start, NULL, NULL, NULL) != QO_OK) {
        fprintf(stderr, "stream_modbus: the move cannot be planned (limits or targets)\n");
        goto out;
    }
    mv.st = &st;
    printf("stream_modbus: %zu joint(s) from %s, %.3f s to the %s target at %.0f Hz\n", n,
           s == QO_OK ? "their feedback" : "0 (no feedback)",
           (double)qo_motion_duration_f32(&mv.tr.planner), argc == 3 ? "first" : "final",
           EX_RATE_HZ);

    cfg = qo_streamer_config_default;
    cfg.rate_hz = EX_RATE_HZ;
    cfg.n_joints = n;
    cfg.sample = sample_move;
    cfg.sample_ctx = &mv;
    (void)qo_modbus_sink_as_sink(sink, &cfg.sink); /* QO_E_NULL only */
    s = qo_streamer_init(&st, &cfg);
    if (s != QO_OK) {
        fprintf(stderr, "stream_modbus: streamer: %s\n", qo_status_str(s));
        goto out;
    }
    qo_streamer_install_stop_signals(&st);
    s = qo_streamer_run(&st); /* until the move is done (or Ctrl-C); then the final write */

    /* Done means the drives hold the final target, not that the plan ended: the max_step
     * catch-up may still be on its way (a drive that missed ticks, a map with a small step). */
    if (s == QO_OK && mv.ended) {
        qo_traj_ns end = 0;
        float goal[QO_REGMAP_MAX_JOINTS];
        qo_modbus_sink_settle_report rep;
        (void)qo_traj_end_time(&mv.tr, &end);
        s = qo_traj_sample(&mv.tr, end, goal, NULL, NULL, NULL);
        if (s == QO_OK)
            s = qo_modbus_sink_settle(sink, goal, n, 1.0 / EX_RATE_HZ,
                                      qo_modbus_sink_settle_time(sink, goal, n, 1.0 / EX_RATE_HZ), &rep);
        if (s != QO_OK) fprintf(stderr, "stream_modbus: the drives do not hold the final target: %s\n",
                                qo_status_str(s));
    }
    (void)qo_streamer_rt_report(&st, &warn);
    if (warn != NULL && *warn != '\0') printf("stream_modbus: note: %s\n", warn);
    qo_streamer_stats_read(&st, &sst);
    qo_modbus_sink_get_stats(sink, &ms);
    printf("stream_modbus: ticks %llu overruns %llu jitter p99 %.1f us max %.1f us; "
           "requests %llu timeouts %llu reconnects %llu rate-limited %llu; final: %s\n",
           (unsigned long long)sst.ticks, (unsigned long long)sst.overruns, sst.lat_p99_ns / 1e3,
           sst.lat_max_ns / 1e3, (unsigned long long)ms.requests, (unsigned long long)ms.timeouts,
           (unsigned long long)ms.common.reconnects, (unsigned long long)ms.rate_limited,
           qo_status_str(s));
    rc = s == QO_OK ? 0 : 1;
out:
    qo_modbus_sink_free(sink);
    return rc;
}
