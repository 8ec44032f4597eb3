/*
 * ports/linux/modbus_reg.h - joint values <-> Modbus holding registers, by our own code.
 *
 * Index:
 *   qo_modbus_reg_type, qo_modbus_reg_word_order, qo_modbus_reg_format
 *                                    how one joint value sits in registers
 *   qo_modbus_reg_type_width()       registers per value (1 or 2)
 *   qo_modbus_reg_type_range()       the type's raw range [lo, hi]
 *   qo_modbus_reg_raw_from_value()   joint units -> raw register units (scale, invert, offset)
 *   qo_modbus_reg_value_from_raw()   raw register units -> joint units
 *   qo_modbus_reg_pack_raw()         raw -> registers (round, saturate, word order)
 *   qo_modbus_reg_unpack_raw()       registers -> raw
 *   qo_modbus_reg_pack()             joint value -> registers
 *   qo_modbus_reg_unpack()           registers -> joint value
 *
 * The conversion, stated once:   raw = scale * (invert ? -value : value) + offset
 * so `scale` is register units per joint unit (e.g. 10000 counts per revolution / 2 pi for a
 * joint in radians) and `offset` is the raw value at joint position 0.
 * Integer types round to nearest (ties away from zero); float32 rounds to nearest float.
 * A raw value outside the type's range saturates to the range end and is reported with
 * QO_E_OVERFLOW. 32-bit values use two consecutive registers; QO_MODBUS_REG_HI_FIRST puts the high
 * 16 bits at the lower address ("ABCD", Leadshine, ZLTECH), QO_MODBUS_REG_LO_FIRST the low 16 bits
 * ("CDAB", Delta ASDA). float32 is the IEEE-754 bit pattern (memcpy), never libmodbus's
 * modbus_set_float* helpers, whose byte order differs between libmodbus builds (Debian 3.1.6).
 * Every register holds its 16 bits in host order; libmodbus sends them big-endian on the wire.
 */
#ifndef QORIENT_MODBUS_REG_H
#define QORIENT_MODBUS_REG_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/status.h"

typedef enum qo_modbus_reg_type {
    QO_MODBUS_REG_INT16 = 0,
    QO_MODBUS_REG_UINT16,
    QO_MODBUS_REG_INT32,
    QO_MODBUS_REG_UINT32,
    QO_MODBUS_REG_FLOAT32,
    QO_MODBUS_REG_TYPE_COUNT_
} qo_modbus_reg_type;

typedef enum qo_modbus_reg_word_order {
    QO_MODBUS_REG_HI_FIRST = 0, /* high word at the lower address (ABCD) */
    QO_MODBUS_REG_LO_FIRST      /* low word at the lower address (CDAB) */
} qo_modbus_reg_word_order;

typedef struct qo_modbus_reg_format {
    qo_modbus_reg_type type;
    qo_modbus_reg_word_order order; /* used by 32-bit types only */
    double scale;        /* register units per joint unit; finite, non-zero */
    double offset;       /* raw value at joint value 0; finite */
    int invert;          /* non-zero: the joint's positive direction is the drive's negative */
} qo_modbus_reg_format;

/* 1 for 16-bit types, 2 for 32-bit types, 0 for an unknown type. */
size_t qo_modbus_reg_type_width(qo_modbus_reg_type type);

/* Raw range of the type: [-32768, 32767], [0, 65535], [-2^31, 2^31-1], [0, 2^32-1],
 * [-FLT_MAX, FLT_MAX]. Returns QO_OK, QO_E_NULL, or QO_E_ARG for an unknown type
 * (*lo = *hi = 0 then). */
qo_status qo_modbus_reg_type_range(qo_modbus_reg_type type, double *lo, double *hi);

/* raw = scale * (invert ? -value : value) + offset, unrounded, not saturated.
 * Returns QO_OK; QO_E_NULL; QO_E_ARG for a bad type or order; QO_E_CONFIG for a zero or
 * non-finite scale or a non-finite offset; QO_E_NONFINITE for a non-finite value or result.
 * *raw is 0 on error. */
qo_status qo_modbus_reg_raw_from_value(const qo_modbus_reg_format *f, double value, double *raw);

/* value = (raw - offset) / scale, negated when invert. Same statuses as above; *value is 0 on
 * error. */
qo_status qo_modbus_reg_value_from_raw(const qo_modbus_reg_format *f, double raw, double *value);

/* Rounds `raw` to the type (nearest integer, or nearest float), saturates it to the type's
 * range and writes qo_modbus_reg_type_width(type) registers to regs[0..] in the given word order.
 * *packed_raw (may be NULL) receives the raw value actually encoded.
 * Returns QO_OK; QO_E_OVERFLOW when saturated (regs hold the saturated value); QO_E_NULL;
 * QO_E_ARG for an unknown type or order; QO_E_NONFINITE for NaN/Inf (regs zero, raw 0). */
qo_status qo_modbus_reg_pack_raw(qo_modbus_reg_type type, qo_modbus_reg_word_order order,
                                 double raw, uint16_t *regs, double *packed_raw);

/* Decodes registers regs[0..width-1] into the raw value. Returns QO_OK, QO_E_NULL, QO_E_ARG
 * (unknown type or order), or QO_E_NONFINITE for a float32 NaN/Inf bit pattern (*raw = 0). */
qo_status qo_modbus_reg_unpack_raw(qo_modbus_reg_type type, qo_modbus_reg_word_order order,
                                   const uint16_t *regs, double *raw);

/* qo_modbus_reg_raw_from_value then qo_modbus_reg_pack_raw. On a conversion error regs are zeroed.
 * Returns the first error, QO_E_OVERFLOW for saturation, else QO_OK. */
qo_status qo_modbus_reg_pack(const qo_modbus_reg_format *f, double value, uint16_t *regs);

/* qo_modbus_reg_unpack_raw then qo_modbus_reg_value_from_raw; *value is 0 on error. */
qo_status qo_modbus_reg_unpack(const qo_modbus_reg_format *f, const uint16_t *regs, double *value);

#endif /* QORIENT_MODBUS_REG_H */
