/*
 * Self-test of the bare-metal cmocka shim (tests/qemu/cmocka.h), run first on every Cortex-M
 * target by tests/qemu/run-target.sh: every check must pass on good input and fail (ending only
 * its own test) on bad input, skip() must skip, and fixtures must run. The runner expects exactly
 * SELFTEST_PASS passed, SELFTEST_FAIL failed and SELFTEST_SKIP skipped; anything else means the
 * shim would misreport the real tests.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#define SELFTEST_PASS 4
#define SELFTEST_FAIL 13
#define SELFTEST_SKIP 1

static volatile int g_after; /* set if a test went on after a failing check */
static int g_fixture = 0x1234;

static void good_checks(void **state)
{
    static const unsigned char a[4] = { 1, 2, 3, 4 };
    static const unsigned char b[4] = { 1, 2, 3, 5 };
    int x = 0;
    (void)state;
    assert_true(1);
    assert_false(0);
    assert_int_equal(-1, -1);
    assert_int_equal(UINT64_MAX, UINT64_MAX);
    assert_int_not_equal(1, 2);
    assert_ptr_equal(&x, &x);
    assert_ptr_not_equal(&x, NULL);
    assert_non_null(&x);
    assert_null(NULL);
    assert_string_equal("abc", "abc");
    assert_string_not_equal("abc", "abd");
    assert_float_equal(1.0f, 1.0f + 1e-7f, 1e-6f);
    assert_float_equal(1e30f, nextafterf(1e30f, 2e30f), 0.0f); /* relative rule, as cmocka */
    assert_float_not_equal(1.0f, 1.1f, 1e-3f);
    assert_memory_equal(a, a, sizeof a);
    assert_memory_not_equal(a, b, sizeof b);
    assert_in_range(5, 1, 10);
    assert_not_in_range(11, 1, 10);
    assert_return_code(0, 0);
    print_message("good checks: %d %s %.3f\n", 42, "text", 0.5);
}

static int setup_state(void **state)
{
    *state = &g_fixture;
    return 0;
}

static int teardown_state(void **state)
{
    return *state == &g_fixture ? 0 : -1;
}

static void uses_fixture(void **state)
{
    assert_ptr_equal(*state, &g_fixture);
    assert_int_equal(*(int *)*state, 0x1234);
}

static int setup_fails(void **state)
{
    (void)state;
    return -1;
}

static void not_run(void **state)
{
    (void)state;
    g_after = 1;
}

/* Each runs one failing check; g_after proves the test stopped at it. */
#define BAD(name, check) static void name(void **state) { (void)state; check; g_after = 1; }
BAD(bad_true, assert_true(0))
BAD(bad_false, assert_false(1))
BAD(bad_int, assert_int_equal(1, 2))
BAD(bad_int_ne, assert_int_not_equal(-3, -3))
BAD(bad_null, assert_null((void *)&g_fixture))
BAD(bad_string, assert_string_equal("abc", "abd"))
BAD(bad_float, assert_float_equal(1.0f, 1.001f, 1e-6f))
BAD(bad_memory, assert_memory_equal("abcd", "abce", 4))
BAD(bad_range, assert_in_range(11, 1, 10))
BAD(bad_fail, fail())
BAD(bad_fail_msg, fail_msg("expected failure %d", 7))
BAD(bad_return_code, assert_return_code(-1, 0))

static void skipped(void **state)
{
    (void)state;
    skip();
    g_after = 1;
}

static void nothing_ran_after_a_failure(void **state)
{
    (void)state;
    assert_int_equal(g_after, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(good_checks),
        cmocka_unit_test_setup_teardown(uses_fixture, setup_state, teardown_state),
        cmocka_unit_test_prestate(uses_fixture, &g_fixture),
        cmocka_unit_test_setup(not_run, setup_fails),
        cmocka_unit_test(bad_true),
        cmocka_unit_test(bad_false),
        cmocka_unit_test(bad_int),
        cmocka_unit_test(bad_int_ne),
        cmocka_unit_test(bad_null),
        cmocka_unit_test(bad_string),
        cmocka_unit_test(bad_float),
        cmocka_unit_test(bad_memory),
        cmocka_unit_test(bad_range),
        cmocka_unit_test(bad_fail),
        cmocka_unit_test(bad_fail_msg),
        cmocka_unit_test(bad_return_code),
        cmocka_unit_test(skipped),
        cmocka_unit_test(nothing_ran_after_a_failure),
    };
    int failed = cmocka_run_group_tests_name("shim self-test", tests, NULL, NULL);
    print_message("selftest expects %d passed, %d failed, %d skipped\n", SELFTEST_PASS,
                  SELFTEST_FAIL, SELFTEST_SKIP);
    return failed == SELFTEST_FAIL ? 0 : 1;
}
