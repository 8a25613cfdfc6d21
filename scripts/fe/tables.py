#!/usr/bin/python3
"""Markdown tables of the convergence-study CSVs (docs/fe_reference.md is made from them):
    /usr/bin/python3 scripts/fe/tables.py tests/data/fe/plate_hole.csv
One row a mesh and an `extrapolated` row per formulation, every quantity column."""
import csv
import sys


def table(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    quantities = [k for k in rows[0] if k not in ("formulation", "degree", "h_mm", "cells",
                                                  "dofs", "max_S33_residual", "time_s")]
    print("| formulation | P | h (mm) | cells | dofs | "
          + " | ".join(q.replace("_", " ") for q in quantities) + " |")
    print("|---" * (5 + len(quantities)) + "|")
    for r in rows:
        values = [f"{float(r[q]):.6f}" if r[q] else "-" for q in quantities]
        print(f"| {r['formulation']} | {r['degree']} | {r['h_mm'] if r['cells'] else ''} | "
              f"{r['cells']} | {r['dofs']} | " + " | ".join(values) + " |")


if __name__ == "__main__":
    for path in sys.argv[1:]:
        table(path)
        print()
