/*
 * fuzz/fuzz_modbus_pack.c - Modbus value packing (ports/linux/modbus_reg.h) fed raw bytes:
 * register formats with any type / word order value (also unknown ones), any double scale and
 * offset (zero, NaN, Inf, denormal), any value, and raw register words.
 * Properties from the header: documented statuses; raw_from_value / value_from_raw give a
 * finite result or an error with 0; pack_raw writes exactly width registers (a guard word
 * after them stays untouched), zeroes them on QO_E_NONFINITE, saturates with QO_E_OVERFLOW,
 * and unpack_raw of what it wrote gives back the packed raw value exactly; unpack of any
 * register words is finite or QO_E_NONFINITE with 0.
 */
#include "fuzz_common.h"
#include "linux/modbus_reg.h"

#ifndef QO_FUZZ_ENTRY
#define QO_FUZZ_ENTRY LLVMFuzzerTestOneInput
#endif

static double fuzz_mp_f64(qo_fz *f)
{
    uint8_t tag = qo_fz_u8(f);
    uint64_t u;
    double d;
    if (tag < 0x80u) {
        u = (uint64_t)qo_fz_u32(f) | ((uint64_t)qo_fz_u32(f) << 32);
        memcpy(&d, &u, sizeof d);
        return d;
    }
    switch (tag & 7u) {
    case 0: return 2147483647.5;
    case 1: return -2147483648.5;
    case 2: return 65535.5;
    case 3: return -32768.5;
    case 4: return 4294967295.4999;
    case 5: return 3.4028235677973366e38;   /* just above FLT_MAX */
    default: return (double)qo_fz_f32(f);
    }
}

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size);

int QO_FUZZ_ENTRY(const uint8_t *data, size_t size)
{
    qo_fz f = qo_fz_init(data, size);
    qo_modbus_reg_format fm;
    uint16_t regs[3], in[2];
    double value, raw, packed, back, lo, hi;
    size_t w;
    qo_status st, sr;

    fm.type = (qo_modbus_reg_type)(qo_fz_u8(&f) % 7u);
    fm.order = (qo_modbus_reg_word_order)(qo_fz_u8(&f) % 3u);
    fm.scale = fuzz_mp_f64(&f);
    fm.offset = fuzz_mp_f64(&f);
    fm.invert = qo_fz_u8(&f) & 1u;
    value = fuzz_mp_f64(&f);
    in[0] = (uint16_t)qo_fz_u32(&f);
    in[1] = (uint16_t)qo_fz_u32(&f);
    w = qo_modbus_reg_type_width(fm.type);
    QO_FUZZ_CHECK(w == ((int)fm.type <= 1 ? 1u : (int)fm.type <= 4 ? 2u : 0u), "width of type %d = %zu", (int)fm.type, w);
    st = qo_modbus_reg_type_range(fm.type, &lo, &hi);
    QO_FUZZ_CHECK(w ? st == QO_OK && lo < hi : st == QO_E_ARG && lo == 0.0 && hi == 0.0, "type_range %d", (int)st);

    /* value -> raw */
    raw = 1.0;
    st = qo_modbus_reg_raw_from_value(&fm, value, &raw);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_CONFIG || st == QO_E_NONFINITE, "raw_from_value status %d", (int)st);
    if (st == QO_OK) {
        QO_FUZZ_CHECK(isfinite(raw), "raw_from_value %g", raw);
        sr = qo_modbus_reg_value_from_raw(&fm, raw, &back);
        QO_FUZZ_CHECK(sr == QO_OK || sr == QO_E_NONFINITE, "value_from_raw status %d", (int)sr);
        if (sr == QO_OK) QO_FUZZ_CHECK(isfinite(back), "value_from_raw %g", back);
        else QO_FUZZ_CHECK(back == 0.0, "value_from_raw error output %g", back);
    } else {
        QO_FUZZ_CHECK(raw == 0.0, "raw_from_value error output %g", raw);
        raw = value;
    }

    /* raw -> registers -> raw */
    regs[0] = regs[1] = 0xA5A5u;
    regs[2] = 0x5A5Au;
    packed = 7.0;
    st = qo_modbus_reg_pack_raw(fm.type, fm.order, raw, regs, &packed);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_OVERFLOW || st == QO_E_ARG || st == QO_E_NONFINITE, "pack_raw status %d", (int)st);
    QO_FUZZ_CHECK(regs[2] == 0x5A5Au && (w == 2 || st == QO_E_ARG || regs[1] == 0xA5A5u), "pack_raw wrote past %zu registers", w);
    if (st == QO_E_NONFINITE) {
        QO_FUZZ_CHECK(packed == 0.0 && regs[0] == 0 && (w < 2 || regs[1] == 0), "pack_raw NONFINITE output");
    } else if (st == QO_OK || st == QO_E_OVERFLOW) {
        double un = 3.0;
        QO_FUZZ_CHECK(isfinite(packed) && packed >= lo && packed <= hi, "packed %g outside [%g, %g]", packed, lo, hi);
        if (st == QO_OK && fm.type != QO_MODBUS_REG_FLOAT32) QO_FUZZ_CHECK(fabs(packed - raw) <= 0.5, "pack_raw %g -> %g", raw, packed);
        sr = qo_modbus_reg_unpack_raw(fm.type, fm.order, regs, &un);
        QO_FUZZ_CHECK(sr == QO_OK && un == packed, "unpack_raw of pack_raw(%g): %d %g, packed %g", raw, (int)sr, un, packed);
    }

    /* whole conversion, and any register words */
    st = qo_modbus_reg_pack(&fm, value, regs);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_OVERFLOW || st == QO_E_ARG || st == QO_E_CONFIG || st == QO_E_NONFINITE,
                  "pack status %d", (int)st);
    back = 5.0;
    st = qo_modbus_reg_unpack(&fm, in, &back);
    QO_FUZZ_CHECK(st == QO_OK || st == QO_E_ARG || st == QO_E_CONFIG || st == QO_E_NONFINITE, "unpack status %d", (int)st);
    if (st == QO_OK) QO_FUZZ_CHECK(isfinite(back), "unpack %g", back);
    else QO_FUZZ_CHECK(back == 0.0, "unpack error output %g", back);
    return 0;
}
