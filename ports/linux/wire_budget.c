/* Wire-time budget of one Modbus tick. Contract: wire_budget.h. */
#include "linux/wire_budget.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linux/modbus_pack.h"

struct item { uint16_t addr; unsigned width; };

static int item_cmp(const void *a, const void *b)
{
    const struct item *x = a, *y = b;
    return (x->addr > y->addr) - (x->addr < y->addr);
}

qo_status qo_wire_budget_compute(const qo_regmap *map, const qo_modbus_spec *spec,
                                 double turnaround_us, qo_wire_budget *out)
{
    struct item items[QO_REGMAP_MAX_JOINTS + QO_REGMAP_MAX_WRITES];
    size_t si, j;
    int rtu;
    if (out == NULL) return QO_E_NULL;
    memset(out, 0, sizeof *out);
    if (map == NULL || spec == NULL) return QO_E_NULL;
    if (!isfinite(turnaround_us) || turnaround_us < 0) return QO_E_RANGE;
    if (map->n_joints == 0) return QO_E_CONFIG;
    rtu = spec->transport == QO_MODBUS_RTU;
    if (rtu) {
        if (spec->baud <= 0) return QO_E_CONFIG;
        out->bits_per_char = 1u + (unsigned)spec->data_bits + (spec->parity == 'N' ? 0u : 1u) +
                             (unsigned)spec->stop_bits;
        out->char_us = 1e6 * out->bits_per_char / spec->baud;
        /* Modbus over serial line V1.02, 2.5.1.1: fixed 1750 us above 19200 baud. */
        out->t35_us = spec->baud > 19200 ? 1750.0 : 3.5 * out->char_us;
    }
    for (si = 0; si < map->n_slaves; si++) {
        const qo_regmap_slave *sl = &map->slaves[si];
        size_t n = 0, k;
        for (j = 0; j < map->n_joints; j++) {
            if (map->joints[j].slave != sl->id) continue;
            items[n].addr = map->joints[j].address;
            items[n].width = (unsigned)qo_reg_type_width(map->joints[j].fmt.type);
            if (items[n].width == 0) return QO_E_CONFIG;
            n++;
        }
        if (n == 0) continue; /* a slave section without joints gets no target writes */
        for (k = 0; k < sl->n_constant; k++) {
            items[n].addr = sl->constant[k].address;
            items[n].width = 1;
            n++;
        }
        qsort(items, n, sizeof items[0], item_cmp);
        for (k = 0; k < n;) {
            /* one run: strictly contiguous, at most max_registers, never cutting a value */
            uint16_t first = items[k].addr;
            unsigned regs = items[k].width;
            size_t e = k + 1;
            while (e < n && (unsigned)items[e].addr == (unsigned)first + regs &&
                   regs + items[e].width <= sl->max_registers) {
                regs += items[e].width;
                e++;
            }
            if (out->n_requests == QO_WIRE_MAX_REQUESTS) {
                memset(out, 0, sizeof *out);
                return QO_E_CAPACITY;
            }
            {
                qo_wire_request *r = &out->req[out->n_requests++];
                r->slave = sl->id;
                r->first = first;
                r->registers = regs;
                r->request_bytes = 9u + 2u * regs;
                r->reply_bytes = 8u;
                if (rtu)
                    r->time_us = (r->request_bytes + r->reply_bytes) * out->char_us +
                                 2.0 * out->t35_us + sl->gap_us + turnaround_us;
                out->tick_us += r->time_us;
            }
            k = e;
        }
    }
    if (rtu && out->tick_us > 0) out->max_rate_hz = 1e6 / out->tick_us;
    return QO_OK;
}
