#!/bin/sh
# `qorient plan --profile trapezoid|scurve`: text contract, limits (also asymmetric),
# sync (also per joint), target states, clamp, wrap, fixed point, streaming and every input
# error. Prints "N passed, M failed".
Q=${QORIENT:-build/qorient}
pass=0; fail=0
tmp=${TMPDIR:-/tmp}/qo-plan.$$
trap 'rm -f "$tmp".*' EXIT INT TERM
ok() { pass=$((pass + 1)); }
ko() { fail=$((fail + 1)); echo "FAIL: $*"; }
check() { # name, then a command that must succeed
    name=$1; shift
    if "$@"; then ok; else ko "$name"; fi
}
P() { "$Q" plan "$@"; }

# --help documents every option
P --profile scurve --help >"$tmp.h" 2>&1; rc=$?
check "help exit 0" [ $rc -eq 0 ]
for o in --profile --vmax --amax --jmax --rate --sync --min --max --wrap --degrees --fixed --min-duration --discrete --help; do
    check "help mentions $o" grep -q -- "$o" "$tmp.h"
done

# 1 joint trapezoid: limits respected, ends at rest on target, fixed rate, last row at rest
printf '0,0\n0,3\n' | P --profile trapezoid --vmax 1 --amax 2 --rate 50 >"$tmp.o" 2>"$tmp.e"; rc=$?
check "trap exit 0" [ $rc -eq 0 ]
check "trap 4 columns" awk -F, 'NF != 4 { exit 1 }' "$tmp.o"
check "trap v,a within limits" awk -F, '{ if ($3 > 1.000001 || $3 < -1.000001 || $4 > 2.000002 || $4 < -2.000002) exit 1 }' "$tmp.o"
check "trap ends at rest on target" awk -F, 'END { if ($2 != 3 || $3 != 0 || $4 != 0) exit 1 }' "$tmp.o"
# optimal duration 3/1 + 1/2 = 3.5 s: the last row is the first at or after it
check "trap duration 3.5 s" awk -F, 'END { if ($1 < 3.5 || $1 > 3.52) exit 1 }' "$tmp.o"
check "trap rate 50 Hz" awk -F, 'NR > 1 { d = $1 - t; if (d < 0.0199999 || d > 0.0200001) exit 1 } { t = $1 }' "$tmp.o"

# 2 joints S-curve, time sync: both arrive in the same row; jerk within limits (finite differences)
printf '0,0,0\n0,1,-4\n' | P --profile scurve --vmax 2 --amax 4 --jmax 20 --rate 1000 >"$tmp.o" 2>"$tmp.e"
check "scurve 7 columns" awk -F, 'NF != 7 { exit 1 }' "$tmp.o"
check "scurve time sync" awk -F, '{ d1 = ($2 == 1 && $4 == 0); d2 = ($3 == -4 && $5 == 0); if (d1 != d2 && $1 > 0) exit 1 }' "$tmp.o"
check "scurve jerk limited" awk -F, 'NR > 1 { j = ($6 - a) / ($1 - t); if (j > 20.01 || j < -20.01) exit 1 } { t = $1; a = $6 }' "$tmp.o"
check "scurve limits" awk -F, '{ if ($4 > 2.000002 || $4 < -2.000002 || $5 > 2.000002 || $5 < -2.000002 || $6 > 4.000004 || $6 < -4.000004 || $7 > 4.000004 || $7 < -4.000004) exit 1 }' "$tmp.o"
check "scurve ends at rest" awk -F, 'END { if ($2 != 1 || $3 != -4 || $4 != 0 || $5 != 0 || $6 != 0 || $7 != 0) exit 1 }' "$tmp.o"

