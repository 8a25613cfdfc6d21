"""Gent hyperelasticity in dolfinx 0.5 (Debian bookworm): the finite-element references
that bapd's accuracy figures are measured against (docs/fe_reference.md). Plane stress
(GentPlaneStress, below); the compressible 3D and plane-strain law of bapd's
Compressible3D and PlaneStrain (GentSolid: displacement only; GentSolidMixed: 3D,
Taylor-Hood u-p, free of volumetric locking), all on GentProblem's load stepping.

Units: mm for lengths, kPa for stresses, so forces come out in kPa mm^2 = mN and a
force over an area in mm^2 is a stress in kPa.

The law is docs/method.md section 4 (paper eqs 24-34):
    Psi = -(mu Jm / 2) ln(1 - (I1bar - 3)/Jm) + (1/D) ((J^2 - 1)/2 - ln J),  K = 2/D,
with C = F^T F, I1bar = tr C J^(-2/3). Plane stress: F = diag(F~, lambda_3),
C33 = lambda_3^2, tr C = tr C~ + C33, J = sqrt(C33) J~.

Two formulations, both displacement-only (u in P1 or P2, no pressure field):

* incompressible (D -> 0): C33 = 1/J~^2 substituted into the energy, J = 1,
  W(F~) = -(mu Jm / 2) ln(1 - (tr C~ + J~^-2 - 3)/Jm).
* compressible (bapd's default K = 1000 mu): C33 is a field on the quadrature points
  (a "Quadrature" element), fixed by S33 = 2 dPsi/dC33 = 0 at every quadrature point
  by a local scalar Newton solve before each residual and Jacobian assembly (the same
  equation bapd solves per bond, docs/method.md section 4):
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

from newton_line_search import NewtonLineSearch, direct_solver

MU_KPA = 4.55          # paper: mu = 4.55 kPa
JM = 162.6             # paper: Jm = 162.6
BULK_RATIO = 1000.0    # bapd's default K / mu (docs/options.md, -material_bulk_ratio)
VERBOSE_NEWTON = False  # the NewtonSolver's per-iteration report (debugging)


def gent_isochoric(I1bar, mu, Jm):
    """Paper eq 24's isochoric term, -(mu Jm / 2) ln(1 - (I1bar - 3)/Jm) (UFL)."""
    return -(mu * Jm / 2) * ufl.ln(1 - (I1bar - 3) / Jm)


def gent_compressible(trC, J, mu, Jm, D):
    """Psi of docs/method.md section 4 from tr C and J (UFL): the isochoric term at
    I1bar = tr C J^(-2/3) plus (1/D) ((J^2 - 1)/2 - ln J); bapd's Compressible3D
    (include/bapd/core/materials/hyperelastic.hpp), PlaneStrain (J = J~, tr C = tr C~ + 1) and
    PlaneStress (C33 solved) are this energy."""
    return (gent_isochoric(trC * J**(-2.0 / 3.0), mu, Jm)
            + (1.0 / D) * ((J**2 - 1) / 2 - ufl.ln(J)))


