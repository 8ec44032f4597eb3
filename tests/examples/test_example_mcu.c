/*
 * tests/examples/test_example_mcu.c - runs examples/mcu/gimbal_follow.c on the host: the example is
 * included with QO_EX_EXTERNAL_HW, and the five hardware functions below simulate its clock
 * (each wait-for-interrupt is one SysTick), its setpoint link and its servos.
 *
 * Setpoints (yaw, pitch, roll in degrees, intrinsic ZYX) arrive every 3 s; just before the
 * next one, the servo pulses must show the setpoint's pose: the three commanded angles (read
 * back from the pulses, 1 us = 3.14 mrad) composed in double must be within 0.012 rad of the
 * setpoint quaternion. Also checked on every tick: pulses in 500..2500 us and no pulse step
 * above what the joints' velocity limits allow; at the gimbal-lock setpoint (pitch 90) the roll
 * joint holds its previous angle and the lock LED is on; a corrupt (zero) setpoint is ignored;
 * yaw from +160 to -160 deg goes the long way round inside its +-172 deg range.
 * The references (quaternions, angle between rotations) are double-precision code of this test.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include <cmocka.h>

#define QO_EX_EXTERNAL_HW 1
#include "qorient/types.h"

/* ---- the simulated hardware (defined before the example, which calls it) ---- */
struct setpoint { double yaw, pitch, roll; int zero; };
static const struct setpoint sim_sp[] = {
    { 90, 0, 0, 0 }, { 90, 30, -10, 0 }, { 0, 90, 0, 0 }, { -60, -20, 25, 0 },
    { 160, 10, 0, 0 }, { -160, 10, 0, 0 }, { 0, 0, 0, 1 } /* corrupt frame */, { 0, 0, 0, 0 },
};
#define SIM_N (sizeof sim_sp / sizeof sim_sp[0])
#define SIM_PERIOD 3072u /* ticks between setpoints (3 s at 1024 Hz) */

static uint32_t sim_pwm[3], sim_prev_pwm[3];
static int sim_have_pwm, sim_led;
static size_t sim_next;
static jmp_buf sim_done;
static int sim_failures;
static double sim_max_err;

static void SysTick_Handler_fwd(void);

static void hw_systick_start(void) {}
static void hw_pwm_write_us(unsigned axis, uint32_t pulse_us) { sim_pwm[axis] = pulse_us; }
static void hw_lock_led(int on) { sim_led = on; }

static void q_from_zyx(double y, double p, double r, double q[4])
{
    const double cy = cos(y / 2), sy = sin(y / 2), cp = cos(p / 2), sp = sin(p / 2);
    const double cr = cos(r / 2), sr = sin(r / 2);
    q[0] = cy * cp * cr + sy * sp * sr;
    q[1] = cy * cp * sr - sy * sp * cr;
    q[2] = cy * sp * cr + sy * cp * sr;
    q[3] = sy * cp * cr - cy * sp * sr;
}

static const double DEG = 3.14159265358979323846 / 180.0;

static int hw_setpoint_poll(qo_quat_q30 *q);
static void hw_wait_for_interrupt(void);

#define main gimbal_main
int gimbal_main(void);
#include "../examples/mcu/gimbal_follow.c"
#undef main

static int hw_setpoint_poll(qo_quat_q30 *q)
{
    double d[4];
    const struct setpoint *s;
    if (sim_next >= SIM_N || g_ticks < (sim_next + 1u) * SIM_PERIOD) return 0;
    s = &sim_sp[sim_next++];
    if (s->zero) {
        q->w = q->x = q->y = q->z = 0;
        return 1;
    }
    q_from_zyx(s->yaw * DEG, s->pitch * DEG, s->roll * DEG, d);
    q->w = (qo_q30)lround(d[0] * 1073741824.0);
    q->x = (qo_q30)lround(d[1] * 1073741824.0);
    q->y = (qo_q30)lround(d[2] * 1073741824.0);
    q->z = (qo_q30)lround(d[3] * 1073741824.0);
    return 1;
}

static double pulse_rad(uint32_t us)
{
    return ((double)us - 1500.0) / (1000.0 / 3.14159265358979323846);
}

/* The pose expected just before setpoint k+1: setpoint k, or for a corrupt frame the one before. */
static const struct setpoint *expected(size_t k)
{
    while (sim_sp[k].zero && k > 0) k--;
    return &sim_sp[k];
}

