/*
 * ports/sink_view.h - what every port's qo_sink view does alike (ports/mock, ports/linux), so
 * the sinks fill and report the same way (portable: no OS header).
 *
 *   qo_sink_view_fill(obj, ops, out)   *out = *ops with ctx = obj; QO_OK. QO_E_NULL if out is
 *                                      NULL (nothing written) or obj is NULL (*out zeroed).
 *   qo_sink_view_stats(src, out)       *out = *src; QO_OK. QO_E_NULL if out is NULL, or src is
 *                                      NULL (the sink's object was NULL: *out zeroed).
 *   qo_sink_view_count(st, result)     counts one write that returned `result` in *st (writes,
 *                                      writes_ok or writes_failed, consecutive_failures); returns
 *                                      result
 *   QO_SINK_VIEW_ADAPTERS(F, T)        the view's write and close of family qo_F_ with object
 *                                      type T: static F_view_write and F_view_close, calling
 *                                      qo_F_write and qo_F_close (the void * stays in the port)
 */
#ifndef QORIENT_PORTS_SINK_VIEW_H
#define QORIENT_PORTS_SINK_VIEW_H

#include <string.h>

#include "qorient/sink.h"

static inline qo_status qo_sink_view_fill(void *obj, const qo_sink *ops, qo_sink *out)
{
    if (out == NULL) return QO_E_NULL;
    memset(out, 0, sizeof *out);
    if (obj == NULL) return QO_E_NULL;
    *out = *ops;
    out->ctx = obj;
    return QO_OK;
}

static inline qo_status qo_sink_view_stats(const qo_sink_stats *src, qo_sink_stats *out)
{
    if (out == NULL) return QO_E_NULL;
    if (src == NULL) {
        memset(out, 0, sizeof *out);
        return QO_E_NULL;
    }
    *out = *src;
    return QO_OK;
}

static inline qo_status qo_sink_view_count(qo_sink_stats *st, qo_status result)
{
    st->writes++;
    if (result == QO_OK) {
        st->writes_ok++;
        st->consecutive_failures = 0;
    } else {
        st->writes_failed++;
        st->consecutive_failures++;
    }
    return result;
}

#define QO_SINK_VIEW_ADAPTERS(F, T)                                                          \
    static qo_status F##_view_write(void *ctx, const float *targets, size_t n, uint64_t tick) \
    {                                                                                        \
        return qo_##F##_write((T *)ctx, targets, n, tick);                                   \
    }                                                                                        \
    static void F##_view_close(void *ctx) { qo_##F##_close((T *)ctx); }

#endif
