/* The INI register map: every key parsed, defaults, the worked example files, and every
 * kind of error reported with the right file and line. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "linux/regmap.h"

static qo_regmap map; /* ~20 KiB: not on the test's stack */

static const char *good =
    "# a comment\n"
    "[slave.3]\n"
    "max_registers = 10\n"
    "gap_us = 1500\n"
    "init = 0x6200=1, 0x0405=0x1 16=-1\n"
    "disable = 0x6002=0x40\n"
    "constant = 0x6203=600 ; inline comment\n"
    "\n"
    "[joint.a]\n"
    "slave = 3\n"
    "address = 0x6201\n"
    "type = int32\n"
    "order = lo-first\n"
    "scale = 1591.5\n"
    "offset = -7\n"
    "invert = yes\n"
    "min = -1.5\n"
    "max = 2.5\n"
    "max_step = 0.02\n"
    "feedback = 0x602A\n"
    "[joint.b]\n"
    "slave = 9\n"
    "address = 010\n"
    "type = float32\n";

static void test_parse_good(void **state)
{
    char err[256];
    const qo_regmap_joint *a, *b;
    const qo_regmap_slave *s3, *s9;
    (void)state;
    assert_int_equal(qo_regmap_parse(good, "good.ini", &map, err, sizeof err), QO_OK);
    assert_string_equal(err, "");
    assert_int_equal(map.n_joints, 2);
    a = &map.joints[0];
    b = &map.joints[1];
    assert_string_equal(a->name, "a");
    assert_int_equal(a->slave, 3);
    assert_int_equal(a->address, 0x6201);
    assert_int_equal(a->fmt.type, QO_MODBUS_REG_INT32);
    assert_int_equal(a->fmt.order, QO_MODBUS_REG_LO_FIRST);
    assert_true(a->fmt.scale == 1591.5 && a->fmt.offset == -7.0 && a->fmt.invert == 1);
    assert_true(a->min == -1.5 && a->max == 2.5 && a->max_step == 0.02);
    assert_true(a->has_feedback && a->feedback == 0x602A);
    assert_int_equal(a->line, 9);
    /* defaults; "010" is decimal ten, not octal */
    assert_string_equal(b->name, "b");
    assert_int_equal(b->address, 10);
    assert_int_equal(b->fmt.type, QO_MODBUS_REG_FLOAT32);
    assert_int_equal(b->fmt.order, QO_MODBUS_REG_HI_FIRST);
    assert_true(b->fmt.scale == 1.0 && b->fmt.offset == 0.0 && b->fmt.invert == 0);
    assert_true(isinf(b->min) && b->min < 0 && isinf(b->max) && b->max > 0);
    assert_true(b->max_step == 0.0 && !b->has_feedback);
    assert_int_equal(map.n_slaves, 2);
    s3 = qo_regmap_find_slave(&map, 3);
    s9 = qo_regmap_find_slave(&map, 9); /* implicit, defaults */
    assert_non_null(s3);
    assert_non_null(s9);
    assert_null(qo_regmap_find_slave(&map, 4));
    assert_int_equal(s3->max_registers, 10);
    assert_int_equal(s3->gap_us, 1500);
    assert_int_equal(s3->n_init, 3);
    assert_int_equal(s3->init[0].address, 0x6200);
    assert_int_equal(s3->init[0].value, 1);
    assert_int_equal(s3->init[1].address, 0x0405);
    assert_int_equal(s3->init[2].address, 16);
    assert_int_equal(s3->init[2].value, 0xFFFF);
    assert_int_equal(s3->n_disable, 1);
    assert_int_equal(s3->disable[0].value, 0x40);
    assert_int_equal(s3->n_constant, 1);
    assert_int_equal(s3->constant[0].address, 0x6203);
    assert_int_equal(s3->constant[0].value, 600);
    assert_int_equal(s9->max_registers, 123);
    assert_int_equal(s9->line, 0);
}

/* A map the parser must refuse with status want: the message must start "bad.ini:LINE: " and
 * contain word, and no joint may be left in the map. */
static void expect_refused(const char *text, qo_status want, int line, const char *word)
{
    char err[256], prefix[32];
    qo_status st = qo_regmap_parse(text, "bad.ini", &map, err, sizeof err);
    (void)snprintf(prefix, sizeof prefix, "bad.ini:%d: ", line);
    if (st != want || strncmp(err, prefix, strlen(prefix)) != 0 || strstr(err, word) == NULL ||
        map.n_joints != 0)
        fail_msg("status %d (want %d), message \"%s\" (want prefix \"%s\" and \"%s\") for:\n%s",
                 st, want, err, prefix, word, text);
}

