/*
 * GPIO sink over a fake pin backend that records every edge with the fake clock's time:
 * step counts, direction setup, the rate limit (also with late wake-ups), no burst after a
 * stall or a jump, carry of remainders, inverted direction, demo servo PWM, errors; plus the
 * libgpiod backend's behaviour on a machine without GPIO chips.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

#include "common/ref.h"
#include "linux/gpio_sink.h"

/* ---- deterministic PRNG: splitmix64 of tests/common/ref.c -------------------------------- */
static ref_rng sm;
static uint64_t sm_below(uint64_t n) { return ref_rng_next(&sm) % n; }

/* ---- fake backend ---------------------------------------------------------------------- */
#define MAXE 200000
#define MAXH 16
typedef struct edge { uint64_t t; int h, v; } edge;
typedef struct fakebe {
    uint64_t now;
    edge e[MAXE];
    size_t ne;
    int level[MAXH];
    int opened[MAXH], closed[MAXH];
    int nopen;
    int fail_open_at;      /* 1-based open call that fails; 0 never */
    int fail_set_h;        /* handle whose set fails; -1 never */
    int fail_set_after;    /* ... after this many successful sets on it */
    int sets_on_fail_h;
    uint64_t max_lat;      /* random extra lateness of each sleep, [0, max_lat) */
    uint64_t set_cost;     /* time one set_value takes */
} fakebe;
static fakebe B;

static qo_status fb_open(void *ctx, const qo_gpio_sink_line *line, int initial, int *h)
{
    fakebe *b = ctx;
    assert_non_null(line);
    if (b->fail_open_at && b->nopen + 1 == b->fail_open_at) { *h = -1; return QO_E_CONFIG; }
    *h = b->nopen++;
    assert_true(*h < MAXH);
    b->opened[*h] = 1;
    b->level[*h] = initial;
    return QO_OK;
}
static qo_status fb_set(void *ctx, int h, int v)
{
    fakebe *b = ctx;
    assert_true(h >= 0 && h < b->nopen && b->opened[h] && !b->closed[h]);
    if (h == b->fail_set_h && b->sets_on_fail_h++ >= b->fail_set_after) return QO_E_IO;
    assert_true(b->ne < MAXE);
    b->now += b->set_cost;
    b->e[b->ne].t = b->now;
    b->e[b->ne].h = h;
    b->e[b->ne].v = v;
    b->ne++;
    b->level[h] = v;
    return QO_OK;
}
static void fb_close(void *ctx, int h) { ((fakebe *)ctx)->closed[h] = 1; }
static uint64_t fb_now(void *ctx) { return ((fakebe *)ctx)->now; }
static int fb_sleep(void *ctx, uint64_t t)
{
    fakebe *b = ctx;
    if (b->now < t) b->now = t;
    if (b->max_lat) b->now += sm_below(b->max_lat);
    return 0;
}

static qo_gpio_sink_backend fake_backend(void)
{
    qo_gpio_sink_backend be = { .ctx = &B, .open = fb_open, .set_value = fb_set, .close = fb_close,
                           .now_ns = fb_now, .sleep_until_ns = fb_sleep };
    return be;
}

static qo_gpio_sink *G; /* the sink under test; open_into frees the previous one */

/* A fresh fake backend; the previous sink is freed first, while its lines still exist. */
static void reset_backend(void)
{
    qo_gpio_sink_free(G);
    G = NULL;
    memset(&B, 0, sizeof B);
    B.now = 5000000000ull;
    B.fail_set_h = -1;
}

static qo_gpio_sink_config C;

/* Joint j: step handle 2j, dir handle 2j+1 (open order), when all joints are step/dir. */
static void make_config(size_t n, double rate, double setup_us, int invert)
{
    qo_gpio_sink_joint j;
    size_t i;
    C = qo_gpio_sink_config_default;
    j = qo_gpio_sink_joint_default;
    C.n_joints = n;
    for (i = 0; i < n; i++) {
        C.joint[i] = j;
        C.joint[i].step.chip = "fake";
        C.joint[i].step.offset = (unsigned)(2 * i);
        C.joint[i].dir.chip = "fake";
        C.joint[i].dir.offset = (unsigned)(2 * i + 1);
        C.joint[i].steps_per_unit = 100.0;
        C.joint[i].max_rate_hz = rate;
        C.joint[i].dir_setup_us = setup_us;
        C.joint[i].invert_dir = invert;
    }
}

