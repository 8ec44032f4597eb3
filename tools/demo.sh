#!/bin/sh
# `make demo`: the main job with no hardware.
#  1. starts two simulated Modbus drive banks on loopback (`qorient sim`): a 6-joint arm
#     (int32 registers) and a 3-axis camera gimbal (float32 registers);
#  2. plans a jerk-limited, time-synchronised move of the arm with a new target issued in the
#     middle of the motion (re-planned without a jump) and streams it at 200 Hz;
#  3. plans a gimbal path through the yaw-pitch-roll singular configuration (pitch 90 deg),
#     turns it into joint angles (nearest solution, hold band, rate limit, then the tracking
#     filter: acceleration- and jerk-limited, so the rates are continuous) and streams those;
#  4. stops the simulators and draws, against the streamer's tick times (seconds since each
#     stream began), what was planned (lines: `qorient plan` with the stream's own options, at
#     the 200 Hz tick times) and what was sent (dots: `qorient stream --log`, each tick's
#     scheduled time and targets) - positions and velocities per joint, the lock margin of the
#     gimbal path and its hold-band flag - into build/demo/demo.png.
set -eu
cd "$(dirname "$0")/.."
Q=build/qorient
D=build/demo
rm -rf "$D"; mkdir -p "$D"
PIDS=""
# SIGTERM lets a simulator finish its log and print its counters; wait for them to exit.
cleanup() { for p in $PIDS; do kill "$p" 2>/dev/null || true; done; for p in $PIDS; do wait "$p" 2>/dev/null || true; done; }
trap cleanup EXIT INT TERM

# Starts a simulator in THIS shell (not in a $(...) subshell, whose children the cleanup could
# not reach) and waits, bounded, for its 'listening' line.
start_sim() { # map out
    $Q sim --map "$1" --listen tcp://127.0.0.1:0 --lag 0.03 --duration 120 > "$2" 2>&1 &
    PIDS="$PIDS $!"
    i=0
    while ! grep -q '^listening' "$2" 2>/dev/null; do
        i=$((i + 1)); [ $i -gt 200 ] && { echo "demo: simulator did not start: $(cat "$2")" >&2; exit 1; }
        sleep 0.05
    done
}
port_of() { sed -n 's/^listening tcp:\/\/127.0.0.1:\([0-9]*\)$/\1/p' "$1"; }

start_sim examples/maps/six_int32.ini "$D/arm-sim.out"
start_sim examples/maps/gimbal3.ini "$D/gimbal-sim.out"
ARM_PORT=$(port_of "$D/arm-sim.out")
GIM_PORT=$(port_of "$D/gimbal-sim.out")
echo "demo: simulated drive banks on tcp://127.0.0.1:$ARM_PORT (arm) and :$GIM_PORT (gimbal)"

# The arm: start at rest, a target at t = 0, a new one issued at t = 0.8 s while moving.
cat > "$D/arm-targets.csv" <<'T'
# t, j1..j6 (rad): t is when the target is issued
0, 0, 0, 0, 0, 0, 0
0, 1.2, -0.8, 0.6, 1.5, -1.0, 0.4
0.8, -0.5, 0.9, -0.2, 0.3, 0.7, -1.2
T
echo "demo: streaming the arm move (jerk-limited, time-synchronised, re-planned at 0.8 s)"
$Q stream --map examples/maps/six_int32.ini --modbus "tcp://127.0.0.1:$ARM_PORT" --rate 200 \
    --timeout-ms 50 --quiet --profile scurve --vmax 2 --amax 6 --jmax 40 --sync time \
    --log "$D/arm-ticks.csv" "$D/arm-targets.csv" | tee "$D/arm-summary.txt"

# The gimbal: yaw swings while pitch goes straight through +90 degrees (the ZYX singularity).
awk 'BEGIN { pi = atan2(0, -1); d = pi / 180;
    print "# t, w, x, y, z: ZYX yaw-pitch-roll keyframes";
    for (i = 0; i <= 6; i++) { t = i * 0.5; yaw = 40 * sin(i * pi / 6) * d; pitch = 25 * i * d; roll = 10 * sin(i * pi / 6) * d;
        cy = cos(yaw / 2); sy = sin(yaw / 2); cp = cos(pitch / 2); sp = sin(pitch / 2); cr = cos(roll / 2); sr = sin(roll / 2);
        printf "%g,%.9f,%.9f,%.9f,%.9f\n", t, cy*cp*cr + sy*sp*sr, cy*cp*sr - sy*sp*cr, cy*sp*cr + sy*cp*sr, sy*cp*cr - cy*sp*sr } }' \
    > "$D/gimbal-keys.csv"
$Q gimbal --seq ZYX --interp spline --rate 200 --band 2 --vmax 3 --amax 20 --jmax 400 "$D/gimbal-keys.csv" > "$D/gimbal-angles.csv"
cut -d, -f1-4 "$D/gimbal-angles.csv" > "$D/gimbal-joint-keys.csv"
echo "demo: streaming the gimbal path through the singular configuration"
$Q stream --map examples/maps/gimbal3.ini --modbus "tcp://127.0.0.1:$GIM_PORT" --rate 200 \
    --timeout-ms 50 --quiet --profile linear --log "$D/gimbal-ticks.csv" "$D/gimbal-joint-keys.csv" \
    | tee "$D/gimbal-summary.txt"

