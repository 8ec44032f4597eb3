/*
 * ports/linux/gpio_sink.c - step/dir and demo servo PWM over a pin backend; the libgpiod
 * backend (v1 API by default, v2 API under QO_GPIOD_V2). See gpio_sink.h for the model.
 */
#include "gpio_sink.h"
#include "mono_clock.h"
#include "sink_view.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gpiod.h>

/* API selection: the build system's macro first, else the header (only v1 defines the bulk
 * limit). */
#if !defined(QO_GPIOD_V1) && !defined(QO_GPIOD_V2)
#if defined(GPIOD_LINE_BULK_MAX_LINES)
#define QO_GPIOD_V1 1
#else
#define QO_GPIOD_V2 1
#endif
#endif

#if defined(QO_GPIOD_V2)
#include <dirent.h>
#endif

/* Per-joint state. */
typedef struct qo_gpio_sink_joint_state {
    int step_h, dir_h;
    int64_t position;
    int dir_level;
    uint64_t dir_time_ns;       /* when the dir line last changed */
    uint64_t last_rise_ns;
    int have_rise;
    uint64_t min_spacing_ns, high_ns, setup_ns;
    uint64_t servo_next_frame_ns;
    int servo_started;
    uint64_t servo_width_ns;
} qo_gpio_sink_joint_state;

struct qo_gpio_sink {
    qo_gpio_sink_config cfg;
    qo_gpio_sink_backend be;
    qo_gpio_sink_joint_state js[QO_GPIO_SINK_MAX_JOINTS];
    uint64_t period_ns, window_ns;
    int open;
    qo_sink_stats stats;
};

/* ---- configuration --------------------------------------------------------------------- */

/* Every joint of the default config is the default joint: its initializer, 32 times. */
#define QO_GPIO_JOINT_DEFAULT_INIT                                                          \
    { .kind = QO_GPIO_SINK_STEP_DIR, .steps_per_unit = 200.0, .max_rate_hz = 1000.0,           \
      .dir_setup_us = 5.0, .servo_center_us = 1500.0, .servo_us_per_unit = 500.0,         \
      .servo_min_us = 1000.0, .servo_max_us = 2000.0 }
#define QO_GPIO_J4 QO_GPIO_JOINT_DEFAULT_INIT, QO_GPIO_JOINT_DEFAULT_INIT, \
                   QO_GPIO_JOINT_DEFAULT_INIT, QO_GPIO_JOINT_DEFAULT_INIT
typedef char qo_gpio_default_covers_every_joint[QO_GPIO_SINK_MAX_JOINTS == 32u ? 1 : -1];

const qo_gpio_sink_joint qo_gpio_sink_joint_default = QO_GPIO_JOINT_DEFAULT_INIT;

const qo_gpio_sink_config qo_gpio_sink_config_default = {
    .period_s = 0.002, .window = 0.75, .step_high_us = 5.0, .servo_frame_us = 20000.0,
    .joint = { QO_GPIO_J4, QO_GPIO_J4, QO_GPIO_J4, QO_GPIO_J4, QO_GPIO_J4, QO_GPIO_J4, QO_GPIO_J4, QO_GPIO_J4 }
};

static int finite_in(double v, double lo, double hi) { return isfinite(v) && v >= lo && v <= hi; }
static int line_given(const qo_gpio_sink_line *l) { return l->chip != NULL || l->name != NULL; }
static uint64_t us_to_ns(double us) { return (uint64_t)llround(us * 1000.0); }

