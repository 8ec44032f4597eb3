/*
 * ports/linux/wire_budget.h - what one tick of the Modbus sink puts on the wire, and the
 * highest tick rate a serial (RTU) line therefore allows.
 *
 * Index:
 *   qo_wire_budget_request    one FC16 request of a tick: slave, registers, frame sizes, time
 *   qo_wire_budget            the whole tick: requests, bytes, time per tick, highest rate
 *   qo_wire_budget_compute()  from a register map and a parsed connection spec
 *
 * Model (Modbus over serial line, V1.02): a request is sent, the drive answers, and the line
 * must be silent for 3.5 character times before the next frame (t3.5; above 19200 baud the
 * specification fixes it at 1.75 ms). A character is start + data + parity + stop bits (11
 * for 8E1, 10 for 8N1). Per FC16 request of R registers: request 9 + 2R bytes (address,
 * function, start, quantity, byte count, data, CRC), reply 8 bytes; time = (request + reply)
 * characters + 2 * t3.5 + the slave's gap_us + `turnaround_us` (the drive's own processing
 * delay before it answers, which the specification does not bound: measure your drive and
 * pass it). The requests are the sink's own (linux/modbus_layout.h): per slave, strictly
 * contiguous registers (targets and the slave's constant registers, also of a slave that
 * has constants only), split at max_registers without cutting a 32-bit value. TCP has no
 * such budget (the figures are still given with time 0).
 */
#ifndef QORIENT_WIRE_BUDGET_H
#define QORIENT_WIRE_BUDGET_H

#include <stddef.h>
#include <stdint.h>

#include "linux/modbus_sink.h"
#include "linux/regmap.h"
#include "qorient/status.h"

#define QO_WIRE_BUDGET_MAX_REQUESTS 256

typedef struct qo_wire_budget_request {
    unsigned slave;
    uint16_t first;        /* first register */
    unsigned registers;    /* count */
    unsigned request_bytes, reply_bytes;
    double time_us;        /* on an RTU line, including the gaps; 0 for TCP */
} qo_wire_budget_request;

typedef struct qo_wire_budget {
    size_t n_requests;
    qo_wire_budget_request req[QO_WIRE_BUDGET_MAX_REQUESTS];
    unsigned bits_per_char;   /* RTU: 10 or 11 (or 9..12 for other frames) */
    double char_us;           /* RTU: one character, us */
    double t35_us;            /* RTU: inter-frame silence, us */
    double tick_us;           /* sum over the requests (RTU), 0 for TCP */
    double max_rate_hz;       /* 1e6 / tick_us (RTU); 0 for TCP (no wire bound) */
} qo_wire_budget;

/* Fills *out for `map` over `spec` with the drive's `turnaround_us` (>= 0) per request.
 * Returns QO_OK; QO_E_NULL; QO_E_CONFIG (as qo_modbus_layout_build);
 * QO_E_CAPACITY (more than QO_WIRE_BUDGET_MAX_REQUESTS requests, or out of memory); QO_E_RANGE
 * (turnaround negative or not finite). *out is zeroed on error. */
qo_status qo_wire_budget_compute(const qo_regmap *map, const qo_modbus_link_spec *spec,
                                 double turnaround_us, qo_wire_budget *out);

#endif
