/*
 * ports/mock/mock_sink.h - a sink that records every tick into caller storage.
 *
 * Index:
 *   qo_mock_sink            the recorder (caller-allocated; fields readable by tests)
 *   qo_mock_sink_init()     attach storage, fill a qo_sink
 *   qo_mock_sink_fail_on()  make write() fail on given tick numbers
 *   qo_mock_sink_row()      the targets recorded for the i-th successful write
 *
 * Used by the host tests of the streamer and by anyone testing firmware against a sink:
 * no heap, no OS, no hidden state. Record i (0-based, in call order) holds n_joints floats at
 * values[i * n_joints] and its tick number at ticks[i] (ticks may be NULL).
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
    int closed;              /* 1 after close() */
    qo_sink_stats stats;
} qo_mock_sink;

/* Prepares `m` to record into `values` (max_records * n_joints floats) and `ticks`
 * (max_records entries, or NULL), and fills *sink with its functions and ctx = m.
 * Returns QO_OK; QO_E_NULL if m, values or sink is NULL; QO_E_TOO_FEW if n_joints or
 * max_records is 0. On error *m is zeroed and *sink has NULL functions (when non-NULL).
 *
 * The sink's write() returns: QO_E_STATE after close(); QO_E_NULL for NULL targets;
 * QO_E_RANGE if n != n_joints; the configured fail status on a fail tick (nothing recorded);
 * QO_E_CAPACITY when the storage is full (the write is counted in `dropped`); otherwise QO_OK.
 * Non-finite targets are recorded as given (the mock shows what a streamer sends). */
qo_status qo_mock_sink_init(qo_mock_sink *m, size_t n_joints, float *values, uint64_t *ticks,
                            size_t max_records, qo_sink *sink);

/* From now on write() returns `st` (not QO_OK; QO_E_IO is used if st == QO_OK) on every tick
 * listed in fail_ticks[0..n-1] (kept by pointer: the array must outlive the sink). n == 0
 * clears the list. Returns QO_OK, or QO_E_NULL if m is NULL or fail_ticks is NULL with n > 0. */
qo_status qo_mock_sink_fail_on(qo_mock_sink *m, const uint64_t *fail_ticks, size_t n,
                               qo_status st);

/* Pointer to record i's n_joints targets, or NULL if m is NULL or i >= m->count. */
const float *qo_mock_sink_row(const qo_mock_sink *m, size_t i);

#endif /* QORIENT_MOCK_SINK_H */
