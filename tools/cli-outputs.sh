#!/bin/sh
# tools/cli-outputs.sh - writes the command's float32 (and fixed-point) outputs for one fixed
# set of inputs, so that two builds' results can be compared file by file: one script, two
# uses. tools/ci-trixie.sh compares Debian 12's with Debian 13's (the same x86 code on two C
# libraries); tests/qemu/run-target.sh compares the host's build with the aarch64 and armhf
# cross builds run under qemu-user (the same code on three instruction sets), with --compare.
# The float32 core must give the same bits everywhere (issue 14).
#
#   sh tools/cli-outputs.sh QORIENT OUTDIR
#       the outputs: OUTDIR/NAME.out (standard output) and NAME.err (standard error) per run
#   sh tools/cli-outputs.sh --compare REF_QORIENT QORIENT OUTDIR
#       both commands' outputs (OUTDIR/ref, OUTDIR/target; either command may be a wrapper
#       script such as "qemu-aarch64 ... build/qemu-aarch64/qorient"), compared byte for byte:
#       for a file that differs, "FAIL NAME: line L differs" and the first differing line of
#       each side ("FAIL NAME:L < ..." the reference's, "> ..." the other's), and a
#       last line "N passed, M failed" (files). Every float is printed with %.9g, which
#       round-trips float32 exactly, so equal text is equal bits (except -0, printed as 0).
#
# The inputs are made here by awk from a Park-Miller generator (seed fixed; every product is an
# exact integer in a double, and printf of a double is exact-rounded by every C library; the
# matrices use only +, *, / and sqrt, all correctly rounded), so they are the same bytes on
# every system; they are written to OUTDIR/in.* too, and the run fails if they are not the
# same as the other system's. Exit: 0, or 1 if a command failed (or, --compare, a file differs).
set -eu
if [ $# = 4 ] && [ "$1" = --compare ]; then
    D=$4
    rm -rf "$D/ref" "$D/target"
    crc=0
    sh "$0" "$2" "$D/ref" || crc=1
    sh "$0" "$3" "$D/target" || crc=1
    p=0; f=0
    for a in "$D"/ref/in.* "$D"/ref/*.out "$D"/ref/*.err; do
        b=${a##*/}
        if cmp -s "$a" "$D/target/$b"; then p=$((p + 1)); continue; fi
        f=$((f + 1))
        # The first differing line, numbered, from both sides (a missing line shows as <EOF>).
        awk -v name="$b" -v ref="$2" -v tgt="$3" '
            NR == FNR { r[FNR] = $0; nr = FNR; next }
            { t[FNR] = $0; nt = FNR }
            END { n = nr > nt ? nr : nt
                  for (i = 1; i <= n; i++) if (!(i in r) || !(i in t) || r[i] != t[i]) break
                  printf "FAIL %s: line %d differs (< %s, > %s)\nFAIL %s:%d < %s\nFAIL %s:%d > %s\n",
                         name, i, ref, tgt, name, i, (i in r) ? r[i] : "<EOF>", name, i, (i in t) ? t[i] : "<EOF>" }' \
            "$a" "$D/target/$b" 2>/dev/null || echo "FAIL $b: missing from $D/target"
    done
    [ "$crc" = 0 ] || { echo "FAIL a command failed (see $D/ref/*.err, $D/target/*.err)"; f=$((f + 1)); }
    set -- "$D"/ref/*.out
    echo "$# runs, $(cat "$@" | wc -l) output lines compared"
    echo "$p passed, $f failed"
    [ "$f" = 0 ]
    exit
fi
[ $# = 2 ] || { echo "usage: sh tools/cli-outputs.sh QORIENT OUTDIR | --compare REF_QORIENT QORIENT OUTDIR" >&2; exit 2; }
Q=$1
O=$2
mkdir -p "$O"
rm -f "$O"/*.out "$O"/*.err "$O"/in.*

# N random unit-ish quaternions, then edges: identity, 180 degrees about each axis, tiny
# angles, a nearly antipodal pair's members, and pitch exactly at +-90 degrees (gimbal lock).
awk -v n=400 'BEGIN {
    s = 20260101
    for (i = 0; i < n; i++) {
        for (k = 0; k < 4; k++) { s = (s * 16807) % 2147483647; c[k] = 2 * s / 2147483647 - 1 }
        printf "%.9f %.9f %.9f %.9f\n", c[0], c[1], c[2], c[3]
    }
    print "1 0 0 0"; print "0 1 0 0"; print "0 0 1 0"; print "0 0 0 1"
    print "1 1e-7 0 0"; print "0.70710678 0 0.70710678 0"; print "0.70710678 0 -0.70710678 0"
    print "-1 0 0 0"; print "0.5 0.5 0.5 0.5"
}' >"$O/in.quat"
# Euler angles in degrees, random and at the singular pitch.
awk -v n=400 'BEGIN {
    s = 777
    for (i = 0; i < n; i++) {
        for (k = 0; k < 3; k++) { s = (s * 16807) % 2147483647; c[k] = 360 * s / 2147483647 - 180 }
        printf "%.6f %.6f %.6f\n", c[0], c[1] / 2, c[2]
    }
    print "0 90 0"; print "30 90 -20"; print "10 -90 40"; print "0 0 0"; print "180 0 180"
}' >"$O/in.euler"
# slerp: random pairs and t, plus identical, antipodal and nearly antipodal pairs.
awk -v n=400 'BEGIN {
    s = 4242
    for (i = 0; i < n; i++) {
        for (k = 0; k < 9; k++) { s = (s * 16807) % 2147483647; c[k] = 2 * s / 2147483647 - 1 }
        printf "%.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.6f\n", c[0], c[1], c[2], c[3],
            c[4], c[5], c[6], c[7], (c[8] + 1) / 2
    }
    print "1 0 0 0 1 0 0 0 0.5"; print "1 0 0 0 -1 0 0 0 0.5"; print "1 0 0 0 0 0 0 1 0.5"
    print "0 0 0 1 0 0 1e-6 -1 0.3"; print "1 0 0 0 0 0 0 1 0"; print "1 0 0 0 0 0 0 1 1"
}' >"$O/in.slerp"
# Gimbal keys: a wandering path through the singular pitch, 20 keys 0.5 s apart.
awk 'BEGIN {
    pi = 3.14159265358979; s = 99
    for (i = 0; i < 20; i++) {
        s = (s * 16807) % 2147483647; y = (s / 2147483647 - 0.5) * pi
        p = (i % 5 == 2) ? pi / 2 : (i / 19 - 0.5) * pi
        h = p / 2; g = y / 2
        printf "%.2f,%.9f,%.9f,%.9f,%.9f\n", i * 0.5, cos(g) * cos(h), -sin(g) * sin(h), cos(g) * sin(h), sin(g) * cos(h)
    }
}' >"$O/in.keys"

# Matrices, rotation vectors and axis-angle pairs: from the same generator (the matrices of
# normalised random quaternions, so they are rotations to the printed digits), plus edges:
# identity, half turns, a zero rotation vector, a half-turn vector.
awk -v n=200 'BEGIN {
    s = 31337
    for (i = 0; i < n; i++) {
        for (k = 0; k < 4; k++) { s = (s * 16807) % 2147483647; c[k] = 2 * s / 2147483647 - 1 }
        r = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]); w = c[0] / r; x = c[1] / r; y = c[2] / r; z = c[3] / r
        printf "%.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n",
            1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
            2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
            2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)
    }
    print "1 0 0 0 1 0 0 0 1"; print "1 0 0 0 -1 0 0 0 -1"; print "-1 0 0 0 1 0 0 0 -1"; print "-1 0 0 0 -1 0 0 0 1"
}' >"$O/in.matrix"
awk -v n=200 'BEGIN {
    s = 2718281
    for (i = 0; i < n; i++) {
        for (k = 0; k < 4; k++) { s = (s * 16807) % 2147483647; c[k] = 2 * s / 2147483647 - 1 }
        printf "%.9f %.9f %.9f\n", 3 * c[0], 3 * c[1], 3 * c[2]
        printf "%.9f %.9f %.9f %.9f\n", c[0], c[1], c[2], 3.14159265 * c[3] > "/dev/stderr"
    }
    print "0 0 0"; print "3.14159265 0 0"; print "1e-7 0 0"
    print "0 0 1 0" > "/dev/stderr"; print "1 1 1 3.14159265" > "/dev/stderr"; print "0 1 0 -3.14159265" > "/dev/stderr"
}' >"$O/in.rotvec" 2>"$O/in.axisangle"
# plan: 3 joints; targets issued every 0.8 s, before the previous one is reached (moves of up
# to 4 units at about 1.5 unit/s), so every re-plan starts moving; with target velocities
# (--target-velocities) and without (the first four columns); and keyframes at uneven times.
awk -v n=7 'BEGIN {
    s = 8675309; print "0,0,0,0,0,0,0"
    for (i = 1; i <= n; i++) {
        for (k = 0; k < 6; k++) { s = (s * 16807) % 2147483647; c[k] = 2 * s / 2147483647 - 1 }
        printf "%.1f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", 0.8 * i, 2 * c[0], 2 * c[1], 2 * c[2],
            0.4 * c[3], 0.3 * c[4], 0.3 * c[5] - 0.1
    }
}' >"$O/in.targets"
cut -d, -f1-4 "$O/in.targets" >"$O/in.moves"
awk -v n=8 'BEGIN {
    s = 4711; t = 0
    for (i = 0; i < n; i++) {
        for (k = 0; k < 4; k++) { s = (s * 16807) % 2147483647; c[k] = s / 2147483647 }
        printf "%.3f,%.4f,%.4f,%.4f\n", t, 4 * c[0] - 2, 4 * c[1] - 2, 4 * c[2] - 2; t += 0.3 + c[3]
    }
}' >"$O/in.jkeys"

rc=0
run() { # NAME INPUT ARGS...: one output file; a failing command is reported, not fatal here
    name=$1; in=$2; shift 2
    "$Q" "$@" <"$in" >"$O/$name.out" 2>"$O/$name.err" || { echo "cli-outputs: '$*' failed" >&2; rc=1; }
}
# convert: quat to every representation and all 24 Euler sequences, each Euler sequence back
# to quat, matrix, rotvec and axis-angle to the others; float32 and --fixed.
SEQS="XYZ XZY YXZ YZX ZXY ZYX XYX XZX YXY YZY ZXZ ZYZ xyz xzy yxz yzx zxy zyx xyx xzx yxy yzy zxz zyz"
for to in matrix rotvec axisangle quat; do
    run "quat-$to" "$O/in.quat" convert quat "$to"
    run "quat-$to-fixed" "$O/in.quat" convert quat "$to" --fixed
done
for seq in $SEQS; do
    run "quat-euler:$seq" "$O/in.quat" convert quat "euler:$seq"
    run "quat-euler:$seq-fixed" "$O/in.quat" convert quat "euler:$seq" --fixed
    run "euler$seq-quat" "$O/in.euler" convert "euler:$seq" quat --degrees
done
for to in quat matrix euler:XYZ; do
    run "eulerZYX-$to" "$O/in.euler" convert euler:ZYX "$to" --degrees
done
for to in quat rotvec axisangle euler:ZXZ euler:yxz; do
    run "matrix-$to" "$O/in.matrix" convert matrix "$to"
    run "matrix-$to-fixed" "$O/in.matrix" convert matrix "$to" --fixed
done
for to in quat matrix axisangle euler:ZYX; do
    run "rotvec-$to" "$O/in.rotvec" convert rotvec "$to"
    run "axisangle-$to" "$O/in.axisangle" convert axisangle "$to" --degrees
done
run slerp "$O/in.slerp" slerp
run slerp-fixed "$O/in.slerp" slerp --fixed
run gimbal "$O/in.keys" gimbal
run gimbal-spline "$O/in.keys" gimbal --interp spline --degrees
run gimbal-vmax "$O/in.keys" gimbal --vmax 1 --rate 50
# the tracking filter (the motion planner re-planned at every step)
run gimbal-amax "$O/in.keys" gimbal --interp spline --rate 200 --band 2 --amax 20
run gimbal-jmax "$O/in.keys" gimbal --interp spline --rate 200 --band 2 --amax 20 --jmax 400
run gimbal-xyz-jmax "$O/in.keys" gimbal --seq XYZ --vmax 2 --amax 8 --jmax 100 --rate 100
# plan: moving targets with target velocities (asymmetric limits, per-joint sync), without,
# trapezoid, and the keyframe profiles; float32 and --fixed
run plan-scurve-states "$O/in.targets" plan --profile scurve --vmax 1,1.5,2 --vmin -0.5,-1.5,-0.8 \
    --amax 3,4,2 --amin -2,-4,-1.5 --jmax 20,30,15 --sync time,phase,none --target-velocities --rate 50
run plan-trapezoid-states "$O/in.targets" plan --profile trapezoid --vmax 2 --amax 4 --target-velocities --rate 50
run plan-scurve-moves "$O/in.moves" plan --profile scurve --vmax 1.5 --amax 3 --jmax 20 --sync phase --rate 50
run plan-scurve-moves-fixed "$O/in.moves" plan --profile scurve --vmax 1.5 --amax 3 --jmax 20 --rate 50 --fixed
for prof in linear catmull spline quintic; do
    run "plan-$prof" "$O/in.jkeys" plan --profile "$prof" --rate 40
done
run plan-spline-fixed "$O/in.jkeys" plan --profile spline --rate 40 --fixed
exit $rc
