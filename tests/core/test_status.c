/* qo_status_str: every code has its own non-empty text; unknown values are safe. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "qorient/status.h"

static void test_every_status_has_distinct_text(void **state)
{
    int i, j;
    (void)state;
    assert_string_equal(qo_status_str(QO_OK), "ok");
    for (i = 0; i < (int)QO_STATUS_COUNT_; i++) {
        const char *a = qo_status_str((qo_status)i);
        assert_non_null(a);
        assert_true(strlen(a) > 0);
        assert_string_not_equal(a, "unknown status");
        for (j = 0; j < i; j++) assert_string_not_equal(a, qo_status_str((qo_status)j));
    }
}

static void test_unknown_status_is_safe(void **state)
{
    (void)state;
    assert_string_equal(qo_status_str(QO_STATUS_COUNT_), "unknown status");
    assert_string_equal(qo_status_str((qo_status)-1), "unknown status");
    assert_string_equal(qo_status_str((qo_status)1000), "unknown status");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_status_has_distinct_text),
        cmocka_unit_test(test_unknown_status_is_safe),
    };
    return cmocka_run_group_tests_name("status", tests, NULL, NULL);
}
