#!/bin/sh
# tests/cli/test_readme.sh - every README example that shows its output prints exactly that.
#
# In README.md's ```sh blocks, a line "$ COMMAND" is run (with sh, from the repository root, the
# command's build/qorient replaced by $QORIENT when set) and the lines after it, up to the next
# "$ " line, a blank line or the end of the block, are its expected standard output, byte for
# byte. Blocks without "$ " lines are listed commands, not checked here. Prints one line per
# example and "N passed, M failed".
set -u
cd "$(dirname "$0")/../.." || exit 2
Q=${QORIENT:-build/qorient}
[ -x "${Q%% *}" ] || command -v "${Q%% *}" >/dev/null 2>&1 || { echo "test_readme: $Q not built"; echo "0 passed, 1 failed"; exit 1; }
tmp=${TMPDIR:-/tmp}/qo-readme.$$
mkdir -p "$tmp" || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM

# Split README into numbered examples: $tmp/N.cmd and $tmp/N.want.
awk -v dir="$tmp" '
    /^```sh[ ]*$/ { inblk = 1; cur = ""; next }
    /^```/ { inblk = 0; cur = ""; next }
    !inblk { next }
    /^\$ / { n++; cur = dir "/" n; c = substr($0, 3); printf "%s\n", c > (cur ".cmd");
             printf "" > (cur ".want"); close(cur ".cmd"); next }
    /^[ \t]*$/ { cur = ""; next }
    cur != "" { printf "%s\n", $0 >> (cur ".want") }
    END { printf "%d\n", n > (dir "/count") }
' README.md
n=$(cat "$tmp/count")
passed=0; failed=0
i=1
while [ "$i" -le "$n" ]; do
    cmd=$(cat "$tmp/$i.cmd")
    # A trailing "# comment" is part of the shell line and harmless; the command itself is run
    # as the README shows it, with the path of the built command substituted.
    run=$(printf '%s\n' "$cmd" | sed "s#build/qorient#$Q#g")
    sh -c "$run" >"$tmp/$i.got" 2>"$tmp/$i.err"
    if cmp -s "$tmp/$i.want" "$tmp/$i.got"; then
        passed=$((passed + 1)); echo "ok    README example $i: $cmd"
    else
        failed=$((failed + 1)); echo "FAIL  README example $i: $cmd"
        diff "$tmp/$i.want" "$tmp/$i.got" | sed 's/^/      /'
        sed 's/^/      stderr: /' "$tmp/$i.err"
    fi
    i=$((i + 1))
done
[ "$n" -gt 0 ] || { echo "test_readme: no examples with output found in README.md"; failed=$((failed + 1)); }
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
