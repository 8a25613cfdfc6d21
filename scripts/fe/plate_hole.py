#!/usr/bin/python3
"""FE reference for the paper's plate with a hole (docs/method.md section 7.1).

80 mm x 160 mm, central hole of diameter 20 mm, thickness 1 mm, plane-stress Gent
(mu = 4.55 kPa, Jm = 162.6). Top and bottom edges displaced symmetrically in y by
+-(lambda - 1) 80 mm and held in x (clamped grips; lambda = current / initial height).
Outputs: u_max = the horizontal displacement of the mid-point of the left edge (mm, the
largest), and the nominal stress s = top reaction / (80 mm x 1 mm) (kPa).
The paper's FEA: u_max = 8.62, 11.10, 13.01 mm at lambda = 1.5, 1.75, 2.0.

By symmetry about both centre lines the default solves the top-left quarter
[0, 40] x [80, 160] mm (ux = 0 on x = 40, uy = 0 on y = 80) and doubles its reaction;
--full solves the whole plate; --grips sliding leaves x free on the gripped edges.
Meshes: gmsh, uniform size h, second-order geometry.
Writes results/plate_hole.csv.
"""
import os
import sys

import numpy as np
from petsc4py import PETSc

from dolfinx import fem

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402

WIDTH, HEIGHT, THICKNESS, RADIUS = 80.0, 160.0, 1.0, 10.0   # mm
PAPER_FEA = {1.5: 8.62, 1.75: 11.10, 2.0: 13.01}              # u_max, mm


def solve(h, degree, bulk_ratio, lambdas, full=False, sliding=False, verbose=False):
    xc, yc = WIDTH / 2, HEIGHT / 2
    x0, y0, x1 = (0.0, 0.0, WIDTH) if full else (0.0, yc, xc)

    def build(gmsh, h):
        occ = gmsh.model.occ
        plate = occ.addRectangle(x0, y0, 0, x1 - x0, HEIGHT - y0)
        hole = occ.addDisk(xc, yc, 0, RADIUS, RADIUS)
        cut, _ = occ.cut([(2, plate)], [(2, hole)])
        occ.synchronize()
        return [tag for _, tag in cut]

    msh = gent_fe.mesh_from_gmsh(build, h)
    fe = gent_fe.GentPlaneStress(msh, degree, THICKNESS, bulk_ratio=bulk_ratio)
    top = fe.facets(lambda x: np.isclose(x[1], HEIGHT))
    low = fe.facets(lambda x: np.isclose(x[1], y0))
    if not sliding:
        fe.add_bc(0, top)
    uy_top = fe.add_bc(1, top)
    uy_low = fe.add_bc(1, low)
    if full and not sliding:
        fe.add_bc(0, low)
    elif full:
        # Sliding grips leave x free on both edges: hold the edges' mid-points in x instead
        # (what symmetry gives), which removes the rigid translation.
        V0, _ = fe.V.sub(0).collapse()
        mids = fem.locate_dofs_geometrical(
            (fe.V.sub(0), V0), lambda x: np.isclose(x[0], xc) & (np.isclose(x[1], 0.0)
                                                                 | np.isclose(x[1], HEIGHT)))
        fe.bcs.append(fem.dirichletbc(PETSc.ScalarType(0), mids[0], fe.V.sub(0)))
    else:
        fe.add_bc(0, fe.facets(lambda x: np.isclose(x[0], x1)))   # symmetry about x = 40
    reaction = fe.reaction_form(1, top)

    def set_load(lam):
        d = (lam - 1.0) * HEIGHT / 2
        uy_top.value = d
        uy_low.value = -d if full else 0.0   # symmetry about y = 80: uy = 0 there

    u_max, stress = {}, {}

    def on_target(lam):
        u_max[lam] = float(gent_fe.point_value(fe.u, (0.0, yc))[0])
        r = gent_fe.fem.assemble_scalar(reaction) * WIDTH / (x1 - x0)
        stress[lam] = r / (WIDTH * THICKNESS)
        if verbose:
            print(f"    lambda {lam:g}: u_max {u_max[lam]:.6f} mm, s {stress[lam]:.6f} kPa",
                  file=sys.stderr)

    fe.march(set_load, lambdas, on_target, verbose=verbose)
    return {"u_max": u_max, "s": stress}, gent_fe.solve_info(fe)


def main():
    ap = gent_fe.study_arguments(__doc__, [4.0, 2.0, 1.0], [1.5, 1.75, 2.0],
                                 "plate_hole.csv")
    ap.add_argument("--full", action="store_true", help="whole plate instead of the quarter")
    ap.add_argument("--grips", choices=["clamped", "sliding"], default="clamped",
                    help="clamped: top and bottom held in x (docs/method.md 7.1's default); "
                         "sliding: x free there (the paper's PD point layers' other reading)")
    args = ap.parse_args()
    print(f"Plate with a hole, 80 x 160 mm, hole d = 20 mm, t = 1 mm, {args.grips} grips, "
          f"plane-stress Gent ({'whole plate' if args.full else 'quarter by symmetry'}): "
          "u_max (mm, mid-point of the left edge) and nominal stress s (kPa); paper's FEA "
          "u_max: " + ", ".join(f"{v:.2f} at {l:g}" for l, v in PAPER_FEA.items()))
    gent_fe.run_study(args, [("u_max", "u_max", "mm"), ("s", "s", "kPa")],
                      lambda h, p, k, lams: solve(h, p, k, lams, args.full,
                                               args.grips == "sliding", args.verbose))


if __name__ == "__main__":
    main()
