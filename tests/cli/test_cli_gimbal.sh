#!/bin/sh
# Shell tests of `qorient gimbal`: continuity through the singular configuration, lock band,
# rate limit, errors naming the line. References come from awk, not from the code under test.
Q=${QORIENT:-build/qorient}
pass=0; fail=0
T=${TMPDIR:-/tmp}/qo-cli-gimbal.$$
mkdir -p "$T"; trap 'rm -rf "$T"' EXIT INT TERM
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# Pitch 0 -> 180 degrees about y (keys every 45 degrees, built by awk): ZYX passes pitch 90.
awk 'BEGIN { pi = atan2(0, -1); for (i = 0; i <= 4; i++) { a = i * pi / 4;
        printf "%g,%.12f,0,%.12f,0\n", i, cos(a / 2), sin(a / 2) } }' > "$T/keys"
$Q gimbal --degrees --rate 50 "$T/keys" > "$T/out"; rc=$?
[ "$rc" = 0 ] && ok || bad "gimbal exit status $rc"
n=$(wc -l < "$T/out"); [ "$n" = 201 ] && ok || bad "expected 201 samples (0..4 s at 50 Hz), got $n"
# a2 follows the path's pitch (45 deg/s) through 90 without a branch flip; a1, a3 stay 0
r=$(awk -F, '{ want = $1 * 45; d = $3 - want; if (d < 0) d = -d; if (d > m) m = d;
               if ($2 > 1e-3 || $2 < -1e-3 || $4 > 1e-3 || $4 < -1e-3) other++ }
             END { printf "%g %d", m, other }' "$T/out")
set -- $r
awk -v m="$1" 'BEGIN { exit !(m < 1e-3) }' && ok || bad "pitch deviates from the path by $1 deg"
[ "$2" = 0 ] && ok || bad "$2 samples moved a1 or a3 (a branch flip)"
# margin = |90 - pitch|; lock exactly where margin <= 1 degree (the default band)
r=$(awk -F, '{ want = 90 - $1 * 45; if (want < 0) want = -want; d = $5 - want; if (d < 0) d = -d; if (d > m) m = d;
               if (($5 <= 0.999 && $6 != 1) || ($5 >= 1.001 && $6 != 0)) wrong++ }
             END { printf "%g %d", m, wrong }' "$T/out")
set -- $r
awk -v m="$1" 'BEGIN { exit !(m < 1e-3) }' && ok || bad "margin off by $1 deg"
[ "$2" = 0 ] && ok || bad "$2 samples with a lock flag that disagrees with the margin"
grep -q ',1,0$' "$T/out" && ok || bad "no locked sample on a path through the singularity"

# Rate limit: 20 deg/s with 45 deg/s requested: every step <= 20/50 deg, clipped reported,
# and the joints still arrive at the end (the output goes on past the last key).
$Q gimbal --degrees --rate 50 --vmax 20 "$T/keys" > "$T/out"
r=$(awk -F, 'NR > 1 { d = $3 - p; if (d < 0) d = -d; if (d > m) m = d } { p = $3; last = $0; if ($7 != 0) c++ }
             END { printf "%g %d %s", m, c, last }' "$T/out")
set -- $r
awk -v m="$1" 'BEGIN { exit !(m <= 0.4 * 1.0001) }' && ok || bad "step $1 deg exceeds 0.4"
[ "$2" -gt 0 ] && ok || bad "no clipped samples under a rate limit"
echo "$3" | awk -F, '{ d = $3 - 180; if (d < 0) d = -d; exit !(d < 1e-3 && $7 == 0) }' && ok || bad "joints did not arrive: last '$3'"

# Errors name the line, exit 1, print nothing
printf '0,1,0,0,0\n1,1,0,0\n' | $Q gimbal > "$T/o" 2> "$T/e"; rc=$?
[ "$rc" = 1 ] && [ ! -s "$T/o" ] && grep -q "line 2" "$T/e" && ok || bad "column count error: rc=$rc $(cat "$T/e")"
printf '0,1,0,0,0\n1,1,0,0,0\n1,0,1,0,0\n' | $Q gimbal > "$T/o" 2> "$T/e"; rc=$?
[ "$rc" = 1 ] && grep -q "line 3" "$T/e" && ok || bad "non-monotonic time: rc=$rc $(cat "$T/e")"
printf '0,1,0,0,0\n1,0,0,0,0\n' | $Q gimbal > "$T/o" 2> "$T/e"; rc=$?
[ "$rc" = 1 ] && grep -q "line 2" "$T/e" && ok || bad "zero quaternion: rc=$rc $(cat "$T/e")"
printf '0,1,0,0,0\n1,x,0,0,0\n' | $Q gimbal > "$T/o" 2> "$T/e"; rc=$?
[ "$rc" = 1 ] && grep -q "line 2: not a number" "$T/e" && ok || bad "non-number: rc=$rc $(cat "$T/e")"
$Q gimbal --seq XYX --rate 0 < "$T/keys" > /dev/null 2>&1; [ $? = 2 ] && ok || bad "--rate 0 accepted"
$Q gimbal --seq XQZ < "$T/keys" > /dev/null 2>&1; [ $? = 2 ] && ok || bad "bad --seq accepted"
$Q gimbal --help | grep -q -- "--band" && ok || bad "--help does not document --band"

# Tracking filter (--amax, --jmax): the demo's path (yaw swings while pitch goes through 90).
# Judged by awk from the printed angles only: second (third) differences over m ticks at the
# printed times are means of the acceleration (jerk), so they never exceed its largest value;
# the tolerance adds float32 rounding of the angles, 4 (8) ulp(4 rad) / (m dt)^2 (^3), m = 1, 4,
# 10 for the acceleration, 4 for the jerk.
awk 'BEGIN { pi = atan2(0, -1); d = pi / 180;
    for (i = 0; i <= 6; i++) { t = i * 0.5; yaw = 40 * sin(i * pi / 6) * d; pitch = 25 * i * d; roll = 10 * sin(i * pi / 6) * d;
        cy = cos(yaw / 2); sy = sin(yaw / 2); cp = cos(pitch / 2); sp = sin(pitch / 2); cr = cos(roll / 2); sr = sin(roll / 2);
        printf "%g,%.9f,%.9f,%.9f,%.9f\n", t, cy*cp*cr + sy*sp*sr, cy*cp*sr - sy*sp*cr, cy*sp*cr + sy*cp*sr, sy*cp*cr - cy*sp*sr } }' \
    > "$T/swing"