/* Each case states its text, the line the message must name and a word it must contain. */
struct bad_case {
    const char *text;
    int line;
    const char *word;
};

#define J "[joint.x]\nslave = 1\naddress = 0\ntype = int16\n"

static void test_errors_name_file_and_line(void **state)
{
    static const struct bad_case cases[] = {
        { J "colour = red\n", 5, "colour" },
        { J "[motor.1]\n", 5, "unknown section" },
        { J "slave = 2\n", 5, "duplicate key" },
        { J J, 5, "duplicate section" },
        { J "[slave.1]\n[slave.1]\n", 6, "duplicate section" },
        { "[joint.x]\nslave = 1\naddress = 0\ntype = int8\n", 4, "type" },
        { "[joint.x]\nslave = 0\n", 2, "slave" },
        { "[joint.x]\nslave = 1\naddress = 0x1G\n", 3, "address" },
        { "[joint.x]\nslave = 1\naddress = 65536\n", 3, "address" },
        { J "scale = 0\n", 5, "scale" },
        { J "scale = nan\n", 5, "scale" },
        { J "max_step = -1\n", 5, "max_step" },
        { J "invert = maybe\n", 5, "invert" },
        { J "order = middle\n", 5, "order" },
        { J "min = 2\nmax = 1\n", 1, "min > max" },
        { "\n\n[joint.x]\nslave = 1\ntype = int16\n", 3, "address" },
        { "[joint.x]\n", 1, "slave" },
        { "[joint.x]\nslave = 1\naddress = 65535\ntype = int32\n", 1, "65535" },
        { J "[joint.y]\nslave = 1\naddress = 0\ntype = int16\n", 5, "overlaps" },
        { J "[slave.1]\nconstant = 0=5\n", 5, "overlaps" },
        { J "feedback = 0\n", 1, "overlaps" },
        { J "[slave.1]\ninit = 5\n", 6, "init" },
        { J "[slave.1]\ninit = 5=70000\n", 6, "init" },
        { J "[slave.1]\nmax_registers = 124\n", 6, "max_registers" },
        { J "[slave.1]\nwhat = 1\n", 6, "what" },
        { J "[slave.256]\n", 5, "slave id" },
        { "slave = 1\n" J, 1, "outside" },
        { J "this line has no equals sign\n", 5, "syntax" },
        { "# nothing\n", 0, "no [joint" },
    };
    size_t i;
    (void)state;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++)
        expect_refused(cases[i].text, QO_E_CONFIG, cases[i].line, cases[i].word);
    expect_refused(J "[slave.1]\ninit = 1=1 2=2 3=3 4=4 5=5 6=6 7=7 8=8 9=9 10=10 11=11 12=12 "
                   "13=13 14=14 15=15 16=16 17=17\n", QO_E_CAPACITY, 6, "entries");
}

/* A map of n uint16 joints j0, j1, ... on slave 1 at addresses 0, 1, ... */
static const char *joints_text(size_t n)
{
    static char text[QO_REGMAP_MAX_JOINTS * 80 + 200];
    size_t i, len = 0;
    text[0] = '\0';
    for (i = 0; i < n; i++)
        len += (size_t)snprintf(text + len, sizeof text - len,
                                "[joint.j%u]\nslave = 1\naddress = %u\ntype = uint16\n",
                                (unsigned)i, (unsigned)i);
    return text;
}

static void test_capacity_of_joints(void **state)
{
    char err[256];
    (void)state;
    assert_int_equal(qo_regmap_parse(joints_text(QO_REGMAP_MAX_JOINTS + 1), "many.ini", &map, err,
                                     sizeof err), QO_E_CAPACITY);
    assert_non_null(strstr(err, "many.ini:"));
    /* exactly the capacity is fine */
    assert_int_equal(qo_regmap_parse(joints_text(QO_REGMAP_MAX_JOINTS), "many.ini", &map, err,
                                     sizeof err), QO_OK);
    assert_int_equal(map.n_joints, QO_REGMAP_MAX_JOINTS);
}

/* Writes `len` bytes to a file and loads it. */
static qo_status load_bytes(const char *bytes, size_t len, char *err, size_t err_len)
{
    FILE *f = fopen("build/test_regmap_bytes.ini", "wb");
    qo_status st;
    assert_non_null(f);
    assert_int_equal(fwrite(bytes, 1, len, f), len);
    fclose(f);
    st = qo_regmap_load("build/test_regmap_bytes.ini", &map, err, err_len);
    remove("build/test_regmap_bytes.ini");
    return st;
}

