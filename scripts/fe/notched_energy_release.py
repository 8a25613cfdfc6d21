#!/usr/bin/python3
"""FE reference for the crack-driving force of the notched pure-shear sheet
(examples/notched_pure_shear.yaml; docs/validation.md section 3): the energy release rate
G(lambda) that a fracture-energy failure criterion is to be validated against.

The sheet: 70 mm wide, H0 = 10 mm between the grips, thickness t = 3 mm, an edge notch
of length a entering from the right edge at mid-height (a traction-free slit), plane-
stress Gent (mu = 4.55 kPa, Jm = 162.6; incompressible by default, --formulations
compressible for K = 1000 mu). Grips as bapd's default (docs/options.md, "Loading"):
clamps outside the specimen, so the free sheet is the body, 10 mm high; bottom edge
held, top edge held in x and moved by (lambda - 1) H0; side edges and notch free.

Symmetry: the mode-I edge notch of this sheet is symmetric about y = 5 mm (with the top
moving by d, uy = d/2 and the shear traction vanishes there). The upper half
[0, 70] x [5, 10] mm is solved, with uy = d/2 on the ligament only (x <= 70 - a, the
line ahead of the tip); the notch face (x > 70 - a) is free. This is exact.

Energy release rate at fixed grips, per unit crack area (the crack face area a t of
one face, the usual convention):
    G(lambda) = -(Pi(a + da) - Pi(a - da)) / (2 da t),   Pi = t int_sheet W dA
              = -(E(a + da) - E(a - da)) / da,           E = int_upper_half W dA
(Pi = 2 t E: the whole sheet is twice the half.) The two notch lengths are solved on
the SAME mesh, whose y = 5 line has vertices at 70 - a -+ da: only the end of the held
segment moves, so the discretisation errors away from the tip cancel in the
difference. Beside it the J-integral (domain form, q = 1 within 1 mm of the tip,
falling linearly to 0 at 4 mm), averaged over the tips at a -+ da:
    G_J = 2 int_half e.(F^T P - W I).grad q dA
with e = (-1, 0) the direction of crack growth, F^T P - W I minus Eshelby's tensor
(the factor 2: both halves; on the ligament F_21 = 0 and P_12 = 0, so the symmetry line
adds nothing).

Rivlin-Thomas (long notch and ligament, steady state): G = W(lambda) H0, with W the
incompressible plane-stress Gent energy density in pure shear,
    W = -(mu Jm / 2) ln(1 - (lambda^2 + lambda^-2 - 2)/Jm).

Units: mm and kPa. E is in kPa mm^2 (energy per mm of thickness) and Pi in kPa mm^3 =
1e3 N/m^2 x 1e-9 m^3 = 1e-6 J (uJ); so G = -dE/da is in kPa mm = 1e3 N/m^2 x 1e-3 m =
1 N/m = 1 J/m^2, and W H0 likewise: kPa x mm = J/m^2. No other conversion enters.

Inverse: for each fracture energy Gamma (J/m^2) the critical stretch lambda_c with
G(lambda_c) = Gamma, per notch length: the ratio G / (W H0) is interpolated linearly in
lambda between the computed stretches (it is smooth and near 1) and
W(lambda) H0 ratio(lambda) = Gamma is solved for lambda; Rivlin-Thomas's lambda_c
solves W(lambda) H0 = Gamma.

Meshes (gmsh, P2, straight edges): element size h away from the tip, h / --tip-ratio
within da_max + 0.5 mm of the tip segment [70 - a - da_max, 70 - a + da_max], growing
linearly to h at 8 mm. Convergence: the meshes of --sizes (coarse to fine, halved),
Richardson from the three finest. The finite-difference step is checked with the
second --delta-a on the second-finest mesh (--check-size).

Writes --csv (default tests/data/fe/notched_energy_release.csv; with --quick,
scripts/fe/results/notched_energy_release_quick.csv): one row per formulation, mesh,
da, notch length and stretch, plus Richardson rows (mesh_h_mm = 0).
"""
import csv
import math
import os
import sys

import numpy as np
import ufl

from dolfinx import fem

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402

WIDTH, HEIGHT, THICKNESS = 70.0, 10.0, 3.0    # mm: the free sheet, H0 = HEIGHT
MID = HEIGHT / 2                               # the notch line, y = 5 mm
J_INNER, J_OUTER = 1.0, 4.0                    # mm: the J-integral's q support
HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def rivlin_thomas(lam, mu=gent_fe.MU_KPA, Jm=gent_fe.JM, H0=HEIGHT):
    """W(lambda) H0 (kPa mm = J/m^2): incompressible plane-stress Gent in pure shear."""
    return -(mu * Jm / 2) * math.log(1 - (lam**2 + lam**-2 - 2) / Jm) * H0