# phase sync: straight line in joint space (p2 = -2 p1 all along)
printf '0,0,0\n0,1,-2\n' | P --profile scurve --vmax 1,3 --amax 4,1 --jmax 20 --sync phase >"$tmp.o"
check "phase sync straight line" awk -F, '{ if ((2 * $2 + $3) > 1e-5 || (2 * $2 + $3) < -1e-5) exit 1 }' "$tmp.o"
# phase requested from a state off the new line: falls back to time sync and says so
printf '0,0,0\n0,1,-2\n0.3,-1,1\n' | P --profile scurve --vmax 1 --amax 4 --jmax 20 --sync phase >"$tmp.o" 2>"$tmp.e"; rc=$?
check "phase fallback exit 0" [ $rc -eq 0 ]
check "phase fallback reported on line 3" grep -q "line 3.*time sync" "$tmp.e"
check "phase no fallback note on line 2" sh -c "! grep -q 'line 2' '$tmp.e'"
# sync none: joint 1 arrives first
printf '0,0,0\n0,1,-4\n' | P --profile trapezoid --vmax 1 --amax 1 --sync none --rate 100 >"$tmp.o"
check "sync none: joint 1 early" awk -F, '$1 > 2.05 && $1 < 2.1 { if ($2 != 1 || $3 == -4) bad = 1; seen = 1 } END { exit !(seen && !bad) }' "$tmp.o"

# streaming targets faster than arrival never stops in between
awk 'BEGIN { print "0,0"; for (i = 1; i <= 30; i++) printf "%g,%g\n", i * 0.1, i * 0.1 }' |
    P --profile scurve --vmax 2 --amax 8 --jmax 80 --rate 100 >"$tmp.o"
check "stream does not stop" awk -F, '$1 > 0.5 && $1 < 3 { if ($3 < 0.5) exit 1 }' "$tmp.o"
check "stream ends at last target" awk -F, 'END { if ($2 != 3 || $3 != 0) exit 1 }' "$tmp.o"
check "stream velocity continuous" awk -F, 'NR > 1 { d = $3 - v; if (d > 0.1 || d < -0.1) exit 1 } { v = $3 }' "$tmp.o"

# a stream issued 2000 s after the start moves exactly like one issued at once (the core's
# float32 time is re-based at each re-plan; ulp(2000 s) would otherwise be 0.12 ms)
awk 'BEGIN { print "0,0"; for (i = 1; i <= 30; i++) printf "%.1f,%g\n", i * 0.1, i * 0.1 }' |
    P --profile scurve --vmax 2 --amax 8 --jmax 80 --rate 10 | cut -d, -f2- >"$tmp.a"
awk 'BEGIN { print "0,0"; for (i = 1; i <= 30; i++) printf "%.1f,%g\n", 2000 + i * 0.1, i * 0.1 }' |
    P --profile scurve --vmax 2 --amax 8 --jmax 80 --rate 10 | awk -F, '$1 >= 1999.99' | cut -d, -f2- >"$tmp.b"
check "late stream same rows" [ "$(wc -l <"$tmp.a")" -eq "$(wc -l <"$tmp.b")" ]
check "late stream same motion" sh -c "paste -d, '$tmp.a' '$tmp.b' | awk -F, '{ for (i = 1; i <= 3; i++) { d = \$i - \$(i + 3); if (d > 1e-5 || d < -1e-5) exit 1 } }'"

# clamp: target beyond --max is clamped and reported
printf '0,0\n0,5\n' | P --profile trapezoid --vmax 1 --amax 1 --min -1 --max 2 >"$tmp.o" 2>"$tmp.e"; rc=$?
check "clamp exit 0" [ $rc -eq 0 ]
check "clamp final at max" awk -F, 'END { if ($2 != 2) exit 1 }' "$tmp.o"
check "clamp reported naming the line" grep -q "line 2.*clamped" "$tmp.e"

# wrap: 170 deg -> -170 deg goes +20 (the short way), output unwrapped
printf '0,170\n0,-170\n' | P --profile trapezoid --vmax 90 --amax 180 --wrap 1 --degrees >"$tmp.o"
check "wrap short way" awk -F, '{ if ($2 < 169.999) exit 1 } END { if ($2 != 190) exit 1 }' "$tmp.o"

