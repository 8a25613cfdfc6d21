#!/usr/bin/env python3
"""Compares the outputs of runs of one scene (history.csv, final_state.csv,
broken_bonds.csv): the first directory is the reference. Exits non-zero on any
difference beyond the tolerance, printing the worst one."""
import argparse
import csv
import sys


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(v) for v in r] for r in rows[1:]]


def max_relative_difference(a, b, columns):
    """Largest |a - b| / scale over a column, scale = the column's largest |value|."""
    worst = (0.0, None, None)
    for c, name in enumerate(columns):
        scale = max(max(abs(r[c]) for r in a), 1e-300)
        for k, (ra, rb) in enumerate(zip(a, b)):
            d = abs(ra[c] - rb[c]) / scale
            if d > worst[0]:
                worst = (d, name, k)
    return worst


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--tolerance", type=float, default=0.0)
    p.add_argument("--expect-broken", action="store_true", help="fail if no bond broke")
    p.add_argument("dirs", nargs="+")
    args = p.parse_args()
    ref = args.dirs[0]
    failed = False
    for name in ("history.csv", "final_state.csv"):
        cols, a = read_csv(f"{ref}/{name}")
        for other in args.dirs[1:]:
            cols_b, b = read_csv(f"{other}/{name}")
            if cols != cols_b or len(a) != len(b):
                print(f"{other}/{name}: different shape ({len(b)} rows vs {len(a)})")
                failed = True
                continue
            d, col, row = max_relative_difference(a, b, cols)
            status = "ok" if d <= args.tolerance else "DIFFERENT"
            print(f"{other}/{name}: max relative difference {d:.3e} ({col}, row {row}) {status}")
            failed |= d > args.tolerance
    with open(f"{ref}/broken_bonds.csv") as f:
        ref_bonds = f.read()
    nbroken = len(ref_bonds.strip().splitlines()) - 1
    print(f"{ref}: {nbroken} broken bonds")
    if args.expect_broken and nbroken <= 0:
        print("expected broken bonds, found none")
        failed = True
    for other in args.dirs[1:]:
        with open(f"{other}/broken_bonds.csv") as f:
            same = f.read() == ref_bonds
        print(f"{other}/broken_bonds.csv: {'same set' if same else 'DIFFERENT set'}")
        failed |= not same
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
