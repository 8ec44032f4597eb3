/*
 * qorient stream --map FILE (--modbus SPEC | --gpio CHIP --lines ...) [plan options] [--live] [FILE|-]
 *
 * Reads keyframes or targets with the planning options of `qorient plan` (cli/planopt.c: the
 * same reader, options and qorient/traj.h trajectory, nothing printed and read back), refuses a
 * plan whose joint count differs from the drives' before anything is written, then streams it
 * with the periodic streamer: each tick samples the trajectory at the ACTUAL wake time and
 * hands the targets to the sink. With --live, targets are read from standard input WHILE
 * streaming (a reader thread) and pushed into the same trajectory, re-planned from the current
 * state. Progress on a terminal, a summary at the end, a clean stop on SIGINT/SIGTERM leaving
 * the drives on the last sampled target.
 */
#include "../cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "linux/gpio_sink.h"
#include "linux/modbus_sink.h"
#include "linux/regmap.h"
#include "linux/streamer.h"
#include "linux/wire_budget.h"

static const char stream_usage[] =
    "usage: qorient stream --map FILE --modbus SPEC [OPTIONS] [PLAN OPTIONS] [FILE|-]\n"
    "       qorient stream --gpio CHIP --lines STEP:DIR[,STEP:DIR...] [OPTIONS] [PLAN OPTIONS] [FILE|-]\n"
    "       qorient stream ... --profile trapezoid|scurve --vmax V --amax A [--jmax J] --live\n"
    "\n"
    "Reads keyframes or targets exactly as 'qorient plan' does (same input, same options:\n"
    "--profile, --vmax, --amax, --jmax, --vmin, --amin, --sync, --target-velocities,\n"
    "--min-duration, --discrete, --min, --max, --wrap, --degrees, ...; with --discrete a move\n"
    "ends on a tick of --rate),\n"
    "plans the motion and streams it to servo drives at --rate HZ (default 100): each tick\n"
    "samples the trajectory at the actual wake time and sends every joint's target. A plan\n"
    "whose joint count differs from the map's (or the --lines list's) is refused, naming both,\n"
    "before anything is sent.\n"
    "\n"
    "Live targets (--live, with --profile trapezoid|scurve): standard input gives lines\n"
    "'p1,...,pN' (no time column; at most 65535 characters; with --target-velocities\n"
    "'p1,...,pN,v1,...,vN'). The first line is the start (the\n"
    "joints at rest there; read before streaming begins); every later line is a new target,\n"
    "applied when it arrives and re-planned from the current position, velocity and\n"
    "acceleration. A bad line is reported (naming it) and skipped; the exit status is then 1.\n"
    "A longer line ends the input there. At end of input the motion finishes, the hold runs\n"
    "and the command exits.\n"
    "\n"
    "Modbus (the register map gives slaves, registers, types, scale, limits, max_step):\n"
    "  --map FILE          register map (INI, see examples/maps); its joints, in file order,\n"
    "                      are the plan's columns p1..pN\n"
    "  --modbus SPEC       tcp://HOST:PORT or rtu:DEVICE,BAUD,8N1 (parity N, E or O)\n"
    "  --timeout-ms MS     response timeout, in [0.1, 60000] (default 0.8 x the period,\n"
    "                      within 2..20 ms); on TCP a later reply is still accepted at the\n"
    "                      next tick, and a link silent for 20 x this (at least 1 s) is\n"
    "                      reconnected\n"
    "  --on-fail hold|disable  after repeated failures: hold the last target (default) or\n"
    "                      send the map's disable writes\n"
    "  --turnaround-us US  the drives' reply delay, for the RTU wire budget, in [0, 1e6]\n"
    "                      (default 0)\n"
    "GPIO step/dir (libgpiod):\n"
    "  --gpio CHIP         chip name, path or label (e.g. gpiochip0, pinctrl-rp1)\n"
    "  --lines S:D,...     step and dir line offsets per joint\n"
    "  --steps-per-unit K[,K...]  steps per joint unit (default 200)\n"
    "  --step-rate HZ[,HZ...]     maximum step rate (default 1000)\n"
    "Streaming:\n"
    "  --rate HZ           tick rate, in [0.001, 100000] (default 100)\n"
    "  --hold S            keep streaming the final target for S seconds, in [0, 86400]\n"
    "                      (default 0.2)\n"
    "  --settle S          Modbus: after the plan (and --hold), keep sending the final target\n"
    "                      until every drive holds it (acknowledged, then read back) or S\n"
    "                      seconds pass, in [0, 86400]; default: twice the max_step catch-up\n"
    "                      time from what the drives hold, plus 0.5 s\n"
    "  --live              targets from standard input while streaming (see above)\n"
    "  --dry-run           check the map and the plan, print the per-tick wire budget (and\n"
    "                      for RTU the highest rate the line allows), send nothing\n"
    "  --no-rt             do not ask for SCHED_FIFO / mlockall\n"
    "  --quiet             no live progress line\n"
    "  --log FILE          one CSV line per target handed to the drives, with the tick's\n"
    "                      scheduled time (see 'Tick log' below)\n"
    "  -h, --help          this text\n"
    "\n"
    "On RTU a --rate above what the wire allows is refused (see --dry-run). Live progress\n"
    "(rate, jitter, errors) is shown on a terminal; a summary line 'summary: ...' is printed\n"
    "at the end. SIGINT/SIGTERM stop cleanly: the drives get the last sampled target.\n";