# --fixed follows the float plan within a few Q16.16 LSB
printf '0,0.5,-1\n0,2,1\n0.4,-1,3\n' | P --profile scurve --vmax 2 --amax 4 --jmax 30 >"$tmp.f"
printf '0,0.5,-1\n0,2,1\n0.4,-1,3\n' | P --profile scurve --vmax 2 --amax 4 --jmax 30 --fixed >"$tmp.x"
check "fixed same rows" [ "$(wc -l <"$tmp.f")" -eq "$(wc -l <"$tmp.x")" ]
check "fixed close to float" sh -c "paste -d, '$tmp.f' '$tmp.x' | awk -F, '{ for (i = 2; i <= 3; i++) { d = \$i - \$(i + 7); if (d > 1e-4 || d < -1e-4) exit 1 } }'"

# input errors: line named on stderr, exit 1, nothing printed (as for keyframes)
printf '0,0\n1,1\n0.5,2\n' | P --profile trapezoid --vmax 1 --amax 1 >"$tmp.o" 2>"$tmp.e"; rc=$?
check "non-monotonic exit 1" [ $rc -eq 1 ]
check "non-monotonic names line 3" grep -q "line 3: time 0.5 is before the previous line's (line 2)" "$tmp.e"
check "non-monotonic prints nothing" [ ! -s "$tmp.o" ]
printf '0,0,0\n1,1\n' | P --profile trapezoid --vmax 1 --amax 1 >"$tmp.o" 2>"$tmp.e"; rc=$?
check "column count exit 1" [ $rc -eq 1 ]
check "column count names line 2" grep -q "line 2" "$tmp.e"
printf '0,0\n# comment\n\n1,abc\n' | P --profile trapezoid --vmax 1 --amax 1 >"$tmp.o" 2>"$tmp.e"; rc=$?
check "non-number exit 1" [ $rc -eq 1 ]
check "non-number names line 4" grep -q "line 4" "$tmp.e"
printf '0,0\n1,nan\n' | P --profile trapezoid --vmax 1 --amax 1 >"$tmp.o" 2>"$tmp.e"; rc=$?
check "nan target exit 1" [ $rc -eq 1 ]
check "nan target names line 2" grep -q "line 2" "$tmp.e"
: | P --profile trapezoid --vmax 1 --amax 1 >"$tmp.o" 2>"$tmp.e"; rc=$?
check "empty input exit 1" [ $rc -eq 1 ]

# usage errors: exit 2 with a message
for args in "--vmax 1 --amax 1" "--profile trapezoid --amax 1" "--profile trapezoid --vmax 1" \
    "--profile scurve --vmax 1 --amax 1" "--profile bogus --vmax 1 --amax 1" \
    "--profile trapezoid --vmax 0 --amax 1" "--profile trapezoid --vmax 1 --amax -2" \
    "--profile scurve --vmax 1 --amax 1 --jmax 0" "--profile trapezoid --vmax 1,2,3 --amax 1" \
    "--profile trapezoid --vmax 1 --amax 1 --min 2 --max 1" "--profile trapezoid --vmax 1 --amax 1 --rate 0" \
    "--profile trapezoid --vmax 1 --amax 1 --sync sideways" "--profile trapezoid --vmax 1 --amax 1 --wrap 3" \
    "--profile trapezoid --vmax x --amax 1" "--profile trapezoid --vmax inf --amax 1"; do
    # shellcheck disable=SC2086
    printf '0,0,0\n0,1,1\n' | P $args >"$tmp.o" 2>"$tmp.e"; rc=$?
    check "usage error exit 2: $args" [ $rc -eq 2 ]
    check "usage error message: $args" [ -s "$tmp.e" ]
