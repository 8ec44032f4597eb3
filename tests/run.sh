#!/bin/sh
# Runs the cmocka test programs and the shell tests given on the command line
# (programs first, then `--`, then shell scripts), adds up what each reports and prints
# a labelled line per program ("== NAME: N passed, M failed"), a summary of them at the end and
# one closing line "N passed, M failed". Exit status 1 if anything failed or a program
# crashed (a crash counts as one failure even if cmocka had no chance to report it).
# The summary also adds them up per suite, the program's folder under tests/: "core" (the
# library's cmocka programs), "ports" (ports/), "command" (tests/cli/: the shell tests of the
# command), "examples" (examples/) and "fuzz" (the fuzz regressions). A cmocka program is found
# by name (build/tests/test_x -> tests/*/test_x.c), a shell test by its path.
passed=0; failed=0; crashed=""; summary=""
SUITES="core ports command examples fuzz other"
for su in $SUITES; do eval "sp_$su=0; sf_$su=0; sn_$su=0"; done
suite_of() {
    if [ "$mode" = sh ]; then src=$1
    else src=$(ls tests/*/"$(basename "$1")".c 2>/dev/null | head -1); fi
    d=$(basename "$(dirname "${src:-unknown/x}")")
    case $d in
    core|ports|examples|fuzz) echo "$d";;
    cli) echo command;;
    *) echo other;;
    esac
}
tmp=${TMPDIR:-/tmp}/qorient-run.$$
trap 'rm -f "$tmp"' EXIT INT TERM
mode=bin
for t in "$@"; do
    if [ "$t" = "--" ]; then mode=sh; continue; fi
    if [ "$mode" = bin ]; then "$t" >"$tmp" 2>&1; rc=$?; else sh "$t" >"$tmp" 2>&1; rc=$?; fi
    cat "$tmp"
    if [ "$mode" = bin ]; then
        p=$(sed -n 's/^\[  PASSED  \] \([0-9]*\) test.*/\1/p' "$tmp" | tail -1)
        f=$(sed -n 's/^\[  FAILED  \] \([0-9]*\) test.*/\1/p' "$tmp" | tail -1)
    else
        p=$(sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed.*/\1/p' "$tmp" | tail -1)
        f=$(sed -n 's/^\([0-9]*\) passed, \([0-9]*\) failed.*/\2/p' "$tmp" | tail -1)
    fi
    p=${p:-0}; f=${f:-0}
    passed=$((passed + p)); failed=$((failed + f))
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        failed=$((failed + 1)); crashed="$crashed $t(rc=$rc)"; f="$f+crash"
    fi
    su=$(suite_of "$t")
    fn=${f%+crash}; [ "$f" = "$fn" ] || fn=$((fn + 1))
    eval "sp_$su=\$((sp_$su + p)); sf_$su=\$((sf_$su + fn)); sn_$su=\$((sn_$su + 1))"
    line=$(printf '%-28s %5s passed, %s failed' "$(basename "$t"):" "$p" "$f")
    echo "== $line"
    summary="$summary
  $line"
done
echo "== summary per program:$summary"
echo "== summary per suite:"
for su in $SUITES; do
    [ "$su" = other ] && eval "[ \$sn_other -eq 0 ]" && continue
    eval "n=\$sn_$su"
    [ "$n" -eq 1 ] && progs="1 program" || progs="$n programs"
    eval "printf '  %-27s %5s passed, %s failed (%s)\n' \"suite \$su:\" \$sp_$su \$sf_$su \"\$progs\""
done
[ -n "$crashed" ] && echo "crashed or exited non-zero without a report:$crashed"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