class GentProblem:
    """What every Gent displacement problem shares: the P1/P2 space, the quadrature,
    Dirichlet conditions on boundary facets, consistent reactions, and Newton with load
    stepping. A subclass sets self.P (first Piola-Kirchhoff stress, UFL), self.residual
    and self.jacobian; self.local is a quadrature-point Function that update_local()
    recomputes before every assembly (plane stress's C33), or None."""

    thickness = 1.0      # the residual's factor: the sheet's thickness in 2D, 1 in 3D
    local = None

    def _setup(self, msh, degree, mu, Jm, bulk_ratio, quadrature_degree):
        self.msh = msh
        self.tdim = msh.topology.dim
        self.degree = degree
        self.mu, self.Jm = mu, Jm
        self.compressible = bulk_ratio is not None
        self.D = 2.0 / (bulk_ratio * mu) if self.compressible else None
        # 2 p: the stiffness integrand of P2 on straight cells is of degree 2 p - 2
        # for a linear law; the Gent terms are not polynomial, the quadrature error
        # converges with the mesh and is part of the discretisation error we measure.
        self.q = quadrature_degree or 2 * degree
        md = {"quadrature_degree": self.q, "quadrature_scheme": "default"}
        self.dx = ufl.Measure("dx", domain=msh, metadata=md)
        self.V = fem.VectorFunctionSpace(msh, ("CG", degree))
        self.u = fem.Function(self.V, name="u")
        self.space = self.V      # the unknown's space (a mixed one holds V as sub(0))
        self.bcs = []
        self.steps_taken = 0
        self.newton_iterations = 0
        self.factorisation = "lu"
        self.line_search = False

    def update_local(self):
        pass

    def displacement(self):
        """The displacement Function (for point values)."""
        return self.u

    def _u_part(self, f):
        return f

    def cells(self):
        return self.msh.topology.index_map(self.tdim).size_local

    # -- boundary conditions ------------------------------------------------------------
    def facets(self, marker):
        return dmesh.locate_entities_boundary(self.msh, self.tdim - 1, marker)

    def dofs(self, component, facets):
        return fem.locate_dofs_topological(self.V.sub(component), self.tdim - 1, facets)

    def add_bc(self, component, facets, value=0.0):
        """u_component = value on the facets; returns the Constant to move it."""
        c = fem.Constant(self.msh, PETSc.ScalarType(value))
        self.bcs.append(fem.dirichletbc(c, self.dofs(component, facets), self.V.sub(component)))
        return c

    def reaction_form(self, component, facets):
        """Form of the consistent reaction in `component` on the facets' dofs."""
        w = fem.Function(self.space)
        w.x.array[self.dofs(component, facets)] = 1.0
        return fem.form(self.thickness * ufl.inner(self.P, ufl.grad(self._u_part(w))) * self.dx)

    # -- Newton with load stepping ------------------------------------------------------
    def _make_solver(self):
        if self.line_search:
            return None, NewtonLineSearch(self)
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
        direct_solver(solver.krylov_solver, solver.A, self.factorisation)
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
        c_old = self.local.x.array.copy() if self.local is not None else None
        for target in targets:
            while lam < target - 1e-12:
                step = min(dlam, target - lam)
                lam_new = target if step == target - lam else lam + step
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
                    if self.local is not None:
                        self.local.x.array[:] = c_old
                    # A diverged Newton can leave inf in the solver's matrix and factor,
                    # and every retry then diverges too: start the retry from a new one.
                    self._problem, self._solver = self._make_solver()
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
                if self.local is not None:
                    c_old = self.local.x.array.copy()
                lam = lam_new
                if n <= fast_iterations and step == dlam:
                    dlam = min(1.5 * dlam, dlam_max)
            on_target(lam)



class GentSolid(GentProblem):
    """Compressible Gent with the full 3D energy (bapd's Compressible3D, paper eqs 24,
    26): a 3D body, or a 2D section in plane strain (F = diag(F~, 1), bapd's
    PlaneStrain) of thickness `thickness` (mm). Displacement only: bulk_ratio is
    required (an incompressible 3D or plane-strain law needs a pressure field)."""

    def __init__(self, msh, degree, bulk_ratio, thickness=1.0, mu=MU_KPA, Jm=JM,
                 quadrature_degree=None):
        if bulk_ratio is None:
            raise ValueError("GentSolid: 3D and plane strain are compressible only "
                             "(give bulk_ratio)")
        self._setup(msh, degree, mu, Jm, bulk_ratio, quadrature_degree)
        self.thickness = thickness if self.tdim == 2 else 1.0
        v = ufl.TestFunction(self.V)
        du = ufl.TrialFunction(self.V)
        Fv = ufl.variable(ufl.Identity(self.tdim) + ufl.grad(self.u))
        # In plane strain tr C = tr C~ + 1 and J = J~: F33 = 1 enters only there.
        trC = ufl.tr(Fv.T * Fv) + (1.0 if self.tdim == 2 else 0.0)
        psi = gent_compressible(trC, ufl.det(Fv), mu, Jm, self.D)
        self.P = ufl.diff(psi, Fv)
        self.residual = self.thickness * ufl.inner(self.P, ufl.grad(v)) * self.dx
        self.jacobian = ufl.derivative(self.residual, self.u, du)
        # The tangent is symmetric (a hyperelastic energy; dolfinx zeroes the Dirichlet
        # rows and columns alike): an LDL^T factorisation halves the 3D cost.
        self.factorisation = "cholesky"
        # Nearly incompressible (K = 1000 mu): a full Newton step from the predictor can
        # overshoot into J <= 0 near the hole; backtracking keeps the steps large.
        self.line_search = True