# check FILE AMAX JMAX: prints "worst_acc worst_jerk acc_violations jerk_violations"
limits() {
    awk -F, -v amax="$2" -v jmax="$3" '{ t[NR] = $1; for (j = 2; j <= 4; j++) p[j, NR] = $j; n = NR }
        function d2(j, i, m) { return 2 * ((p[j, i + m] - p[j, i]) / (t[i + m] - t[i]) - (p[j, i] - p[j, i - m]) / (t[i] - t[i - m])) / (t[i + m] - t[i - m]) }
        END { u = 4 * 1.2e-7;
            for (j = 2; j <= 4; j++) for (i = 2; i < n; i++) for (m = 1; m <= 10; m += m == 1 ? 3 : 6) {
                if (i - m < 1 || i + m > n) continue;
                h = t[i + m] - t[i]; s2 = d2(j, i, m); a = s2 < 0 ? -s2 : s2;
                if (a > wa) wa = a; if (a > amax * (1 + 1e-5) + 4 * u / (h * h)) va++
                if (jmax > 0 && m == 4 && i + 2 * m <= n) {
                    jr = (d2(j, i + m, m) - s2) / h; if (jr < 0) jr = -jr;
                    if (jr > wj) wj = jr; if (jr > jmax * (1 + 1e-5) + 8 * u / (h * h * h)) vj++ } }
            printf "%g %g %d %d", wa, wj, va, vj }' "$1"
}
$Q gimbal --seq ZYX --interp spline --rate 200 --band 2 "$T/swing" > "$T/raw"
$Q gimbal --seq ZYX --interp spline --rate 200 --band 2 --amax 20 "$T/swing" > "$T/acc"; rc=$?
[ "$rc" = 0 ] && ok || bad "--amax exit status $rc"
set -- $(limits "$T/raw" 20 0)
[ "$3" -gt 0 ] && ok || bad "the unfiltered path never exceeds 20 rad/s^2 (worst $1): the check below proves nothing"
set -- $(limits "$T/acc" 20 0)
[ "$3" = 0 ] && ok || bad "--amax 20: $3 second differences above amax (worst $1)"
# the joints end on the path's end, at rest (the output goes on until they are there)
a=$(tail -1 "$T/raw" | cut -d, -f2-4); b=$(tail -1 "$T/acc" | cut -d, -f2-4)
[ "$a" = "$b" ] && ok || bad "--amax ends at $b, the path at $a"
$Q gimbal --seq ZYX --interp spline --rate 200 --band 2 --amax 20 --jmax 400 "$T/swing" > "$T/jerk"; rc=$?
set -- $(limits "$T/jerk" 20 400)
[ "$rc" = 0 ] && [ "$3" = 0 ] && [ "$4" = 0 ] && ok || bad "--jmax 400: rc $rc, $3 acc and $4 jerk violations (worst $1, $2)"
set -- $(limits "$T/acc" 20 400)
[ "$4" -gt 0 ] && ok || bad "without --jmax the jerk never exceeds 400 (worst $2): the jerk check proves nothing"
# --degrees reads the limits in deg/s^2: 1145.9156 deg/s^2 = 20 rad/s^2, the same motion
$Q gimbal --seq ZYX --interp spline --rate 200 --band 2 --degrees --amax 1145.9156 "$T/swing" \
    | awk -F, '{ printf "%s,%.5f,%.5f,%.5f\n", $1, $2 * atan2(0, -1) / 180, $3 * atan2(0, -1) / 180, $4 * atan2(0, -1) / 180 }' > "$T/deg"
r=$(paste -d, "$T/acc" "$T/deg" | awk -F, '{ for (j = 2; j <= 4; j++) { d = $j - $(j + 7); if (d < 0) d = -d; if (d > m) m = d }
        if ($1 != $8) m = 1 } END { print m + 0 }')
awk -v m="$r" 'BEGIN { exit !(m < 1e-4) }' && ok || bad "--degrees --amax differs from rad/s^2 by $r rad"
# bad limits: usage errors
for args in "--jmax 10" "--amax 0" "--amax -1" "--amax x" "--amax 1e39" "--amax 1e-9" "--amax 1 --jmax nan"; do
    # shellcheck disable=SC2086  # $args is a list of options
    $Q gimbal $args "$T/swing" > "$T/o" 2> "$T/e"; rc=$?
    [ "$rc" = 2 ] && [ ! -s "$T/o" ] && [ -s "$T/e" ] && ok || bad "gimbal $args: rc $rc, $(cat "$T/e")"
done
$Q gimbal --help | grep -q -- "--jmax" && ok || bad "--help does not document --jmax"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