/* Apart from stream_usage: C99 guarantees string literals of 4095 characters only. */
static const char stream_fields[] =
    "\n"
    "Summary fields (counts over the whole run, settling included):\n"
    "  ticks         periods the streamer ran (sampled and handed to the sink)\n"
    "  overruns      periods skipped because a tick's work ended after the next deadline\n"
    "  jitter_*_us   wake-up latency after each deadline: median, 99th percentile, maximum\n"
    "  sink_errors   ticks whose targets did not all reach the drives (any of the below)\n"
    "  requests      Modbus requests sent (writes, read-backs, feedback reads)\n"
    "  timeouts      requests not answered within --timeout-ms\n"
    "  late_replies  TCP: replies taken after their tick, matched by transaction id and\n"
    "                accepted (the drive applied the write)\n"
    "  skipped       TCP: slave-ticks not sent because that slave's previous request was\n"
    "                still unanswered (one outstanding request per slave, never queued)\n"
    "  readbacks     target registers read back to learn what a drive holds (after an\n"
    "                unknown outcome or a reconnection; in a fault-free run only the\n"
    "                settle's final confirmation, one per request)\n"
    "  exceptions    exception replies (the drive refused a request: nothing applied)\n"
    "  reconnects    links re-established after a broken or silent connection\n"
    "  rate_limited  joint values held back by the map's max_step\n"
    "  clamped       joint values changed by the map's min/max\n"
    "  settle_s      Modbus: time spent after the plan until the drives held the final\n"
    "                target (see --settle)\n"
    "  final         ok: the drives hold the final target (read back); short: not within\n"
    "                --settle (each short joint is named on stderr); or the status of the\n"
    "                last write (GPIO, or stopped by a signal)\n"
    "\n"
    "Exit status 0 when the plan ran to its end and (Modbus) every drive holds the final\n"
    "target; 1 on a runtime error (map, device, unreachable drive, bad or failed plan, joint\n"
    "count mismatch, a bad --live line, a drive short of its final target after --settle:\n"
    "each such joint is named with how far it is short); 2 on a usage error. Stopped by a\n"
    "signal: 0 when the last sampled target was written.\n";

static const char stream_log_fields[] =
    "\n"
    "Tick log (--log FILE, CSV: a header line, then one line per write to the drives, the final\n"
    "one included; FILE is created or truncated before streaming and written through a 1 MiB\n"
    "buffer from the streaming thread):\n"
    "  tick          the tick number the drives were sent (0, 1, ...)\n"
    "  scheduled_s   when the tick was due: its deadline in seconds since streaming began\n"
    "                (k / --rate on the k-th period; for the final write after the stop, the\n"
    "                next deadline)\n"
    "  sampled_s     the time the targets were sampled at (the tick's actual wake time, on the\n"
    "                same axis: the plan's time minus its first time)\n"
    "  write         ok, or why the write failed (as the summary's final)\n"
    "  p1..pN        the targets handed to the sink, in the plan's units (before the map's\n"
    "                min/max and max_step)\n"
    "A write error on FILE makes the exit status 1.\n";

/* Live input lines longer than this are refused (bounded memory for a pipe from anywhere). */
#define STREAM_LINE_MAX 65536
/* Targets that may arrive within one tick before the reader waits for the sampler. */
#define STREAM_LIVE_QUEUE 64

struct stream_ctx {
    struct qo_cli_plan *plan;
    qo_traj_ns t0;              /* trajectory time of streaming time 0 */
    qo_traj_ns hold;
    qo_streamer *st;
    volatile sig_atomic_t ended; /* the plan ran to its end (not stopped by a signal) */
    /* --live: the reader thread pushes, the streamer thread samples, under `lock` */
    int live;
    pthread_mutex_t lock;
    qo_traj_ns last;            /* latest trajectory time sampled */
    volatile int eof;           /* the reader reached the end of input */
    int bad_lines;
    double sampled;             /* time of the last successful sample (for --log) */
    const struct qo_cli_plan_opts *opts;
    struct qo_cli_rows rows;    /* the start line (row 0) and a scratch row 1 */
    long lineno;
};

/* A sample status that still gives a defined motion: a target the planner refused makes it
 * brake (QO_E_NONFINITE, QO_E_RANGE, QO_E_LIMIT) and its samples are streamed as usual. */
static qo_status traj_sample_ok(qo_status s)
{
    return s == QO_E_NONFINITE || s == QO_E_RANGE || s == QO_E_LIMIT ? QO_OK : s;
}