done
P --profile trapezoid --vmax 1 --amax 1 /nonexistent/file >"$tmp.o" 2>"$tmp.e"; rc=$?
check "missing file exit 1" [ $rc -eq 1 ]
check "missing file named" grep -q "/nonexistent/file: No such file" "$tmp.e"

# --discrete: durations in whole periods of --rate, so a move issued on a row ends on a row.
# Trapezoid, amax 4 at 100 Hz: the last moving row is one period before the end, so its speed
# is amax/rate = 0.04 exactly when the stop lands on a row (without --discrete it is less);
# the next row is at rest (|v| <= 1e-6: float32 rounding of the phase sums) and the plan ends
# there, all velocities 0. The last moving row's time is on the 0.01 grid.
for d in 0.37 1.234 -2.5 7.77; do
    printf '0,0\n0.2,%s\n' "$d" | P --profile trapezoid --vmax 2 --amax 4 --rate 100 --discrete >"$tmp.o" 2>"$tmp.e"; rc=$?
    check "discrete $d exit 0" [ $rc -eq 0 ]
    check "discrete $d: last moving row on the grid, stopping at amax/rate" awk -F, -v d="$d" '
        { v = $3 < 0 ? -$3 : $3 }
        v > 1e-6 { lt = $1; lv = v; mov = NR }
        END {
            k = lt * 100; if (k - int(k + 0.5) > 1e-6 || int(k + 0.5) - k > 1e-6) exit 1
            if (lv < 0.04 * (1 - 1e-4) || lv > 0.04 * (1 + 1e-4)) exit 1
            if (NR != mov + 1 && NR != mov + 2) exit 1
        }' "$tmp.o"
    check "discrete $d: ends at rest on target" awk -F, -v d="$d" 'END { e = $2 - d; if ($3 != 0 || $4 != 0 || e > 1e-6 || e < -1e-6) exit 1 }' "$tmp.o"
    check "discrete $d: the row after the last moving one is at rest" awk -F, '
        { v = $3 < 0 ? -$3 : $3 } v > 1e-6 { mov = NR; next } NR == mov + 1 { ok = (v <= 1e-6) } END { exit !ok }' "$tmp.o"
done
# the same move without --discrete: the stop falls between rows (the check above is not vacuous)
printf '0,0\n0.2,0.37\n' | P --profile trapezoid --vmax 2 --amax 4 --rate 100 >"$tmp.o" 2>"$tmp.e"
check "not discrete: last moving row slower than amax/rate" awk -F, '
    { v = $3 < 0 ? -$3 : $3 } v > 1e-6 { lv = v } END { exit !(lv < 0.04 * (1 - 1e-3)) }' "$tmp.o"
# scurve, 2 joints: the last moving row has |a| = jmax/rate on the moving joint, then rest
printf '0,0,1\n0.2,0.37,-1\n' | P --profile scurve --vmax 2 --amax 4 --jmax 10 --rate 100 --discrete >"$tmp.o" 2>"$tmp.e"; rc=$?
check "discrete scurve exit 0" [ $rc -eq 0 ]
check "discrete scurve: stop lands on a row" awk -F, '
    { v = $4 < 0 ? -$4 : $4; a = $6 < 0 ? -$6 : $6 } v > 1e-6 { la = a } END { exit !(la > 0.1 * 0.999 && la < 0.1 * 1.001) }' "$tmp.o"
check "discrete scurve: ends at rest" awk -F, 'END { if ($4 != 0 || $5 != 0 || $6 != 0 || $7 != 0) exit 1 }' "$tmp.o"

