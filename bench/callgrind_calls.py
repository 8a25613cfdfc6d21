#!/usr/bin/python3
"""Call counts in a callgrind profile of bapd: model calls and residual evaluations.

    callgrind_calls.py PROFILE
prints JSON: calls of PlaneStress<...>::solve, of cbrt, of bond_forces_range (kernel
calls) and of model_lane_fallback (bonds that the four-bond PlaneStress::stress_lanes
did not finish in its one evaluation, handed to the scalar solve).

Up to commit ea828f1 the kernel called solve once per bond and every residual
evaluation called cbrt once: residual_evaluations_per_bond = cbrt / solve.
Since then the kernel evaluates every bond once in stress_lanes (no cbrt, no solve
call) and only lane_fallback_calls bonds go on to the scalar solve (which evaluates
its start again, then one or more further points); the residual evaluations per bond
are 1 + (evaluations of those solves) / bonds, the bond count being the old binary's
solve calls for the same run or kernel_calls times the bonds evaluated per call.
"""
import json
import re
import sys
from collections import Counter


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    names, calls = {}, Counter()
    callee = None
    for line in open(sys.argv[1]):
        m = re.match(r"^(c?fn)=\((\d+)\)\s*(.*)$", line)
        if m:
            kind, ident, name = m.groups()
            if name:
                names[ident] = name
            if kind == "cfn":
                callee = names.get(ident, ident)
            continue
        m = re.match(r"^calls=(\d+)", line)
        if m and callee:
            calls[callee] += int(m.group(1))
    def total(pattern):
        return sum(v for k, v in calls.items() if re.search(pattern, k))
    solve = total(r"PlaneStress<.*>::solve")
    cbrt = total(r"^(__)?cbrt$")
    kernel = total(r"bond_forces_range")
    fallback = total(r"model_lane_fallback")
    print(json.dumps({"model_calls": solve, "cbrt_calls": cbrt, "kernel_calls": kernel,
                      "lane_fallback_calls": fallback,
                      "residual_evaluations_per_bond": cbrt / solve if solve and not fallback else None}))


if __name__ == "__main__":
    main()
