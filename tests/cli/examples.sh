# tests/cli/examples.sh - sourced by test_readme.sh (README.md) and test_manpage.sh (cli/qorient.1):
# runs the examples a document shows with their output and compares the output byte for byte.
# The caller sets Q (the command), T (a scratch folder) and ok/bad (tests/common/sh/prelude.sh),
# and extracts the examples into a folder D: D/count, and for N = 1..count D/N.cmd (the command
# as shown: "$ " removed, continuation lines kept) and D/N.want (the lines shown after it).
#
# examples_run LABEL D EMPTY: runs each D/N.cmd with sh from the repository root, `qorient` and
# `build/qorient` being $Q (a wrapper first in PATH), and compares its standard output with
# D/N.want. EMPTY=check: an example shown with no output must print nothing; EMPTY=skip: it is
# not run (a command shown without its output, such as a server started in the background).
# Prints "ok" or "FAIL" per example, the difference and standard error of a failure.
examples_run() {
    label=$1 dir=$2 empty=$3
    mkdir -p "$T/bin"
    printf '#!/bin/sh\nexec %s "$@"\n' "$Q" > "$T/bin/qorient"
    chmod +x "$T/bin/qorient"
    n=$(cat "$dir/count")
    i=1
    while [ "$i" -le "$n" ]; do
        cmd=$(cat "$dir/$i.cmd")
        if [ "$empty" = skip ] && [ ! -s "$dir/$i.want" ]; then i=$((i + 1)); continue; fi
        run=$(printf '%s\n' "$cmd" | sed 's#build/qorient#qorient#g')
        PATH="$T/bin:$PATH" sh -c "$run" >"$dir/$i.got" 2>"$dir/$i.err"
        if cmp -s "$dir/$i.want" "$dir/$i.got"; then
            ok; echo "ok    $label example $i: $cmd"
        else
            bad "$label example $i: $cmd"
            diff "$dir/$i.want" "$dir/$i.got" | sed 's/^/      /'
            sed 's/^/      stderr: /' "$dir/$i.err"
        fi
        i=$((i + 1))
    done
}
