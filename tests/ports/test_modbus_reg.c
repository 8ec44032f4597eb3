/* Packing joint values into Modbus registers: scale/offset/invert, rounding, saturation at
 * the type's range, explicit word order, float32 by IEEE bits. The reference is integer and
 * double arithmetic written here, and known IEEE-754 bit patterns. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <math.h>
#include <float.h>
#include <cmocka.h>

#include "linux/modbus_reg.h"
#include "common/ref.h"

static uint64_t rng_state = 0x1234567ull;
static uint64_t next_u64(void) { return ref_splitmix64(&rng_state); } /* tests/common/ref.c */
static double uniform(double lo, double hi)
{
    return lo + (hi - lo) * ((double)(next_u64() >> 11) / 9007199254740992.0);
}

static qo_modbus_reg_format fmt(qo_modbus_reg_type t, qo_modbus_reg_word_order o, double scale,
                                double offset, int inv)
{
    qo_modbus_reg_format f = { .type = t, .order = o, .scale = scale, .offset = offset,
                               .invert = inv };
    return f;
}
/* The format the tests start from: type t as is (high word first, scale 1, no offset, no
 * inversion); a test states only what it changes. */
static qo_modbus_reg_format plain(qo_modbus_reg_type t)
{
    return fmt(t, QO_MODBUS_REG_HI_FIRST, 1.0, 0.0, 0);
}

static void test_float32_bits_and_word_order(void **state)
{
    uint16_t r[2];
    double back;
    qo_modbus_reg_format f = plain(QO_MODBUS_REG_FLOAT32);
    (void)state;
    /* 123456.0f = 0x47F12000 (IEEE-754), the value the Debian libmodbus helpers get wrong. */
    assert_int_equal(qo_modbus_reg_pack(&f, 123456.0, r), QO_OK);
    assert_int_equal(r[0], 0x47F1);
    assert_int_equal(r[1], 0x2000);
    f.order = QO_MODBUS_REG_LO_FIRST;
    assert_int_equal(qo_modbus_reg_pack(&f, 123456.0, r), QO_OK);
    assert_int_equal(r[0], 0x2000);
    assert_int_equal(r[1], 0x47F1);
    assert_int_equal(qo_modbus_reg_unpack(&f, r, &back), QO_OK);
    assert_true(back == 123456.0);
    /* -1.5f = 0xBFC00000; 0 and -0 */
    f.order = QO_MODBUS_REG_HI_FIRST;
    assert_int_equal(qo_modbus_reg_pack(&f, -1.5, r), QO_OK);
    assert_int_equal(r[0], 0xBFC0);
    assert_int_equal(r[1], 0x0000);
    /* -0 + offset 0 is +0 in IEEE arithmetic: the register gets 0x0000, not 0x8000 */
    assert_int_equal(qo_modbus_reg_pack(&f, -0.0, r), QO_OK);
    assert_int_equal(r[0], 0x0000);
    /* saturation at FLT_MAX (0x7F7FFFFF) */
    assert_int_equal(qo_modbus_reg_pack(&f, 1e39, r), QO_E_OVERFLOW);
    assert_int_equal(r[0], 0x7F7F);
    assert_int_equal(r[1], 0xFFFF);
    assert_int_equal(qo_modbus_reg_pack(&f, -1e39, r), QO_E_OVERFLOW);
    assert_int_equal(r[0], 0xFF7F);
    /* a NaN bit pattern does not unpack */
    r[0] = 0x7FC0;
    r[1] = 0;
    assert_int_equal(qo_modbus_reg_unpack(&f, r, &back), QO_E_NONFINITE);
    assert_true(back == 0.0);
}

