"""Plane-stress Gent hyperelasticity in dolfinx 0.5 (Debian bookworm): the finite-element
reference that bapd's accuracy figures are measured against (issues 14, 18, 21).

Units: mm for lengths, kPa for stresses, so forces come out in kPa mm^2 = mN and a
force over an area in mm^2 is a stress in kPa.

The law is METHOD.md section 4 (paper eqs 24-34):
    Psi = -(mu Jm / 2) ln(1 - (I1bar - 3)/Jm) + (1/D) ((J^2 - 1)/2 - ln J),  K = 2/D,
with C = F^T F, I1bar = tr C J^(-2/3). Plane stress: F = diag(F~, lambda_3),
C33 = lambda_3^2, tr C = tr C~ + C33, J = sqrt(C33) J~.

Two formulations, both displacement-only (u in P1 or P2, no pressure field):

* incompressible (D -> 0): C33 = 1/J~^2 substituted into the energy, J = 1,
  W(F~) = -(mu Jm / 2) ln(1 - (tr C~ + J~^-2 - 3)/Jm).
* compressible (bapd's default K = 1000 mu): C33 is a field on the quadrature points
  (a "Quadrature" element), fixed by S33 = 2 dPsi/dC33 = 0 at every quadrature point
  by a local scalar Newton solve before each residual and Jacobian assembly (the same
  equation bapd solves per bond, METHOD.md section 4):
      h(C33) = G (2/3 C33 - 1/3 tr C~) + (1/D) (C33 J~^2 - 1) = 0.
  The global problem is then the condensed energy W(F~) = Psi(F~, C33(F~)), whose
  stress is dPsi/dF~ at the solved C33 (envelope theorem: dPsi/dC33 = 0) and whose
  tangent is Psi_FF - Psi_Fc (x) Psi_cF / Psi_cc (the static condensation of C33), so
  Newton converges quadratically. The constraint holds exactly at the points the
  integral uses, so no extra unknown enters the discretisation error.

Loading is displacement-driven, stepped in lambda with the dolfinx NewtonSolver
(MUMPS LU, incremental criterion); a step that fails is halved, a step that converges
in a few iterations lets the next one grow. The predictor extrapolates the last two
converged states linearly, which puts the Dirichlet values exactly where they belong.
Reactions are variationally consistent: the residual form tested with a field that is
1 (in y) on the gripped edge's dofs and 0 elsewhere.
"""
import math
import sys
import time

import numpy as np
import ufl
from mpi4py import MPI
from petsc4py import PETSc

import dolfinx
import dolfinx.fem.petsc
import dolfinx.nls.petsc
from dolfinx import fem, mesh as dmesh

from ffcx.element_interface import create_quadrature

MU_KPA = 4.55          # paper: mu = 4.55 kPa
JM = 162.6             # paper: Jm = 162.6
BULK_RATIO = 1000.0    # bapd's default K / mu (docs/options.md, -material_bulk_ratio)
VERBOSE_NEWTON = False  # the NewtonSolver's per-iteration report (debugging)


