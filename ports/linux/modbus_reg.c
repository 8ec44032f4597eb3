#include "linux/modbus_reg.h"

#include <float.h>
#include <math.h>
#include <string.h>

size_t qo_modbus_reg_type_width(qo_modbus_reg_type type)
{
    switch (type) {
    case QO_MODBUS_REG_INT16:
    case QO_MODBUS_REG_UINT16: return 1;
    case QO_MODBUS_REG_INT32:
    case QO_MODBUS_REG_UINT32:
    case QO_MODBUS_REG_FLOAT32: return 2;
    default: return 0;
    }
}

qo_status qo_modbus_reg_type_range(qo_modbus_reg_type type, double *lo, double *hi)
{
    double l = 0.0, h = 0.0;
    qo_status st = QO_OK;
    switch (type) {
    case QO_MODBUS_REG_INT16: l = -32768.0; h = 32767.0; break;
    case QO_MODBUS_REG_UINT16: l = 0.0; h = 65535.0; break;
    case QO_MODBUS_REG_INT32: l = -2147483648.0; h = 2147483647.0; break;
    case QO_MODBUS_REG_UINT32: l = 0.0; h = 4294967295.0; break;
    case QO_MODBUS_REG_FLOAT32: l = -(double)FLT_MAX; h = (double)FLT_MAX; break;
    default: st = QO_E_ARG; break;
    }
    if (lo == NULL || hi == NULL) return QO_E_NULL;
    *lo = l;
    *hi = h;
    return st;
}

static qo_status check_format(const qo_modbus_reg_format *f)
{
    if (qo_modbus_reg_type_width(f->type) == 0) return QO_E_ARG;
    if (f->order != QO_MODBUS_REG_HI_FIRST && f->order != QO_MODBUS_REG_LO_FIRST) return QO_E_ARG;
    if (!isfinite(f->scale) || f->scale == 0.0 || !isfinite(f->offset)) return QO_E_CONFIG;
    return QO_OK;
}

/* The checks both conversions start with, in their documented order: out NULL (nothing
 * written), then *out = 0, f NULL, a bad format, a non-finite input. */
static qo_status conv_args(const qo_modbus_reg_format *f, double in, double *out)
{
    qo_status st;
    if (out == NULL) return QO_E_NULL;
    *out = 0.0;
    if (f == NULL) return QO_E_NULL;
    st = check_format(f);
    if (st != QO_OK) return st;
    return isfinite(in) ? QO_OK : QO_E_NONFINITE;
}

qo_status qo_modbus_reg_raw_from_value(const qo_modbus_reg_format *f, double value, double *raw)
{
    qo_status st = conv_args(f, value, raw);
    double r;
    if (st != QO_OK) return st;
    r = f->scale * (f->invert ? -value : value) + f->offset;
    if (!isfinite(r)) return QO_E_NONFINITE;
    *raw = r;
    return QO_OK;
}

qo_status qo_modbus_reg_value_from_raw(const qo_modbus_reg_format *f, double raw, double *value)
{
    qo_status st = conv_args(f, raw, value);
    double v;
    if (st != QO_OK) return st;
    v = (raw - f->offset) / f->scale;
    if (f->invert) v = -v;
    if (!isfinite(v)) return QO_E_NONFINITE;
    *value = v;
    return QO_OK;
}

static void put32(qo_modbus_reg_word_order order, uint32_t u, uint16_t *regs)
{
    uint16_t hi = (uint16_t)(u >> 16), lo = (uint16_t)(u & 0xFFFFu);
    regs[0] = order == QO_MODBUS_REG_HI_FIRST ? hi : lo;
    regs[1] = order == QO_MODBUS_REG_HI_FIRST ? lo : hi;
}

static uint32_t get32(qo_modbus_reg_word_order order, const uint16_t *regs)
{
    uint32_t hi = order == QO_MODBUS_REG_HI_FIRST ? regs[0] : regs[1];
    uint32_t lo = order == QO_MODBUS_REG_HI_FIRST ? regs[1] : regs[0];
    return (hi << 16) | lo;
}