class GentSolidMixed(GentProblem):
    """The law of GentSolid in 3D or plane strain (a 2D mesh: F = diag(F~, 1), so
    I1bar = (tr C~ + 1) J^{-2/3} with J = det F~; per unit thickness), discretised
    without volumetric locking: Taylor-Hood
    (u in P2, a pressure p in P1) on the Hu-Washizu functional with the volume variable
    eliminated in closed form,
        Pi(u, p) = int Psi_iso(F) + U(Theta(p)) + p (J - Theta(p)) dV,
        U(J) = (1/D)((J^2 - 1)/2 - ln J),  Theta = U'^-1:  Theta(p) = (D p + sqrt(D^2 p^2 + 4))/2.
    Stationary in p: J = Theta(p), i.e. p = U'(J); in u: P = P_iso + p J F^-T. The same
    continuum problem as GentSolid (bapd's Compressible3D), not the same discretisation:
    the constraint is imposed in the P1 sense, so K = 1000 mu does not lock the P2
    displacement and Newton is not limited by K times a volume error squared."""

    def __init__(self, msh, degree, bulk_ratio, mu=MU_KPA, Jm=JM, quadrature_degree=None):
        self._setup(msh, degree, mu, Jm, bulk_ratio, quadrature_degree)
        cell = msh.ufl_cell()
        element = ufl.MixedElement([ufl.VectorElement("CG", cell, degree),
                                    ufl.FiniteElement("CG", cell, degree - 1)])
        self.space = fem.FunctionSpace(msh, element)
        self.V = self.space.sub(0)
        self.u = fem.Function(self.space, name="u_p")
        u, p = ufl.split(self.u)
        v, q = ufl.TestFunctions(self.space)
        Fv = ufl.variable(ufl.Identity(self.tdim) + ufl.grad(u))
        J = ufl.det(Fv)
        trC = ufl.tr(Fv.T * Fv) + (1.0 if self.tdim == 2 else 0.0)  # plane strain: F33 = 1
        psi_iso = gent_isochoric(trC * J**(-2.0 / 3.0), mu, Jm)
        D = self.D
        theta = (D * p + ufl.sqrt(D * D * p * p + 4.0)) / 2.0
        self.P = ufl.diff(psi_iso, Fv) + p * ufl.diff(J, Fv)
        self.residual = (ufl.inner(self.P, ufl.grad(v)) + (J - theta) * q) * self.dx
        self.jacobian = ufl.derivative(self.residual, self.u, ufl.TrialFunction(self.space))
        self.factorisation = "cholesky"    # symmetric indefinite: LDL^T
        self.line_search = True

    def displacement(self):
        return self.u.sub(0).collapse()

    def _u_part(self, f):
        return ufl.split(f)[0]


class GentPlaneStress(GentProblem):
    """Displacement problem of a plane-stress Gent sheet of thickness `thickness` (mm)."""

    def __init__(self, msh, degree, thickness, mu=MU_KPA, Jm=JM, bulk_ratio=None,
                 quadrature_degree=None):
        self._setup(msh, degree, mu, Jm, bulk_ratio, quadrature_degree)
        self.thickness = thickness
        v = ufl.TestFunction(self.V)
        du = ufl.TrialFunction(self.V)
        Ft = ufl.Identity(2) + ufl.grad(self.u)
        Fv = ufl.variable(Ft)
        Ct = Fv.T * Fv
        Jt = ufl.det(Fv)
        h = thickness
        mu, Jm = self.mu, self.Jm
        if not self.compressible:
            psi = gent_isochoric(ufl.tr(Ct) + 1.0 / Jt**2, mu, Jm)
            self.P = ufl.diff(psi, Fv)
            self.residual = h * ufl.inner(self.P, ufl.grad(v)) * self.dx
            self.jacobian = ufl.derivative(self.residual, self.u, du)
        else:
            Qe = ufl.FiniteElement("Quadrature", msh.ufl_cell(), self.q, quad_scheme="default")
            self.Q = fem.FunctionSpace(msh, Qe)
            self.C33 = fem.Function(self.Q, name="C33")
            self.C33.x.array[:] = 1.0
            self.local = self.C33
            cv = ufl.variable(self.C33)
            psi = gent_compressible(ufl.tr(Ct) + cv, ufl.sqrt(cv) * Jt, mu, Jm, self.D)
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
            ncells = self.cells()
            self._cells = np.arange(ncells, dtype=np.int32)
            self._qdofs = self.Q.dofmap.list.array.reshape(ncells, -1)
            self._nq = points.shape[0]

    def update_local(self):
        if self.compressible:
            self.update_c33()

    # -- compressible plane stress: the local S33 = 0 solve ---------------------------
    def s33_residual(self, c, trCt, Jt):
        """h(C33) = C33 S33 (docs/method.md section 4); written so that complex c works."""
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


