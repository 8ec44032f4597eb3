/*
 * ports/linux/gpio_sink.h - a qo_sink that turns joint targets into step/dir pulses (or, as a
 * demo-grade option, hobby-servo PWM) on GPIO lines, through libgpiod or a fake backend.
 *
 * Index:
 *   qo_gpio_sink_line            how a line is found: chip (name, path or label) + offset, or
 *                                line name
 *   qo_gpio_sink_joint           per joint: kind, lines, steps per unit, max rate, dir setup,
 *                                invert
 *   qo_gpio_sink_config          period, pulse window, step high time, joints
 *   qo_gpio_sink_backend         pin toggling table: open, set_value, close (+ clock, sleep)
 *   qo_gpio_sink_config_default  const defaults of the config (every joint =
 *                                qo_gpio_sink_joint_default)
 *   qo_gpio_sink_joint_default   const defaults of one joint
 *   qo_gpio_sink                 the sink (opaque, on the heap: qo_gpio_sink_open allocates it)
 *   qo_gpio_sink_open()          check the config, open every line through the backend
 *   qo_gpio_sink_as_sink()       fills the qo_sink view of a sink (write, close, stats)
 *   qo_gpio_sink_write()         one tick: emit the owed steps / servo frame (the view's write)
 *   qo_gpio_sink_position()      steps emitted so far for a step/dir joint
 *   qo_gpio_sink_get_stats()     the common counters (qo_sink_stats)
 *   qo_gpio_sink_close()         drive step lines low and close every line (the view's close)
 *   qo_gpio_sink_free()          close, then free the object
 *   qo_gpio_sink_libgpiod_backend()  the libgpiod backend (v1 API default, v2 when QO_GPIOD_V2)
 *   qo_gpio_sink_libgpiod_api()  "v1" or "v2"
 *
 * Lifecycle, the same for the three sinks (linux/modbus_sink.h, linux/gpio_sink.h,
 * mock/mock_sink.h; only the mock lives in caller storage):
 *   open -> as_sink -> write ... -> close -> free
 *   - open: QO_OK and an open object; on error nothing stays open (*out is NULL here).
 *   - a NULL object: write, position, get_stats and as_sink return QO_E_NULL (their outputs
 *     zeroed); close and free do nothing.
 *   - a closed object: write and position return QO_E_STATE; get_stats still reports (QO_OK,
 *     connected 0); as_sink still fills the view (whose write then returns QO_E_STATE); a
 *     second close does nothing; free is the only other call left to make. A closed sink is
 *     not reopened: open a new one.
 *   - the same error gives the same status in every sink: a NULL pointer QO_E_NULL, a wrong
 *     number of targets QO_E_RANGE (nothing emitted), a closed sink QO_E_STATE.
 *
 * Step/dir model. Each joint keeps `position`, the signed count of steps emitted (positive =
 * positive joint direction). A tick with target x owes round(x * steps_per_unit) - position
 * steps (round half away from zero). It emits at most as many as fit the tick's pulse window
 * at the joint's max rate, and NEVER more: whatever is not emitted stays owed, and since the
 * next tick recomputes what is owed from its own target, the remainder is carried without a
 * burst (a stalled or jumping target is followed at max_rate, not faster). Precisely:
 *   - the window is [start, start + window * period), start = the backend clock when write is
 *     called; every pulse (rise to fall) lies inside it, so write returns before
 *     start + window * period and the streamer keeps (1 - window) of the period for itself;
 *   - consecutive rising edges of a joint are at least 1/max_rate_hz apart, also across ticks
 *     and also when an edge was late (the emitter reschedules from the ACTUAL edge times);
 *   - the n steps of a tick are spread evenly: rise_i = first + i * max(span / n, 1/max_rate),
 *     where first is the earliest allowed rise and span runs from first to the window end
 *     minus the high time;
 *   - when the direction changes, the dir line is set at the start of the tick and the first
 *     rise comes dir_setup_us later (at least); the dir line never changes while step is high.
 *     Direction level: 1 for positive steps, 0 for negative; invert_dir swaps them.
 * Step pulses are step_high_us high. Writes block for up to window * period while pulses go
 * out: user-space edges (one ioctl each) are only good for low rates (a few kHz at most, with
 * jitter of tens to hundreds of us on non-RT kernels).
 *
 * Servo PWM (QO_GPIO_SINK_SERVO_PWM, demo grade). One line per joint; every servo_frame_us (20000
 * = 50 Hz) a tick starts a pulse of width center + x * us_per_unit, clamped to [min, max] us
 * (1000..2000 typical). The pulse is timed by a user-space sleep, so its width jitters by the
 * wake-up latency (each us is ~0.1-0.2 degrees on a hobby servo): use hardware PWM or a
 * PCA9685 for anything but a demo. Frames are started by ticks, so the tick period must divide
 * the frame reasonably (e.g. 100-250 Hz); the pulse must fit the window (checked at open).
 *
 * Threads: a sink is used by one thread (the streamer's). The backend table is not called
 * concurrently by the sink.
 */
