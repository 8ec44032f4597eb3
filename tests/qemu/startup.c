/*
 * Reset and fault handling for the core's tests on QEMU's Cortex-M boards (microbit: M0,
 * mps2-an386: M4F, mps2-an500: M7). newlib's rdimon crt0 `_start` (--specs=rdimon.specs) does the
 * rest: .bss, semihosting stdio, heap and stack from SYS_HEAPINFO, constructors, main and exit,
 * whose status becomes QEMU's exit status.
 */
#include <stdint.h>

extern void _start(void);
extern uint32_t __stack_top;

void Reset_Handler(void);
void Fault_Handler(void);

void Reset_Handler(void)
{
#if defined(__ARM_FP)
    /* CPACR: grant CP10/CP11 (the FPU), else the first FP instruction faults (NOCP) silently. */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm volatile("dsb\n\tisb" ::: "memory");
#endif
    _start();
}

/* Any fault: print nothing (the stack may be gone), end QEMU through semihosting
 * SYS_EXIT(ADP_Stopped_RunTimeError), which QEMU turns into exit status 1. */
void Fault_Handler(void)
{
    __asm volatile("movs r0, #0x18\n\tldr r1, =0x20023\n\tbkpt 0xab" ::: "r0", "r1", "memory");
    for (;;) {
    }
}

#define F ((uintptr_t)Fault_Handler)
__attribute__((section(".vectors"), used)) static const uintptr_t vectors[16] = {
    (uintptr_t)&__stack_top, (uintptr_t)Reset_Handler,
    F, F, F, F, F, 0, 0, 0, 0, /* NMI, HardFault, MemManage, BusFault, UsageFault, reserved */
    F, F, 0, F, F              /* SVCall, DebugMon, reserved, PendSV, SysTick */
};
