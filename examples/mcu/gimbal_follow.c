/*
 * examples/mcu/gimbal_follow.c - a bare-metal 3-axis gimbal that follows orientation
 * setpoints smoothly, using only the qorient core (Cortex-M0+ to Cortex-M7, no OS, no heap).
 *
 * What it shows
 *   - Setpoints arrive as quaternions in Q1.30 (from a host link, a joystick, a sensor fusion).
 *     qo_euler_from_quat_near_q30 (euler_fx.h) turns each one into the gimbal's joint angles -
 *     yaw, pitch, roll: intrinsic ZYX, outer to inner axis - choosing the solution nearest the
 *     previous setpoint's angles (so no joint turns further than it must; a joint with end stops
 *     goes round the other way when the short way is beyond its stop, see into_range), and
 *     inside the hold band around pitch = +-90 deg (gimbal lock) the roll joint stays put.
 *   - The main loop re-plans a jerk-limited move of the three joints from their current
 *     position, velocity and acceleration (motion.h, float32: no jump when a setpoint arrives
 *     mid-move) and exports it as a fixed-point table (qo_motion_export_q16).
 *   - The SysTick interrupt samples that table with qo_motion_sample_q16 (motion_fx.h): integer
 *     arithmetic only, so on a Cortex-M0+ without FPU the interrupt never runs soft-float code
 *     and its duration is short and bounded. It writes the angles as servo pulses.
 *   - Two tables and one pointer: the main loop fills the table the interrupt is NOT reading and
 *     then publishes it with one aligned 32-bit store; the interrupt reads the pointer once per
 *     tick. On a single core that is all the synchronisation needed (no lock, no disabling of
 *     interrupts).
 *
 * Tick: QO_EX_TICK_HZ = 1024 Hz, so one tick is exactly 64 LSB of Q16.16 seconds and the
 * interrupt forms the plan time with a shift, no division. With a core clock that is not a
 * multiple of 1024 Hz the tick is off by at most half a SysTick count (3 ppm at 84 MHz).
 *
 * Porting: everything that touches hardware is between the HARDWARE markers below
 * (hw_systick_start, hw_pwm_write_us, hw_lock_led, hw_setpoint_poll, hw_wait_for_interrupt).
 * Define QO_EX_EXTERNAL_HW to leave that block out and define those five static functions
 * before including this file: tests/examples/test_example_mcu.c runs the example on the host that way,
 * with a simulated clock and its own setpoints. The SysTick registers are architectural (the
 * same on every Cortex-M); the PWM is your timer's. Your vendor's startup file provides the
 * vector table that calls SysTick_Handler (on the RP2040 SDK the name is isr_systick). The
 * demo setpoint source replays a fixed list.
 *
 * Build (what tools/check-examples.sh does), e.g. for an RP2040 / STM32G0 class part:
 *   arm-none-eabi-gcc -mcpu=cortex-m0plus -mthumb -mfloat-abi=soft -std=c99 -O2 -Wall -Wextra \
 *       -Werror -ffp-contract=off -Ilib/include -c examples/mcu/gimbal_follow.c
 * then link with the core (every .c file in lib/src, or the CMake target `qorient`), -lm and
 * your startup code. Cost: the re-plan runs in float32 (software floating point on an M0+)
 * in the main loop, never in the interrupt; the interrupt's sampler is the integer code of
 * motion_fx.c.
 */
#include <stddef.h>
#include <stdint.h>

#include "qorient/euler_fx.h"
#include "qorient/fxconv.h"
#include "qorient/fxmath.h"
#include "qorient/motion.h"
#include "qorient/motion_fx.h"

#define QO_EX_AXES 3u                 /* yaw (outer), pitch, roll (inner) */
#define QO_EX_TICK_HZ 1024u           /* SysTick rate; 2^16 / 1024 = 64 exactly */
#define QO_EX_TICK_Q16 64             /* Q16.16 seconds per tick */
#define QO_EX_TICK_MAX ((1u << 25) - 1u) /* ticks that still fit Q16.16 seconds (32767 s) */
#define QO_EX_SETPOINT_TICKS (3u * QO_EX_TICK_HZ) /* demo: a new setpoint every 3 s */

