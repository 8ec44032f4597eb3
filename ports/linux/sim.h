/*
 * ports/linux/sim.h - a simulated drive bank: a libmodbus server serving a register map.
 *
 * Index:
 *   qo_sim_fault_kind, qo_sim_fault    what to do to a share of the requests
 *   qo_sim_settings, qo_sim_settings_default
 *   qo_sim_parse_lag_dist()   "0.97:0-0.2ms,0.03:5-12ms" -> the reply latency model
 *   qo_sim_start()        bind/open, start the server thread
 *   qo_sim_port()         the TCP port actually bound (useful with port 0)
 *   qo_sim_set_fault()    change the fault injection while running
 *   qo_sim_get_joint()    a joint's target and simulated position
 *   qo_sim_get_register() one holding register of one slave
 *   qo_sim_get_stats()    counters
 *   qo_sim_wait_requests() block until N requests were handled (condition variable)
 *   qo_sim_stop()         stop the thread, close, free
 *
 * Behaviour. Every slave of the map gets its own 65536 holding registers. A write (FC06,
 * FC16, FC23) to a joint's target registers sets that joint's target; the joint's position
 * follows with a first-order lag (time constant `lag_s`; 0 = at once) in real time, and is
 * written, packed with the joint's format, to its feedback registers before every request is
 * served. Every target write is logged to `log` (may be NULL) as CSV, one line per joint
 * written, after the header "t_s,request,slave,joint_index,joint,value" (t_s: seconds since
 * start, monotonic; request: 1-based request number; value in joint units, %.9g).
 * Every holding register, target registers included, can be read back with FC03 (unless
 * `targets_unreadable`). Requests for a slave not in the map are answered with exception 0x0B (TCP) or ignored
 * (RTU, as on a shared bus).
 *
 * Reply latency. With `n_lag` > 0 every reply (faults aside) is sent after a delay drawn per
 * request: bucket i with probability share_i / sum(shares), then uniform in [lo_ms, hi_ms];
 * the write is applied at once, as by a drive that is slow to answer. Requests are served
 * in order (one at a time, as a drive does), so a slow reply delays the next request's too.
 * Drawn from its own splitmix64 stream (seed ^ 0x5A5A...), so it does not change which
 * requests are faulted.
 *
 * Fault injection. Request number k (1-based, counting every request received) is faulted
 * when  after < k <= after + count  (after > 0) or, independently, with probability `share`
 * from a splitmix64 PRNG seeded with `seed` (deterministic sequence); `count` > 0 also caps
 * the number of faults since the fault was set (so share 1, count 1 faults exactly the
 * first request).
 *   DELAY      the reply is sent after delay_ms (the write is applied at once);
 *   DROP       the write is applied, no reply is sent (a lost reply);
 *   EXCEPTION  nothing is applied, exception 0x04 (server device failure) is sent;
 *   CLOSE      nothing is applied, the TCP connection is closed (RTU: like DROP without
 *              applying the write).
 *
 * RTU: the server reads frames itself (CRC-checked, any slave id of the map) and answers
 * through libmodbus; a frame with a bad CRC is dropped together with whatever follows it
 * within 5 ms, as a drive would. A pty ignores the baud rate.
 * Threads: one server thread per sim; every function here may be called from other threads.
 */
#ifndef QORIENT_SIM_H
#define QORIENT_SIM_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "qorient/status.h"
#include "linux/regmap.h"

typedef enum qo_sim_fault_kind {
    QO_SIM_FAULT_NONE = 0,
    QO_SIM_FAULT_DELAY,
    QO_SIM_FAULT_DROP,
    QO_SIM_FAULT_EXCEPTION,
    QO_SIM_FAULT_CLOSE
} qo_sim_fault_kind;

typedef struct qo_sim_fault {
    qo_sim_fault_kind kind;
    unsigned delay_ms;   /* DELAY: 0..60000 */
    double share;        /* 0..1: probability per request */
    uint64_t after;      /* fault requests after this many (0 = not by count) */
    uint64_t count;      /* ... and this many of them (0 = all following) */
} qo_sim_fault;

#define QO_SIM_LAG_MAX 8

typedef struct qo_sim_lag {
    double share;        /* > 0, relative weight */
    double lo_ms, hi_ms; /* 0 <= lo_ms <= hi_ms <= 60000 */
} qo_sim_lag;

