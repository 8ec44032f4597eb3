/*
 * qorient stream --map FILE (--modbus SPEC | --gpio CHIP --lines ...) [plan options] [FILE|-]
 *
 * Plans the motion exactly as `qorient plan` does (same options, same input; the plan is run
 * once up front at the stream rate), then streams it to the drives with the periodic streamer:
 * each tick samples the plan at the ACTUAL wake time (cubic Hermite between plan rows, using
 * their velocities) and hands the targets to the sink. Progress on a terminal, a summary at
 * the end, a clean stop on SIGINT/SIGTERM leaving the drives on the last sampled target.
 */
#include "../cli.h"

#include <errno.h>
#include <math.h>
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
    "\n"
    "Reads keyframes or targets exactly as 'qorient plan' does (same input, same options:\n"
    "--profile, --vmax, --amax, --jmax, --sync, --min, --max, --wrap, --degrees, --fixed, ...),\n"
    "plans the motion and streams it to servo drives at --rate HZ (default 100): each tick\n"
    "samples the plan at the actual wake time and sends every joint's target.\n"
    "\n"
    "Modbus (the register map gives slaves, registers, types, scale, limits, max_step):\n"
    "  --map FILE          register map (INI, see examples/maps); its joints, in file order,\n"
    "                      are the plan's columns p1..pN\n"
    "  --modbus SPEC       tcp://HOST:PORT or rtu:DEVICE,BAUD,8N1 (parity N, E or O)\n"
    "  --timeout-ms MS     response timeout (default 0.8 x the period, within 2..20 ms);\n"
    "                      on TCP a later reply is still accepted at the next tick, and a\n"
    "                      link silent for 20 x this (at least 1 s) is reconnected\n"
    "  --on-fail hold|disable  after repeated failures: hold the last target (default) or\n"
    "                      send the map's disable writes\n"
    "  --turnaround-us US  the drives' reply delay, for the RTU wire budget (default 0)\n"
    "GPIO step/dir (libgpiod):\n"
    "  --gpio CHIP         chip name, path or label (e.g. gpiochip0, pinctrl-rp1)\n"
    "  --lines S:D,...     step and dir line offsets per joint\n"
    "  --steps-per-unit K[,K...]  steps per joint unit (default 200)\n"
    "  --step-rate HZ[,HZ...]     maximum step rate (default 1000)\n"
    "Streaming:\n"
    "  --rate HZ           tick rate (default 100); also the rate the plan is sampled at\n"
    "  --hold S            keep streaming the final target for S seconds (default 0.2)\n"
    "  --settle S          Modbus: after the plan (and --hold), keep sending the final target\n"
    "                      until every drive holds it (acknowledged, then read back) or S\n"
    "                      seconds pass; default: twice the max_step catch-up time from\n"
    "                      what the drives hold, plus 0.5 s\n"
    "  --dry-run           check the map and the plan, print the per-tick wire budget (and\n"
    "                      for RTU the highest rate the line allows), send nothing\n"
    "  --no-rt             do not ask for SCHED_FIFO / mlockall\n"
    "  --quiet             no live progress line\n"
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
    "                unknown outcome or a reconnection; 0 in a fault-free run)\n"    "  exceptions    exception replies (the drive refused a request: nothing applied)\n"
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
    "target; 1 on a runtime error (map, device, unreachable drive, failed plan, a drive short\n"
    "of its final target after --settle: each such joint is named with how far it is short);\n"
    "2 on a usage error. Stopped by a signal: 0 when the last sampled target was written.\n";

struct plan_table {
    size_t rows, cols, n;   /* cols = 1 + k*n, k = 1 (p), 2 (p,v) or 3 (p,v,a) */
    double *v;              /* rows x cols */
    double t0, dt;
};

struct stream_ctx {
    const struct plan_table *plan;
    double hold;
    qo_streamer *st;
    volatile sig_atomic_t ended; /* the plan ran to its end (not stopped by a signal) */
};

