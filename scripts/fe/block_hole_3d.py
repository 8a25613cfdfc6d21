#!/usr/bin/python3
"""FE reference for the 3D validation: a block with a cylindrical hole in tension.

The block [0, 10] x [0, 20] x [0, 4] mm (width x, height y: the pulled direction,
thickness z) with a through-thickness hole of radius 2.5 mm along z, centred at
(5, 10). Compressible 3D Gent exactly as bapd's Compressible3D (paper eqs 24, 26):
mu = 4.55 kPa, Jm = 162.6, K = 1000 mu (D = 2/(1000 mu), -material_bulk_ratio 1000).
Grips as bapd's default (docs/options.md, Loading): clamps outside the specimen, so the
free specimen is the whole block; its bottom face y = 0 is held (u = 0), its top face
y = 20 is held in x and z and moved by (lambda - 1) 20 mm in y (the stretch is the grip
separation over the body height). Free: the sides x = 0, 10, the faces z = 0, 4 and the
hole. Displacements are given in that frame (bottom fixed).

Outputs at each stretch: s = top reaction / (10 mm x 4 mm) (kPa, bapd's nominal
stress: reaction over the body's width x thickness) and the displacements (mm) of
named probes:
  side_mid       (0, 10, 2)     ux: the waist of the block's side, mid-thickness
  ligament_mid   (2.5, 10, 2)   ux: the hole's side, mid-thickness
  ligament_face  (2.5, 10, 4)   ux and uz: the hole's side on the free face
  crown_mid      (5, 12.5, 2)   uy: the hole's top, mid-thickness
and, for bapd's lattice spacings (--lattice-dx, default 0.5, 0.25, 0.2 mm: cell centres
(i + 0.5) dx), the FE displacement at the lattice point a bapd probe at each named point
reads (the nearest point outside the hole; a tie goes to the lowest natural id, x
fastest then y then z, as ProbeLocate in src/solver/input/scene_selection.cpp).

By symmetry about x = 5, y = 10 and z = 2 the default solves the octant
[0, 5] x [10, 20] x [2, 4] (ux = 0 on x = 5, uy = 0 on y = 10, uz = 0 on z = 2, the top
moved by (lambda - 1) 10 mm) and maps the results back (--full: the whole block).
Meshes: gmsh tetrahedra, size h, h/2 within 2.5 mm of the hole (--hole-refinement),
second-order geometry. Two discretisations of the same continuum problem:
  --mixed (the reference): Taylor-Hood, u in P2 and a pressure in P1
    (gent_fe.GentSolidMixed), free of volumetric locking; 27 Newton iterations a solve;
  default: P2 displacement only (gent_fe.GentSolid), which at K = 1000 mu (nu = 0.4995)
    is locking-limited: it converges slowly and from the stiff side, and its Newton
    needs a line search and 140 to 280 factorisations a solve (--p1: P1 on the finest
    mesh too, which locks outright).

--slab: the plane-strain check instead. The block's x-y section (quarter by symmetry)
solved in 2D plane strain (bapd's PlaneStrain: F33 = 1) and as a 3D slab 1 mm thick
with uz = 0 on both faces, the slab's mesh the 2D triangles extruded (one layer of
prisms, split into tetrahedra), so the 3D P2 space contains the 2D one.

--all: the mixed reference (h = 1.41, 1, 0.71, 0.5), the displacement-only P2 study
(h = 1.41, 1, 0.71) and the slab check (same sizes): block_hole_3d.csv and .json (the
reference: finest values, their estimated error, the lattice probes),
block_hole_3d_p2.csv and .json, slab_plane_strain.csv, in scripts/fe/results/.
"""
import json
import os
import sys

import numpy as np

from dolfinx import fem

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402

WIDTH, HEIGHT, THICKNESS, RADIUS = 10.0, 20.0, 4.0, 2.5      # mm
XC, YC = WIDTH / 2, HEIGHT / 2                                  # the hole's axis
SLAB = 1.0                                                      # mm, the --slab thickness
FIRST_STEP = 0.05
PROBES = {                                                      # name: point (mm), components
    "side_mid": ((0.0, YC, THICKNESS / 2), "x"),
    "ligament_mid": ((XC - RADIUS, YC, THICKNESS / 2), "x"),
    "ligament_face": ((XC - RADIUS, YC, THICKNESS), "xz"),
    "crown_mid": ((XC, YC + RADIUS, THICKNESS / 2), "y"),
}
AXES = "xyz"
RESULTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "results")