static void test_integer_edges(void **state)
{
    uint16_t r[2];
    qo_modbus_reg_format f;
    double raw;
    (void)state;
    f = plain(QO_MODBUS_REG_INT16);
    assert_int_equal(qo_modbus_reg_pack(&f, -1.0, r), QO_OK);
    assert_int_equal(r[0], 0xFFFF);
    assert_int_equal(qo_modbus_reg_pack(&f, 32767.0, r), QO_OK);
    assert_int_equal(r[0], 0x7FFF);
    assert_int_equal(qo_modbus_reg_pack(&f, 32767.6, r), QO_E_OVERFLOW); /* rounds to 32768 */
    assert_int_equal(r[0], 0x7FFF);
    assert_int_equal(qo_modbus_reg_pack(&f, -32768.0, r), QO_OK);
    assert_int_equal(r[0], 0x8000);
    assert_int_equal(qo_modbus_reg_pack(&f, -40000.0, r), QO_E_OVERFLOW);
    assert_int_equal(r[0], 0x8000);
    assert_int_equal(qo_modbus_reg_pack(&f, 2.5, r), QO_OK); /* ties away from zero */
    assert_int_equal(r[0], 3);
    assert_int_equal(qo_modbus_reg_pack(&f, -2.5, r), QO_OK);
    assert_int_equal(r[0], (uint16_t)-3);
    f.type = QO_MODBUS_REG_UINT16;
    assert_int_equal(qo_modbus_reg_pack(&f, -1.0, r), QO_E_OVERFLOW);
    assert_int_equal(r[0], 0);
    assert_int_equal(qo_modbus_reg_pack(&f, 65535.0, r), QO_OK);
    assert_int_equal(r[0], 0xFFFF);
    f = plain(QO_MODBUS_REG_INT32);
    assert_int_equal(qo_modbus_reg_pack(&f, -5.0, r), QO_OK); /* 0xFFFFFFFB */
    assert_int_equal(r[0], 0xFFFF);
    assert_int_equal(r[1], 0xFFFB);
    assert_int_equal(qo_modbus_reg_pack(&f, 3e9, r), QO_E_OVERFLOW);
    assert_int_equal(r[0], 0x7FFF);
    assert_int_equal(r[1], 0xFFFF);
    assert_int_equal(qo_modbus_reg_pack(&f, -3e9, r), QO_E_OVERFLOW);
    assert_int_equal(r[0], 0x8000);
    assert_int_equal(r[1], 0x0000);
    f.order = QO_MODBUS_REG_LO_FIRST; /* Delta ASDA example: 3000 -> 0x0BB8, 0x0000 */
    assert_int_equal(qo_modbus_reg_pack(&f, 3000.0, r), QO_OK);
    assert_int_equal(r[0], 0x0BB8);
    assert_int_equal(r[1], 0x0000);
    f = plain(QO_MODBUS_REG_UINT32);
    assert_int_equal(qo_modbus_reg_pack(&f, 4294967295.0, r), QO_OK);
    assert_int_equal(r[0], 0xFFFF);
    assert_int_equal(r[1], 0xFFFF);
    assert_int_equal(qo_modbus_reg_pack_raw(QO_MODBUS_REG_UINT32, QO_MODBUS_REG_HI_FIRST,
                                            4294967296.0, r, &raw),
                     QO_E_OVERFLOW);
    assert_true(raw == 4294967295.0);
}

static void test_scale_offset_invert(void **state)
{
    uint16_t r[2];
    double v;
    qo_modbus_reg_format f = fmt(QO_MODBUS_REG_INT32, QO_MODBUS_REG_HI_FIRST, 1000.0, 500.0, 1);
    (void)state;
    /* raw = 1000 * (-(1.25)) + 500 = -750 */
    assert_int_equal(qo_modbus_reg_pack(&f, 1.25, r), QO_OK);
    assert_int_equal((int32_t)(((uint32_t)r[0] << 16) | r[1]), -750);
    assert_int_equal(qo_modbus_reg_unpack(&f, r, &v), QO_OK);
    assert_true(fabs(v - 1.25) < 1e-12);
}

