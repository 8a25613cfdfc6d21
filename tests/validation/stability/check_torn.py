#!/usr/bin/env python3
"""Checks a torn-sheet run (torn_sheet.sh): the sheet is in two pieces and they moved
apart, without NaN.

    check_torn.py RUN_DIR --dx DX --horizon-factor H --critical-stretch S --notches X0,Y0,X1,Y1,... --opening M

RUN_DIR holds history.csv, final_state.csv and broken_bonds.csv (-output_final_state).
The bonds are rebuilt from the reference positions by the solver's rule (|x_j - x_i| <=
delta, none across a notch); with the broken ones removed, no chain of intact bonds
may join a point of the top row to a point of the bottom row. The probes 'above' and
'below' (either side of the crack path) must end more than M metres apart in y, and
at least --min-isolated points must have no intact bond left (and still be finite).

A bond that passes exactly through a notch end point is kept by the solver's rule
(family.hpp), but whether its orientation test gives exactly 0 depends on how the
compiler rounds it (fused multiply-add): such bonds may or may not exist. They count as
intact here only while they are not stretched past S (an existing one would have
broken); every other intact bond stretched past S is an error of the solver.
"""
import argparse
import csv
import math
import sys
from collections import deque


def side(o, s, t):
    v = (s[0] - o[0]) * (t[1] - o[1]) - (s[1] - o[1]) * (t[0] - o[0])
    return (v > 0) - (v < 0)


def crosses(p, q, notches):
    """Segment pq properly crosses a notch (the solver's rule; touching is not crossing)."""
    return any(side(p, q, a) * side(p, q, b) < 0 and side(a, b, p) * side(a, b, q) < 0 for a, b in notches)


def touches_end(p, q, notches):
    """Segment pq passes through an end point of a notch (orientation exactly 0, within pq)."""
    return any(side(p, q, e) == 0 and min(p[0], q[0]) <= e[0] <= max(p[0], q[0]) and min(p[1], q[1]) <= e[1] <= max(p[1], q[1])
               for a, b in notches for e in (a, b))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run")
    ap.add_argument("--dx", type=float, required=True)
    ap.add_argument("--horizon-factor", type=float, required=True)
    ap.add_argument("--critical-stretch", type=float, required=True)
    ap.add_argument("--notches", required=True)
    ap.add_argument("--opening", type=float, required=True)
    ap.add_argument("--min-isolated", type=int, default=0, help="points that must end with no intact bond")
    args = ap.parse_args()
    v = [float(c) for c in args.notches.split(",")]
    notches = [((v[k], v[k + 1]), (v[k + 2], v[k + 3])) for k in range(0, len(v), 4)]
    problems = []

    with open(f"{args.run}/history.csv") as f:
        rows = list(csv.DictReader(f))
    # (the crack's toughness and tip are NaN until the first bond breaks: docs/options_run.md, "Output")
    no_crack_yet = lambda r, k: k.startswith(("effective_fracture_energy", "crack_length", "crack_tip")) and int(r["broken_bonds"]) == 0
    bad = [(r["step"], k) for r in rows for k, v in r.items() if not math.isfinite(float(v)) and not no_crack_yet(r, k)]
    if bad:
        problems.append(f"history.csv holds NaN/Inf (step {bad[0][0]}, {bad[0][1]})")
    broken_final = int(rows[-1]["broken_bonds"])
    if broken_final <= 0:
        problems.append("no bond broke: the scene does not test what it should")
    # The step at which the last bond broke: the run must go on well after it.
    torn_at = next(float(r["stretch"]) for r in rows if int(r["broken_bonds"]) == broken_final)
    final_stretch = float(rows[-1]["stretch"])

    with open(f"{args.run}/final_state.csv") as f:
        state = [[float(r[k]) for k in ("x_m", "y_m", "ux_m", "uy_m")] for r in csv.DictReader(f)]
    points = [(s[0], s[1]) for s in state]
    current = [(s[0] + s[2], s[1] + s[3]) for s in state]
    with open(f"{args.run}/broken_bonds.csv") as f:
        broken = {(int(r["i"]), int(r["j"])) for r in csv.DictReader(f)}
    delta = args.horizon_factor * args.dx
    cell = {}
    for i, (x, y) in enumerate(points):
        cell.setdefault((math.floor(x / delta), math.floor(y / delta)), []).append(i)
    intact = [[] for _ in points]
    overstretched = []
    for i, (x, y) in enumerate(points):
        cx, cy = math.floor(x / delta), math.floor(y / delta)
        for ox in (-1, 0, 1):
            for oy in (-1, 0, 1):
                for j in cell.get((cx + ox, cy + oy), []):
                    p, q = points[i], points[j]
                    if j == i or math.dist(p, q) > delta or crosses(p, q, notches) or (i, j) in broken:
                        continue
                    if math.dist(current[i], current[j]) > args.critical_stretch * math.dist(p, q):
                        if not touches_end(p, q, notches):
                            overstretched.append((i, j))
                        continue
                    intact[i].append(j)
    if overstretched:
        i, j = overstretched[0]
        problems.append(f"{len(overstretched)} intact bond(s) stretched past the critical stretch, e.g. {i}-{j}")
    ys = [p[1] for p in points]
    top = [i for i, p in enumerate(points) if p[1] == max(ys)]
    bottom = {i for i, p in enumerate(points) if p[1] == min(ys)}
    seen, queue = set(top), deque(top)
    while queue:
        for j in intact[queue.popleft()]:
            if j not in seen:
                seen.add(j)
                queue.append(j)
    joined = len(seen & bottom)
    if joined:
        problems.append(f"not torn in two: {joined} bottom-row points still joined to the top row by intact bonds")
    isolated = sum(1 for n in intact if not n)
    if isolated < args.min_isolated:
        problems.append(f"{isolated} isolated points, want at least {args.min_isolated}")

    uy = {name: float(rows[-1][f"{name}_uy_m"]) for name in ("above", "below")}
    opening = uy["above"] - uy["below"]
    if not opening > args.opening:
        problems.append(f"the halves did not move apart: uy(above) - uy(below) = {opening:.3e} m, want > {args.opening:.3e} m")
    print(f"{'FAIL' if problems else 'ok  '} {args.run}: {broken_final} broken bonds, torn through by stretch {torn_at:.3f}, "
          f"ran on to {final_stretch:.3f}; top piece {len(seen)} points, {isolated} isolated points (no intact bond); "
          f"uy(above) - uy(below) = {opening * 1e3:.3f} mm" + ("".join(f"\n     {p}" for p in problems)))
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
