#!/bin/sh
# tools/bench.sh - builds and runs the library comparison and the Cortex-M instruction counts,
# writes build/bench-results/ and draws the report's plots beside its tables there.
#
#   sh tools/bench.sh all     host + qemu + plots (what `make bench` runs)
#   sh tools/bench.sh host    host timing, callgrind instruction counts, accuracy
#   sh tools/bench.sh qemu    Cortex-M0 (soft float) and Cortex-M4F instruction counts
#   sh tools/bench.sh plots   tables + PNGs from existing result files
#
# One flag set for every library (C and C++ alike): bench/compare/build.sh. Override the number of
# timing repetitions with REPS=n (default 41; the median is reported).
set -eu
BUILD=${BUILD:-build}
OUT=$BUILD/bench-results
OBJ=$BUILD/bench-compare
REPS=${REPS:-41}
mkdir -p "$OUT" "$OBJ"

# build_one VARIANT EXTRA_FLAGS: $OBJ/VARIANT/bench with the common flags + EXTRA_FLAGS for every
# source (bench/compare/build.sh, shared with tools/figures/).
build_one() {
    sh bench/compare/build.sh "$OBJ/$1" "$2"
}

# callgrind VARIANT PATTERN: instructions per call of every kernel bk_* matching PATTERN
# (one valgrind run per kernel: only that function is collected, Ir / BK_N).
callgrind() {
    b=$OBJ/$1/bench
    for k in $(nm "$b" | awk -v p="$2" '($2 == "T" || $2 == "t") && $3 ~ p && $3 !~ /_(load|set)$/ { print $3 }' | sort); do
        valgrind --tool=callgrind --callgrind-out-file="$OBJ/cg.out" --toggle-collect="$k" \
            "$b" --once 2> "$OBJ/cg.log"
        awk -v k="${k#bk_}" '/^(summary|totals):/ { printf "ir\t%s\t%.1f\n", k, $2 / 1024; exit }' "$OBJ/cg.out"
    done
}

host() {
    echo "bench: building (flags: see bench/compare/build.sh; and again with -flto)"
    build_one lib ""
    build_one lto "-flto"
    echo "bench: timing ($REPS repetitions of 1024 calls per kernel, interleaved)"
    "$OBJ/lib/bench" --reps "$REPS" > "$OUT/host.tsv"
    "$OBJ/lto/bench" --reps "$REPS" | awk '$2 == "qorient"' > "$OUT/host-lto.tsv"
    if command -v valgrind >/dev/null; then
        echo "bench: callgrind (instructions per call)"
        callgrind lib '^bk_[a-z]+_' > "$OUT/callgrind.tsv"
        callgrind lto '^bk_(qorient|qofx)_' > "$OUT/callgrind-lto.tsv"
    fi
}

case "${1:-all}" in
    host) host ;;
    qemu) sh bench/qemu/run.sh "$OUT" ;;
    plots) sh bench/compare/report.sh "$OUT" ;;
    all) host; sh bench/qemu/run.sh "$OUT"; sh bench/compare/report.sh "$OUT" ;;
    *) echo "usage: $0 [all|host|qemu|plots]" >&2; exit 2 ;;
esac
