#!/bin/sh
# The input edges every subcommand that reads numbers shares (issues #16, #11):
#  1. one parser, one truth: a number float32 cannot hold (1e39, 1e400) is "out of float32
#     range", NaN and Inf are "not a finite number", each with its line, its column and the
#     documented exit status, in convert, slerp, plan (keyframes and targets), gimbal and
#     stream; the float32 bound itself against Python's struct (an independent float32
#     rounding) on random values around it, fixed seed;
#  2. messages repeat at most 40 bytes of the input, quoted, non-printables as \xNN: random
#     binary input (NUL bytes, control characters, long lines, fixed seed) gives stderr lines
#     of printable ASCII only, short;
#  3. the reads that keep what they read are bounded and refused at the line that crosses the
#     bound, never after reading everything: endless generated inputs (keyframes dense in
#     time, keyframes spanning too long, wide lines, comments) end with the message naming
#     that line, within `timeout` (a reader that read it all would hang and fail the case).
# (/dev/zero and a directory as input: test_cli_bad_input.sh.) Prints "N passed, M failed".
Q=${QORIENT:-build/qorient}
T=${TMPDIR:-/tmp}/qo-cli-edges.$$
. tests/common/sh/prelude.sh
MAP=examples/maps/six_int32.ini
STREAM="stream --map $MAP --modbus tcp://127.0.0.1:1 --dry-run"
LIVE="stream --map $MAP --modbus tcp://127.0.0.1:1 --profile scurve --vmax 1 --amax 1 --jmax 1 --live --quiet --no-rt"
SCURVE="--profile scurve --vmax 1 --amax 1 --jmax 1"

# run IN ARGS...: $Q ARGS < IN, bounded; rc, stdout in $T/o, stderr in $T/e.
run() {
    in=$1; shift
    timeout 60 $Q "$@" < "$in" > "$T/o" 2> "$T/e"; rc=$?
}
# said NAME RC LINE: the last run exited RC and its stderr has the line LINE, whole (grep -F -x).
said() {
    if [ "$rc" != "$2" ]; then bad "$1: exit $rc, want $2: $(head -c 300 "$T/e")"; return; fi
    grep -F -x -q -- "$3" "$T/e" && ok || bad "$1: stderr lacks the line '$3': $(head -c 300 "$T/e")"
}

# ---- 1. out of float32 range vs not finite: the same words from every subcommand ----
# each class through every reader (a field as given|the reason said)
while IFS='|' read -r field reason; do
    # convert and slerp answer in place: the record is "error: REASON", stderr names the line
    printf '1 0 0 0\n0 %s 0 1\n' "$field" > "$T/in"
    for fx in "" --fixed; do
        run "$T/in" convert quat quat $fx
        said "convert $fx $field" 1 "qorient convert: line 2: $reason: '$field' (column 2)"
        [ "$(sed -n 2p "$T/o")" = "error: $reason: '$field' (column 2)" ] && ok ||
            bad "convert $fx $field: record '$(sed -n 2p "$T/o")'"
    done
    printf '1 0 0 0 0 0 1 0 0.5\n1 0 0 0 0 0 %s 0 0.5\n' "$field" > "$T/in"
    for fx in "" --fixed; do
        run "$T/in" slerp $fx
        said "slerp $fx $field" 1 "qorient slerp: line 2: $reason: '$field' (column 7)"
        [ "$(sed -n 2p "$T/o")" = "error: $reason: '$field' (column 7)" ] && ok || bad "slerp $fx $field: record"
    done
    # plan, gimbal, stream: refused before anything is printed or sent
    printf '0,0,0\n1,2,%s\n' "$field" > "$T/in"
    run "$T/in" plan;                  said "plan $field" 1 "qorient plan: -: line 2: $reason: '$field' (column 3)"
    [ -s "$T/o" ] && bad "plan $field: stdout" || ok
    run "$T/in" plan $SCURVE;          said "plan scurve $field" 1 "qorient plan: -: line 2: $reason: '$field' (column 3)"
    printf '0 1 0 0 0\n%s 0 1 0 0\n' "$field" > "$T/in"
    run "$T/in" gimbal;                said "gimbal $field" 1 "qorient gimbal: line 2: $reason: '$field' (column 1)"
    [ -s "$T/o" ] && bad "gimbal $field: stdout" || ok
    printf '0,0,0,0,0,0,0\n1,0,0,0,%s,0,0\n' "$field" > "$T/in"
    run "$T/in" $STREAM -;             said "stream $field" 1 "qorient stream: -: line 2: $reason: '$field' (column 5)"
    printf '%s,0,0,0,0,0\n' "$field" > "$T/in"
    run "$T/in" $LIVE;                 said "stream --live $field" 1 "qorient stream: -: line 1: $reason: '$field' (column 1)"
