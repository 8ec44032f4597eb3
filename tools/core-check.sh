#!/bin/sh
# Core portability and hygiene checks (run by .ci/run and `make core-check`).
#  1. the core compiles as strict C99 with -Werror under gcc and clang (host),
#  2. ... under arm-none-eabi-gcc for Cortex-M4F (hard float) and Cortex-M0+ (soft float),
#  3. no core object references malloc/calloc/realloc/free,
#  4. the fixed-point core (lib/src/*_fx.c) references no float/double helper
#     (__aeabi_f*, __aeabi_d*), no libm function and no float32-core symbol (*_f32) on
#     Cortex-M0+ soft float, and builds freestanding for rv32imac,
#  5. no core source includes an OS, bus or stdio header,
#  6. the float core (every non-_fx object) references no libm transcendental function: its
#     results come from qorient/fmath.h's kernels, bit-identical on every target (only the
#     exactly rounded sqrtf, fmodf, roundf, fabsf, fmaxf/fminf, floorf/ceilf may be linked).
set -eu
OUT=${BUILD:-build}/core-check
rm -rf "$OUT"; mkdir -p "$OUT"
WARN="-std=c99 -Wall -Wextra -Wpedantic -Werror -Wshadow -Wdouble-promotion -Wstrict-prototypes -Wmissing-prototypes -ffp-contract=off"
INC="-Ilib/include"
CORE=$(ls lib/src/*.c)
FX=$(ls lib/src/*_fx.c 2>/dev/null || true)
fail=0
say() { printf '%s\n' "$*"; }
bad() { printf 'core-check: FAIL: %s\n' "$*" >&2; fail=1; }

build_set() { # name compiler flags... ; compiles $SRCS into $OUT/name
    name=$1; cc=$2; shift 2
    mkdir -p "$OUT/$name"
    for s in $SRCS; do
        o="$OUT/$name/$(basename "$s" .c).o"
        if ! $cc $WARN $INC "$@" -c "$s" -o "$o"; then bad "$name: $s does not compile"; fi
    done
}

SRCS=$CORE
for cc in gcc clang; do
    if command -v $cc >/dev/null; then build_set "host-$cc" $cc -O2; say "core-check: $cc host: ok"; fi
done
M4="-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16"
M0="-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft"
build_set m4f arm-none-eabi-gcc $M4 -O2 -ffunction-sections -fdata-sections -fstack-usage
say "core-check: arm-none-eabi-gcc cortex-m4f: ok"

for o in "$OUT"/m4f/*.o; do
    if arm-none-eabi-nm -u "$o" | grep -Eq '\b(malloc|calloc|realloc|free)\b'; then
        bad "$o references the heap"
    fi
done

for o in "$OUT"/m4f/*.o "$OUT"/host-gcc/*.o; do
    [ -f "$o" ] || continue
    case $o in *_fx.o) continue;; esac
    for sym in $(nm -u "$o" 2>/dev/null | awk '{print $2}'); do
        case $sym in
        sin|sinf|cos|cosf|sincos|sincosf|tan|tanf|asin|asinf|acos|acosf|atan|atanf|atan2|atan2f|\
exp|expf|exp2f|expm1f|log|logf|log2f|log1pf|pow|powf|cbrt|cbrtf|hypot|hypotf|sinh*|cosh*|tanh*)
            bad "float core $o references libm $sym (use qorient/fmath.h)";;
        esac
    done
done
say "core-check: float core references no libm transcendental (sin ... hypot)"

if [ -n "$FX" ]; then
    SRCS=$FX
    build_set m0 arm-none-eabi-gcc $M0 -O2 -ffunction-sections -fdata-sections -fstack-usage
    for o in "$OUT"/m0/*.o; do
        u=$(arm-none-eabi-nm -u "$o" | awk '{print $2}')
        for sym in $u; do
            case $sym in
            __aeabi_f*|__aeabi_d*|*_f32|*_f32_*) bad "fixed core $o references $sym";;
            sin|sinf|cos|cosf|tan|tanf|sqrt|sqrtf|atan|atanf|atan2|atan2f|asin|asinf|acos|acosf|\
exp|expf|log|logf|pow|powf|fabs|fabsf|floor|floorf|ceil|ceilf|hypot|hypotf|fmod|fmodf|round|roundf|lround|lroundf)
                bad "fixed core $o references libm $sym";;
            malloc|calloc|realloc|free) bad "fixed core $o references the heap: $sym";;
            esac
        done
    done
    say "core-check: fixed core on cortex-m0+ soft float: no float, no libm"
    build_set rv32 riscv64-unknown-elf-gcc -march=rv32imac -mabi=ilp32 -ffreestanding -nostdlib -O2
    say "core-check: fixed core freestanding rv32imac: ok"
fi

# Forbidden includes anywhere in the core.
if grep -nE '#[[:space:]]*include[[:space:]]*<(stdio|stdlib|unistd|time|pthread|signal|fcntl|errno|modbus|gpiod|ini|sys/)' \
       lib/src/*.c lib/include/qorient/*.h; then
    bad "a core file includes an OS, bus, heap or stdio header (listed above)"
fi
# The fixed core and its headers stay free of <math.h> and of float types.
for f in $FX; do
    if grep -nE '#[[:space:]]*include[[:space:]]*<math.h>|\b(float|double)\b' "$f"; then
        bad "$f uses float, double or math.h (listed above)"
    fi
done

[ $fail -eq 0 ] && say "core-check: all ok"
exit $fail
