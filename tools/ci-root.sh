#!/bin/sh
# tools/ci-root.sh - run a command in a clean clone of this checkout inside a Debian minbase root.
#
#   sh tools/ci-root.sh SUITE [--fresh] -- COMMAND [ARG...]
#
# SUITE is a Debian release (bookworm, trixie). The root is made with debootstrap --variant=minbase
# from the mirror this machine's apt uses, and kept in $QO_CI_ROOTS/SUITE (default
# /var/cache/qorient-ci) between runs; --fresh throws it away and makes a new one, which is how a
# "fresh Debian machine" is proved (.ci/run itself, in a new bookworm root). The checkout's HEAD is
# cloned into /src/qorient of the root (committed work only, like CI's clean clone; the root's
# earlier clone is removed) and COMMAND runs there as root, with /proc, /sys, /dev and /dev/pts
# mounted and /etc/resolv.conf copied in. The mounts are undone on every exit.
#
# Prints "ci-root: SUITE: ... in N s" lines for each stage. Exit status: COMMAND's; 77 if the root
# cannot be made here (no debootstrap and no apt-get, not root, mirror unreachable).
set -eu
cd "$(dirname "$0")/.."
SRC=$PWD
usage() { echo "usage: sh tools/ci-root.sh SUITE [--fresh] -- COMMAND [ARG...]" >&2; exit 2; }
[ $# -ge 1 ] || usage
SUITE=$1; shift
case $SUITE in *[!a-z]*|'') usage;; esac
FRESH=0
while [ $# -gt 0 ]; do
    case $1 in
    --fresh) FRESH=1; shift;;
    --) shift; break;;
    *) usage;;
    esac
done
[ $# -ge 1 ] || usage
say() { printf 'ci-root: %s: %s\n' "$SUITE" "$*"; }
skip() { say "SKIPPED: $*"; exit 77; }
[ "$(id -u)" = 0 ] || skip "needs root (debootstrap, chroot, mount)"

if ! command -v debootstrap >/dev/null 2>&1; then
    command -v apt-get >/dev/null 2>&1 || skip "no debootstrap and no apt-get"
    say "installing debootstrap"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends debootstrap >/dev/null ||
        skip "apt-get install debootstrap failed"
fi
# The first Debian archive URI of this machine's apt sources (deb822 or one-line format).
MIRROR=$(cat /etc/apt/sources.list.d/*.sources /etc/apt/sources.list 2>/dev/null |
    sed -n -e 's|^URIs: *\(http[^ ]*/debian\)/*$|\1|p' -e 's|^deb  *\(http[^ ]*/debian\)/* .*|\1|p' |
    head -n 1)
MIRROR=${MIRROR:-http://deb.debian.org/debian}

BASE=${QO_CI_ROOTS:-/var/cache/qorient-ci}
R=$BASE/$SUITE
mounted=""
cleanup() {
    for m in $mounted; do umount -l "$m" 2>/dev/null || true; done
}
trap cleanup EXIT INT TERM

now() { date +%s; }
if [ "$FRESH" = 1 ] && [ -d "$R" ]; then
    # Never rm -rf through a live mount.
    grep -q " $R/" /proc/mounts && skip "$R still has mounts; unmount them first"
    rm -rf "$R"
fi
if [ ! -f "$R/.qorient-ci-ready" ]; then
    t=$(now)
    rm -rf "$R"; mkdir -p "$BASE"
    say "debootstrap --variant=minbase $SUITE from $MIRROR"
    debootstrap --variant=minbase "$SUITE" "$R" "$MIRROR" >"$BASE/$SUITE.debootstrap.log" 2>&1 ||
        { tail -n 20 "$BASE/$SUITE.debootstrap.log" >&2; skip "debootstrap failed (log: $BASE/$SUITE.debootstrap.log)"; }
    # The updates suite too, as on an installed machine (security updates come from another
    # archive, debian-security, that a mirror of the main archive need not carry: not added).
    printf 'deb %s %s main\ndeb %s %s-updates main\n' "$MIRROR" "$SUITE" "$MIRROR" "$SUITE" \
        >"$R/etc/apt/sources.list"
    touch "$R/.qorient-ci-ready"
    say "root made in $(( $(now) - t )) s"
else
    say "root kept from an earlier run ($R)"
fi

cp /etc/resolv.conf "$R/etc/resolv.conf" 2>/dev/null || true
for m in proc sys dev dev/pts; do
    mkdir -p "$R/$m"
    case $m in
    proc) mount -t proc proc "$R/proc";;
    sys) mount -t sysfs sys "$R/sys";;
    dev) mount --bind /dev "$R/dev";;
    dev/pts) mount --bind /dev/pts "$R/dev/pts";; # the host's /dev/ptmx goes with it
    esac
    mounted="$R/$m $mounted"
done

rm -rf "$R/src/qorient"; mkdir -p "$R/src"
git clone -q --no-local "$SRC" "$R/src/qorient"
say "clean clone of $(git -C "$SRC" rev-parse --short HEAD) in /src/qorient"

t=$(now)
set +e
# A clean environment, as a login on that machine would have (PATH of Debian's root).
chroot "$R" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    sh -c 'cd /src/qorient && exec "$@"' sh "$@"
rc=$?
set -e
say "'$*' exited $rc in $(( $(now) - t )) s"
exit $rc