def lattice_point(point, dx):
    """The point a bapd probe at `point` reads on the lattice (i + 0.5) dx of the block
    less the hole: the nearest, a tie to the lowest natural id (x fastest, then y, z)."""
    n = [round(WIDTH / dx), round(HEIGHT / dx), round(THICKNESS / dx)]
    best = None
    centre = [int(np.floor(p / dx)) for p in point]
    for k in range(centre[2] - 2, centre[2] + 3):
        for j in range(centre[1] - 2, centre[1] + 3):
            for i in range(centre[0] - 2, centre[0] + 3):
                if not (0 <= i < n[0] and 0 <= j < n[1] and 0 <= k < n[2]):
                    continue
                x = tuple(round((m + 0.5) * dx, 12) for m in (i, j, k))
                if (x[0] - XC) ** 2 + (x[1] - YC) ** 2 <= RADIUS**2:
                    continue   # in the hole (a point on the curved surface is outside the body)
                d2 = sum((a - b) ** 2 for a, b in zip(x, point))
                key = (d2, i + n[0] * (j + n[1] * k))
                if best is None or key < best[0]:
                    best = (key, x)
    return best[1]


def octant_build(h, refinement):
    """gmsh builder of the octant [0, 5] x [10, 20] x [2, 4] less the hole (or the block
    with full=True), size h, refinement h within a radius of the hole surface."""
    def build(gmsh, h_, full=False):
        occ = gmsh.model.occ
        x0, y0, z0 = (0.0, 0.0, 0.0) if full else (0.0, YC, THICKNESS / 2)
        x1 = WIDTH if full else XC
        box = occ.addBox(x0, y0, z0, x1 - x0, HEIGHT - y0, THICKNESS - z0)
        hole = occ.addCylinder(XC, YC, z0 - 1, 0, 0, THICKNESS - z0 + 2, RADIUS)
        cut, _ = occ.cut([(3, box)], [(3, hole)])
        occ.synchronize()
        add_hole_size_field(gmsh, h_, refinement)
        return [tag for _, tag in cut]
    return build


def add_hole_size_field(gmsh, h, refinement):
    """Size refinement h next to the hole's surface, growing to h at one radius from it."""
    if refinement >= 1.0:
        return
    hole = [tag for dim, tag in gmsh.model.getEntities(2)
            if gmsh.model.getType(dim, tag) == "Cylinder"]
    gent_fe.refine_near(gmsh, "FacesList", hole, refinement * h, h, 0.0, RADIUS, 40)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)


class BlockSolution:
    """Maps a point of the whole block to the solved region and back (the octant's
    mirror images; uy in the frame where the bottom face is held)."""

    def __init__(self, fe, full):
        self.fe, self.full = fe, full

    def values(self, points, lam):
        points = np.asarray(points, dtype=float)
        if self.full:
            return gent_fe.point_values(self.fe.displacement(), points)
        q = points.copy()
        sign = np.ones_like(q)
        for axis, mid, upper in ((0, XC, False), (1, YC, True), (2, THICKNESS / 2, True)):
            # The octant is x <= 5, y >= 10, z >= 2: reflect what lies across.
            across = q[:, axis] < mid if upper else q[:, axis] > mid
            q[across, axis] = 2 * mid - q[across, axis]
            sign[across, axis] = -1.0
        u = gent_fe.point_values(self.fe.displacement(), q) * sign
        u[:, 1] += (lam - 1.0) * HEIGHT / 2     # the octant's y = 10 plane moves by half
        return u