static qo_status sample_traj(void *vctx, double t, float *targets, size_t n)
{
    struct stream_ctx *c = vctx;
    qo_traj_ns tn = c->t0 + (qo_traj_ns)llround(t * 1e9), end = 0;
    qo_status s;
    int finished;
    (void)n;
    if (c->live) pthread_mutex_lock(&c->lock);
    s = qo_traj_sample(&c->plan->tr, tn, targets, NULL, NULL, NULL);
    if (tn > c->last) c->last = tn;
    (void)qo_traj_end_time(&c->plan->tr, &end);
    finished = (!c->live || c->eof) && qo_traj_done(&c->plan->tr, tn) && tn >= end + c->hold;
    if (c->live) pthread_mutex_unlock(&c->lock);
    if (finished) {
        c->ended = 1;
        qo_streamer_request_stop(c->st);
    }
    s = traj_sample_ok(s);
    if (s == QO_OK) c->sampled = t;
    return s;
}

/* --log FILE: a sink in front of the drives' that writes one CSV line per write (streamer
 * thread only, like every sink call). */
struct tick_log {
    FILE *f;
    qo_sink inner;
    qo_streamer *st;
    const struct stream_ctx *sc;
};

static qo_status tick_log_write(void *ctx, const float *targets, size_t n, uint64_t tick)
{
    struct tick_log *l = ctx;
    qo_status s = qo_sink_write(&l->inner, targets, n, tick);
    uint64_t due = 0;
    size_t j;
    (void)qo_streamer_tick_deadline(l->st, &due);
    fprintf(l->f, "%llu,%.9f,%.9f,%s", (unsigned long long)tick, (double)due * 1e-9, l->sc->sampled,
            s == QO_OK ? "ok" : qo_status_str(s));
    for (j = 0; j < n; j++) fprintf(l->f, ",%.9g", (double)targets[j]);
    fputc('\n', l->f);
    return s;
}

static void tick_log_service(void *ctx)
{
    struct tick_log *l = ctx;
    if (l->inner.service) l->inner.service(l->inner.ctx);
}

/* Reads one live line into buf (NUL bytes kept: the parser refuses them); returns its length,
 * -1 at end of input, -2 when the line is longer than the buffer (its rest is discarded). */
static long read_live_line(char *buf, size_t cap, FILE *f)
{
    size_t len = 0;
    int ch;
    while ((ch = getc(f)) != EOF && ch != '\n') {
        /* the rest is left unread and reading stops: skipping to the newline would never end
         * on an endless line (/dev/zero) */
        if (len + 1 >= cap) return -2;
        buf[len++] = (char)ch;
    }
    if (ch == EOF && (len == 0 || ferror(f))) return -1;
    buf[len] = '\0';
    if (len > 0 && buf[len - 1] == '\r') buf[--len] = '\0';
    return (long)len;
}

/* One live line: parsed like a plan line without the time column, pushed at the latest time
 * sampled (so it is applied from the state the drives were just sent). */
static void live_line(struct stream_ctx *c, char *buf, long len)
{
    size_t keep = c->rows.rows;
    qo_status s = QO_OK;
    c->lineno++;
    if (len == -2) {
        fprintf(stderr, "qorient stream: -: line %ld: longer than %d characters: the input ends here\n",
                c->lineno, STREAM_LINE_MAX - 1);
        c->bad_lines++;
        return;
    }
    if (qo_cli_rows_add("stream", "-", c->opts, 0, c->lineno, buf, len, &c->rows) != 0) {
        c->bad_lines++;
        return;
    }
    if (c->rows.rows == keep) return; /* blank or comment */
    /* A full queue empties at the next tick: wait for room rather than drop a target. */
    for (;;) {
        int room;
        pthread_mutex_lock(&c->lock);
        room = c->plan->tr.count < c->plan->tr.cap;
        if (room) s = qo_cli_plan_push("stream", "-", c->plan, c->last, c->rows.v + c->rows.width, c->lineno) ? QO_E_ARG : QO_OK;
        pthread_mutex_unlock(&c->lock);
        if (room) break;
        {
            struct timespec ts = { 0, 1000000 };
            nanosleep(&ts, NULL);
        }
    }
    if (s != QO_OK) c->bad_lines++;
    c->rows.rows = 1; /* keep the start line only: memory stays bounded */
}

static void *live_reader(void *vctx)
{
    struct stream_ctx *c = vctx;
    char *buf = malloc(STREAM_LINE_MAX);
    long len;
    while (buf != NULL && (len = read_live_line(buf, STREAM_LINE_MAX, stdin)) != -1) {
        live_line(c, buf, len);
        if (len == -2) break; /* an over-long line ends the input */
    }
    if (buf == NULL || ferror(stdin)) {
        fprintf(stderr, "qorient stream: standard input: read error\n");
        c->bad_lines++;
    }
    free(buf);
    pthread_mutex_lock(&c->lock);
    c->eof = 1;
    pthread_mutex_unlock(&c->lock);
    return NULL;
}

