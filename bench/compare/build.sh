#!/bin/sh
# bench/compare/build.sh DIR [EXTRA_FLAGS]: builds the comparison program DIR/bench with one flag
# set for every library (qorient, cglm, Eigen and the driver alike; libfixmath is Debian's
# prebuilt .a): -O2 -ffp-contract=off -march=x86-64 -g plus EXTRA_FLAGS (tools/bench.sh passes
# -flto for its second variant). Used by tools/bench.sh and tools/figures/ir.sh, timing.sh.
set -eu
d=$1; f="-O2 -ffp-contract=off -march=x86-64 -g ${2:-}"; objs=""
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
