/*
 * ports/linux/modbus_layout.h - what one tick of the Modbus sink sends: the register map
 * turned into FC16 requests. Pure (no I/O, no heap): the sink streams with it, and the wire
 * budget (and so `stream --dry-run`) counts with it, so the two cannot disagree.
 *
 * Index:
 *   qo_modbus_layout_item, qo_modbus_layout_request, qo_modbus_layout
 *   qo_modbus_layout_build()   map -> requests
 *
 * Rules: the cells (each joint's target registers, 1 or 2, and every slave's `constant`
 * registers, also of a slave without joints) are sorted by slave, then address, and merged
 * into one request while strictly contiguous and within the slave's max_registers; a
 * 32-bit value is never cut. A request's `regs` holds the constants; the sink packs the
 * joints' values at their offsets each tick. Requests go out in this order.
 */
#ifndef QORIENT_MODBUS_LAYOUT_H
#define QORIENT_MODBUS_LAYOUT_H

#include <stddef.h>
#include <stdint.h>

#include "linux/regmap.h"
#include "qorient/status.h"

#define QO_MODBUS_LAYOUT_MAX \
    (QO_REGMAP_MAX_JOINTS + QO_REGMAP_MAX_SLAVES * QO_REGMAP_MAX_WRITES)

typedef struct qo_modbus_layout_item {
    size_t joint;    /* joint index in the map */
    unsigned offset; /* first register of the joint inside its request */
} qo_modbus_layout_item;

typedef struct qo_modbus_layout_request {
    unsigned slave;
    unsigned gap_us;            /* the slave's silence after the request */
    uint16_t start;             /* first register */
    unsigned count;             /* registers, 1..max_registers of the slave */
    uint16_t regs[QO_REGMAP_MAX_REGISTERS]; /* constants filled in; joints packed per tick */
    size_t first_item, n_items; /* the joints it carries: item[first_item ...] */
} qo_modbus_layout_request;

typedef struct qo_modbus_layout {
    size_t n_requests;
    qo_modbus_layout_request req[QO_MODBUS_LAYOUT_MAX];
    size_t n_items;
    qo_modbus_layout_item item[QO_REGMAP_MAX_JOINTS];
} qo_modbus_layout;

/* Fills *out (about 90 KiB: not for the stack) with the requests of one tick of `map`.
 * Returns QO_OK; QO_E_NULL; QO_E_CONFIG (no joint, more than QO_REGMAP_MAX_JOINTS, a joint
 * with an unknown type, registers past 65535, or wider than its slave's max_registers).
 * *out is empty (n_requests 0) on error. */
qo_status qo_modbus_layout_build(const qo_regmap *map, qo_modbus_layout *out);

#endif /* QORIENT_MODBUS_LAYOUT_H */
