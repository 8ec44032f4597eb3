#!/bin/sh
# The manual page cli/qorient.1 against the command: its version, every subcommand
# has its section, every option any --help text shows is documented in the page, every
# EXAMPLES entry that shows its output prints exactly that (as README's, tests/cli/examples.sh),
# and the page formats without a warning (groff -ww, when groff is installed; mandoc -T lint
# when mandoc is).
Q=${QORIENT:-build/qorient}
MAN=cli/qorient.1
T=${TMPDIR:-/tmp}/qo-manpage.$$
. tests/common/sh/prelude.sh
. tests/cli/examples.sh

# The page's text with roff's escaped hyphens made plain, so '\-\-rate' reads '--rate'.
sed 's/\\-/-/g' "$MAN" > "$T/man.txt"

cmds=$($Q --help | awk '/^commands:/ { on = 1; next } on && /^  [a-z]/ { print $1 } on && /^$/ { on = 0 }')
[ -n "$cmds" ] && ok || bad "no command list in '$Q --help'"
for c in $cmds; do
    grep -q "^\.SS \"qorient $c" "$T/man.txt" && ok || bad "no section '.SS \"qorient $c ...' for the command $c"
    [ "$c" = version ] && continue
    $Q "$c" --help > "$T/help" 2>&1 || { bad "$Q $c --help exits non-zero"; continue; }
    [ "$c" = plan ] && $Q plan --profile scurve --help >> "$T/help" 2>&1
    for o in $(grep -oE -- '--[a-z][a-z0-9-]*' "$T/help" | sort -u); do
        grep -q -- "$o\b" "$T/man.txt" && ok || bad "qorient $c: option $o of --help is not in $MAN"
    done
done

# the page's title line names the command's version
v=$($Q version | sed -n 's/^qorient //p')
grep -q "^\.TH QORIENT 1 .* \"qorient $v\"" "$MAN" && ok || bad "the .TH line does not say \"qorient $v\""

# a paragraph request glued to the end of a text line is printed as text (".TP" in the
# middle of the readbacks entry); groff does not warn about it
g=$(grep -nE '[^[:space:]]\.(TP|PP|IP|SH|SS)$' "$MAN")
[ -z "$g" ] && ok || bad "a request at the end of a text line: $g"

if command -v groff >/dev/null 2>&1; then
    w=$(groff -man -Tutf8 -ww -z "$MAN" 2>&1)
    [ -z "$w" ] && ok || bad "groff -man -ww: $w"
fi
if command -v mandoc >/dev/null 2>&1; then
    w=$(mandoc -T lint -W warning "$MAN" 2>&1)
    [ -z "$w" ] && ok || bad "mandoc -T lint: $w"
fi

# The examples: in each .EX/.EE block a line "$ COMMAND" (continued while it ends in a
# backslash) and the lines after it, up to the next "$ " line or .EE, its output; roff's
# \(aq, \- and \e read as ', - and \. An example shown without output is not run (it starts
# a server, or needs a serial port).
mkdir -p "$T/man"
awk -v dir="$T/man" '
    /^\.EX/ { inblk = 1; cur = ""; cont = 0; next }
    /^\.EE/ { inblk = 0; cur = ""; next }
    !inblk { next }
    { l = $0; gsub(/\\\(aq/, "\047", l); gsub(/\\-/, "-", l); gsub(/\\e/, "\\", l) }
    cont { printf "%s\n", l >> (cur ".cmd"); cont = l ~ /\\$/; next }
    l ~ /^\$ / { n++; cur = dir "/" n; printf "%s\n", substr(l, 3) > (cur ".cmd"); printf "" > (cur ".want");
                 cont = l ~ /\\$/; next }
    cur != "" { printf "%s\n", l >> (cur ".want") }
    END { printf "%d\n", n > (dir "/count") }
' "$MAN"
examples_run "man page" "$T/man" skip
shown=$(for f in "$T"/man/*.want; do [ -s "$f" ] && echo "$f"; done | wc -l)
[ "$shown" -ge 2 ] && ok || bad "$MAN: $shown EXAMPLES entries with their output found, expected at least 2"

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