/* Opens G afresh (the previous sink freed first). */
static qo_status open_into(const qo_gpio_sink_config *cfg, const qo_gpio_sink_backend *be)
{
    qo_gpio_sink_free(G);
    G = NULL;
    return qo_gpio_sink_open(cfg, be, &G);
}

static void open_sink(void)
{
    qo_gpio_sink_backend be = fake_backend();
    assert_int_equal(open_into(&C, &be), QO_OK);
}

static size_t ntick;
static uint64_t P_NS;

/* A fresh backend and an open sink of n step/dir joints at 500 Hz (make_config). */
static void start_sink(size_t n, double rate, double setup_us, int invert)
{
    reset_backend();
    ntick = 0;
    make_config(n, rate, setup_us, invert);
    P_NS = 2000000u;
    open_sink();
}

/* Tick starts: the streamer would call write at base + k*P, or later if the last write ran
 * late. */
#define MAXTICK 4000
static uint64_t tick_start[MAXTICK];

static qo_status tick_at(uint64_t t, const float *targets)
{
    if (B.now < t) B.now = t;
    assert_true(ntick < MAXTICK);
    tick_start[ntick++] = B.now;
    return qo_gpio_sink_write(G, targets, C.n_joints, ntick - 1);
}

/* Independent checker over the recorded edges of one step/dir joint. */
typedef struct check_out { int64_t net; size_t rises; size_t max_per_tick; } check_out;

static check_out check_joint(size_t j, double rate, double setup_us, int invert)
{
    const int hs = (int)(2 * j), hd = (int)(2 * j + 1);
    const double min_iv = 1e9 / rate;      /* ns between rises, real-valued */
    const double high = C.step_high_us * 1e3;
    int step = 0, dir = 0, have_rise = 0;
    uint64_t last_rise = 0, last_dir = 5000000000ull; /* dir set at open time */
    size_t k, tk = 0, in_tick = 0;
    check_out o = { 0, 0, 0 };
    for (k = 0; k < B.ne; k++) {
        const edge *e = &B.e[k];
        while (tk + 1 < ntick && e->t >= tick_start[tk + 1]) { tk++; in_tick = 0; }
        if (e->h == hd) {
            if (step) fail_msg("joint %zu: dir changed at %llu while step high", j,
                               (unsigned long long)e->t);
            if (e->v != dir) last_dir = e->t;
            dir = e->v;
        } else if (e->h == hs) {
            if (e->v == 1) {
                if (step) fail_msg("joint %zu: rise while high", j);
                if (have_rise && (double)(e->t - last_rise) < min_iv - 0.5)
                    fail_msg("joint %zu: rises %llu ns apart, min %.1f (rate %g)", j,
                             (unsigned long long)(e->t - last_rise), min_iv, rate);
                if ((double)(e->t - last_dir) < setup_us * 1e3 - 0.5)
                    fail_msg("joint %zu: rise %llu ns after dir change, setup %g us", j,
                             (unsigned long long)(e->t - last_dir), setup_us);
                /* a late wake-up (fake lateness, ioctl cost) may push a planned pulse past the
                 * window: allow exactly that much */
                if (e->t < tick_start[tk] ||
                    (double)e->t + high > (double)tick_start[tk] + C.window * (double)P_NS + 0.5 +
                                              (double)B.max_lat + 2.0 * (double)B.set_cost)
                    fail_msg("joint %zu: pulse at %llu outside tick %zu window", j,
                             (unsigned long long)e->t, tk);
                last_rise = e->t;
                have_rise = 1;
                o.rises++;
                o.net += (dir != 0) != (invert != 0) ? 1 : -1;
                if (++in_tick > o.max_per_tick) o.max_per_tick = in_tick;
            } else {
                if (!step) fail_msg("joint %zu: fall while low", j);
                if ((double)(e->t - last_rise) < high - 0.5) fail_msg("joint %zu: short pulse", j);
            }
            step = e->v;
        }
    }
    if (step) fail_msg("joint %zu: step left high", j);
    return o;
}

