#!/bin/sh
# Instruction counts per call of fixed-point (qorient *_fx.c) vs float32 soft-float operations
# on an emulated Cortex-M0 (qemu-system-arm -M microbit; code built for cortex-m0plus, ARMv6-M,
# which QEMU 7.2 runs on its cortex-m0 model).
#
#   sh tools/qemu-icount.sh            # all operations, K = 16 calls each (~3-5 min)
#   K=64 sh tools/qemu-icount.sh       # more calls (longer)
#   OPS="9 10 11 12" sh tools/qemu-icount.sh   # only the listed operation numbers (see below)
#
# Method (see /work/shared/research/feasibility-cross.md section 4): each operation gets a tiny
# semihosting program, built twice: with its loop calling the operation 0 and K times. QEMU runs
# it with one instruction per translation block and logs every executed instruction
# (-singlestep -d exec,nochain); (lines(K) - lines(0)) / K is the count per call. The loop body
# (load one of 8 inputs, call, store to a volatile) is included: the "loop" row measures it
# alone. Counts are exact and repeatable; they are INSTRUCTIONS, not cycles (QEMU is not
# cycle-accurate; on M0/M0+ most instructions take 1 cycle, loads/stores 2, taken branches 3).
# Float rows use newlib's libm (sinf, atan2f, ...) and the soft-float __aeabi_f* helpers of
# libgcc, i.e. what an FPU-less part runs when it uses float32.
set -eu
K=${K:-16}
OUT=${BUILD:-build}/qemu-icount
mkdir -p "$OUT"
CC=arm-none-eabi-gcc
CPU="-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft"
for tool in $CC qemu-system-arm; do
    command -v $tool >/dev/null || { echo "qemu-icount: $tool not found" >&2; exit 2; }
done

cat > "$OUT/startup.c" <<'EOF'
#include <stdint.h>
extern void _start(void);
extern uint32_t __stack_top;
void Reset_Handler(void);
void Fault_Handler(void);
void Reset_Handler(void) { _start(); }
void Fault_Handler(void)
{
    __asm volatile("movs r0, #0x18\n\tldr r1, =0x20023\n\tbkpt 0xab" ::: "r0", "r1", "memory");
    for (;;) {}
}
#define F ((uintptr_t)Fault_Handler)
__attribute__((section(".vectors"), used)) const uintptr_t vectors[16] = {
    (uintptr_t)&__stack_top, (uintptr_t)Reset_Handler, F, F, F, F, F, 0, 0, 0, 0, F, F, 0, F, F };
EOF

cat > "$OUT/cm.ld" <<'EOF'
MEMORY {
  FLASH (rx)  : ORIGIN = 0x00000000, LENGTH = 256K
  RAM   (rwx) : ORIGIN = 0x20000000, LENGTH = 16K }
ENTRY(Reset_Handler)
SECTIONS {
  .text : { KEEP(*(.vectors)) *(.text .text.*) KEEP(*(.init)) KEEP(*(.fini)) *(.rodata .rodata.*)
    . = ALIGN(4);
    PROVIDE_HIDDEN(__preinit_array_start = .); KEEP(*(.preinit_array)) PROVIDE_HIDDEN(__preinit_array_end = .);
    PROVIDE_HIDDEN(__init_array_start = .); KEEP(*(SORT(.init_array.*))) KEEP(*(.init_array)) PROVIDE_HIDDEN(__init_array_end = .);
    PROVIDE_HIDDEN(__fini_array_start = .); KEEP(*(.fini_array)) PROVIDE_HIDDEN(__fini_array_end = .);
  } > FLASH
  .ARM.exidx : { *(.ARM.exidx* .gnu.linkonce.armexidx.*) } > FLASH
  .data : { *(.data .data.*) } > RAM
  .bss (NOLOAD) : { . = ALIGN(4); __bss_start__ = .; *(.bss .bss.* COMMON) . = ALIGN(4); __bss_end__ = .; } > RAM
  . = ALIGN(8); PROVIDE(end = .); PROVIDE(__end__ = .);
  __stack_top = ORIGIN(RAM) + LENGTH(RAM); PROVIDE(__stack = __stack_top);
}
EOF

