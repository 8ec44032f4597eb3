#!/bin/sh
# Shell tests of `qorient stream` against the simulated drive bank (`qorient sim`) on loopback
# TCP: the targets arrive, no step above the map's max_step, the final targets are reached,
# the RTU wire budget of --dry-run, and clear errors for a bad map, an unreachable drive and
# a rate the serial line cannot carry.
Q=${QORIENT:-build/qorient}
MAP=examples/maps/six_int32.ini
T=${TMPDIR:-/tmp}/qo-cli-stream.$$
. tests/common/sh/prelude.sh

# A simulator on an ephemeral port: start_sim [LOG [SIM OPTIONS]] (default LOG $T/log.csv,
# listening on tcp://127.0.0.1:0); waits (bounded) for its 'listening' line, sets PORT and HOST.
start_sim() {
    log=${1:-$T/log.csv}
    [ $# -gt 0 ] && shift
    [ $# -eq 0 ] && set -- --listen tcp://127.0.0.1:0
    rm -f "$log" "$T/sim.out"
    $Q sim --map $MAP --lag 0 --log "$log" --duration 60 "$@" > "$T/sim.out" 2>&1 &
    SIMPID=$!
    i=0
    while ! grep -q '^listening' "$T/sim.out" 2>/dev/null && [ $i -lt 100 ]; do sleep 0.05; i=$((i + 1)); done
    PORT=$(sed -n 's/^listening tcp:\/\/.*:\([0-9]*\)$/\1/p' "$T/sim.out")
    HOST=$(sed -n 's/^listening tcp:\/\/\(.*\):[0-9]*$/\1/p' "$T/sim.out")
    [ -n "$PORT" ] && ok || bad "simulator did not start: $(cat "$T/sim.out")"
}
stop_sim() { kill "$SIMPID" 2>/dev/null; wait "$SIMPID" 2>/dev/null; SIMPID=""; }
# target writes in the simulator's log, the largest step and the last value per joint
log_summary() {
    awk -F, 'NR > 1 && NF == 6 && $5 ~ /^j/ { j = $5; if (j in last) { d = $6 - last[j]; if (d < 0) d = -d; if (d > m) m = d } last[j] = $6; n++ }
             END { printf "%d %.6f %s %s %s %s %s %s", n, m, last["j1"], last["j2"], last["j3"], last["j4"], last["j5"], last["j6"] }' "$T/log.csv"
}
start_sim

# 1. A jerk-limited move of six joints, re-planned mid-motion, streamed at 100 Hz.
printf '0,0,0,0,0,0,0\n0,1,-1,0.5,0.2,0,0.3\n0.6,0.4,0.2,-0.3,0,0.1,-0.2\n' > "$T/targets"
$Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate 100 --timeout-ms 50 --no-rt --quiet \
    --profile scurve --vmax 2 --amax 4 --jmax 20 --sync time "$T/targets" > "$T/out" 2> "$T/err"; rc=$?
[ "$rc" = 0 ] && ok || bad "stream exit status $rc: $(cat "$T/err")"
grep -q '^summary: ticks [1-9]' "$T/out" && grep -q 'final ok$' "$T/out" && ok || bad "summary: $(cat "$T/out")"
# every field of the summary is explained by --help
$Q stream --help > "$T/help"
for f in $(sed -n 's/^summary: //p' "$T/out" | awk '{ for (i = 1; i <= NF; i += 2) print $i }'); do
    case $f in jitter_*) f='jitter_\*_us' ;; esac
    grep -q "^  $f " "$T/help" && ok || bad "summary field $f is not explained by stream --help"
done
# Stop the simulator (SIGTERM: it finishes its log) before reading the log: a log read while
# it is being written can end in half a line.
stop_sim
# the simulator's log: value per joint, in joint units; steps and final values checked by awk
r=$(log_summary)
set -- $r
[ "$1" -gt 600 ] && ok || bad "only $1 target writes logged"
awk -v m="$2" 'BEGIN { exit !(m <= 0.05 + 1e-9) }' && ok || bad "a step of $2 above max_step 0.05 reached a drive"
shift 2
[ "$*" = "0.4 0.2 -0.3 0 0.1 -0.2" ] && ok || bad "final targets '$*' != '0.4 0.2 -0.3 0 0.1 -0.2'"

printf '0,0,0,0,0,0,0\n1,0.5,-0.5,1,0.2,0,0.3\n2,0,0,0,0,0,0\n' > "$T/keys"

# 1b. A plan of 2 joints for the 6 of the map is refused, naming both counts, before anything
#     is written (the simulator logs no write at all).
start_sim
printf '0,0,0\n0,1,-1\n' | $Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate 100 --no-rt --quiet \
    --profile scurve --vmax 2 --amax 4 --jmax 20 > "$T/out" 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && ok || bad "joint count mismatch: exit $rc"
grep -q "the plan has 2 joint(s) but the map has 6: nothing sent" "$T/err" && ok || bad "mismatch message: $(cat "$T/err")"
[ ! -s "$T/out" ] && ok || bad "mismatch: output $(cat "$T/out")"
# 1c. --live: targets piped in while streaming; each applied when it arrives, re-planned from
#     the current state; a bad line is named and skipped (exit 1); at end of input the motion
#     finishes and the drives hold the last target.
{ printf '0,0,0,0,0,0\n'; sleep 0.3; printf '1,-1,0.5,0.2,0,0.3\n'; sleep 0.4;
  printf '0.4,0.2,-0.3,0,0.1,-0.2\n'; sleep 0.2; printf '1,2\n'; } |
    $Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate 100 --timeout-ms 50 --no-rt --quiet --live \
        --profile scurve --vmax 2 --amax 4 --jmax 20 > "$T/out" 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && ok || bad "live with a bad line: exit $rc: $(cat "$T/err")"
grep -q "^qorient stream: -: line 4: 2 columns, expected 6 as on line 1" "$T/err" && ok || bad "live bad line message: $(cat "$T/err")"
grep -q 'final ok$' "$T/out" && ok || bad "live summary: $(cat "$T/out")"
stop_sim
# joint 2 went toward the first target (-1) before the second (+0.2): both were applied
awk -F, 'NR > 1 && NF == 6 && $5 == "j2" && $6 < m { m = $6 } END { exit !(m < -0.1) }' "$T/log.csv" && ok ||
    bad "live: joint 2 never moved toward the first live target"
r=$(log_summary)
set -- $r
# the second target arrived 0.7 s in, while the first move (1 s at these limits) was running
awk -v m="$2" 'BEGIN { exit !(m <= 0.05 + 1e-9) }' && ok || bad "live: a step of $2 above max_step 0.05"
shift 2
[ "$*" = "0.4 0.2 -0.3 0 0.1 -0.2" ] && ok || bad "live final targets '$*' != '0.4 0.2 -0.3 0 0.1 -0.2'"
# 1d. --live --target-velocities: lines p1..p6,v1..v6; a target passed through moving, one
#     with a velocity beyond --vmax named (line and joint) and skipped (exit 1), the last at
#     rest held by the drives; asymmetric limits and a per-joint sync list taken.
start_sim
{ printf '0,0,0,0,0,0,0,0,0,0,0,0\n'; sleep 0.3; printf '0.5,-0.5,0.2,0,0,0.1,0.5,0,0,0,0,0\n'; sleep 0.2;
  printf '1,1,1,1,1,1,0,0,9,0,0,0\n'; sleep 0.1; printf '0.4,0.2,-0.3,0,0.1,-0.2,0,0,0,0,0,0\n'; } |
    $Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate 100 --timeout-ms 50 --no-rt --quiet --live \
        --profile scurve --vmax 2 --vmin -1.5 --amax 4 --amin -3 --jmax 20 --sync time,time,none,time,if-necessary,time \
        --target-velocities > "$T/out" 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && ok || bad "live target states with a refused line: exit $rc: $(cat "$T/err")"
grep -q "^qorient stream: -: line 3: joint 3: target velocity 9 is outside \[-1.5, 2\]" "$T/err" && ok ||
    bad "live refused target state message: $(cat "$T/err")"
grep -q 'final ok$' "$T/out" && ok || bad "live target states summary: $(cat "$T/out")"
stop_sim
r=$(log_summary)
set -- $r
awk -v m="$2" 'BEGIN { exit !(m <= 0.05 + 1e-9) }' && ok || bad "live target states: a step of $2 above max_step 0.05"
shift 2
[ "$*" = "0.4 0.2 -0.3 0 0.1 -0.2" ] && ok || bad "live target states final '$*' != '0.4 0.2 -0.3 0 0.1 -0.2'"
# without a start line --live says what it needs
: | $Q stream --map $MAP --modbus "tcp://127.0.0.1:1" --live --profile trapezoid --vmax 1 --amax 1 > /dev/null 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && grep -q "needs a start line" "$T/err" && ok || bad "live without input: rc=$rc $(cat "$T/err")"
# --live takes targets only, and standard input only
$Q stream --map $MAP --modbus "tcp://127.0.0.1:1" --live --profile spline "$T/keys" > /dev/null 2>&1; [ $? = 2 ] && ok || bad "--live with keyframes accepted"

# 1e. --discrete and --min-duration, streamed to the simulator (exit 0, the drives hold the
#     final targets, no step above max_step) and the plan's end from --dry-run against the
#     expected value computed here: --discrete at --rate 30 (ticks of the stream's rate, not
#     plan's default 100 Hz), trapezoid vmax 2 amax 4, joint 1 moves 0.37 issued at 0.2 s
#     (tick 6): 2 sqrt(0.37/4) = 0.608 s rounded up to 19 ticks, end 0.2 + 19/30 = 0.833 s
#     (0.808 s without --discrete, 0.810 s at 100 Hz); --min-duration 2: a move of 0.001
#     (0.147 s at these limits: 4 (0.001 / 20)^(1/3)) issued at 0.5 s ends at 2.5 s.
# stream_end NAME: streams $T/NAME.csv with the options $ARGS to a fresh simulator, then
# dry-runs it; FINAL is the drives' last targets, END the plan's end time [s] as printed
stream_end() {
    f=$T/$1.csv
    start_sim
    # shellcheck disable=SC2086
    $Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --timeout-ms 50 --no-rt --quiet --hold 0 $ARGS "$f" \
        > "$T/out" 2> "$T/err"; rc=$?
    stop_sim
    [ "$rc" = 0 ] && grep -q 'final ok$' "$T/out" && ok || bad "$ARGS: rc=$rc $(cat "$T/out" "$T/err")"
    r=$(log_summary)
    set -- $r
    awk -v m="$2" 'BEGIN { exit !(m <= 0.05 + 1e-9) }' && ok || bad "a step of $2 above max_step 0.05"
    shift 2
    FINAL=$*
    # shellcheck disable=SC2086
    END=$($Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --dry-run $ARGS "$f" |
        sed -n 's/^dry-run: plan over \([0-9.]*\) s .*/\1/p')
}
printf '0,0,0,0,0,0,0\n0.2,0.37,0,0,0,0,-0.1\n' > "$T/disc.csv"
ARGS="--rate 30 --profile trapezoid --vmax 2 --amax 4 --sync none --discrete"
stream_end disc
[ "$FINAL" = "0.37 0 0 0 0 -0.1" ] && ok || bad "discrete: final targets '$FINAL'"
want=$(awk 'BEGIN { t = 2 * sqrt(0.37 / 4); k = int(t * 30); if (k < t * 30) k++; printf "%.3f", 0.2 + k / 30 }')
[ "$want" = 0.833 ] && [ "$END" = "$want" ] && ok || bad "discrete: plan ends at '$END' s, want $want s"
printf '0,0,0,0,0,0,0\n0.5,0.001,0,0,0,0,0\n' > "$T/mind.csv"
ARGS="--rate 100 --profile scurve --vmax 2 --amax 4 --jmax 10 --min-duration 2"
stream_end mind
[ "$FINAL" = "0.001 0 0 0 0 0" ] && ok || bad "min-duration: final targets '$FINAL'"
[ "$END" = 2.500 ] && ok || bad "min-duration: plan ends at '$END' s, want 2.500 s"

# 2. --dry-run: the RTU wire budget for 6 int32 joints at 115200 8N1 (one FC16 of 12
#    registers: 33 + 8 bytes at 86.8 us per char, plus 2 x 1.75 ms of t3.5 = 7059 us)
$Q stream --map $MAP --modbus rtu:/dev/null,115200,8N1 --rate 100 --dry-run "$T/keys" > "$T/out" 2>&1; rc=$?
[ "$rc" = 0 ] && ok || bad "dry-run exit $rc: $(cat "$T/out")"
want=$(awk 'BEGIN { c = 10 * 1e6 / 115200; printf "%.0f", (33 + 8) * c + 2 * 1750 }')
grep -q "wire budget per tick: $want us; highest rate: 141.7 Hz" "$T/out" && ok || bad "dry-run budget (want $want us): $(cat "$T/out")"
# ... and a rate above it is refused before anything is opened
$Q stream --map $MAP --modbus rtu:/dev/null,115200,8N1 --rate 500 "$T/keys" > /dev/null 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && grep -q "at most 141.7 Hz" "$T/err" && ok || bad "rate over the wire budget: rc=$rc $(cat "$T/err")"

# ... and a slave that has only constant registers is one more request per tick, as sent
printf '[slave.2]\nconstant = 0x10=5\n[joint.a]\nslave = 1\naddress = 0\ntype = int32\n' > "$T/const.ini"
printf '0,0\n1,0.5\n' > "$T/one.csv"
$Q stream --map "$T/const.ini" --modbus tcp://127.0.0.1:1502 --dry-run "$T/one.csv" > "$T/out" 2>&1; rc=$?
[ "$rc" = 0 ] && grep -q '^dry-run: 2 request(s) per tick' "$T/out" && grep -q '  slave 2: registers 16..16' "$T/out" &&
    ok || bad "dry-run of a constant-only slave: rc=$rc $(cat "$T/out")"

# 3. Errors name what is wrong
printf '[joint.a]\nslave = 1\naddress = 0\ntype = int33\n' > "$T/bad.ini"
$Q stream --map "$T/bad.ini" --modbus "tcp://127.0.0.1:$PORT" "$T/keys" > /dev/null 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && grep -q "bad.ini:4:" "$T/err" && ok || bad "bad map: rc=$rc $(cat "$T/err")"
$Q stream --map $MAP --modbus tcp://127.0.0.1:1 --timeout-ms 50 "$T/keys" > /dev/null 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && grep -q "tcp://127.0.0.1:1" "$T/err" && ok || bad "unreachable drive: rc=$rc $(cat "$T/err")"
$Q stream --map $MAP --modbus rtu:/dev/qorient-no-such-tty,115200,8N1 "$T/keys" > /dev/null 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && grep -q "serial device /dev/qorient-no-such-tty: No such file" "$T/err" && ok || bad "unknown device: rc=$rc $(cat "$T/err")"
printf '0,0,0\n' | $Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --profile spline - > /dev/null 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && ok || bad "plan with the wrong joint count accepted: rc=$rc"
$Q stream --map $MAP "$T/keys" > /dev/null 2>&1; [ $? = 2 ] && ok || bad "no --modbus/--gpio accepted"
$Q stream --help | grep -q -- "--dry-run" && ok || bad "--help does not document --dry-run"

# 4. Success means the drive holds it (the issue's case): a 0.1 s plan moves j1 to 3.0, far
#    beyond max_step 0.05 per tick. The stream keeps sending until the drive holds 3.0 (exit
#    0, the simulator's last logged j1 is 3), and with a --settle too short for the catch-up
#    it exits 1 naming j1 and how far it is short.
printf '0,0,0,0,0,0,0\n0.1,3,0,0,0,0,0\n' > "$T/far.csv"
start_sim "$T/log2.csv" --listen tcp://127.0.0.1:0
$Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate 100 --profile linear --hold 0 --no-rt --quiet \
    "$T/far.csv" > "$T/out" 2> "$T/err"; rc=$?
stop_sim
[ "$rc" = 0 ] && grep -q 'final ok$' "$T/out" && ok || bad "held final target: rc=$rc $(cat "$T/out" "$T/err")"
j1=$(awk -F, '$5 == "j1" { v = $6 } END { print v }' "$T/log2.csv")
[ "$j1" = 3 ] && ok || bad "the drive's last j1 target is '$j1', not 3"
start_sim "$T/log2.csv" --listen tcp://127.0.0.1:0
$Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate 100 --profile linear --hold 0 --no-rt --quiet \
    --settle 0.1 "$T/far.csv" > "$T/out" 2> "$T/err"; rc=$?
stop_sim
[ "$rc" = 1 ] && grep -q 'final short$' "$T/out" && grep -q "j1 at [0-9.]*, short by [0-9.]*;" "$T/err" &&
    ! grep -q "j2 at" "$T/err" && ok || bad "short of the final target: rc=$rc $(cat "$T/out" "$T/err")"

# 5. One exception while connecting (the drive's very first reply) does not abort the stream;
#    over IPv6 loopback where the machine has it, and late replies (--lag-dist) cost nothing.
L=tcp://127.0.0.1:0
grep -q '^0*1 ' /proc/net/if_inet6 2>/dev/null && L='tcp://[::1]:0'
start_sim "$T/log3.csv" --listen "$L" --fault exception --fault-share 1 --fault-count 1 \
    --lag-dist 0.9:0-0.2ms,0.1:30-40ms
$Q stream --map $MAP --modbus "tcp://$HOST:$PORT" --rate 100 --no-rt --quiet --timeout-ms 10 \
    --profile scurve --vmax 2 --amax 4 --jmax 20 --sync time "$T/targets" > "$T/out" 2> "$T/err"; rc=$?
stop_sim
[ "$rc" = 0 ] && grep -q 'final ok$' "$T/out" && grep -q ' reconnects 0 ' "$T/out" &&
    ! grep -q ' late_replies 0 ' "$T/out" && grep -q 'faults 1 ' "$T/sim.out" && ok ||
    bad "exception while connecting, late replies ($L): rc=$rc $(cat "$T/out" "$T/err" "$T/sim.out")"

# 6. --log FILE: one line per write, the final one included, with the tick's scheduled time
#    (a multiple of the period, not the wake time) and the time it was sampled at; the
#    targets checked against `qorient plan` sampled on a 10 kHz grid and interpolated at
#    sampled_s (an independent sampling of the same plan, not the streamer's); what the
#    simulator received last is the log's last line.
start_sim
$Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate 100 --timeout-ms 50 --no-rt --quiet \
    --profile scurve --vmax 2 --amax 4 --jmax 20 --sync time --log "$T/ticks.csv" "$T/targets" > "$T/out" 2> "$T/err"; rc=$?
stop_sim
[ "$rc" = 0 ] && grep -q 'final ok$' "$T/out" && ok || bad "--log: exit $rc: $(cat "$T/out" "$T/err")"
[ "$(head -n 1 "$T/ticks.csv")" = "tick,scheduled_s,sampled_s,write,p1,p2,p3,p4,p5,p6" ] && ok ||
    bad "--log header: $(head -n 1 "$T/ticks.csv")"
ticks=$(sed -n 's/^summary: ticks \([0-9]*\) .*/\1/p' "$T/out")
n=$(($(wc -l < "$T/ticks.csv") - 1))
[ -n "$ticks" ] && [ "$n" = $((ticks + 1)) ] && ok || bad "--log: $n lines for $ticks ticks (+1 final write)"
# tick k on line k; scheduled on the 10 ms grid, increasing; sampled at or after it (the
# final write re-sends the last sample: same targets, next deadline); every write ok
awk -F, 'NR == 1 { next }
    { k = NR - 2; if ($1 != k) { print "line " NR ": tick " $1 " != " k; exit 1 }
      g = $2 * 100; if (g - int(g + 0.5) > 1e-6 || int(g + 0.5) - g > 1e-6) { print "line " NR ": scheduled " $2 " off the grid"; exit 1 }
      if (NR > 2 && $2 <= prev) { print "line " NR ": scheduled " $2 " not after " prev; exit 1 }
      if ($4 != "ok") { print "line " NR ": write " $4; exit 1 }
      if (last != "" && lt < prev - 1e-9) { print "line " (NR - 1) ": sampled " lt " before scheduled " prev; exit 1 }
      last = $0; prev = $2; lt = $3 }' "$T/ticks.csv" > "$T/msg" && ok || bad "--log columns: $(cat "$T/msg")"
t1=$(tail -n 2 "$T/ticks.csv" | head -n 1 | cut -d, -f3,5-); t2=$(tail -n 1 "$T/ticks.csv" | cut -d, -f3,5-)
[ "$t1" = "$t2" ] && ok || bad "--log: the final write '$t2' is not the last sample '$t1' again"
$Q plan --rate 10000 --profile scurve --vmax 2 --amax 4 --jmax 20 --sync time "$T/targets" > "$T/plan10k" || bad "plan 10 kHz"
awk -F, 'NR == FNR { t[NR] = $1; for (j = 1; j <= 6; j++) p[NR, j] = $(j + 1); n = NR; next }
    FNR == 1 { next }
    { i = int($3 * 10000) + 1; if (i >= n) i = n - 1; f = ($3 - t[i]) / (t[i + 1] - t[i]); if (f > 1) f = 1
      for (j = 1; j <= 6; j++) { w = p[i, j] + f * (p[i + 1, j] - p[i, j]); d = $(j + 4) - w; if (d < 0) d = -d
        if (d > m) { m = d; at = FNR " p" j } } }
    END { printf "%.3g at line %s", m, at; exit !(m < 2e-6) }' "$T/plan10k" "$T/ticks.csv" > "$T/msg" && ok ||
    bad "--log targets against the plan at sampled_s: largest difference $(cat "$T/msg")"
r=$(log_summary)
set -- $r
shift 2
last=$(tail -n 1 "$T/ticks.csv" | cut -d, -f5- | awk -F, '{ for (j = 1; j <= 6; j++) printf "%s%.6g", (j > 1 ? " " : ""), $j }')
got=$(echo "$*" | awk '{ for (j = 1; j <= 6; j++) printf "%s%.6g", (j > 1 ? " " : ""), $j }')
[ "$got" = "$last" ] && ok || bad "--log: the drives' last targets '$got' are not the log's last line '$last'"
# a log that cannot be created: exit 1 naming it, nothing sent; --dry-run creates no log
start_sim
$Q stream --map $MAP --modbus "tcp://127.0.0.1:$PORT" --rate 100 --no-rt --quiet --profile scurve --vmax 2 \
    --amax 4 --jmax 20 --log "$T/no/such/dir/ticks.csv" "$T/targets" > "$T/out" 2> "$T/err"; rc=$?
stop_sim
[ "$rc" = 1 ] && grep -q "^qorient stream: --log $T/no/such/dir/ticks.csv: " "$T/err" && ok ||
    bad "--log to a missing directory: exit $rc: $(cat "$T/err")"
[ "$(log_summary | cut -d' ' -f1)" = 0 ] && ok || bad "--log to a missing directory: writes reached the drives"
rm -f "$T/dry.csv"
$Q stream --map $MAP --modbus "tcp://127.0.0.1:1" --dry-run --profile scurve --vmax 2 --amax 4 --jmax 20 \
    --log "$T/dry.csv" "$T/targets" > /dev/null 2>&1; rc=$?
[ "$rc" = 0 ] && [ ! -e "$T/dry.csv" ] && ok || bad "--dry-run --log: exit $rc, or the log was created"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
