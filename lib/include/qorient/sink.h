/*
 * qorient/sink.h - the sink interface: where a streamer hands N joint targets, once per tick.
 *
 * Index:
 *   qo_sink_stats       counters every sink can report (a subset of a port's own statistics)
 *   qo_sink             function pointers + an opaque context
 *   qo_sink_write()     checked call of sink->write
 *   qo_sink_flush()     checked call of sink->flush (a no-op when the sink has none)
 *   qo_sink_close()     checked call of sink->close (a no-op when the sink has none)
 *   qo_sink_get_stats() checked call of sink->stats (QO_E_STATE when the sink has none)
 *
 * A sink is portable: this header includes no OS or bus header. The ports (ports/mock,
 * ports/linux) fill a qo_sink for their own object.
 *
 * Ownership and lifetime:
 *   - `ctx` belongs to the port that filled the qo_sink; the qo_sink struct itself is a plain
 *     value the caller may copy. It stays valid until close() has been called.
 *   - write() reads `targets[0..n-1]` during the call only and keeps no pointer to them.
 *   - close() releases what the port acquired (bus, memory); after it, only the port's own
 *     destroy/reinit call is allowed. Calling close() twice is harmless for every qorient sink.
 *   - A sink is NOT thread-safe: one thread (the streamer's) calls write/flush/stats. A port
 *     documents if some calls (e.g. its statistics) may come from elsewhere.
 *
 * Timing contract: write() must return within the port's configured bus timeouts (it never
 * blocks for reconnection or for unbounded retries); reconnection is done by service(), which
 * the streamer calls outside the periodic deadline.
 */
#ifndef QORIENT_SINK_H
#define QORIENT_SINK_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Counters common to every sink. All monotonic except consecutive_failures and connected. */
typedef struct qo_sink_stats {
    uint64_t writes;               /* write() calls */
    uint64_t writes_ok;            /* write() calls that returned QO_OK */
    uint64_t writes_failed;        /* write() calls that returned an error */
    uint64_t consecutive_failures; /* failed write() calls since the last QO_OK */
    uint64_t limited;              /* joint values changed by a limit (min/max, rate, type range) */
    uint64_t reconnects;           /* successful reconnections (0 for sinks without a link) */
    int connected;                 /* 1 when the sink can currently reach its device */
} qo_sink_stats;

typedef struct qo_sink {
    void *ctx; /* the port's object, passed back to every function below */

    /* Required. Takes the targets of all n joints for tick number `tick` (a counter the
     * streamer increments by 1 per tick it runs; a deadline skipped after an overrun is not a
     * tick and is counted in the streamer's overrun statistics instead), in the joints' user
     * units. Returns QO_OK when every target (possibly limited) reached the device, otherwise the
     * port's error status (QO_E_TIMEOUT, QO_E_IO, QO_E_DISCONNECTED, QO_E_PROTOCOL,
     * QO_E_STATE, QO_E_RANGE for a wrong n, QO_E_NULL, QO_E_NONFINITE, ...). A failed tick is
     * not retried by the sink: the next write() carries the next targets. */
    qo_status (*write)(void *ctx, const float *targets, size_t n, uint64_t tick);

    /* Optional (may be NULL). Pushes anything buffered to the device. */
    qo_status (*flush)(void *ctx);

    /* Optional (may be NULL). Releases the device link; see "Ownership" above. */
    void (*close)(void *ctx);

    /* Optional (may be NULL). Writes the common counters to *out (zeroed on error). */
    qo_status (*stats)(void *ctx, qo_sink_stats *out);

    /* Optional (may be NULL). Slow housekeeping - reconnecting a dropped link with backoff -
     * that must not delay a tick: the streamer calls it after the tick's write, outside the
     * deadline-critical part. It may block for up to the port's connect timeout. */
    void (*service)(void *ctx);
} qo_sink;

/* sink->write(sink->ctx, ...). QO_E_NULL if sink, sink->write or targets (with n > 0) is NULL. */
static inline qo_status qo_sink_write(const qo_sink *sink, const float *targets, size_t n,
                                      uint64_t tick)
{
    if (sink == NULL || sink->write == NULL || (targets == NULL && n > 0)) return QO_E_NULL;
    return sink->write(sink->ctx, targets, n, tick);
}

/* sink->flush(sink->ctx), QO_OK when the sink has no flush. QO_E_NULL if sink is NULL. */
static inline qo_status qo_sink_flush(const qo_sink *sink)
{
    if (sink == NULL) return QO_E_NULL;
    return sink->flush != NULL ? sink->flush(sink->ctx) : QO_OK;
}

/* sink->close(sink->ctx) when present; nothing for a NULL sink. */
static inline void qo_sink_close(const qo_sink *sink)
{
    if (sink != NULL && sink->close != NULL) sink->close(sink->ctx);
}

/* sink->stats(sink->ctx, out). QO_E_NULL if sink or out is NULL, QO_E_STATE if the sink keeps
 * no statistics. *out is zeroed first, so it is defined on every error. */
static inline qo_status qo_sink_get_stats(const qo_sink *sink, qo_sink_stats *out)
{
    if (out == NULL) return QO_E_NULL;
    {
        static const qo_sink_stats zero = { 0, 0, 0, 0, 0, 0, 0 };
        *out = zero;
    }
    if (sink == NULL) return QO_E_NULL;
    if (sink->stats == NULL) return QO_E_STATE;
    return sink->stats(sink->ctx, out);
}

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_SINK_H */
