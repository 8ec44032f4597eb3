#!/bin/sh
# tools/parity.sh [--check] - docs/PARITY.md, the concept x core table of the public API,
# generated from the "parity" index blocks at the top of the public headers.
#
#   sh tools/parity.sh           (make parity, also run by make figures)  rewrites docs/PARITY.md
#   sh tools/parity.sh --check   (make parity-check, CI)  fails when docs/PARITY.md differs from
#                                 the headers, or when the headers' blocks are inconsistent
#
# A block is a comment that starts with "/* parity CORE" (CORE: float32 or fixed) and ends at
# "*/"; each line inside is " *   CONCEPT FUNCTION [note]" or " *   CONCEPT - reason": the
# function of that core for the concept, or "-" and why the core has none. The script fails
# (exit 1, with the reason) when:
#   - a concept has an entry for one core and none for the other: a missing twin must be a
#     written decision ("-" and a reason), never an accident;
#   - a named function is not declared in the public headers (the table cannot name a
#     function that does not exist);
#   - a family (the concept before the dot) is declared in more than one header pair, or in a
#     header not named after it (mat3 lives in convert.h);
#   - a function declared in a header that has a block is in no block (a new function must
#     say which concept it is; names with _internal_ are not API and are exempt);
#   - a public name (function, type, tag or object, qo_<family>_...) is declared outside its
#     family's header pair: the name says the header (FAMILIES below; the value types of
#     types.h excepted), and every QO_ macro and enum constant starts with its header's family
#     (QO_<FAMILY>_..., the shared constants' homes named below). The ports' headers too
#     (PORT_FAMILIES: a port header's family is its file name). Names are read by
#     tools/public_names.py, a small C parser, not by grep.
set -eu
export LC_ALL=C
cd "$(dirname "$0")/.."
DOC=docs/PARITY.md
H=lib/include/qorient
W=${TMPDIR:-/tmp}/qo-parity.$$
trap 'rm -f "$W".*' EXIT INT TERM

# entries: CORE<TAB>CONCEPT<TAB>FUNCTION<TAB>NOTE<TAB>HEADER
for f in "$H"/*.h; do
    awk -v hdr="$(basename "$f")" '
        /^\/\* parity (float32|fixed)/ { core = $3; sub(/[^a-z0-9]+$/, "", core); inb = 1; next }
        inb && /\*\// { inb = 0; next }
        inb {
            line = $0; sub(/^ \*[ \t]+/, "", line)
            if (line == "") next
            n = split(line, w, /[ \t]+/)
            note = ""
            for (i = 3; i <= n; i++) note = note (i > 3 ? " " : "") w[i]
            printf "%s\t%s\t%s\t%s\t%s\n", core, w[1], w[2], note, hdr
        }' "$f"
done > "$W.entries"

fail=0
err() { echo "parity: $*" >&2; fail=1; }

# every name the public headers declare at file scope (tools/public_names.py: a small C
# parser, so continuation lines, typedef lists, function-pointer types, objects, enum
# constants and macros are all seen): FILE<TAB>NAME<TAB>KIND
PORT_HDRS=$(ls ports/*.h ports/*/*.h)
python3 tools/public_names.py "$H"/*.h $PORT_HDRS > "$W.all" || { echo "parity: cannot parse the headers" >&2; exit 1; }
awk -F '\t' -v h="$H/" 'index($1, h) == 1 && $3 == "func" { f = substr($1, length(h) + 1); print f "\t" $2 }' \
    "$W.all" | sort -u > "$W.decl"

# every named function is declared somewhere
cut -f3 "$W.entries" | grep -v '^-$' | sort -u | while read -r fn; do
    cut -f2 "$W.decl" | grep -qx "$fn" || echo "$fn"
done > "$W.missing"
while read -r fn; do err "$fn is in a parity block but declared in no public header"; done < "$W.missing"

# every function of a header with a block is in some block
cut -f5 "$W.entries" | sort -u > "$W.hdrs"
while IFS="$(printf '\t')" read -r hdr fn; do
    grep -qx "$hdr" "$W.hdrs" || continue
    case $fn in *_internal_*) continue;; esac   # named internal: not API (quat.h's SIMD helpers)
    cut -f3 "$W.entries" | grep -qx "$fn" || err "$fn ($hdr) is in no parity block: add it with its concept"
done < "$W.decl"

# every concept has an entry (a function or a stated "-") for both cores
cut -f2 "$W.entries" | sort -u > "$W.concepts"
while read -r c; do
    for core in float32 fixed; do
        awk -F '\t' -v c="$c" -v k="$core" '$1 == k && $2 == c { f = 1 } END { exit !f }' "$W.entries" ||
            err "concept $c has no $core entry: name the function, or write \"$c - reason\" in a $core block"
    done
done < "$W.concepts"

# one home per family: a family's functions are declared in one header and its twin (F.h and
# F_fx.h); the family is named after its header, except mat3, whose home is convert.h (the
# rotation-matrix conversions and the matrix helpers they need are one family of headers)
awk -F '\t' '{ fam = $2; sub(/\..*/, "", fam); h = $5; sub(/(_fx)?\.h$/, "", h); print fam "\t" h }' \
    "$W.entries" | sort -u > "$W.homes"
