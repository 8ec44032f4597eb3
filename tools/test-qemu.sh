#!/bin/sh
# `make test-qemu`: the tests on emulated targets.
#   m0       core cmocka tests on Cortex-M0, soft float  (qemu-system-arm -M microbit)
#   m4f      core cmocka tests on Cortex-M4F             (qemu-system-arm -M mps2-an386)
#   m7       core cmocka tests on Cortex-M7, FPv5        (qemu-system-arm -M mps2-an500)
#   aarch64  whole host suite for Raspberry Pi OS 64-bit (qemu-aarch64 -cpu cortex-a72)
#   armhf    whole host suite for Debian armhf, Pi 2-5   (qemu-arm -cpu cortex-a7)
# "Core" tests include only C99 headers, cmocka.h, qorient/ and common/ headers; they run bare
# metal against the cmocka shim of tests/qemu with newlib semihosting. The Linux targets build the
# top Makefile's tests-build (ASan+UBSan, LeakSanitizer off) with the cross compiler against a
# sysroot of the target's -dev packages, and run every cmocka program and shell test, then
# compare the command's outputs for a fixed input set with the host build's, byte for byte
# (test cli_outputs: tools/cli-outputs.sh --compare; the same float32 bits on every target).
#
#   sh tools/test-qemu.sh [TARGET...]       (default: all five; QEMU_TARGETS works too)
#
# Prints per-target "TARGET: N passed, M failed", a table (also in build/qemu-results.md) and a
# final "N passed, M failed". Exit 0 if all passed, 1 on any failure, 77 if a prerequisite is
# missing and cannot be installed (installs with apt-get when run as root). QEMU_JOBS: targets
# run at once (default: the machine's cores). See run-target.sh for QEMU_TIMEOUT and QEMU_SKIP.
set -u
cd "$(dirname "$0")/.." || exit 2
TARGETS=${*:-${QEMU_TARGETS:-m0 m4f m7 aarch64 armhf}}
# The target libraries the host suite links (the top Makefile's PKGS plus cmocka), as .debs.
SYSROOT_DEBS="libcmocka0 libcmocka-dev libmodbus5 libmodbus-dev libgpiod2 libgpiod-dev libinih1 libinih-dev"

unavailable() {
    echo "test-qemu: SKIPPED: $*" >&2
    exit 77
}

need_cm=0; need_linux=""
for t in $TARGETS; do
    case $t in
    m0|m4f|m7) need_cm=1;;
    aarch64) need_linux="$need_linux arm64";;
    armhf) need_linux="$need_linux armhf";;
    *) echo "test-qemu: unknown target '$t' (m0 m4f m7 aarch64 armhf)" >&2; exit 2;;
    esac
done

pkgs="make pkg-config"
[ "$need_cm" = 1 ] && pkgs="$pkgs gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm"
# The cross C libraries are only Recommends of the cross gcc: named, or a --no-install-recommends
# install leaves the compiler falling back to the host's /usr/include.
case $need_linux in *arm64*) pkgs="$pkgs gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user";; esac
case $need_linux in *armhf*) pkgs="$pkgs gcc-arm-linux-gnueabihf libc6-dev-armhf-cross qemu-user";; esac
command -v dpkg >/dev/null 2>&1 || unavailable "not a Debian system (dpkg missing); needs:$pkgs"
missing=""
for p in $pkgs; do
    case " $missing " in *" $p "*) continue;; esac
    dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
    [ "$(id -u)" = 0 ] || unavailable "missing packages:$missing (run as root, or apt-get install them)"
    echo "test-qemu: installing:$missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -q || echo "test-qemu: apt-get update reported errors; trying the install anyway"
    # shellcheck disable=SC2086
    apt-get install -y -q --no-install-recommends $missing || unavailable "apt-get install$missing failed"
fi

if [ "$need_cm" = 1 ]; then
    boards=$(qemu-system-arm -M help 2>/dev/null)
    for b in microbit mps2-an386 mps2-an500; do
        echo "$boards" | grep -q "^$b " || unavailable "qemu-system-arm has no '$b' board (QEMU >= 4.2 needed)"
    done
fi