/* Round half away from zero, in the test's own terms. */
static int64_t rnd(double v) { return (int64_t)(v < 0 ? -floor(-v + 0.5) : floor(v + 0.5)); }

/* ---- tests ------------------------------------------------------------------------------ */

/* Small moves within the per-tick capacity land exactly; every step is accounted for. */
static void test_step_counts(void **state)
{
    const double rate = 4000.0;
    float x[2];
    size_t k;
    (void)state;
    start_sink(2, rate, 5.0, 0);
    for (k = 0; k < 200; k++) {
        int64_t p0, p1;
        x[0] = (float)(0.02 * sin(0.05 * (double)k));   /* <= ~0.1 step/tick change */
        x[1] = (float)(0.02 * (double)(k % 2) - 0.01 * (double)(k % 3)); /* jumps <= 4 steps */
        assert_int_equal(tick_at(5000000000ull + (uint64_t)k * P_NS, x), QO_OK);
        assert_int_equal(qo_gpio_sink_position(G, 0, &p0), QO_OK);
        assert_int_equal(qo_gpio_sink_position(G, 1, &p1), QO_OK);
        if (p0 != rnd((double)x[0] * 100.0) || p1 != rnd((double)x[1] * 100.0))
            fail_msg("tick %zu: positions %lld %lld, targets %g %g", k, (long long)p0,
                     (long long)p1, (double)x[0] * 100.0, (double)x[1] * 100.0);
    }
    {
        check_out a = check_joint(0, rate, 5.0, 0), b = check_joint(1, rate, 5.0, 0);
        int64_t p0, p1;
        qo_gpio_sink_position(G, 0, &p0);
        qo_gpio_sink_position(G, 1, &p1);
        assert_int_equal(a.net, p0);
        assert_int_equal(b.net, p1);
        assert_true(b.rises > 100);
    }
    qo_gpio_sink_close(G);
    assert_true(B.closed[0] && B.closed[1] && B.closed[2] && B.closed[3]);
}

/* A target far away: each tick emits at most what the rate allows over the window, never
 * more, the remainder is carried, and the target is reached exactly. */
static void test_rate_limit_and_carry(void **state)
{
    const double rate = 2000.0; /* 0.5 ms apart; window 1.5 ms at 500 Hz */
    const size_t cap = (size_t)floor(rate * 0.0015) + 1u; /* upper bound: fencepost of a 1.5 ms window */
    float x[1];
    size_t k, reached = 0;
    int64_t prev = 0;
    (void)state;
    start_sink(1, rate, 0.0, 0);
    x[0] = 0.2f; /* 20 steps */
    for (k = 0; k < 10; k++) {
        int64_t p;
        assert_int_equal(tick_at(5000000000ull + (uint64_t)k * P_NS, x), QO_OK);
        qo_gpio_sink_position(G, 0, &p);
        if ((size_t)(p - prev) > cap) fail_msg("tick %zu: %lld steps > cap %zu", k, (long long)(p - prev), cap);
        if (p < 20 && (size_t)(p - prev) < 3) fail_msg("tick %zu: only %lld steps while owed", k, (long long)(p - prev));
        if (p > 20) fail_msg("overshoot %lld", (long long)p);
        if (p == 20 && !reached) reached = k + 1;
        prev = p;
    }
    assert_true(reached >= (20 + cap - 1) / cap); /* cannot be faster than the cap */
    assert_int_equal(prev, 20);
    {
        check_out o = check_joint(0, rate, 0.0, 0);
        assert_true(o.max_per_tick <= (size_t)floor(rate * 0.002));
        assert_int_equal(o.net, 20);
    }
}

/* After a stall (no writes for 50 periods) and a jump of 1000 steps, each tick still emits at
 * most its rate's worth; nothing is made up in a burst. Repeated with late wake-ups. */