# One program, the operation chosen by -DOP=n. Inputs are 8 fixed values per kind, cycled, so
# data-dependent paths (quadrants, octants, pivots) are exercised rather than one lucky case.
cat > "$OUT/ops.c" <<'EOF'
#include <math.h>
#include <stdint.h>
#include "qorient/convert_fx.h"
#include "qorient/euler.h"
#include "qorient/euler_fx.h"
#include "qorient/fxmath.h"
#include "qorient/interp.h"
#include "qorient/quat.h"
#include "qorient/quat_fx.h"
#if HAVE_INTERP_FX
#include "qorient/interp_fx.h"
#endif
volatile int32_t sink_i;
volatile float sink_f;
static const float af[8] = { 0.1f, -0.7f, 1.3f, 2.9f, -2.2f, 0.001f, 3.1f, -1.57f };
static const float uf[8] = { 0.1f, -0.7f, 0.3f, 0.99f, -0.2f, 0.001f, 0.5f, -0.95f };
static const float pf[8] = { 0.1f, 0.7f, 1.3f, 1.9f, 0.2f, 0.001f, 1.1f, 1.57f };
static const qo_quat_f32 qf[8] = {
    { 0.5f, 0.5f, 0.5f, 0.5f }, { 0.9f, 0.1f, -0.3f, 0.3f }, { -0.2f, 0.7f, 0.1f, 0.68f },
    { 0.0f, 0.0f, 1.0f, 0.0f }, { 0.99f, 0.01f, 0.1f, 0.0f }, { 0.3f, -0.3f, 0.3f, -0.85f },
    { 0.6f, 0.6f, -0.4f, 0.35f }, { -0.7f, 0.1f, 0.7f, 0.1f } };
/* Euler sequences cycled with the inputs: Tait-Bryan and proper, extrinsic and intrinsic. */
static const qo_euler_seq seqs[8] = { QO_EULER_ZYX, QO_EULER_xyz, QO_EULER_ZXZ, QO_EULER_yzy,
    QO_EULER_XYZ, QO_EULER_zyx, QO_EULER_YXY, QO_EULER_xzx };
static const float tf[8] = { 0.5f, 0.1f, 0.9f, 0.33f, 0.75f, 0.01f, 0.6f, 0.25f };
static const qo_vec3_f32 vf[8] = {
    { 1, 0, 0 }, { 0.3f, 0.4f, 0.5f }, { -0.5f, 0.5f, 0.7f }, { 0, 0, 1 }, { 0.1f, -0.9f, 0.2f },
    { 0.6f, 0.6f, 0.5f }, { -0.2f, 0.1f, -0.9f }, { 0.7f, 0.0f, -0.7f } };
/* Fixed inputs as constant initialisers (no start-up code that the K = 0 build could drop). */
#define Q30(v) ((int32_t)((v) * 1073741824.0))
#define Q28(v) ((int32_t)((v) * 268435456.0))
#define QQ(w, x, y, z) { Q30(w), Q30(x), Q30(y), Q30(z) }
static const int32_t ti[8] = { Q30(0.5), Q30(0.1), Q30(0.9), Q30(0.33), Q30(0.75), Q30(0.01), Q30(0.6), Q30(0.25) };
static const int32_t ai[8] = { Q28(0.1), Q28(-0.7), Q28(1.3), Q28(2.9), Q28(-2.2), Q28(0.001), Q28(3.1), Q28(-1.57) };
static const int32_t ui[8] = { Q30(0.1), Q30(-0.7), Q30(0.3), Q30(0.99), Q30(-0.2), Q30(0.001), Q30(0.5), Q30(-0.95) };
static const int32_t pi30[8] = { Q30(0.1), Q30(0.7), Q30(1.3), Q30(1.9), Q30(0.2), Q30(0.001), Q30(1.1), Q30(1.57) };
static const qo_quat_q30 qi[8] = {
    QQ(0.5, 0.5, 0.5, 0.5), QQ(0.9, 0.1, -0.3, 0.3), QQ(-0.2, 0.7, 0.1, 0.68), QQ(0.0, 0.0, 1.0, 0.0),
    QQ(0.99, 0.01, 0.1, 0.0), QQ(0.3, -0.3, 0.3, -0.85), QQ(0.6, 0.6, -0.4, 0.35), QQ(-0.7, 0.1, 0.7, 0.1) };