qo_status qo_modbus_reg_pack_raw(qo_modbus_reg_type type, qo_modbus_reg_word_order order,
                                 double raw, uint16_t *regs, double *packed_raw)
{
    double lo, hi, r;
    size_t w = qo_modbus_reg_type_width(type);
    qo_status st = QO_OK;
    if (packed_raw != NULL) *packed_raw = 0.0;
    if (regs == NULL) return QO_E_NULL;
    regs[0] = 0;
    if (w == 2) regs[1] = 0;
    if (w == 0 || (order != QO_MODBUS_REG_HI_FIRST && order != QO_MODBUS_REG_LO_FIRST))
        return QO_E_ARG;
    if (!isfinite(raw)) return QO_E_NONFINITE;
    (void)qo_modbus_reg_type_range(type, &lo, &hi);
    if (type == QO_MODBUS_REG_FLOAT32) {
        float fv;
        uint32_t u;
        if (raw > hi) { r = hi; st = QO_E_OVERFLOW; }
        else if (raw < lo) { r = lo; st = QO_E_OVERFLOW; }
        else r = raw;
        fv = (float)r;
        /* (float) of a double just under FLT_MAX can round up to Inf: keep it finite. */
        if (isinf(fv)) { fv = fv > 0.0f ? FLT_MAX : -FLT_MAX; st = QO_E_OVERFLOW; }
        memcpy(&u, &fv, sizeof u);
        put32(order, u, regs);
        if (packed_raw != NULL) *packed_raw = (double)fv;
        return st;
    }
    r = round(raw);
    if (r > hi) { r = hi; st = QO_E_OVERFLOW; }
    else if (r < lo) { r = lo; st = QO_E_OVERFLOW; }
    switch (type) {
    case QO_MODBUS_REG_INT16: regs[0] = (uint16_t)(int16_t)r; break;
    case QO_MODBUS_REG_UINT16: regs[0] = (uint16_t)r; break;
    case QO_MODBUS_REG_INT32: put32(order, (uint32_t)(int32_t)r, regs); break;
    default: put32(order, (uint32_t)r, regs); break;
    }
    if (packed_raw != NULL) *packed_raw = r;
    return st;
}

qo_status qo_modbus_reg_unpack_raw(qo_modbus_reg_type type, qo_modbus_reg_word_order order,
                                   const uint16_t *regs, double *raw)
{
    uint32_t u;
    if (raw == NULL) return QO_E_NULL;
    *raw = 0.0;
    if (regs == NULL) return QO_E_NULL;
    if (qo_modbus_reg_type_width(type) == 0 ||
        (order != QO_MODBUS_REG_HI_FIRST && order != QO_MODBUS_REG_LO_FIRST))
        return QO_E_ARG;
    switch (type) {
    case QO_MODBUS_REG_INT16: *raw = (double)(int16_t)regs[0]; break;
    case QO_MODBUS_REG_UINT16: *raw = (double)regs[0]; break;
    case QO_MODBUS_REG_INT32: *raw = (double)(int32_t)get32(order, regs); break;
    case QO_MODBUS_REG_UINT32: *raw = (double)get32(order, regs); break;
    default: {
        float fv;
        u = get32(order, regs);
        memcpy(&fv, &u, sizeof fv);
        if (!isfinite(fv)) return QO_E_NONFINITE;
        *raw = (double)fv;
        break;
    }
    }
    return QO_OK;
}

qo_status qo_modbus_reg_pack(const qo_modbus_reg_format *f, double value, uint16_t *regs)
{
    double raw;
    qo_status st;
    if (regs == NULL) return QO_E_NULL;
    regs[0] = 0;
    if (f == NULL) return QO_E_NULL;
    if (qo_modbus_reg_type_width(f->type) == 2) regs[1] = 0;
    st = qo_modbus_reg_raw_from_value(f, value, &raw);
    if (st != QO_OK) return st;
    return qo_modbus_reg_pack_raw(f->type, f->order, raw, regs, NULL);
}

qo_status qo_modbus_reg_unpack(const qo_modbus_reg_format *f, const uint16_t *regs, double *value)
{
    double raw;
    qo_status st;
    if (value == NULL) return QO_E_NULL;
    *value = 0.0;
    if (f == NULL || regs == NULL) return QO_E_NULL;
    st = check_format(f);
    if (st != QO_OK) return st;
    st = qo_modbus_reg_unpack_raw(f->type, f->order, regs, &raw);
    if (st != QO_OK) return st;
    return qo_modbus_reg_value_from_raw(f, raw, value);
}