static void test_no_burst_after_stall(void **state)
{
    const double rate = 3000.0;
    int pass;
    (void)state;
    for (pass = 0; pass < 2; pass++) {
        float x[1];
        uint64_t t;
        size_t k;
        int64_t prev;
        check_out o;
        reset_backend();
        sm.s = 99;
        B.max_lat = pass ? 300000u : 0u; /* up to 300 us late per sleep */
        B.set_cost = pass ? 2000u : 0u;
        ntick = 0;
        make_config(1, rate, 10.0, 0);
        P_NS = 2000000u;
        open_sink();
        x[0] = 0.01f;
        t = 5000000000ull;
        for (k = 0; k < 5; k++, t += P_NS) assert_int_equal(tick_at(t, x), QO_OK);
        t += 50u * P_NS; /* stall */
        x[0] = 10.01f;   /* 1000 steps further */
        qo_gpio_sink_position(G, 0, &prev);
        assert_int_equal(prev, 1);
        for (k = 0; k < 700; k++, t += P_NS) {
            int64_t p;
            assert_int_equal(tick_at(t, x), QO_OK);
            qo_gpio_sink_position(G, 0, &p);
            if ((double)(p - prev) > rate * 0.002)
                fail_msg("pass %d tick %zu: %lld steps in one period", pass, k, (long long)(p - prev));
            prev = p;
        }
        assert_int_equal(prev, 1001);
        o = check_joint(0, rate, 10.0, 0);
        assert_int_equal(o.net, 1001);
        assert_true((double)o.max_per_tick <= rate * 0.002);
    }
}

/* Fractional targets: 0.3 step more per tick; the position follows round(0.3 k) exactly. */
static void test_fractional_remainders(void **state)
{
    float x[1];
    size_t k;
    (void)state;
    start_sink(1, 5000.0, 5.0, 0);
    for (k = 0; k < 300; k++) {
        int64_t p;
        double steps = 0.3 * (double)k - 1.5;
        x[0] = (float)(steps / 100.0);
        assert_int_equal(tick_at(5000000000ull + (uint64_t)k * P_NS, x), QO_OK);
        qo_gpio_sink_position(G, 0, &p);
        if (p != rnd((double)x[0] * 100.0))
            fail_msg("tick %zu: position %lld, want %lld", k, (long long)p, (long long)rnd((double)x[0] * 100.0));
    }
    (void)check_joint(0, 5000.0, 5.0, 0);
}

/* Direction reversals every tick: dir level matches the sign (1 = positive), each first rise
 * after a change waits the setup time, dir never moves while step is high; inverted too. */
static void test_direction_setup_and_invert(void **state)
{
    int inv;
    (void)state;
    for (inv = 0; inv < 2; inv++) {
        const double setup = 250.0;
        float x[1];
        size_t k;
        check_out o;
        start_sink(1, 4000.0, setup, inv);
        for (k = 0; k < 40; k++) {
            int64_t p;
            size_t e0 = B.ne, e;
            x[0] = (k & 1) ? -0.02f : 0.02f; /* 4 steps per reversal */
            assert_int_equal(tick_at(5000000000ull + (uint64_t)k * P_NS, x), QO_OK);
            qo_gpio_sink_position(G, 0, &p);
            assert_int_equal(p, (k & 1) ? -2 : 2);
            /* the dir line level during this tick's rises */
            for (e = e0; e < B.ne; e++)
                if (B.e[e].h == 0 && B.e[e].v == 1) {
                    int want = ((k & 1) == 0) != (inv != 0);
                    if (B.level[1] != want)
                        fail_msg("inv %d tick %zu: dir %d want %d", inv, k, B.level[1], want);
                }
        }
        o = check_joint(0, 4000.0, setup, inv);
        assert_int_equal(o.net, -2);
        assert_int_equal(o.rises, 2u + 39u * 4u);
    }
}

/* Random targets, random lateness and ioctl cost, two joints: every invariant of the checker
 * holds and the recorded edges add up to the reported positions. */
