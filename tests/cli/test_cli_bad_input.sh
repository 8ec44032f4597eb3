#!/bin/sh
# Bad input of every kind on every subcommand that reads input, as a stranger would feed it:
# endless lines (/dev/zero), a directory on standard input, over-long lines, limits at the
# documented ends of their ranges, float32 overflow, output that would run for hours, bad
# option values. Each case wants a message naming the problem on stderr, the documented exit
# status, a bounded run (timeout 20 s: a hang fails the case, it does not hang the suite) and
# nothing on stdout presented as a result. Prints "N passed, M failed".
Q=${QORIENT:-build/qorient}
T=${TMPDIR:-/tmp}/qo-cli-bad.$$
. tests/common/sh/prelude.sh
MAP=examples/maps/six_int32.ini

# run IN ARGS...: $Q ARGS < IN with a 20 s bound; rc, stdout in $T/o, stderr in $T/e.
run() {
    in=$1; shift
    timeout 20 $Q "$@" < "$in" > "$T/o" 2> "$T/e"; rc=$?
}
# want NAME RC PATTERN: the last run exited RC (124 = it hung), said PATTERN on stderr and
# printed nothing on stdout.
want() {
    if [ "$rc" != "$2" ]; then bad "$1: exit $rc, want $2 ($(head -c 300 "$T/e"))"; return; fi
    grep -q -- "$3" "$T/e" && ok || bad "$1: stderr lacks '$3': $(head -c 300 "$T/e")"
    [ ! -s "$T/o" ] && ok || bad "$1: $(wc -c < "$T/o") bytes on stdout"
}
# want_rec NAME RC PATTERN RECORD: as want, for convert and slerp, which answer each line with
# a line: stdout is exactly RECORD (the "error: REASON" in place of the bad line).
want_rec() {
    printf '%s\n' "$4" > "$T/want"
    if cmp -s "$T/o" "$T/want"; then : > "$T/o"; fi
    want "$1" "$2" "$3"
}

# ---- endless input: /dev/zero is one line that never ends (and NUL bytes) ----
LONG="line 1: longer than 1048576 characters"
REC="error: longer than 1048576 characters"
run /dev/zero convert quat euler:ZYX;  want_rec "convert </dev/zero" 1 "$LONG" "$REC"
run /dev/zero convert quat matrix --fixed; want_rec "convert --fixed </dev/zero" 1 "$LONG" "$REC"
run /dev/zero slerp;                   want_rec "slerp </dev/zero" 1 "$LONG" "$REC"
run /dev/zero plan;                    want "plan </dev/zero" 1 "$LONG"
run /dev/null plan /dev/zero;          want "plan /dev/zero" 1 "/dev/zero: $LONG"
run /dev/zero plan --profile scurve --vmax 1 --amax 1 --jmax 1; want "plan scurve </dev/zero" 1 "$LONG"
run /dev/zero gimbal;                  want "gimbal </dev/zero" 1 "$LONG"
run /dev/null gimbal /dev/zero;        want "gimbal /dev/zero" 1 "$LONG"
# (--dry-run prints the map's wire budget before it reads the plan: only the exit and message)
run /dev/null stream --map $MAP --modbus tcp://127.0.0.1:1 --dry-run /dev/zero
[ "$rc" = 1 ] && grep -q "/dev/zero: $LONG" "$T/e" && ok || bad "stream --dry-run /dev/zero: exit $rc: $(head -c 200 "$T/e")"
run /dev/zero stream --map $MAP --modbus tcp://127.0.0.1:1 --profile scurve --vmax 1 --amax 1 \
    --jmax 1 --live --quiet --no-rt
want "stream --live </dev/zero" 1 "line 1: longer than 65535 characters"

# ---- the longest line read, and one character more ----
awk 'BEGIN { s = "1"; while (length(s) < 1048576) s = s s; print substr(s, 1, 1048576) }' > "$T/max"
awk 'BEGIN { s = "1"; while (length(s) < 1048577) s = s s; print substr(s, 1, 1048577) }' > "$T/over"
run "$T/max" convert quat quat
# (read whole: a number of 1048576 digits, beyond float32, quoted by its first 40)
[ "$rc" = 1 ] && grep -q "line 1: out of float32 range: '1111111111111111111111111111111111111111'\.\.\. (column 1)$" "$T/e" && ok ||
    bad "a line of 1048576 characters is read as a line ($rc: $(head -c 200 "$T/e"))"
