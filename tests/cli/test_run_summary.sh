#!/bin/sh
# tests/run.sh's totals, on stand-in shell tests: per program, per suite ("1 program",
# "2 programs"), the last line and the exit status; a test that exits non-zero without a
# report counts as one failure. Prints "N passed, M failed".
T=${TMPDIR:-/tmp}/qo-run-summary.$$
. tests/common/sh/prelude.sh
mkdir -p "$T/cli" "$T/core"
printf 'echo "3 passed, 0 failed"\n' > "$T/cli/a.sh"
printf 'echo "2 passed, 0 failed"\n' > "$T/cli/b.sh"
printf 'echo "4 passed, 0 failed"\n' > "$T/core/c.sh"
printf 'exit 3\n' > "$T/core/d.sh"

sh tests/run.sh -- "$T/cli/a.sh" "$T/cli/b.sh" "$T/core/c.sh" > "$T/out" 2>&1; rc=$?
[ "$rc" = 0 ] && ok || bad "all passed: exit $rc"
grep -q '^  suite command: *5 passed, 0 failed (2 programs)$' "$T/out" && ok || bad "2 programs: $(grep suite "$T/out")"
grep -q '^  suite core: *4 passed, 0 failed (1 program)$' "$T/out" && ok || bad "1 program: $(grep suite "$T/out")"
grep -q '^  suite ports: *0 passed, 0 failed (0 programs)$' "$T/out" && ok || bad "0 programs: $(grep suite "$T/out")"
[ "$(tail -1 "$T/out")" = "9 passed, 0 failed" ] && ok || bad "total: $(tail -1 "$T/out")"

sh tests/run.sh -- "$T/cli/a.sh" "$T/core/d.sh" > "$T/out" 2>&1; rc=$?
[ "$rc" = 1 ] && ok || bad "a crash: exit $rc"
grep -q '^  suite core: *0 passed, 1 failed (1 program)$' "$T/out" && ok || bad "a crash counted: $(grep suite "$T/out")"
[ "$(tail -1 "$T/out")" = "3 passed, 1 failed" ] && ok || bad "total with a crash: $(tail -1 "$T/out")"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
