# tests/common/sh/prelude.sh - sourced by the shell tests that start simulators (". tests/common/sh/prelude.sh"
# from the repository root, after setting T to the test's scratch folder): the pass/fail
# counters, the scratch folder, and a cleanup that stops the simulator in SIMPID on every exit.
pass=0; fail=0
mkdir -p "$T"
SIMPID=""
cleanup() { [ -n "$SIMPID" ] && kill "$SIMPID" 2>/dev/null; wait 2>/dev/null; rm -rf "$T"; }
trap cleanup EXIT INT TERM
ok()  { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
