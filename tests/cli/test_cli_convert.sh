#!/bin/sh
# Shell tests of `qorient convert` and `qorient slerp`: the text contract of DESIGN.md.
# Reference values come from awk (double precision), not from the code under test.
Q=${QORIENT:-build/qorient}
pass=0; fail=0
T=${TMPDIR:-/tmp}/qo-cli-convert.$$
mkdir -p "$T"; trap 'rm -rf "$T"' EXIT INT TERM
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# Rotation angle between quaternion fields 1-4 and 5-8 of each line (sign-aligned), worst over
# all lines: 2*atan2(|a-b|, |a+b|), which is insensitive to small norm errors (a dot-product
# acos would read a 1e-7 norm error as a 1e-5 rad rotation).
ANGLE_AWK='{ s = ($1*$5 + $2*$6 + $3*$7 + $4*$8 < 0) ? -1 : 1; dm = 0; dp = 0;
    for (i = 1; i <= 4; i++) { u = $i - s*$(i+4); v = $i + s*$(i+4); dm += u*u; dp += v*v }
    a = 2 * atan2(sqrt(dm), sqrt(dp)); if (a > m) m = a } END { printf "%.3g", m }'

# near "name" "got" "want" tol : every field of got within tol of want
near() {
    if awk -v g="$2" -v w="$3" -v tol="$4" 'BEGIN {
            ng = split(g, a, /[ ,]+/); nw = split(w, b, /[ ,]+/);
            if (ng != nw) exit 1;
            for (i = 1; i <= ng; i++) { d = a[i] - b[i]; if (d < 0) d = -d; if (d > tol) exit 1 }
            exit 0 }'; then ok; else bad "$1: got '$2' want '$3' (tol $4)"; fi
}

awk 'BEGIN { s = 12345; for (i = 0; i < 20; i++) {
        # LCG with a fixed seed -> uniform random unit quaternion (Shoemake)
        s = (s * 1103515245 + 12345) % 2147483648; u1 = s / 2147483648;
        s = (s * 1103515245 + 12345) % 2147483648; u2 = s / 2147483648;
        s = (s * 1103515245 + 12345) % 2147483648; u3 = s / 2147483648;
        pi = atan2(0, -1);
        w = sqrt(1-u1)*sin(2*pi*u2); x = sqrt(1-u1)*cos(2*pi*u2);
        y = sqrt(u1)*sin(2*pi*u3);   z = sqrt(u1)*cos(2*pi*u3);
        if (w < 0) { w = -w; x = -x; y = -y; z = -z }
        printf "%.12f %.12f %.12f %.12f\n", w, x, y, z } }' > "$T/q"
# Every check below runs on both cores: the float32 core and (--fixed) the fixed-point core.
for F in "" --fixed; do
    # 1. Lecture example: 30 degrees about (0,3,4) -> (0.966, 0, 0.155, 0.207)
    near "${F:-float32}: axisangle->quat 30deg about (0,3,4)" "$(echo '0 3 4 30' | $Q convert $F axisangle quat --degrees)" "0.966 0 0.155 0.207" 0.0005
    # 2. Lecture example: (1,0,0) rotated 180 degrees about (1,0,1) is (0,0,1): first matrix column
    out=$(echo '1 0 1 180' | $Q convert $F axisangle matrix --degrees)
    col=$(echo "$out" | awk '{print $1, $4, $7}')
    near "${F:-float32}: 180deg about (1,0,1) maps x to z" "$col" "0 0 1" 1e-6
    # 3. 90 degrees yaw is ZYX (90, 0, 0) with no lock
    near "${F:-float32}: axisangle->euler:ZYX" "$(echo '0 0 1 90' | $Q convert $F axisangle euler:ZYX --degrees)" "90 0 0 0" 1e-4
    # 4. Exactly singular input is flagged, and recomposes
    out=$(echo '10 90 20' | $Q convert $F euler:XYZ euler:XYZ --degrees)
    flag=$(echo "$out" | awk '{print $4}')
    [ "$flag" = 1 ] && ok || bad "${F:-float32}: euler XYZ pitch 90 not flagged: '$out'"
    a=$(echo "$out" | awk '{print $1, $2, $3}')
    q1=$(echo '10 90 20' | $Q convert $F euler:XYZ quat --degrees)
    q2=$(echo "$a" | $Q convert $F euler:XYZ quat --degrees)
    near "${F:-float32}: locked angles recompose" "$q2" "$q1" 2e-6
    # 5. Round trip through every one of the 24 conventions, against an awk reference quaternion
    for seq in xyz xzy yxz yzx zxy zyx xyx xzx yxy yzy zxz zyz XYZ XZY YXZ YZX ZXY ZYX XYX XZX YXY YZY ZXZ ZYZ; do
        $Q convert $F quat "euler:$seq" < "$T/q" | awk '{print $1, $2, $3}' | $Q convert $F "euler:$seq" quat > "$T/r" 2>&1
        worst=$(paste -d' ' "$T/q" "$T/r" | awk "$ANGLE_AWK")
        if awk -v m="$worst" 'BEGIN { exit !(m <= 1e-5) }'; then ok; else bad "${F:-float32}: euler:$seq round trip worst $worst rad"; fi
    done
    # 6. Every representation round-trips (quat -> X -> quat)
    for rep in matrix rotvec axisangle; do
        $Q convert $F quat $rep < "$T/q" | $Q convert $F $rep quat > "$T/r"
        worst=$(paste -d' ' "$T/q" "$T/r" | awk "$ANGLE_AWK")
        if awk -v m="$worst" 'BEGIN { exit !(m <= 1e-6) }'; then ok; else bad "${F:-float32}: $rep round trip worst $worst rad"; fi
    done
