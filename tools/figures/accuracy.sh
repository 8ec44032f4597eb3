#!/bin/sh
# Figures section "accuracy": every bench/accuracy_*.c program (float32 and fixed point,
# fixed-seed inputs against double references), its report verbatim. Deterministic: the float
# core uses its own kernels (qorient/fmath.h), the references double libm on this machine.
# The programs' informative host timings are left out (not reproducible).
set -eu
BUILD=${BUILD:-build}
progs=$(ls bench/accuracy_*.c | sed "s|^bench/|$BUILD/bench/|; s|\.c\$||")
make -s $progs >/dev/null
for p in $progs; do
    echo "\`$p\`:"
    echo
    echo '```'
    "$p" | grep -v 'host time per call'
    echo '```'
    echo
done
