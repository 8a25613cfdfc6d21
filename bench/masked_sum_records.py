#!/usr/bin/python3
"""Records a masked sum adds per bond on an interior lattice family (docs/notes/performance-kernel-3.md 1k).

A bond's sums (bond_geometry.hpp masked_sum) add the records of the BA family's
members, or the total minus the others: whichever set is smaller, decided over the
whole mask (an earlier form of the kernel) or per chunk of `chunk` members (a 64-bit
mask word, as the kernel decides: chunk 64). Members in natural order (x fastest, then y,
then z), as build_families sorts them.

    bench/masked_sum_records.py [FACTOR] [DIM]     (defaults 3.015, 3)
"""
import itertools
import math
import sys

factor = float(sys.argv[1]) if len(sys.argv) > 1 else 3.015
dim = int(sys.argv[2]) if len(sys.argv) > 2 else 3
reach = int(math.ceil(factor))
members = [p for p in itertools.product(range(-reach, reach + 1), repeat=dim)
           if any(p) and sum(c * c for c in p) <= factor * factor]
members.sort(key=lambda p: tuple(reversed(p)))  # natural order: the last coordinate slowest
m = len(members)


def added(chunk):
    total = 0
    for p in members:  # bond (i -> p), i at the origin; B_ip = {q : |x_q - x_p| <= delta}
        inside = [math.dist(q, p) <= factor for q in members]
        for w in range(0, m, chunk):
            part = inside[w:w + chunk]
            total += min(sum(part), len(part) - sum(part))
    return total / m


print(f"{dim}D, delta = {factor} dx: {m} members, {(m + 63) // 64} mask word(s)")
for chunk, name in ((m, "whole mask"), (64, "per 64-bit word"), (32, "per 32 members"), (16, "per 16 members")):
    print(f"  smaller set decided {name:>16}: {added(chunk):5.1f} records a sum")