# A sysroot per architecture, unpacked from the target's .debs with apt-get download: no dpkg
# --add-architecture on the machine (a foreign index that lags the host's makes Multi-Arch: same
# -dev packages uninstallable), nothing installed system-wide.
make_sysroot() { # DEBARCH
    a=$1; S=$PWD/build/qemu-sysroot-$a; A=$PWD/build/qemu-apt-$a
    if [ -f "$S/.stamp" ] && [ "$(cat "$S/.stamp")" = "$SYSROOT_DEBS" ]; then return 0; fi
    echo "test-qemu: making the $a sysroot ($SYSROOT_DEBS)"
    rm -rf "$S" "$A"
    mkdir -p "$S" "$A/lists/partial" "$A/cache/archives/partial" "$A/debs"
    O="-o APT::Architecture=$a -o APT::Architectures::=$a -o Dir::State::Lists=$A/lists \
       -o Dir::Cache=$A/cache -o Dir::State::status=/dev/null -o Debug::NoLocking=1 \
       -o APT::Sandbox::User=root"
    # A fault in one index (seen: bookworm-security armhf) makes update exit 100 though the
    # packages are still found in the others: judge by the download.
    # shellcheck disable=SC2086
    apt-get $O update -q >"$A/update.log" 2>&1 || echo "test-qemu: apt-get update for $a reported errors (see $A/update.log)"
    # shellcheck disable=SC2086
    (cd "$A/debs" && apt-get $O download $SYSROOT_DEBS) >"$A/download.log" 2>&1 ||
        unavailable "cannot download the $a packages $SYSROOT_DEBS (see $A/download.log)"
    for d in "$A"/debs/*.deb; do dpkg-deb -x "$d" "$S" || unavailable "cannot unpack $d"; done
    echo "$SYSROOT_DEBS" >"$S/.stamp"
}
for a in $need_linux; do make_sysroot "$a"; done

mkdir -p build
# The Linux targets compare their command's outputs with the host's build/qorient: made once
# here, before the lanes below could start two makes of the same files at once.
if [ -n "$need_linux" ]; then
    make -s -j2 build/qorient >build/qemu-host-qorient.log 2>&1 ||
        echo "test-qemu: the host's build/qorient did not build (see build/qemu-host-qorient.log)"
fi

# The targets run in QEMU_JOBS lanes at once (default: the cores this process may use, as
# nproc counts them; never more lanes than targets): every program is one single-threaded
# emulator, so one lane per core is what the machine can give. Each lane takes the next target
# from a queue, longest first (the soft-float M0, then the two Linux suites), and prints its
# target's report when the target is done.
JOBS=${QEMU_JOBS:-$(nproc 2>/dev/null || echo 1)}
case $JOBS in ''|*[!0-9]*|0) JOBS=1;; esac
NT=$(echo $TARGETS | wc -w)
[ "$JOBS" -gt "$NT" ] && JOBS=$NT
Q=build/qemu-queue
rm -rf "$Q"; mkdir -p "$Q/todo" "$Q/done"
i=10
for t in m0 armhf aarch64 m4f m7; do
    case " $TARGETS " in *" $t "*) i=$((i + 1)); echo "$t" >"$Q/todo/$i";; esac
done
lane() {
    for f in "$Q"/todo/*; do
        [ -e "$f" ] || continue
        # rename is atomic: the lane whose mv succeeds runs the target
        mv "$f" "$f.$1" 2>/dev/null || continue
        t=$(cat "$f.$1")
        s=$(date +%s)
        sh tests/qemu/run-target.sh "$t" >"$Q/done/$t.out" 2>&1
        echo "$? $(( $(date +%s) - s ))" >"$Q/done/$t.rc"
        cat "$Q/done/$t.out"
    done
}
T0=$(date +%s)
echo "test-qemu: $NT targets in $JOBS lanes"
l=1
while [ "$l" -le "$JOBS" ]; do lane "$l" & l=$((l + 1)); done
wait

RES=build/qemu-results.md
{
    echo "| target | emulator | programs | tests passed | tests failed | programs skipped | time: target total wall / tests' CPU |"
    echo "|---|---|---|---|---|---|---|"
} >"$RES"
total_p=0; total_f=0; bad=""
for t in $TARGETS; do
    if [ -f "$Q/done/$t.rc" ]; then read -r rc dt <"$Q/done/$t.rc"; else rc=2; dt=0; fi
    sum=build/qemu-$t/summary.txt
    [ -f "$sum" ] || : >"$sum"
    p=$(awk '$2 != "skipped" { s += $2 } END { print s + 0 }' "$sum")
    f=$(awk '$2 != "skipped" { s += $3 } END { print s + 0 }' "$sum")
    n=$(awk '$2 != "skipped"' "$sum" | wc -l)
    k=$(awk '$2 == "skipped" { printf "%s%s", sep, $1; sep = ", " }' "$sum")
    c=$(awk '$2 != "skipped" { s += $5 } END { printf "%.0f", s }' "$sum")
    case $t in
    m0) emu="qemu-system-arm microbit (Cortex-M0, soft float)";;
    m4f) emu="qemu-system-arm mps2-an386 (Cortex-M4F)";;
    m7) emu="qemu-system-arm mps2-an500 (Cortex-M7, FPv5-D16)";;
    aarch64) emu="qemu-aarch64 -cpu cortex-a72";;
    armhf) emu="qemu-arm -cpu cortex-a7";;
    esac
    echo "| $t | $emu | $n | $p | $f | ${k:-none} | $dt s / $c s |" >>"$RES"
    total_p=$((total_p + p)); total_f=$((total_f + f))
    [ "$rc" -ne 0 ] && bad="$bad $t"
done
echo
echo "== test-qemu results ($(( $(date +%s) - T0 )) s), also in $RES"
cat "$RES"
for t in $TARGETS; do
    awk -v t="$t" '$2 != "skipped" { p += $2; f += $3 } END { printf "%s: %d passed, %d failed\n", t, p, f }' \
        "build/qemu-$t/summary.txt"
done
[ -n "$bad" ] && echo "failing targets:$bad"
echo "$total_p passed, $total_f failed"
[ -z "$bad" ] && [ "$total_f" -eq 0 ] && [ "$total_p" -gt 0 ]