static qo_status check_config(const qo_gpio_sink_config *c)
{
    size_t i;
    if (c->n_joints == 0) return QO_E_TOO_FEW;
    if (c->n_joints > QO_GPIO_SINK_MAX_JOINTS) return QO_E_CAPACITY;
    if (!finite_in(c->period_s, 1e-6, 10.0) || !finite_in(c->window, 1e-3, 1.0) ||
        !finite_in(c->step_high_us, 1e-3, 1e6) || !finite_in(c->servo_frame_us, 1.0, 1e7))
        return QO_E_LIMIT;
    for (i = 0; i < c->n_joints; i++) {
        const qo_gpio_sink_joint *j = &c->joint[i];
        double window_us = c->period_s * c->window * 1e6;
        if (j->kind == QO_GPIO_SINK_STEP_DIR) {
            if (!line_given(&j->step) || !line_given(&j->dir)) return QO_E_NULL;
            if (!finite_in(j->steps_per_unit, 1e-9, 1e12) || !finite_in(j->max_rate_hz, 1e-6, 1e7) ||
                !finite_in(j->dir_setup_us, 0.0, 1e6))
                return QO_E_LIMIT;
            if (!(c->step_high_us < 1e6 / j->max_rate_hz)) return QO_E_CONFIG;
            /* a window that cannot hold one pulse after a direction change would stall forever */
            if (!(c->step_high_us + j->dir_setup_us < window_us)) return QO_E_CONFIG;
        } else if (j->kind == QO_GPIO_SINK_SERVO_PWM) {
            if (!line_given(&j->step)) return QO_E_NULL;
            if (!isfinite(j->servo_center_us) || !isfinite(j->servo_us_per_unit) ||
                !finite_in(j->servo_min_us, 1.0, 1e6) || !finite_in(j->servo_max_us, 1.0, 1e6) ||
                j->servo_min_us > j->servo_max_us)
                return QO_E_LIMIT;
            if (j->servo_max_us >= window_us || j->servo_max_us >= c->servo_frame_us)
                return QO_E_CONFIG;
        } else {
            return QO_E_ARG;
        }
    }
    return QO_OK;
}

static void close_all(qo_gpio_sink *g)
{
    size_t i;
    for (i = 0; i < g->cfg.n_joints; i++) {
        qo_gpio_sink_joint_state *s = &g->js[i];
        if (s->step_h >= 0) {
            (void)g->be.set_value(g->be.ctx, s->step_h, 0);
            g->be.close(g->be.ctx, s->step_h);
            s->step_h = -1;
        }
        if (s->dir_h >= 0) {
            g->be.close(g->be.ctx, s->dir_h);
            s->dir_h = -1;
        }
    }
}

static uint64_t servo_width_ns(const qo_gpio_sink_joint *j, double x)
{
    double w = j->servo_center_us + x * j->servo_us_per_unit;
    if (w < j->servo_min_us) w = j->servo_min_us;
    if (w > j->servo_max_us) w = j->servo_max_us;
    return us_to_ns(w);
}

qo_status qo_gpio_sink_open(const qo_gpio_sink_config *cfg, const qo_gpio_sink_backend *be,
                            qo_gpio_sink **out)
{
    qo_gpio_sink *g;
    qo_status st;
    size_t i;
    if (out != NULL) *out = NULL;
    if (!out || !cfg || !be || !be->open || !be->set_value || !be->close) return QO_E_NULL;
    st = check_config(cfg);
    if (st != QO_OK) return st;
    g = calloc(1, sizeof *g);
    if (g == NULL) return QO_E_IO;
    g->cfg = *cfg;
    g->be = *be;
    if (!g->be.now_ns) g->be.now_ns = qo_mono_clock_now_ns;
    if (!g->be.sleep_until_ns) g->be.sleep_until_ns = qo_mono_clock_sleep_until_ns;
    g->period_ns = (uint64_t)llround(cfg->period_s * 1e9);
    g->window_ns = (uint64_t)llround(cfg->period_s * cfg->window * 1e9);
    for (i = 0; i < cfg->n_joints; i++) { g->js[i].step_h = -1; g->js[i].dir_h = -1; }
    for (i = 0; i < cfg->n_joints; i++) {
        const qo_gpio_sink_joint *j = &cfg->joint[i];
        qo_gpio_sink_joint_state *s = &g->js[i];
        st = g->be.open(g->be.ctx, &j->step, 0, &s->step_h);
        if (st != QO_OK) { s->step_h = -1; break; }
        s->high_ns = us_to_ns(cfg->step_high_us);
        if (j->kind == QO_GPIO_SINK_STEP_DIR) {
            st = g->be.open(g->be.ctx, &j->dir, 0, &s->dir_h);
            if (st != QO_OK) { s->dir_h = -1; break; }
            s->dir_level = 0;
            s->dir_time_ns = g->be.now_ns(g->be.ctx);
            s->min_spacing_ns = (uint64_t)ceil(1e9 / j->max_rate_hz);
            s->setup_ns = us_to_ns(j->dir_setup_us);
        } else {
            s->servo_width_ns = servo_width_ns(j, 0.0);
        }
    }
    if (st != QO_OK) {
        close_all(g);
        free(g);
        return st;
    }
    g->open = 1;
    g->stats.connected = 1;
    *out = g;
    return QO_OK;
}

