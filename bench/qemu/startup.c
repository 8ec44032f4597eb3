/* bench/qemu/startup.c - vector table and reset for the QEMU instruction-count images:
 * enable the FPU when there is one, then newlib's rdimon _start (.bss, semihosting argv,
 * exit status). Any fault exits QEMU with status 1 through semihosting. */
#include <stdint.h>

extern void _start(void);
extern uint32_t __stack_top;

void Reset_Handler(void);
void Fault_Handler(void);

void Reset_Handler(void)
{
#if defined(__ARM_FP)
    /* CPACR: enable CP10/CP11, else the first FP instruction faults (NOCP). */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm volatile("dsb\n\tisb");
#endif
    _start();
}

void Fault_Handler(void)
{
    __asm volatile("movs r0, #0x18\n\tldr r1, =0x20023\n\tbkpt 0xab" ::: "r0", "r1", "memory");
    for (;;) {}
}

#define F ((uintptr_t)Fault_Handler)
__attribute__((section(".vectors"), used)) const uintptr_t qo_bench_vectors[16] = {
    (uintptr_t)&__stack_top, (uintptr_t)Reset_Handler,
    F, F, F, F, F, 0, 0, 0, 0,
    F, F, 0, F, F };
