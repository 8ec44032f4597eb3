#!/bin/sh
# bench/motion/ir.sh [N] - instructions per plan (callgrind Ir) of today's planner and of the
# planner of commit 9bf587d on make bench-motion's cases (N per scenario, default 2000): each
# plan one callgrind dump part (build/bench/motion_ir --ir N). Deterministic for one compiler,
# so the speed ratio can be followed without the shared machine's timing noise. Prints median,
# p99 and worst per planner and scenario and the per-case ratio old / new (median, p1), like
# make bench-motion; the per-case counts go to $BUILD/figures/motion-ir/cases.txt
# (scenario case new old).
set -eu
BUILD=${BUILD:-build}
N=${1:-2000}
D=$BUILD/figures/motion-ir
mkdir -p "$D"
valgrind --tool=callgrind --collect-atstart=yes --combine-dumps=yes --dump-instr=no --dump-line=no \
    --callgrind-out-file="$D/cg.out" "$BUILD/bench/motion_ir" --ir "$N" >"$D/log" 2>&1 || {
    cat "$D/log"
    exit 1
}
# parts in order: per scenario (rest, moving), per case: new, old; then the exit's
awk -v n="$N" '/^totals:/ { k = np++; if (k >= 4 * n) next
        s = int(k / (2 * n)); c = int((k % (2 * n)) / 2)
        if (k % 2 == 0) nw[s, c] = $2; else print (s ? "moving" : "rest"), c, nw[s, c], $2 }' \
    "$D/cg.out" >"$D/cases.txt"
[ "$(wc -l <"$D/cases.txt")" -eq $((2 * N)) ] || { echo "motion-ir: expected $((2 * N)) plans" >&2; exit 1; }
echo "motion planning, 7 joints, SCURVE, SYNC_TIME, $N cases per scenario, instructions per plan (callgrind Ir)"
for s in rest moving; do
    [ $s = rest ] && echo "from rest:" || echo "from moving starts:"
    for col in 3 4; do
        awk -v s=$s -v c=$col '$1 == s { print $c }' "$D/cases.txt" | sort -n | awk -v name="$([ $col = 3 ] && echo 'today (this tree)' || echo 'before (9bf587d)')" '
            { x[NR] = $1 } END { printf "  %-26s median %6d Ir  p99 %6d Ir  worst %7d Ir\n", name,
                x[int(NR / 2) + 1], x[int(0.99 * (NR - 1)) + 1], x[NR] }'
    done
    awk -v s=$s '$1 == s { printf "%.6f\n", $4 / $3 }' "$D/cases.txt" | sort -g | awk '
        { x[NR] = $1 } END { printf "  per-case speed-up old/new: median %.2fx, p1 %.2fx\n", x[int(NR / 2) + 1], x[int(NR / 100) + 1] }'
done