done <<'EOF'
1e39|out of float32 range
nan|not a finite number
EOF
# the other spellings of each class, in one run of the shared parser
printf '%s\n' '-3.5e38 0 0 1' '0 1e400 0 1' '0 0 -1e309 1' '-inf 0 0 1' '0 Infinity 0 1' '0 0 NAN 1' > "$T/in"
run "$T/in" convert quat quat
printf '%s\n' "error: out of float32 range: '-3.5e38' (column 1)" "error: out of float32 range: '1e400' (column 2)" \
    "error: out of float32 range: '-1e309' (column 3)" "error: not a finite number: '-inf' (column 1)" \
    "error: not a finite number: 'Infinity' (column 2)" "error: not a finite number: 'NAN' (column 3)" > "$T/want"
[ "$rc" = 1 ] && cmp -s "$T/o" "$T/want" && ok || bad "spellings of out of range and not finite: $(diff "$T/want" "$T/o" | head -5)"
# an option list goes through the same parser
printf '0,0\n1,1\n' > "$T/in"
run "$T/in" plan --max 1e39;           said "plan --max 1e39" 2 "qorient plan: --max: out of float32 range: '1e39' (value 1)"
run "$T/in" plan $SCURVE --vmax 1,nan; said "plan --vmax 1,nan" 2 "qorient plan: --vmax: not a finite number: 'nan' (value 2)"
# the largest float32 and what rounds to it are numbers; 1e-400 (below every subnormal) is 0
printf '3.4028235e38 0 0 0\n3.40282356e38 0 0 0\n1 1e-400 0 0\n' > "$T/in"
run "$T/in" convert quat quat
[ "$rc" = 0 ] && [ "$(cat "$T/o" | tr '\n' ' ')" = "1 0 0 0 1 0 0 0 1 0 0 0 " ] && ok ||
    bad "FLT_MAX and 1e-400 refused: exit $rc: $(cat "$T/o" "$T/e" | head -c 300)"

# The bound itself against an independent float32 rounding: Python's struct.pack('f') raises
# OverflowError exactly when a double rounds beyond float32. Values spread over a few float32
# ulps either side of the bound (2^128 - 2^103, a tie that rounds to infinity) and over
# 1e30..1e45, both signs, the two doubles next to the bound, fixed seed; printed with 17
# digits, so the command reads the very double Python judged.
python3 - "$T/vals" "$T/want" <<'EOF'
import random, struct, sys
rng = random.Random(20261202)
edge = 2.0**128 - 2.0**103
vals = [edge, float.fromhex('0x1.fffffefffffffp127'), float.fromhex('0x1.ffffff0000001p127'),
        float.fromhex('0x1.fffffep127'), 3.4028235e38, 3.4028236e38]
for _ in range(1500):
    vals.append(edge + rng.uniform(-4, 4) * 2.0**104)
for _ in range(500):
    vals.append(10.0 ** rng.uniform(30, 45))
vals = [v if rng.random() < 0.5 else -v for v in vals]
with open(sys.argv[1], 'w') as f, open(sys.argv[2], 'w') as w:
    for v in vals:
        try:
            struct.pack('<f', v)
            ok = 'in'
        except OverflowError:
            ok = 'out'
        f.write('%.17g 0 0 1\n' % v)
        w.write(ok + '\n')
EOF
run "$T/vals" convert quat quat
awk '{ print ($0 ~ /^error: out of float32 range: /) ? "out" : ($0 ~ /^error/ ? "other: " $0 : "in") }' "$T/o" > "$T/got"
n_out=$(grep -c '^out$' "$T/want")
if cmp -s "$T/want" "$T/got"; then ok; else
    bad "float32 range: $(paste -d' ' "$T/vals" "$T/want" "$T/got" | awk '$5 != $6' | head -3)"