/* Runs `qorient plan` with args into a temporary file and reads the table back. */
static int run_plan(int argc, char **argv, const char *rate, struct plan_table *pt)
{
    char **pargv = calloc((size_t)argc + 4, sizeof *pargv);
    FILE *tmp = tmpfile();
    int saved, rc, i, pargc = 0;
    char *line = NULL;
    size_t cap = 0, rcap = 0;
    if (pargv == NULL || tmp == NULL) {
        fprintf(stderr, "qorient stream: cannot create a temporary file for the plan\n");
        free(pargv);
        if (tmp) fclose(tmp);
        return 1;
    }
    pargv[pargc++] = "plan";
    pargv[pargc++] = "--rate";
    pargv[pargc++] = (char *)rate;
    for (i = 0; i < argc; i++) pargv[pargc++] = argv[i];
    fflush(stdout);
    saved = dup(1);
    dup2(fileno(tmp), 1);
    qo_cli_reset_getopt();
    rc = qo_cli_plan(pargc, pargv);
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    free(pargv);
    if (rc != 0) {
        fclose(tmp);
        fprintf(stderr, "qorient stream: planning failed (see above)\n");
        return 1;
    }
    rewind(tmp);
    memset(pt, 0, sizeof *pt);
    while (qo_cli_getline(&line, &cap, tmp) >= 0) {
        double f[1 + 3 * QO_REGMAP_MAX_JOINTS];
        size_t m;
        if (qo_cli_parse_numbers(line, f, sizeof f / sizeof f[0], &m) != 0 || m == 0) continue;
        if (pt->cols == 0) pt->cols = m;
        if (m != pt->cols) continue;
        if (pt->rows == rcap) {
            size_t nc = rcap ? 2 * rcap : 1024;
            double *nv = realloc(pt->v, nc * pt->cols * sizeof *nv);
            if (nv == NULL) { free(line); fclose(tmp); return 1; }
            pt->v = nv;
            rcap = nc;
        }
        memcpy(pt->v + pt->rows * pt->cols, f, pt->cols * sizeof f[0]);
        pt->rows++;
    }
    free(line);
    fclose(tmp);
    if (pt->rows < 1) {
        fprintf(stderr, "qorient stream: the plan produced no samples\n");
        return 1;
    }
    pt->t0 = pt->v[0];
    pt->dt = pt->rows > 1 ? pt->v[pt->cols] - pt->v[0] : 1.0;
    return 0;
}

/* Position of joint j at plan time t: cubic Hermite between rows with velocities, linear
 * without. Before the first row / after the last: held. */
