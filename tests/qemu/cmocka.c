/*
 * The cmocka shim for bare-metal Cortex-M (see tests/qemu/cmocka.h). Output goes through newlib's
 * semihosting stdio; everything is written to stdout and flushed per line so that messages and
 * results keep their order on the host (cmocka sends errors to stderr; the runner merges both).
 */
#include "cmocka.h"

#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* The one piece of mutable state a test runner needs: where a failing check jumps back to. */
static jmp_buf g_jump;
static int g_in_test;
static int g_skipped;
/* stdout's buffer: newlib would malloc 1 KB for it, a sixteenth of the microbit's RAM. */
static char g_outbuf[128];

static void vout(const char *format, va_list ap)
{
    vfprintf(stdout, format, ap);
    fflush(stdout);
}

void print_message(const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    vout(format, ap);
    va_end(ap);
}

void print_error(const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    vout(format, ap);
    va_end(ap);
}

void _fail(const char *file, int line)
{
    print_error("[   LINE   ] --- %s:%d: error: Failure!\n", file, line);
    if (g_in_test) longjmp(g_jump, 1);
    /* A check outside a test (in a group fixture): nothing to jump back to, end the run. */
    print_error("[  ERROR   ] --- check failed outside a test\n");
    fflush(stdout);
    exit(1);
}

void _skip(const char *file, int line)
{
    (void)file;
    (void)line;
    g_skipped = 1;
    if (g_in_test) longjmp(g_jump, 1);
    exit(1);
}

void _assert_true(LargestIntegralType result, const char *expression, const char *file, int line)
{
    if (!result) {
        print_error("[  ERROR   ] --- %s\n", expression);
        _fail(file, line);
    }
}

void _assert_return_code(LargestIntegralType result, size_t rlen, LargestIntegralType error,
                         const char *expression, const char *file, int line)
{
    /* The value is negative if its sign bit (at its own width) is set. */
    LargestIntegralType sign = (LargestIntegralType)1 << (rlen * 8u - 1u);
    if (result & sign) {
        print_error("[  ERROR   ] --- %s < 0, errno(%llu)\n", expression, (unsigned long long)error);
        _fail(file, line);
    }
}

void _assert_int_equal(LargestIntegralType a, LargestIntegralType b, const char *file, int line)
{
    if (a != b) {
        print_error("[  ERROR   ] --- %lld != %lld (%#llx != %#llx)\n", (long long)a, (long long)b,
                    (unsigned long long)a, (unsigned long long)b);
        _fail(file, line);
    }
}

void _assert_int_not_equal(LargestIntegralType a, LargestIntegralType b, const char *file, int line)
{
    if (a == b) {
        print_error("[  ERROR   ] --- %lld == %lld (%#llx)\n", (long long)a, (long long)b,
                    (unsigned long long)a);
        _fail(file, line);
    }
}

/* cmocka's rule: equal if |a - b| <= epsilon, or if |a - b| is within FLT_EPSILON of the larger
 * magnitude (so large values compare relatively). */
static int float_close(float a, float b, float epsilon)
{
    float diff = a - b;
    float aa = a < 0.0f ? -a : a;
    float ab = b < 0.0f ? -b : b;
    float largest = ab > aa ? ab : aa;
    diff = diff >= 0.0f ? diff : -diff;
    if (diff <= epsilon) return 1;
    return diff <= largest * FLT_EPSILON;
}

void _assert_float_equal(float a, float b, float epsilon, const char *file, int line)
{
    if (!float_close(a, b, epsilon)) {
        print_error("[  ERROR   ] --- %.9g != %.9g (epsilon %.3g)\n", (double)a, (double)b,
                    (double)epsilon);
        _fail(file, line);
    }
}

void _assert_float_not_equal(float a, float b, float epsilon, const char *file, int line)
{
    if (float_close(a, b, epsilon)) {
        print_error("[  ERROR   ] --- %.9g == %.9g (epsilon %.3g)\n", (double)a, (double)b,
                    (double)epsilon);
        _fail(file, line);
    }
}

void _assert_string_equal(const char *a, const char *b, const char *file, int line)
{
    if (a == NULL || b == NULL ? a != b : strcmp(a, b) != 0) {
        print_error("[  ERROR   ] --- \"%s\" != \"%s\"\n", a ? a : "(null)", b ? b : "(null)");
        _fail(file, line);
    }
}

void _assert_string_not_equal(const char *a, const char *b, const char *file, int line)
{
    if (a == NULL || b == NULL ? a == b : strcmp(a, b) == 0) {
        print_error("[  ERROR   ] --- \"%s\" == \"%s\"\n", a ? a : "(null)", b ? b : "(null)");
        _fail(file, line);
    }
}

void _assert_memory_equal(const void *a, const void *b, size_t size, const char *file, int line)
{
    const unsigned char *pa = a;
    const unsigned char *pb = b;
    size_t i;
    for (i = 0; i < size; i++) {
        if (pa[i] != pb[i]) {
            print_error("[  ERROR   ] --- byte %u of %u differs: 0x%02x != 0x%02x\n", (unsigned)i,
                        (unsigned)size, pa[i], pb[i]);
            _fail(file, line);
        }
    }
}

