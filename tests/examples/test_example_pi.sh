#!/bin/sh
# Smoke test of examples/pi/stream_modbus.c against the simulated drive bank (`qorient sim`) on
# loopback TCP: the example is built here (against the build's libqorient_ports.a and
# libqorient.a), streams a move with explicit targets and then its demo move (re-planned
# mid-move), and must exit 0 with the simulator's log showing every joint's final target;
# usage errors exit 2; an unreachable drive, a missing serial device and an RTU rate above the
# line's wire budget exit 1.
Q=${QORIENT:-build/qorient}
B=${QORIENT_BUILD:-$(dirname "$Q")}   # where the archives are (make test: build/)
MAP=examples/maps/six_int32.ini
PKG_CONFIG=${PKG_CONFIG:-pkg-config}
T=${TMPDIR:-/tmp}/qo-example-pi.$$
. tests/common/sh/prelude.sh

# last logged value of each joint j1..j6 (joint units), as "v1 v2 ... v6"
finals() {
    awk -F, 'NR > 1 && NF == 6 && $5 ~ /^j/ { last[$5] = $6 }
             END { printf "%s %s %s %s %s %s", last["j1"], last["j2"], last["j3"], last["j4"], last["j5"], last["j6"] }' "$1"
}
# equal within 0.5e-3 (the map's resolution is 1e-3 rad), element by element
same() {
    awk -v a="$1" -v b="$2" 'BEGIN { n = split(a, x, " "); m = split(b, y, " "); if (n != m || n == 0) exit 1
        for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d < 0) d = -d; if (d > 5e-4) exit 1 } }'
}

EX="$T/stream_modbus"
if cc -std=c99 -Wall -Wextra -Wpedantic -Werror -ffp-contract=off -O1 -D_POSIX_C_SOURCE=200809L \
        -D_DEFAULT_SOURCE -Ilib/include -Iports $($PKG_CONFIG --cflags libmodbus libgpiod inih) \
        examples/pi/stream_modbus.c "$B/libqorient_ports.a" "$B/libqorient.a" \
        $($PKG_CONFIG --libs libmodbus libgpiod inih) -lm -pthread -o "$EX" 2> "$T/cc.err"; then
    ok
else
    bad "examples/pi/stream_modbus.c does not build: $(cat "$T/cc.err")"
    echo "$pass passed, $((fail + 1)) failed"
    exit 1
fi

start_sim() { # $1 = log file
    $Q sim --map $MAP --listen tcp://127.0.0.1:0 --lag 0 --log "$1" --duration 60 > "$T/sim.out" 2>&1 &
    SIMPID=$!
    i=0
    while ! grep -q '^listening' "$T/sim.out" 2>/dev/null && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
    PORT=$(sed -n 's/^listening tcp:\/\/127.0.0.1:\([0-9]*\)$/\1/p' "$T/sim.out")
}
stop_sim() { kill "$SIMPID" 2>/dev/null; wait "$SIMPID" 2>/dev/null; SIMPID=""; }

# 1. explicit final targets, one per joint of the map
start_sim "$T/log1.csv"
[ -n "$PORT" ] && ok || bad "simulator did not start: $(cat "$T/sim.out")"
want="0.3 -0.25 0.2 -0.15 0.1 -0.05"
"$EX" $MAP "tcp://127.0.0.1:$PORT" $want > "$T/out" 2> "$T/err"; rc=$?
[ "$rc" = 0 ] && ok || bad "explicit targets: exit status $rc: $(cat "$T/out" "$T/err")"
grep -q 'final: ok$' "$T/out" && ok || bad "explicit targets: no 'final: ok' (the drives hold the target): $(cat "$T/out")"
stop_sim  # the simulator finishes its log on SIGTERM: never read a log that is still being written
got=$(finals "$T/log1.csv")
same "$got" "$want" && ok || bad "explicit targets: the drives' last targets '$got' != '$want'"
n=$(awk -F, 'NR > 1 && $5 == "j1"' "$T/log1.csv" | wc -l)
[ "$n" -gt 20 ] && ok || bad "explicit targets: only $n targets of j1 reached the simulator"

# 2. the demo: first toward -0.2 (j+1) (-1)^j, re-planned at 0.5 s to 0.1 (j+1) (-1)^j (j from 0)
start_sim "$T/log2.csv"
"$EX" $MAP "tcp://127.0.0.1:$PORT" > "$T/out" 2> "$T/err"; rc=$?
[ "$rc" = 0 ] && ok || bad "demo: exit status $rc: $(cat "$T/out" "$T/err")"
want=$(awk 'BEGIN { for (j = 0; j < 6; j++) printf "%s%.4f", j ? " " : "", 0.1 * (j + 1) * (j % 2 ? -1 : 1) }')
stop_sim
got=$(finals "$T/log2.csv")
same "$got" "$want" && ok || bad "demo: the drives' last targets '$got' != '$want'"
# the re-plan happened mid-move: j6 (j = 5) heads for +1.2 first, so before turning to its
# final -0.6 some of its logged targets are above 0
awk -F, 'NR > 1 && $5 == "j6" && $6 > 0.05 { found = 1 } END { exit !found }' "$T/log2.csv" && ok || \
    bad "demo: j6 never moved toward its first target (+1.2) before the re-plan"

# 3. errors
"$EX" $MAP > /dev/null 2>&1; [ $? = 2 ] && ok || bad "missing SPEC not a usage error (2)"
"$EX" $MAP tcp://127.0.0.1:1 0 0 > /dev/null 2>&1; [ $? = 2 ] && ok || bad "wrong target count not a usage error (2)"
"$EX" $MAP tcp://127.0.0.1:1 > /dev/null 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && grep -q "cannot reach the drives at tcp://127.0.0.1:1" "$T/err" && ok || \
    bad "unreachable drive: rc=$rc $(cat "$T/err")"

# RTU: 2 Leadshine drives x 8 registers need two FC16 of 25 bytes + replies + 4 t3.5 per tick:
# more than 10 ms at 19200 8E1, so 100 Hz is refused before any device is opened
"$EX" examples/maps/leadshine_cs2rs_pr.ini rtu:/dev/qorient-no-such-tty,19200,8E1 > /dev/null 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && grep -q "100 Hz needs more than .* at most [0-9.]* Hz" "$T/err" && ok || \
    bad "RTU rate over the wire budget: rc=$rc $(cat "$T/err")"
# ... while six int32 joints fit at 115200 8N1, and the missing device is named
"$EX" $MAP rtu:/dev/qorient-no-such-tty,115200,8N1 > /dev/null 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && grep -q "cannot reach the drives at rtu:/dev/qorient-no-such-tty" "$T/err" && ok || \
    bad "RTU missing device: rc=$rc $(cat "$T/err")"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