static void test_random_invariants(void **state)
{
    const double rate[2] = { 2500.0, 7000.0 };
    float x[2];
    size_t k;
    uint64_t t = 5000000000ull;
    (void)state;
    reset_backend();
    sm.s = 2024;
    B.max_lat = 150000u;
    B.set_cost = 1500u;
    ntick = 0;
    make_config(2, 1000.0, 20.0, 0);
    C.joint[0].max_rate_hz = rate[0];
    C.joint[1].max_rate_hz = rate[1];
    C.joint[1].invert_dir = 1;
    P_NS = 2000000u;
    open_sink();
    for (k = 0; k < 1500; k++) {
        x[0] = (float)((double)sm_below(2001) / 100.0 - 10.0);
        x[1] = (float)(sin(0.01 * (double)k) * 0.5 + (double)sm_below(5) / 100.0);
        assert_int_equal(tick_at(t, x), QO_OK);
        t += P_NS;
        if (sm_below(50) == 0) t += sm_below(10) * P_NS; /* occasional stalls */
    }
    {
        check_out a = check_joint(0, rate[0], 20.0, 0), b = check_joint(1, rate[1], 20.0, 1);
        int64_t p0, p1;
        qo_gpio_sink_position(G, 0, &p0);
        qo_gpio_sink_position(G, 1, &p1);
        assert_int_equal(a.net, p0);
        assert_int_equal(b.net, p1);
        assert_true(a.rises > 1000 && b.rises > 100);
    }
}

/* Demo servo PWM: 50 Hz frames, width = clamp(1500 + 500 x) us, NaN holds the width. */
static void test_servo_pwm(void **state)
{
    qo_gpio_sink_joint j;
    const float xs[] = { 0.0f, 0.5f, -0.5f, 3.0f, -3.0f, NAN, 0.25f };
    size_t k, rises = 0;
    uint64_t last_rise = 0, rise_t = 0;
    double want_w = 1500.0;
    (void)state;
    reset_backend();
    ntick = 0;
    C = qo_gpio_sink_config_default;
    j = qo_gpio_sink_joint_default;
    C.period_s = 0.004; /* 250 Hz; window 3 ms > 2 ms pulse */
    C.n_joints = 1;
    C.joint[0] = j;
    C.joint[0].kind = QO_GPIO_SINK_SERVO_PWM;
    C.joint[0].step.chip = "fake";
    P_NS = 4000000u;
    open_sink();
    for (k = 0; k < 7 * 25; k++) {
        float x[1];
        size_t e0 = B.ne, e;
        qo_status st;
        x[0] = xs[k / 25];
        st = tick_at(5000000000ull + (uint64_t)k * P_NS, x);
        if (isfinite(x[0])) {
            double w = 1500.0 + 500.0 * (double)x[0];
            want_w = w < 1000.0 ? 1000.0 : w > 2000.0 ? 2000.0 : w;
            assert_int_equal(st, QO_OK);
        } else {
            assert_int_equal(st, QO_E_NONFINITE);
        }
        for (e = e0; e < B.ne; e++) {
            if (B.e[e].v == 1) {
                if (rises && B.e[e].t - last_rise < 20000000u) fail_msg("frame shorter than 20 ms");
                last_rise = rise_t = B.e[e].t;
                rises++;
            } else {
                double w = (double)(B.e[e].t - rise_t) / 1000.0;
                if (fabs(w - want_w) > 1e-6) fail_msg("tick %zu width %g us want %g", k, w, want_w);
            }
        }
    }
    /* 175 ticks of 4 ms = 700 ms: one frame per 5 ticks */
    assert_int_equal(rises, 35);
    {
        int64_t p;
        assert_int_equal(qo_gpio_sink_position(G, 0, &p), QO_E_RANGE);
    }
    qo_gpio_sink_close(G);
}