/* A constant Q1.30 value from a decimal literal, rounded at compile time (no run-time float). */
#define QO_EX_Q30(x) ((qo_q30)((x) >= 0 ? (x) * 1073741824.0 + 0.5 : (x) * 1073741824.0 - 0.5))

/* Hold band around gimbal lock: 1 degree in Q3.28 rad (0.0174533 * 2^28). Inside it the roll
 * joint keeps its angle and yaw absorbs the rest, so the head does not spin its roll motor
 * when asked to look straight up. */
#define QO_EX_LOCK_BAND_Q28 ((qo_q28)4685082)

/* Servo scaling: 1500 us at 0 rad, 1000 us per pi rad (318.31 us/rad, in Q16.16), 500..2500 us. */
#define QO_EX_US_PER_RAD_Q16 ((qo_q16)20860757)
#define QO_EX_PULSE_MID_US 1500
#define QO_EX_PULSE_MIN_US 500
#define QO_EX_PULSE_MAX_US 2500

/* One published plan: the fixed-point table and the tick at which its local time 0 lies. */
struct gimbal_plan {
    qo_motion_seg_q16 segs[QO_EX_AXES * QO_MOTION_Q16_SEGS];
    qo_motion_table_q16 table;
    uint32_t tick0;
};

static struct gimbal_plan g_plan[2];
/* Read by the interrupt once per tick; written by the main loop only after the table it
 * points to is complete. NULL until the first plan exists. */
static const struct gimbal_plan *volatile g_active;
static volatile uint32_t g_ticks;

/* ================================ HARDWARE (board-specific) ================================ */
#ifndef QO_EX_EXTERNAL_HW

#ifndef QO_EX_CPU_HZ
#define QO_EX_CPU_HZ 48000000u        /* core clock that feeds SysTick */
#endif

/* SysTick, architectural on ARMv6-M and ARMv7-M. */
#define QO_EX_SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define QO_EX_SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define QO_EX_SYST_CVR (*(volatile uint32_t *)0xE000E018u)

/* Stand-ins for your timer's compare registers, so the example links and can be watched in
 * a debugger. Replace hw_pwm_write_us's body with e.g. TIM3->CCR1 = us (1 MHz timer clock). */
static volatile uint32_t g_pwm_us[QO_EX_AXES];
static volatile uint32_t g_lock_led;

static void hw_systick_start(void)
{
    QO_EX_SYST_RVR = (QO_EX_CPU_HZ + QO_EX_TICK_HZ / 2u) / QO_EX_TICK_HZ - 1u; /* 24-bit */
    QO_EX_SYST_CVR = 0u;
    QO_EX_SYST_CSR = 7u; /* processor clock, interrupt on, counter on */
}

static void hw_pwm_write_us(unsigned axis, uint32_t pulse_us)
{
    g_pwm_us[axis] = pulse_us;
}

static void hw_lock_led(int on)
{
    g_lock_led = on ? 1u : 0u;
}

static void hw_wait_for_interrupt(void)
{
    __asm__ volatile ("wfi");
}

/* Demo setpoint source: replays (yaw, pitch, roll) in degrees, every QO_EX_SETPOINT_TICKS.
 * A real one parses a frame from a UART/USB/CAN receive buffer. Returns 1 with *q set when a
 * new setpoint is there, else 0. */