typedef struct qo_sim_settings {
    double lag_s;        /* first-order time constant, seconds, >= 0 */
    FILE *log;           /* CSV of received target writes, or NULL; not closed by the sim */
    qo_sim_fault fault;
    uint64_t seed;       /* PRNG seed for `share` */
    int targets_unreadable; /* 1: an FC03 covering a joint's target registers is answered
                               with exception 0x02 (illegal data address), as on drives
                               whose targets are write-only; 0: readable (default) */
    qo_sim_lag lag[QO_SIM_LAG_MAX]; /* reply latency buckets (see above) */
    size_t n_lag;                   /* 0 = reply at once */
    int rt_priority;     /* > 0: run the server thread SCHED_FIFO at this priority (1..99),
                            best effort (without the privilege it runs normally): a drive
                            has its own CPU, so CPU-bound processes on the master's machine
                            must not slow its replies; 0 = normal scheduling (default) */
} qo_sim_settings;

/* Parses "SHARE:LO-HIms[,SHARE:LO-HIms...]" (also "SHARE:Xms" for a fixed delay; "us" for
 * microseconds) into set->lag / set->n_lag, e.g. "0.97:0-0.2ms,0.03:5-12ms": 97% of the
 * replies within 0.2 ms, 3% after 5 to 12 ms. Returns QO_OK; QO_E_NULL; QO_E_CONFIG
 * (syntax, a share not > 0, lo > hi, a delay outside 0..60000 ms, more than QO_SIM_LAG_MAX
 * buckets; set->n_lag is 0 then). */
qo_status qo_sim_parse_lag_dist(const char *text, qo_sim_settings *set);

/* lag 0.05 s, no log, no fault, seed 1, targets readable, replies at once, no RT. */
extern const qo_sim_settings qo_sim_settings_default;

typedef struct qo_sim_stats {
    uint64_t requests;       /* requests received (framed and for a known slave) */
    uint64_t target_writes;  /* joint targets set (log lines) */
    uint64_t faults;         /* faulted requests */
    uint64_t connections;    /* TCP connections accepted */
    uint64_t bad_frames;     /* RTU frames dropped for a bad CRC or length */
} qo_sim_stats;

typedef struct qo_sim qo_sim;

/* Starts a simulator for `map` (kept by pointer: it must outlive the sim) listening on
 * `spec` ("tcp://IPV4:PORT", "tcp://localhost:PORT" (= 127.0.0.1), "tcp://[IPV6]:PORT",
 * PORT 0 = ephemeral, 0.0.0.0 = every IPv4 interface; or "rtu:DEVICE,BAUD,8N1"). It serves
 * one master at a time: a new connection replaces the old one, as on most drives.
 * settings NULL = defaults. Returns QO_OK with *out set, or (with *out NULL):
 * QO_E_NULL; QO_E_CONFIG (bad spec, empty map, bad settings); QO_E_IO (cannot bind or open
 * the device, cannot start the thread); QO_E_CAPACITY (out of memory). */
qo_status qo_sim_start(const char *spec, const qo_regmap *map, const qo_sim_settings *settings,
                       qo_sim **out);

/* The bound TCP port; 0 for RTU or a NULL sim. */
int qo_sim_port(const qo_sim *sim);

/* Replaces the fault settings (and restarts the request count used by `after` from the
 * current request). QO_OK, QO_E_NULL, QO_E_CONFIG (share outside [0,1], bad kind). */
qo_status qo_sim_set_fault(qo_sim *sim, const qo_sim_fault *fault);

/* Joint i's last target and its simulated position now, in joint units.
 * QO_OK, QO_E_NULL, QO_E_RANGE (i out of range; outputs 0). */
qo_status qo_sim_get_joint(qo_sim *sim, size_t i, double *target, double *position);

/* Holding register `address` of `slave`. QO_OK, QO_E_NULL, QO_E_RANGE (slave not in the
 * map; *value 0). */
qo_status qo_sim_get_register(qo_sim *sim, unsigned slave, uint16_t address, uint16_t *value);

/* QO_OK or QO_E_NULL (*out zeroed). */
qo_status qo_sim_get_stats(qo_sim *sim, qo_sim_stats *out);

/* Waits until at least n requests have been handled, at most timeout_ms.
 * QO_OK, QO_E_NULL, QO_E_TIMEOUT. */
qo_status qo_sim_wait_requests(qo_sim *sim, uint64_t n, unsigned timeout_ms);

/* Stops the server thread (within ~20 ms plus any reply delay in progress), flushes the log,
 * closes and frees. NULL is ignored. */
void qo_sim_stop(qo_sim *sim);

#endif /* QORIENT_SIM_H */