/* What one joint does in the current tick. */
typedef struct joint_plan {
    int active;
    int rising;          /* next event is a rise (else a fall) */
    uint64_t next_ns;    /* time of the next event */
    uint64_t first_ns, spacing_ns;
    uint64_t n, done;
    int sign;
} joint_plan;

static qo_status keep_first(qo_status cur, qo_status st) { return cur != QO_OK ? cur : st; }

static qo_status plan_step(qo_gpio_sink *g, size_t i, float target, uint64_t start,
                           uint64_t win_end, joint_plan *p)
{
    const qo_gpio_sink_joint *j = &g->cfg.joint[i];
    qo_gpio_sink_joint_state *s = &g->js[i];
    double d, r;
    int64_t desired, owed;
    uint64_t first, span, cap, mag;
    int level;
    if (!isfinite(target)) return QO_E_NONFINITE;
    d = (double)target * j->steps_per_unit;
    if (fabs(d) > 9007199254740992.0) return QO_E_OVERFLOW;
    r = floor(fabs(d) + 0.5); /* round half away from zero */
    desired = (int64_t)(d < 0.0 ? -r : r);
    owed = desired - s->position;
    if (owed == 0) return QO_OK;
    p->sign = owed > 0 ? 1 : -1;
    mag = owed > 0 ? (uint64_t)owed : (uint64_t)(-owed);
    level = (p->sign > 0) != (j->invert_dir != 0);
    if (level != s->dir_level) {
        if (g->be.set_value(g->be.ctx, s->dir_h, level) != QO_OK) return QO_E_IO;
        s->dir_level = level;
        s->dir_time_ns = g->be.now_ns(g->be.ctx);
    }
    first = start;
    if (s->dir_time_ns + s->setup_ns > first) first = s->dir_time_ns + s->setup_ns;
    if (s->have_rise && s->last_rise_ns + s->min_spacing_ns > first)
        first = s->last_rise_ns + s->min_spacing_ns;
    if (first + s->high_ns > win_end) return QO_OK; /* nothing fits this tick: all carried */
    span = win_end - s->high_ns - first;
    cap = span / s->min_spacing_ns + 1u;
    p->n = mag < cap ? mag : cap;
    p->spacing_ns = span / p->n;
    if (p->spacing_ns < s->min_spacing_ns) p->spacing_ns = s->min_spacing_ns;
    p->first_ns = first;
    p->next_ns = first;
    p->rising = 1;
    p->done = 0;
    p->active = 1;
    return QO_OK;
}

static qo_status plan_servo(qo_gpio_sink *g, size_t i, float target, uint64_t start,
                            uint64_t win_end, joint_plan *p)
{
    const qo_gpio_sink_joint *j = &g->cfg.joint[i];
    qo_gpio_sink_joint_state *s = &g->js[i];
    qo_status st = QO_OK;
    uint64_t at;
    if (isfinite(target)) s->servo_width_ns = servo_width_ns(j, (double)target);
    else st = QO_E_NONFINITE; /* keep the previous width */
    at = start;
    if (s->servo_started && s->servo_next_frame_ns > at) at = s->servo_next_frame_ns;
    if (at + s->servo_width_ns > win_end) return st; /* frame not due within this window */
    /* Frames follow the schedule while on time; a late frame restarts it (no catch-up). */
    s->servo_next_frame_ns = at + us_to_ns(g->cfg.servo_frame_us);
    s->servo_started = 1;
    p->next_ns = at;
    p->rising = 1;
    p->active = 1;
    return st;
}

static void sleep_until(qo_gpio_sink *g, uint64_t t)
{
    int r;
    do r = g->be.sleep_until_ns(g->be.ctx, t); while (r == EINTR);
}

