#!/usr/bin/python3
"""Self-check of gent_fe.GentSolid (3D and plane-strain compressible Gent, the law of
block_hole_3d.py) against the closed form of paper eq 26 (the light ctest
fe.homogeneous_solid).

A unit cube (and a unit square in plane strain) whose whole boundary follows a general
homogeneous deformation x = F X (shear, stretch and a volume change in every component):
the exact solution is that affine field, which P1 and P2 represent exactly, so Newton must
find it and the mean first Piola-Kirchhoff stress (1/V) int P dV must equal
    P = G J^(-2/3) (F - tr C / 3 F^-T) + (1/D) (J^2 - 1) F^-T,  G = mu Jm / (Jm - I1bar + 3)
(bapd's Compressible3D, include/bapd/core/materials/hyperelastic.hpp; plane strain: F = diag(F~, 1), the
in-plane block) to round-off, evaluated here in numpy, independently of the UFL energy.
The interior is checked too: max |u - (F - I) X| at the dofs. Exit 0 on agreement, 1 on a
mismatch, 77 (ctest SKIP_RETURN_CODE) without dolfinx.
"""
import os
import sys

try:
    import numpy as np
    from mpi4py import MPI
    from dolfinx import fem, mesh as dmesh
except ImportError as e:
    print(f"check_homogeneous_solid: skipped, dolfinx is not installed ({e}); "
          "scripts/fe/install-fe-deps.sh installs it")
    sys.exit(77)

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gent_fe  # noqa: E402

# J = det F = 1.3 in 3D, 1.43 in plane strain: far enough from 1 that the volumetric term
# is exercised at K = 10 mu and 1000 mu alike.
F3 = np.array([[1.2, 0.3, -0.1], [0.15, 1.4, 0.2], [0.05, -0.25, 0.8]])
F2 = np.array([[1.1, 0.4], [-0.2, 1.3]])


def closed_form_P(F, bulk_ratio, mu=gent_fe.MU_KPA, Jm=gent_fe.JM):
    D = 2.0 / (bulk_ratio * mu)
    J = np.linalg.det(F)
    trC = np.sum(F * F)
    q = J ** (-2.0 / 3.0)
    G = mu * Jm / (Jm - trC * q + 3.0)
    Finv_t = np.linalg.inv(F).T
    return G * q * (F - trC / 3.0 * Finv_t) + (J * J - 1.0) / D * Finv_t


def check(dim, degree, bulk_ratio, mixed=False):
    if dim == 3:
        msh = dmesh.create_unit_cube(MPI.COMM_WORLD, 2, 2, 2)
        F = F3
    else:
        msh = dmesh.create_unit_square(MPI.COMM_WORLD, 3, 3)
        F = F2
    if mixed:
        fe = gent_fe.GentSolidMixed(msh, degree, bulk_ratio)
        V, _ = fe.space.sub(0).collapse()
        target = fem.Function(V)
        fe_boundary = fe.facets(lambda x: np.full(x.shape[1], True))
        dofs = fem.locate_dofs_topological((fe.space.sub(0), V), dim - 1, fe_boundary)
        fe.bcs.append(fem.dirichletbc(target, dofs, fe.space.sub(0)))
    else:
        fe = gent_fe.GentSolid(msh, degree, bulk_ratio)
        boundary = fe.facets(lambda x: np.full(x.shape[1], True))
        target = fem.Function(fe.V)
        fe.bcs.append(fem.dirichletbc(target, fem.locate_dofs_topological(fe.V, dim - 1,
                                                                          boundary)))
    H = F - np.eye(dim)

    def set_load(t):
        # t runs from 1 to 2: u = (t - 1) (F - I) X on the boundary.
        target.interpolate(lambda x: (t - 1.0) * (H @ x[:dim]))

    got = {}

    def on_target(t):
        # The domain's volume is 1: int P dV is the mean stress, component by component.
        got["P"] = np.array([[fem.assemble_scalar(fem.form(fe.P[i, j] * fe.dx))
                              for j in range(dim)] for i in range(dim)])

    fe.march(set_load, [2.0], on_target, dlam0=0.25)
    u = fe.displacement()
    exact_u = fem.Function(u.function_space)
    exact_u.interpolate(lambda x: H @ x[:dim])
    u_err = float(np.max(np.abs(u.x.array - exact_u.x.array)))
    want = closed_form_P(F if dim == 3 else np.pad(F, (0, 1)) + np.diag([0, 0, 1.0]), bulk_ratio)
    want = want[:dim, :dim]
    err = float(np.max(np.abs(got["P"] - want)) / np.max(np.abs(want)))
    # Exact representation: only round-off and the Newton tolerance (1e-8 mm) remain.
    ok = err < 1e-9 and u_err < 1e-9
    name = "3D mixed P2-P1" if mixed else f"{'3D' if dim == 3 else 'plane strain'} P{degree}"
    print(f"{name} K={bulk_ratio:g}mu: mean P vs eq 26 "
          f"rel. error {err:.1e}, max |u - (F - I) X| {u_err:.1e} mm {'ok' if ok else 'FAIL'}")
    return ok


def main():
    failures = 0
    for dim in (3, 2):
        for degree in (1, 2):
            for bulk in (1000.0, 10.0):
                failures += not check(dim, degree, bulk)
    failures += not check(3, 2, 1000.0, mixed=True)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
