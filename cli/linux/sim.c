/* `qorient sim`: the simulated drive bank as a command, for demos and for testing a
 * streamer (or any Modbus master) without hardware. */
#include "../cli.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "linux/regmap.h"
#include "linux/sim.h"

static void sim_usage(FILE *f)
{
    fputs("usage: qorient sim --map FILE [--listen SPEC] [--lag SECONDS] [--log FILE]\n"
          "                   [--lag-dist DIST] [--fault KIND] [--fault-share P]\n"
          "                   [--fault-after N] [--fault-count N] [--seed N] [--duration S]\n"
          "                   [--no-rt]\n\n"
          "Serves the register map FILE as a bank of simulated servo drives (Modbus server).\n"
          "Each joint moves toward its last target with a first-order lag and reports its\n"
          "position in its feedback registers. It serves one master at a time, as most\n"
          "drives do: a new TCP connection replaces the previous one. Requests are answered\n"
          "in order.\n\n"
          "  --map FILE        register map (INI; see examples/maps)\n"
          "  --listen SPEC     tcp://HOST:PORT (HOST an IPv4 address, localhost or [IPv6],\n"
          "                    default 127.0.0.1; PORT 0 = any free port) or\n"
          "                    rtu:DEVICE,BAUD,8N1 (parity N, E or O);\n"
          "                    default tcp://127.0.0.1:0\n"
          "  --lag SECONDS     time constant of the joints' lag (default 0.05; 0 = instant)\n"
          "  --log FILE        CSV of every target received: t_s,request,slave,joint_index,\n"
          "                    joint,value ('-' = standard output)\n"
          "  --lag-dist DIST   reply latency: SHARE:LO-HIms[,SHARE:LO-HIms...], e.g.\n"
          "                    0.97:0-0.2ms,0.03:5-12ms (97% within 0.2 ms, 3% after 5 to\n"
          "                    12 ms, uniform; 'us' for microseconds); the write is applied\n"
          "                    at once, the reply waits (default: reply at once)\n"
          "  --fault KIND      delay:MS, drop, exception or close\n"
          "  --fault-share P   fault each request with probability P (0..1)\n"
          "  --fault-after N   fault the requests after the first N ...\n"
          "  --fault-count N   at most N faults in all (default 0 = no limit); with\n"
          "                    --fault-after: the N requests after the first N\n"
          "  --seed N          seed of the fault PRNG (default 1)\n"
          "  --no-rt           do not ask for SCHED_FIFO 70 for the server thread (asked by\n"
          "                    default, best effort: a drive has its own CPU, so other\n"
          "                    processes on this machine should not slow its replies)\n"
          "  --duration S      stop after S seconds (default: run until SIGINT/SIGTERM)\n\n"
          "Prints 'listening SPEC' (with the actual port) when ready, and on exit\n"
          "'requests N target_writes N faults N connections N bad_frames N'.\n"
          "Exit status 0, 1 on a runtime error, 2 on a usage or map error.\n", f);
}

static int parse_u64(const char *s, uint64_t *out)
{
    char *end;
    unsigned long long v;
    if (s[0] < '0' || s[0] > '9') return -1;
    errno = 0;
    v = strtoull(s, &end, 10);
    if (errno != 0 || *end != '\0') return -1;
    *out = (uint64_t)v;
    return 0;
}

static int parse_dbl(const char *s, double lo, double hi, double *out)
{
    char *end;
    double v;
    errno = 0;
    v = strtod(s, &end);
    if (end == s || *end != '\0' || !(v >= lo && v <= hi)) return -1;
    *out = v;
    return 0;
}

static int parse_fault(const char *s, qo_sim_fault *f)
{
    if (strncmp(s, "delay:", 6) == 0) {
        uint64_t ms;
        if (parse_u64(s + 6, &ms) != 0 || ms > 60000) return -1;
        f->kind = QO_SIM_FAULT_DELAY;
        f->delay_ms = (unsigned)ms;
        return 0;
    }
    if (strcmp(s, "drop") == 0) f->kind = QO_SIM_FAULT_DROP;
    else if (strcmp(s, "exception") == 0) f->kind = QO_SIM_FAULT_EXCEPTION;
    else if (strcmp(s, "close") == 0) f->kind = QO_SIM_FAULT_CLOSE;
    else return -1;
    return 0;
}