static void test_config_errors(void **state)
{
    qo_gpio_sink_backend be;
    qo_gpio_sink_config bad;
    float x[2] = { 0.0f, 0.0f };
    int64_t p;
    (void)state;
    reset_backend();
    be = fake_backend();
    make_config(2, 1000.0, 5.0, 0);
    assert_int_equal(open_into(&C, &be), QO_OK);
    assert_int_equal(qo_gpio_sink_open(&C, &be, NULL), QO_E_NULL);
    assert_int_equal(open_into(NULL, &be), QO_E_NULL);
    assert_null(G); /* *out NULL on error */
    assert_int_equal(open_into(&C, NULL), QO_E_NULL);
    assert_int_equal(qo_gpio_sink_write(G, x, 2, 0), QO_E_NULL);
    { qo_gpio_sink_backend b2 = be; b2.set_value = NULL; assert_int_equal(open_into(&C, &b2), QO_E_NULL); }
    bad = C; bad.n_joints = 0; assert_int_equal(open_into(&bad, &be), QO_E_TOO_FEW);
    bad = C; bad.n_joints = QO_GPIO_SINK_MAX_JOINTS + 1; assert_int_equal(open_into(&bad, &be), QO_E_CAPACITY);
    bad = C; bad.period_s = 0.0; assert_int_equal(open_into(&bad, &be), QO_E_LIMIT);
    bad = C; bad.period_s = NAN; assert_int_equal(open_into(&bad, &be), QO_E_LIMIT);
    bad = C; bad.window = 1.5; assert_int_equal(open_into(&bad, &be), QO_E_LIMIT);
    bad = C; bad.joint[1].max_rate_hz = 0.0; assert_int_equal(open_into(&bad, &be), QO_E_LIMIT);
    bad = C; bad.joint[1].max_rate_hz = INFINITY; assert_int_equal(open_into(&bad, &be), QO_E_LIMIT);
    bad = C; bad.joint[0].steps_per_unit = -5.0; assert_int_equal(open_into(&bad, &be), QO_E_LIMIT);
    bad = C; bad.joint[0].dir_setup_us = -1.0; assert_int_equal(open_into(&bad, &be), QO_E_LIMIT);
    bad = C; bad.joint[0].kind = (qo_gpio_sink_joint_kind)7; assert_int_equal(open_into(&bad, &be), QO_E_ARG);
    bad = C; bad.joint[0].dir.chip = NULL; assert_int_equal(open_into(&bad, &be), QO_E_NULL);
    bad = C; bad.step_high_us = 1000.0; /* = 1/max_rate: no low time left */
    assert_int_equal(open_into(&bad, &be), QO_E_CONFIG);
    bad = C; bad.joint[1].dir_setup_us = 1496.0; /* + 5 us high > 1.5 ms window */
    assert_int_equal(open_into(&bad, &be), QO_E_CONFIG);
    bad.joint[1].dir_setup_us = 1494.0; bad.joint[1].max_rate_hz = 100.0;
    assert_int_equal(open_into(&bad, &be), QO_OK);
    qo_gpio_sink_close(G);
    reset_backend();
    bad = C; bad.joint[0].kind = QO_GPIO_SINK_SERVO_PWM; /* 2 ms pulse in a 1.5 ms window */
    assert_int_equal(open_into(&bad, &be), QO_E_CONFIG);
    assert_int_equal(B.nopen, 0);
    /* backend open failure on the 3rd line: the two opened are closed again */
    B.fail_open_at = 3;
    assert_int_equal(open_into(&C, &be), QO_E_CONFIG);
    assert_int_equal(B.nopen, 2);
    assert_true(B.closed[0] && B.closed[1]);
    assert_null(G);
    assert_int_equal(qo_gpio_sink_write(G, x, 2, 0), QO_E_NULL);
    assert_int_equal(qo_gpio_sink_position(G, 0, &p), QO_E_NULL);
    qo_gpio_sink_close(G); /* NULL: nothing */
    qo_gpio_sink_free(G);
}