# --min-duration 2: a tiny move issued at 0.5 s lasts 2 s: the last sample is at 2.5 s
printf '0,0\n0.5,0.001\n' | P --profile scurve --vmax 2 --amax 4 --jmax 10 --min-duration 2 >"$tmp.o" 2>"$tmp.e"; rc=$?
check "min-duration exit 0" [ $rc -eq 0 ]
check "min-duration: last sample 2 s after the target" awk -F, 'END { if ($1 != 2.5 || $3 != 0) exit 1 }' "$tmp.o"
printf '0,0\n0.5,0.001\n' | P --profile scurve --vmax 2 --amax 4 --jmax 10 >"$tmp.o" 2>"$tmp.e"
check "without min-duration the tiny move is short" awk -F, 'END { if ($1 > 1.0) exit 1 }' "$tmp.o"
# bad values, and both options with a keyframe profile: exit 2 naming the option
for args in "--min-duration -1" "--min-duration nan" "--min-duration abc" "--min-duration inf" \
    "--min-duration 1e5" "--min-duration="; do
    # shellcheck disable=SC2086
    printf '0,0\n0.5,1\n' | P --profile scurve --vmax 1 --amax 1 --jmax 1 $args >"$tmp.o" 2>"$tmp.e"; rc=$?
    check "refused exit 2: $args" [ $rc -eq 2 ]
    check "refused names the option: $args" grep -q -- "--min-duration" "$tmp.e"
    check "refused prints nothing: $args" [ ! -s "$tmp.o" ]
done
for args in "--discrete" "--min-duration 1" "--profile linear --discrete"; do
    # shellcheck disable=SC2086
    printf '0,0\n1,1\n' | P $args >"$tmp.o" 2>"$tmp.e"; rc=$?
    check "keyframes refuse: $args" [ $rc -eq 2 ]
    case $args in *discrete) o=--discrete ;; *) o=--min-duration ;; esac
    check "keyframes refuse names it: $args" grep -q -- "$o applies to --profile trapezoid|scurve only" "$tmp.e"
done
printf '0,0\n0.5,1\n' | P --profile trapezoid --vmax 1 --amax 1 --discrete=1 >"$tmp.o" 2>"$tmp.e"; rc=$?
check "--discrete takes no value" [ $rc -eq 2 ]

# ---- the planner's new limits and target states ----
# --vmin/--amin (asymmetric limits), --target-velocities (target lines t,p1..pN,v1..vN),
# per-joint --sync lists and --sync if-necessary. Judged by awk from the printed samples only
# (never from the planner's coefficients): every velocity within [vmin, vmax], every
# acceleration and every finite difference of the velocities within [amin, amax], jerk by
# differences of the accelerations within jmax, each target state reached, refusals named.
P --profile scurve --help >"$tmp.h" 2>&1
for o in --vmin --amin --target-velocities if-necessary; do
    check "help mentions $o" grep -q -- "$o" "$tmp.h"
done

# limits FILE N VMAX VMIN AMAX AMIN JMAX RATE: prints the number of violations of the limits
# in the printed samples (t, p1..pN, v1..vN, a1..aN), each list one value per joint. The
# difference checks are means of the next derivative, so within its bounds (float32 values of
# v and a, ~2e-6 of their range, and the float32 rounding of the plan's time since its
# re-plan, ulp(t) times the next derivative, enter divided by dt: the tolerance is 1e-5 of
# the limit plus those; t since the first sample bounds the time since the re-plan).
limits() {
    awk -F, -v n="$2" -v VX="$3" -v VN="$4" -v AX="$5" -v AN="$6" -v JX="$7" -v rate="$8" '
        BEGIN { split(VX, vx, " "); split(VN, vn, " "); split(AX, ax, " "); split(AN, an, " "); split(JX, jx, " ") }
        NR == 1 { tf = $1 }
        { for (j = 1; j <= n; j++) {
              v = $(1 + n + j); a = $(1 + 2 * n + j)
              if (v > vx[j] * (1 + 1e-5) || v < vn[j] * (1 + 1e-5)) { bad++; if (bad < 4) print "v", NR, j, v > "/dev/stderr" }
              if (a > ax[j] * (1 + 1e-5) || a < an[j] * (1 + 1e-5)) { bad++; if (bad < 4) print "a", NR, j, a > "/dev/stderr" }
              if (NR > 1) {
                  h = $1 - t0; ut = 1.2e-7 * ($1 - tf); tol = (2e-6 * (vx[j] - vn[j]) + 2 * ax[j] * ut) / h
                  fa = (v - pv[j]) / h
                  if (fa > ax[j] * (1 + 1e-5) + tol || fa < an[j] * (1 + 1e-5) - tol) { bad++; if (bad < 4) print "fd a", NR, j, fa > "/dev/stderr" }
                  fj = (a - pa[j]) / h; tol = (2e-6 * (ax[j] - an[j]) + 2 * jx[j] * ut) / h
                  if (fj > jx[j] * (1 + 1e-5) + tol || fj < -jx[j] * (1 + 1e-5) - tol) { bad++; if (bad < 4) print "fd j", NR, j, fj > "/dev/stderr" }
              }
              pv[j] = v; pa[j] = a }
          t0 = $1 }
        END { print bad + 0 }' "$1"
}

