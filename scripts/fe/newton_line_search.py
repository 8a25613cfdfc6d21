"""The nonlinear and linear solvers of gent_fe.py's problems (a file of their own, so
that each file has one job): MUMPS through a KSP, and Newton with a backtracking line search
for the load steps where dolfinx's plain NewtonSolver stalls."""
import numpy as np
from mpi4py import MPI
from petsc4py import PETSc

from dolfinx import fem


def direct_solver(ksp, A, factorisation):
    """MUMPS through the KSP: "lu", or "cholesky" (LDL^T) for a symmetric A."""
    ksp.setType("preonly")
    ksp.getPC().setType(factorisation)
    ksp.getPC().setFactorSolverType("mumps")
    if factorisation == "cholesky":
        # MUMPS's Cholesky reads the upper triangle; the flag must outlive the
        # reassemblies (symmetric indefinite LDL^T, no SPD assumption).
        A.setOption(PETSc.Mat.Option.SYMMETRIC, True)
        A.setOption(PETSc.Mat.Option.SYMMETRY_ETERNAL, True)


class NewtonLineSearch:
    """Newton with a backtracking line search on the residual norm (PETSc SNES newtonls,
    bt), with the NewtonSolver's interface (solve(u) -> (iterations, converged)) and its
    stopping rule: the Newton correction below 1e-8 mm. The Dirichlet values enter as
    in dolfinx's NewtonSolver (lifting with x0 = x, so the first correction moves the
    constrained dofs onto them)."""

    ATOL_MM = 1e-8
    MAX_IT = 25

    def __init__(self, gent):
        from dolfinx.fem import petsc as fp
        self.gent = gent
        self.L = fem.form(gent.residual)
        self.a = fem.form(gent.jacobian)
        self.A = fp.create_matrix(self.a)
        self.b = fp.create_vector(self.L)
        self.x = gent.u.vector.duplicate()
        snes = PETSc.SNES().create(MPI.COMM_WORLD)
        snes.setFunction(self._residual, self.b)
        snes.setJacobian(self._jacobian, self.A)
        snes.setType("newtonls")
        # petsc4py 3.18 has no SNESLineSearch object: the type goes through the options.
        snes.setOptionsPrefix("gent_fe_")
        PETSc.Options()["gent_fe_snes_linesearch_type"] = "bt"
        snes.setFromOptions()
        snes.setConvergenceTest(self._converged)
        direct_solver(snes.getKSP(), self.A, gent.factorisation)
        self.snes = snes

    def _residual(self, snes, x, b):
        from dolfinx.fem import petsc as fp
        x.ghostUpdate(addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
        x.copy(self.gent.u.vector)
        self.gent.u.x.scatter_forward()
        self.gent.update_local()
        with b.localForm() as local:
            local.set(0.0)
        fp.assemble_vector(b, self.L)
        fp.apply_lifting(b, [self.a], bcs=[self.gent.bcs], x0=[x], scale=-1.0)
        b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        fp.set_bc(b, self.gent.bcs, x, -1.0)

    def _jacobian(self, snes, x, A, P):
        from dolfinx.fem import petsc as fp
        A.zeroEntries()
        fp.assemble_matrix(A, self.a, bcs=self.gent.bcs)
        A.assemble()

    def _converged(self, snes, it, norms):
        _, step_norm, residual_norm = norms
        R = PETSc.SNES.ConvergedReason
        if not np.isfinite(residual_norm):
            return R.DIVERGED_FNORM_NAN
        if it > 0 and step_norm < self.ATOL_MM:
            return R.CONVERGED_SNORM_RELATIVE
        if it >= self.MAX_IT:
            return R.DIVERGED_MAX_IT
        return R.ITERATING

    def solve(self, u):
        u.vector.copy(self.x)
        self.snes.solve(None, self.x)
        self.x.copy(u.vector)
        u.x.scatter_forward()
        return self.snes.getIterationNumber(), self.snes.getConvergedReason() > 0