static const qo_vec3_q30 vi[8] = {
    { Q30(1), 0, 0 }, { Q30(0.3), Q30(0.4), Q30(0.5) }, { Q30(-0.5), Q30(0.5), Q30(0.7) }, { 0, 0, Q30(1) },
    { Q30(0.1), Q30(-0.9), Q30(0.2) }, { Q30(0.6), Q30(0.6), Q30(0.5) }, { Q30(-0.2), Q30(0.1), Q30(-0.9) },
    { Q30(0.7), 0, Q30(-0.7) } };
static const qo_vec3_q28 ri[8] = {
    { Q28(1), 0, 0 }, { Q28(0.3), Q28(0.4), Q28(0.5) }, { Q28(-0.5), Q28(0.5), Q28(0.7) }, { 0, 0, Q28(1) },
    { Q28(0.1), Q28(-0.9), Q28(0.2) }, { Q28(0.6), Q28(0.6), Q28(0.5) }, { Q28(-0.2), Q28(0.1), Q28(-0.9) },
    { Q28(0.7), 0, Q28(-0.7) } };
int main(void)
{
    int i;
    for (i = 0; i < K; i++) {
        int j = i & 7;
#if OP == 0
        sink_i = ai[j];
#elif OP == 1
        qo_q30 s, c; (void)qo_fx_sincos_q28(ai[j], &s, &c); sink_i = s + c;
#elif OP == 2
        sink_f = sinf(af[j]) + cosf(af[j]);
#elif OP == 3
        sink_i = qo_fx_atan2_q28(ui[j], ui[(j + 3) & 7]);
#elif OP == 4
        sink_f = atan2f(uf[j], uf[(j + 3) & 7]);
#elif OP == 5
        qo_q30 r; (void)qo_fx_sqrt_q30(pi30[j], &r); sink_i = r;
#elif OP == 6
        sink_f = sqrtf(pf[j]);
#elif OP == 7
        sink_i = qo_fx_asin_q28(ui[j]);
#elif OP == 8
        sink_f = asinf(uf[j]);
#elif OP == 9
        qo_quat_q30 r = qo_quat_mul_q30(qi[j], qi[(j + 1) & 7]); sink_i = r.w + r.x + r.y + r.z;
#elif OP == 10
        qo_quat_f32 r = qo_quat_mul_f32(qf[j], qf[(j + 1) & 7]); sink_f = r.w + r.x + r.y + r.z;
#elif OP == 11
        qo_quat_q30 r; (void)qo_quat_normalize_q30(qi[j], &r); sink_i = r.w + r.x + r.y + r.z;
#elif OP == 12
        qo_quat_f32 r; (void)qo_quat_normalize_f32(qf[j], &r); sink_f = r.w + r.x + r.y + r.z;
#elif OP == 13
        qo_vec3_q30 r = qo_quat_rotate_q30(qi[j], vi[j]); sink_i = r.x + r.y + r.z;
#elif OP == 14
        qo_vec3_f32 r = qo_quat_rotate_f32(qf[j], vf[j]); sink_f = r.x + r.y + r.z;
#elif OP == 15
        qo_quat_q30 r; (void)qo_rotvec_to_quat_q30(ri[j], &r); sink_i = r.w + r.x + r.y + r.z;
#elif OP == 16
        qo_mat3_q30 m; (void)qo_mat3_from_quat_q30(qi[j], &m); sink_i = m.m[0][0] + m.m[1][2];
#elif OP == 17
        qo_quat_q30 r; qo_mat3_q30 m; (void)qo_mat3_from_quat_q30(qi[j], &m);
        (void)qo_mat3_to_quat_q30(&m, &r); sink_i = r.w;
#elif OP == 18
        qo_euler_q28 e; (void)qo_euler_from_quat_q30(qi[j], seqs[j], &e, NULL); sink_i = e.a1 + e.a2 + e.a3;
#elif OP == 19
        qo_euler_f32 e; (void)qo_euler_from_quat_f32(qf[j], seqs[j], &e, NULL); sink_f = e.a1 + e.a2 + e.a3;
#elif OP == 20 && HAVE_INTERP_FX
        qo_quat_q30 r; (void)qo_interp_slerp_q30(qi[j], qi[(j + 1) & 7], ti[j], &r); sink_i = r.w + r.x + r.y + r.z;
#elif OP == 21
        qo_quat_f32 r; (void)qo_interp_slerp_f32(qf[j], qf[(j + 1) & 7], tf[j], &r); sink_f = r.w + r.x + r.y + r.z;
#elif OP == 22
        qo_quat_q30 r; (void)qo_quat_normalize_fast_q30(qi[j], &r); sink_i = r.w + r.x + r.y + r.z;
#elif OP == 23 && HAVE_INTERP_FX
        qo_quat_q30 r; (void)qo_interp_slerp_fast_q30(qi[j], qi[(j + 1) & 7], ti[j], &r); sink_i = r.w + r.x + r.y + r.z;
#elif OP == 24
        qo_euler_q28 e; (void)qo_euler_from_quat_fast_q30(qi[j], seqs[j], QO_EULER_LOCK_BAND_Q28, &e, NULL); sink_i = e.a1 + e.a2 + e.a3;
#endif
    }
    return 0;
}
EOF

