#!/bin/sh
# The command's contracts that were found broken (issue 12), one check each, plus the shape
# of the command: `qorient --version`, `qorient help CMD` == `CMD --help`, and the keyframe and
# target modes of `plan` behaving the same on a bad line and printing --fixed the same way.
# Prints "N passed, M failed".
Q=${QORIENT:-build/qorient}
pass=0; fail=0
T=${TMPDIR:-/tmp}/qo-contracts.$$
mkdir -p "$T"
trap 'rm -rf "$T"' EXIT INT TERM
ok() { pass=$((pass + 1)); }
ko() { fail=$((fail + 1)); echo "FAIL: $*"; }
check() { name=$1; shift; if "$@"; then ok; else ko "$name"; fi; }

# ---- --version, help CMD ----
v=$($Q --version); rc=$?
check "--version exit 0" [ $rc -eq 0 ]
check "--version == version" [ "$v" = "$($Q version)" ]
check "--version text" sh -c "echo '$v' | grep -Eq '^qorient [0-9]+\.[0-9]+\.[0-9]+'"
for c in convert slerp plan gimbal stream sim version; do
    $Q help $c > "$T/h1" 2>&1; r1=$?
    $Q $c --help > "$T/h2" 2>&1; r2=$?
    check "help $c == $c --help" cmp -s "$T/h1" "$T/h2"
    check "help $c exit == $c --help exit" [ $r1 -eq $r2 ]
done
$Q help nosuch > /dev/null 2>&1; check "help of an unknown command exits 2" [ $? -eq 2 ]

# ---- unbounded output: a documented maximum, --max-samples to raise it ----
printf '0,0\n1e6,1\n' | $Q plan --profile trapezoid --vmax 1 --amax 1 > "$T/o" 2> "$T/e"; rc=$?
check "targets over --max-samples refused" [ $rc -eq 1 ]
check "targets over --max-samples: nothing printed" [ ! -s "$T/o" ]
check "targets over --max-samples: says so" grep -q "more than --max-samples 1000000" "$T/e"
printf '0,0\n20000,1\n' | $Q plan --profile linear > "$T/o" 2> "$T/e"; rc=$?
check "keys over --max-samples refused" [ $rc -eq 1 ]
check "keys: refused at the line whose time crosses it" grep -q "^qorient plan: -: line 2: the plan is at least 2000001 samples at 100 Hz by this line's time, more than --max-samples 1000000" "$T/e"
# one sample over: the exact count named (keyframes: the rows through the line's time)
printf '0,0\n10000,1\n' | $Q plan --profile linear > "$T/o" 2> "$T/e"; rc=$?
check "keys one sample over --max-samples refused" [ $rc -eq 1 ]
check "keys: the count is named" grep -q "line 2: the plan is at least 1000001 samples at 100 Hz" "$T/e"
printf '0,0\n20000,1\n' | $Q plan --profile linear --max-samples 2000001 > "$T/o" 2> "$T/e"; rc=$?
check "--max-samples raises it" [ $rc -eq 0 ]
check "--max-samples: every row" [ "$(wc -l < "$T/o")" -eq 2000001 ]
printf '1,0\n2,1\n' | $Q plan --rate 1e300 > "$T/o" 2> "$T/e"; rc=$?
check "--rate 1e300 refused" [ $rc -eq 2 ]
check "--rate names its range" grep -q "is not a number in \[0.001, 1e+06\] Hz" "$T/e"
printf '1,0\n2,1\n' | $Q plan --rate inf > /dev/null 2>&1; check "--rate inf refused" [ $? -eq 2 ]
printf '1,0\n2,1\n' | $Q plan --max-samples 0 > /dev/null 2>&1; check "--max-samples 0 refused" [ $? -eq 2 ]
$Q stream --map examples/maps/six_int32.ini --modbus tcp://127.0.0.1:1 --hold 1e300 - < /dev/null > /dev/null 2> "$T/e"; rc=$?
check "stream --hold 1e300 refused" [ $rc -eq 2 ]
check "stream --hold names its range" grep -q "hold: '1e300' is not a number in \[0, 86400\] s" "$T/e"
$Q stream --map examples/maps/six_int32.ini --modbus tcp://127.0.0.1:1 --rate 200000 - < /dev/null > /dev/null 2> "$T/e"; rc=$?
check "stream --rate above the streamer's bound refused" [ $rc -eq 2 ]