# A stream of target states (fixed seed): 3 joints, asymmetric limits, targets every 12 s
# with velocities in [vmin, vmax]/2, passing through without stopping. Checked: the limits in
# every sample, and each target state reached (position, velocity, acceleration 0 on one row
# between its issue and the next: --discrete makes each move end on a sample).
awk 'BEGIN { srand(20261201); printf "0,0,0,0,0,0,0\n";
    for (k = 1; k <= 6; k++) {
        printf "%g", (k - 1) * 12
        for (j = 1; j <= 3; j++) printf ",%.4f", -2 + 4 * rand()
        printf ",%.4f,%.4f,%.4f\n", 0.9 * rand(), -0.2 * rand(), 0.6 * rand() - 0.3 } }' > "$tmp.in"
P --profile scurve --vmax 1,1.5,2 --vmin -0.5,-1.5,-0.8 --amax 3,4,2 --amin -2,-4,-1.5 --jmax 20,30,15 \
    --target-velocities --discrete --rate 100 "$tmp.in" > "$tmp.o" 2> "$tmp.e"; rc=$?
check "states: exit 0 ($(cat "$tmp.e"))" [ $rc -eq 0 ]
check "states: 10 columns" awk -F, 'NF != 10 { exit 1 }' "$tmp.o"
v=$(limits "$tmp.o" 3 "1 1.5 2" "-0.5 -1.5 -0.8" "3 4 2" "-2 -4 -1.5" "20 30 15" 100)
check "states: $v samples outside [vmin,vmax] / [amin,amax] / jmax" [ "$v" = 0 ]
# the asymmetric limits are in force, not just respected by luck: joint 1 brakes with -2 at
# most (symmetric would allow -3), and the velocity floor of joint 2 is used
check "states: amin reached" awk -F, '{ if ($8 < m) m = $8 } END { exit !(m < -1.9) }' "$tmp.o"
r=$(awk -F, 'NR == FNR { if (FNR > 1) { tt[FNR - 1] = $1; for (j = 1; j <= 6; j++) w[FNR - 1, j] = $(j + 1); nk = FNR - 1 } next }
    { for (k = 1; k <= nk; k++) {
          if ($1 < tt[k] || (k < nk && $1 >= tt[k + 1]) || hit[k]) continue
          m = 0
          for (j = 1; j <= 3; j++) {
              d = $(j + 1) - w[k, j]; if (d < 0) d = -d; if (d > m) m = d
              d = $(j + 4) - w[k, j + 3]; if (d < 0) d = -d; if (d > m) m = d
              d = $(j + 7); if (d < 0) d = -d; if (d * 0.01 > m) m = d * 0.01 }
          if (m < 1e-4) hit[k] = 1 } }
    END { for (k = 1; k <= nk; k++) if (!hit[k]) miss = miss " " k; print miss "" }' "$tmp.in" "$tmp.o")
check "states: target state(s)$r not reached on a sample" [ -z "$r" ]

# trapezoid takes target velocities too (zero target acceleration)
P --profile trapezoid --vmax 2 --amax 4 --target-velocities --discrete --rate 50 "$tmp.in" > "$tmp.o" 2> "$tmp.e"; rc=$?
v=$(limits "$tmp.o" 3 "2 2 2" "-2 -2 -2" "4 4 4" "-4 -4 -4" "1e30 1e30 1e30" 50)
check "trapezoid states: exit $rc, $v violations" [ $rc -eq 0 ] && [ "$v" = 0 ]

# --vmin alone: a long move down cruises at vmin, not at -vmax
printf '0,0\n0,-10\n' | P --profile scurve --vmax 2 --vmin -0.5 --amax 4 --jmax 20 --rate 50 > "$tmp.o"
check "vmin cruise" awk -F, '{ if ($3 < m) m = $3 } END { exit !(m > -0.5 * 1.00001 && m < -0.4999) }' "$tmp.o"

# refusals: named line, nothing printed, exit 1 (plan), and before anything is sent (stream)
printf '0,0,0,0,0\n1,1,1,0.5,2.5\n' > "$tmp.bad"
P --profile scurve --vmax 2 --amax 4 --jmax 20 --target-velocities "$tmp.bad" > "$tmp.o" 2> "$tmp.e"; rc=$?
check "v > vmax refused: exit $rc" [ $rc -eq 1 ]
check "v > vmax: nothing printed" [ ! -s "$tmp.o" ]
check "v > vmax: names line 2 and joint 2" grep -q "line 2: joint 2: target velocity 2.5" "$tmp.e"
printf '0,0,0\n1,1,-0.75\n' | P --profile scurve --vmax 2 --vmin -0.5 --amax 4 --jmax 20 --target-velocities > "$tmp.o" 2> "$tmp.e"; rc=$?
check "v < vmin refused ($rc)" [ $rc -eq 1 ] && [ ! -s "$tmp.o" ] && grep -q "outside \[-0.5, 2\]" "$tmp.e"
printf '0,0,0.5\n' | P --profile scurve --vmax 2 --amax 4 --jmax 20 --target-velocities > "$tmp.o" 2> "$tmp.e"; rc=$?
check "moving start refused ($rc)" [ $rc -eq 1 ] && grep -q "line 1: the start line is at rest" "$tmp.e"
printf '0,0,0\n1,1\n' | P --profile scurve --vmax 2 --amax 4 --jmax 20 --target-velocities > "$tmp.o" 2> "$tmp.e"; rc=$?
check "column count with --target-velocities ($rc)" [ $rc -eq 1 ] && grep -q "line 2" "$tmp.e"
MAP=examples/maps/six_int32.ini
printf '0,0,0,0,0,0,0,0,0,0,0,0,0\n1,1,1,1,1,1,1,0,0,0,9,0,0\n' > "$tmp.bad6"
"$Q" stream --map $MAP --modbus rtu:/dev/null,115200,8N1 --dry-run --profile scurve --vmax 2 --amax 4 --jmax 20 \
    --target-velocities "$tmp.bad6" > "$tmp.o" 2> "$tmp.e"; rc=$?
check "stream refuses v > vmax before sending ($rc: $(cat "$tmp.e"))" [ $rc -eq 1 ] && grep -q "line 2: joint 4" "$tmp.e"
printf '0,0,0,0,0,0,0,0,0,0,0,0,0\n1,1,1,1,1,1,1,0,0,0,1,0,0\n' > "$tmp.ok6"
printf '0,0,0,0,0,0,0\n1,1,1,1,1,1,1\n' > "$tmp.p6"
"$Q" stream --map $MAP --modbus rtu:/dev/null,115200,8N1 --dry-run --profile scurve --vmax 2 --amax 4 --jmax 20 \
    --vmin -1 --amin -3 --sync time,time,none,if-necessary,phase,time --target-velocities "$tmp.ok6" > "$tmp.o" 2> "$tmp.e"; rc=$?
check "stream dry-run with the new options ($rc: $(cat "$tmp.e"))" [ $rc -eq 0 ] && grep -q "dry-run: plan over" "$tmp.o"
"$Q" stream --map $MAP --modbus rtu:/dev/null,115200,8N1 --dry-run --profile scurve --vmax 2 --amax 4 --jmax 20 \
    --sync time,none "$tmp.p6" > "$tmp.o" 2> "$tmp.e"; rc=$?
check "stream: --sync list of the wrong length is a usage error ($rc)" [ $rc -eq 2 ]

# per-joint sync: joint 1 (short move) with none arrives before joint 2 (long move);
# with time they arrive on the same row. if-necessary: joint 1's target is at rest (own
# time), joint 2's moves (synchronised): joint 1 arrives first as with none.
arrive() { # file joint target: row index where the joint is on its target at rest for good
    awk -F, -v j="$2" -v p="$3" '{ n = NR; d = $(1 + j) - p; if (d < 0) d = -d
        if (d < 1e-6 && $(3 + j) == 0) { if (!at) at = NR } else at = 0 } END { print at }' "$1"
}
printf '0,0,0\n0,0.2,3\n' > "$tmp.s"
P --profile scurve --vmax 2 --amax 4 --jmax 20 --sync time "$tmp.s" > "$tmp.o"
a1=$(arrive "$tmp.o" 1 0.2); a2=$(arrive "$tmp.o" 2 3)
check "sync time: together ($a1, $a2)" [ -n "$a1" ] && [ "$a1" = "$a2" ]
P --profile scurve --vmax 2 --amax 4 --jmax 20 --sync none,time "$tmp.s" > "$tmp.o"
a1=$(arrive "$tmp.o" 1 0.2); a2=$(arrive "$tmp.o" 2 3)
check "sync none,time: joint 1 first ($a1 < $a2)" [ "$a1" -gt 0 ] && [ "$a1" -lt "$a2" ]
printf '0,0,0,0,0\n0,0.2,3,0,0.5\n' > "$tmp.s"
P --profile scurve --vmax 2 --amax 4 --jmax 20 --sync if-necessary --target-velocities "$tmp.s" > "$tmp.o"
a1=$(arrive "$tmp.o" 1 0.2); last=$(wc -l < "$tmp.o")
check "sync if-necessary: the joint at rest arrives before the moving one ends ($a1 < $last)" [ "$a1" -gt 0 ] && [ "$a1" -lt "$last" ]
P --profile scurve --vmax 2 --amax 4 --jmax 20 --sync time --target-velocities "$tmp.s" > "$tmp.o"
a1=$(arrive "$tmp.o" 1 0.2); last=$(wc -l < "$tmp.o")
check "sync time with a moving target: together ($a1 = $last)" [ "$a1" = "$last" ]

# option errors: usage (2)
for args in "--vmin 1" "--vmin 0" "--amin x" "--sync time,bogus" "--sync time,none,phase" "--vmin -1,-1,-1"; do
    # shellcheck disable=SC2086  # $args is a list of options
    printf '0,0,0\n0,1,1\n' | P --profile scurve --vmax 2 --amax 4 --jmax 20 $args > "$tmp.o" 2> "$tmp.e"; rc=$?
    check "'$args' is a usage error ($rc: $(cat "$tmp.e"))" [ $rc -eq 2 ] && [ ! -s "$tmp.o" ]
done
for args in "--vmin -1" "--target-velocities" "--sync if-necessary"; do
    # shellcheck disable=SC2086
    printf '0,0\n1,1\n' | P --profile spline $args > "$tmp.o" 2> "$tmp.e"; rc=$?
    check "'$args' refused for keyframes ($rc)" [ $rc -eq 2 ]
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
