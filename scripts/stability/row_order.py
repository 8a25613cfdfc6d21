#!/usr/bin/python3
"""Row order of a sheet pulled along y, from the field files of a run (-output_fields).

For every lattice column (points with the same reference x), sorted by reference y,
the spacing ratio of each pair of neighbouring free rows: their current spacing over
the mean spacing of the free rows of that column. 1 in a uniform stretch, 0 when two
rows meet, < 0 when they have crossed (a row of points has passed the next one: the
grip boundary layer of docs/stability.md, section 2). Gaps inside a grip (both rows
held: spacing unchanged to round-off) are left out. Prints, per field file, the
stretch and the smallest and largest ratio.

    row_order.py RUN_DIR [--json]
"""
import glob
import json
import os
import sys

import h5py
import numpy as np


def ratios(path):
    with h5py.File(path, "r") as f:
        stretch = float(f.attrs["stretch"])
        ref = np.asarray(f["reference_position"])[:, :2]
        cur = np.asarray(f["position"])[:, :2]
    lo, hi = np.inf, -np.inf
    for x in np.unique(np.round(ref[:, 0], 12)):
        col = np.nonzero(np.abs(ref[:, 0] - x) < 1e-12)[0]
        col = col[np.argsort(ref[col, 1])]
        if len(col) < 4:
            continue
        dy = np.diff(cur[col, 1])
        dY = np.diff(ref[col, 1])
        free = np.abs(dy - dY) > 1e-9 * dY
        if stretch == 1.0 or not free.any():
            lo, hi = min(lo, 1.0), max(hi, 1.0)
            continue
        r = dy[free] / dy[free].mean()
        lo, hi = min(lo, r.min()), max(hi, r.max())
    return stretch, lo, hi


def main():
    run = sys.argv[1]
    files = sorted(glob.glob(os.path.join(run, "fields", "step_*.h5")))
    out = [ratios(p) for p in files]
    if "--json" in sys.argv:
        print(json.dumps(out))
    else:
        for s, lo, hi in out:
            print(f"stretch {s:7.3f}  spacing ratio min {lo:+.3f}  max {hi:+.3f}")


if __name__ == "__main__":
    main()