# ---- absolute time exact at 1e7 s ----
printf '10000000,0\n10000010,1\n' | $Q plan --profile linear --rate 2 > "$T/o"
check "plan at 1e7 s: 0.05 at 10000000.5" grep -qx "10000000.5,0.0500000007,0.100000001,0" "$T/o"
check "plan at 1e7 s: 21 rows" [ "$(wc -l < "$T/o")" -eq 21 ]
# the same plan at t = 0 prints the same values (only the time column differs by 1e7)
printf '0,0\n10,1\n' | $Q plan --profile linear --rate 2 | cut -d, -f2- > "$T/o0"
cut -d, -f2- "$T/o" > "$T/o1"
check "plan at 1e7 s == plan at 0" cmp -s "$T/o0" "$T/o1"
printf '10000000,0\n10000000,1\n10000003.25,-2\n' | $Q plan --profile scurve --vmax 2 --amax 4 --jmax 20 | cut -d, -f2- > "$T/o1"
printf '0,0\n0,1\n3.25,-2\n' | $Q plan --profile scurve --vmax 2 --amax 4 --jmax 20 | cut -d, -f2- > "$T/o0"
check "targets at 1e7 s == targets at 0" cmp -s "$T/o0" "$T/o1"
printf '10000000 1 0 0 0\n10000002 0 0 0 1\n' | $Q gimbal --rate 4 > "$T/o" 2> "$T/e"; rc=$?
check "gimbal at 1e7 s exit 0" [ $rc -eq 0 ]
check "gimbal at 1e7 s: every row" [ "$(wc -l < "$T/o")" -eq 9 ]
check "gimbal at 1e7 s: exact times" grep -q "^10000001.75," "$T/o"
printf '0 1 0 0 0\n2 0 0 0 1\n' | $Q gimbal --rate 4 | cut -d, -f2- > "$T/o0"
cut -d, -f2- "$T/o" > "$T/o1"
check "gimbal at 1e7 s == gimbal at 0" cmp -s "$T/o0" "$T/o1"

# ---- wrap with large values: reduced in double, reaches its keys ----
printf '0,1e10\n1,-1e10\n' | $Q plan --wrap 1 --degrees --profile linear --rate 2 > "$T/o"
# 1e10 mod 360 = 280 = -80; -1e10 mod 360 = 80: the short way is +160
check "wrap 1e10: first key -80" grep -qx "0,-80,160,0" "$T/o"
check "wrap 1e10: last key +80" grep -qx "1,80,160,0" "$T/o"
printf '0,0\n0,1e10\n' | $Q plan --wrap 1 --degrees --profile trapezoid --vmax 100 --amax 100 > "$T/o"
check "wrap 1e10 target: ends at -80" awk -F, 'END { exit !($2 == -80 && $3 == 0) }' "$T/o"

# ---- gimbal catch-up that ends far from the target: exit 1, says so ----
printf '0 1 0 0 0\n1 0 0 0 1\n' | $Q gimbal --vmax 1e-30 --rate 4 > "$T/o" 2> "$T/e"; rc=$?
check "gimbal catch-up far from target exit 1" [ $rc -eq 1 ]
check "gimbal catch-up message" grep -q "after one hour of catch-up --vmax still holds joints back" "$T/e"
check "gimbal catch-up rows written" awk -F, 'END { exit !($7 == 1) }' "$T/o"

