#!/usr/bin/env python3
"""Checks the short notched pure-shear run (notched_short.sh): the crack started near
the stretch and stress of the full scene, ran straight along the notch line through
the whole width, symmetric about it, while the step was shortened.

    check_notched.py RUN_DIR LOG

RUN_DIR holds history.csv, final_state.csv and broken_bonds.csv (-output_final_state).
Bonds are rebuilt from the reference positions by the solver's rule (|x_j - x_i| <=
delta, none across the notch), so the checks see every bond, broken or not.
"""
import csv
import re
import sys

import numpy as np

DX, DELTA = 0.5e-3, 3.015 * 0.5e-3
NOTCH_Y, NOTCH_X0 = 0.005, 0.025           # the notch runs from x0 to the right edge
# Where the crack may start and how high the stress may go. With the defaults (grips
# outside the 10 mm free sheet, two horizons deep, affine field) this grid
# measures a start (20 broken bonds) at stretch 2.827 and a peak of 9.90 kPa, the same
# on 1 and 2 ranks (three rigid rows inside, -load_grip_placement inside, with the
# stretch over the 8 mm between them, gave 3.22 and 11.3 kPa). The full scene on the
# paper's grid has not been run with these grips. The bounds are this run's figures
# +-10 %: a crack that starts early (spurious breaking, e.g. at the grips) or late fails.
START_STRETCH = (2.55, 3.1)                 # the stretch with 20 broken bonds
PEAK_STRESS = (8.9e3, 10.9e3)               # Pa


def main():
    run, log = sys.argv[1], sys.argv[2]
    failures = []
    rows = list(csv.DictReader(open(f"{run}/history.csv")))
    stretch = np.array([float(r["stretch"]) for r in rows])
    stress = np.array([float(r["top_nominal_stress_Pa"]) for r in rows])
    broken = np.array([int(r["broken_bonds"]) for r in rows])
    start = stretch[np.argmax(broken >= 20)] if (broken >= 20).any() else float("nan")
    peak = stress.max()
    print(f"crack starts (20 broken bonds) at stretch {start:.3f}, peak nominal stress {peak:.0f} Pa at {stretch[stress.argmax()]:.3f}")
    if not START_STRETCH[0] <= start <= START_STRETCH[1]:
        failures.append(f"the crack started at stretch {start:.3f}, outside {START_STRETCH}")
    if not PEAK_STRESS[0] <= peak <= PEAK_STRESS[1]:
        failures.append(f"peak nominal stress {peak:.0f} Pa outside {PEAK_STRESS}")
    if not stress[-1] < 0.2 * peak:
        failures.append(f"the sheet still carries {stress[-1]:.0f} Pa at the end ({stress[-1] / peak:.2f} of the peak): not torn through")

    state = np.loadtxt(f"{run}/final_state.csv", delimiter=",", skiprows=1)
    ids, x = state[:, 0].astype(int), state[:, 1:3]
    index = {k: n for n, k in enumerate(ids)}
    pairs = np.loadtxt(f"{run}/broken_bonds.csv", delimiter=",", skiprows=1, dtype=int, ndmin=2)
    broken_set = {(index[i], index[j]) for i, j in pairs}
    # Every bond of the lattice crossing the notch line to the left of the notch.
    crossing = []
    for i in range(len(x)):
        d = x - x[i]
        for j in np.nonzero((np.hypot(d[:, 0], d[:, 1]) <= DELTA * (1 + 1e-9)) & (x[:, 1] > x[i, 1]))[0]:
            if (x[i, 1] - NOTCH_Y) * (x[j, 1] - NOTCH_Y) < 0:
                xc = x[i, 0] + (NOTCH_Y - x[i, 1]) / (x[j, 1] - x[i, 1]) * (x[j, 0] - x[i, 0])
                if xc < NOTCH_X0:
                    crossing.append((i, j))
    intact = [(i, j) for i, j in crossing if (i, j) not in broken_set and (j, i) not in broken_set]
    print(f"{len(crossing)} bonds cross the notch line left of the notch, {len(intact)} of them intact")
    if intact:
        failures.append(f"{len(intact)} bonds across the crack line are intact: the crack did not run through the width")
    off_line = [(i, j) for i, j in broken_set if max(abs(x[i, 1] - NOTCH_Y), abs(x[j, 1] - NOTCH_Y)) > 2 * DELTA]
    print(f"{len(broken_set)} broken (directed) bonds, {len(off_line)} with an end more than 2 horizons from the notch line")
    if off_line:
        failures.append(f"{len(off_line)} broken bonds lie away from the notch line (e.g. at y = {x[off_line[0][0], 1]:.4f} m)")
    # Symmetry: broken bonds per row, mirrored about the notch line.
    per_row = {}
    for i, _ in broken_set:
        key = round((x[i, 1] - NOTCH_Y) / DX * 2)
        per_row[key] = per_row.get(key, 0) + 1
    for key in sorted(k for k in per_row if k > 0):
        a, b = per_row.get(key, 0), per_row.get(-key, 0)
        print(f"  row {key * DX / 2 * 1e3:+.2f} mm: {a} broken, mirror row: {b}")
        if abs(a - b) > 0.15 * max(a, b) + 3:
            failures.append(f"rows +-{key * DX / 2 * 1e3:.2f} mm from the notch line: {a} and {b} broken bonds: not symmetric")

    text = open(log).read()
    # The summary: "time step: N of M step(s) shorter than the full ...: K by stiffness
    # ..., T by the travel limit (...)": the travel limit (chosen by the solver with
    # failure) must have acted while the crack ran.
    m = re.search(r"(\d+) by the travel limit", text)
    print(f"steps shortened by the travel limit: {m.group(1) if m else 0}")
    if not m or int(m.group(1)) == 0:
        failures.append("no step was shortened by the travel limit: the crack ran without it acting")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
