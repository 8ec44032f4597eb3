#!/bin/sh
# tools/bench.sh - builds and runs the library comparison and the Cortex-M instruction counts,
# writes build/bench-results/ and regenerates the report's plots (docs/img/*.png).
#
#   sh tools/bench.sh all     host + qemu + plots (what `make bench` runs)
#   sh tools/bench.sh host    host timing, callgrind instruction counts, accuracy
#   sh tools/bench.sh qemu    Cortex-M0 (soft float) and Cortex-M4F instruction counts
#   sh tools/bench.sh plots   tables + PNGs from existing result files
#
# One flag set for every library (C and C++ alike): BENCH_FLAGS below. Override the number of
# timing repetitions with REPS=n (default 41; the median is reported).
set -eu
BUILD=${BUILD:-build}
OUT=$BUILD/bench-results
OBJ=$BUILD/bench-compare
REPS=${REPS:-41}
BENCH_FLAGS="-O2 -ffp-contract=off -march=x86-64 -g"
mkdir -p "$OUT" "$OBJ"

# build_one VARIANT EXTRA_FLAGS: builds $OBJ/VARIANT/bench with BENCH_FLAGS + EXTRA_FLAGS for
# every source (qorient, cglm, Eigen and the driver alike; libfixmath is Debian's prebuilt .a).
build_one() {
    d=$OBJ/$1; f="$BENCH_FLAGS $2"; objs=""
    mkdir -p "$d"
    for s in lib/src/*.c; do
        o=$d/lib_$(basename "$s" .c).o
        gcc -std=c99 $f -Ilib/include -c "$s" -o "$o"; objs="$objs $o"
    done
    gcc -std=c99 $f -Ilib/include -Itests -c tests/common/ref.c -o "$d/ref.o"
    for s in bench/compare/*.c; do
        o=$d/$(basename "$s" .c).o
        gcc -std=c11 -D_POSIX_C_SOURCE=200809L -Wall -Wextra $f -Ilib/include -Itests -c "$s" -o "$o"
        objs="$objs $o"
    done
    g++ -std=c++14 -Wall -Wextra $f -Ilib/include -I/usr/include/eigen3 \
        -c bench/compare/k_eigen.cpp -o "$d/k_eigen.o"
    g++ $f -o "$d/bench" $objs "$d/ref.o" "$d/k_eigen.o" -llibfixmath -lm
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
    echo "bench: building (flags: $BENCH_FLAGS; and again with -flto)"
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