FX_SRC="lib/src/fxmath_fx.c lib/src/quat_fx.c lib/src/convert_fx.c lib/src/euler_fx.c lib/src/euler_seq.c"
F32_SRC="lib/src/quat.c lib/src/euler.c lib/src/interp.c lib/src/fmath.c lib/src/status.c"
HAVE_INTERP_FX=0
if [ -f lib/src/interp_fx.c ]; then FX_SRC="$FX_SRC lib/src/interp_fx.c"; HAVE_INTERP_FX=1; fi
run_count() { # op k -> executed instruction count
    elf="$OUT/op$1_k$2.elf"
    $CC $CPU -std=c99 -O2 -ffunction-sections -fdata-sections -Ilib/include -DOP=$1 -DK=$2 \
        -DHAVE_INTERP_FX=$HAVE_INTERP_FX \
        --specs=rdimon.specs -T "$OUT/cm.ld" -Wl,--gc-sections \
        "$OUT/ops.c" "$OUT/startup.c" $FX_SRC $F32_SRC -lm -o "$elf"
    log="$OUT/op$1_k$2.log"
    rm -f "$log"
    timeout 120 qemu-system-arm -M microbit -nographic -monitor none -serial none \
        -semihosting-config enable=on,target=native -singlestep -d exec,nochain -D "$log" \
        -kernel "$elf" >/dev/null
    wc -l < "$log"
    rm -f "$log"
}

printf '%-30s %s\n' "operation (K=$K calls)" "instructions/call (incl. loop body)"
for spec in "0:loop body alone" \
            "1:qo_fx_sincos_q28" "2:sinf + cosf (soft float)" \
            "3:qo_fx_atan2_q28" "4:atan2f (soft float)" \
            "5:qo_fx_sqrt_q30" "6:sqrtf (soft float)" \
            "7:qo_fx_asin_q28" "8:asinf (soft float)" \
            "9:qo_quat_mul_q30" "10:qo_quat_mul_f32 (soft float)" \
            "11:qo_quat_normalize_q30" "12:qo_quat_normalize_f32 (soft)" \
            "13:qo_quat_rotate_q30" "14:qo_quat_rotate_f32 (soft)" \
            "15:qo_rotvec_to_quat_q30" "16:qo_mat3_from_quat_q30" \
            "17:mat3_from_quat + mat3_to_quat _q30" \
            "18:qo_euler_from_quat_q30" "19:qo_euler_from_quat_f32 (soft)" \
            "20:qo_interp_slerp_q30" "21:qo_interp_slerp_f32 (soft)" \
            "22:qo_quat_normalize_fast_q30" "23:qo_interp_slerp_fast_q30" \
            "24:qo_euler_from_quat_fast_q30"; do
    op=${spec%%:*}; name=${spec#*:}
    case " ${OPS:-$op} " in *" $op "*) ;; *) continue ;; esac
    if { [ "$op" = 20 ] || [ "$op" = 23 ]; } && [ "$HAVE_INTERP_FX" = 0 ]; then
        printf '%-30s %s\n' "$name" "n/a (lib/src/interp_fx.c not on this branch)"; continue
    fi
    n0=$(run_count "$op" 0)
    nk=$(run_count "$op" "$K")
    printf '%-30s %d\n' "$name" $(( (nk - n0) / K ))
done
