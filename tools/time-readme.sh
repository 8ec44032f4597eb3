#!/bin/sh
# tools/time-readme.sh - times README's two commands, `make demo` and `make test`, each on a
# fresh Debian minbase root with only make and git installed, as a new user would run them
# (the figures of docs/PLATFORMS.md).
#
#   sh tools/time-readme.sh SUITE [COMMAND...]      e.g.  sh tools/time-readme.sh trixie
#
# A pristine root of SUITE is made once with tools/ci-root.sh (debootstrap, kept in
# $QO_TIME_ROOTS/SUITE-pristine, default /var/cache/qorient-time); each command then runs in
# its own copy of it, in a clean clone of HEAD, after `apt-get install make git`. The time
# includes the packages the command installs (tools/deps.sh) and the whole build, so it
# depends on the mirror and on the machine's load; it does not include make and git.
# COMMANDs default to "make demo" "make test". Prints "time-readme: SUITE: 'CMD' ... N s" lines.
# Exit: 0, 1 if a command failed, 77 if the root cannot be made.
set -eu
cd "$(dirname "$0")/.."
[ $# -ge 1 ] || { echo "usage: sh tools/time-readme.sh SUITE [COMMAND...]" >&2; exit 2; }
SUITE=$1; shift
[ $# -ge 1 ] || set -- "make demo" "make test"
BASE=${QO_TIME_ROOTS:-/var/cache/qorient-time}
say() { printf 'time-readme: %s: %s\n' "$SUITE" "$*"; }
mkdir -p "$BASE/pristine"
set +e
QO_CI_ROOTS=$BASE/pristine sh tools/ci-root.sh "$SUITE" -- true
rc=$?
set -e
[ $rc = 0 ] || exit $rc
rc=0
for cmd in "$@"; do
    rm -rf "$BASE/run/$SUITE"; mkdir -p "$BASE/run"
    cp -a "$BASE/pristine/$SUITE" "$BASE/run/$SUITE"
    set +e
    QO_CI_ROOTS=$BASE/run sh tools/ci-root.sh "$SUITE" -- sh -c '
        export DEBIAN_FRONTEND=noninteractive
        { apt-get update -q && apt-get install -y -q --no-install-recommends make git; } >/dev/null || exit 1
        t=$(date +%s)
        '"$cmd"' >/tmp/time-readme.log 2>&1
        r=$?
        tail -n 5 /tmp/time-readme.log
        echo "time-readme: '"$SUITE"': '"'$cmd'"' exited $r in $(( $(date +%s) - t )) s on a fresh root"
        exit $r'
    r=$?
    set -e
    [ $r = 0 ] || rc=1
done
say "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores"
rm -rf "$BASE/run/$SUITE"
exit $rc
