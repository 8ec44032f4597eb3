#!/bin/sh
# tools/stream-latency.sh - planning-to-first-sample latency of `qorient stream` for a 6-joint
# target, against the simulated drive bank on loopback TCP.
#
#   sh tools/stream-latency.sh [RUNS] [DISTANCE] [RATE]      (defaults 5, 20, 1000)
#   QORIENT=/path/to/other/qorient sh tools/stream-latency.sh  compare another build
#
# Each run streams a jerk-limited move of six joints from 0 to DISTANCE (rad; --vmax 2
# --amax 4 --jmax 20: about DISTANCE/2 + 1 s of motion, i.e. DISTANCE/2 * RATE samples) under
# strace, and measures, on strace's clock, the time from the command's execve to the first
# Modbus request the streaming thread sends (its first tick). That span holds reading the
# input, planning, connecting to the drives (the same in every build) and, in a build that
# samples the whole plan up front (the command before qorient/traj.h), that sampling and its
# re-parsing. The command is then stopped with SIGINT (a clean stop). Prints one line per run and
# the median. Needs strace. Not a test: a loaded machine moves the figures, not a verdict.
set -u
cd "$(dirname "$0")/.."
Q=${QORIENT:-build/qorient}
RUNS=${1:-5}
DIST=${2:-20}
RATE=${3:-1000}
MAP=examples/maps/six_int32.ini
command -v strace >/dev/null || { echo "stream-latency: strace not installed" >&2; exit 2; }
[ -x "$Q" ] || { echo "stream-latency: $Q not built (make)" >&2; exit 2; }
T=$(mktemp -d)
SIMPID=""
cleanup() { [ -n "$SIMPID" ] && kill "$SIMPID" 2>/dev/null; wait 2>/dev/null; rm -rf "$T"; }
trap cleanup EXIT
trap 'echo "stream-latency: interrupted" >&2; exit 1' INT TERM

# the simulator: always this checkout's command, so only the streaming side differs
build/qorient sim --map $MAP --listen tcp://127.0.0.1:0 --lag 0 --duration 600 > "$T/sim.out" 2>&1 &
SIMPID=$!
i=0
while ! grep -q '^listening' "$T/sim.out" 2>/dev/null && [ $i -lt 200 ]; do sleep 0.05; i=$((i + 1)); done
PORT=$(sed -n 's/^listening tcp:\/\/127.0.0.1:\([0-9]*\)$/\1/p' "$T/sim.out")
[ -n "$PORT" ] || { echo "stream-latency: simulator did not start" >&2; exit 1; }
# The map's max_step (0.05 rad per tick) would hold the joints back at low rates: the
# latency is what is measured here, not the motion.
printf '0,0,0,0,0,0,0\n0,%s,%s,%s,%s,%s,%s\n' "$DIST" "$DIST" "$DIST" "$DIST" "$DIST" "$DIST" > "$T/targets"

echo "stream-latency: $Q, 6 joints, 0 -> $DIST at --rate $RATE, $RUNS run(s)"
r=1
while [ $r -le "$RUNS" ]; do
    rm -f "$T/trace"
    strace -f -ttt -e trace=execve,clone,clone3,sendto -o "$T/trace" \
        "$Q" stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate "$RATE" --no-rt --quiet \
        --profile scurve --vmax 2 --amax 4 --jmax 20 "$T/targets" > "$T/out" 2>&1 &
    SPID=$!
    # wait (bounded) for the streaming thread's first request, then stop the run
    i=0
    while [ $i -lt 600 ]; do
        # strace -f -ttt lines are "PID TIME call(...) = RESULT"; clone's result is the thread id
        ms=$(awk '
            { pid = $1; t = $2 + 0; call = $3 }
            call ~ /^execve\(/ && t0 == "" { t0 = t; mainpid = pid }
            call ~ /^clone/ && pid == mainpid && thr == "" && $NF ~ /^[0-9]+$/ { thr = $NF }
            call ~ /^sendto\(/ && thr != "" && pid == thr { printf "%.3f", (t - t0) * 1000; exit }
        ' "$T/trace" 2>/dev/null)
        [ -n "$ms" ] && break
        sleep 0.05
        i=$((i + 1))
    done
    # stop the command itself (its pid is strace's first field), not strace: strace then ends
    qpid=$(awk '$3 ~ /^execve\(/ { print $1; exit }' "$T/trace")
    [ -n "$qpid" ] && kill -INT "$qpid" 2>/dev/null
    wait $SPID 2>/dev/null
    if [ -z "$ms" ]; then echo "run $r: no request seen: $(tail -3 "$T/out")"; exit 1; fi
    echo "run $r: first sample sent $ms ms after start"
    echo "$ms" >> "$T/all"
    r=$((r + 1))
done
sort -n "$T/all" | awk '{ v[NR] = $1 } END { printf "median: %s ms (min %s, max %s)\n", v[int((NR + 1) / 2)], v[1], v[NR] }'
