#!/bin/sh
# tests/vm/run-gpiosim.sh - the GPIO sink against real kernel GPIO lines (gpio-sim) in a
# qemu VM (what `make test-vm` runs). Debian's kernel lacks gpio-sim, so irq_sim and gpio-sim
# are built out of tree from the matching linux-source (see
# /work/shared/research/feasibility-gpiosim.md for why and for the one-line irq_sim patch).
#
#   sh tests/vm/run-gpiosim.sh            from the repository root
#
# Env: QO_VM_DIR (cache, default build/vm), QO_VM_INSTALL=0 to never apt-get install,
#      VM_MEM (MB, default 256; 96 is the known minimum), QO_VM_TIMEOUT (s, default 240).
# Needs: root for apt-get and mknod (CI has it), about 200 MB of .debs on the first run (kept
# in the cache), qemu-system-x86_64 (TCG is fine: about 5-10 s per boot).
# Exit: 0 pass, 1 fail, 2 no result (panic, OOM, timeout), 77 skipped (cannot set up).
# Last line: "N passed, M failed" like the other shell tests.
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
VM=$ROOT/tests/vm
W=${QO_VM_DIR:-$ROOT/build/vm}
mkdir -p "$W/debs"
W=$(cd "$W" && pwd)
say() { printf 'run-gpiosim: %s\n' "$*"; }
skip() { say "SKIP: $*"; echo "0 passed, 0 failed"; exit 77; }
APT="apt-get -o DPkg::Lock::Timeout=900"

KPKG=$(apt-cache depends linux-image-amd64 2>/dev/null |
       sed -n 's/.*Depends: \(linux-image-[0-9].*-amd64\).*/\1/p' | head -n1)
