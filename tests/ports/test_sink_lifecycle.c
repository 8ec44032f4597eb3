/* The three sinks alike (#16): ONE test body run against the Modbus sink (a real simulator on
 * a loopback TCP port), the GPIO sink (a fake pin backend) and the mock sink, through an
 * adapter table as tests/common/cores.h does for the two cores. Each body checks what every
 * sink header documents in its "Lifecycle" paragraph: open -> as_sink -> write ... -> close ->
 * free; open's failure leaves nothing open; QO_E_NULL for a NULL object (outputs zeroed),
 * QO_E_RANGE for a wrong number of targets (nothing reaches the device), QO_E_STATE after
 * close (also through the view), statistics still readable after close, close and free
 * harmless on NULL and twice. A failure message starts with the sink's name. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "linux/gpio_sink.h"
#include "linux/modbus_sink.h"
#include "linux/sim.h"
#include "mock/mock_sink.h"

#define NJ 2

/* One sink behind the lifecycle verbs. `dev_writes` counts what reached the device (the
 * simulator's target writes, the backend's edges, the mock's records), so a refused write can
 * be shown to have sent nothing. */
typedef struct sink_row {
    const char *name;
    qo_status (*open)(void **obj);       /* QO_OK and an open object of NJ joints */
    qo_status (*open_null)(void **obj);  /* open with its required input NULL */
    qo_status (*as_sink)(void *obj, qo_sink *out);
    qo_status (*write)(void *obj, const float *targets, size_t n, uint64_t tick);
    qo_status (*get_stats)(const void *obj, qo_sink_stats *out);
    void (*close)(void *obj);
    void (*free)(void *obj);
    uint64_t (*dev_writes)(void);
    void (*teardown)(void);
} sink_row;

/* The typed verbs seen through void *: one wrapper set per family, written once. */
#define SINK_VERBS(F, T)                                                                     \
    static qo_status F##_as(void *o, qo_sink *out) { return qo_##F##_as_sink((T *)o, out); } \
    static qo_status F##_wr(void *o, const float *x, size_t n, uint64_t t)                  \
    {                                                                                        \
        return qo_##F##_write((T *)o, x, n, t);                                              \
    }                                                                                        \
    static qo_status F##_st(const void *o, qo_sink_stats *out)                               \
    {                                                                                        \
        return F##_stats((const T *)o, out);                                                 \
    }                                                                                        \
    static void F##_cl(void *o) { qo_##F##_close((T *)o); }                                  \
    static void F##_fr(void *o) { qo_##F##_free((T *)o); }

/* ---- mock: caller storage ---- */
static qo_mock_sink M;
static float M_store[8 * NJ];

static qo_status mock_sink_stats(const qo_mock_sink *m, qo_sink_stats *out)
{
    return qo_mock_sink_get_stats(m, out);
}
SINK_VERBS(mock_sink, qo_mock_sink)

static qo_status mock_open(void **obj)
{
    *obj = &M;
    return qo_mock_sink_open(&M, NJ, M_store, NULL, 8);
}

static qo_status mock_open_null(void **obj)
{
    *obj = &M;
    return qo_mock_sink_open(&M, NJ, NULL, NULL, 8);
}

static uint64_t mock_dev(void) { return M.count; }
static void mock_teardown(void) {}

/* ---- GPIO: a fake pin backend on a fake clock ---- */
static uint64_t G_now, G_sets;

static qo_status fb_open(void *ctx, const qo_gpio_sink_line *l, int initial, int *h)
{
    (void)ctx; (void)initial;
    *h = (int)l->offset;
    return QO_OK;
}
static qo_status fb_set(void *ctx, int h, int v) { (void)ctx; (void)h; (void)v; G_sets++; return QO_OK; }
static void fb_close(void *ctx, int h) { (void)ctx; (void)h; }
static uint64_t fb_now(void *ctx) { (void)ctx; return G_now; }
static int fb_sleep(void *ctx, uint64_t t) { (void)ctx; if (t > G_now) G_now = t; return 0; }

static qo_gpio_sink_config G_cfg;

static qo_status gpio_sink_stats(const qo_gpio_sink *g, qo_sink_stats *out)
{
    return qo_gpio_sink_get_stats(g, out);
}
SINK_VERBS(gpio_sink, qo_gpio_sink)

static qo_status gpio_open_with(void **obj, const qo_gpio_sink_config *cfg)
{
    static const qo_gpio_sink_backend be = { NULL, fb_open, fb_set, fb_close, fb_now, fb_sleep };
    qo_gpio_sink *g = (qo_gpio_sink *)&G_now; /* not NULL: open must clear it on error */
    qo_status st;
    size_t i;
    G_cfg = qo_gpio_sink_config_default;
    G_cfg.n_joints = NJ;
    for (i = 0; i < NJ; i++) {
        G_cfg.joint[i].step.chip = "fake";
        G_cfg.joint[i].step.offset = (unsigned)(2 * i);
        G_cfg.joint[i].dir.chip = "fake";
        G_cfg.joint[i].dir.offset = (unsigned)(2 * i + 1);
    }
    G_now = 1000000000ull;
    G_sets = 0;
    st = qo_gpio_sink_open(cfg != NULL ? &G_cfg : NULL, &be, &g);
    *obj = g;
    return st;
}