def build_half(a, das, h, tip_ratio):
    """gmsh builder of the upper half with vertices on y = 5 at 70 - a -+ da."""
    xt = WIDTH - a
    dmax = max(das)

    def build(gmsh, hh):
        occ = gmsh.model.occ
        xs = sorted({0.0, xt, WIDTH} | {xt - d for d in das} | {xt + d for d in das})
        bottom = [occ.addPoint(x, MID, 0) for x in xs]
        top = [occ.addPoint(WIDTH, HEIGHT, 0), occ.addPoint(0.0, HEIGHT, 0)]
        ring = bottom + top
        lines = [occ.addLine(ring[i], ring[(i + 1) % len(ring)]) for i in range(len(ring))]
        surface = occ.addPlaneSurface([occ.addCurveLoop(lines)])
        occ.synchronize()
        near = [lines[i] for i in range(len(xs) - 1)
                if xs[i] >= xt - dmax - 1e-9 and xs[i + 1] <= xt + dmax + 1e-9]
        gent_fe.refine_near(gmsh, "CurvesList", near, hh / tip_ratio, hh, dmax + 0.5, 8.0, 200)
        return [surface]

    return build


def energy_density(fe):
    """W (UFL) of the solved state: the condensed plane-stress Gent energy."""
    Ft = ufl.Identity(2) + ufl.grad(fe.u)
    Ct = Ft.T * Ft
    Jt = ufl.det(Ft)
    if fe.compressible:
        return gent_fe.gent_compressible(ufl.tr(Ct) + fe.C33, ufl.sqrt(fe.C33) * Jt,
                                         fe.mu, fe.Jm, fe.D)
    return gent_fe.gent_isochoric(ufl.tr(Ct) + 1.0 / Jt**2, fe.mu, fe.Jm)


def solve_release(msh, degree, bulk_ratio, lambdas, x_release, x_tip_q, verbose=False):
    """The upper half with the ligament held for x <= x_release: E (kPa mm^2) and the
    half J-integral about (x_tip_q, 5) (kPa mm) at each stretch."""
    fe = gent_fe.GentPlaneStress(msh, degree, THICKNESS, bulk_ratio=bulk_ratio)
    top = fe.facets(lambda x: np.isclose(x[1], HEIGHT))
    lig = fe.facets(lambda x: np.isclose(x[1], MID) & (x[0] <= x_release + 1e-9))
    fe.add_bc(0, top)
    uy_top = fe.add_bc(1, top)
    uy_lig = fe.add_bc(1, lig)

    W = energy_density(fe)
    energy = fem.form(W * fe.dx)
    Vq = fem.FunctionSpace(msh, ("CG", degree))
    q = fem.Function(Vq)
    q.interpolate(lambda x: np.clip((J_OUTER - np.hypot(x[0] - x_tip_q, x[1] - MID))
                                    / (J_OUTER - J_INNER), 0.0, 1.0))
    Ft = ufl.Identity(2) + ufl.grad(fe.u)
    e = ufl.as_vector([-1.0, 0.0])
    sigma = Ft.T * fe.P - W * ufl.Identity(2)        # minus Eshelby's tensor
    jform = fem.form(ufl.dot(e, sigma * ufl.grad(q)) * fe.dx)

    def set_load(lam):
        d = (lam - 1.0) * HEIGHT
        uy_top.value = d
        uy_lig.value = d / 2

    E, J = {}, {}

    def on_target(lam):
        fe.update_local()
        E[lam] = fem.assemble_scalar(energy)
        J[lam] = fem.assemble_scalar(jform)
        if verbose:
            print(f"    x_release {x_release:g} lambda {lam:g}: E {E[lam]:.8f} kPa mm^2, "
                  f"J_half {J[lam]:.6f} kPa mm", file=sys.stderr)

    fe.march(set_load, lambdas, on_target, verbose=verbose)
    return E, J, gent_fe.solve_info(fe)