def solve_block(h, degree, bulk_ratio, lambdas, *, full=False, refinement=0.5,
                lattice_dx=(), mixed=False, verbose=False):
    build = octant_build(h, refinement)
    msh = gent_fe.mesh_from_gmsh(lambda g, hh: build(g, hh, full), h, dim=3)
    fe = (gent_fe.GentSolidMixed if mixed else gent_fe.GentSolid)(msh, degree, bulk_ratio)
    y0 = 0.0 if full else YC
    top = fe.facets(lambda x: np.isclose(x[1], HEIGHT))
    low = fe.facets(lambda x: np.isclose(x[1], y0))
    fe.add_bc(0, top)
    fe.add_bc(2, top)
    uy_top = fe.add_bc(1, top)
    fe.add_bc(1, low)
    if full:
        fe.add_bc(0, low)
        fe.add_bc(2, low)
    else:
        fe.add_bc(0, fe.facets(lambda x: np.isclose(x[0], XC)))
        fe.add_bc(2, fe.facets(lambda x: np.isclose(x[2], THICKNESS / 2)))
    reaction = fe.reaction_form(1, top)
    quarter = 1.0 if full else 4.0            # the octant holds a quarter of the top face
    solution = BlockSolution(fe, full)
    names = list(PROBES)
    lattice = {(name, dx): lattice_point(PROBES[name][0], dx)
               for name in names for dx in lattice_dx}

    def set_load(lam):
        uy_top.value = (lam - 1.0) * (HEIGHT - y0)

    values = {"s": {}}
    at_lattice = {}

    def on_target(lam):
        values["s"][lam] = quarter * fem.assemble_scalar(reaction) / (WIDTH * THICKNESS)
        u = solution.values([PROBES[n][0] for n in names], lam)
        for n, un in zip(names, u):
            for c in PROBES[n][1]:
                values.setdefault(f"{n}_u{c}", {})[lam] = float(un[AXES.index(c)])
        if lattice:
            keys = list(lattice)
            ul = solution.values([lattice[k] for k in keys], lam)
            for k, uk in zip(keys, ul):
                at_lattice.setdefault(k, {})[lam] = [float(v) for v in uk]
        if verbose:
            print(f"    lambda {lam:g}: s {values['s'][lam]:.6f} kPa, "
                  + ", ".join(f"{k} {v[lam]:.6f}" for k, v in values.items() if k != "s"),
                  file=sys.stderr)

    # K = 1000 mu: a displacement step's volume error costs K times its square, so
    # Newton's basin is narrow (the line search of GentSolid keeps it going); steps
    # grow while Newton takes at most 10 iterations.
    fe.march(set_load, lambdas, on_target, dlam0=FIRST_STEP, fast_iterations=10, dlam_max=0.25,
            verbose=verbose)
    values["lattice"] = {k: (lattice[k], v) for k, v in at_lattice.items()}
    return values, gent_fe.solve_info(fe)


QUANTITIES = [("s", "s", "kPa")] + [(f"{n}_u{c}", f"{n}.u{c}", "mm")
                                    for n, (_, comps) in PROBES.items() for c in comps]


# -- the slab against plane strain -----------------------------------------------------
def solve_section(h, bulk_ratio, lambdas, slab, verbose=False):
    """The block's x-y section, quarter [0, 5] x [10, 20] less the hole: plane strain
    (slab False) or a 3D slab of thickness SLAB held in z on both faces (the 2D mesh
    extruded, one layer). Returns s, side_mid ux, ligament ux, crown uy per stretch."""
    def build(gmsh, h_):
        occ = gmsh.model.occ
        plate = occ.addRectangle(0.0, YC, 0.0, XC, HEIGHT - YC)
        disk = occ.addDisk(XC, YC, 0.0, RADIUS, RADIUS)
        cut, _ = occ.cut([(2, plate)], [(2, disk)])
        occ.synchronize()
        if not slab:
            return [tag for _, tag in cut]
        layers = occ.extrude(cut, 0, 0, SLAB, numElements=[1])
        occ.synchronize()
        return [tag for dim, tag in layers if dim == 3]
    msh = gent_fe.mesh_from_gmsh(build, h, dim=3 if slab else 2)
    fe = gent_fe.GentSolid(msh, 2, bulk_ratio, thickness=SLAB)
    top = fe.facets(lambda x: np.isclose(x[1], HEIGHT))
    fe.add_bc(0, top)
    uy_top = fe.add_bc(1, top)
    fe.add_bc(1, fe.facets(lambda x: np.isclose(x[1], YC)))
    fe.add_bc(0, fe.facets(lambda x: np.isclose(x[0], XC)))
    if slab:
        fe.add_bc(2, fe.facets(lambda x: np.isclose(x[2], 0.0) | np.isclose(x[2], SLAB)))
    reaction = fe.reaction_form(1, top)
    z = (SLAB / 2,) if slab else ()
    points = [(0.0, YC) + z, (XC - RADIUS, YC) + z, (XC, YC + RADIUS) + z]
    out = {"s": {}, "side_mid_ux": {}, "ligament_ux": {}, "crown_uy": {}}

    def set_load(lam):
        uy_top.value = (lam - 1.0) * (HEIGHT - YC)

    def on_target(lam):
        # s per unit thickness x the block's 4 mm: the same nominal stress either way.
        out["s"][lam] = 2 * fem.assemble_scalar(reaction) / (WIDTH * SLAB)
        u = gent_fe.point_values(fe.u, points)
        out["side_mid_ux"][lam] = float(u[0][0])
        out["ligament_ux"][lam] = float(u[1][0])
        out["crown_uy"][lam] = float(u[2][1]) + (lam - 1.0) * HEIGHT / 2
        if slab:
            out.setdefault("max_abs_uz", {})[lam] = float(np.max(np.abs(
                fe.u.x.array.reshape(-1, 3)[:, 2])))

    fe.march(set_load, lambdas, on_target, dlam0=FIRST_STEP, fast_iterations=10, dlam_max=0.25,
            verbose=verbose)
    return out, gent_fe.solve_info(fe)


