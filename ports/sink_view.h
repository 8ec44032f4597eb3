/*
 * ports/sink_view.h - what every port's qo_sink view does alike (ports/mock, ports/linux), so
 * the sinks fill and report the same way (portable: no OS header).
 *
 *   qo_sink_view_fill(obj, ops, out)   *out = *ops with ctx = obj; QO_OK. QO_E_NULL if out is
 *                                      NULL (nothing written) or obj is NULL (*out zeroed).
 *   qo_sink_view_stats(src, out)       *out = *src; QO_OK. QO_E_NULL if out is NULL, or src is
 *                                      NULL (the sink's object was NULL: *out zeroed).
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

#endif
