#!/bin/sh
# Figures section "stream" (live): qorient stream against qorient sim with drives that answer
# late (tools/stream-figures.sh, FIGURES_STREAM_SECONDS each, default 20; the 60 s with
# FIGURES_STREAM_SECONDS=60), the Modbus sink against a bare libmodbus loop
# (build/bench/bench_modbus), and the fault scenarios of the live stream
# (build/tests/test_stream_faults: faults injected and survived, steps above max_step).
set -eu
BUILD=${BUILD:-build}
S=${FIGURES_STREAM_SECONDS:-20}
echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC') on $(uname -m), $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg)."
echo
echo '```'
echo "\$ sh tools/stream-figures.sh --seconds $S"
sh tools/stream-figures.sh --seconds "$S" 2>&1 | grep -v '^make'
echo "\$ build/bench/bench_modbus"
make -s --no-print-directory "$BUILD/bench/bench_modbus" >/dev/null 2>&1
"$BUILD/bench/bench_modbus" 2>&1
echo "\$ build/tests/test_stream_faults | grep '^stream_faults:'"
make -s --no-print-directory "$BUILD/tests/test_stream_faults" >/dev/null 2>&1
"$BUILD/tests/test_stream_faults" 2>&1 | grep '^stream_faults:'
echo '```'