void _assert_memory_not_equal(const void *a, const void *b, size_t size, const char *file, int line)
{
    if (size == 0 || memcmp(a, b, size) == 0) {
        print_error("[  ERROR   ] --- %u bytes are equal\n", (unsigned)size);
        _fail(file, line);
    }
}

void _assert_in_range(LargestIntegralType value, LargestIntegralType minimum,
                      LargestIntegralType maximum, const char *file, int line)
{
    if (value < minimum || value > maximum) {
        print_error("[  ERROR   ] --- %llu is not within the range [%llu, %llu]\n",
                    (unsigned long long)value, (unsigned long long)minimum,
                    (unsigned long long)maximum);
        _fail(file, line);
    }
}

void _assert_not_in_range(LargestIntegralType value, LargestIntegralType minimum,
                          LargestIntegralType maximum, const char *file, int line)
{
    if (value >= minimum && value <= maximum) {
        print_error("[  ERROR   ] --- %llu is within the range [%llu, %llu]\n",
                    (unsigned long long)value, (unsigned long long)minimum,
                    (unsigned long long)maximum);
        _fail(file, line);
    }
}

enum { R_PASS, R_FAIL, R_SKIP };

/* Runs one test with its fixtures; a check that fails longjmp()s back here. */
static int run_one(const struct CMUnitTest *t, void *group_state)
{
    void *volatile state = t->initial_state ? t->initial_state : group_state;
    volatile int result = R_PASS;

    g_skipped = 0;
    g_in_test = 1;
    if (setjmp(g_jump) == 0) {
        void *s = state;
        if (t->setup_func && t->setup_func(&s) != 0) {
            print_error("[  ERROR   ] --- test setup failed\n");
            result = R_FAIL;
        } else {
            t->test_func(&s);
        }
        state = s;
    } else {
        result = g_skipped ? R_SKIP : R_FAIL;
    }
    if (t->teardown_func && result != R_FAIL) {
        if (setjmp(g_jump) == 0) {
            void *s = state;
            if (t->teardown_func(&s) != 0) {
                print_error("[  ERROR   ] --- test teardown failed\n");
                result = R_FAIL;
            }
        } else {
            result = R_FAIL;
        }
    }
    g_in_test = 0;
    return result;
}

static const char *g_filter;

void cmocka_set_test_filter(const char *pattern) { g_filter = pattern; }

/* glob match of s against p: * any run (also empty), ? one character; bounded by the lengths */
static int glob_match(const char *p, const char *s)
{
    const char *star = NULL, *resume = NULL;
    while (*s) {
        if (*p == '?' || *p == *s) { p++; s++; }
        else if (*p == '*') { star = p++; resume = s; }
        else if (star) { p = star + 1; s = ++resume; }
        else return 0;
    }
    while (*p == '*') p++;
    return *p == '\0';
}

int _cmocka_run_group_tests(const char *group_name, const struct CMUnitTest *tests, size_t count,
                            CMFixtureFunction group_setup, CMFixtureFunction group_teardown)
{
    void *group_state = NULL;
    unsigned passed = 0, failed = 0, skipped = 0, run = 0;
    size_t i;

    setvbuf(stdout, g_outbuf, _IOLBF, sizeof g_outbuf);
    print_message("[==========] %s: Running %u test(s).\n", group_name, (unsigned)count);
    if (group_setup && group_setup(&group_state) != 0) {
        print_error("[  ERROR   ] --- group setup failed\n");
        print_error("[  FAILED  ] %u test(s), listed below:\n", (unsigned)count);
        return (int)count;
    }
    for (i = 0; i < count; i++) {
        const struct CMUnitTest *t = &tests[i];
        int r;
        clock_t t0, dt;
        if (t->test_func == NULL || (g_filter && !glob_match(g_filter, t->name))) continue;
        print_message("[ RUN      ] %s\n", t->name);
        t0 = clock();
        r = run_one(t, group_state);
        dt = clock() - t0;
        run++;
        if (r == R_PASS) {
            passed++;
            print_message("[       OK ] %s\n", t->name);
        } else if (r == R_SKIP) {
            skipped++;
            print_message("[  SKIPPED ] %s\n", t->name);
        } else {
            failed++;
            print_message("[  FAILED  ] %s\n", t->name);
        }
        /* Not in cmocka: which tests are slow on an emulated core. clock() is semihosting
         * SYS_CLOCK, which QEMU answers with its own host CPU time: a busy host does not inflate it. */
        if (dt >= CLOCKS_PER_SEC)
            print_message("[   TIME   ] %s: %.1f s\n", t->name, (double)dt / (double)CLOCKS_PER_SEC);
    }
    if (group_teardown && group_teardown(&group_state) != 0) {
        print_error("[  ERROR   ] --- group teardown failed\n");
        failed++;
    }
    print_message("[==========] %s: %u test(s) run.\n", group_name, run);
    print_error("[  PASSED  ] %u test(s).\n", passed);
    /* The per-test lines above name the skipped and failed tests. */
    if (skipped) print_error("[  SKIPPED ] %u test(s).\n", skipped);
    if (failed) {
        print_error("[  FAILED  ] %u test(s), listed below:\n", failed);
        print_error("\n %u FAILED TEST(S)\n", failed);
    }
    return (int)failed;
}
