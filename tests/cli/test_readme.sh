#!/bin/sh
# tests/cli/test_readme.sh - every README example that shows its output prints exactly that.
#
# In README.md's ```sh blocks, a line "$ COMMAND" is run (with sh, from the repository root, the
# command's build/qorient replaced by $QORIENT when set) and the lines after it, up to the next
# "$ " line, a blank line or the end of the block, are its expected standard output, byte for
# byte. Blocks without "$ " lines are listed commands, not checked here. The running and the
# comparing are tests/cli/examples.sh's, shared with the man page's examples (test_manpage.sh).
# Prints one line per example and "N passed, M failed".
cd "$(dirname "$0")/../.." || exit 2
Q=${QORIENT:-build/qorient}
T=${TMPDIR:-/tmp}/qo-readme.$$
. tests/common/sh/prelude.sh
. tests/cli/examples.sh
[ -x "${Q%% *}" ] || command -v "${Q%% *}" >/dev/null 2>&1 || { echo "test_readme: $Q not built"; echo "0 passed, 1 failed"; exit 1; }

# Split README into numbered examples: $T/readme/N.cmd and $T/readme/N.want.
mkdir -p "$T/readme"
awk -v dir="$T/readme" '
    /^```sh[ ]*$/ { inblk = 1; cur = ""; next }
    /^```/ { inblk = 0; cur = ""; next }
    !inblk { next }
    /^\$ / { n++; cur = dir "/" n; c = substr($0, 3); printf "%s\n", c > (cur ".cmd");
             printf "" > (cur ".want"); close(cur ".cmd"); next }
    /^[ \t]*$/ { cur = ""; next }
    cur != "" { printf "%s\n", $0 >> (cur ".want") }
    END { printf "%d\n", n > (dir "/count") }
' README.md
examples_run README "$T/readme" check
[ "$(cat "$T/readme/count")" -gt 0 ] || bad "test_readme: no examples with output found in README.md"
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