static qo_status gpio_open(void **obj) { return gpio_open_with(obj, &G_cfg); }
static qo_status gpio_open_null(void **obj) { return gpio_open_with(obj, NULL); }
static uint64_t gpio_dev(void) { return G_sets; }
static void gpio_teardown(void) {}

/* ---- Modbus: the simulator on an ephemeral loopback port ---- */
static qo_regmap MB_map; /* large: off the stack */
static qo_sim *MB_sim;
static char MB_spec[64];

static const char MB_map_text[] =
    "[slave.1]\n"
    "[joint.a]\nslave = 1\naddress = 0\ntype = int32\nscale = 1000\nmin = -10\nmax = 10\n"
    "[joint.b]\nslave = 1\naddress = 2\ntype = int32\nscale = 1000\nmin = -10\nmax = 10\n";

static qo_status modbus_sink_stats(const qo_modbus_sink *s, qo_sink_stats *out)
{
    qo_modbus_sink_stats ms;
    qo_status st = qo_modbus_sink_get_stats(s, &ms);
    if (out != NULL) *out = ms.common;
    return out != NULL ? st : QO_E_NULL;
}
SINK_VERBS(modbus_sink, qo_modbus_sink)

static qo_status modbus_open_spec(void **obj, const char *spec)
{
    char err[256];
    qo_modbus_sink *s = (qo_modbus_sink *)&MB_spec; /* not NULL: open must clear it on error */
    qo_status st;
    if (qo_regmap_parse(MB_map_text, "lifecycle.ini", &MB_map, err, sizeof err) != QO_OK)
        fail_msg("modbus: map: %s", err);
    if (MB_sim == NULL) {
        assert_int_equal(qo_sim_start("tcp://127.0.0.1:0", &MB_map, NULL, &MB_sim), QO_OK);
        snprintf(MB_spec, sizeof MB_spec, "tcp://127.0.0.1:%d", qo_sim_port(MB_sim));
    }
    st = qo_modbus_sink_open(spec != NULL ? MB_spec : NULL, &MB_map, NULL, &s);
    *obj = s;
    return st;
}

static qo_status modbus_open(void **obj) { return modbus_open_spec(obj, MB_spec); }
static qo_status modbus_open_null(void **obj) { return modbus_open_spec(obj, NULL); }

static uint64_t modbus_dev(void)
{
    qo_sim_stats st;
    assert_int_equal(qo_sim_get_stats(MB_sim, &st), QO_OK);
    return st.target_writes;
}

static void modbus_teardown(void)
{
    qo_sim_stop(MB_sim);
    MB_sim = NULL;
}

static const sink_row MOCK = { "mock", mock_open, mock_open_null, mock_sink_as, mock_sink_wr,
                               mock_sink_st, mock_sink_cl, mock_sink_fr, mock_dev, mock_teardown };
static const sink_row GPIO = { "gpio", gpio_open, gpio_open_null, gpio_sink_as, gpio_sink_wr,
                               gpio_sink_st, gpio_sink_cl, gpio_sink_fr, gpio_dev, gpio_teardown };
static const sink_row MODBUS = { "modbus", modbus_open, modbus_open_null, modbus_sink_as,
                                 modbus_sink_wr, modbus_sink_st, modbus_sink_cl, modbus_sink_fr,
                                 modbus_dev, modbus_teardown };

#define CHECK(r, got, want)                                                                  \
    do {                                                                                     \
        qo_status got_ = (got);                                                              \
        if (got_ != (want))                                                                  \
            fail_msg("%s: %s: status %s, want %s", (r)->name, #got, qo_status_str(got_),    \
                     qo_status_str(want));                                                   \
    } while (0)

static int all_zero(const void *p, size_t n)
{
    const unsigned char *b = p;
    size_t i;
    for (i = 0; i < n; i++)
        if (b[i] != 0) return 0;
    return 1;
}

/* open's failure leaves nothing open: the heap sinks hand back NULL, the mock is not open. */
static void test_open_failure(void **state)
{
    const sink_row *r = *state;
    const float x[NJ] = { 0.0f, 0.0f };
    void *obj = NULL;
    CHECK(r, r->open_null(&obj), QO_E_NULL);
    if (r != &MOCK && obj != NULL) fail_msg("%s: *out not NULL after a failed open", r->name);
    CHECK(r, r->write(obj, x, NJ, 0), r == &MOCK ? QO_E_STATE : QO_E_NULL);
    r->close(obj);
    r->free(obj);
    r->teardown();
}