run "$T/over" convert quat quat;       want_rec "convert, 1048577 characters" 1 "$LONG" "$REC"
{ echo "0 1 0 0 0"; cat "$T/over"; } > "$T/over2"
run "$T/over2" gimbal;                 want "gimbal, line 2 too long" 1 "line 2: longer than 1048576 characters"
# convert answers line by line: the lines before the long one are printed, the exit is 1
{ echo "1 0 0 0"; cat "$T/over"; echo "1 0 0 0"; } > "$T/mixed"
timeout 20 $Q convert quat quat < "$T/mixed" > "$T/o" 2> "$T/e"; rc=$?
printf '1 0 0 0\n%s\n' "$REC" > "$T/want"
[ "$rc" = 1 ] && cmp -s "$T/o" "$T/want" && grep -q "line 2: longer than" "$T/e" && ok ||
    bad "convert after an over-long line: exit $rc, stdout '$(head -c 100 "$T/o")'"

# ---- a directory on standard input is a read error, not an empty input ----
run "$T" convert quat quat;            want "convert <directory" 1 "read error: Is a directory"
run "$T" slerp;                        want "slerp <directory" 1 "read error: Is a directory"
run "$T" plan;                         want "plan <directory" 1 "read error: Is a directory"
run "$T" gimbal;                       want "gimbal <directory" 1 "read error: Is a directory"

# ---- limits at the documented ends of their ranges: [1e-3, 1e9], asymmetry within 20x ----
printf '0,0\n1,1\n' > "$T/p"
for opt in --vmax --amax --jmax; do
    set -- --vmax 1 --amax 1 --jmax 1 "$opt" 1e9
    run "$T/p" plan --profile scurve "$@"
    [ "$rc" = 0 ] && [ -s "$T/o" ] && ok || bad "plan $opt 1e9 (the top of the range) refused: $(head -c 200 "$T/e")"
    set -- --vmax 1 --amax 1 --jmax 1 "$opt" 1.0001e9
    run "$T/p" plan --profile scurve "$@"; want "plan $opt 1.0001e9" 2 "$opt: value 1 (1.0001e+09) is not a number in \[0.001, 1e+09\]"
done
run "$T/p" plan --profile scurve --vmax 1 --amax 1 --jmax 1 --vmin -20
[ "$rc" = 0 ] && ok || bad "plan --vmin -20 with --vmax 1 (the ratio bound) refused: $(head -c 200 "$T/e")"
run "$T/p" plan --profile scurve --vmax 1 --amax 1 --jmax 1 --vmin -20.01
want "plan --vmin -20.01 --vmax 1" 2 "--vmin: joint 1: -20.01 is not within a factor 20 of -vmax"
run "$T/p" plan --profile scurve --vmax 1 --amax 30 --jmax 1 --amin -1
want "plan --amin -1 --amax 30" 2 "--amin: joint 1: -1 is not within a factor 20 of -amax"
run "$T/p" plan --profile scurve --vmax 1e-3 --amax 1 --jmax 1 --rate 0.01
[ "$rc" = 0 ] && ok || bad "plan --vmax 1e-3 (the bottom of the range) refused: $(head -c 200 "$T/e")"
run "$T/p" plan --profile scurve --vmax 9.99e-4 --amax 1 --jmax 1
want "plan --vmax 9.99e-4" 2 "is not a number in \[0.001, 1e+09\]"
run "$T/p" plan --max-samples 1.5;     want "plan --max-samples 1.5" 2 "max-samples: '1.5' is not a whole number"

# ---- gimbal: float32 overflow names its line; output that would not end is refused first ----
printf '0 1 0 0 0\n2 1e39 0 0 0\n' > "$T/g"
run "$T/g" gimbal;                     want "gimbal 1e39" 1 "line 2: out of float32 range: '1e39' (column 2)"
printf '0 1 0 0 0\n2 0.7071068 0 0.7071068 0\n4 0 0 1 0\n' > "$T/g"
# a path the joints never catch up with: an hour of rows, exit 1, said (test_cli_contracts.sh)
run "$T/g" gimbal --vmax 1e-30 --rate 10
[ "$rc" = 1 ] && grep -q "after one hour of catch-up --vmax still holds joints back" "$T/e" && ok ||
    bad "gimbal --vmax 1e-30: exit $rc: $(head -c 200 "$T/e")"