def refine_near(gmsh, kind, tags, size_min, size_max, dist_min, dist_max, points):
    """Background size field: size_min within dist_min of the entities (kind "CurvesList"
    or "FacesList"), growing linearly to size_max at dist_max; `points` samples a curve."""
    field = gmsh.model.mesh.field
    dist = field.add("Distance")
    field.setNumbers(dist, kind, tags)
    field.setNumber(dist, "NumPointsPerCurve", points)
    thr = field.add("Threshold")
    field.setNumber(thr, "InField", dist)
    field.setNumber(thr, "SizeMin", size_min)
    field.setNumber(thr, "SizeMax", size_max)
    field.setNumber(thr, "DistMin", dist_min)
    field.setNumber(thr, "DistMax", dist_max)
    field.setAsBackgroundMesh(thr)
    return thr


class _Problem(dolfinx.fem.petsc.NonlinearProblem):
    """NonlinearProblem whose form() also solves S33 = 0 at the quadrature points."""

    def __init__(self, gent):
        super().__init__(gent.residual, gent.u, gent.bcs, gent.jacobian)
        self.gent = gent

    def form(self, x):
        super().form(x)
        self.gent.update_local()


def mesh_from_gmsh(build, h, geometry_order=2, dim=2):
    """dolfinx mesh of the gmsh model that build(gmsh, h) makes (it returns the surface
    tags, or the volume tags with dim = 3, synchronised; it may add a size field),
    element size at most h; geometry_order 2 puts the edge mid-nodes on the curves
    (and surfaces), so P2 does not lose its order to a polygonal hole."""
    import gmsh
    from dolfinx.io import gmshio
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("fe")
    entities = build(gmsh, h)
    gmsh.model.occ.synchronize()
    gmsh.model.addPhysicalGroup(dim, entities, 1)
    gmsh.option.setNumber("Mesh.CharacteristicLengthMax", h)
    gmsh.model.mesh.generate(dim)
    gmsh.model.mesh.setOrder(geometry_order)
    msh, _, _ = gmshio.model_to_mesh(gmsh.model, MPI.COMM_WORLD, 0, gdim=dim)
    gmsh.finalize()
    return msh


def solve_gripped_specimen(build, h, degree, bulk_ratio, lambdas, *, height, width, thickness,
                           grip_depth, reference_length, probe, verbose=False):
    """A specimen of a bapd scene gripped by edge layers: the shape build(gmsh, h) makes,
    between y = grip_depth and height - grip_depth, clamped there (ux = 0; uy = 0 below,
    (lambda - 1) reference_length above). Returns the probe's ux, uy (mm) and
    s = top reaction / (width x thickness) (kPa), bapd's nominal stress, per stretch."""
    msh = mesh_from_gmsh(build, h)
    fe = GentPlaneStress(msh, degree, thickness, bulk_ratio=bulk_ratio)
    top = fe.facets(lambda x: np.isclose(x[1], height - grip_depth))
    low = fe.facets(lambda x: np.isclose(x[1], grip_depth))
    for facets in (top, low):
        fe.add_bc(0, facets)
    fe.add_bc(1, low)
    uy_top = fe.add_bc(1, top)
    reaction = fe.reaction_form(1, top)

    def set_load(lam):
        uy_top.value = (lam - 1.0) * reference_length

    ux, uy, stress = {}, {}, {}

    def on_target(lam):
        u = point_value(fe.u, probe)
        ux[lam], uy[lam] = float(u[0]), float(u[1])
        stress[lam] = fem.assemble_scalar(reaction) / (width * thickness)
        if verbose:
            print(f"    lambda {lam:g}: probe ({ux[lam]:.6f}, {uy[lam]:.6f}) mm, "
                  f"s {stress[lam]:.6f} kPa", file=sys.stderr)

    fe.march(set_load, lambdas, on_target, verbose=verbose)
    return {"ux": ux, "uy": uy, "s": stress}, solve_info(fe)


