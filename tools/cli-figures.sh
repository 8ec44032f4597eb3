#!/bin/sh
# tools/cli-figures.sh - the `qorient` command's size and its number parsers, now and at a
# given commit (default 9bf587d, the command before issue 12, when it lived in ports/linux/cli).
#
#   sh tools/cli-figures.sh [REV]
#
# Prints, for REV and for the working tree:
#   lines      wc -l of the command's C sources and headers (not the man page)
#   list parsers   functions that parse a number list given as an option value
#                  ("static ... parse_list(" then, qo_cli_list now)
#   scalar parsers strtod() call sites that parse an option value (the input-line parser
#                  qo_cli_parse_numbers in util.c is counted apart: it is the one line parser)
set -eu
cd "$(dirname "$0")/.."
REV=${1:-9bf587d}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT INT TERM
git archive "$REV" | tar -x -C "$T"
if [ -d "$T/cli" ]; then OLD="$T/cli"; else OLD="$T/ports/linux/cli"; fi

figures() { # label, directory
    d=$2
    files=$(find "$d" -name '*.[ch]' | sort)
    lines=$(cat $files | wc -l)
    lists=$(cat $(echo "$files" | grep '\.c$') | grep -cE '^(static )?[a-z].*[ *](parse_list|qo_cli_list)\(' || true)
    scalars=$(for f in $files; do case $f in */util.c) ;; *) grep -c 'strtod(' "$f" || true ;; esac; done |
              awk '{ s += $1 } END { print s + 0 }')
    utils=$(grep -c 'strtod(' "$d/util.c" || true)
    printf '%-12s lines %5d   list parsers %d   scalar option parsers %d (+ %d strtod in util.c)\n' \
        "$1" "$lines" "$lists" "$scalars" "$utils"
}
figures "$REV" "$OLD"
figures "now" cli
