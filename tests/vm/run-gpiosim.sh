#!/bin/sh
# tests/vm/run-gpiosim.sh - the GPIO sink against real kernel GPIO lines (gpio-sim) in a
# qemu VM (what `make test-vm` runs), on the libgpiod API this machine's libgpiod-dev has
# (pkg-config: v2 from libgpiod 2.x, Debian 13; else v1, Debian 12).
#
#   sh tests/vm/run-gpiosim.sh            from the repository root
#
# The kernel is Debian's (linux-image-amd64 of this machine's apt). Its modules are under
# /lib/modules (Debian 12) or /usr/lib/modules (Debian 13), plain or compressed (.ko.xz,
# .ko.zst): they are decompressed here, because busybox insmod in the initramfs takes plain .ko.
# When the kernel ships gpio-sim (CONFIG_GPIO_SIM=m) that module and its dependencies are used
# (no Debian kernel does yet, so that branch is not exercised here); else (Debian 12 and 13)
# irq_sim and gpio-sim are built out of tree from the matching linux-source
# (see /work/shared/research/feasibility-gpiosim.md for why and for the one-line irq_sim patch).
#
# Env: QO_VM_DIR (cache, default build/vm), QO_VM_INSTALL=0 to never apt-get install,
#      VM_MEM (MB, default 256; 96 is the known minimum), QO_VM_TIMEOUT (s, default 240).
# Needs: root for apt-get and mknod (CI has it), up to about 200 MB of .debs on the first run
# (kept in the cache), qemu-system-x86_64 (TCG is fine: about 5-10 s per boot).
# Exit: 0 pass, 1 fail, 2 no result (panic, OOM, timeout), 77 skipped (cannot set up: no
# Debian kernel in apt, packages that cannot be installed or downloaded, no root).
# Prints the libgpiod API exercised, the ticks and the positions the kernel saw ("QOVM:" lines);
# last line: "N passed, M failed" like the other shell tests.
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
VM=$ROOT/tests/vm
W=${QO_VM_DIR:-$ROOT/build/vm}
mkdir -p "$W/debs"
W=$(cd "$W" && pwd)
say() { printf 'run-gpiosim: %s\n' "$*"; }
skip() { say "SKIP: $*"; echo "0 passed, 0 failed"; exit 77; }
APT="apt-get -o DPkg::Lock::Timeout=900"
export DEBIAN_FRONTEND=noninteractive

kernel_pkg() {
    apt-cache depends linux-image-amd64 2>/dev/null |
        sed -n 's/.*Depends: \(linux-image-[0-9].*-amd64\).*/\1/p' | head -n1
}
KPKG=$(kernel_pkg)
# A fresh root may have no package lists yet.
if [ -z "$KPKG" ] && [ "${QO_VM_INSTALL:-1}" = 1 ] && [ "$(id -u)" = 0 ]; then
    $APT update -q >/dev/null 2>&1 || true
    KPKG=$(kernel_pkg)
fi
[ -n "$KPKG" ] || skip "no linux-image-amd64 in apt (not Debian amd64?)"
KVER=${KPKG#linux-image-}                                        # 6.1.0-56-amd64, 6.12.48+deb13-amd64
PVER=$(apt-cache policy "$KPKG" | sed -n 's/ *Candidate: //p')   # 6.1.192-2
SRCPKG=linux-source-$(echo "$KVER" | cut -d. -f1,2)              # linux-source-6.1

# Prints a module decompressed (plain, .xz or .zst); fails when it cannot.
unpack_ko() {
    case $1 in
    *.ko.xz) xz -dc "$1";;
    *.ko.zst) zstd -qdc "$1";;
    *.ko.gz) gzip -dc "$1";;
    *.ko) cat "$1";;
    *) return 1;;
    esac
}

# ---- host packages ----
need_pkgs() {
    missing=""
    for p in "$@"; do dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"; done
    [ -z "$missing" ] && return 0
    [ "${QO_VM_INSTALL:-1}" = 1 ] && [ "$(id -u)" = 0 ] || skip "missing:$missing"
    say "installing:$missing"
    $APT install -y -q --no-install-recommends $missing >/dev/null ||
        { $APT update -q >/dev/null 2>&1 && $APT install -y -q --no-install-recommends $missing >/dev/null; } ||
        skip "apt-get install$missing failed"
}
need_pkgs qemu-system-x86 busybox-static cpio xz-utils zstd gcc libc6-dev pkg-config libgpiod-dev
command -v qemu-system-x86_64 >/dev/null || skip "no qemu-system-x86_64 after install"