done

# 7. Errors: bad line replaced in place, named on stderr, exit status 1, other lines still converted
printf '1 0 0 0\nfoo 1 2 3\n0 0 0 0\n1 2 3\n# comment\n\n0 1 0 0\nnan 0 0 1\n' > "$T/in"
$Q convert quat quat < "$T/in" > "$T/out" 2> "$T/err"; rc=$?
[ "$rc" = 1 ] && ok || bad "exit status with bad lines: $rc"
[ "$(wc -l < "$T/out")" = 8 ] && ok || bad "output line count $(wc -l < "$T/out") != 8"
[ "$(sed -n 2p "$T/out")" = "error: not a number: 'foo' (column 1)" ] && ok || bad "line 2: '$(sed -n 2p "$T/out")'"
[ "$(sed -n 3p "$T/out")" = "error: zero-length quaternion or vector" ] && ok || bad "line 3: '$(sed -n 3p "$T/out")'"
[ "$(sed -n 4p "$T/out")" = "error: expected 4 numbers, got 3" ] && ok || bad "line 4: '$(sed -n 4p "$T/out")'"
[ "$(sed -n 5p "$T/out")" = "# comment" ] && ok || bad "comment not copied"
[ "$(sed -n 8p "$T/out")" = "error: not a finite number: 'nan' (column 1)" ] && ok || bad "line 8: '$(sed -n 8p "$T/out")'"
grep -q "line 2:" "$T/err" && grep -q "line 3:" "$T/err" && grep -q "line 8:" "$T/err" && ok || bad "stderr does not name the lines: $(cat "$T/err")"
near "good line after errors" "$(sed -n 7p "$T/out")" "0 1 0 0" 0
# 8. A non-rotation matrix is rejected
out=$(echo '2 0 0 0 1 0 0 0 1' | $Q convert matrix quat 2>/dev/null); rc=$?
[ "$rc" = 1 ] && [ "$out" = "error: matrix is not a rotation" ] && ok || bad "scaled matrix: rc=$rc '$out'"
# 8b. --fixed: a value that does not fit its format is an error, not a clipped guess
out=$(echo '9 0 0' | $Q convert rotvec quat --fixed 2>/dev/null); rc=$?
[ "$rc" = 1 ] && [ "$out" = "error: fixed-point overflow (saturated)" ] && ok || bad "fixed rotvec of 9 rad: rc=$rc '$out'"
out=$(echo '0 0 0 0' | $Q convert quat quat --fixed 2>/dev/null); rc=$?
[ "$rc" = 1 ] && [ "$out" = "error: zero-length quaternion or vector" ] && ok || bad "fixed zero quaternion: rc=$rc '$out'"
# 9. Usage: --help exits 0, unknown representation exits 2
$Q convert --help > /dev/null && ok || bad "convert --help"
$Q convert quat bogus < /dev/null 2>/dev/null; [ $? = 2 ] && ok || bad "unknown representation exit status"
$Q convert quat euler:xyX < /dev/null 2>/dev/null; [ $? = 2 ] && ok || bad "mixed-case sequence accepted"
# 10. slerp: halfway between identity and 180 degrees about z; t = 0 and 1 exact; t out of range
for F in "" --fixed; do
    near "${F:-float32}: slerp halfway" "$(echo '1 0 0 0 0 0 0 1 0.5' | $Q slerp $F)" "0.707106781 0 0 0.707106781" 1e-7
    near "${F:-float32}: slerp t=0" "$(echo '1 0 0 0 0 0 0.6 0.8 0' | $Q slerp $F)" "1 0 0 0" 0
    near "${F:-float32}: slerp t=1" "$(echo '1 0 0 0 0 0 0.6 0.8 1' | $Q slerp $F)" "0 0 0.6 0.8" 1e-7
    near "${F:-float32}: slerp takes the short way" "$(echo '1 0 0 0 -0.7071067811865476 0 0 -0.7071067811865476 0.5' | $Q slerp $F)" \
         "$(awk 'BEGIN { printf "%.9f 0 0 %.9f", cos(atan2(0,-1)/8), sin(atan2(0,-1)/8) }')" 1e-6
    out=$(echo '1 0 0 0 0 0 0 1 1.5' | $Q slerp $F 2>/dev/null); rc=$?
    [ "$rc" = 1 ] && [ "$out" = "error: parameter out of range" ] && ok || bad "${F:-float32}: slerp t=1.5: rc=$rc '$out'"
done
$Q slerp --help > /dev/null && ok || bad "slerp --help"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