static int hw_setpoint_poll(qo_quat_q30 *q)
{
    static const qo_quat_q30 demo[] = {
        /* 90, 0, 0 */
        { QO_EX_Q30(0.707106781), 0, 0, QO_EX_Q30(0.707106781) },
        /* 90, 30, -10 */
        { QO_EX_Q30(0.664463024), QO_EX_Q30(-0.241844763), QO_EX_Q30(0.122787804),
          QO_EX_Q30(0.696364240) },
        /* 0, 90, 0: gimbal lock */
        { QO_EX_Q30(0.707106781), 0, QO_EX_Q30(0.707106781), 0 },
        /* -60, -20, 25 */
        { QO_EX_Q30(0.851444315), QO_EX_Q30(0.099828525), QO_EX_Q30(-0.253394743),
          QO_EX_Q30(-0.448182941) },
        /* 160, 10, 0 */
        { QO_EX_Q30(0.172987394), QO_EX_Q30(-0.085831651), QO_EX_Q30(0.015134436),
          QO_EX_Q30(0.981060262) },
        /* -160, 10, 0: yaw goes round the other way (its stops are at +-172 deg) */
        { QO_EX_Q30(0.172987394), QO_EX_Q30(0.085831651), QO_EX_Q30(0.015134436),
          QO_EX_Q30(-0.981060262) },
        /* level */
        { QO_Q30_ONE, 0, 0, 0 },
    };
    static uint32_t next_tick = QO_EX_SETPOINT_TICKS;
    static size_t next;
    if ((int32_t)(g_ticks - next_tick) < 0) return 0;
    next_tick += QO_EX_SETPOINT_TICKS;
    *q = demo[next];
    next = (next + 1u) % (sizeof demo / sizeof demo[0]);
    return 1;
}

#endif /* QO_EX_EXTERNAL_HW */
/* ============================== END HARDWARE ============================================== */

/* Q16.16 radians -> servo pulse in us, clamped to the servo's range. */
static uint32_t pulse_from_rad_q16(qo_q16 rad)
{
    int64_t us_q16 = (int64_t)qo_fx_mul_q16(rad, QO_EX_US_PER_RAD_Q16)
                     + ((int64_t)QO_EX_PULSE_MID_US << 16) + 32768; /* + 0.5 us: rounds */
    if (us_q16 < ((int64_t)QO_EX_PULSE_MIN_US << 16)) return QO_EX_PULSE_MIN_US;
    if (us_q16 > ((int64_t)QO_EX_PULSE_MAX_US << 16)) return QO_EX_PULSE_MAX_US;
    return (uint32_t)(us_q16 >> 16); /* non-negative here */
}

void SysTick_Handler(void);

/* Every tick: integer-only sampling of the published plan. */
void SysTick_Handler(void)
{
    const struct gimbal_plan *p = g_active;
    uint32_t now = g_ticks + 1u;
    uint32_t dt;
    qo_q16 pos[QO_EX_AXES];
    qo_status st;
    unsigned axis;

    g_ticks = now;
    if (p == NULL) return;
    dt = now - p->tick0; /* modulo 2^32: right across the counter's wrap */
    if (dt > QO_EX_TICK_MAX) dt = QO_EX_TICK_MAX; /* long at rest: the end of the plan */
    st = qo_motion_sample_q16(&p->table, (qo_q16)dt * QO_EX_TICK_Q16, pos, NULL, NULL);
    /* QO_E_OVERFLOW only saturates an angle beyond +-32768 rad; anything else: hold. */
    if (st != QO_OK && st != QO_E_OVERFLOW) return;
    for (axis = 0; axis < QO_EX_AXES; axis++) hw_pwm_write_us(axis, pulse_from_rad_q16(pos[axis]));
}

/* Joint limits (rad, rad/s, rad/s^2, rad/s^3): yaw +-172 deg, pitch +-95 deg, roll +-46 deg. */
static const qo_motion_limits_f32 g_limits[QO_EX_AXES] = {
    { 3.0f, 20.0f, 200.0f, -3.0f, 3.0f, 0.0f, 0.0f, 0.0f },
    { 3.0f, 20.0f, 200.0f, -1.66f, 1.66f, 0.0f, 0.0f, 0.0f },
    { 4.0f, 30.0f, 300.0f, -0.8f, 0.8f, 0.0f, 0.0f, 0.0f },
};

/* An angle and the same angle +-2 pi give the same pose. When the solution nearest the previous
 * angles lies beyond a joint's range, the one a turn back is taken if it is inside: a yaw joint
 * with end stops then goes the long way round instead of pressing against its stop. */
static qo_q28 into_range(qo_q28 a, const qo_motion_limits_f32 *lim)
{
    const qo_q28 lo = qo_q28_from_f32(lim->pmin), hi = qo_q28_from_f32(lim->pmax);
    if (a > hi && (int64_t)a - QO_Q28_TWO_PI >= lo) return a - QO_Q28_TWO_PI;
    if (a < lo && (int64_t)a + QO_Q28_TWO_PI <= hi) return a + QO_Q28_TWO_PI;
    return a;
}