/* --live: the start line, read before streaming. Returns 0 or 1 (message printed). */
static int live_start(struct stream_ctx *c)
{
    char *buf = malloc(STREAM_LINE_MAX);
    long len = -1;
    int rc = 1;
    while (buf != NULL && (len = read_live_line(buf, STREAM_LINE_MAX, stdin)) != -1) {
        c->lineno++;
        if (len == -2) {
            fprintf(stderr, "qorient stream: -: line %ld: longer than %d characters\n", c->lineno, STREAM_LINE_MAX - 1);
            break;
        }
        if (qo_cli_rows_add("stream", "-", c->opts, 0, c->lineno, buf, len, &c->rows) != 0) break;
        if (c->rows.rows == 1) {
            rc = 0;
            break;
        }
    }
    if (rc && c->rows.rows == 0 && buf != NULL && len == -1)
        fprintf(stderr, "qorient stream: -: --live needs a start line p1,...,pN on standard input\n");
    free(buf);
    return rc;
}

static void print_budget(const qo_wire_budget *b, const qo_modbus_link_spec *spec, double rate)
{
    size_t i;
    printf("dry-run: %zu request(s) per tick (FC16)\n", b->n_requests);
    for (i = 0; i < b->n_requests; i++) {
        const qo_wire_budget_request *r = &b->req[i];
        printf("  slave %u: registers %u..%u (%u), request %u bytes, reply %u bytes",
               r->slave, r->first, r->first + r->registers - 1, r->registers, r->request_bytes, r->reply_bytes);
        if (spec->transport == QO_MODBUS_LINK_RTU) printf(", %.0f us on the wire", r->time_us);
        putchar('\n');
    }
    if (spec->transport == QO_MODBUS_LINK_RTU) {
        printf("rtu: %d baud %d%c%d: %u bits/char, %.1f us/char, t3.5 = %.0f us\n", spec->baud,
               spec->data_bits, spec->parity, spec->stop_bits, b->bits_per_char, b->char_us, b->t35_us);
        printf("wire budget per tick: %.0f us; highest rate: %.1f Hz; requested %g Hz: %s\n",
               b->tick_us, b->max_rate_hz, rate, rate <= b->max_rate_hz ? "fits" : "does NOT fit");
    } else {
        printf("tcp: no wire-time bound (the network and the drives' reply time decide)\n");
    }
}

/* After the plan: the drives must hold its final position, the trajectory's value at its end
 * (see qo_modbus_sink_settle). Names every joint that is short on stderr. 0 when reached,
 * else 1; *elapsed = time spent settling. */
static int stream_settle(qo_modbus_sink *ms, const qo_regmap *map, qo_traj *tr, size_t n, double rate,
                         double settle, double *elapsed)
{
    float final[QO_REGMAP_MAX_JOINTS];
    qo_modbus_sink_settle_report rep;
    qo_traj_ns end = 0;
    qo_status s;
    size_t j;
    *elapsed = 0.0;
    (void)qo_traj_end_time(tr, &end);
    s = traj_sample_ok(qo_traj_sample(tr, end, final, NULL, NULL, NULL));
    if (s != QO_OK) {
        fprintf(stderr, "qorient stream: cannot sample the final target: %s\n", qo_status_str(s));
        return 1;
    }
    if (settle < 0) settle = qo_modbus_sink_settle_time(ms, final, n, 1.0 / rate);
    s = qo_modbus_sink_settle(ms, final, n, 1.0 / rate, settle, &rep);
    *elapsed = rep.elapsed_s;
    if (s == QO_OK) return 0;
    fprintf(stderr, "qorient stream: the drives do not hold the final target after %.3f s of --settle (%s):",
            rep.deadline_s, qo_status_str(s));
    for (j = 0; j < rep.n; j++)
        if (rep.short_of[j])
            fprintf(stderr, " %s at %.9g, short by %.9g;", map->joints[j].name, rep.held[j],
                    rep.goal[j] - rep.held[j]);
    fputc('\n', stderr);
    return 1;
}

enum { SO_MAP = QO_CLI_OPT_LAST_, SO_MODBUS, SO_GPIO, SO_LINES, SO_SPU, SO_STEP_RATE, SO_ON_FAIL, SO_HOLD,
       SO_TIMEOUT, SO_TURNAROUND, SO_DRY, SO_NO_RT, SO_QUIET, SO_LIVE, SO_SETTLE, SO_LOG };