def energy_release(a, da, das, h, tip_ratio, degree, bulk_ratio, lambdas, verbose=False):
    """G (FD of the energy) and G_J (J-integral) in J/m^2 per stretch for notch a,
    both notch lengths a -+ da on one mesh built with vertices for every da in das."""
    msh = gent_fe.mesh_from_gmsh(build_half(a, das, h, tip_ratio), h)
    xt = WIDTH - a
    # Notch a - da: held up to xt + da; notch a + da: held up to xt - da.
    E_short, J_short, info = solve_release(msh, degree, bulk_ratio, lambdas, xt + da, xt + da,
                                           verbose)
    E_long, J_long, info2 = solve_release(msh, degree, bulk_ratio, lambdas, xt - da, xt - da,
                                          verbose)
    G = {lam: -(E_long[lam] - E_short[lam]) / da for lam in lambdas}
    GJ = {lam: J_short[lam] + J_long[lam] for lam in lambdas}   # 2 x the mean half J
    info = dict(info, steps=info["steps"] + info2["steps"],
                newton=info["newton"] + info2["newton"], s33=max(info["s33"], info2["s33"]))
    return G, GJ, info


def critical_stretch(gamma, lambdas, ratio):
    """lambda with W(lambda) H0 r(lambda) = gamma, r interpolated linearly in lambda
    (constant beyond the ends); None outside the computed stretches."""
    lams = np.array(lambdas)
    r = np.array([ratio[l] for l in lambdas])
    f = lambda lam: rivlin_thomas(lam) * np.interp(lam, lams, r) - gamma  # noqa: E731
    if f(lams[0]) > 0 or f(lams[-1]) < 0:
        return None
    return bisect(f, lams[0], lams[-1])


