#!/bin/sh
# Builds and runs the tests for one emulated target (called by tools/test-qemu.sh, which
# installs the prerequisites first):
#
#   sh tests/qemu/run-target.sh m0|m4f|m7       core cmocka tests, bare metal under
#                                               qemu-system-arm (microbit, mps2-an386, mps2-an500)
#                                               with semihosting and the cmocka shim of tests/qemu
#   sh tests/qemu/run-target.sh aarch64|armhf   the whole host suite (core, ports, cmocka and
#                                               shell tests, ASan+UBSan) cross-built with the top
#                                               Makefile and run under qemu-aarch64 / qemu-arm,
#                                               and the command's outputs compared with the
#                                               host's (cli_outputs: tools/cli-outputs.sh)
#   sh tests/qemu/run-target.sh list            prints which programs each kind of target takes
#                                               ("cortex-m tests/core/test_quat.c", "linux ...")
#                                               and builds nothing
#
# The programs are tests/SUITE/test_*.c and tests/SUITE/test_*.sh (SUITE: core, ports, examples,
# fuzz, cli); the Cortex-M targets take the C programs that pass is_core below, whatever their folder.
#
# Prints one line per program ("  test_quat: 14 passed, 0 failed (3.1 s wall, 2.9 s cpu)"), a
# "[   TIME   ]" line from the Cortex-M shim for each test function over 1 s of CPU, and a last line
# "TARGET: N passed, M failed". A program that does not build, crashes, times out or exits
# non-zero without a cmocka report counts as one failure. Logs: build/qemu-TARGET/logs/.
# Exit status 0 only if nothing failed and something passed.
#
# Environment: QEMU_TIMEOUT (seconds per program; default 1800 on m0 and armhf, 600 elsewhere:
# wall time on a possibly shared machine; test_motion_oracle is the longest everywhere),
# QEMU_SKIP (space-separated test names to skip on purpose, reported as skipped),
# QEMU_SYSROOT (default build/qemu-sysroot-ARCH, made by tools/test-qemu.sh).
set -u
cd "$(dirname "$0")/../.." || exit 2
T=${1:?usage: run-target.sh m0|m4f|m7|aarch64|armhf}
OUT=build/qemu-$T
LOGS=$OUT/logs
passed=0; failed=0; skipped=""; problems=""
SUMMARY=$OUT/summary.txt
if [ "$T" != list ]; then mkdir -p "$LOGS"; : >"$SUMMARY"; fi

