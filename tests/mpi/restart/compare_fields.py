#!/usr/bin/python3
"""Compares two field files (bapd -output_fields): every dataset but /rank (which rank
owned a point: the one that depends on the rank layout by design) and the step and
time attributes. Exits non-zero on a difference beyond the relative tolerance
(relative to each dataset's largest magnitude)."""
import argparse
import sys

import h5py
import numpy as np


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--tolerance", type=float, default=0.0)
    p.add_argument("reference")
    p.add_argument("other")
    args = p.parse_args()
    failed = False
    with h5py.File(args.reference, "r") as a, h5py.File(args.other, "r") as b:
        if sorted(a.keys()) != sorted(b.keys()):
            print(f"{args.other}: datasets {sorted(b.keys())}, expected {sorted(a.keys())}")
            sys.exit(1)
        for name in ("step", "time_s"):
            if a.attrs[name] != b.attrs[name]:
                print(f"{args.other}: {name} {b.attrs[name]} != {a.attrs[name]}")
                failed = True
        for name in sorted(set(a.keys()) - {"rank"}):
            x, y = a[name][()], b[name][()]
            if x.shape != y.shape:
                print(f"{args.other}:/{name} shape {y.shape} != {x.shape}")
                failed = True
                continue
            scale = max(np.max(np.abs(x)), 1e-300)
            d = np.max(np.abs(x - y)) / scale if x.size else 0.0
            ok = d <= args.tolerance
            print(f"{args.other}:/{name} max relative difference {d:.3e} {'ok' if ok else 'DIFFERENT'}")
            failed |= not ok
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
