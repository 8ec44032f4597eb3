/*
 * ports/linux/modbus_sink.h - a qo_sink that streams joint targets to drives over Modbus
 * RTU or TCP (libmodbus), using a register map (linux/regmap.h).
 *
 * The sink orchestrates three parts, split along libmodbus's own seams:
 *   linux/modbus_link.h    specs, contexts, connect, reconnection backoff, Modbus TCP
 *                          framed by us (late replies matched by transaction id); the
 *                          simulator shares its specs and contexts
 *   linux/modbus_layout.h  map -> the FC16 requests of one tick (pure; also the wire budget's)
 *   linux/joint_guard.h    clamp, type range and the max_step window per joint (pure)
 *
 * Index:
 *   (specs and contexts: linux/modbus_link.h, included)
 *   qo_modbus_sink_settings, qo_modbus_sink_settings_default
 *   qo_modbus_sink_open()        connect, send the slaves' init writes, seed from feedback
 *   qo_modbus_sink_as_sink()     the generic qo_sink view
 *   qo_modbus_sink_write()       one tick: read back after a fault, limit, pack, FC16 per run
 *   qo_modbus_sink_service()     reconnect with backoff, outside the periodic deadline
 *   qo_modbus_sink_enable()      leave the "disabled" state after the disable action
 *   qo_modbus_sink_seed()        tell the sink where the drives are (no feedback registers)
 *   qo_modbus_sink_read_feedback()  read the feedback registers (FC03)
 *   qo_modbus_sink_get_stats()   counters
 *   qo_modbus_sink_settle_time() the default settle deadline for a final target
 *   qo_modbus_sink_settle()      after the plan: send the final target until the drives hold it
 *   qo_modbus_sink_close()       drop the link (idempotent)
 *   qo_modbus_sink_free()        close, then free the object
 *
 * What one write() does, in order:
 *   1. every target is checked (NaN/Inf -> nothing is sent), clamped to the joint's
 *      [min, max] and converted to register units;
 *   2. read-back (only after a fault): a joint is "uncertain" after any request to its
 *      slave had an unknown outcome (timeout, garbled or misattributable reply, lost link)
 *      and after every reconnection (the drive may have restarted and lost its target).
 *      Before the first write of a tick to a slave with uncertain joints, the sink reads
 *      their target registers back (FC03 over each FC16 group holding one; on RTU after
 *      draining the line for one response timeout) and sets lo = hi = the value read, which
 *      is what the drive holds. FC03 is another function code than FC16, so a late FC16
 *      echo cannot be taken for its reply (libmodbus rejects it, the read-back fails); and
 *      since a drive answers in order, a successful read-back means no earlier reply of
 *      that slave is still on its way: the next FC16 reply is the FC16's own. A failed
 *      read-back sends nothing more this tick (the drives hold), returns its error, and is
 *      retried next tick. An exception 0x01/0x02 (targets not readable on that drive) falls
 *      back to the joint's feedback registers, else keeps the old range (see 3.); any other
 *      exception is a failed read-back. A fault-free tick sends no read-back;
 *   3. rate limit, in register units after rounding, so the drive NEVER receives a change
 *      bigger than max_step from what it may hold. The sink remembers, per joint, the range
 *      [lo, hi] of values the drive may hold: one value after a confirmed write or a
 *      read-back, both the old and the new value after a write whose outcome is unknown.
 *      A new value is always within max_step of every value in that range (the window
 *      [hi - max_step, lo + max_step]); so after a fault the stream resumes from what the
 *      drive holds and walks toward the new target at max_step per tick. A Modbus exception
 *      reply to a write means "not applied" and leaves the range as it was. If the window
 *      is empty (the range is wider than 2 x max_step; widening alone keeps it within
 *      max_step, so this is a guard, not a path) or rounding cannot land inside it, NOTHING
 *      is sent to that joint's slave this tick: write() returns QO_E_INFEASIBLE (after the
 *      other slaves were written), `blocked` counts it, and the joint is read back next
 *      tick. Before the first write the range is seeded from the feedback registers (when
 *      the map has them) or from qo_modbus_sink_seed(); a joint with neither gets its first
 *      target unlimited (and that is counted nowhere: give the map feedback registers or
 *      call seed if that matters);
 *      Weaker cases: the feedback fallback assumes the feedback shows the target (a drive
 *      whose position lags its target seeds the limit from the lagging position); keeping
 *      the old range misses a drive that restarted. On RTU a reply later than the response
 *      timeout plus the drain (about two response timeouts) that slips past both can still
 *      be misattributed: RTU has no transaction id; keep the timeout above the drive's worst
 *      reply latency.
 *   4. the targets and the slaves' constant registers are packed (linux/modbus_reg.h) and
 *      sent as one FC16 per run of strictly contiguous registers of one slave, split at the
 *      slave's max_registers (never inside a 32-bit value); runs go out in slave, then
 *      address order, each followed by the slave's gap_us of silence;
 *   5. RTU: the tick stops at the first failed request (read-back or write), modbus_flush()
 *      drops any stale reply, and the failure is counted. A tick costs at most the drain
 *      and one response timeout plus the answered read-backs and the gaps.
 *   5. TCP: at most one request per slave is outstanding. Replies that arrived since the
 *      last tick are taken first, matched by transaction id, and accepted: an FC16's
 *      joints then hold what it carried (an exception: what they held before), so a late
 *      reply is no error and needs no read-back (`late_replies`). A slave whose request is
 *      still unanswered is waited for until one response timeout after the tick began; if
 *      still unanswered, its tick is skipped (`skipped`; nothing is queued) and write()
 *      returns QO_E_TIMEOUT, which does NOT count towards fail_threshold. A request
 *      without a reply within the response timeout stays outstanding the same way (its
 *      joints may hold the old or the new value meanwhile). A request unanswered for
 *      silence_us drops the link (reconnect with the backoff) when nothing at all came back
 *      since it was sent, else it is abandoned and its joints read back; a reply that
 *      matches nothing is dropped (`stale_replies`). A broken socket or a byte stream that
 *      is not Modbus TCP drops the link at once.
 * libmodbus's own error recovery is NONE: its LINK mode can loop for ever.
 *
 * After `fail_threshold` consecutive failed ticks the sink takes its failure action: HOLD
 * leaves the drives on their last target and the link as it is (closing a working link
 * would only add a slow first reply: the reconnect spiral); a link found broken is closed
 * at once. DISABLE closes the link after first sending every slave's `disable` writes
 * (best effort) and then refuses
 * writes (QO_E_STATE) until qo_modbus_sink_enable(). While the link is down write() returns
 * QO_E_DISCONNECTED at once, without touching the bus; qo_modbus_sink_service() (called by
 * the streamer after its deadline work) reconnects with exponential backoff, resends the
 * init writes (the disable writes instead, while disabled) and clears the failure count.
 *
 * Lifecycle, the same for the three sinks (linux/modbus_sink.h, linux/gpio_sink.h,
 * mock/mock_sink.h; only the mock lives in caller storage):
 *   open -> as_sink -> write ... -> close -> free
 *   - open: QO_OK and an open object; on error nothing stays open (*out is NULL here).
 *   - a NULL object: write, as_sink, get_stats and the other calls returning a status return
 *     QO_E_NULL (as_sink and get_stats zero their output, read_feedback fills NaN); close and
 *     free do nothing.
 *   - a closed object: write, service, enable, read_feedback and settle return QO_E_STATE;
 *     get_stats still reports (QO_OK, connected 0); as_sink still fills the view (whose write
 *     then returns QO_E_STATE); a second close does nothing; free is the only other call left
 *     to make. A closed sink is not reopened: open a new one.
 *   - the same error gives the same status in every sink: a NULL pointer QO_E_NULL, a wrong
 *     number of targets QO_E_RANGE (nothing sent), a closed sink QO_E_STATE.
 *
 * Threads: a sink is used by one thread at a time (libmodbus contexts are not thread-safe).
 */