def gripped_specimen_main(description, title, csv_name, build, lambdas, *, height, width,
                          thickness, grip_depth, probe, sizes=(2.0, 1.0, 0.5)):
    """Command line, convergence study and table of a bapd scene's specimen held by edge
    grips (solve_gripped_specimen); build(gmsh, h, grip_depth) makes the free shape."""
    ap = study_arguments(description, list(sizes), lambdas, csv_name)
    ap.add_argument("--grip-depth", type=float, default=grip_depth,
                    help=f"mm of each end held by a grip (default {grip_depth:g}: the scene's rows)")
    ap.add_argument("--reference-length", type=float, default=height,
                    help="L (mm) in u_top = (lambda - 1) L (default: the body height)")
    args = ap.parse_args()
    print(f"{title}, free between y = {args.grip_depth:g} and {height - args.grip_depth:g} mm, "
          f"top moved by (lambda - 1) {args.reference_length:g} mm, plane-stress Gent: probe "
          f"at {probe} mm (ux, uy in mm), nominal stress s = reaction / ({width:g} mm x "
          f"{thickness:g} mm) (kPa)")
    run_study(args, [("ux", "ux", "mm"), ("uy", "uy", "mm"), ("s", "s", "kPa")],
              lambda h, p, k, lams: solve_gripped_specimen(
                  lambda g, hh: build(g, hh, args.grip_depth), h, p, k, lams,
                  height=height, width=width, thickness=thickness, grip_depth=args.grip_depth,
                  reference_length=args.reference_length, probe=probe, verbose=args.verbose))


def point_value(function, point):
    """Value of a vector Function at a point of the mesh, (x, y) or (x, y, z) in mm."""
    return point_values(function, [point])[0]


def point_values(function, points):
    """Values of a vector Function at points of the mesh (rows (x, y) or (x, y, z), mm)."""
    from dolfinx import geometry
    msh = function.function_space.mesh
    p = np.zeros((len(points), 3))
    for i, q in enumerate(points):
        p[i, :len(q)] = q
    tree = geometry.BoundingBoxTree(msh, msh.topology.dim)
    candidates = geometry.compute_collisions(tree, p)
    colliding = geometry.compute_colliding_cells(msh, candidates, p)
    cells = []
    for i in range(len(p)):
        if len(colliding.links(i)) == 0:
            raise RuntimeError(f"point {tuple(points[i])} is not in the mesh")
        cells.append(colliding.links(i)[0])
    return function.eval(p, np.array(cells, dtype=np.int32)).reshape(len(points), -1)


def formulation_name(bulk_ratio):
    return "incompressible" if bulk_ratio is None else f"K={bulk_ratio:g}mu"


def dofs_of(problem):
    im = problem.space.dofmap.index_map
    return (im.size_local + im.num_ghosts) * problem.space.dofmap.index_map_bs


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


def study_arguments(description, sizes, lambdas, csv_name):
    """The command line every script shares."""
    import argparse
    import os
    ap = argparse.ArgumentParser(description=description,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="the two coarsest meshes only")
    ap.add_argument("--sizes", type=float, nargs="+", default=sizes,
                    help="P2 element sizes (mm), coarse to fine; P1 runs on the finest")
    ap.add_argument("--lambdas", type=float, nargs="+", default=lambdas, help="stretches")
    ap.add_argument("--formulations", nargs="+", default=["incompressible", "compressible"],
                    choices=["incompressible", "compressible"])
    ap.add_argument("--bulk-ratio", type=float, default=BULK_RATIO,
                    help="K/mu of the compressible law (bapd's default 1000)")
    ap.add_argument("--csv", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                  "results", csv_name))
    ap.add_argument("--verbose", action="store_true", help="report the load steps")
    return ap


