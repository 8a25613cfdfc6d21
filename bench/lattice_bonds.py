#!/usr/bin/python3
"""Directed bond counts of square (2D) and simple cubic (3D) lattices.

    lattice_bonds.py --match SIDE FACTOR
prints `n bonds3 bonds2 steps`: the 3D lattice of (n + 1)^3 points (LAMMPS' region
block 0..n in lattice units holds n + 1 points a side) with horizon FACTOR x spacing
whose directed bond count is closest to that of the SIDE x SIDE 2D lattice of
kernel_bench at the same FACTOR, and a LAMMPS step count that makes the timed loop
last about 3 s at 60 ns a bond.

Exact for lattices without holes: a bond offset o with |o| <= FACTOR occurs
prod_d (points_d - |o_d|) times.
"""
import itertools
import math
import sys


def bonds(points_per_side, factor, dim):
    r = int(math.floor(factor))
    total = 0
    for o in itertools.product(range(-r, r + 1), repeat=dim):
        if any(o) and sum(c * c for c in o) <= factor * factor:
            total += math.prod(max(0, points_per_side - abs(c)) for c in o)
    return total


def main():
    if len(sys.argv) != 4 or sys.argv[1] != "--match":
        sys.exit(__doc__)
    side, factor = int(sys.argv[2]), float(sys.argv[3])
    target = bonds(side, factor, 2)
    best = min(range(2, 400), key=lambda n: abs(bonds(n + 1, factor, 3) - target))
    b3 = bonds(best + 1, factor, 3)
    steps = max(3, math.ceil(3.0 / (b3 * 60e-9)))
    print(best, b3, target, steps)


if __name__ == "__main__":
    main()
