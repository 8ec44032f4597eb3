#!/bin/sh
# Flash (.text+.rodata) and largest stack frame of each core module on Cortex-M targets.
#   sh tools/size-report.sh            markdown table on stdout
# Every module is built for Cortex-M0+ (no FPU: float32 modules then use soft float - use the
# fixed core there), Cortex-M4F (hard float, fpv4-sp-d16) and Cortex-M7 (fpv5-d16), -O2.
# Flash is .text + .rodata of the module's object (libgcc/libm helpers it calls not included).
# Stack is GCC's -fstack-usage figure for the function's own frame (static), the largest
# over the module's functions; callers add their callees' frames.
set -eu
OUT=${BUILD:-build}/size
rm -rf "$OUT"; mkdir -p "$OUT"
CF="-std=c99 -O2 -ffp-contract=off -ffunction-sections -fdata-sections -fstack-usage -Ilib/include"
M0="-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft"
M4="-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16"
M7="-mcpu=cortex-m7 -mthumb -mfloat-abi=hard -mfpu=fpv5-d16"

one() { # target flags src -> "text stack"
    t=$1; fl=$2; s=$3; b=$(basename "$s" .c)
    mkdir -p "$OUT/$t"
    arm-none-eabi-gcc $CF $fl -c "$s" -o "$OUT/$t/$b.o"
    text=$(arm-none-eabi-size -A "$OUT/$t/$b.o" | awk '$1 ~ /^\.(text|rodata)/ {s += $2} END {print s+0}')
    stack=$(awk -F'\t' '{ if ($2+0 > m) m = $2+0 } END { print m+0 }' "$OUT/$t/$b.su")
    echo "$text $stack"
}

printf '| module | core | Cortex-M0+ flash B | M0+ stack B | Cortex-M4F flash B | M4F stack B | Cortex-M7 flash B | M7 stack B |\n'
printf '|---|---|---|---|---|---|---|---|\n'
# totals per core kind (f = float32 + common, x = fixed + common) and target
tf0=0; tf4=0; tf7=0; tx0=0; tx4=0; tx7=0; sf0=0; sf4=0; sf7=0; sx0=0; sx4=0; sx7=0
for s in lib/src/*.c; do
    b=$(basename "$s" .c)
    set -- $(one m0 "$M0" "$s"); f0=$1; k0=$2
    set -- $(one m4 "$M4" "$s"); f4=$1; k4=$2
    set -- $(one m7 "$M7" "$s"); f7=$1; k7=$2
    case $b in
    *_fx) kind=fixed;;
    status|euler_seq) kind=common;;
    *) kind=float32;;
    esac
    if [ $kind != fixed ]; then
        tf0=$((tf0 + f0)); tf4=$((tf4 + f4)); tf7=$((tf7 + f7))
        [ "$k0" -gt "$sf0" ] && sf0=$k0; [ "$k4" -gt "$sf4" ] && sf4=$k4; [ "$k7" -gt "$sf7" ] && sf7=$k7
    fi
    if [ $kind != float32 ]; then
        tx0=$((tx0 + f0)); tx4=$((tx4 + f4)); tx7=$((tx7 + f7))
        [ "$k0" -gt "$sx0" ] && sx0=$k0; [ "$k4" -gt "$sx4" ] && sx4=$k4; [ "$k7" -gt "$sx7" ] && sx7=$k7
    fi
    note=""; [ $kind = float32 ] && note=" (soft float on M0+)"
    printf '| %s | %s%s | %s | %s | %s | %s | %s | %s |\n' "$b" "$kind" "$note" "$f0" "$k0" "$f4" "$k4" "$f7" "$k7"
done
printf '| **float32 core** (all float modules + common) | float32 | %s | %s (max) | %s | %s (max) | %s | %s (max) |\n' "$tf0" "$sf0" "$tf4" "$sf4" "$tf7" "$sf7"
printf '| **fixed core** (all *_fx modules + common) | fixed | %s | %s (max) | %s | %s (max) | %s | %s (max) |\n' "$tx0" "$sx0" "$tx4" "$sx4" "$tx7" "$sx7"