def run_study(args, quantities, solve):
    """Convergence study: for each formulation, P2 on args.sizes (the two coarsest with
    --quick) and P1 on the finest; prints a row a mesh and the Richardson estimate of each
    quantity from the three finest P2 meshes, writes args.csv.
    quantities: [(key, label, unit)]; solve(h, degree, bulk_ratio, lambdas) returns
    ({key: {lambda: value}}, {"cells":, "dofs":, "steps":, "newton":, "s33":})."""
    import csv
    import os
    sizes = args.sizes[:2] if args.quick else args.sizes
    lambdas = sorted(args.lambdas)
    rows = []
    columns = [(key, lam) for key, _, _ in quantities for lam in lambdas]
    labels = {key: label for key, label, _ in quantities}
    units = {key: unit for key, _, unit in quantities}
    header = (f"{'formulation':<15} {'P':>2} {'h_mm':>7} {'cells':>7} {'dofs':>8} "
              + " ".join(f"{labels[k] + '(' + format(l, 'g') + ')':>12}" for k, l in columns)
              + f" {'steps':>5} {'newton':>6} {'time_s':>7}")
    for form in args.formulations:
        bulk = None if form == "incompressible" else args.bulk_ratio
        name = formulation_name(bulk)
        print(header)
        p2 = {c: [] for c in columns}
        p1 = [(1, sizes[-1])] if getattr(args, "p1", True) else []
        for degree, h in [(2, h) for h in sizes] + p1:
            timer = Timer()
            values, info = solve(h, degree, bulk, lambdas)
            t = timer()
            print(f"{name:<15} {degree:>2} {h:>7.4g} {info['cells']:>7} {info['dofs']:>8} "
                  + " ".join(f"{values[k][l]:>12.6f}" for k, l in columns)
                  + f" {info['steps']:>5} {info['newton']:>6} {t:>7.1f}", flush=True)
            row = dict(formulation=name, degree=degree, h_mm=h, cells=info["cells"],
                       dofs=info["dofs"])
            for k, l in columns:
                row[f"{k}_{l:g}_{units[k]}"] = f"{values[k][l]:.8f}"
                if degree == 2:
                    p2[(k, l)].append(values[k][l])
            row["max_S33_residual"] = f"{info['s33']:.1e}"
            row["time_s"] = f"{t:.1f}"
            rows.append(row)
        ratio = sizes[-2] / sizes[-1] if len(sizes) > 1 else 2.0
        extrapolated = dict(formulation=name, degree="extrapolated", h_mm=0, cells="", dofs="")
        for k, l in columns:
            p, ext = richardson(p2[(k, l)], ratio)
            fine = p2[(k, l)][-1]
            if ext is None:
                diffs = " ".join(f"{d:+.1e}" for d in np.diff(p2[(k, l)]))
                print(f"  {labels[k]}({l:g}): finest P2 {fine:.6f} {units[k]}; no Richardson "
                      f"estimate (P2 differences {diffs})")
                extrapolated[f"{k}_{l:g}_{units[k]}"] = ""
            else:
                print(f"  {labels[k]}({l:g}): finest P2 {fine:.6f} {units[k]}, observed order "
                      f"{p:.2f}, extrapolated {ext:.6f}, estimated relative error of the "
                      f"finest {abs(fine - ext) / abs(ext):.1e}")
                extrapolated[f"{k}_{l:g}_{units[k]}"] = f"{ext:.8f}"
        extrapolated["max_S33_residual"] = ""
        extrapolated["time_s"] = ""
        rows.append(extrapolated)
    os.makedirs(os.path.dirname(args.csv), exist_ok=True)
    with open(args.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {args.csv}")


def solve_info(fe):
    """The bookkeeping run_study prints for a solved problem."""
    return {"cells": fe.cells(), "dofs": dofs_of(fe),
            "steps": fe.steps_taken, "newton": fe.newton_iterations,
            "s33": fe.s33_check() if fe.local is not None else 0.0}


def pure_shear_analytic(lam, mu=MU_KPA, Jm=JM):
    """Paper eq 36: incompressible homogeneous pure shear, nominal stress (kPa)."""
    return mu * Jm * (lam - lam**-3) / (Jm - lam**2 - lam**-2 + 2)


class Timer:
    def __init__(self):
        self.t0 = time.perf_counter()

    def __call__(self):
        return time.perf_counter() - self.t0