class GentPlaneStress:
    """Displacement problem of a plane-stress Gent sheet of thickness `thickness` (mm)."""

    def __init__(self, msh, degree, thickness, mu=MU_KPA, Jm=JM, bulk_ratio=None,
                 quadrature_degree=None):
        self.msh = msh
        self.degree = degree
        self.thickness = thickness
        self.mu, self.Jm = mu, Jm
        self.compressible = bulk_ratio is not None
        self.D = 2.0 / (bulk_ratio * mu) if self.compressible else None
        # 2 p: the stiffness integrand of P2 on straight triangles is of degree 2 p - 2
        # for a linear law; the Gent terms are not polynomial, the quadrature error
        # converges with the mesh and is part of the discretisation error we measure.
        self.q = quadrature_degree or 2 * degree
        md = {"quadrature_degree": self.q, "quadrature_scheme": "default"}
        self.dx = ufl.Measure("dx", domain=msh, metadata=md)

        self.V = fem.VectorFunctionSpace(msh, ("CG", degree))
        self.u = fem.Function(self.V, name="u")
        v = ufl.TestFunction(self.V)
        du = ufl.TrialFunction(self.V)
        Ft = ufl.Identity(2) + ufl.grad(self.u)
        Fv = ufl.variable(Ft)
        Ct = Fv.T * Fv
        Jt = ufl.det(Fv)
        h = thickness
        mu, Jm = self.mu, self.Jm
        if not self.compressible:
            I1 = ufl.tr(Ct) + 1.0 / Jt**2
            psi = -(mu * Jm / 2) * ufl.ln(1 - (I1 - 3) / Jm)
            self.P = ufl.diff(psi, Fv)
            self.residual = h * ufl.inner(self.P, ufl.grad(v)) * self.dx
            self.jacobian = ufl.derivative(self.residual, self.u, du)
        else:
            Qe = ufl.FiniteElement("Quadrature", msh.ufl_cell(), self.q, quad_scheme="default")
            self.Q = fem.FunctionSpace(msh, Qe)
            self.C33 = fem.Function(self.Q, name="C33")
            self.C33.x.array[:] = 1.0
            cv = ufl.variable(self.C33)
            J = ufl.sqrt(cv) * Jt
            I1bar = (ufl.tr(Ct) + cv) * J**(-2.0 / 3.0)
            psi = (-(mu * Jm / 2) * ufl.ln(1 - (I1bar - 3) / Jm)
                   + (1.0 / self.D) * ((J**2 - 1) / 2 - ufl.ln(J)))
            self.P = ufl.diff(psi, Fv)
            psi_Fc = ufl.diff(self.P, cv)
            psi_cc = ufl.diff(ufl.diff(psi, cv), cv)
            self.residual = h * ufl.inner(self.P, ufl.grad(v)) * self.dx
            # Static condensation of C33: d^2W/dF~^2 = Psi_FF - Psi_Fc (x) Psi_cF / Psi_cc.
            self.jacobian = (ufl.derivative(self.residual, self.u, du)
                             - h * ufl.inner(psi_Fc, ufl.grad(v)) * ufl.inner(psi_Fc, ufl.grad(du))
                             / psi_cc * self.dx)
            points, _ = create_quadrature(msh.ufl_cell().cellname(), self.q, "default")
            self._kin = fem.Expression(ufl.as_vector([ufl.tr(Ct), Jt]), points)
            ncells = msh.topology.index_map(2).size_local
            self._cells = np.arange(ncells, dtype=np.int32)
            self._qdofs = self.Q.dofmap.list.array.reshape(ncells, -1)
            self._nq = points.shape[0]
        self.bcs = []
        self.steps_taken = 0
        self.newton_iterations = 0

    # -- compressible plane stress: the local S33 = 0 solve ---------------------------
    def s33_residual(self, c, trCt, Jt):
        """h(C33) = C33 S33 (METHOD.md section 4); written so that complex c works."""
        mu, Jm, D = self.mu, self.Jm, self.D
        Jm23 = (c * Jt**2) ** (-1.0 / 3.0)
        G = mu * Jm * Jm23 / (Jm + 3 - (trCt + c) * Jm23)
        return G * (2.0 * c / 3.0 - trCt / 3.0) + (c * Jt**2 - 1.0) / D

    def solve_c33(self, trCt, Jt, c0):
        """Vectorised Newton on h(C33) = 0, derivative by complex step (exact to round-off)."""
        c = c0.copy()
        for _ in range(60):
            hc = self.s33_residual(c + 1e-30j * c, trCt, Jt)
            step = hc.real / (hc.imag / (1e-30 * c))
            c_new = c - step
            # Guard: C33 > 0 (halve towards 0 instead of crossing it).
            c_new = np.where(c_new > 0, c_new, 0.5 * c)
            done = np.all(np.abs(c_new - c) <= 1e-14 * np.abs(c))
            c = c_new
            if done:
                break
        else:
            raise RuntimeError("local S33 = 0 solve did not converge")
        if not np.all(np.isfinite(c)):
            raise RuntimeError("local S33 = 0 solve gave a non-finite C33")
        return c

    def update_c33(self):
        vals = self._kin.eval(self._cells).reshape(len(self._cells), self._nq, 2)
        trCt = vals[:, :, 0].ravel()
        Jt = vals[:, :, 1].ravel()
        if np.any(Jt <= 0):
            raise RuntimeError("inverted element (J~ <= 0)")
        c0 = self.C33.x.array[self._qdofs].ravel()
        c0 = np.where(np.isfinite(c0) & (c0 > 0), c0, 1.0 / Jt**2)
        c = self.solve_c33(trCt, Jt, c0)
        self.C33.x.array[self._qdofs.ravel()] = c

    def s33_check(self):
        """Largest |h(C33)| D over the quadrature points (0 up to round-off)."""
        vals = self._kin.eval(self._cells).reshape(len(self._cells), self._nq, 2)
        c = self.C33.x.array[self._qdofs].ravel()
        return float(np.max(np.abs(self.s33_residual(c, vals[:, :, 0].ravel(),
                                                     vals[:, :, 1].ravel())) * self.D))

    # -- boundary conditions ------------------------------------------------------------
    def facets(self, marker):
        return dmesh.locate_entities_boundary(self.msh, 1, marker)

    def dofs(self, component, facets):
        return fem.locate_dofs_topological(self.V.sub(component), 1, facets)

    def add_bc(self, component, facets, value=0.0):
        """u_component = value on the facets; returns the Constant to move it."""
        c = fem.Constant(self.msh, PETSc.ScalarType(value))
        self.bcs.append(fem.dirichletbc(c, self.dofs(component, facets), self.V.sub(component)))
        return c

    def reaction_form(self, component, facets):
        """Form of the consistent reaction in `component` on the facets' dofs."""
        w = fem.Function(self.V)
        w.x.array[self.dofs(component, facets)] = 1.0
        return fem.form(self.thickness * ufl.inner(self.P, ufl.grad(w)) * self.dx)

    # -- Newton with load stepping ------------------------------------------------------
    def _make_solver(self):
        problem = _Problem(self)
        solver = dolfinx.nls.petsc.NewtonSolver(MPI.COMM_WORLD, problem)
        solver.convergence_criterion = "incremental"
        # The correction's l2 norm (mm) stalls at 1e-11..1e-10 from round-off; Newton
        # converges quadratically (1e-5 -> 1e-10), so 1e-8 mm leaves the reactions exact to
        # about 1e-12 and never waits on the round-off floor.
        solver.rtol = 1e-12
        solver.atol = 1e-8
        solver.max_it = 12
        solver.error_on_nonconvergence = False
        solver.report = VERBOSE_NEWTON
        ksp = solver.krylov_solver
        ksp.setType("preonly")
        ksp.getPC().setType("lu")
        ksp.getPC().setFactorSolverType("mumps")
        return problem, solver

    def march(self, set_load, targets, on_target, dlam0=0.05, dlam_max=0.2,
              dlam_min=1e-4, fast_iterations=4, verbose=False):
        """Steps lambda from 1 through the sorted targets. set_load(lam) moves the
        Dirichlet Constants; on_target(lam) is called at each target (converged)."""
        if not hasattr(self, "_solver"):
            self._problem, self._solver = self._make_solver()
        lam, dlam = 1.0, dlam0
        set_load(lam)
        u_old = self.u.x.array.copy()        # converged at lam
        u_older, lam_older = u_old.copy(), lam
        c_old = self.C33.x.array.copy() if self.compressible else None
        for target in targets:
            while lam < target - 1e-12:
                step = min(dlam, target - lam)
                lam_new = lam + step
                # Linear extrapolation of the last two converged states.
                if lam > lam_older:
                    ratio = step / (lam - lam_older)
                    self.u.x.array[:] = u_old + ratio * (u_old - u_older)
                else:
                    self.u.x.array[:] = u_old
                set_load(lam_new)
                ok = True
                try:
                    n, converged = self._solver.solve(self.u)
                    ok = converged and np.all(np.isfinite(self.u.x.array))
                except RuntimeError:
                    ok, n = False, 0
                if not ok:
                    self.u.x.array[:] = u_old
                    if self.compressible:
                        self.C33.x.array[:] = c_old
                    dlam = step / 2
                    if verbose:
                        print(f"    lambda {lam_new:.5f}: no convergence, step -> {dlam:.2e}",
                              file=sys.stderr)
                    if dlam < dlam_min:
                        raise RuntimeError(f"load stepping stalled at lambda = {lam:.5f}")
                    continue
                self.steps_taken += 1
                self.newton_iterations += n
                u_older, lam_older = u_old, lam
                u_old = self.u.x.array.copy()
                if self.compressible:
                    c_old = self.C33.x.array.copy()
                lam = lam_new
                if n <= fast_iterations and step == dlam:
                    dlam = min(1.5 * dlam, dlam_max)
            on_target(lam)


