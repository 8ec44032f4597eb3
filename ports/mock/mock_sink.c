#include "mock/mock_sink.h"
#include "sink_view.h"

#include <string.h>

qo_status qo_mock_sink_write(qo_mock_sink *m, const float *targets, size_t n, uint64_t tick)
{
    size_t i;
    qo_status st = QO_OK;
    if (m == NULL) return QO_E_NULL;
    if (targets == NULL) st = QO_E_NULL;
    else if (m->closed) st = QO_E_STATE;
    else if (n != m->n_joints) st = QO_E_RANGE;
    else {
        for (i = 0; i < m->n_fail_ticks; i++)
            if (m->fail_ticks[i] == tick) st = m->fail_status;
    }
    if (st == QO_OK) {
        if (m->count >= m->max_records) {
            m->dropped++;
            st = QO_E_CAPACITY;
        } else {
            memcpy(m->values + m->count * m->n_joints, targets, n * sizeof *targets);
            if (m->ticks != NULL) m->ticks[m->count] = tick;
            m->count++;
        }
    }
    return qo_sink_view_count(&m->stats, st);
}

static qo_status mock_flush(void *ctx)
{
    qo_mock_sink *m = ctx;
    if (m == NULL) return QO_E_NULL;
    if (m->closed) return QO_E_STATE;
    m->flushes++;
    return QO_OK;
}

void qo_mock_sink_close(qo_mock_sink *m)
{
    if (m != NULL) {
        m->closed = 1;
        m->stats.connected = 0;
    }
}

void qo_mock_sink_free(qo_mock_sink *m)
{
    qo_mock_sink_close(m);
}

qo_status qo_mock_sink_get_stats(const qo_mock_sink *m, qo_sink_stats *out)
{
    return qo_sink_view_stats(m != NULL ? &m->stats : NULL, out);
}

/* The qo_sink adapters: the void * of the sink interface stays in here. */
QO_SINK_VIEW_ADAPTERS(mock_sink, qo_mock_sink)

static qo_status mock_stats(void *ctx, qo_sink_stats *out)
{
    return qo_mock_sink_get_stats(ctx, out);
}

qo_status qo_mock_sink_open(qo_mock_sink *m, size_t n_joints, float *values, uint64_t *ticks,
                            size_t max_records)
{
    if (m == NULL) return QO_E_NULL;
    memset(m, 0, sizeof *m);
    m->closed = 1; /* until every check passed */
    if (values == NULL) return QO_E_NULL;
    if (n_joints == 0 || max_records == 0) return QO_E_TOO_FEW;
    m->n_joints = n_joints;
    m->values = values;
    m->ticks = ticks;
    m->max_records = max_records;
    m->fail_status = QO_E_IO;
    m->closed = 0;
    m->stats.connected = 1;
    return QO_OK;
}

qo_status qo_mock_sink_as_sink(qo_mock_sink *m, qo_sink *out)
{
    static const qo_sink ops = { .write = mock_sink_view_write, .flush = mock_flush,
                                 .close = mock_sink_view_close,
                                 .stats = mock_stats };
    return qo_sink_view_fill(m, &ops, out);
}

qo_status qo_mock_sink_fail_on(qo_mock_sink *m, const uint64_t *fail_ticks, size_t n,
                               qo_status st)
{
    if (m == NULL || (fail_ticks == NULL && n > 0)) return QO_E_NULL;
    m->fail_ticks = n > 0 ? fail_ticks : NULL;
    m->n_fail_ticks = n;
    m->fail_status = st == QO_OK ? QO_E_IO : st;
    return QO_OK;
}

const float *qo_mock_sink_row(const qo_mock_sink *m, size_t i)
{
    if (m == NULL || i >= m->count) return NULL;
    return m->values + i * m->n_joints;
}