fi
[ "$n_out" -gt 500 ] && [ "$n_out" -lt 1500 ] && ok || bad "float32 range: $n_out of 2006 out: not both sides"

# ---- 2. messages quote at most 40 bytes of the input, escaped ----
# a control character, DEL, a quote, a backslash and 100 more bytes: 40 bytes quoted, then ...
printf '0,0\n1,\001\177'"'"'\\%0100d\n' 0 > "$T/in"
Y="\\x01\\x7f\\'\\\\$(printf '%036d' 0)"
run "$T/in" plan;   said "plan quotes the field" 1 "qorient plan: -: line 2: not a number: '$Y'... (column 2)"
printf '1 0 0 0\n1 \001\177'"'"'\\%0100d 0 0\n' 0 > "$T/in"
run "$T/in" convert quat quat
said "convert quotes the field" 1 "qorient convert: line 2: not a number: '$Y'... (column 2)"
printf '0 1 0 0 0\n1 \001\177'"'"'\\%0100d 0 0 0\n' 0 > "$T/in"
run "$T/in" gimbal; said "gimbal quotes the field" 1 "qorient gimbal: line 2: not a number: '$Y'... (column 2)"
# an option value and an unknown command, the same way
run /dev/null plan --profile "$(printf 'x\033[2Jy')"
said "plan --profile ESC" 2 "qorient plan: --profile: 'x\x1b[2Jy' is not linear, cubic, catmull, spline, quintic, trapezoid or scurve"
run /dev/null $STREAM --on-fail "$(printf 'a\033b')" -
said "stream --on-fail ESC" 2 "qorient stream: --on-fail: 'a\x1bb' is not hold or disable"
run /dev/null sim --map $MAP --fault "$(printf 'drop\001')"
said "sim --fault ^A" 2 "qorient sim: bad --fault 'drop\x01' (delay:MS, drop, exception, close)"
run /dev/null "$(printf 'no\tsuch%060d' 0)"
grep -F -q "qorient: unknown command 'no\\x09such$(printf '%033d' 0)'..." "$T/e" && ok ||
    bad "unknown command not quoted: $(head -c 200 "$T/e")"
# printable NAME: $T/e.all is short lines of printable ASCII
printable() {
    if LC_ALL=C grep -q '[^ -~]' "$T/e.all" || awk 'length($0) > 200 { f = 1 } END { exit !f }' "$T/e.all"; then
        bad "$1, binary input: stderr not short printable ASCII: $(LC_ALL=C grep -v '^[ -~]*$' "$T/e.all" | head -1 | od -c | head -2)"
    else ok; fi
}
# random binary input (NUL bytes, control characters, bytes >= 0x80, lines of any length):
# whatever the subcommand says, stderr is printable ASCII in short lines
python3 -c '
import random, sys
rng = random.Random(11)
out = bytearray()
for _ in range(400):
    n = rng.choice([0, 1, 5, 40, 300])
    out += bytes(rng.randrange(256) for _ in range(n)) + b"\n"
sys.stdout.buffer.write(bytes(out))' > "$T/bin"
# convert and slerp answer every line (one message each); the others stop at the first bad
# line: one run each for lines of every length, after a good first line (--live: first)
for c in "convert quat quat" "slerp"; do
    run "$T/bin" $c; mv "$T/e" "$T/e.all"
    [ "$(wc -l < "$T/e.all")" -gt 300 ] && ok || bad "qorient $c, binary input: $(wc -l < "$T/e.all") messages"
    printable "qorient $c"
done
for c in "plan" "plan $SCURVE" "gimbal" "$STREAM -" "$LIVE"; do
    : > "$T/e.all"
    for i in 1 2 3 4 5 6; do
        case $c in gimbal) echo '0 1 0 0 0' ;; *--live*) : ;; *) echo '0,0,0,0,0,0,0' ;; esac > "$T/in"
        awk -v i=$i 'length($0) > 0 && ++n == i' "$T/bin" >> "$T/in"
        run "$T/in" $c; cat "$T/e" >> "$T/e.all"
        [ "$rc" = 1 ] || bad "qorient $c, binary line $i: exit $rc"
    done
    [ "$(wc -l < "$T/e.all")" -ge 6 ] && ok || bad "qorient $c, binary input: $(wc -l < "$T/e.all") messages"
    printable "qorient $c"