#ifndef QORIENT_MODBUS_SINK_H
#define QORIENT_MODBUS_SINK_H

#include <stddef.h>
#include <stdint.h>

#include <modbus.h>

#include "qorient/sink.h"
#include "qorient/status.h"
#include "linux/modbus_link.h"
#include "linux/regmap.h"

typedef enum qo_modbus_sink_fail_action {
    QO_MODBUS_SINK_ON_FAIL_HOLD = 0, /* drives keep their last target; resume after reconnect */
    QO_MODBUS_SINK_ON_FAIL_DISABLE   /* send the disable writes; stay disabled until enable() */
} qo_modbus_sink_fail_action;

typedef struct qo_modbus_sink_settings {
    uint32_t response_timeout_us; /* first reply byte (and TCP connect); keep it below the
                                     control period; 1..10000000. On RTU it also covers the
                                     request's own wire time: at 19200 8E1 a 6 x int32 FC16
                                     (33 bytes) takes 19 ms before the drive can answer */
    uint32_t byte_timeout_us;     /* between reply bytes; 0 = whole reply within the response
                                     timeout */
    unsigned fail_threshold;      /* consecutive failed ticks before the action; >= 1 */
    qo_modbus_sink_fail_action on_fail;
    uint32_t reconnect_min_us;    /* first backoff after a failed reconnection; >= 1 */
    uint32_t reconnect_max_us;    /* backoff ceiling; >= reconnect_min_us */
    int rs485;                    /* RTU: try MODBUS_RTU_RS485 mode (failure is ignored:
                                     ptys and many USB adapters refuse it) */
    int seed_from_feedback;       /* read feedback registers at (re)connect to seed the rate
                                     limit of joints never written */
    uint32_t open_timeout_us;     /* response timeout for the first connection, its init writes
                                     and feedback reads in qo_modbus_sink_open only (outside any
                                     control loop, so it can be generous); 0 = the response
                                     timeout; at most 10000000 */
    uint32_t silence_us;          /* TCP: a request unanswered this long makes the link count
                                     as broken (reconnect) when nothing at all came back since
                                     it was sent, else it is abandoned and its joints read
                                     back; 0 = max(1 s, 20 x the response timeout); at most
                                     60000000 */
} qo_modbus_sink_settings;