static void test_example_files(void **state)
{
    static const char bad[] = "[joint.a]\nslave = 1\naddress = 0\ntype = int16\n\nbogus = 1\n";
    char err[256];
    size_t i;
    (void)state;
    assert_int_equal(qo_regmap_load("examples/maps/six_int32.ini", &map, err, sizeof err), QO_OK);
    assert_int_equal(map.n_joints, 6);
    for (i = 0; i < 6; i++) {
        assert_int_equal(map.joints[i].address, 2 * i);
        assert_int_equal(map.joints[i].fmt.type, QO_MODBUS_REG_INT32);
        assert_true(map.joints[i].has_feedback);
    }
    assert_int_equal(qo_regmap_load("examples/maps/leadshine_cs2rs_pr.ini", &map, err, sizeof err),
                     QO_OK);
    assert_int_equal(map.n_joints, 2);
    assert_int_equal(map.n_slaves, 2);
    assert_int_equal(map.slaves[0].n_constant, 6);
    assert_true(map.joints[1].fmt.invert);
    assert_int_equal(qo_regmap_load("examples/maps/no-such-file.ini", &map, err, sizeof err),
                     QO_E_IO);
    assert_non_null(strstr(err, "no-such-file.ini:0: cannot open"));
    /* a file with an error names the file and line */
    assert_int_equal(load_bytes(bad, sizeof bad - 1, err, sizeof err), QO_E_CONFIG);
    assert_non_null(strstr(err, "build/test_regmap_bytes.ini:6: "));
}

/* A list too long for one line continues on indented lines; an over-long line is an error
 * on its own line (inih would otherwise read its tail as a bogus key). */
static void test_long_lists(void **state)
{
    static char text[2048];
    char err[256];
    size_t len = 0, i;
    const qo_regmap_slave *sl;
    (void)state;
    len += (size_t)snprintf(text + len, sizeof text - len, "[slave.1]\nconstant = ");
    for (i = 0; i < 8; i++)
        len += (size_t)snprintf(text + len, sizeof text - len, "0x%04X=%u, ", (unsigned)(0x100 + i),
                                (unsigned)i);
    len += (size_t)snprintf(text + len, sizeof text - len, "\n    ; a comment between\n    ");
    for (i = 8; i < 16; i++)
        len += (size_t)snprintf(text + len, sizeof text - len, "0x%04X=%u ", (unsigned)(0x100 + i),
                                (unsigned)i);
    len += (size_t)snprintf(text + len, sizeof text - len,
                            "\n[joint.a]\nslave = 1\naddress = 0\ntype = int16\n");
    assert_int_equal(qo_regmap_parse(text, "long.ini", &map, err, sizeof err), QO_OK);
    sl = qo_regmap_find_slave(&map, 1);
    assert_non_null(sl);
    assert_int_equal(sl->n_constant, 16);
    for (i = 0; i < 16; i++) {
        assert_int_equal(sl->constant[i].address, 0x100 + i);
        assert_int_equal(sl->constant[i].value, i);
    }
    /* a 17th entry on a continuation line exceeds the capacity */
    assert_int_equal(qo_regmap_parse("[slave.1]\ninit = 1=1 2=2 3=3 4=4 5=5 6=6 7=7 8=8\n"
                                     "  9=9 10=10 11=11 12=12 13=13 14=14 15=15 16=16\n  17=17\n"
                                     "[joint.a]\nslave = 1\naddress = 0\ntype = int16\n",
                                     "cap.ini", &map, err, sizeof err), QO_E_CAPACITY);
    assert_non_null(strstr(err, "cap.ini:4: "));
    /* continuing a one-value key is an error */
    assert_int_equal(qo_regmap_parse("[joint.a]\nslave = 1\naddress = 0\n  5\ntype = int16\n",
                                     "cont.ini", &map, err, sizeof err), QO_E_CONFIG);
    assert_non_null(strstr(err, "cont.ini:4: "));
    /* one line of 300 characters */
    len = (size_t)snprintf(text, sizeof text, "[slave.1]\ninit = ");
    for (i = 0; i < 20; i++)
        len += (size_t)snprintf(text + len, sizeof text - len, "0x%04X=0x%04X, ", (unsigned)i,
                                (unsigned)i);
    (void)snprintf(text + len, sizeof text - len,
                   "\n[joint.a]\nslave = 1\naddress = 0\ntype = int16\n");
    assert_int_equal(qo_regmap_parse(text, "wide.ini", &map, err, sizeof err), QO_E_CONFIG);
    if (strncmp(err, "wide.ini:2: line longer than", 28) != 0) fail_msg("message: %s", err);
}

