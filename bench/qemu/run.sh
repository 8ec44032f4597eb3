#!/bin/sh
# bench/qemu/run.sh OUTDIR - instructions per call of qorient's float32 and fixed-point
# operations on an emulated Cortex-M0 (soft float, QEMU microbit) and Cortex-M4F (hard float,
# fpv4-sp-d16, QEMU mps2-an386). Writes OUTDIR/qemu.tsv: "qemu <cpu> <op> <instructions>".
# QEMU runs one instruction per translation block and logs each executed block (-singlestep
# -d exec,nochain), so the line count is the exact, repeatable number of instructions executed.
set -eu
OUT=${1:-build/bench-results}
B=${BUILD:-build}/bench-qemu
mkdir -p "$OUT" "$B"
FLAGS="-std=c99 -O2 -ffp-contract=off -ffunction-sections -fdata-sections"
SRC="bench/qemu/ops.c bench/qemu/startup.c $(ls lib/src/*.c)"
OPS=$(grep -o '{ "[a-zA-Z0-9_]*", op_' bench/qemu/ops.c | sed 's/{ "\(.*\)", op_/\1/' | tr '\n' ' ')
: > "$OUT/qemu.tsv"

count() { # elf board op n -> executed instructions of the whole program
    timeout 120 qemu-system-arm -M "$2" -nographic -monitor none -serial none \
        -semihosting-config enable=on,target=native -singlestep -d exec,nochain -D "$B/exec.log" \
        -kernel "$1" -append "$3 $4" || { echo "bench-qemu: $3 $4 failed on $2" >&2; exit 1; }
    grep -c '^Trace' "$B/exec.log"
}

for cpu in m0 m4f; do
    if [ $cpu = m0 ]; then F="-mcpu=cortex-m0 -mthumb -mfloat-abi=soft"; board=microbit
    else F="-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16"; board=mps2-an386; fi
    elf=$B/ops-$cpu.elf
    arm-none-eabi-gcc $F $FLAGS -Ilib/include --specs=nano.specs --specs=rdimon.specs \
        -T bench/qemu/cm.ld -Wl,--gc-sections $SRC -lm -o "$elf"
    base=""
    for op in $OPS; do
        # "nop" is measured (and listed) first: its per-call count is the harness overhead.
        c0=$(count "$elf" $board "$op" 0); c8=$(count "$elf" $board "$op" 8)
        per=$(( (c8 - c0) / 8 ))
        if [ "$op" = nop ]; then base=$per; fi
        printf 'qemu\t%s\t%s\t%d\n' $cpu "$op" $((per - base)) >> "$OUT/qemu.tsv"
    done
    echo "bench-qemu: $cpu done"
done
rm -f "$B/exec.log"
