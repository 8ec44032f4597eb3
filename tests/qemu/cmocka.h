/*
 * tests/qemu/cmocka.h - a small cmocka-compatible shim for bare-metal Cortex-M under QEMU.
 *
 * There is no cmocka for arm-none-eabi. The core's test programs (tests/core/test_*.c) are built
 * unmodified against this header (it is found first through -isystem tests/qemu) and run on
 * emulated Cortex-M0 / M4F / M7 cores with newlib's semihosting stdio. It provides exactly the
 * part of cmocka's API that the tests use, with cmocka's semantics:
 *
 *   CMUnitTest, CMFixtureFunction, cmocka_unit_test(_setup|_teardown|_setup_teardown|_prestate)
 *   cmocka_run_group_tests, cmocka_run_group_tests_name   (return the number of failed tests)
 *   assert_true / false, assert_int_equal / not_equal, assert_ptr_equal / not_equal,
 *   assert_null / non_null, assert_string_equal / not_equal, assert_float_equal / not_equal,
 *   assert_in_range / not_in_range, assert_memory_equal / not_equal, assert_return_code
 *   fail, fail_msg, skip, print_error, print_message, cmocka_set_test_filter (glob: * and ?)
 *
 * Not provided (no test uses them): mocks (will_return, expect_*), test_malloc leak checks.
 * A failing assert prints the check and its file:line, then longjmp()s out of the test (newlib
 * setjmp), exactly as cmocka does; the run ends with cmocka's summary lines
 * "[  PASSED  ] N test(s)." and "[  FAILED  ] M test(s), listed below:", which tests/run.sh and
 * tools/test-qemu.sh parse. A crash (HardFault) ends QEMU with status 1 through the fault
 * handler of tests/qemu/startup.c.
 *
 * Like the real header, this one expects <stdarg.h>, <stddef.h>, <stdint.h> and <setjmp.h> to be
 * included first; it includes them itself as well so it also works alone.
 */
#ifndef QORIENT_TESTS_QEMU_CMOCKA_H
#define QORIENT_TESTS_QEMU_CMOCKA_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

/* cmocka's widest integer: every integer check is done in it (as cmocka does). */
typedef uintmax_t LargestIntegralType;

#define cast_to_largest_integral_type(value) ((LargestIntegralType)(value))
#define cast_ptr_to_largest_integral_type(value) ((LargestIntegralType)(uintptr_t)(value))

typedef void (*CMUnitTestFunction)(void **state);
typedef int (*CMFixtureFunction)(void **state);

struct CMUnitTest {
    const char *name;
    CMUnitTestFunction test_func;
    CMFixtureFunction setup_func;
    CMFixtureFunction teardown_func;
    void *initial_state;
};

#define cmocka_unit_test(f) { #f, f, NULL, NULL, NULL }
#define cmocka_unit_test_setup(f, setup) { #f, f, setup, NULL, NULL }
#define cmocka_unit_test_teardown(f, teardown) { #f, f, NULL, teardown, NULL }
#define cmocka_unit_test_setup_teardown(f, setup, teardown) { #f, f, setup, teardown, NULL }
#define cmocka_unit_test_prestate(f, state) { #f, f, NULL, NULL, state }

#define cmocka_run_group_tests(group_tests, group_setup, group_teardown) \
    _cmocka_run_group_tests(#group_tests, group_tests, sizeof(group_tests) / sizeof((group_tests)[0]), \
                            group_setup, group_teardown)
#define cmocka_run_group_tests_name(group_name, group_tests, group_setup, group_teardown) \
    _cmocka_run_group_tests(group_name, group_tests, sizeof(group_tests) / sizeof((group_tests)[0]), \
                            group_setup, group_teardown)

