#!/bin/sh
# fuzz/run.sh SECONDS NAME... - runs build/fuzz/fuzz_NAME for SECONDS each, FUZZ_JOBS of them at
# a time (default 1: the machine may be shared; `make fuzz-ci` gives one per core), and prints per
# target, in the order given, the executions (libFuzzer's stat::number_of_executed_units from
# -print_final_stats=1), then a last line "N passed, M failed". A target fails on any finding
# (crash, sanitizer report, property violation, timeout, leak, out-of-memory): its input is kept
# in $FUZZ_BUILD/artifacts and the log in $FUZZ_BUILD/logs/NAME.log. Exit status 1 if any
# target failed.
#
# Environment: FUZZ_BUILD (default build/fuzz), FUZZ_MAX_LEN (default 4096 bytes per input),
# FUZZ_TIMEOUT (seconds one input may take, default 10), FUZZ_ARGS (extra libFuzzer flags),
# FUZZ_JOBS (targets run at once, default 1).
set -u
secs=$1; shift
B=${FUZZ_BUILD:-build/fuzz}
jobs=${FUZZ_JOBS:-1}
case $jobs in ''|*[!0-9]*|0) jobs=1;; esac
mkdir -p "$B/artifacts" "$B/logs"

# one NAME: runs one target; its report goes to $B/logs/NAME.report, its verdict (ok or
# failed) to $B/logs/NAME.verdict.
one() {
    name=$1
    bin=$B/fuzz_$name
    log=$B/logs/$name.log
    work=$B/corpus/$name
    mkdir -p "$work"
    dirs="$work"
    for d in fuzz/corpus/$name fuzz/regress/$name; do [ -d "$d" ] && dirs="$dirs $d"; done
    if [ ! -x "$bin" ]; then
        echo "fuzz $name: no binary $bin" >"$B/logs/$name.report"; echo failed >"$B/logs/$name.verdict"
        return
    fi
    # shellcheck disable=SC2086  # word splitting of $dirs and $FUZZ_ARGS is intended
    "$bin" -max_total_time="$secs" -print_final_stats=1 -timeout="${FUZZ_TIMEOUT:-10}" \
        -max_len="${FUZZ_MAX_LEN:-4096}" -artifact_prefix="$B/artifacts/$name-" \
        ${FUZZ_ARGS:-} $dirs >"$log" 2>&1
    rc=$?
    execs=$(sed -n 's/^stat::number_of_executed_units: *\([0-9]*\).*/\1/p' "$log" | tail -1)
    rate=$(sed -n 's/^stat::average_exec_per_sec: *\([0-9]*\).*/\1/p' "$log" | tail -1)
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | sed 's/cov: //')
    if [ "$rc" -eq 0 ]; then
        echo "fuzz $name: ok, ${execs:-0} executions in ${secs} s (${rate:-0}/s, cov ${cov:-?})"
        echo ok >"$B/logs/$name.verdict"
    else
        echo "fuzz $name: FAILED (exit $rc) after ${execs:-?} executions; log $log"
        grep -E '^(==[0-9]+==ERROR|SUMMARY|fuzz property violated|.*runtime error)' "$log" | head -5
        grep -E 'Test unit written to' "$log" | head -2
        echo failed >"$B/logs/$name.verdict"
    fi >"$B/logs/$name.report"
}

# In batches of $jobs (every target runs for the same time, so a batch ends together).
i=0
for name in "$@"; do
    rm -f "$B/logs/$name.verdict" "$B/logs/$name.report"
    one "$name" &
    i=$((i + 1))
    [ $((i % jobs)) -eq 0 ] && wait
done
wait
passed=0; failed=0
for name in "$@"; do
    cat "$B/logs/$name.report" 2>/dev/null || echo "fuzz $name: no report"
    if [ "$(cat "$B/logs/$name.verdict" 2>/dev/null)" = ok ]; then passed=$((passed + 1)); else failed=$((failed + 1)); fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
