#!/bin/sh
# `qorient plan` with keyframe profiles: output shape and values, keys hit, limits, wrap,
# --fixed against float, and every error path (message naming the line, exit status).
# QORIENT gives the command (default build/qorient). Prints "N passed, M failed".
Q=${QORIENT:-build/qorient}
pass=0; fail=0
tmp=${TMPDIR:-/tmp}/qo-plan-keys.$$
mkdir -p "$tmp"
trap 'rm -rf "$tmp"' EXIT INT TERM

ok() { pass=$((pass + 1)); echo "ok   $1"; }
ko() { fail=$((fail + 1)); echo "FAIL $1"; [ -n "${2:-}" ] && echo "     $2"; }

# run NAME EXPECTED_STATUS INPUT ARGS... : runs the command, stores stdout/stderr.
run() {
    name=$1; want=$2; input=$3; shift 3
    printf '%b' "$input" | "$Q" plan "$@" >"$tmp/out" 2>"$tmp/err"
    rc=$?
    if [ "$rc" -eq "$want" ]; then return 0; fi
    ko "$name" "exit $rc, want $want; stderr: $(head -2 "$tmp/err")"
    return 1
}

# expect_err NAME STATUS INPUT PATTERN ARGS...: error status, stderr matches, stdout empty
expect_err() {
    name=$1; want=$2; input=$3; pat=$4; shift 4
    run "$name" "$want" "$input" "$@" || return
    if ! grep -Eq -e "$pat" "$tmp/err"; then ko "$name" "stderr lacks /$pat/: $(cat "$tmp/err")"; return; fi
    if [ -s "$tmp/out" ]; then ko "$name" "stdout not empty on error"; return; fi
    ok "$name"
}

# ---- help documents every option ----
if "$Q" plan --help >"$tmp/help" 2>&1; then
    missing=""
    for o in --profile --rate --end --columns --derivs --min --max --wrap --unwrapped --degrees \
             --fixed --vmax --amax --jmax --sync --help linear cubic catmull spline quintic \
             trapezoid scurve; do
        grep -q -- "$o" "$tmp/help" || missing="$missing $o"
    done
    if [ -z "$missing" ]; then ok "help lists every option"; else ko "help lists every option" "missing:$missing"; fi
else
    ko "help exits 0"
fi

# ---- linear: exact values (t, p, v, a per joint) ----
if run "linear values" 0 "0,0,10\n1,10,0\n" --profile linear --rate 4; then
    exp="0,0,10,10,-10,0,0
0.25,2.5,7.5,10,-10,0,0
0.5,5,5,10,-10,0,0
0.75,7.5,2.5,10,-10,0,0
1,10,0,10,-10,0,0"
    if [ "$(cat "$tmp/out")" = "$exp" ]; then ok "linear values"; else ko "linear values" "$(cat "$tmp/out")"; fi
fi

