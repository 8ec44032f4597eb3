#!/bin/sh
# tools/figures.sh [--check] - every table of docs/FIGURES.md, regenerated from the code.
#
#   sh tools/figures.sh          (make figures)        rewrites every section in place
#   FIGURES_ONLY="sizes" sh tools/figures.sh                 only the sections named
#   sh tools/figures.sh --check  (make figures-check)  regenerates the deterministic sections and
#                                                      fails (exit 1, with a diff) when they differ
#                                                      from what is committed
#
# A section is one script, tools/figures/NAME.sh, that prints markdown on stdout; its output
# replaces the text between the lines <!-- figures:NAME begin --> and <!-- figures:NAME end -->
# of docs/FIGURES.md (a section without markers yet is appended under a "## NAME" heading).
# To add a section: write the script and add one line to SECTIONS below. Kind "check" = the
# output is deterministic (same code, same toolchain -> same text) and CI compares it; "live" =
# measured on the machine (timings: they carry their date and machine), never compared.
set -eu
cd "$(dirname "$0")/.."
SECTIONS="
accuracy check
ir check
sizes check
m0 check
motion-ir check
timing live
motion live
stream live
"
DOC=docs/FIGURES.md
BUILD=${BUILD:-build}
export BUILD
check=0
[ "${1:-}" = --check ] && check=1

# What the sections need beyond the CI base packages: installed when root, else named.
need="valgrind g++ libcglm-dev libeigen3-dev libfixmath-dev gcc-arm-none-eabi libnewlib-arm-none-eabi qemu-system-arm"
missing=""
for p in $need; do dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"; done
if [ -n "$missing" ]; then
    if [ "$(id -u)" = 0 ]; then
        echo "figures: installing:$missing" >&2
        DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends $missing >&2
    else
        echo "figures: missing packages:$missing (apt-get install them)" >&2; exit 2
    fi
fi

W=$BUILD/figures
mkdir -p "$W"
[ -f "$DOC" ] || printf '# qorient figures\n' > "$DOC"
cp "$DOC" "$W/FIGURES.md"
echo "$SECTIONS" | while read -r name kind; do
    [ -n "$name" ] || continue
    [ $check = 1 ] && [ "$kind" != check ] && continue
    # FIGURES_ONLY="sizes m0": only those sections (the others are kept as they are)
    [ -n "${FIGURES_ONLY:-}" ] && case " $FIGURES_ONLY " in *" $name "*) ;; *) continue;; esac
    echo "figures: $name" >&2
    sh "tools/figures/$name.sh" > "$W/$name.md"
    b="<!-- figures:$name begin -->"; e="<!-- figures:$name end -->"
    if ! grep -qF "$b" "$W/FIGURES.md"; then
        printf '\n## %s\n\n%s\n%s\n' "$name" "$b" "$e" >> "$W/FIGURES.md"
    fi
    awk -v b="$b" -v e="$e" -v f="$W/$name.md" '
        $0 == b { print; while ((getline l < f) > 0) print l; skip = 1; next }
        $0 == e { skip = 0 }
        !skip { print }' "$W/FIGURES.md" > "$W/FIGURES.new"
    mv "$W/FIGURES.new" "$W/FIGURES.md"
done
if [ $check = 1 ]; then
    if diff -u "$DOC" "$W/FIGURES.md"; then
        echo "figures-check: $DOC matches the code"
    else
        echo "figures-check: FAIL: $DOC differs from what the code measures (diff above); run make figures" >&2
        exit 1
    fi
else
    cp "$W/FIGURES.md" "$DOC"
    echo "figures: $DOC rewritten"
fi
