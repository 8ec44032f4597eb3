#!/bin/sh
# Soak run (not part of `make test`): builds bench/soak.c optimised, runs it in full
# (1e6 ticks of an 18-joint stream against the simulator over loopback TCP, 1e7 composed
# rotations; about a minute), then the short mode under valgrind memcheck, which must report
# no leak and no error. Prints the figures of both runs; exit status 0 only if both pass.
#   sh tools/soak.sh            full run + valgrind on --short
#   sh tools/soak.sh --short    --short only, natively and under valgrind
set -eu
BUILD=${BUILD:-build}
make --no-print-directory -j2 "$BUILD/bench/soak" >/dev/null
fail=0
if [ "${1:-}" != "--short" ]; then
    echo "== $BUILD/bench/soak (full)"
    start=$(date +%s)
    "$BUILD/bench/soak" || fail=1
    echo "full soak wall time: $(( $(date +%s) - start )) s"
else
    "$BUILD/bench/soak" --short || fail=1
fi
if command -v valgrind >/dev/null 2>&1; then
    echo "== valgrind --leak-check=full --error-exitcode=1 $BUILD/bench/soak --short"
    if valgrind -q --leak-check=full --show-leak-kinds=definite,indirect,possible \
        --errors-for-leak-kinds=definite,indirect,possible --error-exitcode=1 \
        "$BUILD/bench/soak" --short; then
        echo "valgrind: clean"
    else
        echo "valgrind: FAIL"
        fail=1
    fi
else
    echo "valgrind: not installed (apt-get install valgrind)"
    fail=1
fi
[ "$fail" -eq 0 ] && echo "soak.sh: ok" || echo "soak.sh: FAIL"
exit "$fail"