# ---- NUL byte in a line is an error ----
printf '1 0 0 0\0 2 3\n' | $Q convert quat quat > "$T/o" 2> "$T/e"; rc=$?
check "convert NUL exit 1" [ $rc -eq 1 ]
check "convert NUL in place" grep -qx "error: contains a NUL byte" "$T/o"
printf '0,0\n1,1\0,5\n' | $Q plan --profile linear > "$T/o" 2> "$T/e"; rc=$?
check "plan NUL exit 1" [ $rc -eq 1 ]
check "plan NUL names line 2" grep -q "line 2: contains a NUL byte" "$T/e"
printf '0 1 0 0 0\n1 0 0 0 1\0 9\n' | $Q gimbal > /dev/null 2> "$T/e"; rc=$?
check "gimbal NUL exit 1" [ $rc -eq 1 ]
check "gimbal NUL names line 2" grep -q "line 2: contains a NUL byte" "$T/e"

# ---- convert --fixed refuses what float32 refuses ----
for x in '1e39 0 0 0' '1e-320 0 0 0' '0 1e39 0 0'; do
    echo "$x" | $Q convert quat euler:ZYX > "$T/f" 2>/dev/null; r1=$?
    echo "$x" | $Q convert quat euler:ZYX --fixed > "$T/x" 2>/dev/null; r2=$?
    check "convert --fixed '$x' refused" [ $r2 -eq 1 ]
    check "convert --fixed '$x' as float32" cmp -s "$T/f" "$T/x"
done
echo '1e39 0 0 0 1 0 0 0 0.5' | $Q slerp --fixed > /dev/null 2>&1; check "slerp --fixed 1e39 refused" [ $? -eq 1 ]

# ---- messages name the real rule; a directory is an I/O error ----
printf '0,0\n1,1\n' | $Q plan --profile trapezoid --vmax 1e-30 --amax 1 > /dev/null 2> "$T/e"; rc=$?
check "--vmax 1e-30 usage error" [ $rc -eq 2 ]
check "--vmax 1e-30 names the range" grep -q "vmax: value 1 (1e-30) is not a number in \[0.001, 1e+09\]" "$T/e"
$Q plan "$T" > /dev/null 2> "$T/e"; rc=$?
check "plan of a directory exit 1" [ $rc -eq 1 ]
check "plan of a directory: I/O error" grep -q "read error: Is a directory" "$T/e"
$Q plan --profile scurve --vmax 1 --amax 1 --jmax 1 "$T" > /dev/null 2> "$T/e"
check "targets of a directory: I/O error" grep -q "read error: Is a directory" "$T/e"
$Q gimbal "$T" > /dev/null 2> "$T/e"; rc=$?
check "gimbal of a directory: I/O error" grep -q "read error: Is a directory" "$T/e"

# ---- keyframes and targets: same bad-line behaviour, same --fixed format ----
printf '0,0\n1,x\n2,2\n' | $Q plan --profile linear > "$T/k" 2> "$T/ke"; rk=$?
printf '0,0\n1,x\n2,2\n' | $Q plan --profile trapezoid --vmax 1 --amax 1 > "$T/t" 2> "$T/te"; rt=$?
check "bad line: same exit" [ $rk -eq 1 ] && [ $rt -eq 1 ]
check "bad line: nothing printed (keys)" [ ! -s "$T/k" ]
check "bad line: nothing printed (targets)" [ ! -s "$T/t" ]
check "bad line: same message" cmp -s "$T/ke" "$T/te"
printf '0,0\n1,0.3\n' | $Q plan --profile linear --fixed --rate 4 > "$T/k"
printf '0,0\n0,0.3\n' | $Q plan --profile trapezoid --vmax 1 --amax 1 --fixed --rate 4 > "$T/t"
# Q16.16 values printed exactly: every value times 65536 is an integer
for f in k t; do
    check "--fixed $f values are exact Q16.16" awk -F, '{ for (i = 2; i <= NF; i++) { x = $i * 65536; if (x != int(x)) exit 1 } }' "$T/$f"
done
check "--fixed keys: 0.075 at 0.25 s" grep -qx "0.25,0.0749969482421875,0.3000030517578125,0" "$T/k"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
