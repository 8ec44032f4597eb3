#!/bin/sh
# bench/compare/report.sh RESULTDIR - markdown tables (RESULTDIR/tables.md) and plots
# (RESULTDIR/bench-*.png, gnuplot pngcairo or png) from the result files written by
# tools/bench.sh: host.tsv, host-lto.tsv, callgrind.tsv, callgrind-lto.tsv, qemu.tsv.
# They stay in RESULTDIR, beside the run they describe: the committed figures are
# docs/FIGURES.md's, written by `make figures` and checked by CI (docs/BENCHMARKS.md).
set -eu
R=${1:-build/bench-results}
IMG=$R
mkdir -p "$IMG"
cat "$R"/host.tsv "$R"/host-lto.tsv "$R"/callgrind.tsv "$R"/callgrind-lto.tsv "$R"/qemu.tsv 2>/dev/null |
awk -v R="$R" '
$1 == "time" { if (lto_seen[$2 SUBSEP $3]++ && $2 == "qorient") tl[$3] = $4; else t[$2, $3] = $4 }
$1 == "acc"  { if (alto_seen[$2 SUBSEP $3]++ && $2 == "qorient") next; amax[$2, $3] = $4; amean[$2, $3] = $5; unit[$3] = $6
               if (!(($3) in seen)) { seen[$3] = 1; order[++n] = $3 } }
$1 == "ir"   { k = $2; lib = k; sub(/_.*/, "", lib); op = k; sub(/^[a-z]+_/, "", op)
               if (lib == "qofx") lib = "qorient"; if (lib == "fixmath") lib = "libfixmath"
               if (irseen[lib SUBSEP op]++ && lib == "qorient") irl[op] = $3; else ir[lib, op] = $3 }
