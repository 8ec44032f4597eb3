#!/bin/sh
# Throughput of `qorient stream` against a bare libmodbus FC16 loop on the same simulated drive
# bank (`qorient sim`, loopback TCP, 6 int32 joints = one FC16 of 12 registers), in one run.
# The stream is asked for 100 kHz, far above what loopback Modbus can do, so every tick runs
# back to back (sample at the actual time + limit + pack + FC16 + reply + statistics) and the
# ticks per second are its throughput. Rounds alternate; the best of each is kept.
#   sh tools/bench-stream.sh [ROUNDS=3] [SECONDS=3]
set -eu
cd "$(dirname "$0")/.."
ROUNDS=${1:-3}; SECS=${2:-3}
make -s build/qorient build/bench/bare_fc16
D=build/bench-stream; rm -rf "$D"; mkdir -p "$D"
build/qorient sim --map examples/maps/six_int32.ini --listen tcp://127.0.0.1:0 --lag 0 > "$D/sim.out" 2>&1 &
SIM=$!
trap 'kill $SIM 2>/dev/null; wait $SIM 2>/dev/null' EXIT INT TERM
i=0; while ! grep -q '^listening' "$D/sim.out"; do i=$((i + 1)); [ $i -gt 200 ] && exit 1; sleep 0.05; done
PORT=$(sed -n 's/^listening tcp:\/\/127.0.0.1:\([0-9]*\)$/\1/p' "$D/sim.out")
# a slow 6-joint move lasting SECS seconds
awk -v s="$SECS" 'BEGIN { print "0,0,0,0,0,0,0"; printf "%g,0.5,-0.5,0.3,0.2,-0.1,0.4\n", s }' > "$D/keys.csv"
best_s=0; best_b=0; r=0
while [ $r -lt "$ROUNDS" ]; do
    b=$(build/bench/bare_fc16 127.0.0.1 "$PORT" 6 "$SECS" | sed -n 's/.*updates_per_s \([0-9]*\).*/\1/p')
    out=$(build/qorient stream --map examples/maps/six_int32.ini --modbus "tcp://127.0.0.1:$PORT" \
          --rate 100000 --hold 0 --no-rt --quiet --timeout-ms 50 --profile linear "$D/keys.csv")
    ticks=$(echo "$out" | sed -n 's/^summary: ticks \([0-9]*\) .*/\1/p')
    s=$(awk -v t="$ticks" -v d="$SECS" 'BEGIN { printf "%.0f", t / d }')
    echo "round $((r + 1)): bare FC16 loop $b updates/s, qorient stream $s updates/s"
    [ "$b" -gt "$best_b" ] && best_b=$b
    [ "$s" -gt "$best_s" ] && best_s=$s
    r=$((r + 1))
done
awk -v s="$best_s" -v b="$best_b" 'BEGIN { printf "best: bare %d/s, stream %d/s, stream overhead %.1f%%\n", b, s, 100 * (1 - s / b) }'
