#!/bin/sh
# Figures section "m0": instructions per call on an FPU-less Cortex-M0 (tools/qemu-icount.sh:
# qemu-system-arm microbit, K = 16 calls, loop body included), the fixed core against qorient's
# own float32 code on libgcc's soft float, with issue 14's goals for the fixed core (half of what
# the float32 code runs on the fastest soft-float library: mul 910, normalise 505, rotate 928,
# quat->Euler 2330, slerp 3855), held by the fast tiers where Q1.30's exact path cannot (the
# exact rows are listed too). Exact and repeatable for one compiler and QEMU version.
set -eu
BUILD=${BUILD:-build}
D=$BUILD/figures/m0
mkdir -p "$D"
K=16 BUILD="$D" sh tools/qemu-icount.sh > "$D/counts.txt"
awk '
    NR == 1 { next }
    { n = $NF; $NF = ""; sub(/[ \t]+$/, ""); c[$0] = n; order[++k] = $0 }
    END {
        split("qo_quat_mul_q30:910 qo_quat_normalize_fast_q30:505 qo_quat_rotate_q30:928 qo_euler_from_quat_fast_q30:2330 qo_interp_slerp_fast_q30:3855", g, " ")
        for (i in g) { split(g[i], kv, ":"); goal[kv[1]] = kv[2] }
        print "| operation | instructions per call | goal | met |"
        print "|---|---|---|---|"
        for (i = 1; i <= k; i++) {
            o = order[i]
            if (o in goal) printf "| %s | %s | <= %s | %s |\n", o, c[o], goal[o], (c[o] + 0 <= goal[o] ? "yes" : "**no**")
            else printf "| %s | %s | | |\n", o, c[o]
        }
    }' "$D/counts.txt"
