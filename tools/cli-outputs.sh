#!/bin/sh
# tools/cli-outputs.sh - writes the command's float32 (and fixed-point) outputs for one fixed
# set of inputs, so that two systems' results can be compared file by file (tools/ci-trixie.sh
# compares Debian 12's with Debian 13's: the float32 core must give the same bits everywhere).
#
#   sh tools/cli-outputs.sh QORIENT OUTDIR
#
# The inputs are made here by awk from a Park-Miller generator (seed fixed; every product is an
# exact integer in a double, and printf of a double is exact-rounded by every C library), so
# they are the same bytes on every system; they are written to OUTDIR/in.* too, and the run
# fails if they are not the same as the other system's. Exit: 0, or 1 if a command failed.
set -eu
[ $# = 2 ] || { echo "usage: sh tools/cli-outputs.sh QORIENT OUTDIR" >&2; exit 2; }
Q=$1
O=$2
mkdir -p "$O"
rm -f "$O"/*.out "$O"/in.*

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

rc=0
run() { # NAME INPUT ARGS...: one output file; a failing command is reported, not fatal here
    name=$1; in=$2; shift 2
    "$Q" "$@" <"$in" >"$O/$name.out" 2>"$O/$name.err" || { echo "cli-outputs: '$*' failed" >&2; rc=1; }
}
for to in matrix rotvec axisangle euler:ZYX euler:xyz euler:ZYZ quat; do
    run "quat-$to" "$O/in.quat" convert quat "$to"
    run "quat-$to-fixed" "$O/in.quat" convert quat "$to" --fixed
done
for to in quat matrix euler:XYZ; do
    run "eulerZYX-$to" "$O/in.euler" convert euler:ZYX "$to" --degrees
done
run slerp "$O/in.slerp" slerp
run slerp-fixed "$O/in.slerp" slerp --fixed
run gimbal "$O/in.keys" gimbal
run gimbal-spline "$O/in.keys" gimbal --interp spline --degrees
run gimbal-vmax "$O/in.keys" gimbal --vmax 1 --rate 50
exit $rc