done

# ---- 3. bounded reads: refused at the line that crosses the bound ----
# endless GEN (an awk program) into the command; the reader must stop on its own
endless() {
    gen=$1; shift
    awk "BEGIN { for (i = 0; ; i++) $gen }" 2>/dev/null | timeout 60 $Q "$@" > "$T/o" 2> "$T/e"; rc=$?
}
# more keyframes than --max-samples: line 1001 of keyframes 1 us apart (a short plan)
endless 'printf "%.6f,0\n", i * 1e-6' plan --max-samples 1000
said "plan: keyframes over --max-samples" 1 \
    "qorient plan: -: line 1001: more than --max-samples 1000 keyframes: nothing more is read (raise --max-samples)"
endless 'printf "%.6f,0\n", i * 1e-6' plan --max-samples 1000 $SCURVE
said "plan: targets over --max-samples" 1 \
    "qorient plan: -: line 1001: more than --max-samples 1000 targets: nothing more is read (raise --max-samples)"
endless 'printf "%.6f 1 0 0 0\n", i * 1e-6' gimbal --max-samples 1000
said "gimbal: keyframes over --max-samples" 1 \
    "qorient gimbal: line 1001: more than --max-samples 1000 keyframes: nothing more is read (raise --max-samples)"
endless 'printf "%.6f,0,0,0,0,0,0\n", i * 1e-6' $STREAM --max-samples 1000 -
said "stream: keyframes over --max-samples" 1 \
    "qorient stream: -: line 1001: more than --max-samples 1000 keyframes: nothing more is read (raise --max-samples)"
# keyframes 1 s apart at 100 Hz: line 11 (t = 10 s) makes 1001 samples
endless 'printf "%d,0\n", i' plan --max-samples 1000
said "plan: the span over --max-samples" 1 "qorient plan: -: line 11: the plan is at least 1001 samples at 100 Hz by this line's time, more than --max-samples 1000: lower --rate or raise --max-samples"
endless 'printf "%d,0\n", i' plan --max-samples 1000 $SCURVE
said "plan: targets spanning over --max-samples" 1 "qorient plan: -: line 11: the plan is at least 1001 samples at 100 Hz by this line's time, more than --max-samples 1000: lower --rate or raise --max-samples"
endless 'printf "%d 1 0 0 0\n", i' gimbal --max-samples 1000
said "gimbal: the span over --max-samples" 1 "qorient gimbal: line 11: the output is at least 1001 rows at 100 Hz by this key's time, more than --max-samples 1000: lower --rate or raise --max-samples"
# ... and one sample less is read whole and planned
printf '0,0\n9.99,1\n' > "$T/in"
run "$T/in" plan --max-samples 1000
[ "$rc" = 0 ] && [ "$(wc -l < "$T/o")" = 1000 ] && ok || bad "plan of exactly --max-samples rows: exit $rc, $(wc -l < "$T/o") rows"
# wide lines: 3072 joints a line, 4194304 numbers kept at most: line 1366 (1366 x 3072 > 2^22)
z=$(awk 'BEGIN { for (j = 0; j < 3072; j++) printf ",0" }')
awk -v z="$z" 'BEGIN { for (i = 0; ; i++) printf "%.6f%s\n", i * 1e-6, z }' 2>/dev/null | timeout 60 $Q plan > "$T/o" 2> "$T/e"; rc=$?
said "plan: wide lines over the numbers kept" 1 \
    "qorient plan: -: line 1366: more than 4194304 numbers (keyframes or targets x columns): nothing more is read"
# bytes: 64 MiB of comments (2 bytes a line): line 33554433 is past the bound
for c in plan gimbal "$STREAM -"; do
    yes '#' 2>/dev/null | timeout 120 $Q $c > "$T/o" 2> "$T/e"; rc=$?
    case $c in gimbal) w="qorient gimbal: line 33554433" ;; *) w="qorient ${c%% *}: -: line 33554433" ;; esac
    said "$c: bytes over 64 MiB" 1 "$w: the input is longer than 67108864 bytes: nothing more is read"
done

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