/* 20 ms response, 5 ms byte timeout, threshold 5, HOLD, backoff 50 ms .. 2 s, no RS485 ioctl,
 * seed from feedback, open timeout 0 (= the response timeout), silence 0 (automatic). */
extern const qo_modbus_sink_settings qo_modbus_sink_settings_default;

typedef struct qo_modbus_sink_stats {
    qo_sink_stats common;        /* writes, ok, failed, consecutive, limited, reconnects */
    uint64_t requests;           /* Modbus requests sent (FC16 + FC06 + FC03) */
    uint64_t requests_failed;
    uint64_t timeouts;           /* ETIMEDOUT */
    uint64_t exceptions;         /* exception replies */
    uint64_t protocol_errors;    /* bad CRC, wrong slave, bad data, ... */
    uint64_t disconnects;        /* links found down (or closed after the threshold) */
    uint64_t reconnect_attempts;
    uint64_t rate_limited;       /* joint values changed by max_step */
    uint64_t clamped;            /* joint values changed by min/max */
    uint64_t saturated;          /* joint values changed by the register type's range */
    uint64_t actions;            /* failure actions taken */
    uint64_t readbacks;          /* FC03 read-backs of target registers (after an unknown
                                    outcome or a (re)connection; never in a fault-free tick) */
    uint64_t readback_fallbacks; /* read-backs answered by an exception: feedback used, or
                                    the old range kept */
    uint64_t blocked;            /* joint values not sent: no value within max_step of every
                                    value the drive may hold (the slave held that tick) */
    uint64_t drains;             /* RTU: line drains before a read-back */
    uint64_t drained_bytes;      /* RTU: bytes dropped by the drains (late replies, noise) */
    uint64_t skipped;            /* TCP: slave-ticks not sent because that slave's previous
                                    request was still unanswered at the tick's deadline */
    uint64_t late_replies;       /* TCP: replies taken after their request's call returned
                                    (accepted: the drive's state is then known) */
    uint64_t stale_replies;      /* TCP: replies matching no outstanding request (dropped) */
    uint64_t abandoned;          /* TCP: requests given up after silence_us (joints read back) */
    uint64_t silences;           /* TCP: links dropped because nothing came back for
                                    silence_us */
    unsigned groups;             /* FC16 requests per tick */
    int disabled;                /* 1 while in the disabled state */
    qo_status last_error;        /* last failure, QO_OK if none yet */
    uint32_t backoff_us;         /* current reconnection backoff */
} qo_modbus_sink_stats;