$1 == "qemu" { q[$2, $3] = $4 }
END {
    f = R "/tables.md"; df = R "/float.dat"; xf = R "/fixed.dat"; mf = R "/qemu.dat"
    print "### float32: qorient against cglm and Eigen\n" > f
    print "| operation | qorient ns | qorient -flto ns | cglm ns | Eigen ns | qorient Ir | qorient -flto Ir | cglm Ir | Eigen Ir | ratio ns (lib / lto) | ratio Ir (lib / lto) | max err qorient | cglm | Eigen |" > f
    print "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|" > f
    print "# op ratio_ns ratio_ir ratio_ns_lto ratio_ir_lto" > df
    for (i = 1; i <= n; i++) {
        op = order[i]; if (op ~ /^fx_/) continue
        best = ""; bir = ""
        for (l = 1; l <= 2; l++) { lib = (l == 1) ? "cglm" : "eigen"
            if (((lib, op) in t) && (best == "" || t[lib, op] < best)) best = t[lib, op]
            if (((lib, op) in ir) && (bir == "" || ir[lib, op] < bir)) bir = ir[lib, op] }
        rn = best > 0 ? t["qorient", op] / best : 0; ri = bir > 0 ? ir["qorient", op] / bir : 0
        rnl = best > 0 ? tl[op] / best : 0; ril = bir > 0 ? irl[op] / bir : 0
        printf "| %s | %.1f | %.1f | %s | %s | %.0f | %.0f | %s | %s | %.2f / %.2f | %.2f / %.2f | %s | %s | %s |\n", op,
            t["qorient", op], tl[op], v(t["cglm", op], "%.1f"), v(t["eigen", op], "%.1f"), ir["qorient", op], irl[op],
            v(ir["cglm", op], "%.0f"), v(ir["eigen", op], "%.0f"), rn, rnl, ri, ril,
            amax["qorient", op], v(amax["cglm", op], "%s"), v(amax["eigen", op], "%s") > f
        printf "%s %.3f %.3f %.3f %.3f\n", op, rn, ri, rnl, ril > df
    }
    print "\n### fixed point: qorient (Q1.30 values, Q3.28 angles) against libfixmath (Q16.16)\n" > f
    print "| operation | qorient ns | libfixmath ns | qorient Ir | libfixmath Ir | speed-up (Ir) | max err qorient | max err libfixmath | accuracy ratio | unit |" > f
    print "|---|---|---|---|---|---|---|---|---|---|" > f
    print "# op ir_qorient ir_libfixmath err_qorient err_libfixmath" > xf
    for (i = 1; i <= n; i++) {
        op = order[i]; if (op !~ /^fx_/) continue
        hq = (("qorient", op) in t)
        printf "| %s | %s | %.1f | %s | %.0f | %s | %s | %s | %s | %s |\n", op, v(t["qorient", op], "%.1f"), t["libfixmath", op],
            v(ir["qorient", op], "%.0f"), ir["libfixmath", op],
            (hq ? sprintf("%.1fx", ir["libfixmath", op] / ir["qorient", op]) : "-"),
            v(amax["qorient", op], "%s"), amax["libfixmath", op],
            ((hq && amax["qorient", op] > 0) ? sprintf("%.0fx", amax["libfixmath", op] / amax["qorient", op]) : "-"), unit[op] > f
        if (hq) printf "%s %s %s %s %s\n", op, ir["qorient", op], ir["libfixmath", op], amax["qorient", op], amax["libfixmath", op] > xf
    }
    print "\n### Cortex-M instruction counts per call (QEMU, qorient)\n" > f
    print "| operation | M0 float32 (soft float) | M0 fixed | M0 float/fixed | M4F float32 | M4F fixed |" > f
    print "|---|---|---|---|---|---|" > f
    print "# op m0_float m0_fixed m4f_float m4f_fixed" > mf
    split("mul rotate normalize to_mat3 from_mat3 to_euler_ZYX slerp sqrt sin atan2", qops, " ")
    for (i = 1; i <= 10; i++) {
        op = qops[i]; a = q["m0", "f_" op]; b = q["m0", "x_" op]; c = q["m4f", "f_" op]; d = q["m4f", "x_" op]
        if (a == "" && b == "") continue
        printf "| %s | %s | %s | %s | %s | %s |\n", op, v(a, "%d"), v(b, "%d"), ((a != "" && b > 0) ? sprintf("%.1fx", a / b) : "-"),
            v(c, "%d"), v(d, "%d") > f
        printf "%s %s %s %s %s\n", op, (a == "" ? "0" : a), (b == "" ? "0" : b), (c == "" ? "0" : c), (d == "" ? "0" : d) > mf
    }
}
function v(x, fmt) { return x == "" ? "-" : sprintf(fmt, x) }
'
G="set terminal pngcairo size 900,480 font 'sans,10'"
gnuplot -e "set terminal pngcairo" >/dev/null 2>&1 || G="set terminal png size 900,480"
gnuplot <<EOG
$G
set termoption noenhanced
set output '$IMG/bench-float-ratio.png'
set title 'qorient float32 / fastest of cglm and Eigen (same inputs, x86-64, -O2); goal <= 1'
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set boxwidth 0.9
set yrange [0:*]
set ylabel 'ratio (lower is better)'
set xtics rotate by -30
set grid ytics
set key top left
set arrow from graph 0, first 1 to graph 1, first 1 nohead lw 2 dt 2 lc rgb 'red'
plot '$R/float.dat' using 2:xtic(1) title 'time, library call', '' using 3 title 'instructions, library call', \
     '' using 4 title 'time, -flto', '' using 5 title 'instructions, -flto'
EOG
gnuplot <<EOG
$G
set termoption noenhanced
set output '$IMG/bench-fixed.png'
set key below
set multiplot layout 1,2 title 'qorient fixed point (Q1.30) against libfixmath (Q16.16), x86-64 callgrind'
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set xtics rotate by -30
set grid ytics
set logscale y
set title 'instructions per call (lower is better)'
plot '$R/fixed.dat' using 2:xtic(1) title 'qorient', '' using 3 title 'libfixmath'
set title 'max error vs double (lower is better)'
plot '$R/fixed.dat' using 4:xtic(1) title 'qorient', '' using 5 title 'libfixmath'
unset multiplot
EOG
gnuplot <<EOG
$G
set termoption noenhanced
set output '$IMG/bench-qemu.png'
set title 'qorient instructions per call on Cortex-M (QEMU, exact counts); 0 = not measured'
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.8 border -1
set logscale y
set yrange [10:*]
set xtics rotate by -30
set grid ytics
plot '$R/qemu.dat' using (\$2 > 0 ? \$2 : 1):xtic(1) title 'M0 float32 (soft float)', '' using (\$3 > 0 ? \$3 : 1) title 'M0 fixed', \
     '' using (\$4 > 0 ? \$4 : 1) title 'M4F float32', '' using (\$5 > 0 ? \$5 : 1) title 'M4F fixed'
EOG
echo "bench: tables in $R/tables.md, plots in $IMG/bench-*.png"
