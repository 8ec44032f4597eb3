#!/usr/bin/env python3
"""Which durations can one joint take? An LP feasibility check, independent of lib/ and of
tests/common/motion_ref.c: piecewise-constant jerk on N equal steps of T/N, the state integrated
exactly, bounds on the jerk at every step and on v, a at every node, the end state fixed.
Solved by GLPK's glpsol (Debian: glpk-utils); not part of make test.

Used for qorient/motion.h's TIME-sync gap (make check-motion TIME_IF_NECESSARY case 5781,
joint 5: minimum 0.809 s, common duration 1.560 s):

    python3 tests/core/motion_gap_lp.py 0.81 0.85 0.87 1.0 1.56 2.0 2.02 2.5

prints one line per T: "feasible" or "infeasible". With N = 400 and the bounds widened by SLACK
(0.02 u/s, u/s^2: the grid's jerk switches fall between nodes), durations in about
[0.809, 0.861] and [2.019, inf) are feasible, and none in between: no profile of 1.560 s exists.
"""
import os
import subprocess
import sys
import tempfile

# vmax vmin amax amin jmax; p0 v0 a0; target p v a (float32 values of the oracle case)
VMAX, VMIN, AMAX, AMIN, J = 3.4372437, -3.4372437, 2.062994, -15.6111498, 20.7182293
P0, V0, A0 = -1.47362924, 2.52445889, -11.3011713
PF, VF, AF = -2.19661188, -3.04818821, -0.323818952
N = int(os.environ.get("N", "400"))
SLACK = float(os.environ.get("SLACK", "0.02"))


def model(T):
    h = T / N
    return "\n".join([
        "param N := %d;" % N,
        "var u{k in 0..N-1} >= %r, <= %r;" % (-J, J),
        # the start's own acceleration may lie beyond the bounds it is brought back into
        "var a{k in 0..N} >= %r, <= %r;" % (min(AMIN, A0) - SLACK, max(AMAX, A0) + SLACK),
        "var v{k in 0..N} >= %r, <= %r;" % (VMIN - SLACK, VMAX + SLACK),
        "var p{k in 0..N};",
        "minimize obj: sum{k in 0..N-1} 0*u[k];",
        "s.t. a0c: a[0] = %r;" % A0,
        "s.t. v0c: v[0] = %r;" % V0,
        "s.t. p0c: p[0] = %r;" % P0,
        "s.t. ar{k in 0..N-1}: a[k+1] = a[k] + %r*u[k];" % h,
        "s.t. vr{k in 0..N-1}: v[k+1] = v[k] + %r*a[k] + %r*u[k];" % (h, h * h / 2),
        "s.t. pr{k in 0..N-1}: p[k+1] = p[k] + %r*v[k] + %r*a[k] + %r*u[k];" % (h, h * h / 2, h ** 3 / 6),
        "s.t. pe: p[N] = %r;" % PF,
        "s.t. ve: v[N] = %r;" % VF,
        "s.t. ae: a[N] = %r;" % AF,
        "solve;",
        'printf "LP_RESULT_FEASIBLE\\n";',
        "end;",
    ])


def feasible(T):
    with tempfile.NamedTemporaryFile("w", suffix=".mod", delete=False) as f:
        f.write(model(T) + "\n")
        name = f.name
    try:
        out = subprocess.run(["glpsol", "--math", name], capture_output=True, text=True).stdout
    finally:
        os.unlink(name)
    if "LP_RESULT_FEASIBLE" in out:
        return True
    if "NO PRIMAL FEASIBLE" in out:
        return False
    raise SystemExit("glpsol gave no answer for T = %g:\n%s" % (T, out))


if __name__ == "__main__":
    for arg in sys.argv[1:]:
        T = float(arg)
        print("T %g: %s" % (T, "feasible" if feasible(T) else "infeasible"))