# ---- kernel image and the modules gpio-sim needs (cached per kernel package version: the
# sources must be the very version the image was built from) ----
K=$W/$KVER-$PVER
KDEB=$W/debs/${KPKG}_${PVER}_amd64.deb
SDEB=$W/debs/${SRCPKG}_${PVER}_all.deb
if [ ! -f "$K/ready" ]; then
    rm -rf "$K"; mkdir -p "$K/mods"
    [ -f "$KDEB" ] || (cd "$W/debs" && $APT download "$KPKG=$PVER" >/dev/null 2>&1) ||
        skip "cannot download $KPKG=$PVER"
    dpkg-deb -x "$KDEB" "$K/kroot" || skip "cannot unpack $KDEB"
    cp "$K/kroot/boot/vmlinuz-$KVER" "$K/vmlinuz" || skip "no /boot/vmlinuz-$KVER in $KPKG"
    MD=""
    for d in "$K/kroot/lib/modules/$KVER" "$K/kroot/usr/lib/modules/$KVER"; do
        [ -d "$d/kernel" ] && MD=$d
    done
    [ -n "$MD" ] || skip "no modules directory for $KVER in $KPKG"
    # Finds a module file by name (any compression) under the kernel's module tree.
    # (depends= names use '_' where a file name may have '-')
    find_ko() {
        p=$(echo "$1" | sed 's/[-_]/[-_]/g')
        find "$MD/kernel" \( -name "$p.ko" -o -name "$p.ko.*" \) | head -n 1
    }
    # Loads NAME's dependencies first (modinfo's depends= read from the module itself, since
    # the package ships no modules.dep), then NAME; appends to mods/order.
    add_mod() {
        grep -qx "$1" "$K/mods/order" 2>/dev/null && return 0
        f=$(find_ko "$1")
        [ -n "$f" ] || return 1
        unpack_ko "$f" >"$K/mods/$1.ko" || return 1
        for dep in $(tr '\0' '\n' <"$K/mods/$1.ko" | sed -n 's/^depends=//p' | tr ',' ' '); do
            add_mod "$dep" || return 1
        done
        echo "$1" >>"$K/mods/order"
    }
    if [ -n "$(find_ko gpio-sim)" ]; then
        add_mod gpio-sim || skip "cannot unpack gpio-sim and its dependencies from $KPKG"
        echo "kernel's own gpio-sim" >"$K/how"
    else
        # Debian 12: CONFIG_GPIO_SIM is not set. configfs from the package, the two drivers
        # built from the same kernel version's sources.
        add_mod configfs || skip "no configfs module in $KPKG"
        need_pkgs make "linux-headers-$KVER"
        [ -f "$SDEB" ] || (cd "$W/debs" && $APT download "$SRCPKG=$PVER" >/dev/null 2>&1) ||
            skip "cannot download $SRCPKG=$PVER"
        mkdir -p "$K/kmod" "$K/src"
        dpkg-deb --fsys-tarfile "$SDEB" | tar -xO "./usr/src/$SRCPKG.tar.xz" | xz -dc |
            tar -x -C "$K/src" --strip-components=1 --wildcards '*/drivers/gpio/gpio-sim.c' \
                '*/drivers/gpio/gpiolib.h' '*/kernel/irq/irq_sim.c' || skip "cannot unpack $SRCPKG"
        cp "$K/src/drivers/gpio/gpio-sim.c" "$K/src/drivers/gpio/gpiolib.h" "$K/src/kernel/irq/irq_sim.c" "$K/kmod/"
        # irq_to_desc() is not exported to modules; generic_handle_irq() reaches the same
        # handle_simple_irq handler.
        sed -i 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' "$K/kmod/irq_sim.c"
        grep -q 'generic_handle_irq(irqnum)' "$K/kmod/irq_sim.c" || skip "irq_sim.c patch did not apply"
        printf 'MODULE_LICENSE("GPL");\n' >> "$K/kmod/irq_sim.c"
        echo 'obj-m := irq_sim.o gpio-sim.o' > "$K/kmod/Kbuild"
        make -s -C "/usr/src/linux-headers-$KVER" M="$K/kmod" modules 2>&1 | grep -v 'Skipping BTF' || true
        [ -f "$K/kmod/gpio-sim.ko" ] || skip "module build failed"
        cp "$K/kmod/irq_sim.ko" "$K/kmod/gpio-sim.ko" "$K/mods/"
        printf 'irq_sim\ngpio-sim\n' >>"$K/mods/order"
        echo "gpio-sim built out of tree from $SRCPKG=$PVER" >"$K/how"
        rm -rf "$K/src" "$K/kmod"
    fi
    rm -rf "$K/kroot"
    touch "$K/ready"