class _Problem(dolfinx.fem.petsc.NonlinearProblem):
    """NonlinearProblem whose form() also solves S33 = 0 at the quadrature points."""

    def __init__(self, gent):
        super().__init__(gent.residual, gent.u, gent.bcs, gent.jacobian)
        self.gent = gent

    def form(self, x):
        super().form(x)
        if self.gent.compressible:
            self.gent.update_c33()


def formulation_name(bulk_ratio):
    return "incompressible" if bulk_ratio is None else f"K={bulk_ratio:g}mu"


def dofs_of(problem):
    im = problem.V.dofmap.index_map
    return (im.size_local + im.num_ghosts) * problem.V.dofmap.index_map_bs


def richardson(values, ratio=2.0):
    """Observed order and extrapolated value from the three finest of a sequence of
    results on meshes refined by `ratio`; None where the differences do not shrink."""
    if len(values) < 3:
        return None, None
    a, b, c = values[-3:]
    d1, d2 = b - a, c - b
    if d1 == 0 or d2 == 0 or d2 / d1 <= 0 or abs(d2) >= abs(d1):
        return None, None
    p = math.log(abs(d1 / d2)) / math.log(ratio)
    return p, c + d2 / (ratio**p - 1)


def pure_shear_analytic(lam, mu=MU_KPA, Jm=JM):
    """Paper eq 36: incompressible homogeneous pure shear, nominal stress (kPa)."""
    return mu * Jm * (lam - lam**-3) / (Jm - lam**2 - lam**-2 + 2)


class Timer:
    def __init__(self):
        self.t0 = time.perf_counter()

    def __call__(self):
        return time.perf_counter() - self.t0