static void check_pose(size_t k)
{
    const struct setpoint *e = expected(k);
    double want[4], got[4], dot, ang;
    q_from_zyx(e->yaw * DEG, e->pitch * DEG, e->roll * DEG, want);
    q_from_zyx(pulse_rad(sim_pwm[0]), pulse_rad(sim_pwm[1]), pulse_rad(sim_pwm[2]), got);
    dot = fabs(want[0] * got[0] + want[1] * got[1] + want[2] * got[2] + want[3] * got[3]);
    ang = 2.0 * acos(dot > 1.0 ? 1.0 : dot);
    if (ang > sim_max_err) sim_max_err = ang;
    if (ang > 0.012) {
        print_error("setpoint %zu (yaw %g pitch %g roll %g deg%s): servos at %u %u %u us = "
                    "(%.4f, %.4f, %.4f) rad, %.4f rad from the setpoint\n", k, e->yaw, e->pitch,
                    e->roll, sim_sp[k].zero ? ", after a zero frame" : "", sim_pwm[0], sim_pwm[1],
                    sim_pwm[2], pulse_rad(sim_pwm[0]), pulse_rad(sim_pwm[1]), pulse_rad(sim_pwm[2]),
                    ang);
        sim_failures++;
    }
    if (e->pitch == 90.0) { /* lock: roll held at the previous setpoint's -10 deg, LED on */
        if (fabs(pulse_rad(sim_pwm[2]) - (-10.0 * DEG)) > 0.004 || !sim_led) {
            print_error("setpoint %zu at gimbal lock: roll %.4f rad (want the held -0.1745), "
                        "LED %d\n", k, pulse_rad(sim_pwm[2]), sim_led);
            sim_failures++;
        }
    }
    if (e->yaw == -160.0 && pulse_rad(sim_pwm[0]) > 0.0) {
        print_error("setpoint %zu: yaw %.4f rad: pressed against the +stop instead of going "
                    "round\n", k, pulse_rad(sim_pwm[0]));
        sim_failures++;
    }
}

/* One simulated tick per wait: the interrupt runs, then the per-tick and checkpoint checks. */
static void hw_wait_for_interrupt(void)
{
    unsigned a;
    SysTick_Handler_fwd();
    for (a = 0; a < 3; a++) {
        /* vmax 3 / 3 / 4 rad/s at 1024 Hz and 318.3 us/rad: <= 1.25 us per tick, +1 rounding */
        const uint32_t step_max = 3u;
        uint32_t d;
        if (sim_pwm[a] < 500u || sim_pwm[a] > 2500u) {
            print_error("tick %u: axis %u pulse %u us outside 500..2500\n", (unsigned)g_ticks, a,
                        (unsigned)sim_pwm[a]);
            sim_failures++;
        }
        d = sim_pwm[a] > sim_prev_pwm[a] ? sim_pwm[a] - sim_prev_pwm[a]
                                         : sim_prev_pwm[a] - sim_pwm[a];
        if (sim_have_pwm && d > step_max) {
            print_error("tick %u: axis %u jumped %u us (%u -> %u)\n", (unsigned)g_ticks, a,
                        (unsigned)d, (unsigned)sim_prev_pwm[a], (unsigned)sim_pwm[a]);
            sim_failures++;
        }
        sim_prev_pwm[a] = sim_pwm[a];
    }
    sim_have_pwm = 1;
    if (g_ticks % SIM_PERIOD == SIM_PERIOD - 1u && g_ticks > SIM_PERIOD)
        check_pose(g_ticks / SIM_PERIOD - 1u);
    if (g_ticks >= (SIM_N + 1u) * SIM_PERIOD) longjmp(sim_done, 1);
}

static void SysTick_Handler_fwd(void) { SysTick_Handler(); }

static void test_gimbal_follows_setpoints(void **state)
{
    (void)state;
    if (setjmp(sim_done) == 0) {
        gimbal_main();
        fail_msg("the example's main returned");
    }
    print_message("gimbal_follow on the host: %zu setpoints, worst pose error %.4f rad (pulse "
                  "resolution 3.1 mrad per joint)\n", SIM_N, sim_max_err);
    assert_int_equal(sim_next, SIM_N);
    assert_int_equal(sim_failures, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_gimbal_follows_setpoints),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
