#!/bin/sh
# tools/ci-trixie.sh - CI's trixie stage: Debian 13 (today's Raspberry Pi OS base, libgpiod 2.x)
# tested from CI's bookworm machine, in a trixie minbase root made by tools/ci-root.sh (kept in
# /var/cache/qorient-ci/trixie between runs, rebuilt when absent).
#
#   sh tools/ci-trixie.sh [--fresh]
#
# In a clean clone inside the root, as on a fresh machine that has only make and git:
#   1. README's `make test` (it installs its own packages through tools/deps.sh);
#   2. `make test-vm` on the libgpiod v2 path (the VM's kernel and modules are Debian 13's,
#      cached in the root's /var/cache/qorient-vm); its 77 (cannot set up) counts as a failure
#      here, since the root and its mirror are known to work;
#   3. the command's outputs for fixed inputs (tools/cli-outputs.sh), compared with this
#      bookworm machine's build/qorient (built here when absent). The float32 core must give
#      the same bits on both systems. QO_CLI_COMPARE=warn (default) reports differences without
#      failing; QO_CLI_COMPARE=fail fails the stage on any difference (switch once the core no
#      longer calls libm); off skips it.
#
# Exit: 0 pass, 1 fail, 77 only when the root itself cannot be made (no debootstrap, not root,
# mirror unreachable). Prints "ci-trixie: ..." lines with each part's result and time.
set -eu
cd "$(dirname "$0")/.."
say() { printf 'ci-trixie: %s\n' "$*"; }
now() { date +%s; }

if [ "${1:-}" = --inside ]; then
    # Runs inside the root (tools/ci-root.sh): each part's status is reported, none stops the others.
    export DEBIAN_FRONTEND=noninteractive
    rc=0
    t=$(now)
    { apt-get update -q && apt-get install -y -q --no-install-recommends make git; } >/dev/null ||
        { say "FAIL: apt-get install make git"; exit 1; }
    say "make and git installed in $(( $(now) - t )) s"
    t=$(now)
    if make test; then say "make test passed in $(( $(now) - t )) s"
    else say "FAIL: make test in $(( $(now) - t )) s"; rc=1; fi
    t=$(now)
    set +e
    QO_VM_DIR=/var/cache/qorient-vm make test-vm >build/test-vm.log 2>&1
    vrc=$?
    set -e
    cat build/test-vm.log
    if [ $vrc = 0 ] && ! grep -q 'QOVM: libgpiod v2 API' build/test-vm.log; then
        say "FAIL: make test-vm passed but not on the libgpiod v2 API"; vrc=1
    fi
    if [ $vrc = 0 ]; then say "make test-vm (v2) passed in $(( $(now) - t )) s"
    else say "FAIL: make test-vm exited $vrc in $(( $(now) - t )) s"; rc=1; fi
    if [ "${QO_CLI_COMPARE:-warn}" != off ]; then
        sh tools/cli-outputs.sh build/qorient build/cli-trixie || { say "FAIL: cli-outputs"; rc=1; }
    fi
    exit $rc
fi

FRESH=""
[ "${1:-}" = --fresh ] && FRESH=--fresh
MODE=${QO_CLI_COMPARE:-warn}
case $MODE in warn|fail|off) ;; *) echo "ci-trixie: QO_CLI_COMPARE must be warn, fail or off" >&2; exit 2;; esac
T0=$(now)
set +e
sh tools/ci-root.sh trixie $FRESH -- env QO_CLI_COMPARE="$MODE" sh tools/ci-trixie.sh --inside
rc=$?
set -e
if [ $rc = 77 ]; then say "SKIPPED: no trixie root on this machine (see above)"; exit 77; fi
[ $rc = 0 ] || rc=1

if [ "$MODE" != off ]; then
    TRIX=${QO_CI_ROOTS:-/var/cache/qorient-ci}/trixie/src/qorient/build/cli-trixie
    if [ ! -x build/qorient ]; then make -s build/qorient; fi
    crc=0 same=0 same_list=""
    sh tools/cli-outputs.sh build/qorient build/cli-bookworm || crc=1
    for f in build/cli-bookworm/in.* build/cli-bookworm/*.out; do
        b=${f##*/}
        [ -f "$TRIX/$b" ] || { say "cli compare: $b missing from trixie"; crc=1; continue; }
        if cmp -s "$f" "$TRIX/$b"; then
            case $b in *.out) same=$((same + 1)); same_list="$same_list ${b%.out}";; esac
            continue
        fi
        case $b in in.*) say "cli compare: input $b differs between the systems"; crc=1; continue;; esac
        # Lines that differ, the largest difference of a number in them, and the largest in
        # float32 ulps of the bookworm value (2^(floor(log2|x|) - 23); the outputs are float32).
        paste -d '\n' "$f" "$TRIX/$b" | awk -v name="$b" '
            NR % 2 == 1 { a = $0; next }
            a != $0 { n++; na = split(a, x, /[ ,]+/); split($0, y, /[ ,]+/)
                      for (i = 1; i <= na; i++) {
                          d = x[i] - y[i]; if (d < 0) d = -d; if (d > m) m = d
                          ax = x[i] < 0 ? -x[i] : x[i]
                          if (d > 0 && ax > 1e-30) { u = d / 2 ^ (int(log(ax) / log(2) + 64) - 64 - 23); if (u > mu) mu = u }
                      }
                      if (n == 1) first = "bookworm: " a "\n          trixie:   " $0 }
            END { printf "ci-trixie: cli compare: %s: %d of %d lines differ, largest difference %.3g (%.0f ulp)\n          %s\n",
                         name, n, NR / 2, m, mu, first }'
        crc=1
    done
    say "cli compare: $same of $(ls build/cli-bookworm/*.out | wc -l) output files identical: $same_list"
    if [ $crc = 0 ]; then say "cli compare: bookworm and trixie outputs are identical"
    elif [ "$MODE" = fail ]; then say "FAIL: cli compare: outputs differ between bookworm and trixie"; rc=1
    else say "WARNING: cli compare: outputs differ between bookworm and trixie (QO_CLI_COMPARE=fail makes this fail)"; fi
fi
say "trixie stage $( [ $rc = 0 ] && echo passed || echo FAILED ) in $(( $(now) - T0 )) s"
exit $rc
