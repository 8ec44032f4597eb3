#!/bin/sh
# Figures section "motion" (live: timings): planning time of 7 jerk-limited, time-synchronised
# joints against the planner of commit 9bf587d on the same cases in one run (make bench-motion)
# and the sampling cost per joint per tick, float32 and Q16.16 (build/bench/bench_motion). The
# same comparison in instructions per plan (deterministic, compared by make figures-check) is
# section "motion-ir" (tools/figures/motion-ir.sh).
# The planner's optimality and limits are judged by make test / make check-motion (an
# independent double-precision reference, tests/common/motion_ref.c), not here.
set -eu
BUILD=${BUILD:-build}
echo "Measured $(date -u '+%Y-%m-%d %H:%M UTC') on $(uname -m), $(nproc) CPUs, load average $(cut -d' ' -f1-3 /proc/loadavg)."
echo
echo '```'
echo "\$ make bench-motion MOTION_CASES=2000"
make -s --no-print-directory bench-motion MOTION_CASES=2000 2>&1
echo "\$ build/bench/bench_motion 1000"
make -s --no-print-directory "$BUILD/bench/bench_motion" >/dev/null 2>&1
"$BUILD/bench/bench_motion" 1000 2>&1
echo '```'
