/*
 * examples/platformio/src/main.c - qorient as a PlatformIO library: a pan-tilt head that
 * repeats a smooth scan pattern, planned once at start-up and sampled in the SysTick interrupt
 * with the fixed-point keyframe sampler (spline_fx.h).
 *
 *   start-up:  a C2 cubic spline through five keyframes of two joints (float32, once:
 *              qo_spline_init_f32), converted to a Q16.16 table (qo_spline_export_q16);
 *   interrupt: qo_spline_sample_q16 at the tick's time in the pattern (integer only), the two
 *              angles written as servo pulses.
 * The pattern starts and ends at rest at the same pose, so repeating it never jumps.
 *
 * Environments (platformio.ini): nucleo_f401re (Cortex-M4F, framework stm32cube: the CMSIS
 * startup calls main, SysTick is ours because this program does not use the HAL's tick) and
 * pico (RP2040, Cortex-M0+, Arduino-Pico core: the core owns main and calls setup()/loop(); the
 * SDK names the SysTick vector isr_systick). Without either (tools/check-examples.sh) it is a
 * plain bare-metal program with main(). Hardware access is in the HARDWARE block only.
 */
#include <stddef.h>
#include <stdint.h>

#include "qorient/fxmath.h"
#include "qorient/spline.h"
#include "qorient/spline_fx.h"

#define QO_EX_JOINTS 2u               /* pan, tilt */
#define QO_EX_KEYS 5u
#define QO_EX_TICK_HZ 1024u           /* 2^16 / 1024 = 64: tick -> Q16.16 s by a multiply */
#define QO_EX_TICK_Q16 64
#define QO_EX_PATTERN_S 6u            /* the pattern's length, the last key time */

/* Keyframes: time (s), then pan and tilt (rad) per key. */
static const float g_key_t[QO_EX_KEYS] = { 0.0f, 1.5f, 3.0f, 4.5f, 6.0f };
static const float g_key_p[QO_EX_KEYS * QO_EX_JOINTS] = {
    0.0f, 0.0f,
    1.2f, 0.3f,
    1.2f, -0.4f,
    -1.2f, 0.2f,
    0.0f, 0.0f,
};

/* The sampler's table (5K + 3N + 7KN = 101 words) and its descriptor. The interrupt reads
 * g_plan_ready before the table: it is set once, after the table is complete. */
static int32_t g_table[QO_EX_KEYS * 5u + QO_EX_JOINTS * 3u + QO_EX_KEYS * QO_EX_JOINTS * 7u];
static qo_spline_table_q16 g_plan;
static volatile int g_plan_ready;
static volatile uint32_t g_ticks;

/* ================================ HARDWARE (board-specific) ================================ */

#if defined(QO_EX_CMSIS_CLOCK)
extern uint32_t SystemCoreClock;      /* CMSIS system_<device>.c: the core clock in Hz */
#define QO_EX_CPU_HZ ((uint32_t)SystemCoreClock)
#elif defined(F_CPU)
#define QO_EX_CPU_HZ ((uint32_t)F_CPU)
#else
#define QO_EX_CPU_HZ 48000000u
#endif

#if defined(ARDUINO_ARCH_RP2040)
#define SysTick_Handler isr_systick   /* the pico SDK's name for the SysTick vector */
#endif

#define QO_EX_SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define QO_EX_SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define QO_EX_SYST_CVR (*(volatile uint32_t *)0xE000E018u)

/* Stand-in for the PWM compare registers (replace with your timer's, 1 MHz clock). */
static volatile uint32_t g_pwm_us[QO_EX_JOINTS];

static void hw_systick_start(void)
{
    QO_EX_SYST_RVR = (QO_EX_CPU_HZ + QO_EX_TICK_HZ / 2u) / QO_EX_TICK_HZ - 1u;
    QO_EX_SYST_CVR = 0u;
    QO_EX_SYST_CSR = 7u; /* processor clock, interrupt, enable */
}

static void hw_pwm_write_us(unsigned joint, uint32_t us)
{
    g_pwm_us[joint] = us;
}

static void hw_idle(void)
{
    __asm__ volatile ("wfi");
}

/* ============================== END HARDWARE ============================================== */

void SysTick_Handler(void);

void SysTick_Handler(void)
{
    uint32_t now = g_ticks + 1u;
    qo_q16 pos[QO_EX_JOINTS];
    unsigned j;

    g_ticks = now;
    if (!g_plan_ready) return;
    /* Time within the pattern, Q16.16 s: the remainder keeps it below 6 s however long the
     * board runs. */
    if (qo_spline_sample_q16(&g_plan,
                             (qo_q16)(now % (QO_EX_PATTERN_S * QO_EX_TICK_HZ)) * QO_EX_TICK_Q16,
                             pos, NULL, NULL, NULL) != QO_OK)
        return; /* hold the last pulses */
    for (j = 0; j < QO_EX_JOINTS; j++) {
        /* 1500 us + 318.31 us/rad (1000 us per pi rad), rounded; |pos| <= 1.2 rad here. */
        int32_t us = (qo_fx_mul_q16(pos[j], (qo_q16)20860757) + (1500 << 16) + 32768) >> 16;
        hw_pwm_write_us(j, (uint32_t)us);
    }
}

/* Plans the pattern once. Returns 0, or -1 if the keyframes above are wrong. */
static int app_init(void)
{
    static float coef[QO_EX_KEYS + 3u * QO_EX_JOINTS + 6u * QO_EX_KEYS * QO_EX_JOINTS];
    qo_spline_f32 plan;

    if (qo_spline_init_f32(QO_EX_JOINTS, QO_EX_KEYS, g_key_t, g_key_p, &qo_spline_settings_default,
                           coef, sizeof coef / sizeof coef[0], &plan) != QO_OK)
        return -1;
    if (qo_spline_export_q16(&plan, &g_plan, g_table, sizeof g_table / sizeof g_table[0]) != QO_OK)
        return -1;
    __asm__ volatile ("" ::: "memory"); /* the table is complete before the flag is set */
    g_plan_ready = 1;
    hw_systick_start();
    return 0;
}

#if defined(ARDUINO)
void setup(void);
void loop(void);

void setup(void)
{
    (void)app_init();
}

void loop(void)
{
    hw_idle();
}
#else
int main(void)
{
    (void)app_init(); /* on failure the interrupt never starts: the servos get no pulses */
    for (;;) hw_idle();
}
#endif