int qo_cli_stream(int argc, char **argv)
{
    static const struct option opts[] = {
        QO_CLI_PLAN_OPTIONS,
        { "map", required_argument, NULL, SO_MAP }, { "modbus", required_argument, NULL, SO_MODBUS },
        { "gpio", required_argument, NULL, SO_GPIO }, { "lines", required_argument, NULL, SO_LINES },
        { "steps-per-unit", required_argument, NULL, SO_SPU },
        { "step-rate", required_argument, NULL, SO_STEP_RATE },
        { "on-fail", required_argument, NULL, SO_ON_FAIL }, { "hold", required_argument, NULL, SO_HOLD },
        { "timeout-ms", required_argument, NULL, SO_TIMEOUT },
        { "turnaround-us", required_argument, NULL, SO_TURNAROUND },
        { "dry-run", no_argument, NULL, SO_DRY }, { "no-rt", no_argument, NULL, SO_NO_RT },
        { "quiet", no_argument, NULL, SO_QUIET }, { "live", no_argument, NULL, SO_LIVE },
        { "settle", required_argument, NULL, SO_SETTLE }, { "log", required_argument, NULL, SO_LOG },
        { "help", no_argument, NULL, 'h' }, { NULL, 0, NULL, 0 }
    };
    const char *map_path = NULL, *modbus = NULL, *gpio = NULL, *lines = NULL, *in_path = "-";
    const char *spu_s = NULL, *step_rate_s = NULL, *on_fail = "hold", *log_path = NULL;
    static struct tick_log tl;
    double rate = 100.0, hold = 0.2, timeout_ms = -1, turnaround = 0, settle = -1;
    int dry = 0, no_rt = 0, quiet = 0, live = 0, c, rc = 1, reader = 0;
    static qo_regmap map; /* 20 KiB: not on the stack */
    /* GPIO: step and dir line offsets per joint, steps per unit, step rates */
    double sp[QO_GPIO_SINK_MAX_LINES], spu[QO_GPIO_SINK_MAX_JOINTS], sr[QO_GPIO_SINK_MAX_JOINTS];
    struct qo_cli_plan_opts po;
    struct qo_cli_rows rows;
    static struct qo_cli_plan plan;
    static struct stream_ctx sc;
    pthread_t reader_thread;
    qo_streamer st;
    qo_streamer_config cfg;
    qo_modbus_sink *ms = NULL;
    qo_gpio_sink *gs = NULL;
    size_t n_joints = 0, plan_joints;
    char err[256];
    qo_status s;

    memset(&rows, 0, sizeof rows);
    memset(&plan, 0, sizeof plan);
    memset(&sc, 0, sizeof sc);
    memset(&tl, 0, sizeof tl);
    qo_cli_plan_opts_default(&po);
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        int bad = 0;
        switch (c) {
        case 'h': fputs(stream_usage, stdout); fputs(stream_fields, stdout); fputs(stream_log_fields, stdout); return 0;
        case SO_MAP: map_path = optarg; break;
        case SO_MODBUS: modbus = optarg; break;
        case SO_GPIO: gpio = optarg; break;
        case SO_LINES: lines = optarg; break;
        case SO_SPU: spu_s = optarg; break;
        case SO_STEP_RATE: step_rate_s = optarg; break;
        case SO_ON_FAIL: on_fail = optarg; break;
        /* the streamer's rate bound, not plan's */
        case QO_CLI_OPT_RATE: bad = qo_cli_number("stream", "--rate", optarg, QO_CLI_RATE_MIN, 100000.0, "Hz", &rate); break;
        case SO_HOLD: bad = qo_cli_number("stream", "--hold", optarg, 0.0, 86400.0, "s", &hold); break;
        case SO_TIMEOUT: bad = qo_cli_number("stream", "--timeout-ms", optarg, 0.1, 60000.0, "ms", &timeout_ms); break;
        case SO_TURNAROUND: bad = qo_cli_number("stream", "--turnaround-us", optarg, 0.0, 1e6, "us", &turnaround); break;
        case SO_SETTLE: bad = qo_cli_number("stream", "--settle", optarg, 0.0, 86400.0, "s", &settle); break;
        case SO_DRY: dry = 1; break;
        case SO_NO_RT: no_rt = 1; break;
        case SO_QUIET: quiet = 1; break;
        case SO_LIVE: live = 1; break;
        case SO_LOG: log_path = optarg; break;
        case '?': bad = 2; break;
        default: bad = qo_cli_plan_opt("stream", &po, c, optarg); break;
        }
        if (bad) goto usage;
    }
    /* --discrete rounds durations to ticks of the stream's --rate (plan's --rate is its
     * sample rate, which stream does not have) */
    po.rate = rate;
    if (qo_cli_plan_opts_check("stream", &po) != 0) goto usage;
    if (po.fixed) {
        fprintf(stderr, "qorient stream: --fixed: the stream samples with float32 (use plan --fixed to see the "
                "fixed-point samples)\n");
        goto usage;
    }
    if (live && !po.motion) {
        fprintf(stderr, "qorient stream: --live takes targets: give --profile trapezoid|scurve\n");
        goto usage;
    }
    if (optind + 1 < argc) {
        fprintf(stderr, "qorient stream: at most one input file\n");
        goto usage;
    }
    if (optind < argc) in_path = argv[optind];
    if (live && strcmp(in_path, "-") != 0) {
        fprintf(stderr, "qorient stream: --live reads standard input, not %s\n", QO_CLI_QUOTED(in_path));
        goto usage;
    }
    if ((modbus != NULL) == (gpio != NULL)) {
        fprintf(stderr, "qorient stream: give exactly one of --modbus SPEC or --gpio CHIP\n");
        goto usage;
    }
    if (modbus && !map_path) {
        fprintf(stderr, "qorient stream: --modbus needs --map FILE\n");
        goto usage;
    }
    if (gpio && !lines) {
        fprintf(stderr, "qorient stream: --gpio needs --lines STEP:DIR,...\n");
        goto usage;
    }
    if (strcmp(on_fail, "hold") != 0 && strcmp(on_fail, "disable") != 0) {
        fprintf(stderr, "qorient stream: --on-fail: %s is not hold or disable\n", QO_CLI_QUOTED(on_fail));
        goto usage;
    }

    /* The drives' description first: a bad map is reported before anything else happens. */
    if (modbus) {
        qo_modbus_link_spec spec;
        if (qo_regmap_load(map_path, &map, err, sizeof err) != QO_OK) {
            fprintf(stderr, "qorient stream: %s\n", err);
            goto out;
        }
        if (qo_modbus_link_parse_spec(modbus, &spec) != QO_OK) {
            fprintf(stderr, "qorient stream: --modbus: '%s' is not tcp://HOST:PORT or rtu:DEVICE,BAUD,8N1\n", modbus);
            goto usage;
        }
        n_joints = map.n_joints;
        if (!dry && spec.transport == QO_MODBUS_LINK_RTU && access(spec.device, R_OK | W_OK) != 0) {
            fprintf(stderr, "qorient stream: serial device %s: %s\n", spec.device, strerror(errno));
            goto out;
        }
        {
            static qo_wire_budget b;
            if (qo_wire_budget_compute(&map, &spec, turnaround, &b) != QO_OK) {
                fprintf(stderr, "qorient stream: %s: cannot group the registers into requests\n", map_path);
                goto out;
            }
            if (dry) print_budget(&b, &spec, rate);
            else if (spec.transport == QO_MODBUS_LINK_RTU && rate > b.max_rate_hz) {
                fprintf(stderr, "qorient stream: --rate %g Hz is more than %s allows for this map "
                        "(%.0f us of wire time per tick: at most %.1f Hz; see --dry-run)\n",
                        rate, modbus, b.tick_us, b.max_rate_hz);
                goto out;
            }
        }
    } else {
        size_t n, i;
        char buf[1024];
        char *p;
        if (strlen(lines) >= sizeof buf) goto usage;
        strcpy(buf, lines);
        for (p = buf; *p; p++) if (*p == ':') *p = ',';
        n = 0;
        if (qo_cli_parse_numbers(buf, sp, QO_GPIO_SINK_MAX_LINES, &n) != 0 || n == 0 || n % 2)
            n = 0;
        /* line offsets are unsigned: -1 or 1e30 would not convert (undefined behaviour) */
        for (i = 0; i < n; i++)
            if (!(sp[i] >= 0.0 && sp[i] <= 65535.0 && sp[i] == floor(sp[i]))) n = 0;
        if (n == 0) {
            fprintf(stderr, "qorient stream: --lines: %s is not STEP:DIR[,STEP:DIR...] (offsets 0..65535)\n",
                    QO_CLI_QUOTED(lines));
            goto usage;
        }
        n_joints = n / 2;
        /* checked here, so that --dry-run checks them too */
        if (qo_cli_list("stream", "--steps-per-unit", spu_s, n_joints, 1e-6, 1e9, spu) ||
            qo_cli_list("stream", "--step-rate", step_rate_s, n_joints, 1e-3, 1e7, sr))
            goto usage;
    }

    /* The plan, checked against the drives before anything is opened or written. */
    sc.opts = &po;
    if (live) {
        if (live_start(&sc) != 0) goto out;
        plan_joints = sc.rows.width / (size_t)po.columns;
    } else {
        if (qo_cli_rows_read("stream", &po, in_path, &rows) != 0) goto out;
        plan_joints = rows.width / (size_t)po.columns;
    }
    if (plan_joints != n_joints) {
        fprintf(stderr, "qorient stream: the plan has %zu joint(s) but the %s has %zu: nothing sent\n",
                plan_joints, modbus ? "map" : "--lines list", n_joints);
        goto out;
    }
    if (live) {
        rc = qo_cli_plan_build("stream", &po, n_joints, STREAM_LIVE_QUEUE, &plan);
        if (rc == 0) rc = qo_cli_plan_push("stream", "-", &plan, 0, sc.rows.v, sc.rows.line[0]);
        sc.t0 = 0;
    } else {
        qo_traj_ns end;
        /* targets: a trial run first, so a target state the limits refuse stops the command
         * (naming its line) before anything is sent */
        rc = po.motion ? qo_cli_plan_trial("stream", in_path, &po, &rows, &end) : 0;
        if (rc == 0) rc = qo_cli_plan_from_rows("stream", in_path, &po, &rows, &plan);
        sc.t0 = rows.t[0];
    }
    if (rc != 0) {
        if (rc == 2) goto usage;
        rc = 1;
        goto out;
    }
    rc = 1;
    if (dry) {
        qo_traj_ns end = 0;
        float tmp[QO_CLI_MAX_FIELDS];
        if (!live) (void)qo_traj_sample(&plan.tr, rows.t[rows.rows - 1], tmp, NULL, NULL, NULL);
        (void)qo_traj_end_time(&plan.tr, &end);
        printf("dry-run: plan over %.3f s for %zu joint(s); nothing sent\n", (double)(end - sc.t0) * 1e-9,
               n_joints);
        rc = 0;
        goto out;
    }

    cfg = qo_streamer_config_default;
    cfg.rate_hz = rate;
    cfg.n_joints = n_joints;
    cfg.sample = sample_traj;
    cfg.sample_ctx = &sc;
    if (no_rt) { cfg.rt_priority = 0; cfg.lock_memory = 0; }
    if (modbus) {
        qo_modbus_sink_settings ss = qo_modbus_sink_settings_default;
        double period_us = 1e6 / rate;
        /* Below the period so one slow reply cannot eat the next tick, but not below 2 ms:
         * a loaded Linux box answers loopback in ~0.1 ms, a real drive in ~1 ms. */
        double to = timeout_ms > 0 ? timeout_ms * 1000.0 : fmax(2000.0, fmin(20000.0, 0.8 * period_us));
        ss.response_timeout_us = (uint32_t)to;
        ss.byte_timeout_us = (uint32_t)fmin(to, 5000.0);
        ss.open_timeout_us = 500000u; /* connecting is outside the loop: be patient there */
        ss.on_fail = strcmp(on_fail, "disable") == 0 ? QO_MODBUS_SINK_ON_FAIL_DISABLE : QO_MODBUS_SINK_ON_FAIL_HOLD;
        s = qo_modbus_sink_open(modbus, &map, &ss, &ms);
        if (s != QO_OK) {
            fprintf(stderr, "qorient stream: cannot reach the drives at %s: %s\n", modbus, qo_status_str(s));
            goto out;
        }
        (void)qo_modbus_sink_as_sink(ms, &cfg.sink); /* QO_E_NULL only */
    } else {
        qo_gpio_sink_config gc;
        qo_gpio_sink_joint jd;
        qo_gpio_sink_backend be;
        static qo_gpio_sink_libgpiod gstore;
        size_t nspu = 0, nsr = 0, j;
        nspu = spu_s ? n_joints : 0;
        nsr = step_rate_s ? n_joints : 0;
        gc = qo_gpio_sink_config_default;
        jd = qo_gpio_sink_joint_default;
        gc.period_s = 1.0 / rate;
        gc.n_joints = n_joints;
        for (j = 0; j < n_joints; j++) {
            gc.joint[j] = jd;
            gc.joint[j].step.chip = gpio;
            gc.joint[j].step.offset = (unsigned)sp[2 * j];
            gc.joint[j].dir.chip = gpio;
            gc.joint[j].dir.offset = (unsigned)sp[2 * j + 1];
            if (nspu) gc.joint[j].steps_per_unit = spu[nspu == 1 ? 0 : j];
            if (nsr) gc.joint[j].max_rate_hz = sr[nsr == 1 ? 0 : j];
        }
        qo_gpio_sink_libgpiod_backend(&gstore, "qorient", &be);
        s = qo_gpio_sink_open(&gc, &be, &gs);
        if (s != QO_OK) {
            fprintf(stderr, "qorient stream: cannot open the GPIO lines on %s: %s\n", gpio, qo_status_str(s));
            goto out;
        }
        (void)qo_gpio_sink_as_sink(gs, &cfg.sink); /* QO_E_NULL only */
    }

    if (log_path && !dry) {
        size_t j;
        tl.f = fopen(log_path, "w");
        if (tl.f == NULL) {
            fprintf(stderr, "qorient stream: --log %s: %s\n", log_path, strerror(errno));
            goto out;
        }
        (void)setvbuf(tl.f, NULL, _IOFBF, 1u << 20);
        fputs("tick,scheduled_s,sampled_s,write", tl.f);
        for (j = 0; j < n_joints; j++) fprintf(tl.f, ",p%zu", j + 1);
        fputc('\n', tl.f);
        tl.inner = cfg.sink;
        tl.st = &st;
        tl.sc = &sc;
        memset(&cfg.sink, 0, sizeof cfg.sink);
        cfg.sink.ctx = &tl;
        cfg.sink.write = tick_log_write;
        cfg.sink.service = tick_log_service;
    }
    sc.plan = &plan;
    sc.hold = (qo_traj_ns)llround(hold * 1e9);
    sc.st = &st;
    sc.ended = 0;
    sc.live = live;
    if (live && pthread_mutex_init(&sc.lock, NULL) != 0) {
        fprintf(stderr, "qorient stream: cannot create a mutex\n");
        goto out;
    }
    s = qo_streamer_init(&st, &cfg);
    if (s != QO_OK) {
        fprintf(stderr, "qorient stream: %s\n", qo_status_str(s));
        goto out;
    }
    qo_streamer_install_stop_signals(&st);
    s = qo_streamer_start(&st);
    if (s != QO_OK) {
        fprintf(stderr, "qorient stream: cannot start the streaming thread: %s\n", qo_status_str(s));
        goto out;
    }
    if (live) {
        if (pthread_create(&reader_thread, NULL, live_reader, &sc) != 0) {
            fprintf(stderr, "qorient stream: cannot start the input reader thread\n");
            qo_streamer_request_stop(&st);
            (void)qo_streamer_join(&st);
            goto out;
        }
        reader = 1;
    }
    {
        /* Live progress from this thread while the streamer runs in its own. */
        int tty = !quiet && isatty(2);
        uint64_t last_ticks = 0;
        struct timespec ts = { 0, 250000000 };
        volatile sig_atomic_t *stop = qo_streamer_stop_flag(&st);
        qo_streamer_stats ss;
        qo_status fin;
        double elapsed = 0, settle_s = 0;
        int settled = -1;
        while (!*stop) {
            nanosleep(&ts, NULL);
            elapsed += 0.25;
            if (tty && qo_streamer_stats_read(&st, &ss) == QO_OK) {
                fprintf(stderr, "\r%7.2f s  %7.1f Hz  jitter p99 %5.0f us  max %6.0f us  overruns %llu  errors %llu   ",
                        elapsed, (double)(ss.ticks - last_ticks) / 0.25, ss.lat_p99_ns / 1e3, ss.lat_max_ns / 1e3,
                        (unsigned long long)ss.overruns, (unsigned long long)ss.sink_errors);
                last_ticks = ss.ticks;
            }
        }
        fin = qo_streamer_join(&st);
        if (tty) fputc('\n', stderr);
        /* The plan ended: success is the drives holding its last row, not the last write. */
        if (ms && sc.ended) settled = stream_settle(ms, &map, &plan.tr, n_joints, rate, settle, &settle_s);
        qo_streamer_stats_read(&st, &ss);
        {
            const char *warn = NULL;
            (void)qo_streamer_rt_report(&st, &warn);
            if (!no_rt && warn && *warn) fprintf(stderr, "qorient stream: note: %s\n", warn);
        }
        printf("summary: ticks %llu overruns %llu jitter_p50_us %.1f jitter_p99_us %.1f jitter_max_us %.1f "
               "sink_errors %llu",
               (unsigned long long)ss.ticks, (unsigned long long)ss.overruns, ss.lat_p50_ns / 1e3,
               ss.lat_p99_ns / 1e3, ss.lat_max_ns / 1e3, (unsigned long long)ss.sink_errors);
        if (ms) {
            qo_modbus_sink_stats ms_st;
            if (qo_modbus_sink_get_stats(ms, &ms_st) == QO_OK)
                printf(" requests %llu timeouts %llu late_replies %llu skipped %llu readbacks %llu exceptions %llu"
                       " reconnects %llu rate_limited %llu clamped %llu",
                       (unsigned long long)ms_st.requests, (unsigned long long)ms_st.timeouts,
                       (unsigned long long)ms_st.late_replies, (unsigned long long)ms_st.skipped,
                       (unsigned long long)ms_st.readbacks,
                       (unsigned long long)ms_st.exceptions, (unsigned long long)ms_st.common.reconnects,
                       (unsigned long long)ms_st.rate_limited, (unsigned long long)ms_st.clamped);
        }
        if (settled >= 0) printf(" settle_s %.3f final %s\n", settle_s, settled == 0 ? "ok" : "short");
        else printf(" final %s\n", qo_status_str(fin));
        if (settled > 0) goto out;
        if (fin != QO_OK && settled < 0) {
            fprintf(stderr, "qorient stream: the final target did not reach the drives: %s\n", qo_status_str(fin));
            goto out;
        }
    }
    rc = 0;
    goto out;
usage:
    rc = 2;
    fputs("try 'qorient stream --help'\n", stderr);
out:
    if (tl.f && (ferror(tl.f) | fclose(tl.f)) != 0) {
        fprintf(stderr, "qorient stream: --log %s: write error\n", log_path);
        if (rc == 0) rc = 1;
    }
    qo_modbus_sink_free(ms); /* NULL: nothing */
    qo_gpio_sink_free(gs);
    if (reader) {
        /* At end of input the reader has ended; after SIGINT it may still wait on a read:
         * detach it, the process ends with this return. */
        if (sc.eof) pthread_join(reader_thread, NULL);
        else pthread_detach(reader_thread);
    }
    if (rc == 0 && sc.bad_lines) rc = 1;
    if (!reader || sc.eof) {
        qo_cli_plan_free(&plan);
        qo_cli_rows_free(&sc.rows);
    }
    qo_cli_rows_free(&rows);
    return rc;
}
