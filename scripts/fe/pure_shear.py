#!/usr/bin/python3
"""FE reference for the clamped pure-shear sheet (docs/method.md section 7.2).

A 70 mm x 10 mm free region, thickness 3 mm, plane-stress Gent (mu = 4.55 kPa,
Jm = 162.6); bottom edge held (ux = uy = 0), top edge moved by (0, (lambda - 1) 10 mm),
side edges free. Nominal stress s = top reaction / (70 mm x 3 mm), in kPa.

The sheet is symmetric about x = 35 mm and (with the top moving by d) about y = 5 mm,
where uy = d/2 and the shear traction vanishes; the default solves the quarter
[35, 70] x [5, 10] mm with those conditions (ux = 0 on x = 35, uy = d/2 on y = 5) and
doubles its reaction; --full solves the whole sheet (a check of the symmetry).
Meshes: squares of side h, each cut into 4 triangles by its diagonals.

Prints one row per mesh (P2 on meshes halved in size, P1 on the finest), the
Richardson estimate from the three finest P2 meshes, and writes results/pure_shear.csv.
"""
import os
import sys

import numpy as np
from mpi4py import MPI

from dolfinx import mesh as dmesh

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402

WIDTH, HEIGHT, THICKNESS = 70.0, 10.0, 3.0   # mm


def solve(h, degree, bulk_ratio, lambdas, full=False, verbose=False):
    x0, y0 = (0.0, 0.0) if full else (WIDTH / 2, HEIGHT / 2)
    nx = int(round((WIDTH - x0) / h))
    ny = int(round((HEIGHT - y0) / h))
    if not (np.isclose(nx * h, WIDTH - x0) and np.isclose(ny * h, HEIGHT - y0)):
        sys.exit(f"pure_shear: --sizes {h:g} does not divide the {WIDTH - x0:g} x "
                 f"{HEIGHT - y0:g} mm domain; use 5/n mm (1, 0.5, 0.25, ...)")
    msh = dmesh.create_rectangle(MPI.COMM_WORLD, [np.array([x0, y0]), np.array([WIDTH, HEIGHT])],
                                 [nx, ny], dmesh.CellType.triangle, dmesh.GhostMode.none,
                                 diagonal=dmesh.DiagonalType.crossed)
    fe = gent_fe.GentPlaneStress(msh, degree, THICKNESS, bulk_ratio=bulk_ratio)
    top = fe.facets(lambda x: np.isclose(x[1], HEIGHT))
    low = fe.facets(lambda x: np.isclose(x[1], y0))
    fe.add_bc(0, top)
    uy_top = fe.add_bc(1, top)
    if full:
        fe.add_bc(0, low)
        fe.add_bc(1, low)
        uy_low = None
    else:
        fe.add_bc(0, fe.facets(lambda x: np.isclose(x[0], x0)))   # symmetry about x = 35
        uy_low = fe.add_bc(1, low)                                 # symmetry about y = 5
    reaction = fe.reaction_form(1, top)

    def set_load(lam):
        d = (lam - 1.0) * HEIGHT
        uy_top.value = d
        if uy_low is not None:
            uy_low.value = d / 2

    stress = {}

    def on_target(lam):
        r = gent_fe.fem.assemble_scalar(reaction) * WIDTH / (WIDTH - x0)
        stress[lam] = r / (WIDTH * THICKNESS)
        if verbose:
            print(f"    lambda {lam:g}: nominal stress {stress[lam]:.6f} kPa", file=sys.stderr)

    fe.march(set_load, lambdas, on_target, verbose=verbose)
    return {"s": stress}, gent_fe.solve_info(fe)


def main():
    ap = gent_fe.study_arguments(__doc__, [1.0, 0.5, 0.25], [1.5, 2.0, 3.0, 5.125],
                                 "pure_shear.csv")
    ap.add_argument("--full", action="store_true", help="whole sheet instead of the quarter")
    args = ap.parse_args()
    print(f"Pure shear, 70 x 10 mm free region, t = 3 mm, clamped, plane-stress Gent "
          f"({'whole sheet' if args.full else 'quarter by symmetry'}): nominal stress s (kPa); "
          "eq 36 (homogeneous): "
          + ", ".join(f"{gent_fe.pure_shear_analytic(l):.4f}" for l in sorted(args.lambdas)))
    gent_fe.run_study(args, [("s", "s", "kPa")],
                      lambda h, p, k, lams: solve(h, p, k, lams, args.full, args.verbose))


if __name__ == "__main__":
    main()