def bisect(f, lo, hi, tol=1e-10):
    flo = f(lo)
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        fm = f(mid)
        if (fm > 0) == (flo > 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main():
    lambdas = [round(1.2 + 0.2 * i, 10) for i in range(15)]      # 1.2 .. 4.0
    ap = gent_fe.study_arguments(__doc__, [1.0, 0.5, 0.25], lambdas,
                                 "notched_energy_release_quick.csv")
    ap.set_defaults(formulations=["incompressible"], csv=None)
    ap.add_argument("--notches", type=float, nargs="+", default=[15.0, 20.0, 30.0],
                    help="notch lengths a (mm)")
    ap.add_argument("--delta-a", type=float, nargs="+", default=[1.0, 0.5],
                    help="finite-difference half steps da (mm): the first on every mesh, "
                         "the others on --check-size's mesh (the check)")
    ap.add_argument("--check-size", type=float, default=None,
                    help="h (mm) of the mesh on which the other da run (default the "
                         "second finest of --sizes: the finest costs 5x as much)")
    ap.add_argument("--tip-ratio", type=float, default=8.0,
                    help="element size at the tip = h / tip-ratio (default 8)")
    ap.add_argument("--gammas", type=float, nargs="+", default=[100.0, 165.0, 300.0],
                    help="fracture energies (J/m^2) for the critical stretch")
    args = ap.parse_args()
    if args.quick:
        args.sizes = args.sizes[:2]
        args.notches = [20.0]
        args.lambdas = [2.0, 3.0, 4.0]
        args.delta_a = args.delta_a[:1]
    if args.csv is None:
        args.csv = (os.path.join(HERE, "results", "notched_energy_release_quick.csv")
                    if args.quick else
                    os.path.join(ROOT, "tests", "data", "fe", "notched_energy_release.csv"))
    lams = sorted(args.lambdas)
    das = args.delta_a
    print(f"Notched pure shear, 70 x {HEIGHT:g} mm between the grips, t = {THICKNESS:g} mm, "
          f"edge notch a at mid-height, upper half by symmetry, plane-stress Gent: "
          f"G = -dPi/(t da) (J/m^2) at fixed grips, by central differences +-da on one mesh, "
          f"and by the J-integral; Rivlin-Thomas W H0 (J/m^2)")
    rows, summary = [], {}
    for form in args.formulations:
        bulk = None if form == "incompressible" else args.bulk_ratio
        name = gent_fe.formulation_name(bulk)
        for a in args.notches:
            print(f"\n{name}, a = {a:g} mm")
            print(f"{'h_mm':>6} {'h_tip':>7} {'da':>5} {'cells':>7} {'dofs':>7} "
                  + " ".join(f"{'G(' + format(l, 'g') + ')':>9}" for l in lams)
                  + f" {'steps':>5} {'newton':>6} {'time_s':>7}")
            check = args.check_size or args.sizes[-2 if len(args.sizes) > 1 else -1]
            runs = [(h, das[0]) for h in args.sizes] + [(check, d) for d in das[1:]]
            results = {}
            for h, da in runs:
                timer = gent_fe.Timer()
                G, GJ, info = energy_release(a, da, das, h, args.tip_ratio, 2, bulk, lams,
                                             args.verbose)
                t = timer()
                results[(h, da)] = (G, GJ)
                print(f"{h:>6.4g} {h / args.tip_ratio:>7.4g} {da:>5.3g} {info['cells']:>7} "
                      f"{info['dofs']:>7} " + " ".join(f"{G[l]:>9.4f}" for l in lams)
                      + f" {info['steps']:>5} {info['newton']:>6} {t:>7.1f}", flush=True)
                print(f"{'':>6} {'':>7} {'J':>5} {'':>7} {'':>7} "
                      + " ".join(f"{GJ[l]:>9.4f}" for l in lams), flush=True)
                for l in lams:
                    rt = rivlin_thomas(l)
                    rows.append(dict(formulation=name, stretch=f"{l:g}", notch_mm=f"{a:g}",
                                     delta_a_mm=f"{da:g}", mesh_h_mm=f"{h:g}",
                                     mesh_h_tip_mm=f"{h / args.tip_ratio:g}",
                                     cells=info["cells"], dofs=info["dofs"],
                                     G_J_per_m2=f"{G[l]:.6f}",
                                     G_Jintegral_J_per_m2=f"{GJ[l]:.6f}",
                                     rivlin_thomas_J_per_m2=f"{rt:.6f}",
                                     G_over_rivlin_thomas=f"{G[l] / rt:.6f}",
                                     time_s=f"{t:.1f}"))
            # Mesh convergence of G at the first da.
            series = {l: [results[(h, das[0])][0][l] for h in args.sizes] for l in lams}
            ratio_h = args.sizes[-2] / args.sizes[-1] if len(args.sizes) > 1 else 2.0
            best = {}
            for l in lams:
                p, ext = gent_fe.richardson(series[l], ratio_h)
                if p is not None and p < 1:
                    # Below first order the differences are the unstructured meshes'
                    # noise, not a converging sequence: no extrapolation.
                    p, ext = None, None
                fine = series[l][-1]
                best[l] = fine
                rt = rivlin_thomas(l)
                text = ""
                for d in das[1:]:
                    g1 = results[(check, das[0])][0][l]
                    gd = results[(check, d)][0][l]
                    text += f"; h = {check:g}, da = {d:g}: {gd:.4f} ({(gd - g1) / g1:+.1e})"
                gj = results[(args.sizes[-1], das[0])][1][l]
                if ext is None:
                    diffs = " ".join(f"{x:+.1e}" for x in np.diff(series[l]))
                    est = f"no Richardson estimate (differences {diffs})"
                else:
                    est = (f"order {p:.2f}, extrapolated {ext:.4f}, est. rel. error "
                           f"{abs(fine - ext) / abs(ext):.1e}")
                    rows.append(dict(formulation=name, stretch=f"{l:g}", notch_mm=f"{a:g}",
                                     delta_a_mm=f"{das[0]:g}", mesh_h_mm="0",
                                     mesh_h_tip_mm="0", cells="", dofs="",
                                     G_J_per_m2=f"{ext:.6f}", G_Jintegral_J_per_m2="",
                                     rivlin_thomas_J_per_m2=f"{rt:.6f}",
                                     G_over_rivlin_thomas=f"{ext / rt:.6f}", time_s=""))
                print(f"  G({l:g}) = {fine:.4f} J/m^2 (W H0 {rt:.4f}, ratio {fine / rt:.4f}); "
                      f"{est}; J-integral {gj:.4f} ({(gj - fine) / fine:+.1e}){text}")
            summary[(name, a)] = {l: best[l] / rivlin_thomas(l) for l in lams}
    print("\nCritical stretch lambda_c with G(lambda_c) = Gamma (finest mesh, da = "
          f"{das[0]:g} mm; G / (W H0) interpolated linearly in lambda)")
    print(f"{'formulation':<15} {'a_mm':>5} " + " ".join(f"{'G=' + format(g, 'g'):>8}"
                                                      for g in args.gammas))
    for (name, a), ratio in summary.items():
        lc = [critical_stretch(g, lams, ratio) for g in args.gammas]
        print(f"{name:<15} {a:>5g} " + " ".join(f"{x:>8.4f}" if x else f"{'-':>8}" for x in lc))
    one = {l: 1.0 for l in lams}
    lc = [critical_stretch(g, lams, one) for g in args.gammas]
    print(f"{'Rivlin-Thomas':<15} {'':>5} " + " ".join(f"{x:>8.4f}" if x else f"{'-':>8}"
                                                      for x in lc))
    os.makedirs(os.path.dirname(os.path.abspath(args.csv)), exist_ok=True)
    with open(args.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {args.csv}")


if __name__ == "__main__":
    main()
