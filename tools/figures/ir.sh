#!/bin/sh
# Figures section "ir": float32 instructions per call (callgrind Ir, gcc -O2, through the public
# names) of qorient against cglm and Eigen on bench/compare's fixed-seed inputs (BK_N random
# unit quaternions, vectors, rotation matrices, slerp parameters), with the ratio to the faster
# peer. Deterministic for one compiler and library version. Prints a markdown table.
# Needs valgrind, libcglm-dev, libeigen3-dev, libfixmath (tools/deps.sh bench installs them).
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
