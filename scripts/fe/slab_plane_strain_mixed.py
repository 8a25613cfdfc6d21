#!/usr/bin/python3
"""Plane-strain reference without volumetric locking: the block's x-y section
(examples/slab_plane_strain.yaml: [0, 10] x [0, 20] mm less a hole of radius 2.5 mm
through (5, 10), top edge clamped and moved by (lambda - 1) 20 mm, bottom held),
compressible Gent in plane strain exactly as bapd's PlaneStrain (F = diag(F~, 1):
tr C = tr C~ + 1, J = det F~), mu = 4.55 kPa, Jm = 162.6, K = 1000 mu by default.

Discretised by gent_fe.GentSolidMixed (on a 2D mesh, plane strain): Taylor-Hood, u in P2 and a pressure
in P1, on the Hu-Washizu functional with the volume variable eliminated,
    Pi(u, p) = int Psi_iso(F) + U(Theta(p)) + p (J - Theta(p)) dA,
so K = 1000 mu does not lock the displacement (block_hole_3d.py --slab solves the same
section with P2 displacement only, which does, slowly converging from the stiff side).
Quarter by symmetry (block_hole_3d.solve_section's mesh and conditions). Outputs, per
mesh size h (refined by sqrt 2 by default): s = top reaction / (10 mm x thickness), per
unit thickness as bapd's (kPa), side_mid ux (0, 10), ligament ux (2.5, 10), crown uy
(5, 12.5) mm, at lambda 1.25 and 1.5, and the same at the lattice points bapd's probes
read at dx = 0.5 and 0.25 mm (side (dx/2, 10 - dx/2), ligament (2.5 - dx/2, 10 - dx/2),
crown (5 - dx/2, 12.5 + dx/2): the ux of the first two from their mirror images in
y = 10); --csv writes them.
    /usr/bin/python3 scripts/fe/slab_plane_strain_mixed.py [--bulk-ratio 1000]
        [--sizes 1.41 1 0.71 0.5] [--csv scripts/fe/results/slab_plane_strain_mixed.csv]
"""
import argparse
import csv
import os
import sys

import numpy as np
from dolfinx import fem

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402
from block_hole_3d import FIRST_STEP, HEIGHT, RADIUS, WIDTH, XC, YC  # noqa: E402

LATTICE_DX = (0.5, 0.25)    # mm: bapd spacings whose probe points are reported


def solve(h, bulk_ratio, lambdas, verbose=False):
    def build(gmsh, h_):
        occ = gmsh.model.occ
        plate = occ.addRectangle(0.0, YC, 0.0, XC, HEIGHT - YC)
        disk = occ.addDisk(XC, YC, 0.0, RADIUS, RADIUS)
        cut, _ = occ.cut([(2, plate)], [(2, disk)])
        occ.synchronize()
        return [tag for _, tag in cut]
    msh = gent_fe.mesh_from_gmsh(build, h, dim=2)
    fe = gent_fe.GentSolidMixed(msh, 2, bulk_ratio)  # a 2D mesh: plane strain
    top = fe.facets(lambda x: np.isclose(x[1], HEIGHT))
    fe.add_bc(0, top)
    uy_top = fe.add_bc(1, top)
    fe.add_bc(1, fe.facets(lambda x: np.isclose(x[1], YC)))
    fe.add_bc(0, fe.facets(lambda x: np.isclose(x[0], XC)))
    reaction = fe.reaction_form(1, top)
    points = [(0.0, YC), (XC - RADIUS, YC), (XC, YC + RADIUS)]
    for dx in LATTICE_DX:
        points += [(dx / 2, YC + dx / 2), (XC - RADIUS - dx / 2, YC + dx / 2), (XC - dx / 2, YC + RADIUS + dx / 2)]
    out = {"s": {}, "side_mid_ux": {}, "ligament_ux": {}, "crown_uy": {}}
    for dx in LATTICE_DX:
        for k in ("side_mid_ux", "ligament_ux", "crown_uy"):
            out[f"{k}_dx{dx:g}"] = {}

    def set_load(lam):
        uy_top.value = (lam - 1.0) * (HEIGHT - YC)

    def on_target(lam):
        out["s"][lam] = 2 * fem.assemble_scalar(reaction) / WIDTH   # the quarter's half width, per unit thickness
        u = gent_fe.point_values(fe.displacement(), points)
        out["side_mid_ux"][lam] = float(u[0][0])
        out["ligament_ux"][lam] = float(u[1][0])
        out["crown_uy"][lam] = float(u[2][1]) + (lam - 1.0) * HEIGHT / 2
        for n, dx in enumerate(LATTICE_DX):
            side, ligament, crown = u[3 + 3 * n: 6 + 3 * n]
            out[f"side_mid_ux_dx{dx:g}"][lam] = float(side[0])
            out[f"ligament_ux_dx{dx:g}"][lam] = float(ligament[0])
            out[f"crown_uy_dx{dx:g}"][lam] = float(crown[1]) + (lam - 1.0) * HEIGHT / 2

    fe.march(set_load, lambdas, on_target, dlam0=FIRST_STEP, fast_iterations=10, dlam_max=0.25,
             verbose=verbose)
    return out, gent_fe.solve_info(fe)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bulk-ratio", type=float, default=1000.0, help="K / mu (default 1000)")
    ap.add_argument("--sizes", type=float, nargs="*", default=[1.41, 1.0, 0.71, 0.5], help="mesh sizes h (mm)")
    ap.add_argument("--csv", default=None, help="write the table here")
    ap.add_argument("--verbose", action="store_true")
    args = ap.parse_args()
    lambdas = [1.25, 1.5]
    keys = ["s", "side_mid_ux", "ligament_ux", "crown_uy"] + [
        f"{k}_dx{dx:g}" for dx in LATTICE_DX for k in ("side_mid_ux", "ligament_ux", "crown_uy")]
    rows = []
    print(f"Plane-strain section, Taylor-Hood P2-P1, K = {args.bulk_ratio:g} mu: "
          "s (kPa), side_mid ux, ligament ux, crown uy (mm)")
    for h in args.sizes:
        timer = gent_fe.Timer()
        values, info = solve(h, args.bulk_ratio, lambdas, args.verbose)
        row = dict(h_mm=h, cells=info["cells"], dofs=info["dofs"])
        for k in keys:
            for lam in lambdas:
                row[f"{k}_{lam:g}"] = f"{values[k][lam]:.8f}"
        row["time_s"] = f"{timer():.1f}"
        rows.append(row)
        print(f"  h {h:g}: {info['cells']} cells, {info['dofs']} dofs, "
              + ", ".join(f"{k}({lam:g}) {values[k][lam]:.6f}" for k in keys for lam in lambdas), flush=True)
    if args.csv:
        os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
        with open(args.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
        print(f"wrote {args.csv}")


if __name__ == "__main__":
    main()