static void test_null_and_small_buffers(void **state)
{
    char err[8];
    qo_regmap_write w[2];
    size_t n = 9;
    (void)state;
    assert_int_equal(qo_regmap_parse(NULL, "x", &map, err, sizeof err), QO_E_NULL);
    assert_int_equal(qo_regmap_parse(good, "x", NULL, err, sizeof err), QO_E_NULL);
    assert_int_equal(qo_regmap_load(NULL, &map, err, sizeof err), QO_E_NULL);
    /* a message longer than the buffer is truncated, still terminated */
    assert_int_equal(qo_regmap_parse("[joint.x]\nfoo=1\n", "file.ini", &map, err, sizeof err),
                     QO_E_CONFIG);
    assert_int_equal(strlen(err), sizeof err - 1);
    assert_int_equal(qo_regmap_parse(good, NULL, &map, NULL, 0), QO_OK);
    assert_int_equal(qo_regmap_parse_writes("1=2,3=4", w, 2, &n), QO_OK);
    assert_int_equal(n, 2);
    assert_int_equal(qo_regmap_parse_writes("1=2,3=4,5=6", w, 2, &n), QO_E_CAPACITY);
    assert_int_equal(n, 0);
    assert_int_equal(qo_regmap_parse_writes("1==2", w, 2, &n), QO_E_CONFIG);
    assert_int_equal(qo_regmap_parse_writes("", w, 2, &n), QO_OK);
    assert_int_equal(n, 0);
}

/* Input that is not a text map: an endless one stops, a NUL is an error wherever it is, a
 * byte-order mark is skipped. */
static void test_bounded_and_binary_input(void **state)
{
    static const char nul_after_comment[] =
        "[joint.a]\nslave = 1\naddress = 0\ntype = int16\n; note\0bogus = 1\n";
    static const char bom[] = "\xEF\xBB\xBF[joint.a]\nslave = 1\naddress = 7\ntype = int16\n";
    static char big[QO_REGMAP_MAX_BYTES + 4096];
    char err[256];
    size_t i, len = 0;
    (void)state;
    /* /dev/zero never ends: refused at the first line of NUL bytes, not read for ever */
    assert_int_equal(qo_regmap_load("/dev/zero", &map, err, sizeof err), QO_E_CONFIG);
    assert_non_null(strstr(err, "/dev/zero:1: NUL byte"));
    assert_int_equal(map.n_joints, 0);
    /* a NUL inside a comment must not end the line there and expose a key after it */
    assert_int_equal(load_bytes(nul_after_comment, sizeof nul_after_comment - 1, err, sizeof err),
                     QO_E_CONFIG);
    if (strstr(err, ":5: NUL byte") == NULL) fail_msg("message: %s", err);
    /* a NUL on line 1 of an otherwise good map */
    assert_int_equal(load_bytes("\0[joint.a]\n", 12, err, sizeof err), QO_E_CONFIG);
    assert_non_null(strstr(err, ":1: NUL byte"));
    /* a UTF-8 byte-order mark, from a file and from memory */
    assert_int_equal(load_bytes(bom, sizeof bom - 1, err, sizeof err), QO_OK);
    assert_int_equal(map.n_joints, 1);
    assert_int_equal(map.joints[0].address, 7);
    assert_int_equal(qo_regmap_parse(bom, "bom.ini", &map, err, sizeof err), QO_OK);
    assert_string_equal(map.joints[0].name, "a");
    /* the mark is a mark only at the very start */
    assert_int_equal(qo_regmap_parse("[joint.a]\n\xEF\xBB\xBFslave = 1\naddress = 0\ntype = int16\n",
                                     "mid.ini", &map, err, sizeof err), QO_E_CONFIG);
    /* too many lines, and too many bytes (comment lines: nothing else is wrong with them) */
    for (i = 0; len + 3 < sizeof big && i <= QO_REGMAP_MAX_LINES; i++) {
        big[len++] = ';';
        big[len++] = '\n';
    }
    big[len] = '\0';
    assert_int_equal(qo_regmap_parse(big, "lines.ini", &map, err, sizeof err), QO_E_CAPACITY);
    assert_non_null(strstr(err, "lines"));
    for (len = 0; len + 100 < sizeof big;) {
        memset(big + len, ' ', 98);
        big[len] = ';';
        big[len + 98] = '\n';
        len += 99;
    }
    big[len] = '\0';
    assert_int_equal(qo_regmap_parse(big, "bytes.ini", &map, err, sizeof err), QO_E_CAPACITY);
    assert_int_equal(map.n_joints, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse_good),
        cmocka_unit_test(test_errors_name_file_and_line),
        cmocka_unit_test(test_capacity_of_joints),
        cmocka_unit_test(test_example_files),
        cmocka_unit_test(test_long_lists),
        cmocka_unit_test(test_null_and_small_buffers),
        cmocka_unit_test(test_bounded_and_binary_input),
    };
    return cmocka_run_group_tests_name("regmap", tests, NULL, NULL);
}