cleanup; PIDS=""

# What was planned: qorient plan with the stream's own options, exact positions and velocities
# at the 200 Hz tick times k / 200 s. What was sent: the streams' tick logs (qorient stream
# --log), one line per tick: its scheduled time (when it was due, k / 200 s) and the targets
# handed to the drives (sampled at the tick's wake time, a few hundred microseconds later).
# Velocities are the planner's: differences over receive or wake times would draw a loaded
# machine's jitter, which is not motion. Angles in radians for the arm, degrees for the
# gimbal, as the axes say.
$Q plan --rate 200 --profile scurve --vmax 2 --amax 6 --jmax 40 --sync time "$D/arm-targets.csv" \
    | tr ',' ' ' > "$D/arm-plan.dat"
$Q plan --rate 200 --profile linear "$D/gimbal-joint-keys.csv" | tr ',' ' ' > "$D/gimbal-plan.dat"
# sent.dat: scheduled_s p1..pN, one line per write (the final one included)
for which in arm gimbal; do
    awk -F, 'NR > 1 { printf "%s", $2; for (j = 5; j <= NF; j++) printf " %s", $j; printf "\n" }' \
        "$D/$which-ticks.csv" > "$D/$which-sent.dat"
done
awk -F, '{ print $1, $5 * 180 / atan2(0, -1), $6 }' "$D/gimbal-angles.csv" > "$D/gimbal-margin.dat"
# One x range per stream, shared by all of its panels: from 0 to the last tick (the final
# write included), or the gimbal path's last sample if later.
XA=$(awk 'END { print $1 }' "$D/arm-sent.dat")
XG=$(cat "$D/gimbal-sent.dat" "$D/gimbal-margin.dat" | awk '$1 > m { m = $1 } END { print m }')
# The gimbal's limits (qorient gimbal --vmax 3 --amax 20 --jmax 400, rad/s, rad/s^2, rad/s^3)
# in the panel's unit, degrees.
GLIM=$(awk 'BEGIN { d = 180 / atan2(0, -1); printf "%.0f deg/s, %.0f deg/s^2, %.0f deg/s^3", 3 * d, 20 * d, 400 * d }')

gnuplot <<G
set terminal pngcairo size 1400,1000 font ",10"
set output "$D/demo.png"
set multiplot layout 3,2 title "qorient demo: planned (lines) and sent to the simulated drives (dots, every 4th tick) at the streamer's 200 Hz tick times; loopback Modbus TCP"
set grid
set key outside right
set xlabel "t (s), tick time since the stream began"
r2d = 180 / pi
set xrange [0:$XA]
set ylabel "position (rad)"
set title "arm: jerk-limited, time-synchronised move, new target at 0.8 s"
plot for [j=0:5] "$D/arm-plan.dat" using 1:(column(j+2)) with lines lw 2 lc j+1 title "j".(j+1), \
     for [j=0:5] "$D/arm-sent.dat" using 1:(column(j+2)) every 4 with points pt 7 ps 0.3 lc j+1 notitle
set ylabel "velocity (rad/s)"
set title "arm: planned velocities at the tick times (no jump at the re-plan)"
plot for [j=0:5] "$D/arm-plan.dat" using 1:(column(j+8)) with lines lw 1.5 lc j+1 title "j".(j+1)
set xrange [0:$XG]
set ylabel "angle (deg)"
set title "gimbal ZYX joints: pitch carries on through 90 deg to 150 deg, no flip"
plot for [j=0:2] "$D/gimbal-plan.dat" using 1:(column(j+2)*r2d) with lines lw 2 lc j+1 title word("yaw pitch roll", j+1), \
     for [j=0:2] "$D/gimbal-sent.dat" using 1:(column(j+2)*r2d) every 4 with points pt 7 ps 0.3 lc j+1 notitle
set ylabel "rate (deg/s)"
set title "gimbal: planned joint rates, continuous through the hold band (limits $GLIM)"
plot for [j=0:2] "$D/gimbal-plan.dat" using 1:(column(j+5)*r2d) with lines lw 1.5 lc j+1 title word("yaw pitch roll", j+1)
set ylabel "margin (deg)"
set title "gimbal: lock margin (angle from the singular configuration); hold band 2 deg"
set yrange [0:*]
plot "$D/gimbal-margin.dat" using 1:2 with lines lw 2 title "margin", 2 with lines dt 2 title "hold band"
unset yrange
set ylabel "in the hold band (1 = yes)"
set title "gimbal: planned samples inside the hold band (free angle held)"
set yrange [-0.1:1.1]
set ytics ("0" 0, "1" 1)
plot "$D/gimbal-margin.dat" using 1:3 with steps lw 2 title "lock"
unset multiplot
G
echo "demo: the picture is $D/demo.png"