typedef struct qo_modbus_sink qo_modbus_sink;

/* qo_modbus_sink_open retries a connection whose link came up but whose init writes or
 * feedback reads failed (an exception, a lost reply) this many times, with the backoff. */
#define QO_MODBUS_SINK_OPEN_RETRIES 4

/* Validates settings (NULL = defaults) and `map` (kept by pointer: it must outlive the sink),
 * connects to `spec`, sends the init writes and seeds from feedback (retried up to
 * QO_MODBUS_SINK_OPEN_RETRIES times with the reconnection backoff when the link came up but a
 * request failed: one exception while connecting does not fail the open).
 * Returns QO_OK with *out set; on error *out is NULL and nothing stays open:
 * QO_E_NULL; QO_E_CONFIG (bad spec, empty map, bad settings); QO_E_LIMIT (a zero timeout);
 * QO_E_IO, QO_E_TIMEOUT, QO_E_DISCONNECTED, QO_E_PROTOCOL (connection or init failed). */
qo_status qo_modbus_sink_open(const char *spec, const qo_regmap *map,
                              const qo_modbus_sink_settings *settings, qo_modbus_sink **out);

/* Fills *out (write, flush, close, stats) with ctx = s. close is qo_modbus_sink_close, so
 * the object still needs qo_modbus_sink_free. QO_E_NULL if either is NULL (*out zeroed). */
qo_status qo_modbus_sink_as_sink(qo_modbus_sink *s, qo_sink *out);

/* One tick; see the header comment. `targets` holds map->n_joints values in joint units.
 * Returns QO_OK; QO_E_NULL; QO_E_RANGE (n != number of joints); QO_E_NONFINITE (nothing
 * sent); QO_E_STATE (closed, or disabled); QO_E_DISCONNECTED (link down, nothing sent);
 * QO_E_TIMEOUT; QO_E_PROTOCOL (exception or malformed reply); QO_E_IO (other errors);
 * QO_E_INFEASIBLE (a joint had no value within max_step of every value its drive may hold:
 * its slave was not written, the others were). A failed read-back returns its bus error. */
qo_status qo_modbus_sink_write(qo_modbus_sink *s, const float *targets, size_t n,
                               uint64_t tick);

/* Reconnection, outside the deadline. A reconnection marks every joint with a known range
 * uncertain (read back before its next write). When the link is up: QO_OK at once. When down and the
 * backoff has not expired: QO_E_DISCONNECTED at once. Otherwise one attempt (bounded by the
 * response timeout per request): QO_OK when reconnected, else its error and a doubled
 * backoff. QO_E_NULL, QO_E_STATE after close. */
qo_status qo_modbus_sink_service(qo_modbus_sink *s);

/* Leaves the disabled state: resends the init writes when connected (else they go with the
 * next reconnection). QO_OK, QO_E_NULL, QO_E_STATE (closed), or the bus error (still
 * disabled). */
qo_status qo_modbus_sink_enable(qo_modbus_sink *s);

/* Declares the drives' current positions (joint units, n = number of joints) as the start of
 * the rate limit. A joint already marked uncertain is still read back before its next write
 * (the read value wins). QO_OK, QO_E_NULL, QO_E_RANGE, QO_E_NONFINITE (nothing changed). */
