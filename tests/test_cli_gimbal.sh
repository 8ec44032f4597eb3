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

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
