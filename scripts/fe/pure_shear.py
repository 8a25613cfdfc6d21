#!/usr/bin/python3
"""FE reference for the clamped pure-shear sheet (issue 14; METHOD.md section 7.2).

A 70 mm x 10 mm free region, thickness 3 mm, plane-stress Gent (mu = 4.55 kPa,
Jm = 162.6); bottom edge held (ux = uy = 0), top edge moved by (0, (lambda - 1) 10 mm),
side edges free. Nominal stress = top reaction / (70 mm x 3 mm), in kPa.

The sheet is symmetric about x = 35 mm and (with the top moving by d) about y = 5 mm,
where uy = d/2 and the shear traction vanishes; the default solves the quarter
[35, 70] x [5, 10] mm with those conditions (ux = 0 on x = 35, uy = d/2 on y = 5) and
doubles its reaction; --full solves the whole sheet (a check of the symmetry).

Prints one row per mesh (P2 on meshes halved in size, P1 on the finest), the
Richardson estimate from the three finest P2 meshes, and writes results/pure_shear.csv.
"""
import argparse
import csv
import os
import sys

import numpy as np
from mpi4py import MPI

from dolfinx import mesh as dmesh

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402

WIDTH, HEIGHT, THICKNESS = 70.0, 10.0, 3.0   # mm


def solve(h, degree, bulk_ratio, lambdas, full=False, verbose=False):
    if full:
        x0, y0 = 0.0, 0.0
    else:
        x0, y0 = WIDTH / 2, HEIGHT / 2
    nx = int(round((WIDTH - x0) / h))
    ny = int(round((HEIGHT - y0) / h))
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
    width_modelled = WIDTH - x0

    def set_load(lam):
        d = (lam - 1.0) * HEIGHT
        uy_top.value = d
        if uy_low is not None:
            uy_low.value = d / 2

    stresses = {}

    def on_target(lam):
        r = gent_fe.fem.assemble_scalar(reaction)
        stresses[lam] = r * (WIDTH / width_modelled) / (WIDTH * THICKNESS)
        if verbose:
            print(f"    lambda {lam:g}: nominal stress {stresses[lam]:.6f} kPa", file=sys.stderr)

    fe.march(set_load, lambdas, on_target, verbose=verbose)
    s33 = fe.s33_check() if fe.compressible else 0.0
    ncells = msh.topology.index_map(2).size_local
    return stresses, ncells, gent_fe.dofs_of(fe), fe.steps_taken, fe.newton_iterations, s33


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="the two coarsest meshes only")
    ap.add_argument("--full", action="store_true", help="whole sheet instead of the quarter")
    ap.add_argument("--sizes", type=float, nargs="+", default=[1.0, 0.5, 0.25, 0.125],
                    help="P2 element sizes (mm), coarse to fine (crossed squares of this side)")
    ap.add_argument("--lambdas", type=float, nargs="+", default=[1.5, 2.0, 3.0, 5.125])
    ap.add_argument("--formulations", nargs="+", default=["incompressible", "compressible"],
                    choices=["incompressible", "compressible"])
    ap.add_argument("--bulk-ratio", type=float, default=gent_fe.BULK_RATIO,
                    help="K/mu of the compressible law (bapd's default 1000)")
    ap.add_argument("--csv", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                  "results", "pure_shear.csv"))
    ap.add_argument("--verbose", action="store_true")
    args = ap.parse_args()
    sizes = args.sizes[:2] if args.quick else args.sizes
    lambdas = sorted(args.lambdas)

    rows = []
    print(f"Pure shear, 70 x 10 mm free region, t = 3 mm, plane-stress Gent "
          f"({'full sheet' if args.full else 'quarter by symmetry'}); "
          f"nominal stress (kPa) at lambda = {', '.join(f'{l:g}' for l in lambdas)}")
    header = (f"{'formulation':<15} {'P':>2} {'h_mm':>7} {'cells':>7} {'dofs':>8} "
              + " ".join(f"{'s(' + format(l, 'g') + ')':>11}" for l in lambdas)
              + f" {'steps':>5} {'newton':>6} {'time_s':>7}")
    for form in args.formulations:
        bulk = None if form == "incompressible" else args.bulk_ratio
        name = gent_fe.formulation_name(bulk)
        print(header)
        runs = [(2, h) for h in sizes] + [(1, sizes[-1])]
        p2_values = {l: [] for l in lambdas}
        for degree, h in runs:
            timer = gent_fe.Timer()
            s, ncells, ndofs, steps, its, s33 = solve(h, degree, bulk, lambdas, args.full,
                                                      args.verbose)
            t = timer()
            print(f"{name:<15} {degree:>2} {h:>7.4g} {ncells:>7} {ndofs:>8} "
                  + " ".join(f"{s[l]:>11.6f}" for l in lambdas)
                  + f" {steps:>5} {its:>6} {t:>7.1f}", flush=True)
            if degree == 2:
                for l in lambdas:
                    p2_values[l].append(s[l])
            for l in lambdas:
                rows.append(dict(formulation=name, degree=degree, h_mm=h, cells=ncells,
                                 dofs=ndofs, stretch=l, nominal_stress_kPa=f"{s[l]:.8f}",
                                 eq36_homogeneous_kPa=f"{gent_fe.pure_shear_analytic(l):.8f}",
                                 max_S33_residual=f"{s33:.1e}", time_s=f"{t:.1f}"))
        for l in lambdas:
            p, ext = gent_fe.richardson(p2_values[l])
            fine = p2_values[l][-1]
            if ext is None:
                print(f"  lambda {l:g}: finest P2 {fine:.6f} kPa (no Richardson estimate: "
                      f"differences {np.diff(p2_values[l])})")
            else:
                print(f"  lambda {l:g}: finest P2 {fine:.6f} kPa, observed order {p:.2f}, "
                      f"extrapolated {ext:.6f} kPa, estimated error of the finest "
                      f"{abs(fine - ext) / abs(ext):.1e} (relative); "
                      f"eq 36 (homogeneous) {gent_fe.pure_shear_analytic(l):.4f}")
                rows.append(dict(formulation=name, degree="extrapolated", h_mm=0, cells="",
                                 dofs="", stretch=l, nominal_stress_kPa=f"{ext:.8f}",
                                 eq36_homogeneous_kPa=f"{gent_fe.pure_shear_analytic(l):.8f}",
                                 max_S33_residual="", time_s=f"order {p:.2f}"))
    os.makedirs(os.path.dirname(args.csv), exist_ok=True)
    with open(args.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {args.csv}")


if __name__ == "__main__":
    main()
