#!/bin/sh
# fuzz/run.sh SECONDS NAME... - runs build/fuzz/fuzz_NAME for SECONDS each, one after the
# other (one fuzzer at a time: the machine is shared), and prints per target the executions
# (libFuzzer's stat::number_of_executed_units from -print_final_stats=1), then a last line
# "N passed, M failed". A target fails on any finding (crash, sanitizer report, property
# violation, timeout, leak, out-of-memory): its input is kept in $FUZZ_BUILD/artifacts and
# the log in $FUZZ_BUILD/logs/NAME.log. Exit status 1 if any target failed.
#
# Environment: FUZZ_BUILD (default build/fuzz), FUZZ_MAX_LEN (default 4096 bytes per input),
# FUZZ_TIMEOUT (seconds one input may take, default 10), FUZZ_ARGS (extra libFuzzer flags).
set -u
secs=$1; shift
B=${FUZZ_BUILD:-build/fuzz}
passed=0; failed=0
mkdir -p "$B/artifacts" "$B/logs"
for name in "$@"; do
    bin=$B/fuzz_$name
    log=$B/logs/$name.log
    work=$B/corpus/$name
    mkdir -p "$work"
    dirs="$work"
    for d in fuzz/corpus/$name fuzz/regress/$name; do [ -d "$d" ] && dirs="$dirs $d"; done
    if [ ! -x "$bin" ]; then
        echo "fuzz $name: no binary $bin"; failed=$((failed + 1)); continue
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
        passed=$((passed + 1))
        echo "fuzz $name: ok, ${execs:-0} executions in ${secs} s (${rate:-0}/s, cov ${cov:-?})"
    else
        failed=$((failed + 1))
        echo "fuzz $name: FAILED (exit $rc) after ${execs:-?} executions; log $log"
        grep -E '^(==[0-9]+==ERROR|SUMMARY|fuzz property violated|.*runtime error)' "$log" | head -5
        grep -E 'Test unit written to' "$log" | head -2
    fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