fi

# ---- the test program, static, from the current sources, on the API pkg-config selects ----
API=v1
pkg-config --atleast-version=2 libgpiod 2>/dev/null && API=v2
LIBA=$(pkg-config --variable=libdir libgpiod 2>/dev/null)/libgpiod.a
[ -f "$LIBA" ] || skip "no static $LIBA (libgpiod-dev)"
CC=${CC:-cc}
# The port and core archives `make test-vm` builds first: the linker takes what gpio_sink and the
# streamer need from them, so a new source file in ports/ cannot be forgotten here.
BUILD=${BUILD:-$ROOT/build}
for a in libqorient_ports.a libqorient.a; do
    [ -f "$BUILD/$a" ] || { echo "run-gpiosim: $BUILD/$a missing (run make test-vm)" >&2; exit 1; }
done
DEF=-DQO_GPIOD_V1
[ $API = v2 ] && DEF=-DQO_GPIOD_V2
$CC -std=c99 -O2 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE $DEF \
    $(pkg-config --cflags libgpiod) -I"$ROOT/lib/include" -I"$ROOT/ports" -static -o "$W/gpiosim_stream" \
    "$VM/gpiosim_stream.c" "$BUILD/libqorient_ports.a" "$BUILD/libqorient.a" "$LIBA" -lm -pthread

# ---- initramfs ----
R=$(mktemp -d)
trap 'rm -rf "$R"' EXIT
mkdir -p "$R/bin" "$R/dev" "$R/proc" "$R/sys" "$R/lib/modules"
cp /bin/busybox "$R/bin/busybox"
ln -s busybox "$R/bin/sh"
cp "$VM/init" "$R/init"
chmod 755 "$R/init"
cp "$W/gpiosim_stream" "$R/gpiosim_stream"
cp "$K/mods/"*.ko "$K/mods/order" "$R/lib/modules/"
mknod "$R/dev/console" c 5 1 2>/dev/null || skip "mknod needs root"   # else no console output
(cd "$R" && find . | cpio -o -H newc --quiet) | gzip -1 > "$W/initramfs.cpio.gz"

# ---- boot ----
LOG=$W/vm.log
say "booting $KVER (TCG, ${VM_MEM:-256} MB), $(cat "$K/how"), modules: $(tr '\n' ' ' <"$K/mods/order")"
say "libgpiod $(pkg-config --modversion libgpiod) ($API API)"
timeout "${QO_VM_TIMEOUT:-240}" qemu-system-x86_64 -m "${VM_MEM:-256}" -nographic -no-reboot -net none \
    -kernel "$K/vmlinuz" -initrd "$W/initramfs.cpio.gz" \
    -append "console=ttyS0 quiet panic=-1" </dev/null >"$LOG" 2>&1 || true
# The serial log starts with firmware escape sequences: match markers unanchored.
tr -d '\r' <"$LOG" | grep -a -o -E '(RESULT|MISMATCH|TIMING|QOVM):.*' || true
RC=$(tr -d '\r' <"$LOG" | sed -n 's/.*QOTEST-EXIT=\([0-9]*\).*/\1/p' | tail -n1)
if [ -z "$RC" ]; then say "VM gave no result (log: $LOG)"; echo "0 passed, 1 failed"; exit 2; fi
if [ "$RC" = 0 ]; then echo "1 passed, 0 failed"; exit 0; fi
echo "0 passed, 1 failed"
exit 1
