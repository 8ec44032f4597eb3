#!/bin/sh
# Figures section "ir": instructions per call (callgrind Ir, gcc -O2, through the public names)
# on bench/compare's fixed-seed inputs (BK_N random unit quaternions, vectors, rotation
# matrices, slerp parameters, primitive arguments), two tables:
#   1. qorient float32 against cglm and Eigen, with the ratio to the faster peer;
#   2. qorient's fixed core (Q1.30 values, Q3.28 angles) against libfixmath (Q16.16) for every
#      operation both have (every bk_qofx_* kernel with a bk_fixmath_* twin), with each side's
#      worst error against double on the same inputs (bench --reps 1's acc lines), so that a
#      count is read beside the precision it buys.
# Deterministic for one compiler and library version. Prints markdown.
# Needs valgrind, libcglm-dev, libeigen3-dev, libfixmath-dev (tools/deps.sh bench installs them).
set -eu
BUILD=${BUILD:-build}
D=$BUILD/figures/ir
mkdir -p "$D"
sh bench/compare/build.sh "$D"

ir() { # kernel -> instructions per call, or "-" when the kernel does not exist
    if ! nm "$D/bench" | grep -q " [Tt] $1\$"; then echo "-"; return; fi
    valgrind --tool=callgrind --callgrind-out-file="$D/cg.out" --toggle-collect="$1" \
        "$D/bench" --once >/dev/null 2>"$D/cg.log"
    awk '/^(summary|totals):/ { printf "%.0f\n", $2 / 1024; exit }' "$D/cg.out"
}

echo "| operation | qorient Ir | cglm Ir | Eigen Ir | ratio to the faster peer | goal |"
echo "|---|---|---|---|---|---|"
# from_mat3_trusted (no rotation check) is compared with the peers' from_mat3 (neither checks).
for op in mul rotate normalize to_mat3 from_mat3 from_mat3_trusted to_euler_XYZ to_euler_ZYX slerp; do
    p=${op%_trusted}
    q=$(ir "bk_qorient_$op"); c=$(ir "bk_cglm_$p"); e=$(ir "bk_eigen_$p")
    goal="<= 1.00"; [ "$op" = from_mat3 ] && goal="<= 2.00"
    echo "$op $q $c $e $goal" | awk '{
        best = ""; if ($3 != "-") best = $3; if ($4 != "-" && (best == "" || $4 + 0 < best + 0)) best = $4
        printf "| %s | %s | %s | %s | %s | %s %s |\n", $1, $2, $3, $4,
            (best == "" ? "-" : sprintf("%.2f", $2 / best)), $5, $6 }'
done

# The operations both fixed-point libraries have: taken from the binary, so a kernel added on
# both sides joins the table without an edit here (and one dropped leaves it), in source order.
fxops=$(nm -n "$D/bench" | awk '$2 ~ /^[Tt]$/ && $3 ~ /^bk_qofx_fx_/ { sub(/^bk_qofx_/, "", $3); print $3 }' |
    while read -r op; do nm "$D/bench" | grep -q " [Tt] bk_fixmath_$op\$" && echo "$op"; done)
# Worst errors: one timing repetition (not used) and the accuracy pass, set 0 as callgrind's.
"$D/bench" --reps 1 | awk -F'\t' '$1 == "acc"' > "$D/acc.tsv"
err() { # lib op -> "max error unit"
    awk -F'\t' -v l="$1" -v o="$2" '$2 == l && $3 == o { print $4, $6 }' "$D/acc.tsv"
}
cat <<'TXT'

Fixed core against libfixmath (Debian libfixmath-dev, prebuilt, as shipped: its sin and atan
memo caches on, every input new to them), callgrind Ir per call, same build and driver as above. The formats differ, so the counts buy different
precision: qorient computes in Q1.30 (values, LSB 9.3e-10) and Q3.28 (angles, LSB 3.7e-9), its
quaternion products exact in 64 bits and rounded once per component; libfixmath in Q16.16
(LSB 1.5e-5), every product rounded. libfixmath has no quaternions: its quaternion rows are
bench/compare/k_fixmath.c's textbook compositions of fix16_mul, fix16_sqrt/div,
fix16_atan2/asin (Euler ZYX) and fix16_acos/sin/div (slerp). Max error: against double on the same 1024 inputs as each library
received them (bench/compare/bench_main.c: quaternions per component with the sign aligned,
Euler angles as the rotation angle between input and result). Goal (issue 14): ratio <= 1.00.

| operation | qorient Q1.30 Ir | libfixmath Q16.16 Ir | ratio | qorient max error | libfixmath max error | unit | goal met |
|---|---|---|---|---|---|---|---|
TXT
for op in $fxops; do
    echo "${op#fx_} $(ir "bk_qofx_$op") $(ir "bk_fixmath_$op") $(err qorient "$op") $(err libfixmath "$op")" |
        awk '{ r = $2 / $3
            printf "| %s | %s | %s | %.2f | %s | %s | %s | %s |\n", $1, $2, $3, r, $4, $6, $5,
                (r <= 1 ? "yes" : "no") }'
done