cut -f1 "$W.homes" | uniq -d | while read -r fam; do
    echo "family $fam is declared in more than one header pair: $(awk -F '\t' -v f="$fam" '$1 == f { printf "%s.h ", $2 }' "$W.homes")"
done > "$W.split"
while read -r line; do err "$line"; done < "$W.split"
while IFS="$(printf '\t')" read -r fam h; do
    [ "$fam" = "$h" ] || { [ "$fam" = mat3 ] && [ "$h" = convert ]; } ||
        err "family $fam lives in $h.h: a family's home is the header named after it (mat3: convert.h)"
done < "$W.homes"

# every public name in the header of its family: qo_<family>_... is declared in <home>.h or
# <home>_fx.h. One line per home: the header, then the families (name prefixes) it holds.
# A name belongs to the longest family it starts with (qo_euler_seq_parse: euler_seq).
FAMILIES='quat quat
convert convert mat3 axis_angle rotvec
euler euler
euler_seq euler_seq
interp interp
gimbal gimbal
spline spline
motion motion
traj traj
fmath fm
fxmath fx
fxconv q16 q28 q30 fxconv
sink sink
status status'
# The ports' headers (installed under qorient/ports/) follow the same rule with no exception:
# a port header's family is its file name, so qo_modbus_link_tcp_take is in modbus_link.h and
# a sub-family reads as a word after it (_tcp_, _backoff_, _jitter_hist_, _libgpiod_). Here
# the ports' macros and enum constants follow it too: QO_<FAMILY>_... (QO_MODBUS_REG_INT16).
PORT_FAMILIES='ports/sink_view sink_view
ports/mock/mock_sink mock_sink
ports/linux/gpio_sink gpio_sink
ports/linux/joint_guard joint_guard
ports/linux/modbus_layout modbus_layout
ports/linux/modbus_link modbus_link
ports/linux/modbus_reg modbus_reg
ports/linux/modbus_sink modbus_sink
ports/linux/mono_clock mono_clock
ports/linux/regmap regmap
ports/linux/sim sim
ports/linux/streamer streamer
ports/linux/wire_budget wire_budget'
homes=$(printf '%s\n' "$FAMILIES" | sed "s|^|$H/|"; printf '%s\n' "$PORT_FAMILIES")

