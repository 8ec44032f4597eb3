#!/bin/sh
# Figures section "motion-ir" (check: deterministic): instructions per plan (callgrind Ir) of
# 7 jerk-limited, time-synchronised joints, today's planner against the planner of commit
# 9bf587d on the same fixed-seed cases (make bench-motion-ir, bench/motion/ir.sh): median, p99
# and worst per planner and scenario, and the per-case ratio old / new. Deterministic for one
# compiler (the same code and toolchain give the same text), so make figures-check compares it;
# the timed comparison on the machine is section "motion" (live). 2000 cases per scenario: the
# whole section takes about a minute under callgrind. Needs valgrind.
set -eu
BUILD=${BUILD:-build}
echo '```'
echo "\$ make bench-motion-ir MOTION_CASES=2000"
make -s --no-print-directory bench-motion-ir MOTION_CASES=2000 2>&1
echo '```'