static qo_status emit(qo_gpio_sink *g, const float *targets, size_t n)
{
    joint_plan plan[QO_GPIO_SINK_MAX_JOINTS];
    qo_status res = QO_OK;
    uint64_t start, win_end;
    size_t i;
    memset(plan, 0, sizeof plan);
    start = g->be.now_ns(g->be.ctx);
    win_end = start + g->window_ns;
    for (i = 0; i < n; i++) {
        qo_status st = g->cfg.joint[i].kind == QO_GPIO_SINK_STEP_DIR
                           ? plan_step(g, i, targets[i], start, win_end, &plan[i])
                           : plan_servo(g, i, targets[i], start, win_end, &plan[i]);
        res = keep_first(res, st);
    }
    /* Emit the edges of all joints in time order; each joint reschedules from actual times. */
    for (;;) {
        joint_plan *p = NULL;
        qo_gpio_sink_joint_state *s;
        size_t k = 0;
        uint64_t t;
        for (i = 0; i < n; i++)
            if (plan[i].active && (!p || plan[i].next_ns < p->next_ns)) { p = &plan[i]; k = i; }
        if (!p) break;
        s = &g->js[k];
        sleep_until(g, p->next_ns);
        if (g->be.set_value(g->be.ctx, s->step_h, p->rising) != QO_OK) {
            res = keep_first(res, QO_E_IO);
            p->active = 0;
            continue;
        }
        t = g->be.now_ns(g->be.ctx);
        if (g->cfg.joint[k].kind == QO_GPIO_SINK_SERVO_PWM) {
            if (p->rising) { p->rising = 0; p->next_ns = t + s->servo_width_ns; }
            else p->active = 0;
            continue;
        }
        if (p->rising) {
            s->position += p->sign;
            s->last_rise_ns = t;
            s->have_rise = 1;
            p->rising = 0;
            p->next_ns = t + s->high_ns;
        } else {
            uint64_t nt;
            p->done++;
            if (p->done >= p->n) { p->active = 0; continue; }
            nt = p->first_ns + p->done * p->spacing_ns;
            if (nt < s->last_rise_ns + s->min_spacing_ns) nt = s->last_rise_ns + s->min_spacing_ns;
            if (nt + s->high_ns > win_end) { p->active = 0; continue; } /* rest carried */
            p->rising = 1;
            p->next_ns = nt;
        }
    }
    return res;
}

qo_status qo_gpio_sink_write(qo_gpio_sink *g, const float *targets, size_t n, uint64_t tick)
{
    qo_status st;
    (void)tick;
    if (!g) return QO_E_NULL;
    if (!targets) st = QO_E_NULL;
    else if (!g->open) st = QO_E_STATE;
    else if (n != g->cfg.n_joints) st = QO_E_RANGE;
    else st = emit(g, targets, n);
    return qo_sink_view_count(&g->stats, st);
}

/* The qo_sink adapters: the void * of the sink interface stays in here, the public
 * functions take the typed handle (as the Modbus sink's do). */
QO_SINK_VIEW_ADAPTERS(gpio_sink, qo_gpio_sink)

static qo_status sink_stats(void *ctx, qo_sink_stats *out)
{
    return qo_gpio_sink_get_stats(ctx, out);
}

qo_status qo_gpio_sink_as_sink(qo_gpio_sink *g, qo_sink *out)
{
    /* flush, service: none (every write is emitted at once; no link to revive) */
    static const qo_sink ops = { .write = gpio_sink_view_write, .close = gpio_sink_view_close,
                                 .stats = sink_stats };
    return qo_sink_view_fill(g, &ops, out);
}

qo_status qo_gpio_sink_position(const qo_gpio_sink *g, size_t joint, int64_t *steps)
{
    if (steps) *steps = 0;
    if (!g || !steps) return QO_E_NULL;
    if (!g->open) return QO_E_STATE;
    if (joint >= g->cfg.n_joints || g->cfg.joint[joint].kind != QO_GPIO_SINK_STEP_DIR)
        return QO_E_RANGE;
    *steps = g->js[joint].position;
    return QO_OK;
}

qo_status qo_gpio_sink_get_stats(const qo_gpio_sink *g, qo_sink_stats *out)
{
    return qo_sink_view_stats(g != NULL ? &g->stats : NULL, out);
}

void qo_gpio_sink_close(qo_gpio_sink *g)
{
    if (!g || !g->open) return;
    close_all(g);
    g->open = 0;
    g->stats.connected = 0;
}

void qo_gpio_sink_free(qo_gpio_sink *g)
{
    if (!g) return;
    qo_gpio_sink_close(g);
    free(g);
}

/* ---- libgpiod backend ------------------------------------------------------------------ */