/* NULL objects and NULL outputs, a wrong joint count, a good tick, the statistics. */
static void test_null_range_write(void **state)
{
    const sink_row *r = *state;
    const float x[NJ + 1] = { 0.01f, -0.02f, 0.0f }; /* 2 and 4 steps, 10 and 20 counts */
    qo_sink v;
    qo_sink_stats st;
    uint64_t dev;
    void *obj = NULL;
    CHECK(r, r->open(&obj), QO_OK);
    if (obj == NULL) fail_msg("%s: open returned no object", r->name);

    memset(&v, 0xA5, sizeof v);
    CHECK(r, r->as_sink(NULL, &v), QO_E_NULL);
    if (!all_zero(&v, sizeof v)) fail_msg("%s: as_sink(NULL) left *out unzeroed", r->name);
    CHECK(r, r->as_sink(obj, NULL), QO_E_NULL);
    CHECK(r, r->as_sink(obj, &v), QO_OK);
    if (v.ctx != obj || v.write == NULL || v.close == NULL || v.stats == NULL)
        fail_msg("%s: the view lacks ctx, write, close or stats", r->name);

    memset(&st, 0xA5, sizeof st);
    CHECK(r, r->get_stats(NULL, &st), QO_E_NULL);
    if (!all_zero(&st, sizeof st)) fail_msg("%s: get_stats(NULL) left *out unzeroed", r->name);
    CHECK(r, r->get_stats(obj, NULL), QO_E_NULL);

    dev = r->dev_writes();
    CHECK(r, r->write(NULL, x, NJ, 0), QO_E_NULL);
    CHECK(r, r->write(obj, NULL, NJ, 0), QO_E_NULL);
    CHECK(r, r->write(obj, x, NJ + 1, 0), QO_E_RANGE);
    CHECK(r, r->write(obj, x, NJ - 1, 0), QO_E_RANGE);
    CHECK(r, qo_sink_write(&v, x, NJ + 1, 0), QO_E_RANGE);
    if (r->dev_writes() != dev) fail_msg("%s: a refused write reached the device", r->name);
    CHECK(r, r->write(obj, x, NJ, 1), QO_OK);
    if (r->dev_writes() == dev) fail_msg("%s: a good write did not reach the device", r->name);
    CHECK(r, qo_sink_write(&v, x, NJ, 2), QO_OK);

    CHECK(r, r->get_stats(obj, &st), QO_OK);
    /* every call with an object is counted: NULL targets, 3 wrong counts, 2 good ticks */
    if (st.writes != 6 || st.writes_ok != 2 || st.writes_failed != 4 ||
        st.consecutive_failures != 0 || st.connected != 1)
        fail_msg("%s: stats writes %llu ok %llu failed %llu consecutive %llu connected %d",
                 r->name, (unsigned long long)st.writes, (unsigned long long)st.writes_ok,
                 (unsigned long long)st.writes_failed,
                 (unsigned long long)st.consecutive_failures, st.connected);
    {
        qo_sink_stats vs;
        CHECK(r, qo_sink_get_stats(&v, &vs), QO_OK);
        if (memcmp(&vs, &st, sizeof st) != 0)
            fail_msg("%s: the view's stats differ from get_stats", r->name);
    }
    r->close(obj);
    r->free(obj);
    r->teardown();
}

/* After close: QO_E_STATE from write and the view's write, nothing sent, stats still read
 * (connected 0), as_sink still fills, close twice and close/free of NULL harmless. */
static void test_closed(void **state)
{
    const sink_row *r = *state;
    const float x[NJ] = { 0.001f, 0.001f };
    qo_sink v;
    qo_sink_stats st;
    uint64_t dev;
    void *obj = NULL;
    CHECK(r, r->open(&obj), QO_OK);
    CHECK(r, r->as_sink(obj, &v), QO_OK);
    qo_sink_close(&v); /* the view's close is the family's close */
    r->close(obj);     /* twice: nothing */
    r->close(NULL);
    dev = r->dev_writes();
    CHECK(r, r->write(obj, x, NJ, 0), QO_E_STATE);
    CHECK(r, qo_sink_write(&v, x, NJ, 0), QO_E_STATE);
    CHECK(r, r->write(obj, NULL, NJ, 0), QO_E_NULL); /* NULL first, as before close */
    if (r->dev_writes() != dev) fail_msg("%s: a closed sink reached the device", r->name);
    CHECK(r, r->get_stats(obj, &st), QO_OK);
    if (st.connected != 0 || st.writes != 3 || st.writes_failed != 3)
        fail_msg("%s: closed stats connected %d writes %llu failed %llu", r->name, st.connected,
                 (unsigned long long)st.writes, (unsigned long long)st.writes_failed);
    CHECK(r, r->as_sink(obj, &v), QO_OK);
    CHECK(r, qo_sink_write(&v, x, NJ, 1), QO_E_STATE);
    r->free(obj);
    r->free(NULL);
    r->teardown();
}

/* Each body three times, named after its sink (cmocka's prestate form, with a name). */
#define ALL3(t)                                                                              \
    { #t " (modbus)", t, NULL, NULL, (void *)&MODBUS },                                      \
        { #t " (gpio)", t, NULL, NULL, (void *)&GPIO },                                      \
        { #t " (mock)", t, NULL, NULL, (void *)&MOCK }

int main(void)
{
    const struct CMUnitTest tests[] = {
        ALL3(test_open_failure),
        ALL3(test_null_range_write),
        ALL3(test_closed),
    };
    return cmocka_run_group_tests_name("sink_lifecycle", tests, NULL, NULL);
}
