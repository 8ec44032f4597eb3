#!/bin/sh
# The figures of issue 13: `qorient stream` against `qorient sim` with drives that answer
# late, at default settings (no --timeout-ms, real-time scheduling as the user gets it).
#   sh tools/stream-figures.sh [--seconds S] [--only tcp|load|rtu]     (default 60 s each)
# 1. tcp:  6 int32 joints at 200 Hz over loopback TCP, 3% of the replies 5-12 ms late
#          (sim --lag-dist 0.97:0-0.2ms,0.03:5-12ms): reconnects (goal 0), slave-ticks
#          skipped (goal <= 5%), final targets exact, steps above max_step (goal 0).
# 2. load: the same at the simulator's defaults (no lag model) while two CPU-bound
#          processes run: reconnects (goal 0), skipped (goal <= 1%).
# 3. rtu:  RTU 115200 8N1 over a pseudo-terminal pair (socat) at 100 Hz, 3% late replies:
#          failed ticks, recoveries (read-backs after an unknown outcome), worst gap between
#          two targets the drive received.
# Every figure comes from the command's summary line and the simulator's log of received
# targets (checked here with awk, in joint units, against max_step 0.05 of the map).
# Needs: make (build/qorient), socat for rtu (apt-get install socat).
set -eu
cd "$(dirname "$0")/.."
SECS=60; ONLY=""
while [ $# -gt 0 ]; do
    case $1 in
    --seconds) SECS=$2; shift 2 ;;
    --only) ONLY=$2; shift 2 ;;
    *) echo "usage: sh tools/stream-figures.sh [--seconds S] [--only tcp|load|rtu]" >&2; exit 2 ;;
    esac
done
make -s build/qorient
Q=build/qorient
MAP=examples/maps/six_int32.ini
D=build/stream-figures; rm -rf "$D"; mkdir -p "$D"
PIDS=""
cleanup() { for p in $PIDS; do kill "$p" 2>/dev/null || :; done; wait 2>/dev/null || :; }
trap cleanup EXIT INT TERM

# A 6-joint motion lasting SECS: a keyframe every second, each joint moving 0.2..0.9 rad/s
# (well under max_step 0.05 x 200 Hz = 10 rad/s), ending on known values.
awk -v s="$SECS" 'BEGIN { for (t = 0; t <= s; t++) { printf "%d", t;
    for (j = 1; j <= 6; j++) printf ",%.3f", (t == s) ? 0.1 * j - 0.35 : 0.9 * sin(0.7 * t + j) * (j % 2 ? 1 : -1);
    printf "\n" } }' > "$D/keys.csv"
FINAL=$(tail -1 "$D/keys.csv" | cut -d, -f2-)

wait_listen() { i=0; while ! grep -q '^listening' "$1"; do i=$((i + 1)); [ $i -gt 200 ] && exit 1; sleep 0.05; done; }

# Reads the summary and the simulator's log, prints the figures of one run.
report() { # name summary-file sim-log
    awk -v name="$1" -v final="$FINAL" '
        FNR == 1 { file++ }
        file == 1 && /^summary:/ { for (i = 2; i < NF; i += 2) v[$i] = $(i + 1); fin = $NF }
        file == 2 && FNR > 1 && split($0, c, ",") == 6 {
            j = c[5]; if (j in last) { d = c[6] - last[j]; if (d < 0) d = -d; if (d > 0.05 + 1e-9) above++;
                if (j == "j1") { g = c[1] - tl; if (g > gap) gap = g } }
            last[j] = c[6]; if (j == "j1") tl = c[1] }
        END {
            n = split(final, f, ","); exact = 1
            for (k = 1; k <= n; k++) if (last["j" k] + 0 != f[k] + 0) exact = 0
            printf "%s: ticks %d overruns %d reconnects %d skipped %d (%.2f%% of ticks) timeouts %d late_replies %d exceptions %d ",
                name, v["ticks"], v["overruns"], v["reconnects"], v["skipped"], 100 * v["skipped"] / v["ticks"],
                v["timeouts"], v["late_replies"], v["exceptions"]
            printf "steps_above_max_step %d final_exact %s final %s worst_gap_ms %.1f jitter_max_us %s\n",
                above + 0, exact ? "yes" : "no", fin, 1000 * gap, v["jitter_max_us"] }' "$2" "$3"
}

tcp_run() { # name, extra sim options...
    name=$1; shift
    $Q sim --map $MAP --lag 0 --log "$D/$name.log" "$@" > "$D/$name.sim" 2>&1 &
    SIM=$!; PIDS="$PIDS $SIM"
    wait_listen "$D/$name.sim"
    PORT=$(sed -n 's/^listening tcp:\/\/127.0.0.1:\([0-9]*\)$/\1/p' "$D/$name.sim")
    rc=0
    $Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate 200 --quiet "$D/keys.csv" \
        > "$D/$name.out" 2> "$D/$name.err" || rc=$?
    kill "$SIM"; wait "$SIM" 2>/dev/null || :
    report "$name (exit $rc)" "$D/$name.out" "$D/$name.log"
}

if [ -z "$ONLY" ] || [ "$ONLY" = tcp ]; then
    tcp_run tcp-200hz-3pct-late --lag-dist 0.97:0-0.2ms,0.03:5-12ms
fi
if [ -z "$ONLY" ] || [ "$ONLY" = load ]; then
    sh -c 'while :; do :; done' & L1=$!; sh -c 'while :; do :; done' & L2=$!
    PIDS="$PIDS $L1 $L2"
    tcp_run tcp-200hz-two-cpu-hogs
    kill "$L1" "$L2"; wait "$L1" "$L2" 2>/dev/null || :
fi
if [ -z "$ONLY" ] || [ "$ONLY" = rtu ]; then
    command -v socat > /dev/null || { echo "rtu: socat not installed (apt-get install socat)"; exit 1; }
    socat pty,raw,echo=0,link="$PWD/$D/ttyA" pty,raw,echo=0,link="$PWD/$D/ttyB" 2> "$D/socat.err" &
    SOC=$!; PIDS="$PIDS $SOC"
    i=0; while [ ! -e "$D/ttyB" ]; do i=$((i + 1)); [ $i -gt 100 ] && exit 1; sleep 0.05; done
    $Q sim --map $MAP --lag 0 --log "$D/rtu.log" --listen "rtu:$PWD/$D/ttyA,115200,8N1" \
        --lag-dist 0.97:0-0.2ms,0.03:5-12ms > "$D/rtu.sim" 2>&1 &
    SIM=$!; PIDS="$PIDS $SIM"
    wait_listen "$D/rtu.sim"
    rc=0
    $Q stream --map $MAP --modbus "rtu:$PWD/$D/ttyB,115200,8N1" --rate 100 --quiet "$D/keys.csv" \
        > "$D/rtu.out" 2> "$D/rtu.err" || rc=$?
    kill "$SIM"; wait "$SIM" 2>/dev/null || :
    report "rtu-100hz-3pct-late (exit $rc)" "$D/rtu.out" "$D/rtu.log"
    sed -n 's/^summary: .* sink_errors \([0-9]*\) .*/rtu: failed ticks (sink_errors) \1/p' "$D/rtu.out"
    grep -o 'readbacks [0-9]*' "$D/rtu.out" | sed 's/^/rtu: recoveries (read-backs) /' || :
fi