static int lg_slot(qo_gpio_sink_libgpiod *b)
{
    int i;
    for (i = 0; i < (int)QO_GPIO_SINK_MAX_LINES; i++)
        if (!b->used[i]) return i;
    return -1;
}

#if defined(QO_GPIOD_V2)
/* ==== libgpiod 2.x (Debian 13, Raspberry Pi OS trixie). Tested against the kernel's gpio-sim by
 * `make test-vm` in CI's trixie stage (tools/ci-trixie.sh); Debian 12 ships 1.6.3 (v1 below). ==== */

/* Opens a chip by path, by name under /dev, or by label (scanning /dev/gpiochip*). */
static struct gpiod_chip *lg2_open_chip(const char *desc)
{
    char path[280];
    struct gpiod_chip *c;
    DIR *d;
    struct dirent *e;
    if (desc[0] == '/') return gpiod_chip_open(desc);
    snprintf(path, sizeof path, "/dev/%s", desc);
    c = gpiod_chip_open(path);
    if (c) return c;
    d = opendir("/dev");
    if (!d) return NULL;
    while ((e = readdir(d)) != NULL) {
        struct gpiod_chip_info *info;
        int match = 0;
        if (strncmp(e->d_name, "gpiochip", 8) != 0) continue;
        snprintf(path, sizeof path, "/dev/%s", e->d_name);
        c = gpiod_chip_open(path);
        if (!c) continue;
        info = gpiod_chip_get_info(c);
        if (info) {
            match = strcmp(gpiod_chip_info_get_label(info), desc) == 0;
            gpiod_chip_info_free(info);
        }
        if (match) { closedir(d); return c; }
        gpiod_chip_close(c);
    }
    closedir(d);
    errno = ENOENT;
    return NULL;
}

/* Finds a line by name on any chip; returns its chip and sets *offset. */
static struct gpiod_chip *lg2_find_line(const char *name, unsigned *offset)
{
    char path[280];
    DIR *d = opendir("/dev");
    struct dirent *e;
    if (!d) return NULL;
    while ((e = readdir(d)) != NULL) {
        struct gpiod_chip *c;
        int off;
        if (strncmp(e->d_name, "gpiochip", 8) != 0) continue;
        snprintf(path, sizeof path, "/dev/%s", e->d_name);
        c = gpiod_chip_open(path);
        if (!c) continue;
        off = gpiod_chip_get_line_offset_from_name(c, name);
        if (off >= 0) { closedir(d); *offset = (unsigned)off; return c; }
        gpiod_chip_close(c);
    }
    closedir(d);
    errno = ENOENT;
    return NULL;
}

static qo_status lg_open(void *ctx, const qo_gpio_sink_line *line, int initial, int *handle)
{
    qo_gpio_sink_libgpiod *b = ctx;
    struct gpiod_chip *chip;
    struct gpiod_line_settings *ls = NULL;
    struct gpiod_line_config *lc = NULL;
    struct gpiod_request_config *rc = NULL;
    struct gpiod_line_request *req = NULL;
    unsigned off = line->offset;
    int err = 0;
    int slot = lg_slot(b);
    *handle = -1;
    if (slot < 0) return QO_E_CAPACITY;
    chip = line->name ? lg2_find_line(line->name, &off) : lg2_open_chip(line->chip);
    if (!chip) return QO_E_CONFIG;
    ls = gpiod_line_settings_new();
    lc = gpiod_line_config_new();
    rc = gpiod_request_config_new();
    if (ls && lc && rc &&
        gpiod_line_settings_set_direction(ls, GPIOD_LINE_DIRECTION_OUTPUT) == 0 &&
        gpiod_line_settings_set_output_value(ls, initial ? GPIOD_LINE_VALUE_ACTIVE
                                                         : GPIOD_LINE_VALUE_INACTIVE) == 0 &&
        gpiod_line_config_add_line_settings(lc, &off, 1, ls) == 0) {
        gpiod_request_config_set_consumer(rc, b->consumer);
        req = gpiod_chip_request_lines(chip, rc, lc);
        if (!req) err = errno; /* before the frees below can change it */
    }
    gpiod_request_config_free(rc);
    gpiod_line_config_free(lc);
    gpiod_line_settings_free(ls);
    /* A v2 request lives on without its chip object. */
    gpiod_chip_close(chip);
    if (!req) return err == EINVAL ? QO_E_CONFIG : QO_E_IO;
    b->line[slot] = req;
    b->chip[slot] = NULL;
    b->offset[slot] = off;
    b->used[slot] = 1;
    *handle = slot;
    return QO_OK;
}

