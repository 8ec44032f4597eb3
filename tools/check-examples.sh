#!/bin/sh
# Checks the examples a user copies from (called by .ci/run):
#  1. examples/mcu/gimbal_follow.c and examples/platformio/src/main.c compile warning-free
#     (-std=c99 -Wall -Wextra -Wpedantic -Werror and the core's conversion warnings) with
#     arm-none-eabi-gcc for Cortex-M0+ (soft float) and Cortex-M4F (hard float);
#  2. each links with the qorient core for both cores (newlib, nosys.specs, --gc-sections,
#     SysTick_Handler kept: no vector table here, the user's startup file provides it), and the
#     flash/RAM it takes is printed;
#  3. on Cortex-M0+ nothing reachable from SysTick_Handler (the call graph of the linked image)
#     is a floating-point helper (__aeabi_f*, __aeabi_d*, libm): the interrupt is integer-only;
#  4. examples/pi/stream_modbus.c compiles warning-free on the host (built and run against the
#     simulator by tests/examples/test_example_pi.sh);
#  5. tools/check-library-json.py: the PlatformIO manifest builds and names existing examples.
# PlatformIO itself is not run (not installed in CI; see examples/platformio/README.md).
set -eu
cd "$(dirname "$0")/.."
OUT=${BUILD:-build}/check-examples
rm -rf "$OUT"; mkdir -p "$OUT"
CC_ARM=arm-none-eabi-gcc
WARN="-std=c99 -Wall -Wextra -Wpedantic -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes \
-Wdouble-promotion -Wconversion -Wno-sign-conversion -Wcast-align -ffp-contract=off"
M0="-mcpu=cortex-m0plus -mthumb -mfloat-abi=soft"
M4="-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16"
MCU_EXAMPLES="examples/mcu/gimbal_follow.c examples/platformio/src/main.c"
fail=0
bad() { printf 'check-examples: FAIL: %s\n' "$*" >&2; fail=1; }

for cpu in m0 m4f; do
    if [ $cpu = m0 ]; then FLAGS=$M0; else FLAGS=$M4; fi
    mkdir -p "$OUT/$cpu/core"
    # the core, as a firmware build would compile it
    for s in lib/src/*.c; do
        $CC_ARM $FLAGS -std=c99 -O2 -ffunction-sections -fdata-sections -ffp-contract=off -Ilib/include \
            -c "$s" -o "$OUT/$cpu/core/$(basename "$s" .c).o" || bad "$cpu: core $s does not compile"
    done
    arm-none-eabi-ar rcs "$OUT/$cpu/libqorient.a" "$OUT/$cpu"/core/*.o
    for ex in $MCU_EXAMPLES; do
        name=$(echo "$ex" | sed 's|^examples/||; s|/src/main\.c$||; s|\.c$||; s|/|_|g')
        o="$OUT/$cpu/$name.o"
        if ! $CC_ARM $FLAGS $WARN -O2 -ffunction-sections -fdata-sections -Ilib/include -c "$ex" -o "$o"; then
            bad "$ex does not compile warning-free for $cpu"; continue
        fi
        elf="$OUT/$cpu/$name.elf"
        if ! $CC_ARM $FLAGS --specs=nosys.specs -Wl,--gc-sections -Wl,-u,SysTick_Handler \
                -o "$elf" "$o" "$OUT/$cpu/libqorient.a" -lm; then
            bad "$ex does not link with the qorient core for $cpu"; continue
        fi
        set -- $(arm-none-eabi-size "$elf" | awk 'NR == 2 { print $1, $2, $3 }')
        printf 'check-examples: %-28s %-4s ok: flash %6d B (text+data), RAM %5d B (data+bss), newlib included\n' \
            "$ex" "$cpu" $(($1 + $2)) $(($2 + $3))
        if [ $cpu = m0 ]; then
            arm-none-eabi-objdump -d "$elf" > "$OUT/$cpu/$name.dis"
            if ! python3 - "$OUT/$cpu/$name.dis" <<'EOF'
import re, sys
# Call graph of the linked image from its disassembly: function -> functions it branches to.
calls, cur = {}, None
for line in open(sys.argv[1]):
    m = re.match(r"^[0-9a-f]+ <([^>]+)>:$", line)
    if m:
        cur = m.group(1); calls.setdefault(cur, set()); continue
    m = re.search(r"\t(?:bl|b|blx|b\.n|b\.w|bl\.w)\s+[0-9a-f]+ <([^>+]+)(?:\+0x[0-9a-f]+)?>", line)
    if m and cur and m.group(1) != cur:
        calls[cur].add(m.group(1))
float_fn = re.compile(r"^(__aeabi_[fd]|__aeabi_[iu]2[fd]|__aeabi_[fd]2|__(add|sub|mul|div)[sd]f3|"
                      r"(sin|cos|tan|sqrt|atan2?|asin|acos|exp|log|pow|fabs|floor|ceil|fmod|hypot)f?$)")
seen, todo, hits = set(), ["SysTick_Handler"], []
while todo:
    f = todo.pop()
    if f in seen: continue
    seen.add(f)
    if float_fn.match(f): hits.append(f)
    todo.extend(calls.get(f, ()))
if "SysTick_Handler" not in calls:
    sys.exit("SysTick_Handler is not in the image")
if hits:
    sys.exit("SysTick_Handler reaches floating-point code: " + ", ".join(sorted(hits)))
print("check-examples: %s: SysTick_Handler reaches %d functions, no floating-point helper"
      % (sys.argv[1].split("/")[-1].replace(".dis", ""), len(seen) - 1))
EOF
            then bad "$ex: the interrupt is not integer-only on cortex-m0+"; fi
        fi
    done
done

# The host example: compile only (tests/examples/test_example_pi.sh builds, links and runs it).
PKG_CONFIG=${PKG_CONFIG:-pkg-config}
if cc -std=c99 -Wall -Wextra -Wpedantic -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes \
        -ffp-contract=off -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE -Ilib/include -Iports \
        $($PKG_CONFIG --cflags libmodbus libgpiod inih 2>/dev/null) \
        -c examples/pi/stream_modbus.c -o "$OUT/stream_modbus.o"; then
    echo "check-examples: examples/pi/stream_modbus.c host ok"
else
    bad "examples/pi/stream_modbus.c does not compile warning-free on the host"
fi

python3 tools/check-library-json.py || bad "tools/check-library-json.py"

[ $fail -eq 0 ] && echo "check-examples: all ok"
exit $fail