int qo_cli_sim(int argc, char **argv)
{
    static const struct option opts[] = {
        { "map", required_argument, NULL, 'm' },
        { "listen", required_argument, NULL, 'l' },
        { "lag", required_argument, NULL, 'g' },
        { "log", required_argument, NULL, 'o' },
        { "lag-dist", required_argument, NULL, 'L' },
        { "no-rt", no_argument, NULL, 'R' },
        { "fault", required_argument, NULL, 'f' },
        { "fault-share", required_argument, NULL, 'p' },
        { "fault-after", required_argument, NULL, 'a' },
        { "fault-count", required_argument, NULL, 'c' },
        { "seed", required_argument, NULL, 's' },
        { "duration", required_argument, NULL, 'd' },
        { "help", no_argument, NULL, 'h' },
        { NULL, 0, NULL, 0 }
    };
    static qo_regmap map; /* ~20 KiB */
    const char *map_path = NULL, *listen = "tcp://127.0.0.1:0", *log_path = NULL;
    qo_sim_settings set = qo_sim_settings_default;
    double duration = -1.0;
    int fault_given = 0, c, rc = 0;
    char err[512];
    qo_sim *sim = NULL;
    qo_sim_stats st;
    qo_status s;
    FILE *log = NULL;
    sigset_t sigs;

    /* A drive has its own CPU: best effort, the server thread preempts CPU-bound processes
     * (below the streamer's SCHED_FIFO 80, so a master on the same machine goes first). */
    set.rt_priority = 70;
    while ((c = getopt_long(argc, argv, "h", opts, NULL)) != -1) {
        uint64_t u;
        switch (c) {
        case 'm': map_path = optarg; break;
        case 'l': listen = optarg; break;
        case 'g':
            if (qo_cli_number("sim", "--lag", optarg, 0.0, 1e6, "s", &set.lag_s)) return 2;
            break;
        case 'o': log_path = optarg; break;
        case 'R': set.rt_priority = 0; break;
        case 'L':
            if (qo_sim_parse_lag_dist(optarg, &set) != QO_OK) {
                fprintf(stderr, "qorient sim: bad --lag-dist '%s' (SHARE:LO-HIms,...)\n", optarg);
                return 2;
            }
            break;
        case 'f':
            if (parse_fault(optarg, &set.fault) != 0) {
                fprintf(stderr, "qorient sim: bad --fault %s (delay:MS, drop, exception, close)\n",
                        QO_CLI_QUOTED(optarg));
                return 2;
            }
            fault_given = 1;
            break;
        case 'p':
            if (parse_dbl(optarg, 0.0, 1.0, &set.fault.share) != 0) {
                fprintf(stderr, "qorient sim: bad --fault-share %s (0..1)\n", QO_CLI_QUOTED(optarg));
                return 2;
            }
            break;
        case 'a':
        case 'c':
        case 's':
            if (parse_u64(optarg, &u) != 0) {
                fprintf(stderr, "qorient sim: bad number %s\n", QO_CLI_QUOTED(optarg));
                return 2;
            }
            if (c == 'a') set.fault.after = u;
            else if (c == 'c') set.fault.count = u;
            else set.seed = u;
            break;
        case 'd':
            if (qo_cli_number("sim", "--duration", optarg, 0.0, 1e9, "s", &duration)) return 2;
            break;
        case 'h': sim_usage(stdout); return 0;
        default: sim_usage(stderr); return 2;
        }
    }
    if (optind < argc || map_path == NULL) {
        if (map_path == NULL) fputs("qorient sim: --map FILE is required\n", stderr);
        else fprintf(stderr, "qorient sim: unexpected argument %s\n", QO_CLI_QUOTED(argv[optind]));
        sim_usage(stderr);
        return 2;
    }
    if (!fault_given && (set.fault.share > 0.0 || set.fault.after > 0)) {
        fputs("qorient sim: --fault-share/--fault-after need --fault KIND\n", stderr);
        return 2;
    }
    s = qo_regmap_load(map_path, &map, err, sizeof err);
    if (s != QO_OK) {
        fprintf(stderr, "qorient sim: %s\n", err);
        return 2;
    }
    if (log_path != NULL) {
        log = strcmp(log_path, "-") == 0 ? stdout : fopen(log_path, "w");
        if (log == NULL) {
            fprintf(stderr, "qorient sim: cannot open log '%s': %s\n", log_path, strerror(errno));
            return 1;
        }
        set.log = log;
    }
    /* Block the stop signals before the server thread starts, so only sigtimedwait sees them. */
    sigemptyset(&sigs);
    sigaddset(&sigs, SIGINT);
    sigaddset(&sigs, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &sigs, NULL);
    s = qo_sim_start(listen, &map, &set, &sim);
    if (s != QO_OK) {
        fprintf(stderr, "qorient sim: cannot listen on '%s': %s\n", listen, qo_status_str(s));
        if (log != NULL && log != stdout) fclose(log);
        pthread_sigmask(SIG_UNBLOCK, &sigs, NULL);
        return s == QO_E_CONFIG ? 2 : 1;
    }
    if (qo_sim_port(sim) > 0) {
        const char *h = listen + 6, *colon = strrchr(h, ':');
        int hl = colon != NULL ? (int)(colon - h) : (int)strlen(h);
        if (hl == 0) {
            h = "127.0.0.1";
            hl = 9;
        }
        printf("listening tcp://%.*s:%d\n", hl, h, qo_sim_port(sim));
    } else {
        printf("listening %s\n", listen);
    }
    fflush(stdout);
    for (;;) {
        struct timespec to;
        double wait = duration < 0.0 ? 3600.0 : duration;
        to.tv_sec = (time_t)wait;
        to.tv_nsec = (long)((wait - floor(wait)) * 1e9);
        if (sigtimedwait(&sigs, NULL, &to) >= 0) break; /* SIGINT / SIGTERM */
        if (errno == EAGAIN && duration >= 0.0) break;  /* --duration elapsed */
        if (errno != EAGAIN && errno != EINTR) {
            rc = 1;
            break;
        }
    }
    (void)qo_sim_get_stats(sim, &st);
    qo_sim_stop(sim);
    pthread_sigmask(SIG_UNBLOCK, &sigs, NULL);
    /* a log that could not all be written (a full disk) is not a success; both run */
    if (log != NULL && log != stdout && (ferror(log) | fclose(log)) != 0) {
        fprintf(stderr, "qorient sim: log '%s': write error\n", log_path);
        rc = 1;
    }
    printf("requests %llu target_writes %llu faults %llu connections %llu bad_frames %llu\n",
           (unsigned long long)st.requests, (unsigned long long)st.target_writes,
           (unsigned long long)st.faults, (unsigned long long)st.connections,
           (unsigned long long)st.bad_frames);
    return rc;
}