static qo_status lg_set(void *ctx, int h, int v)
{
    qo_gpio_sink_libgpiod *b = ctx;
    if (h < 0 || h >= (int)QO_GPIO_SINK_MAX_LINES || !b->used[h]) return QO_E_ARG;
    return gpiod_line_request_set_value((struct gpiod_line_request *)b->line[h], b->offset[h],
                                        v ? GPIOD_LINE_VALUE_ACTIVE : GPIOD_LINE_VALUE_INACTIVE) == 0
               ? QO_OK : QO_E_IO;
}

static void lg_close(void *ctx, int h)
{
    qo_gpio_sink_libgpiod *b = ctx;
    if (h < 0 || h >= (int)QO_GPIO_SINK_MAX_LINES || !b->used[h]) return;
    gpiod_line_request_release((struct gpiod_line_request *)b->line[h]);
    b->used[h] = 0;
    b->line[h] = NULL;
}

const char *qo_gpio_sink_libgpiod_api(void) { return "v2"; }

#else
/* ==== libgpiod 1.6.x (v1 API, GPIO uAPI v1: needs CONFIG_GPIO_CDEV_V1) ==== */

static qo_status lg_open(void *ctx, const qo_gpio_sink_line *line, int initial, int *handle)
{
    qo_gpio_sink_libgpiod *b = ctx;
    struct gpiod_chip *chip = NULL;
    struct gpiod_line *l;
    int slot = lg_slot(b);
    *handle = -1;
    if (slot < 0) return QO_E_CAPACITY;
    if (line->name) {
        /* gpiod_line_find opens the chip; it is closed with the line below. */
        l = gpiod_line_find(line->name);
        if (!l) return QO_E_CONFIG;
        chip = gpiod_line_get_chip(l);
    } else {
        /* lookup accepts a name, a path, a label or a number */
        chip = gpiod_chip_open_lookup(line->chip);
        if (!chip) return QO_E_CONFIG;
        l = gpiod_chip_get_line(chip, line->offset);
        if (!l) { gpiod_chip_close(chip); return QO_E_CONFIG; }
    }
    if (gpiod_line_request_output(l, b->consumer, initial ? 1 : 0) != 0) {
        gpiod_chip_close(chip);
        return QO_E_IO;
    }
    b->chip[slot] = chip;
    b->line[slot] = l;
    b->offset[slot] = gpiod_line_offset(l);
    b->used[slot] = 1;
    *handle = slot;
    return QO_OK;
}

static qo_status lg_set(void *ctx, int h, int v)
{
    qo_gpio_sink_libgpiod *b = ctx;
    if (h < 0 || h >= (int)QO_GPIO_SINK_MAX_LINES || !b->used[h]) return QO_E_ARG;
    return gpiod_line_set_value((struct gpiod_line *)b->line[h], v ? 1 : 0) == 0 ? QO_OK : QO_E_IO;
}

static void lg_close(void *ctx, int h)
{
    qo_gpio_sink_libgpiod *b = ctx;
    if (h < 0 || h >= (int)QO_GPIO_SINK_MAX_LINES || !b->used[h]) return;
    gpiod_line_release((struct gpiod_line *)b->line[h]);
    gpiod_chip_close((struct gpiod_chip *)b->chip[h]);
    b->used[h] = 0;
    b->line[h] = NULL;
    b->chip[h] = NULL;
}

const char *qo_gpio_sink_libgpiod_api(void) { return "v1"; }
#endif

qo_status qo_gpio_sink_libgpiod_backend(qo_gpio_sink_libgpiod *store, const char *consumer,
                                        qo_gpio_sink_backend *be)
{
    if (be) memset(be, 0, sizeof *be);
    if (!store || !be) return QO_E_NULL;
    memset(store, 0, sizeof *store);
    store->consumer = consumer ? consumer : "qorient";
    be->ctx = store;
    be->open = lg_open;
    be->set_value = lg_set;
    be->close = lg_close;
    be->now_ns = qo_mono_clock_now_ns;
    be->sleep_until_ns = qo_mono_clock_sleep_until_ns;
    return QO_OK;
}
