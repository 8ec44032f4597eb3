/*
 * ports/mock/mock_sink.h - a sink that records every tick into caller storage.
 *
 * Index:
 *   qo_mock_sink            the recorder (caller-allocated; fields readable by tests)
 *   qo_mock_sink_open()     attach storage (the object is the caller's)
 *   qo_mock_sink_as_sink()  the generic qo_sink view (write, flush, close, stats)
 *   qo_mock_sink_write()    record one tick (the view's write)
 *   qo_mock_sink_get_stats() the common counters
 *   qo_mock_sink_close()    later writes return QO_E_STATE (the view's close)
 *   qo_mock_sink_free()     close; nothing to free (caller storage): the lifecycle's last verb
 *   qo_mock_sink_fail_on()  make write() fail on given tick numbers
 *   qo_mock_sink_row()      the targets recorded for the i-th successful write
 *
 * Used by the host tests of the streamer and by anyone testing firmware against a sink:
 * no heap, no OS, no hidden state. Record i (0-based, in call order) holds n_joints floats at
 * values[i * n_joints] and its tick number at ticks[i] (ticks may be NULL).
 *
 * Lifecycle, the same for the three sinks (linux/modbus_sink.h, linux/gpio_sink.h,
 * mock/mock_sink.h); the mock alone lives in caller storage, so its open takes the object
 * instead of handing one out and its free releases nothing:
 *   open -> as_sink -> write ... -> close -> free
 *   - open: QO_OK and an open object; on error nothing stays open (*m is zeroed and not open:
 *     its write returns QO_E_STATE).
 *   - a NULL object: write, get_stats and as_sink return QO_E_NULL (their outputs zeroed);
 *     close and free do nothing; fail_on returns QO_E_NULL, row NULL.
 *   - a closed object: write and the view's flush return QO_E_STATE; get_stats still reports
 *     (QO_OK, connected 0); as_sink still fills the view (whose write then returns
 *     QO_E_STATE); a second close does nothing. open may be called again on the same storage.
 *   - the same error gives the same status in every sink: a NULL pointer QO_E_NULL, a wrong
 *     number of targets QO_E_RANGE (nothing recorded), a closed sink QO_E_STATE.
 */
#ifndef QORIENT_MOCK_SINK_H
#define QORIENT_MOCK_SINK_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/sink.h"

typedef struct qo_mock_sink {
    size_t n_joints;         /* targets expected per write */
    float *values;           /* max_records * n_joints floats */
    uint64_t *ticks;         /* max_records tick numbers, or NULL */
    size_t max_records;
    size_t count;            /* records stored */
    uint64_t dropped;        /* successful writes that found the storage full */
    const uint64_t *fail_ticks; /* ticks on which write() fails (not recorded) */
    size_t n_fail_ticks;
    qo_status fail_status;   /* status returned on those ticks */
    uint64_t flushes;        /* flush() calls */
    int closed;              /* 1 after close() or a failed open: not open */
    qo_sink_stats stats;
} qo_mock_sink;

/* Prepares `m` to record into `values` (max_records * n_joints floats) and `ticks`
 * (max_records entries, or NULL). Returns QO_OK; QO_E_NULL if m or values is NULL;
 * QO_E_TOO_FEW if n_joints or max_records is 0. On error *m is zeroed and not open. */
qo_status qo_mock_sink_open(qo_mock_sink *m, size_t n_joints, float *values, uint64_t *ticks,
                            size_t max_records);

/* Fills *out (write, flush, close, stats; service NULL) with ctx = m. close is
 * qo_mock_sink_close. QO_OK; QO_E_NULL if m or out is NULL (*out zeroed when out is not
 * NULL). */
qo_status qo_mock_sink_as_sink(qo_mock_sink *m, qo_sink *out);

/* Records one tick. Returns QO_OK; QO_E_NULL (m or targets NULL); QO_E_STATE (closed, or
 * never opened); QO_E_RANGE (n != n_joints: nothing recorded); the configured fail status on a
 * fail tick (nothing recorded); QO_E_CAPACITY when the storage is full (the write is counted
 * in `dropped`). Non-finite targets are recorded as given (the mock shows what a streamer
 * sends). Every call but one with m NULL is counted in the statistics. */
qo_status qo_mock_sink_write(qo_mock_sink *m, const float *targets, size_t n, uint64_t tick);

/* Copies the common counters (connected 1 while open). QO_OK; QO_E_NULL if m or out is NULL
 * (*out zeroed when out is not NULL). */
qo_status qo_mock_sink_get_stats(const qo_mock_sink *m, qo_sink_stats *out);

/* Later writes return QO_E_STATE; the records stay readable. Idempotent; NULL is ignored. */
void qo_mock_sink_close(qo_mock_sink *m);

/* Closes; the object and its storage are the caller's, so nothing is freed (the records stay
 * readable). NULL is ignored. */
void qo_mock_sink_free(qo_mock_sink *m);

/* From now on write() returns `st` (not QO_OK; QO_E_IO is used if st == QO_OK) on every tick
 * listed in fail_ticks[0..n-1] (kept by pointer: the array must outlive the sink). n == 0
 * clears the list. Returns QO_OK, or QO_E_NULL if m is NULL or fail_ticks is NULL with n > 0. */
qo_status qo_mock_sink_fail_on(qo_mock_sink *m, const uint64_t *fail_ticks, size_t n,
                               qo_status st);

/* Pointer to record i's n_joints targets, or NULL if m is NULL or i >= m->count. */
const float *qo_mock_sink_row(const qo_mock_sink *m, size_t i);

#endif /* QORIENT_MOCK_SINK_H */