#ifndef QORIENT_GPIO_SINK_H
#define QORIENT_GPIO_SINK_H

#include <stddef.h>
#include <stdint.h>

#include "qorient/status.h"
#include "qorient/sink.h"

#ifdef __cplusplus
extern "C" {
#endif

#define QO_GPIO_SINK_MAX_JOINTS 32u
#define QO_GPIO_SINK_MAX_LINES (2u * QO_GPIO_SINK_MAX_JOINTS)

/*
 * A line: if `name` is not NULL the line is searched by its name (label) on every chip;
 * otherwise `chip` names the chip (a path "/dev/gpiochip0", a name "gpiochip0", or a chip
 * label such as "pinctrl-rp1", the robust choice on a Pi 5) and `offset` the line on it.
 */
typedef struct qo_gpio_sink_line {
    const char *chip;
    unsigned offset;
    const char *name;
} qo_gpio_sink_line;

typedef enum qo_gpio_sink_joint_kind {
    QO_GPIO_SINK_STEP_DIR = 0,
    QO_GPIO_SINK_SERVO_PWM = 1
} qo_gpio_sink_joint_kind;

typedef struct qo_gpio_sink_joint {
    qo_gpio_sink_joint_kind kind;
    qo_gpio_sink_line step;     /* step line; for a servo, the PWM line */
    qo_gpio_sink_line dir;      /* step/dir only */
    double steps_per_unit;      /* steps per joint unit (rad or m), finite, > 0 */
    double max_rate_hz;         /* max step rate, finite, > 0 */
    double dir_setup_us;        /* min time from a dir change to the next rise, [0, 1e6] */
    int invert_dir;             /* nonzero: dir level 0 for positive steps */
    double servo_center_us;     /* servo: pulse width at target 0 */
    double servo_us_per_unit;   /* servo: width change per joint unit (sign = direction) */
    double servo_min_us, servo_max_us; /* servo: clamp, 0 < min <= max */
} qo_gpio_sink_joint;

typedef struct qo_gpio_sink_config {
    double period_s;            /* the streamer period (s), finite, (0, 10] */
    double window;              /* fraction of the period pulses may use, (0, 1]; default 0.75 */
    double step_high_us;        /* step pulse high time, > 0, < 1/max_rate_hz; default 5 */
    double servo_frame_us;      /* servo frame, default 20000 (50 Hz) */
    size_t n_joints;            /* 1..QO_GPIO_SINK_MAX_JOINTS */
    qo_gpio_sink_joint joint[QO_GPIO_SINK_MAX_JOINTS];
} qo_gpio_sink_config;

/*
 * The pin backend. open() requests `line` as an output driven to `initial` (0/1) and returns a
 * small handle >= 0; set_value() drives it; close() releases it. now_ns/sleep_until_ns are the
 * clock the pulses are timed with (NULL: CLOCK_MONOTONIC and clock_nanosleep TIMER_ABSTIME);
 * sleep_until_ns returns 0 or an errno value (EINTR is retried by the sink).
 * A test backend records edges with the fake clock's timestamps.
 */
typedef struct qo_gpio_sink_backend {
    void *ctx;
    qo_status (*open)(void *ctx, const qo_gpio_sink_line *line, int initial, int *handle);
    qo_status (*set_value)(void *ctx, int handle, int value);
    void (*close)(void *ctx, int handle);
    uint64_t (*now_ns)(void *ctx);
    int (*sleep_until_ns)(void *ctx, uint64_t abs_ns);
} qo_gpio_sink_backend;

/* The sink: opaque (qo_gpio_sink_open allocates it, qo_gpio_sink_free frees it). */
typedef struct qo_gpio_sink qo_gpio_sink;

/*
 * Defaults, copied by value (cfg = qo_gpio_sink_config_default): period 0.002 s (500 Hz),
 * window 0.75, step_high_us 5, servo frame 20000 us, n_joints 0 and every joint =
 * qo_gpio_sink_joint_default: a step/dir joint with 200 steps/unit, 1000 Hz, dir setup 5 us, no
 * invert, servo 1500 +- 500 us/unit clamped to 1000..2000. Lines are left empty (chip NULL,
 * name NULL): set n_joints and each joint's lines.
 */
extern const qo_gpio_sink_config qo_gpio_sink_config_default;
extern const qo_gpio_sink_joint qo_gpio_sink_joint_default;

/*
 * Checks cfg, allocates the sink, then opens every line through be (step lines low; dir lines
 * at level 0, which counts as a direction change at open time for the setup delay). cfg and
 * *be are copied (the backend's ctx must outlive the sink). Returns QO_OK with *out set; on
 * error *out is NULL and nothing stays open (the lines already opened are closed again):
 * QO_E_NULL (cfg, be, out or a required backend function NULL, or a joint with neither chip
 * nor name); QO_E_TOO_FEW (n_joints 0); QO_E_CAPACITY (n_joints > QO_GPIO_SINK_MAX_JOINTS);
 * QO_E_LIMIT (period, window, rate, steps per unit, high time, setup or servo widths not
 * finite or out of range); QO_E_ARG (unknown joint kind); QO_E_CONFIG (high time not below
 * 1/max rate, high time + dir setup not below the window, a servo pulse that does not fit the
 * window or the frame, or the backend could not find a chip/line); QO_E_IO (the backend
 * failed otherwise, or no memory).
 */
qo_status qo_gpio_sink_open(const qo_gpio_sink_config *cfg, const qo_gpio_sink_backend *be,
                            qo_gpio_sink **out);

/* Fills *out (write, close, stats; flush and service NULL: every write is emitted at once and
 * there is no link to revive) with ctx = g. close is qo_gpio_sink_close (step/PWM lines driven
 * low, every line closed), so the object still needs qo_gpio_sink_free. Returns QO_OK;
 * QO_E_NULL if g or out is NULL (*out zeroed when out is not NULL). */
qo_status qo_gpio_sink_as_sink(qo_gpio_sink *g, qo_sink *out);

/*
 * One tick (the view's write). targets[j] in joint units; n must be cfg.n_joints. Emits the
 * pulses as described above and returns when the last one is done. Returns QO_OK; QO_E_NULL
 * (g or targets NULL); QO_E_STATE (closed); QO_E_RANGE (n differs from n_joints: nothing
 * emitted); QO_E_NONFINITE (a target NaN/Inf: that joint holds, the others run);
 * QO_E_OVERFLOW (a target whose step count exceeds +-2^53: that joint holds); QO_E_IO (a set_value failed:
 * that joint stops for this tick; position counts only the rises that succeeded). The first
 * error wins. Every call is counted in the statistics.
 */
qo_status qo_gpio_sink_write(qo_gpio_sink *g, const float *targets, size_t n, uint64_t tick);

/*
 * Steps emitted so far by a step/dir joint (signed, positive direction +1). Returns QO_OK;
 * QO_E_NULL; QO_E_STATE (closed); QO_E_RANGE (joint index out of range or a servo joint).
 * *steps is 0 on error.
 */
qo_status qo_gpio_sink_position(const qo_gpio_sink *g, size_t joint, int64_t *steps);

/* Copies the common counters (writes, ok, failed, consecutive failures; limited and
 * reconnects stay 0; connected 1 while open). QO_OK; QO_E_NULL if g or out is NULL (*out
 * zeroed when out is not NULL). */
qo_status qo_gpio_sink_get_stats(const qo_gpio_sink *g, qo_sink_stats *out);

/* Drives every step/PWM line low and closes all lines; later writes return QO_E_STATE.
 * Idempotent; NULL is ignored. */
void qo_gpio_sink_close(qo_gpio_sink *g);

/* Closes and frees. NULL is ignored. */
void qo_gpio_sink_free(qo_gpio_sink *g);

/* ---- libgpiod backend ------------------------------------------------------------------ */

/* Storage of the libgpiod backend (one per sink); members private. */
typedef struct qo_gpio_sink_libgpiod {
    void *chip[QO_GPIO_SINK_MAX_LINES];
    void *line[QO_GPIO_SINK_MAX_LINES]; /* v1: struct gpiod_line *;
                                           v2: struct gpiod_line_request * */
    unsigned offset[QO_GPIO_SINK_MAX_LINES];
    int used[QO_GPIO_SINK_MAX_LINES];
    const char *consumer;
} qo_gpio_sink_libgpiod;

/*
 * Fills *be with the libgpiod backend using *store (zeroed here) and consumer name `consumer`
 * (NULL: "qorient"); real clock. Built against the libgpiod v1 API (1.6.x, Debian bookworm)
 * unless QO_GPIOD_V2 is defined (set it when `pkg-config --atleast-version=2 libgpiod`); with
 * neither QO_GPIOD_V1 nor QO_GPIOD_V2 defined the header decides (only v1 defines
 * GPIOD_LINE_BULK_MAX_LINES). The backend's open returns QO_E_CONFIG when the chip or line
 * does not exist, QO_E_IO when the request fails (busy, permission), QO_E_CAPACITY when more
 * than QO_GPIO_SINK_MAX_LINES lines are open. Returns QO_OK or QO_E_NULL.
 */
qo_status qo_gpio_sink_libgpiod_backend(qo_gpio_sink_libgpiod *store, const char *consumer,
                                        qo_gpio_sink_backend *be);

/* "v1" or "v2": which libgpiod API this build uses. */
const char *qo_gpio_sink_libgpiod_api(void);

#ifdef __cplusplus
}
#endif
#endif /* QORIENT_GPIO_SINK_H */