now() { date +%s.%N; }
# CPU seconds used so far by finished children (user + sys), from `times` run in this shell
# (in a $(...) subshell it would count the subshell's children only): unlike wall time, not
# inflated when the machine is shared.
TIMES=$LOGS/.times
cpu_of() { tail -1 "$1" | awk '{ n = 0; for (i = 1; i <= NF; i++) { split($i, a, "m"); n += a[1] * 60 + a[2] } printf "%.2f", n }'; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.1f", b - a }'; }

# A core test includes only C99 headers, <cmocka.h>, "qorient/..." and "common/..." (the core and
# tests/common), or an example's source (say "../examples/mcu/x.c", found like the compiler does:
# beside the including file, else through -Itests) that itself follows this rule: anything else
# (ports/, POSIX, libmodbus, libgpiod) keeps it on Linux.
is_core() {
    d=$(dirname "$1")
    for inc in $(grep -E '^[[:space:]]*#[[:space:]]*include' "$1" | grep -Ev \
        -e '<(assert|ctype|errno|float|inttypes|iso646|limits|locale|math|setjmp|signal|stdarg|stdbool|stddef|stdint|stdio|stdlib|string|wchar|wctype|cmocka)\.h>' \
        -e '"(qorient|common)/[A-Za-z0-9_]+\.h"' | sed 's/[^"<]*[<"]\([^">]*\)[">].*/\1/'); do
        case $inc in
        ../examples/*.[ch])
            if [ -f "$d/$inc" ]; then is_core "$d/$inc" || return 1
            elif [ -f "tests/$inc" ]; then is_core "tests/$inc" || return 1
            else return 1; fi;;
        *) return 1;;
        esac
    done
    return 0
}

# A shell test that compiles a program with the host's cc cannot run against a cross build.
host_cc_test() { grep -Eq '(^|[;&|(]|[[:space:]]|if )cc[[:space:]]' "$1"; }

# count LOG KIND -> "P F" from a cmocka (bin) or shell-test (sh) report
count() {
    if [ "$2" = bin ]; then
        p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$1" | tail -1)
        f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$1" | tail -1)
    else
        p=$(sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed.*/\1/p' "$1" | tail -1)
        f=$(sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed.*/\2/p' "$1" | tail -1)
    fi
    echo "${p:-0} ${f:-0}"
}

# run NAME KIND COMMAND... : runs one program under `timeout`, adds up its report
run() {
    name=$1; kind=$2; shift 2
    log=$LOGS/$name.log
    times >"$TIMES"; c0=$(cpu_of "$TIMES"); t0=$(now)
    timeout -k 10 "$TMO" "$@" >"$log" 2>&1
    rc=$?
    times >"$TIMES"; dt=$(secs "$t0" "$(now)"); dc=$(secs "$c0" "$(cpu_of "$TIMES")")
    set -- $(count "$log" "$kind")
    p=$1; f=$2; note=""
    if [ "$rc" -eq 124 ] || [ "$rc" -eq 137 ]; then
        note=" TIMEOUT after ${TMO} s"; f=$((f + 1))
    elif [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        note=" exited $rc without a failure report (crash?)"; f=$((f + 1))
    elif [ "$p" -eq 0 ] && [ "$f" -eq 0 ]; then
        note=" no report"; f=1
    fi
    [ -n "$note" ] && problems="$problems $name"
    passed=$((passed + p)); failed=$((failed + f))
    echo "  $name: $p passed, $f failed ($dt s wall, $dc s cpu)$note"
    echo "$name $p $f $dt $dc$note" >>"$SUMMARY"
    grep '^\[   TIME   \]' "$log" | sed 's/^/    /'
    if [ "$f" -gt 0 ]; then
        grep -E '^\[  (ERROR|FAILED)|^\[   LINE|FAIL|ERROR|runtime error|Sanitizer|assertion' "$log" | head -20 | sed 's/^/    | /'
    fi
}

skip_it() { # NAME REASON
    skipped="$skipped $1"
    echo "  $1: skipped ($2)"
    echo "$1 skipped $2" >>"$SUMMARY"
}

wanted() { # NAME -> false if listed in QEMU_SKIP
    for s in ${QEMU_SKIP:-}; do [ "$s" = "$1" ] && return 1; done
    return 0
}

build_failed() { # NAME LOGFILE
    failed=$((failed + 1)); problems="$problems $1"
    echo "  $1: BUILD FAILED for $T (counted as 1 failure), see $2:"
    grep -E 'error:' "$2" | sort -u | head -5 | sed 's/^/    | /'
    echo "$1 0 1 0 0 BUILD FAILED" >>"$SUMMARY"
}

case $T in
list)
    for src in tests/*/test_*.c; do
        if is_core "$src"; then echo "cortex-m $src"; else echo "linux $src"; fi
    done
    for sh in tests/*/test_*.sh; do echo "linux $sh"; done
    exit 0
    ;;
m0|m4f|m7)
    case $T in
    m0) BOARD=microbit; CPU=cortex-m0; TMO=${QEMU_TIMEOUT:-1800};;
    m4f) BOARD=mps2-an386; CPU=cortex-m4; TMO=${QEMU_TIMEOUT:-600};;
    m7) BOARD=mps2-an500; CPU=cortex-m7; TMO=${QEMU_TIMEOUT:-600};;
    esac
    echo "== $T: core tests on $CPU ($BOARD) under qemu-system-arm + semihosting"
    core=""
    for src in tests/*/test_*.c; do
        n=$(basename "$src" .c)
        if ! is_core "$src"; then skip_it "$n" "not core: includes a port, POSIX or bus header"; continue; fi
        if ! wanted "$n"; then skip_it "$n" "QEMU_SKIP"; continue; fi
        core="$core $n"
    done
    # -k: one test that does not build for this core must not hide the others.
    make -k -j2 -s -f tests/qemu/cortexm.mk QT="$T" TESTS="$core" >"$LOGS/build.log" 2>&1
    w=$(grep -c 'warning:' "$LOGS/build.log")
    [ "$w" -gt 0 ] && echo "  ($w compiler warnings in test sources for $T, see $LOGS/build.log)"
    QSYS="qemu-system-arm -M $BOARD -nographic -monitor none -serial none -semihosting-config enable=on,target=native"
    # The shim must report exactly what its self-test expects before its reports are believed.
    log=$LOGS/selftest.log
    if [ -f "$OUT/selftest.elf" ]; then
        timeout -k 10 60 $QSYS -kernel "$OUT/selftest.elf" >"$log" 2>&1; rc=$?
    else
        rc=build; echo "selftest.elf did not build" >"$log"
    fi
    want=$(sed -n 's/^#define SELFTEST_\(PASS\|FAIL\|SKIP\) \([0-9]*\)$/\2/p' tests/qemu/selftest.c | tr '\n' ' ' | sed 's/ $//')
    got="$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$log") $(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$log") $(sed -n 's/^\[  SKIPPED \] \([0-9]*\) test.*/\1/p' "$log")"
    if [ "$rc" = 0 ] && [ "$got" = "$want" ]; then
        echo "  shim self-test: ok (passed, failed, skipped = $got as expected; not counted)"
    else
        failed=$((failed + 1)); problems="$problems shim-selftest"
        echo "  shim self-test: FAILED (rc $rc, passed/failed/skipped '$got', want '$want'), see $log"
        echo "shim-selftest 0 1 0 0 SELFTEST FAILED" >>"$SUMMARY"
    fi
    for n in $core; do
        if [ ! -f "$OUT/$n.elf" ]; then
            # Again alone, for this test's own messages: a test whose static data does not fit
            # the board (microbit: 16 KB RAM, 256 KB flash) is skipped with its size, not failed.
            make -s -f tests/qemu/cortexm.mk QT="$T" TESTS="$n" >"$LOGS/$n.build.log" 2>&1
            over=$(sed -n "s/.*region \`\(RAM\|FLASH\)' overflowed by \([0-9]*\) bytes.*/\1 overflowed by \2 bytes/p" \
                "$LOGS/$n.build.log" | head -1)
            if [ -n "$over" ] && ! grep -Eq '\.[ch]:[0-9]+:[0-9]+: error:' "$LOGS/$n.build.log"; then
                skip_it "$n" "does not fit $BOARD: $over"
            else
                build_failed "$n" "$LOGS/$n.build.log"
            fi
            continue
        fi
        run "$n" bin $QSYS -kernel "$OUT/$n.elf"
    done
    ;;