run "$T/g" gimbal --amax 1e-3 --rate 1e6
want "gimbal --amax 1e-3 --rate 1e6 (hours of rows)" 1 "more than --max-samples 1000000"
run "$T/g" gimbal --rate 1000 --max-samples 4000
want "gimbal --max-samples under the path" 1 "more than --max-samples 4000"
run "$T/g" gimbal --rate 1000 --max-samples 4001
[ "$rc" = 0 ] && [ "$(wc -l < "$T/o")" = 4001 ] && ok || bad "gimbal --max-samples 4001: exit $rc, $(wc -l < "$T/o") rows"
run "$T/g" gimbal --max-samples 0;     want "gimbal --max-samples 0" 2 "max-samples: '0' is not a whole number in \[1, 1e+10\]"
run "$T/g" gimbal --max-samples nan;   want "gimbal --max-samples nan" 2 "max-samples: 'nan' is not a whole number"
# the same path sampled twice (count, then print) prints what one pass printed before: the
# rows of the reference run at 50 Hz with the filter, checked by their count and last row
run "$T/g" gimbal --rate 50 --amax 2 --jmax 20
[ "$rc" = 0 ] && tail -1 "$T/o" | awk -F, '{ exit !($7 == 0 && $6 == 0) }' && ok || bad "gimbal --amax 2 --jmax 20: exit $rc"

# ---- option values: ranges named ----
run /dev/null sim --map $MAP --lag 1e39 --duration 1; want "sim --lag 1e39" 2 "lag: '1e39' is not a number in \[0, 1e+06\] s"
run /dev/null sim --map $MAP --duration 1e300;      want "sim --duration 1e300" 2 "duration: '1e300' is not a number in \[0, 1e+09\] s"
run /dev/null sim --map $MAP --duration nan;        want "sim --duration nan" 2 "duration: 'nan' is not a number"
printf '0,0,0\n1,1,1\n' > "$T/s2"
run "$T/s2" stream --gpio gpiochip0 --lines 1:2,3:4 --steps-per-unit nan --dry-run
want "stream --dry-run --steps-per-unit nan" 2 "steps-per-unit: not a finite number: 'nan' (value 1)"
run "$T/s2" stream --gpio gpiochip0 --lines 1:2,3:4 --step-rate -1 --dry-run
want "stream --dry-run --step-rate -1" 2 "step-rate: value 1 (-1) is not a number"
for l in -1:2,3:4 1e30:2,3:4 1.5:2,3:4 1:2,3; do
    run "$T/s2" stream --gpio gpiochip0 --lines $l --dry-run
    want "stream --lines $l" 2 "lines: '$l' is not STEP:DIR"
done
run "$T/s2" stream --gpio gpiochip0 --lines 1:2,3:4 --steps-per-unit 100,200 --dry-run
[ "$rc" = 0 ] && ok || bad "stream --dry-run with good --steps-per-unit: exit $rc"

# ---- output that cannot be written (a full disk) is not a success ----
printf '0,0\n1,1\n' > "$T/p"
printf '0 1 0 0 0\n1 0 0 0 1\n' > "$T/g"
for c in "convert quat quat" "slerp" "plan" "gimbal" "--help" "--version" "convert --help"; do
    case $c in
    convert\ quat*) echo '1 0 0 0' > "$T/in" ;;
    slerp) echo '1 0 0 0 0 0 0 1 0.5' > "$T/in" ;;
    plan) cp "$T/p" "$T/in" ;;
    gimbal) cp "$T/g" "$T/in" ;;
    *) : > "$T/in" ;;
    esac
    timeout 20 $Q $c < "$T/in" > /dev/full 2> "$T/e"; rc=$?
    [ "$rc" = 1 ] && grep -q "standard output: write error" "$T/e" && ok ||
        bad "qorient $c > /dev/full: exit $rc: $(head -c 200 "$T/e")"
done
timeout 20 $Q sim --map $MAP --log /dev/full --duration 0 > "$T/o" 2> "$T/e"; rc=$?
[ "$rc" = 1 ] && grep -q "log '/dev/full': write error" "$T/e" && ok ||
    bad "sim --log /dev/full: exit $rc: $(head -c 200 "$T/e")"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