static double plan_at(const struct plan_table *pt, double t, size_t j)
{
    const size_t c = pt->cols, n = pt->n;
    double x, u, h;
    size_t i;
    const double *r0, *r1;
    if (t <= pt->t0 || pt->rows == 1) return pt->v[1 + j];
    x = (t - pt->t0) / pt->dt;
    i = (size_t)x;
    if (i + 1 >= pt->rows) return pt->v[(pt->rows - 1) * c + 1 + j];
    r0 = pt->v + i * c;
    r1 = r0 + c;
    h = r1[0] - r0[0];
    u = (t - r0[0]) / h;
    if (u < 0) u = 0;
    if (u > 1) u = 1;
    if (c >= 1 + 2 * n) {
        double p0 = r0[1 + j], p1 = r1[1 + j], v0 = r0[1 + n + j] * h, v1 = r1[1 + n + j] * h;
        double u2 = u * u, u3 = u2 * u;
        return (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * v0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * v1;
    }
    return r0[1 + j] + u * (r1[1 + j] - r0[1 + j]);
}

static qo_status sample_plan(void *vctx, double t, float *targets, size_t n)
{
    struct stream_ctx *c = vctx;
    const struct plan_table *pt = c->plan;
    double tp = pt->t0 + t, tend = pt->v[(pt->rows - 1) * pt->cols];
    size_t j;
    for (j = 0; j < n; j++) targets[j] = (float)plan_at(pt, tp, j);
    if (tp >= tend + c->hold) {
        c->ended = 1;
        qo_streamer_request_stop(c->st);
    }
    return QO_OK;
}

static int parse_list(const char *s, double *out, size_t max, size_t *n)
{
    char buf[1024];
    if (strlen(s) >= sizeof buf) return -1;
    strcpy(buf, s);
    return qo_cli_parse_numbers(buf, out, max, n);
}

static void print_budget(const qo_wire_budget *b, const qo_modbus_spec *spec, double rate)
{
    size_t i;
    printf("dry-run: %zu request(s) per tick (FC16)\n", b->n_requests);
    for (i = 0; i < b->n_requests; i++) {
        const qo_wire_request *r = &b->req[i];
        printf("  slave %u: registers %u..%u (%u), request %u bytes, reply %u bytes",
               r->slave, r->first, r->first + r->registers - 1, r->registers, r->request_bytes, r->reply_bytes);
        if (spec->transport == QO_MODBUS_RTU) printf(", %.0f us on the wire", r->time_us);
        putchar('\n');
    }
    if (spec->transport == QO_MODBUS_RTU) {
        printf("rtu: %d baud %d%c%d: %u bits/char, %.1f us/char, t3.5 = %.0f us\n", spec->baud,
               spec->data_bits, spec->parity, spec->stop_bits, b->bits_per_char, b->char_us, b->t35_us);
        printf("wire budget per tick: %.0f us; highest rate: %.1f Hz; requested %g Hz: %s\n",
               b->tick_us, b->max_rate_hz, rate, rate <= b->max_rate_hz ? "fits" : "does NOT fit");
    } else {
        printf("tcp: no wire-time bound (the network and the drives' reply time decide)\n");
    }
}

/* After the plan: the drives must hold its last row (see qo_modbus_sink_settle). Names every
 * joint that is short on stderr. 0 when reached, else 1; *elapsed = time spent settling. */
static int stream_settle(qo_modbus_sink *ms, const qo_regmap *map, const struct plan_table *pt,
                         size_t n, double rate, double settle, double *elapsed)
{
    float final[QO_REGMAP_MAX_JOINTS];
    qo_modbus_settle_report rep;
    qo_status s;
    size_t j;
    for (j = 0; j < n; j++) final[j] = (float)pt->v[(pt->rows - 1) * pt->cols + 1 + j];
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

int qo_cli_stream(int argc, char **argv)
{
    const char *map_path = NULL, *modbus = NULL, *gpio = NULL, *lines = NULL, *rate_s = "100";
    const char *spu_s = NULL, *step_rate_s = NULL, *on_fail = "hold";
    double rate = 100.0, hold = 0.2, timeout_ms = -1, turnaround = 0, settle = -1;
    int dry = 0, no_rt = 0, quiet = 0, i, pargc = 0, rc = 1;
    char **pargv = calloc((size_t)argc + 1, sizeof *pargv);
    static qo_regmap map; /* 20 KiB: not on the stack */
    struct plan_table pt;
    struct stream_ctx sc;
    qo_streamer st;
    qo_streamer_config cfg;
    qo_modbus_sink *ms = NULL;
    qo_gpio_sink gs;
    int gpio_open = 0;
    size_t n_joints = 0;
    char err[256];
    qo_status s;

    memset(&pt, 0, sizeof pt);
    if (pargv == NULL) return 1;
    /* Our own options are taken out; everything else goes to the planner unchanged. */
    for (i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *val = (i + 1 < argc) ? argv[i + 1] : NULL;
#define TAKE(opt, var) if (strcmp(a, opt) == 0) { if (!val) { fprintf(stderr, "qorient stream: %s needs a value\n", opt); goto usage; } var = val; i++; continue; }
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) { fputs(stream_usage, stdout); fputs(stream_fields, stdout); free(pargv); return 0; }
        TAKE("--map", map_path)
        TAKE("--modbus", modbus)
        TAKE("--gpio", gpio)
        TAKE("--lines", lines)
        TAKE("--steps-per-unit", spu_s)
        TAKE("--step-rate", step_rate_s)
        TAKE("--on-fail", on_fail)
        TAKE("--rate", rate_s)
        if (strcmp(a, "--hold") == 0 || strcmp(a, "--timeout-ms") == 0 || strcmp(a, "--turnaround-us") == 0 ||
            strcmp(a, "--settle") == 0) {
            char *end;
            double v;
            if (!val) { fprintf(stderr, "qorient stream: %s needs a value\n", a); goto usage; }
            v = strtod(val, &end);
            if (end == val || *end || !isfinite(v) || v < 0) {
                fprintf(stderr, "qorient stream: %s: '%s' is not a non-negative number\n", a, val);
                goto usage;
            }
            if (a[2] == 'h') hold = v; else if (a[2] == 's') settle = v;
            else if (a[2] == 't' && a[3] == 'i') timeout_ms = v; else turnaround = v;
            i++;
            continue;
        }
        if (strcmp(a, "--dry-run") == 0) { dry = 1; continue; }
        if (strcmp(a, "--no-rt") == 0) { no_rt = 1; continue; }
        if (strcmp(a, "--quiet") == 0) { quiet = 1; continue; }
#undef TAKE
        pargv[pargc++] = argv[i];
    }
    {
        char *end;
        rate = strtod(rate_s, &end);
        if (end == rate_s || *end || !isfinite(rate) || rate <= 0 || rate > 100000) {
            fprintf(stderr, "qorient stream: --rate: '%s' is not a rate in (0, 100000] Hz\n", rate_s);
            goto usage;
        }
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
        fprintf(stderr, "qorient stream: --on-fail: '%s' is not hold or disable\n", on_fail);
        goto usage;
    }

    /* The drives' description first: a bad map is reported before anything else happens. */
    if (modbus) {
        qo_modbus_spec spec;
        if (qo_regmap_load(map_path, &map, err, sizeof err) != QO_OK) {
            fprintf(stderr, "qorient stream: %s\n", err);
            goto out;
        }
        if (qo_modbus_parse_spec(modbus, &spec) != QO_OK) {
            fprintf(stderr, "qorient stream: --modbus: '%s' is not tcp://HOST:PORT or rtu:DEVICE,BAUD,8N1\n", modbus);
            goto usage;
        }
        n_joints = map.n_joints;
        if (!dry && spec.transport == QO_MODBUS_RTU && access(spec.device, R_OK | W_OK) != 0) {
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
            else if (spec.transport == QO_MODBUS_RTU && rate > b.max_rate_hz) {
                fprintf(stderr, "qorient stream: --rate %g Hz is more than %s allows for this map "
                        "(%.0f us of wire time per tick: at most %.1f Hz; see --dry-run)\n",
                        rate, modbus, b.tick_us, b.max_rate_hz);
                goto out;
            }
        }
    } else {
        double sp[QO_GPIO_MAX_LINES];
        size_t n;
        char buf[1024];
        char *p;
        if (strlen(lines) >= sizeof buf) goto usage;
        strcpy(buf, lines);
        for (p = buf; *p; p++) if (*p == ':') *p = ',';
        if (qo_cli_parse_numbers(buf, sp, QO_GPIO_MAX_LINES, &n) != 0 || n == 0 || n % 2) {
            fprintf(stderr, "qorient stream: --lines: '%s' is not STEP:DIR[,STEP:DIR...]\n", lines);
            goto usage;
        }
        n_joints = n / 2;
    }

    pt.n = n_joints;
    if (run_plan(pargc, pargv, rate_s, &pt) != 0) goto out;
    if ((pt.cols - 1) % n_joints != 0 || (pt.cols - 1) / n_joints < 1 || (pt.cols - 1) / n_joints > 3) {
        fprintf(stderr, "qorient stream: the plan has %zu joint column(s) but the %s has %zu joint(s)\n",
                (pt.cols - 1) / 3, modbus ? "map" : "--lines list", n_joints);
        goto out;
    }
    if (dry) {
        printf("dry-run: plan of %zu samples over %.3f s for %zu joint(s); nothing sent\n", pt.rows,
               pt.v[(pt.rows - 1) * pt.cols] - pt.t0, n_joints);
        rc = 0;
        goto out;
    }

    qo_streamer_config_default(&cfg);
    cfg.rate_hz = rate;
    cfg.n_joints = n_joints;
    cfg.sample = sample_plan;
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
        ss.on_fail = strcmp(on_fail, "disable") == 0 ? QO_MODBUS_ON_FAIL_DISABLE : QO_MODBUS_ON_FAIL_HOLD;
        s = qo_modbus_sink_open(modbus, &map, &ss, &ms);
        if (s != QO_OK) {
            fprintf(stderr, "qorient stream: cannot reach the drives at %s: %s\n", modbus, qo_status_str(s));
            goto out;
        }
        qo_modbus_sink_as_sink(ms, &cfg.sink);
    } else {
        qo_gpio_sink_config gc;
        qo_gpio_joint jd;
        qo_gpio_backend be;
        static qo_gpio_libgpiod gstore;
        double sp[QO_GPIO_MAX_LINES], spu[QO_GPIO_MAX_JOINTS], sr[QO_GPIO_MAX_JOINTS];
        size_t n, nspu = 0, nsr = 0, j;
        char buf[1024];
        char *p;
        strcpy(buf, lines);
        for (p = buf; *p; p++) if (*p == ':') *p = ',';
        qo_cli_parse_numbers(buf, sp, QO_GPIO_MAX_LINES, &n);
        if ((spu_s && (parse_list(spu_s, spu, QO_GPIO_MAX_JOINTS, &nspu) != 0 || (nspu != 1 && nspu != n_joints))) ||
            (step_rate_s && (parse_list(step_rate_s, sr, QO_GPIO_MAX_JOINTS, &nsr) != 0 || (nsr != 1 && nsr != n_joints)))) {
            fprintf(stderr, "qorient stream: --steps-per-unit / --step-rate take one value or one per joint\n");
            goto usage;
        }
        qo_gpio_sink_config_default(&gc, &jd);
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
        qo_gpio_libgpiod_backend(&gstore, "qorient", &be);
        s = qo_gpio_sink_open(&gs, &gc, &be);
        if (s != QO_OK) {
            fprintf(stderr, "qorient stream: cannot open the GPIO lines on %s: %s\n", gpio, qo_status_str(s));
            goto out;
        }
        gpio_open = 1;
        cfg.sink = qo_gpio_sink_as_sink(&gs);
    }

    sc.plan = &pt;
    sc.hold = hold;
    sc.st = &st;
    sc.ended = 0;
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
        if (ms && sc.ended) settled = stream_settle(ms, &map, &pt, n_joints, rate, settle, &settle_s);
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
    if (ms) qo_modbus_sink_free(ms);
    if (gpio_open) qo_gpio_sink_close(&gs);
    free(pt.v);
    free(pargv);
    return rc;
}