/* Random values in all types and orders against a reference written with integer maths. */
static void test_random_against_reference(void **state)
{
    int i;
    (void)state;
    for (i = 0; i < 20000; i++) {
        qo_modbus_reg_type t = (qo_modbus_reg_type)(next_u64() % 5);
        qo_modbus_reg_word_order o = (qo_modbus_reg_word_order)(next_u64() % 2);
        double scale = uniform(0.01, 5000.0) * ((next_u64() & 1) ? 1.0 : -1.0);
        double offset = uniform(-100.0, 100.0);
        int inv = (int)(next_u64() & 1);
        qo_modbus_reg_format f = fmt(t, o, scale, offset, inv);
        double lo, hi, value, ref, back;
        uint16_t r[2] = { 0, 0 };
        qo_status st;
        (void)qo_modbus_reg_type_range(t, &lo, &hi);
        value = uniform(-1e6, 1e6) / fabs(scale);
        ref = scale * (inv ? -value : value) + offset;
        st = qo_modbus_reg_pack(&f, value, r);
        if (t == QO_MODBUS_REG_FLOAT32) {
            float want = (float)ref;
            uint32_t bits, got;
            memcpy(&bits, &want, sizeof bits);
            got = o == QO_MODBUS_REG_HI_FIRST ? ((uint32_t)r[0] << 16 | r[1]) : ((uint32_t)r[1] << 16 | r[0]);
            if (st != QO_OK || got != bits)
                fail_msg("case %d float32 value %.17g: bits %08x want %08x st %d", i, value,
                         (unsigned)got, (unsigned)bits, st);
        } else {
            double want = round(ref);
            int64_t rawv;
            int sat = 0;
            if (want < lo) { want = lo; sat = 1; }
            if (want > hi) { want = hi; sat = 1; }
            if (t == QO_MODBUS_REG_INT16) rawv = (int16_t)r[0];
            else if (t == QO_MODBUS_REG_UINT16) rawv = r[0];
            else {
                uint32_t u = o == QO_MODBUS_REG_HI_FIRST ? ((uint32_t)r[0] << 16 | r[1])
                                                   : ((uint32_t)r[1] << 16 | r[0]);
                rawv = t == QO_MODBUS_REG_INT32 ? (int64_t)(int32_t)u : (int64_t)u;
            }
            if ((double)rawv != want || st != (sat ? QO_E_OVERFLOW : QO_OK))
                fail_msg("case %d type %d order %d scale %g offset %g inv %d value %.17g: raw %lld"
                         " want %.17g st %d", i, t, o, scale, offset, inv, value, (long long)rawv,
                         want, st);
            if (!sat) {
                /* Round trip within half a register unit. */
                assert_int_equal(qo_modbus_reg_unpack(&f, r, &back), QO_OK);
                if (fabs(back - value) > 0.5 / fabs(scale) * (1.0 + 1e-9))
                    fail_msg("case %d: round trip %.17g -> %.17g", i, value, back);
            }
        }
    }
}

static void test_bad_inputs(void **state)
{
    uint16_t r[2] = { 7, 7 };
    double v = 1.0, lo, hi;
    qo_modbus_reg_format f = plain(QO_MODBUS_REG_INT32);
    (void)state;
    assert_int_equal(qo_modbus_reg_pack(&f, NAN, r), QO_E_NONFINITE);
    assert_int_equal(r[0], 0);
    assert_int_equal(r[1], 0);
    assert_int_equal(qo_modbus_reg_pack(&f, INFINITY, r), QO_E_NONFINITE);
    assert_int_equal(qo_modbus_reg_pack(NULL, 1.0, r), QO_E_NULL);
    assert_int_equal(qo_modbus_reg_pack(&f, 1.0, NULL), QO_E_NULL);
    f.scale = 0.0;
    assert_int_equal(qo_modbus_reg_pack(&f, 1.0, r), QO_E_CONFIG);
    f.scale = NAN;
    assert_int_equal(qo_modbus_reg_unpack(&f, r, &v), QO_E_CONFIG);
    assert_true(v == 0.0);
    f.scale = 1e308;
    assert_int_equal(qo_modbus_reg_pack(&f, 1e308, r), QO_E_NONFINITE); /* raw overflows double */
    f.scale = 1.0;
    f.type = QO_MODBUS_REG_TYPE_COUNT_;
    assert_int_equal(qo_modbus_reg_pack(&f, 1.0, r), QO_E_ARG);
    assert_int_equal(qo_modbus_reg_type_width(QO_MODBUS_REG_TYPE_COUNT_), 0);
    assert_int_equal(qo_modbus_reg_type_range(QO_MODBUS_REG_TYPE_COUNT_, &lo, &hi), QO_E_ARG);
    f.type = QO_MODBUS_REG_INT16;
    f.order = (qo_modbus_reg_word_order)7;
    assert_int_equal(qo_modbus_reg_pack(&f, 1.0, r), QO_E_ARG);
    assert_int_equal(qo_modbus_reg_unpack_raw(QO_MODBUS_REG_INT16, QO_MODBUS_REG_HI_FIRST, NULL,
                                              &v),
                     QO_E_NULL);
    assert_int_equal(qo_modbus_reg_pack_raw(QO_MODBUS_REG_INT16, QO_MODBUS_REG_HI_FIRST, NAN, r,
                                            &v),
                     QO_E_NONFINITE);
    assert_true(v == 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_float32_bits_and_word_order),
        cmocka_unit_test(test_integer_edges),
        cmocka_unit_test(test_scale_offset_invert),
        cmocka_unit_test(test_random_against_reference),
        cmocka_unit_test(test_bad_inputs),
    };
    return cmocka_run_group_tests_name("modbus_reg", tests, NULL, NULL);
}
