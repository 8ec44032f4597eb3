/* Wire-time budget of one Modbus tick. Contract: wire_budget.h. */
#include "linux/wire_budget.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linux/modbus_layout.h"

qo_status qo_wire_budget_compute(const qo_regmap *map, const qo_modbus_link_spec *spec,
                                 double turnaround_us, qo_wire_budget *out)
{
    qo_modbus_layout *lay;
    qo_status st;
    size_t k;
    int rtu;
    if (out == NULL) return QO_E_NULL;
    memset(out, 0, sizeof *out);
    if (map == NULL || spec == NULL) return QO_E_NULL;
    if (!isfinite(turnaround_us) || turnaround_us < 0) return QO_E_RANGE;
    if (map->n_joints == 0) return QO_E_CONFIG;
    rtu = spec->transport == QO_MODBUS_LINK_RTU;
    if (rtu) {
        if (spec->baud <= 0) return QO_E_CONFIG;
        out->bits_per_char = 1u + (unsigned)spec->data_bits + (spec->parity == 'N' ? 0u : 1u) +
                             (unsigned)spec->stop_bits;
        out->char_us = 1e6 * out->bits_per_char / spec->baud;
        /* Modbus over serial line V1.02, 2.5.1.1: fixed 1750 us above 19200 baud. */
        out->t35_us = spec->baud > 19200 ? 1750.0 : 3.5 * out->char_us;
    }
    lay = malloc(sizeof *lay);
    if (lay == NULL) return QO_E_CAPACITY;
    st = qo_modbus_layout_build(map, lay);
    if (st == QO_OK && lay->n_requests > QO_WIRE_BUDGET_MAX_REQUESTS) st = QO_E_CAPACITY;
    for (k = 0; st == QO_OK && k < lay->n_requests; k++) {
        const qo_modbus_layout_request *q = &lay->req[k];
        qo_wire_budget_request *r = &out->req[out->n_requests++];
        r->slave = q->slave;
        r->first = q->start;
        r->registers = q->count;
        r->request_bytes = 9u + 2u * q->count;
        r->reply_bytes = 8u;
        if (rtu)
            r->time_us = (r->request_bytes + r->reply_bytes) * out->char_us + 2.0 * out->t35_us +
                         q->gap_us + turnaround_us;
        out->tick_us += r->time_us;
    }
    free(lay);
    if (st != QO_OK) {
        memset(out, 0, sizeof *out);
        return st;
    }
    if (rtu && out->tick_us > 0) out->max_rate_hz = 1e6 / out->tick_us;
    return QO_OK;
}