# every lower-case name (function, type, tag, object) in the header of its family, and every
# macro and enum constant QO_<FAMILY>_... of its header's family (include guards QORIENT_..._H
# aside). The core's shared constants have fixed homes: the status codes (QO_OK, QO_E_...) in
# status.h, the fixed-point formats' constants (QO_Q30_ONE, QO_Q28_PI) in types.h, the Euler
# sequences (QO_EULER_XYZ) in euler_seq.h, which the euler family shares.
awk -F '\t' -v homes="$homes" -v core="$H/" '
    BEGIN {
        n = split(homes, lines, "\n")
        for (i = 1; i <= n; i++) {
            k = split(lines[i], w, " ")
            for (j = 2; j <= k; j++) { home[w[j]] = w[1]; fams[w[1]] = fams[w[1]] " " toupper(w[j]) }
        }
        fams[core "types"] = " Q16 Q28 Q30"; fams[core "version"] = " VERSION"
        fams[core "status"] = fams[core "status"] " E"; fams[core "euler_seq"] = fams[core "euler_seq"] " EULER"
    }
    { h = $1; sub(/(_fx)?\.h$/, "", h) }
    $3 == "macro" || $3 == "enum" {
        if ($2 ~ /^QORIENT_[A-Z0-9_]*_H$/ || $2 == "QO_OK" && $1 == core "status.h") next
        ok = 0; k = split(fams[h], fs, " ")
        for (j = 1; j <= k; j++) if (index($2, "QO_" fs[j] "_") == 1) ok = 1
        if (!ok) print $2 " (" $1 "): a macro or enum constant starts with its header family, QO_" (k ? fs[1] : "?") "_"
        next
    }
    $1 == core "types.h" { next }
    {
        if ($2 !~ /^qo_/) { print $2 " (" $1 "): a public name starts with qo_"; next }
        name = substr($2, 4); best = ""
        for (fam in home) if ((name == fam || index(name, fam "_") == 1) && length(fam) > length(best)) best = fam
        if (best == "") print $2 " (" $1 "): no family: add its prefix to FAMILIES (core) or PORT_FAMILIES in tools/parity.sh"
        else if (home[best] != h) print $2 " is declared in " $1 ": family " best " lives in " home[best] ".h"
    }' "$W.all" > "$W.names"
while read -r line; do err "$line"; done < "$W.names"

[ $fail = 0 ] || { echo "parity: FAIL (the blocks are at the top of $H/*.h, the families in tools/parity.sh)" >&2; exit 1; }

# the table
{
    echo "# Parity: float32 and fixed point"
    echo
    echo "Generated by \`sh tools/parity.sh\` (\`make parity\`, also run by \`make figures\`) from the"
    echo "\"parity\" blocks at the top of the public headers; CI runs \`make parity-check\`. One row per"
    echo "concept; a cell names the function of that core, or says (—) why the core has none: a"
    echo "missing twin is a decision written in the header, and the script fails on a concept that"
    echo "one core has and the other does not mention. The kernels (fmath.h, fxmath.h) and the"
    echo "float/fixed conversions (fxconv.h) are one core's tools by design and have no row."
    echo
    awk -F '\t' '
        { fam = $2; sub(/\..*/, "", fam) }
        !(fam in seen) { seen[fam] = 1; order[++nf] = fam }
        {
            cell = ($3 == "-") ? "— " $4 : "`" $3 "`" ($4 != "" ? " " $4 : "")
            key = $1 SUBSEP $2
            if (key in v) cell = v[key] "<br>" cell
            v[key] = cell
            if (!(($2) in cseen)) { cseen[$2] = 1; cons[fam] = cons[fam] " " $2 }
            if ($3 == "-") gaps[$1]++
            else fns[$1]++
        }
        END {
            for (i = 1; i <= nf; i++) {
                fam = order[i]
                printf "## %s\n\n| concept | float32 | fixed point |\n|---|---|---|\n", fam
                n = split(substr(cons[fam], 2), cl, " ")
                for (j = 1; j <= n; j++)
                    printf "| %s | %s | %s |\n", cl[j], v["float32" SUBSEP cl[j]], v["fixed" SUBSEP cl[j]]
                printf "\n"
            }
            printf "Totals: float32 %d functions, %d stated gaps; fixed point %d functions, %d stated gaps.\n",
                fns["float32"], gaps["float32"], fns["fixed"], gaps["fixed"]
        }' "$W.entries"
} > "$W.md"

if [ "${1:-}" = --check ]; then
    if diff -u "$DOC" "$W.md"; then
        echo "parity-check: $DOC matches the headers"
    else
        echo "parity-check: FAIL: $DOC differs from the headers' parity blocks (diff above); run make parity" >&2
        exit 1
    fi
else
    cp "$W.md" "$DOC"
    echo "parity: $DOC rewritten"
fi