def slab_study(sizes, bulk_ratio, lambdas, csv_path, verbose=False):
    import csv
    rows = []
    keys = ["s", "side_mid_ux", "ligament_ux", "crown_uy"]
    print("Slab held in z (1 mm, uz = 0 on both faces, the 2D mesh extruded) against plane "
          "strain, the block's section (quarter), P2, K = "
          f"{bulk_ratio:g} mu: s (kPa), side_mid ux, ligament ux, crown uy (mm)")
    for h in sizes:
        results = {}
        for slab in (False, True):
            timer = gent_fe.Timer()
            values, info = solve_section(h, bulk_ratio, lambdas, slab, verbose)
            results[slab] = values
            row = dict(model="slab_3d" if slab else "plane_strain_2d", h_mm=h,
                       cells=info["cells"], dofs=info["dofs"])
            for k in keys:
                for lam in lambdas:
                    row[f"{k}_{lam:g}"] = f"{values[k][lam]:.8f}"
            row["time_s"] = f"{timer():.1f}"
            rows.append(row)
            print(f"  {row['model']:<16} h {h:g}: {info['cells']} cells, {info['dofs']} dofs, "
                  + ", ".join(f"{k}({lam:g}) {values[k][lam]:.6f}" for k in keys
                              for lam in lambdas), flush=True)
        worst = max(abs(results[True][k][lam] - results[False][k][lam])
                    / abs(results[False][k][lam]) for k in keys for lam in lambdas)
        uz = max(results[True]["max_abs_uz"].values())
        print(f"  h {h:g}: largest relative slab - plane strain difference {worst:.1e}; "
              f"max |uz| of the slab {uz:.1e} mm")
        row = dict(model="relative_difference", h_mm=h, cells="", dofs="")
        for k in keys:
            for lam in lambdas:
                d = (results[True][k][lam] - results[False][k][lam]) / results[False][k][lam]
                row[f"{k}_{lam:g}"] = f"{d:.2e}"
        row["time_s"] = ""
        rows.append(row)
    os.makedirs(os.path.dirname(csv_path), exist_ok=True)
    with open(csv_path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {csv_path}")


# -- the convergence study and the JSON reference --------------------------------------
def block_study(args):
    solves = {}

    def solve(h, degree, bulk, lambdas):
        values, info = solve_block(h, degree, bulk, lambdas, full=args.full,
                                   refinement=args.hole_refinement,
                                   lattice_dx=args.lattice_dx if degree == 2 else (),
                                   mixed=args.mixed, verbose=args.verbose)
        solves[(degree, h)] = (values, info)
        return values, info

    args.formulations = ["compressible"]
    print(f"Block with a hole, {WIDTH:g} x {HEIGHT:g} x {THICKNESS:g} mm, hole r = {RADIUS:g} "
          f"mm along z at ({XC:g}, {YC:g}), compressible 3D Gent K = {args.bulk_ratio:g} mu, "
          f"clamped grips (bottom held, top moved (lambda - 1) {HEIGHT:g} mm), "
          f"{'whole block' if args.full else 'octant by symmetry'}, h / "
          f"{1 / args.hole_refinement:g} near the hole, "
          f"{'mixed P2-P1 (u, p)' if args.mixed else 'P2 displacement only'}: s (kPa), "
          "probe displacements (mm)")
    gent_fe.run_study(args, QUANTITIES, solve)
    write_reference(args, solves)


def write_reference(args, solves):
    """The JSON reference: the finest P2's values with the change from the one before
    (the estimated error's upper bound where the convergence is monotone and fast) and
    the Richardson extrapolation, and the values at bapd's lattice probe points."""
    p2 = sorted((h for d, h in solves if d == 2), reverse=True)
    if len(p2) < 2:
        return
    fine, prev = solves[(2, p2[-1])][0], solves[(2, p2[-2])][0]
    lambdas = sorted(args.lambdas)
    ref = {"problem": {"block_mm": [WIDTH, HEIGHT, THICKNESS], "hole_radius_mm": RADIUS,
                       "hole_axis": [XC, YC, "z"], "mu_kPa": gent_fe.MU_KPA, "Jm": gent_fe.JM,
                       "bulk_ratio": args.bulk_ratio,
                       "grips": "bottom face y = 0 held; top face y = 20 held in x, z and "
                                "moved by (lambda - 1) 20 mm in y",
                       "s": "top reaction / (10 mm x 4 mm), kPa"},
           "fe": {"element": ("Taylor-Hood P2-P1 (u, p) tetrahedra" if args.mixed else
                              "P2 tetrahedra, displacement only") + ", second-order geometry",
                  "sizes_mm": p2,
                  "hole_refinement": args.hole_refinement,
                  "dofs": [solves[(2, h)][1]["dofs"] for h in p2]},
           "probes": {n: {"point_mm": list(p), "components": c} for n, (p, c) in PROBES.items()},
           "values": {}, "lattice": {}}
    for key, _, unit in QUANTITIES:
        for lam in lambdas:
            seq = [solves[(2, h)][0][key][lam] for h in p2]
            order, ext = gent_fe.richardson(seq, p2[-2] / p2[-1])
            ref["values"][f"{key}_{lam:g}"] = {
                "unit": unit, "finest": seq[-1],
                "change_from_previous_rel": abs(seq[-1] - seq[-2]) / abs(seq[-1]),
                "observed_order": order, "extrapolated": ext,
                "estimated_error_rel": None if ext is None else abs(seq[-1] - ext) / abs(ext)}
    for (name, dx), (point, by_lam) in fine["lattice"].items():
        entry = ref["lattice"].setdefault(f"{dx:g}", {})
        _, prev_lam = prev["lattice"][(name, dx)]
        entry[name] = {"point_mm": list(point),
                       "u_mm": {f"{lam:g}": by_lam[lam] for lam in lambdas},
                       "change_from_previous_mm": {f"{lam:g}": float(np.max(np.abs(
                           np.subtract(by_lam[lam], prev_lam[lam])))) for lam in lambdas}}
    path = os.path.splitext(args.csv)[0] + ".json"
    with open(path, "w") as f:
        json.dump(ref, f, indent=1)
    print(f"wrote {path}")
    for dx, probes in ref["lattice"].items():
        for name, e in probes.items():
            print(f"  dx {dx} mm: {name} reads the lattice point {tuple(e['point_mm'])}: u = "
                  + "; ".join(f"({', '.join(f'{v:.5f}' for v in e['u_mm'][f'{lam:g}'])}) at "
                              f"{lam:g}" for lam in lambdas))


def main():
    # Refined by sqrt(2). The mixed model (the reference) takes about 27 factorisations a
    # solve; the displacement-only P2 about 140 to 280 (Newton limited by K times a volume
    # error squared), so its finest default is h = 0.71 (8.5 minutes on one core).
    ap = gent_fe.study_arguments(__doc__, [2**0.5, 1.0, 2**-0.5], [1.25, 1.5],
                                 "block_hole_3d_p2.csv")
    ap.add_argument("--full", action="store_true", help="whole block instead of the octant")
    ap.add_argument("--hole-refinement", type=float, default=0.5,
                    help="element size next to the hole over h (1: uniform)")
    ap.add_argument("--lattice-dx", type=float, nargs="*", default=[0.5, 0.25, 0.2],
                    help="bapd spacings (mm) whose probe lattice points get FE values")
    ap.add_argument("--mixed", action="store_true",
                    help="Taylor-Hood P2-P1 (u, p) instead of P2 displacement only: the same "
                         "law without volumetric locking (gent_fe.GentSolidMixed); writes "
                         "block_hole_3d.csv / .json unless --csv is given")
    ap.add_argument("--p1", action="store_true",
                    help="P1 on the finest mesh too (it locks at K = 1000 mu; slow Newton)")
    ap.add_argument("--slab", action="store_true", help="the slab / plane-strain check only")
    ap.add_argument("--all", action="store_true",
                    help="everything docs/fe_reference.md shows: the mixed reference (h down to "
                         "0.5), the displacement-only P2 study and the slab check")
    args = ap.parse_args()
    results = os.path.dirname(args.csv)
    if args.mixed and "--csv" not in sys.argv:
        args.csv = os.path.join(results, "block_hole_3d.csv")
    if args.all:
        sizes = list(args.sizes)
        args.mixed, args.sizes = True, sizes + [0.5]
        args.csv = os.path.join(results, "block_hole_3d.csv")
        block_study(args)
        args.mixed, args.sizes = False, sizes
        args.csv = os.path.join(results, "block_hole_3d_p2.csv")
        block_study(args)
    elif not args.slab:
        block_study(args)
    if args.all or args.slab:
        sizes = args.sizes[:2] if args.quick else args.sizes
        slab_study(sizes, args.bulk_ratio, sorted(args.lambdas),
                   os.path.join(results, "slab_plane_strain.csv"), args.verbose)


if __name__ == "__main__":
    main()