/* Bad targets hold that joint only; a failing pin stops that joint and is reported. */
static void test_write_errors(void **state)
{
    float x[2];
    int64_t p0, p1;
    (void)state;
    start_sink(2, 4000.0, 5.0, 0);
    x[0] = 0.02f; x[1] = 0.02f;
    assert_int_equal(qo_gpio_sink_write(G, x, 1, 0), QO_E_RANGE);
    assert_int_equal(qo_gpio_sink_write(NULL, x, 2, 0), QO_E_NULL);
    assert_int_equal(qo_gpio_sink_write(G, NULL, 2, 0), QO_E_NULL);
    assert_int_equal(B.ne, 0);
    x[0] = NAN;
    assert_int_equal(tick_at(5000000000ull, x), QO_E_NONFINITE);
    qo_gpio_sink_position(G, 0, &p0);
    qo_gpio_sink_position(G, 1, &p1);
    assert_int_equal(p0, 0);
    assert_int_equal(p1, 2);
    x[0] = 1e20f;
    assert_int_equal(tick_at(5000000000ull + P_NS, x), QO_E_OVERFLOW);
    x[0] = -INFINITY;
    assert_int_equal(tick_at(5000000000ull + 2 * P_NS, x), QO_E_NONFINITE);
    qo_gpio_sink_position(G, 0, &p0);
    assert_int_equal(p0, 0);
    /* step line of joint 1 (handle 2) fails after 3 more sets: rise, fall, rise OK, fall fails */
    B.fail_set_h = 2;
    B.fail_set_after = 3;
    x[0] = 0.0f; x[1] = 0.08f;
    assert_int_equal(tick_at(5000000000ull + 3 * P_NS, x), QO_E_IO);
    qo_gpio_sink_position(G, 1, &p1);
    assert_int_equal(p1, 4); /* two more rises went out */
    assert_int_equal(qo_gpio_sink_position(G, 2, &p1), QO_E_RANGE);
    assert_int_equal(qo_gpio_sink_position(G, 0, NULL), QO_E_NULL);
    {
        qo_sink s;
        memset(&s, 0xA5, sizeof s);
        assert_int_equal(qo_gpio_sink_as_sink(NULL, &s), QO_E_NULL);
        assert_null(s.ctx); /* zeroed on error */
        assert_null(s.write);
        assert_int_equal(qo_gpio_sink_as_sink(G, NULL), QO_E_NULL);
        assert_int_equal(qo_gpio_sink_as_sink(G, &s), QO_OK);
        assert_ptr_equal(s.ctx, G);
        assert_null(s.service);
        assert_null(s.flush);
        assert_non_null(s.stats);
        assert_non_null(s.write);
        assert_non_null(s.close);
    }
}

/* The qo_sink view drives the sink as its typed functions do: a tick through view.write emits
 * the same steps as qo_gpio_sink_write, a wrong n is refused, and view.close (set, as the
 * Modbus sink's is) drives every line low and closes every line the sink opened; after it
 * the sink is closed (write QO_E_STATE), a second close is harmless and a new sink opens on
 * the same lines. */
static void test_sink_view_write_close(void **state)
{
    qo_sink v;
    float x[2] = { 0.01f, -0.02f };
    int64_t p0, p1;
    int h;
    (void)state;
    start_sink(2, 4000.0, 5.0, 0);
    assert_int_equal(qo_gpio_sink_as_sink(G, &v), QO_OK);
    B.now = 5000000000ull;
    assert_int_equal(v.write(v.ctx, x, 1, 0), QO_E_RANGE);
    assert_int_equal(B.ne, 0);
    assert_int_equal(v.write(v.ctx, x, 2, 0), QO_OK);
    assert_int_equal(qo_gpio_sink_position(G, 0, &p0), QO_OK);
    assert_int_equal(qo_gpio_sink_position(G, 1, &p1), QO_OK);
    /* 0.01 and -0.02 joint units at the test's 100 steps per unit (make_config) */
    assert_int_equal(p0, rnd(0.01f * C.joint[0].steps_per_unit));
    assert_int_equal(p1, rnd(-0.02f * C.joint[1].steps_per_unit));
    assert_true(p0 != 0 && p1 != 0);
    for (h = 0; h < B.nopen; h++) assert_false(B.closed[h]);
    qo_sink_close(&v);
    assert_true(B.nopen == 4);
    for (h = 0; h < B.nopen; h++) {
        assert_true(B.closed[h]);
        if (h % 2 == 0) assert_int_equal(B.level[h], 0); /* step lines left low */
    }
    assert_int_equal(B.level[1], 1); /* joint 0's dir line as its last (positive) move set it */
    assert_int_equal(v.write(v.ctx, x, 2, 1), QO_E_STATE);
    assert_int_equal(qo_gpio_sink_write(G, x, 2, 1), QO_E_STATE);
    qo_sink_close(&v); /* twice: harmless */
    reset_backend();
    open_sink();
    assert_int_equal(qo_gpio_sink_write(G, x, 2, 2), QO_OK);
    qo_gpio_sink_close(G);
}

