#!/bin/sh
# Installs the Debian packages a make target needs, when they are missing.
#   sh tools/deps.sh build|test|demo|fuzz
# On Debian bookworm / Raspberry Pi OS: uses apt-get, through sudo when not root (sudo asks for
# your password; nothing is installed without it). Set QO_NO_INSTALL=1 to only list what is
# missing and fail instead.
set -eu
BUILD="build-essential pkg-config libmodbus-dev libgpiod-dev libinih-dev"
TEST="$BUILD libcmocka-dev python3"
DEMO="$BUILD gnuplot-nox"
# libFuzzer and the sanitizer runtimes are in libclang-rt-N-dev, only a Recommends of clang: named
# for the clang that is installed (14 on Debian 12, 19 on Debian 13), after clang itself.
FUZZ="$BUILD clang"
case ${1:-build} in
build) want=$BUILD;;
test) want=$TEST;;
demo) want=$DEMO;;
fuzz)
    if ! dpkg -s clang >/dev/null 2>&1; then sh "$0" fuzz-clang || exit 1; fi
    v=$(clang --version 2>/dev/null | sed -n 's/.*clang version \([0-9][0-9]*\)\..*/\1/p' | head -n 1)
    [ -n "$v" ] || { echo "qorient: cannot tell the version of clang" >&2; exit 1; }
    want="$FUZZ libclang-rt-$v-dev";;
fuzz-clang) want=$FUZZ;;
*) echo "usage: tools/deps.sh build|test|demo|fuzz" >&2; exit 2;;
esac
missing=""
for p in $want; do
    dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
[ -z "$missing" ] && exit 0
echo "qorient: the '${1:-build}' target needs these Debian packages:$missing"
if [ "${QO_NO_INSTALL:-0}" = 1 ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "qorient: install them (apt-get install$missing) and run make again" >&2
    exit 1
fi
if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; echo "qorient: installing with sudo (you may be asked for your password)"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends $missing
