#!/usr/bin/python3
"""Call counts in a callgrind profile of bapd: model calls and residual evaluations.

    callgrind_calls.py PROFILE
prints JSON: calls of PlaneStress<...>::solve (one per bond evaluation of the plane-
stress model), of cbrt (one per residual evaluation of the S33 = 0 solve), of
bond_forces_range (kernel calls) and their ratio, the mean residual evaluations per
bond in the run that was profiled.
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
    print(json.dumps({"model_calls": solve, "cbrt_calls": cbrt, "kernel_calls": kernel,
                      "residual_evaluations_per_bond": cbrt / solve if solve else None}))


if __name__ == "__main__":
    main()
