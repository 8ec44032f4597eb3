/* The mock sink: records every successful tick in order, fails on the ticks it is told,
 * reports a full store and a wrong joint count, and keeps the common counters. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "mock/mock_sink.h"

#define NJ 3
#define MAXR 8

static void test_records_every_tick(void **state)
{
    float store[MAXR * NJ];
    uint64_t ticks[MAXR];
    qo_mock_sink m;
    qo_sink s;
    qo_sink_stats st;
    uint64_t t;
    (void)state;
    assert_int_equal(qo_mock_sink_open(&m, NJ, store, ticks, MAXR), QO_OK);
    assert_int_equal(qo_mock_sink_as_sink(&m, &s), QO_OK);
    for (t = 0; t < 5; t++) {
        float v[NJ];
        v[0] = (float)t;
        v[1] = -(float)t * 0.5f;
        v[2] = 100.0f + (float)t;
        assert_int_equal(qo_sink_write(&s, v, NJ, 10 + t), QO_OK);
    }
    assert_int_equal(m.count, 5);
    for (t = 0; t < 5; t++) {
        const float *r = qo_mock_sink_row(&m, (size_t)t);
        assert_non_null(r);
        if (r[0] != (float)t || r[1] != -(float)t * 0.5f || r[2] != 100.0f + (float)t ||
            ticks[t] != 10 + t)
            fail_msg("record %u: got %g %g %g tick %llu", (unsigned)t, (double)r[0],
                     (double)r[1], (double)r[2], (unsigned long long)ticks[t]);
    }
    assert_null(qo_mock_sink_row(&m, 5));
    assert_int_equal(qo_sink_get_stats(&s, &st), QO_OK);
    assert_int_equal(st.writes, 5);
    assert_int_equal(st.writes_ok, 5);
    assert_int_equal(st.writes_failed, 0);
    assert_int_equal(st.connected, 1);
    assert_int_equal(qo_sink_flush(&s), QO_OK);
    assert_int_equal(m.flushes, 1);
}

static void test_fail_ticks_and_errors(void **state)
{
    float store[MAXR * NJ];
    qo_mock_sink m;
    qo_sink s;
    qo_sink_stats st;
    static const uint64_t fails[] = { 2, 3 };
    float v[NJ] = { 1.0f, 2.0f, NAN };
    uint64_t t;
    (void)state;
    assert_int_equal(qo_mock_sink_open(&m, NJ, store, NULL, MAXR), QO_OK);
    assert_int_equal(qo_mock_sink_as_sink(&m, &s), QO_OK);
    assert_int_equal(qo_mock_sink_fail_on(&m, fails, 2, QO_E_TIMEOUT), QO_OK);
    for (t = 0; t < 5; t++) {
        qo_status want = (t == 2 || t == 3) ? QO_E_TIMEOUT : QO_OK;
        qo_status got = qo_sink_write(&s, v, NJ, t);
        if (got != want) fail_msg("tick %u: status %d, want %d", (unsigned)t, got, want);
    }
    assert_int_equal(m.count, 3);
    assert_true(isnan(qo_mock_sink_row(&m, 0)[2])); /* recorded as given */
    assert_int_equal(qo_sink_get_stats(&s, &st), QO_OK);
    assert_int_equal(st.writes_failed, 2);
    assert_int_equal(st.consecutive_failures, 0);
    /* QO_OK as fail status falls back to QO_E_IO, never "fails" with success */
    assert_int_equal(qo_mock_sink_fail_on(&m, fails, 1, QO_OK), QO_OK);
    assert_int_equal(qo_sink_write(&s, v, NJ, 2), QO_E_IO);
    assert_int_equal(qo_mock_sink_fail_on(&m, NULL, 0, QO_OK), QO_OK);
    assert_int_equal(qo_sink_write(&s, v, NJ, 2), QO_OK);
    assert_int_equal(qo_sink_write(&s, v, NJ - 1, 9), QO_E_RANGE);
    assert_int_equal(qo_sink_write(&s, NULL, NJ, 9), QO_E_NULL);
    assert_int_equal(qo_mock_sink_fail_on(&m, NULL, 3, QO_E_IO), QO_E_NULL);
    qo_sink_close(&s);
    qo_sink_close(&s); /* twice is harmless */
    assert_int_equal(qo_sink_write(&s, v, NJ, 10), QO_E_STATE);
    assert_int_equal(qo_sink_flush(&s), QO_E_STATE);
}

static void test_capacity_and_init_errors(void **state)
{
    float store[2 * NJ];
    qo_mock_sink m;
    qo_sink s;
    float v[NJ] = { 0.0f, 0.0f, 0.0f };
    (void)state;
    assert_int_equal(qo_mock_sink_open(&m, NJ, store, NULL, 2), QO_OK);
    assert_int_equal(qo_mock_sink_as_sink(&m, &s), QO_OK);
    assert_int_equal(qo_sink_write(&s, v, NJ, 0), QO_OK);
    assert_int_equal(qo_sink_write(&s, v, NJ, 1), QO_OK);
    assert_int_equal(qo_sink_write(&s, v, NJ, 2), QO_E_CAPACITY);
    assert_int_equal(m.dropped, 1);
    assert_int_equal(m.count, 2);
    qo_mock_sink_free(&m);
    assert_int_equal(qo_mock_sink_open(&m, 0, store, NULL, 2), QO_E_TOO_FEW);
    assert_int_equal(m.count, 0); /* zeroed */
    assert_int_equal(qo_mock_sink_write(&m, v, 0, 0), QO_E_STATE); /* not open */
    assert_int_equal(qo_mock_sink_open(&m, NJ, store, NULL, 0), QO_E_TOO_FEW);
    assert_int_equal(qo_mock_sink_write(&m, v, NJ, 0), QO_E_STATE);
    assert_int_equal(qo_mock_sink_open(&m, NJ, NULL, NULL, 2), QO_E_NULL);
    assert_int_equal(qo_mock_sink_open(NULL, NJ, store, NULL, 2), QO_E_NULL);
    /* open again on the same storage after close: a fresh recorder */
    assert_int_equal(qo_mock_sink_open(&m, NJ, store, NULL, 2), QO_OK);
    assert_int_equal(qo_mock_sink_write(&m, v, NJ, 7), QO_OK);
    assert_int_equal(m.count, 1);
    {
        qo_sink_stats st;
        qo_sink bare;
        memset(&bare, 0, sizeof bare);
        assert_int_equal(qo_sink_get_stats(&bare, &st), QO_E_STATE);
        assert_int_equal(qo_sink_get_stats(NULL, &st), QO_E_NULL);
        assert_int_equal(qo_sink_write(&bare, v, NJ, 0), QO_E_NULL);
        assert_int_equal(qo_sink_flush(&bare), QO_OK);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_records_every_tick),
        cmocka_unit_test(test_fail_ticks_and_errors),
        cmocka_unit_test(test_capacity_and_init_errors),
    };
    return cmocka_run_group_tests_name("mock_sink", tests, NULL, NULL);
}