aarch64|armhf)
    TMO=${QEMU_TIMEOUT:-600}
    [ "$T" = armhf ] && TMO=${QEMU_TIMEOUT:-1800}
    if [ "$T" = aarch64 ]; then
        GCC=aarch64-linux-gnu-gcc; TRIPLE=aarch64-linux-gnu; DEB=arm64; QEMU=qemu-aarch64; QCPU=cortex-a72
    else
        GCC=arm-linux-gnueabihf-gcc; TRIPLE=arm-linux-gnueabihf; DEB=armhf; QEMU=qemu-arm; QCPU=cortex-a7
    fi
    S=${QEMU_SYSROOT:-$PWD/build/qemu-sysroot-$DEB}
    L=$S/usr/lib/$TRIPLE
    echo "== $T: host suite cross-built with $GCC, run under $QEMU -cpu $QCPU"
    # The libraries' headers come from a sysroot unpacked from the target's .debs (no dpkg
    # multiarch change); -isystem so that cmocka.h is a system header as on the host.
    export PKG_CONFIG_SYSROOT_DIR="$S" PKG_CONFIG_LIBDIR="$L/pkgconfig"
    # The motion oracle at a tenth of the host's count (its first 1,050 joints per sync mode, the
    # same seeds): under qemu-user with ASan its double reference runs 10-30x slower than on the
    # host (the full count runs there).
    XCC="$GCC -isystem $S/usr/include -L$L -Wl,-rpath-link,$L -DQO_MOTION_ORACLE_JOINTS=1050"
    make -k -j2 -s BUILD="$OUT" CC="$XCC" tests-build >"$LOGS/build.log" 2>&1
    w=$(grep -c 'warning:' "$LOGS/build.log")
    [ "$w" -gt 0 ] && echo "  ($w compiler warnings for $T, see $LOGS/build.log)"
    # -L plus the cross libc first on the library path: with only -L, a multiarch libc6:ARCH on
    # the machine can be picked up next to the cross ld.so and hang in pthread_create.
    QRUN="$QEMU -cpu $QCPU -L /usr/$TRIPLE -E LD_LIBRARY_PATH=/usr/$TRIPLE/lib:$L"
    # LeakSanitizer cannot stop the world under qemu-user (it exits 1 after the report): off.
    export ASAN_OPTIONS=detect_leaks=0
    # The command runs as the target's build/qorient under qemu-user (binfmt_misc is not
    # assumed), through $QORIENT: for the shell tests and for the cmocka programs that run the
    # command as a child (test_fuzz_regress's cli_* cases), never the host's build.
    QW=$PWD/$OUT/qorient-qemu
    printf '#!/bin/sh\nexec %s %s "$@"\n' "$QRUN" "$PWD/$OUT/qorient" >"$QW"
    chmod +x "$QW"
    QORIENT=$QW; export QORIENT
    for src in tests/*/test_*.c; do
        n=$(basename "$src" .c)
        if ! wanted "$n"; then skip_it "$n" "QEMU_SKIP"; continue; fi
        if [ ! -f "$OUT/tests/$n" ]; then build_failed "$n" "$LOGS/build.log"; continue; fi
        run "$n" bin $QRUN "$OUT/tests/$n"
    done
    for sh in tests/*/test_*.sh; do
        n=$(basename "$sh" .sh)
        if ! wanted "$n"; then skip_it "$n" "QEMU_SKIP"; continue; fi
        if host_cc_test "$sh"; then skip_it "$n" "builds and runs a program with the host's cc"; continue; fi
        if [ ! -f "$OUT/qorient" ]; then build_failed "$n" "$LOGS/build.log"; continue; fi
        run "$n" sh sh "$sh"
    done
    # The same bits as on the host (issue 14): the command's outputs for fixed inputs
    # (tools/cli-outputs.sh: convert in every direction and all 24 Euler sequences, slerp,
    # gimbal with the tracking filter, plan with moving targets and target velocities), made by
    # the host's build/qorient and by this target's under qemu-user, compared byte for byte
    # (%.9g round-trips float32); one test per file; run's report of a failure shows the first
    # differing line of each file that differs.
    n=cli_outputs
    if ! wanted "$n"; then skip_it "$n" "QEMU_SKIP"
    elif [ ! -f "$OUT/qorient" ]; then build_failed "$n" "$LOGS/build.log"
    # the host's build, without the target's pkg-config paths exported above
    elif ! env -u PKG_CONFIG_SYSROOT_DIR -u PKG_CONFIG_LIBDIR make -s -j2 build/qorient \
            >"$LOGS/host-qorient.log" 2>&1; then build_failed "$n" "$LOGS/host-qorient.log"
    else
        run "$n" sh sh tools/cli-outputs.sh --compare "$PWD/build/qorient" "$QW" "$OUT/cli-outputs"
    fi
    ;;
*)
    echo "run-target.sh: unknown target '$T' (m0, m4f, m7, aarch64, armhf, list)" >&2
    exit 2
    ;;
esac

[ -n "$problems" ] && echo "  problems:$problems"
echo "$T: $passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