qo_status qo_modbus_sink_seed(qo_modbus_sink *s, const float *positions, size_t n);

/* Reads every joint's feedback registers (FC03) into out[0..n-1] in joint units; joints
 * without feedback get NaN. QO_OK, QO_E_NULL, QO_E_RANGE, QO_E_STATE, QO_E_DISCONNECTED or
 * the bus error (out is all NaN then). */
qo_status qo_modbus_sink_read_feedback(qo_modbus_sink *s, float *out, size_t n);

/* What qo_modbus_sink_settle found. Joint units; NaN where nothing is known. */
typedef struct qo_modbus_sink_settle_report {
    int reached;                        /* 1: every joint holds its goal (read back) */
    uint64_t ticks;                     /* writes sent while settling */
    double elapsed_s;                   /* time spent settling */
    double deadline_s;                  /* the deadline it was given */
    size_t n;                           /* joints */
    double goal[QO_REGMAP_MAX_JOINTS];  /* the final target as the drive must hold it: clamped
                                           to min/max and the type range, rounded to the
                                           register's resolution */
    double held[QO_REGMAP_MAX_JOINTS];  /* the value the drive is known to hold (acknowledged
                                           or read back), NaN when unknown (a write of unknown
                                           outcome) */
    int short_of[QO_REGMAP_MAX_JOINTS]; /* 1 when held != goal (or unknown) at the end */
} qo_modbus_sink_settle_report;

/* The default settle deadline in seconds for `final` (n joint targets, joint units) at one
 * write per `period_s`: twice the time the max_step catch-up needs from what the drives
 * are known to hold (ceil(distance / max_step) ticks for the slowest joint, plus one), plus
 * QO_MODBUS_SINK_SETTLE_SLACK_S for replies and read-backs. A joint without max_step, or whose
 * held value is unknown, needs one tick. Returns the deadline, or QO_MODBUS_SINK_SETTLE_SLACK_S
 * when an argument is NULL, n does not match, a target is not finite or period_s <= 0. */
#define QO_MODBUS_SINK_SETTLE_SLACK_S 0.5
double qo_modbus_sink_settle_time(const qo_modbus_sink *s, const float *final, size_t n,
                                  double period_s);

/* "Done" means the drives hold the final target, not that the plan ended: the max_step
 * window lets a drive lag a fast plan by many ticks. Writes `final` (joint units, n =
 * number of joints) once per `period_s` (absolute CLOCK_MONOTONIC deadlines, reconnecting
 * with the usual backoff when the link is down) until every joint's last acknowledged
 * target equals its goal (see the report), then reads the targets back (FC03; on a drive
 * whose targets are unreadable, its feedback registers, see the header comment) and stops
 * when the values read are the goals too; or until `deadline_s` seconds have passed.
 * *out is always written. Returns QO_OK (reached); QO_E_TIMEOUT (deadline passed: see
 * out->short_of); QO_E_NULL; QO_E_RANGE (n); QO_E_NONFINITE; QO_E_LIMIT (period_s not > 0,
 * deadline_s negative or not finite); QO_E_STATE (closed or disabled). Blocks the caller
 * for up to deadline_s plus one tick's requests: call it from the thread that owns the
 * sink, after the streamer stopped. */
qo_status qo_modbus_sink_settle(qo_modbus_sink *s, const float *final, size_t n,
                                double period_s, double deadline_s,
                                qo_modbus_sink_settle_report *out);

/* Copies the counters (zeroed when s is NULL). QO_OK or QO_E_NULL. */
qo_status qo_modbus_sink_get_stats(const qo_modbus_sink *s, qo_modbus_sink_stats *out);

/* Closes the link; later writes return QO_E_STATE. Idempotent; NULL is ignored. */
void qo_modbus_sink_close(qo_modbus_sink *s);

/* Closes and frees. NULL is ignored. */
void qo_modbus_sink_free(qo_modbus_sink *s);

#endif /* QORIENT_MODBUS_SINK_H */