/* Exports the planner's current plan into the table the interrupt is not using and publishes
 * it. t0_tick is the tick the plan's local time 0 corresponds to. */
static void publish(const qo_motion_planner_f32 *pl, uint32_t t0_tick)
{
    struct gimbal_plan *b = (g_active == &g_plan[0]) ? &g_plan[1] : &g_plan[0];
    qo_status st = qo_motion_export_q16(pl, &b->table, b->segs, sizeof b->segs / sizeof b->segs[0]);
    if (st != QO_OK && st != QO_E_OVERFLOW) return; /* keep following the old plan */
    b->tick0 = t0_tick;
    /* The table's stores must be done before the pointer store: a compiler barrier suffices on
     * one core (an interrupt sees this core's stores in program order). */
    __asm__ volatile ("" ::: "memory");
    g_active = b;
}

int main(void)
{
    static qo_motion_joint_f32 joints[QO_EX_AXES]; /* 236 B each: not on the stack */
    static const float start[QO_EX_AXES] = { 0.0f, 0.0f, 0.0f };
    qo_motion_planner_f32 pl;
    uint32_t epoch = 0; /* tick of the planner's time 0 */

    /* Level at power-up; the first setpoint moves away from it. */
    if (qo_motion_init_f32(&pl, joints, QO_EX_AXES, g_limits, start, 0.0f, NULL) != QO_OK) {
        for (;;) hw_wait_for_interrupt(); /* only with bad limits above */
    }
    publish(&pl, epoch);
    hw_systick_start();

    for (;;) {
        qo_quat_q30 sp;
        qo_euler_q28 prev, e;
        qo_euler_info_q28 info;
        float target[QO_EX_AXES];
        uint32_t now;
        float t_now;
        qo_status st;

        if (!hw_setpoint_poll(&sp)) {
            hw_wait_for_interrupt();
            continue;
        }
        now = g_ticks;
        /* The planner keeps absolute float32 time: rebase it while at rest so its time stays
         * small (float32 resolution, see motion.h). (now - epoch) / 1024 is exact in float32
         * below 2^24 ticks (4.5 h of continuous motion). */
        t_now = (float)(now - epoch) * (1.0f / (float)QO_EX_TICK_HZ);
        if (qo_motion_done_f32(&pl, t_now)) {
            float at[QO_EX_AXES];
            if (qo_motion_sample_f32(&pl, t_now, at, NULL, NULL) == QO_OK &&
                qo_motion_init_f32(&pl, joints, QO_EX_AXES, g_limits, at, 0.0f, NULL) == QO_OK) {
                epoch = now;
                t_now = 0.0f;
            }
        }

        /* Joint angles of the setpoint nearest the current goals (the last clamped targets). */
        prev.a1 = qo_q28_from_f32(joints[0].goal);
        prev.a2 = qo_q28_from_f32(joints[1].goal);
        prev.a3 = qo_q28_from_f32(joints[2].goal);
        st = qo_euler_from_quat_near_q30(sp, QO_EULER_ZYX, prev, QO_EX_LOCK_BAND_Q28, &e, &info);
        /* QO_E_OVERFLOW: an angle was taken a turn back to fit Q3.28 (still the right pose);
         * QO_E_DEGENERATE: a zero quaternion - a corrupt frame; ignore it. */
        if (st != QO_OK && st != QO_E_OVERFLOW) continue;
        hw_lock_led(info.locked);

        target[0] = qo_q28_to_f32(into_range(e.a1, &g_limits[0]));
        target[1] = qo_q28_to_f32(into_range(e.a2, &g_limits[1]));
        target[2] = qo_q28_to_f32(into_range(e.a3, &g_limits[2]));
        /* Re-plan from the state at t_now (continuous position, velocity, acceleration).
         * The interrupt keeps sampling the old table until publish(): the two plans share the
         * state at t_now, and in the few ms the re-plan takes they part by only ~jmax dt^3 / 6.
         * Targets beyond the joint limits are clamped by the planner (mask not needed here). */
        if (qo_motion_set_target_f32(&pl, t_now, target, NULL) != QO_OK) continue;
        publish(&pl, now);
    }
}