#define assert_true(c) _assert_true(cast_to_largest_integral_type(c), #c, __FILE__, __LINE__)
#define assert_false(c) _assert_true(!(cast_to_largest_integral_type(c)), #c, __FILE__, __LINE__)
#define assert_return_code(rc, error) \
    _assert_return_code(cast_to_largest_integral_type(rc), sizeof(rc), \
                        cast_to_largest_integral_type(error), #rc, __FILE__, __LINE__)
#define assert_non_null(c) _assert_true(cast_ptr_to_largest_integral_type(c), #c, __FILE__, __LINE__)
#define assert_null(c) _assert_true(!(cast_ptr_to_largest_integral_type(c)), #c, __FILE__, __LINE__)
#define assert_ptr_equal(a, b) \
    _assert_int_equal(cast_ptr_to_largest_integral_type(a), cast_ptr_to_largest_integral_type(b), \
                      __FILE__, __LINE__)
#define assert_ptr_not_equal(a, b) \
    _assert_int_not_equal(cast_ptr_to_largest_integral_type(a), cast_ptr_to_largest_integral_type(b), \
                          __FILE__, __LINE__)
#define assert_int_equal(a, b) \
    _assert_int_equal(cast_to_largest_integral_type(a), cast_to_largest_integral_type(b), \
                      __FILE__, __LINE__)
#define assert_int_not_equal(a, b) \
    _assert_int_not_equal(cast_to_largest_integral_type(a), cast_to_largest_integral_type(b), \
                          __FILE__, __LINE__)
#define assert_float_equal(a, b, epsilon) \
    _assert_float_equal((float)a, (float)b, (float)epsilon, __FILE__, __LINE__)
#define assert_float_not_equal(a, b, epsilon) \
    _assert_float_not_equal((float)a, (float)b, (float)epsilon, __FILE__, __LINE__)
#define assert_string_equal(a, b) \
    _assert_string_equal((const char *)(a), (const char *)(b), __FILE__, __LINE__)
#define assert_string_not_equal(a, b) \
    _assert_string_not_equal((const char *)(a), (const char *)(b), __FILE__, __LINE__)
#define assert_memory_equal(a, b, size) \
    _assert_memory_equal((const void *)(a), (const void *)(b), size, __FILE__, __LINE__)
#define assert_memory_not_equal(a, b, size) \
    _assert_memory_not_equal((const void *)(a), (const void *)(b), size, __FILE__, __LINE__)
#define assert_in_range(value, minimum, maximum) \
    _assert_in_range(cast_to_largest_integral_type(value), cast_to_largest_integral_type(minimum), \
                     cast_to_largest_integral_type(maximum), __FILE__, __LINE__)
#define assert_not_in_range(value, minimum, maximum) \
    _assert_not_in_range(cast_to_largest_integral_type(value), cast_to_largest_integral_type(minimum), \
                         cast_to_largest_integral_type(maximum), __FILE__, __LINE__)

#define fail() _fail(__FILE__, __LINE__)
#define skip() _skip(__FILE__, __LINE__)
/* As in cmocka (a GNU ## extension, tolerated because this header is included as a system one). */
#define fail_msg(msg, ...) do { \
        print_error("ERROR: " msg "\n", ##__VA_ARGS__); \
        fail(); \
    } while (0)

void print_message(const char *format, ...) __attribute__((format(printf, 1, 2)));
void print_error(const char *format, ...) __attribute__((format(printf, 1, 2)));

int _cmocka_run_group_tests(const char *group_name, const struct CMUnitTest *tests, size_t count,
                            CMFixtureFunction group_setup, CMFixtureFunction group_teardown);

/* Runs only the tests whose name matches pattern (* any run, ? one character), as cmocka. */
void cmocka_set_test_filter(const char *pattern);

void _assert_true(LargestIntegralType result, const char *expression, const char *file, int line);
void _assert_return_code(LargestIntegralType result, size_t rlen, LargestIntegralType error,
                         const char *expression, const char *file, int line);
void _assert_int_equal(LargestIntegralType a, LargestIntegralType b, const char *file, int line);
void _assert_int_not_equal(LargestIntegralType a, LargestIntegralType b, const char *file, int line);
void _assert_float_equal(float a, float b, float epsilon, const char *file, int line);
void _assert_float_not_equal(float a, float b, float epsilon, const char *file, int line);
void _assert_string_equal(const char *a, const char *b, const char *file, int line);
void _assert_string_not_equal(const char *a, const char *b, const char *file, int line);
void _assert_memory_equal(const void *a, const void *b, size_t size, const char *file, int line);
void _assert_memory_not_equal(const void *a, const void *b, size_t size, const char *file, int line);
void _assert_in_range(LargestIntegralType value, LargestIntegralType minimum,
                      LargestIntegralType maximum, const char *file, int line);
void _assert_not_in_range(LargestIntegralType value, LargestIntegralType minimum,
                          LargestIntegralType maximum, const char *file, int line);
void _fail(const char *file, int line) __attribute__((noreturn));
void _skip(const char *file, int line) __attribute__((noreturn));

#endif /* QORIENT_TESTS_QEMU_CMOCKA_H */