# ---- every profile: column count 1+3N, keys hit exactly, t from first to last key ----
keys="# three joints\n\n0.5 1 2 3\n1.5, -1, 0.5, 2\n2.0,0,0,0\n3.25 4 -2 1\n"
for prof in linear catmull spline quintic; do
    if run "$prof shape" 0 "$keys" --profile "$prof" --rate 20; then
        bad=$(awk -F, 'NF != 10 { print "line " NR ": " NF " fields" }
            $1 == 0.5 && ($2 != 1 || $3 != 2 || $4 != 3) { print "key 0.5: " $0 }
            $1 == 1.5 && ($2 != -1 || $3 != 0.5 || $4 != 2) { print "key 1.5: " $0 }
            $1 == 2 && ($2 != 0 || $3 != 0 || $4 != 0) { print "key 2: " $0 }
            $1 == 3.25 && ($2 != 4 || $3 != -2 || $4 != 1) { print "key 3.25: " $0 }
            $1 == 0.5 || $1 == 1.5 || $1 == 2 || $1 == 3.25 { hit++ }
            END { if (hit != 4) print "keys sampled: " hit+0; if (NR != 56) print NR " samples, want 56" }' "$tmp/out")
        if [ -z "$bad" ]; then ok "$prof shape and keys"; else ko "$prof shape and keys" "$bad"; fi
    fi
done

# the rate does not land on the last key: a final sample at exactly the last key time
if run "last key sample" 0 "0 0\n1.05 1\n" --profile quintic --rate 10; then
    last=$(tail -1 "$tmp/out")
    n=$(wc -l <"$tmp/out")
    if [ "$last" = "1.05,1,0,0" ] && [ "$n" -eq 12 ]; then ok "last key sample"; else ko "last key sample" "$n lines, last '$last'"; fi
fi

# rest ends (default) vs natural: velocity 0 at both ends vs acceleration 0
if run "end rest" 0 "0 0\n1 1\n2 3\n" --profile spline --rate 2; then
    if awk -F, 'NR == 1 && $3 != 0 { exit 1 } END { if ($3 != 0) exit 1 }' "$tmp/out"; then ok "end rest: zero end velocity"
    else ko "end rest: zero end velocity" "$(cat "$tmp/out")"; fi
fi
if run "end natural" 0 "0 0\n1 1\n2 3\n" --profile spline --end natural --rate 2; then
    if awk -F, 'function abs(x) { return x < 0 ? -x : x }
        NR == 1 && (abs($4) > 1e-5 || $3 == 0) { exit 1 } END { if (abs($4) > 1e-5) exit 1 }' "$tmp/out"
    then ok "end natural: zero end acceleration"; else ko "end natural: zero end acceleration" "$(cat "$tmp/out")"; fi
fi

# cubic Hermite with given velocities (--columns pv is the default for cubic):
# p(t) = 2t - t^3 has p(0) = 0, p'(0) = 2, p(1) = 1, p'(1) = -1, p''(0) = 0, p''(1) = -6
if run "cubic pv" 0 "0 0 2\n1 1 -1\n" --profile cubic --rate 1; then
    exp="0,0,2,0
1,1,-1,-6"
    if [ "$(cat "$tmp/out")" = "$exp" ]; then ok "cubic with key velocities"; else ko "cubic with key velocities" "$(cat "$tmp/out")"; fi
fi
# quintic with p, v, a given: the key values come back
if run "quintic pva" 0 "0 0 1 2\n2 4 -1 0.5\n" --profile quintic --columns pva --rate 1; then
    if [ "$(head -1 "$tmp/out")" = "0,0,1,2" ] && [ "$(tail -1 "$tmp/out")" = "2,4,-1,0.5" ]; then ok "quintic with p, v, a"
    else ko "quintic with p, v, a" "$(cat "$tmp/out")"; fi
fi
if run "quintic zero derivs" 0 "0 0\n1 1\n2 3\n" --profile quintic --derivs zero --rate 1; then
    if [ "$(sed -n 2p "$tmp/out")" = "1,1,0,0" ]; then ok "quintic --derivs zero stops at keys"
    else ko "quintic --derivs zero stops at keys" "$(cat "$tmp/out")"; fi
fi

# ---- limits: clamped inside, note on stderr, one value for all joints ----
if run "limits" 0 "0 0 0\n1 10 -10\n2 0 0\n" --profile quintic --min -1,-5 --max 8 --rate 50; then
    bad=$(awk -F, '$2 > 8 || $2 < -1 || $3 > 8 || $3 < -5 { print NR ": " $0 }' "$tmp/out" | head -3)
    if [ -z "$bad" ] && grep -q "joint 1 clamped" "$tmp/err" && grep -q "joint 2 clamped" "$tmp/err"
    then ok "limits clamp and report"; else ko "limits clamp and report" "$bad / $(cat "$tmp/err")"; fi
fi

# ---- wrap: short way across +-pi, degrees, unwrapped output ----
if run "wrap rad" 0 "0 3 3\n1 -3 -3\n" --profile linear --wrap 1 --rate 10; then
    bad=$(awk -F, 'function abs(x) { return x < 0 ? -x : x }
        abs($2) < 2.99 || abs($2) > 3.1416 { print "wrapped joint " $0 }
        NR == 6 && abs($3) > 0.001 { print "unwrapped joint should cross 0: " $0 }' "$tmp/out")
    if [ -z "$bad" ]; then ok "wrap takes the short way across pi"; else ko "wrap takes the short way across pi" "$bad"; fi
fi
if run "wrap deg" 0 "0 170\n1 -170\n" --profile linear --wrap 1 --degrees --rate 2; then
    exp="0,170,20,0
0.5,180,20,0
1,-170,20,0"
    if [ "$(cat "$tmp/out")" = "$exp" ]; then ok "wrap in degrees"; else ko "wrap in degrees" "$(cat "$tmp/out")"; fi
fi
if run "unwrapped" 0 "0 170\n1 -170\n" --profile linear --wrap 1 --degrees --unwrapped --rate 2; then
    if [ "$(tail -1 "$tmp/out")" = "1,190,20,0" ]; then ok "unwrapped output"; else ko "unwrapped output" "$(cat "$tmp/out")"; fi
fi

# 100 Hz times read as decimals
if run "time column" 0 "0 0\n0.05 1\n" --profile linear; then
    if [ "$(cut -d, -f1 "$tmp/out" | tr '\n' ' ')" = "0 0.01 0.02 0.03 0.04 0.05 " ]; then ok "time column at 100 Hz"
    else ko "time column at 100 Hz" "$(cut -d, -f1 "$tmp/out" | tr '\n' ' ')"; fi
fi

# ---- --fixed agrees with float32 ----
if run "fixed" 0 "$keys" --profile quintic --rate 50 --fixed && cp "$tmp/out" "$tmp/fixed" &&
   run "float" 0 "$keys" --profile quintic --rate 50; then
    worst=$(paste -d, "$tmp/fixed" "$tmp/out" | awk -F, 'function abs(x) { return x < 0 ? -x : x }
        { for (i = 1; i <= 7; i++) { d = abs($i - $(i + 10)); if (d > w) w = d } } END { print w + 0 }')
    if awk -v w="$worst" 'BEGIN { exit !(w < 0.001) }' && [ "$(wc -l <"$tmp/fixed")" -eq "$(wc -l <"$tmp/out")" ]
    then ok "fixed matches float (worst pos/vel diff $worst)"; else ko "fixed matches float" "worst $worst"; fi
fi
expect_err "fixed out of range" 1 "0 0\n1 40000\n" "fixed.*overflow" --fixed

# ---- errors naming the line ----
expect_err "non-monotonic" 1 "0 0\n1 1\n1 2\n" "line 3: time 1 is not after.*line 2"
expect_err "decreasing" 1 "0 0\n2 1\n1 2\n" "line 3: time"
expect_err "column count" 1 "0 0 0\n1 1\n" "line 2: 2 columns, expected 3 as on line 1"
expect_err "not a number" 1 "0 0\n1 abc\n" "line 2: not a number"
expect_err "nan" 1 "0 0\n1 nan\n" "line 2: not a finite number: 'nan' \\(column 2\\)"
expect_err "too few keys" 1 "# only one\n0 0\n" "at least 2 keyframes, got 1"
expect_err "empty input" 1 "" "at least 2 keyframes, got 0"
expect_err "pv columns odd" 1 "0 1 2 3\n" "line 1: 4 columns: expected t and 2" --profile cubic
expect_err "min > max" 2 "0 0 0\n1 1 1\n" "joint 2: min 3 > max 2" --min 0,3 --max 5,2
expect_err "limit count" 2 "0 0 0\n1 1 1\n" "--min has 3 values for 2 joint" --min 0,1,2
expect_err "bad limit" 2 "0 0\n1 1\n" "--min: not a number: 'x' \\(value 1\\)" --min x
expect_err "wrap index" 2 "0 0\n1 1\n" "--wrap: .2. is not a joint number 1..1" --wrap 2
expect_err "vmax with keyframes" 2 "0 0\n1 1\n" "--vmax applies to --profile trapezoid[|]scurve only" --vmax 1
expect_err "sync with keyframes" 2 "0 0\n1 1\n" "--sync applies to --profile trapezoid" --profile quintic --sync time
# --profile trapezoid|scurve are routed to the motion planner by plan.c (tests/cli/test_plan_moves.sh)
expect_err "unknown profile" 2 "0 0\n1 1\n" "--profile: 'bogus' is not linear, cubic" --profile bogus
expect_err "bad rate" 2 "0 0\n1 1\n" "--rate: .0. is not a number in .0.001, 1e.06. Hz" --rate 0
expect_err "cubic needs pv" 2 "0 0\n1 1\n" "cubic needs key velocities" --profile cubic --columns p
expect_err "pv only cubic/quintic" 2 "0 0 0\n1 1 1\n" "only with --profile cubic or quintic" --profile spline --columns pv
expect_err "missing file" 1 "" "nonexistent.*No such file" "$tmp/nonexistent"

# a file argument and '-' both read
printf '0 0\n1 2\n' >"$tmp/keys.txt"
if "$Q" plan --rate 1 --profile linear "$tmp/keys.txt" >"$tmp/out" 2>"$tmp/err" &&
   [ "$(cat "$tmp/out")" = "0,0,2,0
1,2,2,0" ]; then ok "reads a file"; else ko "reads a file" "$(cat "$tmp/out" "$tmp/err")"; fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