/* The defaults are constants (one idiom with the streamer and the Modbus sink): the documented
 * values, and every one of the QO_GPIO_SINK_MAX_JOINTS joints equal to the default joint. */
static void test_default_constants(void **state)
{
    const qo_gpio_sink_config *c = &qo_gpio_sink_config_default;
    const qo_gpio_sink_joint *j = &qo_gpio_sink_joint_default;
    size_t i;
    (void)state;
    assert_true(c->period_s == 0.002 && c->window == 0.75 && c->step_high_us == 5.0);
    assert_true(c->servo_frame_us == 20000.0);
    assert_int_equal(c->n_joints, 0);
    assert_int_equal(j->kind, QO_GPIO_SINK_STEP_DIR);
    assert_true(j->steps_per_unit == 200.0 && j->max_rate_hz == 1000.0 && j->dir_setup_us == 5.0);
    assert_int_equal(j->invert_dir, 0);
    assert_true(j->servo_center_us == 1500.0 && j->servo_us_per_unit == 500.0);
    assert_true(j->servo_min_us == 1000.0 && j->servo_max_us == 2000.0);
    assert_null(j->step.chip);
    assert_null(j->step.name);
    assert_null(j->dir.chip);
    assert_null(j->dir.name);
    for (i = 0; i < QO_GPIO_SINK_MAX_JOINTS; i++)
        if (memcmp(&c->joint[i], j, sizeof *j) != 0) fail_msg("default joint %u differs", (unsigned)i);
}

/* No GPIO chips on this machine: the libgpiod backend reports a missing chip/line as a
 * configuration error and leaks nothing (ASan). */
static void test_libgpiod_backend_without_chips(void **state)
{
    static qo_gpio_sink_libgpiod store;
    qo_gpio_sink_backend be;
    qo_gpio_sink_line l;
    int h = 7;
    (void)state;
    assert_int_equal(qo_gpio_sink_libgpiod_backend(NULL, NULL, &be), QO_E_NULL);
    assert_int_equal(qo_gpio_sink_libgpiod_backend(&store, NULL, &be), QO_OK);
    assert_string_equal(store.consumer, "qorient");
    assert_true(strcmp(qo_gpio_sink_libgpiod_api(), "v1") == 0 || strcmp(qo_gpio_sink_libgpiod_api(), "v2") == 0);
    memset(&l, 0, sizeof l);
    l.chip = "qorient-no-such-chip";
    assert_int_equal(be.open(be.ctx, &l, 0, &h), QO_E_CONFIG);
    assert_int_equal(h, -1);
    l.chip = NULL;
    l.name = "qorient-no-such-line";
    assert_int_equal(be.open(be.ctx, &l, 0, &h), QO_E_CONFIG);
    assert_int_equal(be.set_value(be.ctx, 0, 1), QO_E_ARG);
    be.close(be.ctx, 0); /* not open: ignored */
}

/* Group teardown: the last sink is freed (LeakSanitizer sees none left). */
static int free_sink(void **state)
{
    (void)state;
    qo_gpio_sink_free(G);
    G = NULL;
    return 0;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_step_counts),
        cmocka_unit_test(test_rate_limit_and_carry),
        cmocka_unit_test(test_no_burst_after_stall),
        cmocka_unit_test(test_fractional_remainders),
        cmocka_unit_test(test_direction_setup_and_invert),
        cmocka_unit_test(test_random_invariants),
        cmocka_unit_test(test_servo_pwm),
        cmocka_unit_test(test_config_errors),
        cmocka_unit_test(test_write_errors),
        cmocka_unit_test(test_sink_view_write_close),
        cmocka_unit_test(test_libgpiod_backend_without_chips),
        cmocka_unit_test(test_default_constants),
    };
    return cmocka_run_group_tests_name("gpio_sink", tests, NULL, free_sink);
}
