#!/usr/bin/python3
"""Self-check of scripts/fe/gent_fe.py against closed forms (the light ctest fe.homogeneous).

A unit square (1 mm, t = 1 mm) held in x on every edge, bottom fixed, top moved by
lambda - 1: the exact solution is homogeneous pure shear F~ = diag(1, lambda), which P1
and P2 represent exactly, so the consistent top reaction must equal P_yy to round-off:
  incompressible: paper eq 36, s = mu Jm (lambda - lambda^-3) / (Jm - lambda^2 - lambda^-2 + 2);
  compressible:   P~ = G (F~ - C33 F~^-T) (docs/method.md section 4) with C33 from S33 = 0
                  found here by bisection, independently of the FE code's Newton.
Exit 0 on agreement, 1 on a mismatch, 77 (ctest SKIP_RETURN_CODE) without dolfinx.
"""
import os
import sys

try:
    import numpy as np
    from mpi4py import MPI
    from dolfinx import mesh as dmesh
except ImportError as e:
    print(f"check_homogeneous: skipped, dolfinx is not installed ({e}); "
          "scripts/fe/install-fe-deps.sh installs it")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402


def compressible_pure_shear(lam, bulk_ratio, mu=gent_fe.MU_KPA, Jm=gent_fe.JM):
    """P_yy of F~ = diag(1, lambda), C33 from S33 = 0 by bisection."""
    D = 2.0 / (bulk_ratio * mu)
    trCt, Jt = 1.0 + lam**2, lam

    def g(c):  # C33 S33, increasing in C33
        J = np.sqrt(c) * Jt
        I1bar = (trCt + c) * J ** (-2.0 / 3.0)
        G = mu * Jm * J ** (-2.0 / 3.0) / (Jm - I1bar + 3)
        return G * (2 * c / 3 - trCt / 3) + (c * Jt**2 - 1) / D

    lo, hi = 1e-6, 10.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if g(mid) < 0 else (lo, mid)
    c = 0.5 * (lo + hi)
    J = np.sqrt(c) * Jt
    I1bar = (trCt + c) * J ** (-2.0 / 3.0)
    G = mu * Jm * J ** (-2.0 / 3.0) / (Jm - I1bar + 3)
    return G * (lam - c / lam)


def main():
    lambdas = [1.5, 3.0]
    failures = 0
    for degree in (1, 2):
        for bulk in (None, 1000.0, 10.0):
            msh = dmesh.create_unit_square(MPI.COMM_WORLD, 3, 3)
            fe = gent_fe.GentPlaneStress(msh, degree, 1.0, bulk_ratio=bulk)
            top = fe.facets(lambda x: np.isclose(x[1], 1.0))
            every = fe.facets(lambda x: np.full(x.shape[1], True))
            fe.add_bc(0, every)
            fe.add_bc(1, fe.facets(lambda x: np.isclose(x[1], 0.0)))
            uy = fe.add_bc(1, top)
            reaction = fe.reaction_form(1, top)
            got = {}

            def set_load(lam):
                uy.value = lam - 1.0

            def on_target(lam):
                got[lam] = gent_fe.fem.assemble_scalar(reaction)

            fe.march(set_load, lambdas, on_target)
            for lam in lambdas:
                want = (gent_fe.pure_shear_analytic(lam) if bulk is None
                        else compressible_pure_shear(lam, bulk))
                err = abs(got[lam] - want) / want
                # Exact representation: only round-off and the Newton tolerance remain.
                ok = err < 1e-9
                failures += not ok
                print(f"P{degree} {gent_fe.formulation_name(bulk):<15} lambda {lam:g}: "
                      f"FE {got[lam]:.12f} kPa, closed form {want:.12f} kPa, "
                      f"rel. error {err:.1e} {'ok' if ok else 'FAIL'}")
            if fe.compressible:
                r = fe.s33_check()
                ok = r < 1e-12
                failures += not ok
                print(f"    max |S33 C33| D at the quadrature points: {r:.1e} "
                      f"{'ok' if ok else 'FAIL'}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