[ -n "$KPKG" ] || skip "no linux-image-amd64 in apt (not Debian amd64?)"
KVER=${KPKG#linux-image-}                                        # e.g. 6.1.0-56-amd64
PVER=$(apt-cache policy "$KPKG" | sed -n 's/ *Candidate: //p')   # e.g. 6.1.192-2
SRCPKG=linux-source-$(echo "$KVER" | cut -d. -f1,2)              # linux-source-6.1

# ---- host packages ----
missing=""
command -v qemu-system-x86_64 >/dev/null || missing="$missing qemu-system-x86"
dpkg -s busybox-static >/dev/null 2>&1 || missing="$missing busybox-static"
command -v cpio >/dev/null || missing="$missing cpio"
[ -d "/usr/src/linux-headers-$KVER" ] || missing="$missing linux-headers-$KVER"
[ -f /usr/lib/x86_64-linux-gnu/libgpiod.a ] || missing="$missing libgpiod-dev"
if [ -n "$missing" ]; then
    [ "${QO_VM_INSTALL:-1}" = 1 ] && [ "$(id -u)" = 0 ] || skip "missing:$missing"
    say "installing:$missing"
    $APT install -y --no-install-recommends $missing >/dev/null || skip "apt-get install failed"
fi

# ---- kernel image and gpio-sim modules (cached per kernel version) ----
K=$W/$KVER
if [ ! -f "$K/gpio-sim.ko" ] || [ ! -f "$K/vmlinuz" ] || [ ! -f "$K/configfs.ko" ]; then
    mkdir -p "$K/kmod" "$K/src"
    (cd "$W/debs" && { ls ${KPKG}_*.deb >/dev/null 2>&1 || $APT download "$KPKG" >/dev/null 2>&1; } &&
        { ls ${SRCPKG}_*.deb >/dev/null 2>&1 || $APT download "$SRCPKG=$PVER" >/dev/null 2>&1; }) ||
        skip "cannot download $KPKG / $SRCPKG=$PVER"
    rm -rf "$K/kroot"
    dpkg-deb -x "$W/debs/${KPKG}"_*.deb "$K/kroot"
    cp "$K/kroot/boot/vmlinuz-$KVER" "$K/vmlinuz"
    cp "$K/kroot/lib/modules/$KVER/kernel/fs/configfs/configfs.ko" "$K/configfs.ko"
    dpkg-deb --fsys-tarfile "$W/debs/${SRCPKG}"_*.deb | tar -xO "./usr/src/$SRCPKG.tar.xz" | xz -dc |
        tar -x -C "$K/src" --strip-components=1 --wildcards '*/drivers/gpio/gpio-sim.c' \
            '*/drivers/gpio/gpiolib.h' '*/kernel/irq/irq_sim.c'
    cp "$K/src/drivers/gpio/gpio-sim.c" "$K/src/drivers/gpio/gpiolib.h" "$K/src/kernel/irq/irq_sim.c" "$K/kmod/"
    # irq_to_desc() is not exported to modules; generic_handle_irq() reaches the same
    # handle_simple_irq handler.
    sed -i 's/handle_simple_irq(irq_to_desc(irqnum));/generic_handle_irq(irqnum);/' "$K/kmod/irq_sim.c"
    grep -q 'generic_handle_irq(irqnum)' "$K/kmod/irq_sim.c" || skip "irq_sim.c patch did not apply"
    printf 'MODULE_LICENSE("GPL");\n' >> "$K/kmod/irq_sim.c"
    echo 'obj-m := irq_sim.o gpio-sim.o' > "$K/kmod/Kbuild"
    make -s -C "/usr/src/linux-headers-$KVER" M="$K/kmod" modules 2>&1 | grep -v 'Skipping BTF' || true
    [ -f "$K/kmod/gpio-sim.ko" ] || skip "module build failed"
    cp "$K/kmod/irq_sim.ko" "$K/kmod/gpio-sim.ko" "$K/"
    rm -rf "$K/kroot" "$K/src"
fi

# ---- the test program, static, from the current sources ----
CC=${CC:-cc}
$CC -std=c99 -O2 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE \
    -I"$ROOT/lib/include" -I"$ROOT/ports" -static -o "$W/gpiosim_stream" \
    "$VM/gpiosim_stream.c" "$ROOT/ports/linux/gpio_sink.c" "$ROOT/ports/linux/streamer.c" \
    "$ROOT/lib/src/status.c" -lgpiod -lm -pthread

# ---- initramfs ----
R=$(mktemp -d)
trap 'rm -rf "$R"' EXIT
mkdir -p "$R/bin" "$R/dev" "$R/proc" "$R/sys" "$R/lib/modules"
cp /bin/busybox "$R/bin/busybox"
ln -s busybox "$R/bin/sh"
cp "$VM/init" "$R/init"
chmod 755 "$R/init"
cp "$W/gpiosim_stream" "$R/gpiosim_stream"
cp "$K/configfs.ko" "$K/irq_sim.ko" "$K/gpio-sim.ko" "$R/lib/modules/"
mknod "$R/dev/console" c 5 1 2>/dev/null || skip "mknod needs root"   # else no console output
(cd "$R" && find . | cpio -o -H newc --quiet) | gzip -1 > "$W/initramfs.cpio.gz"

# ---- boot ----
LOG=$W/vm.log
say "booting $KVER (TCG, ${VM_MEM:-256} MB)"
timeout "${QO_VM_TIMEOUT:-240}" qemu-system-x86_64 -m "${VM_MEM:-256}" -nographic -no-reboot -net none \
    -kernel "$K/vmlinuz" -initrd "$W/initramfs.cpio.gz" \
    -append "console=ttyS0 quiet panic=-1" </dev/null >"$LOG" 2>&1 || true
# The serial log starts with firmware escape sequences: match markers unanchored.
tr -d '\r' <"$LOG" | grep -a -E 'RESULT|MISMATCH|part [AB]|libgpiod' || true
RC=$(tr -d '\r' <"$LOG" | sed -n 's/.*QOTEST-EXIT=\([0-9]*\).*/\1/p' | tail -n1)
if [ -z "$RC" ]; then say "VM gave no result (log: $LOG)"; echo "0 passed, 1 failed"; exit 2; fi
if [ "$RC" = 0 ]; then echo "1 passed, 0 failed"; exit 0; fi
echo "0 passed, 1 failed"
exit 1
