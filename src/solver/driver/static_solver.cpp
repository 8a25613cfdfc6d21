// Static states by Newton (static_solver.hpp): load steps along the schedule, each a
// tangent predictor and a PETSc SNES solve of R(u) = dW/du = 0.
#include "bapd/solver/driver/static_solver.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <string>

#include "bapd/solver/input/options_reader.hpp"

namespace bapd {

PetscErrorCode StaticSolverCheckScene(MPI_Comm comm, const RunSection &run, const FailureSection &failure, ForceForm force_form,
                                      const Schedule &s, const CheckpointOptions &checkpoint)
{
  PetscFunctionBegin;
  if (run.solver != SolverKind::static_newton) PetscFunctionReturn(0);
  PetscCheck(failure.softening == Softening::none, comm, PETSC_ERR_USER,
             "-solver static breaks bonds at once (-failure_critical_stretch, -failure_fracture_energy) but does not soften them "
             "yet: remove -failure_softening, or use -solver dynamic (the default) for softening bonds");
  PetscCheck(checkpoint.restart.empty() && !checkpoint.periodic(), comm, PETSC_ERR_USER,
             "-solver static writes no checkpoints and does not restart yet (a whole static run takes seconds to minutes): remove "
             "-checkpoint_interval, -checkpoint_wall_interval and -restart, or use -solver dynamic");
  PetscCheck(force_form == ForceForm::energy_consistent, comm, PETSC_ERR_USER,
             "-solver static needs -force_form energy_consistent (the default): the bond-only force is not the gradient of an "
             "energy, so there is no energy to minimise and no symmetric tangent");
  PetscCheck(!s.time.empty() && s.time.size() >= 2, comm, PETSC_ERR_USER,
             "-solver static follows -load_schedule: give one with at least two knots (time, stretch), e.g. -load_schedule 0,1,1,1.5");
  PetscCheck(s.stretch.front() == 1.0, comm, PETSC_ERR_USER,
             "-solver static starts from the undeformed body: -load_schedule must start at stretch 1 (it starts at %g)", s.stretch.front());
  PetscFunctionReturn(0);
}


template <int D> StaticSolver<D>::~StaticSolver()
{
  SNESDestroy(&snes_);
  MatDestroy(&H_);
  MatDestroy(&P_);
  VecDestroy(&u_);
  VecDestroy(&r_);
  VecDestroy(&u_last_);
  VecDestroy(&du_);
  VecDestroy(&b_);
  VecDestroy(&u_before_);
}

template <int D> PetscErrorCode StaticSolver<D>::Setup()
{
  const Layout  &layout = sim_.layout_;
  const PetscInt n      = D * layout.n_owned;
  KSP            ksp;
  PC             pc;

  PetscFunctionBegin;
  PetscCall(tangent_.Setup<D>(sim_.comm_, sim_.scene_.material, layout, sim_.families_, sim_.geometry_, sim_.bond_state_));
  PetscCall(tangent_.CreateMatrix(&H_));
  {
    // The preconditioner's copy in AIJ (GAMG, hypre and the factorisations take it), by
    // conversion after each assembly: blocks are inserted into H_ at one search each.
    PetscBool aij;
    PetscCall(PetscObjectBaseTypeCompare((PetscObject)H_, MATAIJ, &aij));
    if (!aij) PetscCall(PetscObjectTypeCompareAny((PetscObject)H_, &aij, MATSEQAIJ, MATMPIAIJ, ""));
    if (aij) {
      PetscCall(PetscObjectReference((PetscObject)H_));
      P_ = H_;
    } else PetscCall(MatConvert(H_, MATAIJ, MAT_INITIAL_MATRIX, &P_));
  }
  PetscCall(VecCreateMPI(sim_.comm_, n, PETSC_DETERMINE, &u_));
  PetscCall(VecSetBlockSize(u_, D));
  PetscCall(VecDuplicate(u_, &r_));
  PetscCall(VecDuplicate(u_, &u_last_));
  PetscCall(VecDuplicate(u_, &du_));
  PetscCall(VecDuplicate(u_, &b_));
  PetscCall(VecDuplicate(u_, &u_before_));
  u_scratch_.assign(n, 0.0);
  grips_before_.assign(n, 0.0);
  grips_after_.assign(n, 0.0);
  c33_last_.reserve(sim_.force_.warm_start().size());
  force_density_.assign(n, 0.0);
  {
    // The rigid-body modes at the reference positions: the near null space that an
    // algebraic multigrid (-pc_type gamg) builds its coarse spaces from.
    Vec          coordinates;
    MatNullSpace rigid;
    double      *c;
    PetscCall(VecDuplicate(u_, &coordinates));
    PetscCall(VecGetArray(coordinates, &c));
    std::copy(layout.cloud.x.begin(), layout.cloud.x.begin() + n, c);
    PetscCall(VecRestoreArray(coordinates, &c));
    PetscCall(MatNullSpaceCreateRigidBody(coordinates, &rigid));
    PetscCall(MatSetNearNullSpace(P_, rigid));
    PetscCall(MatNullSpaceDestroy(&rigid));
    PetscCall(VecDestroy(&coordinates));
  }
  held_.clear();
  for (const ConstrainedDof &c : sim_.loading_.constrained()) {
    const PetscInt point = c.dof / D, component = c.dof % D;
    held_.push_back(D * layout.petsc_index[point] + component);
  }
  t_ = sim_.loading_.schedule().time.empty() ? 0.0 : sim_.loading_.schedule().time.front();

  PetscCall(SNESCreate(sim_.comm_, &snes_));
  PetscCall(SNESSetFunction(snes_, r_, FormFunction, this));
  PetscCall(SNESSetJacobian(snes_, H_, P_, FormJacobian, this));
  PetscCall(SNESSetConvergenceTest(snes_, ConvergenceTest, this, nullptr));
  // Defaults that the options may change: Newton with a backtracking line search, 50
  // iterations; the convergence test is relative to the grips' reactions (ConvergenceTest),
  // so PETSc's own relative tests are set tight enough not to end a solve before it.
  PetscCall(SNESSetTolerances(snes_, 0.0, 1e-14, 1e-14, 50, 10000));
  PetscCall(SNESGetKSP(snes_, &ksp));
  // CG with algebraic multigrid on the rigid-body modes: the tangent of a stable static
  // state is symmetric positive definite; the wide stencil (two horizons) makes a direct
  // factorisation costly beyond a few thousand points (docs/options_run.md "Static solver").
  // Modified Newton: a load step builds its tangent once, at its first iteration, and keeps
  // it (and the preconditioner built on it) while the residual falls fast enough
  // (ConvergenceTest); assembling a tangent costs about as much as twenty CG iterations.
  // With a kept tangent the convergence is linear, its rate set by the tangent's change,
  // not by the linear solve: CG to 3e-2 takes about as many Newton iterations as to 1e-8
  // and 40 % fewer CG iterations than to 1e-3 (plate with a hole, docs/performance.md
  // section 6). -snes_lag_jacobian N gives PETSc's fixed lag instead (1: full Newton, a
  // fresh tangent every iteration, CG to 1e-8).
  PetscBool lag_given = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-snes_lag_jacobian", &lag_given));
  reuse_tangent_ = !lag_given;
  // With failure GMRES: between a break and its re-equilibration the state is not static,
  // and its tangent need not be positive definite (CG failed on the notched sheet once its
  // crack ran; docs/options_run.md "Static solver").
  PetscCall(KSPSetType(ksp, sim_.scene_.failure.enabled ? KSPGMRES : KSPCG));
  PetscCall(KSPSetTolerances(ksp, reuse_tangent_ ? 3e-2 : 1e-8, PETSC_DEFAULT, PETSC_DEFAULT, 1000));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCGAMG));
  PetscCall(SNESSetFromOptions(snes_));
  use_secant_ = sim_.scene_.run.static_options.secant_predictor;
  PetscFunctionReturn(0);
}

template <int D> void StaticSolver<D>::HoldGrips(double t, double *u) const { sim_.loading_.Apply(t, u, nullptr); }

template <int D> PetscErrorCode StaticSolver<D>::CopyHeld(Vec U)
{
  const double *u;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(U, &u));
  std::copy(u, u + u_scratch_.size(), u_scratch_.begin());
  PetscCall(VecRestoreArrayRead(U, &u));
  HoldGrips(t_target_, u_scratch_.data());
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode StaticSolver<D>::Evaluate(const double *u, bool *ok)
{
  PetscFunctionBegin;
  PetscCall(sim_.force_.Evaluate(u, force_density_.data(), ForceOperator::WarmStart::commit));
  int failed = sim_.force_.stats().failed() > 0, any = 0;
  PetscCallMPI(MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, sim_.comm_));
  *ok = !any;
  PetscFunctionReturn(0);
}

// R = -V f on the free dofs, 0 on the grips' (their values are held at t_target_).
template <int D> PetscErrorCode StaticSolver<D>::FormFunction(SNES snes, Vec U, Vec R, void *ctx)
{
  auto          *self = static_cast<StaticSolver<D> *>(ctx);
  const Layout  &layout = self->sim_.layout_;
  double        *r;
  bool           ok;

  PetscFunctionBegin;
  PetscCall(self->CopyHeld(U));
  PetscCall(self->Evaluate(self->u_scratch_.data(), &ok));
  if (!ok) { // a bond past its law's limit or inverted: not a state of the body
    PetscCall(SNESSetFunctionDomainError(snes));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetArray(R, &r));
  for (PetscInt i = 0; i < layout.n_owned; ++i)
    for (int c = 0; c < D; ++c) r[D * i + c] = -layout.cloud.volume[i] * self->force_density_[D * i + c];
  double reaction = 0.0;
  for (const ConstrainedDof &c : self->sim_.loading_.constrained()) {
    reaction += r[c.dof] * r[c.dof];
    r[c.dof] = 0.0;
  }
  PetscCall(VecRestoreArray(R, &r));
  PetscCallMPI(MPI_Allreduce(&reaction, &self->reaction_norm_, 1, MPI_DOUBLE, MPI_SUM, self->sim_.comm_));
  self->reaction_norm_ = std::sqrt(self->reaction_norm_);
  PetscFunctionReturn(0);
}

// The tangent at u (its warm starts those of the evaluation at u, which SNES makes first),
// the grips' dofs as Dirichlet rows and columns.
template <int D> PetscErrorCode StaticSolver<D>::FormJacobian(SNES, Vec U, Mat H, Mat P, void *ctx)
{
  auto *self = static_cast<StaticSolver<D> *>(ctx);

  PetscFunctionBegin;
  PetscCall(self->Tangent(U, H));
  if (!(self->dirichlet_diagonal_ > 0)) {
    // The Dirichlet rows' diagonal: the mean of H's at the first tangent (its scale, for
    // the conditioning of an iterative solve; the solution does not depend on it), kept.
    PetscScalar sum;
    PetscInt    size;
    PetscCall(MatGetDiagonal(H, self->du_));
    PetscCall(VecNorm(self->du_, NORM_1, &sum));
    PetscCall(VecGetSize(self->du_, &size));
    self->dirichlet_diagonal_ = sum > 0 ? sum / size : 1.0;
  }
  PetscCall(MatZeroRowsColumns(H, (PetscInt)self->held_.size(), self->held_.data(), self->dirichlet_diagonal_, nullptr, nullptr));
  if (P != self->P_ || H != self->H_) SETERRQ(self->sim_.comm_, PETSC_ERR_ARG_WRONG, "the static solver's SNES was given other matrices");
  PetscCall(self->CopyToPreconditioner());
  ++self->jacobians_;
  ++self->step_tangents_;
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode StaticSolver<D>::Tangent(Vec U, Mat H)
{
  PetscInt failed;

  PetscFunctionBegin;
  PetscCall(CopyHeld(U));
  PetscCall(sim_.force_.UpdatePositions(u_scratch_.data()));
  std::vector<double> &c33 = sim_.force_.warm_start();
  PetscCall(tangent_.Assemble(sim_.force_.positions(), c33.empty() ? nullptr : c33.data(), H, &failed));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode StaticSolver<D>::NodalForce(Vec U, Vec force)
{
  const double *u;
  double       *f;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(sim_.force_.Evaluate(u, force_density_.data(), ForceOperator::WarmStart::keep));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(VecGetArray(force, &f));
  for (PetscInt i = 0; i < sim_.layout_.n_owned; ++i)
    for (int c = 0; c < D; ++c) f[D * i + c] = -sim_.layout_.cloud.volume[i] * force_density_[D * i + c];
  PetscCall(VecRestoreArray(force, &f));
  PetscFunctionReturn(0);
}

template <int D>
PetscErrorCode StaticSolver<D>::ConvergenceTest(SNES snes, PetscInt it, PetscReal xnorm, PetscReal step, PetscReal fnorm,
                                                SNESConvergedReason *reason, void *ctx)
{
  auto *self = static_cast<StaticSolver<D> *>(ctx);

  PetscFunctionBegin;
  const double previous = self->last_fnorm_;
  self->last_fnorm_      = fnorm;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, step, fnorm, reason, nullptr));
  // Relative to the reactions, or to 1e-3 of the largest so far where they have fallen
  // further (a sheet cut through by a crack, or unloaded, holds almost none).
  const double scale = std::max(self->reaction_norm_, 1e-3 * self->peak_reaction_);
  if (*reason == SNES_CONVERGED_ITERATING && fnorm <= self->sim_.scene_.run.static_options.residual_tolerance * scale)
    *reason = SNES_CONVERGED_FNORM_ABS;
  // Modified Newton (Setup): the kept tangent is rebuilt at the next iteration once an
  // iteration with it reduces |R| by less than reuse_rate (linear convergence too slow to
  // beat a fresh tangent's quadratic one); the lag -2 means once, then kept again.
  constexpr double reuse_rate = 0.25; // (0.1 and 0.5 cost 10 % and 20 % more on the plate with a hole)
  if (self->reuse_tangent_ && *reason == SNES_CONVERGED_ITERATING && it > 0 && fnorm > reuse_rate * previous) PetscCall(SNESSetLagJacobian(snes, -2));
  PetscFunctionReturn(0);
}

// The tangent predictor: H(u) du = 0 on the free dofs with du = the grips' increment on
// theirs (MatZeroRowsColumns moves the known columns to the right-hand side), u += du.
template <int D> PetscErrorCode StaticSolver<D>::Predict(double t)
{
  KSP      ksp;
  PetscInt its;
  double  *x;

  PetscFunctionBegin;
  const double lambda = sim_.loading_.stretch_at(t_), next = sim_.loading_.stretch_at(t);
  if (secant_ && lambda != lambda_before_) {
    // After a converged step: the secant through the last two states, u += (dlambda /
    // dlambda_last) (u - u_before), no solve (the grips' dofs are set exactly by HoldGrips).
    PetscCall(VecWAXPY(du_, -1.0, u_before_, u_));
    PetscCall(VecAXPY(u_, (next - lambda) / (lambda - lambda_before_), du_));
    PetscFunctionReturn(0);
  }
  const double t_now = t_target_;
  t_target_          = t_;
  PetscCall(Tangent(u_, H_));
  t_target_ = t_now;
  std::copy(u_scratch_.begin(), u_scratch_.end(), grips_before_.begin());
  std::copy(u_scratch_.begin(), u_scratch_.end(), grips_after_.begin());
  HoldGrips(t_, grips_before_.data());
  HoldGrips(t, grips_after_.data());
  PetscCall(VecSet(du_, 0.0));
  PetscCall(VecSet(b_, 0.0));
  PetscCall(VecGetArray(du_, &x));
  for (const ConstrainedDof &c : sim_.loading_.constrained()) x[c.dof] = grips_after_[c.dof] - grips_before_[c.dof];
  PetscCall(VecRestoreArray(du_, &x));
  PetscCall(MatZeroRowsColumns(H_, (PetscInt)held_.size(), held_.data(), 1.0, du_, b_));
  PetscCall(CopyToPreconditioner());
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(KSPSetOperators(ksp, H_, P_));
  PetscCall(KSPSolve(ksp, b_, du_));
  PetscCall(KSPGetIterationNumber(ksp, &its));
  krylov_iterations_ += its;
  ++jacobians_;
  PetscCall(VecAXPY(u_, 1.0, du_));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode StaticSolver<D>::Newton(PetscBool *converged, PetscInt *iterations)
{
  PetscInt its, lits;

  PetscFunctionBegin;
  step_tangents_ = 0;
  // A fresh tangent at the first iteration, then kept (ConvergenceTest). Keeping the last
  // load step's instead saves 2 of 7 tangents on the plate with a hole but takes more CG
  // iterations, and its static states end closer to the tolerance (1, 2 and 3 ranks then
  // differ by 1e-9 with CG to 3e-2).
  if (reuse_tangent_) PetscCall(SNESSetLagJacobian(snes_, -2));
  PetscCall(SNESSolve(snes_, nullptr, u_));
  PetscCall(SNESGetConvergedReason(snes_, &last_reason_));
  PetscCall(SNESGetIterationNumber(snes_, &its));
  PetscCall(SNESGetLinearSolveIterations(snes_, &lits));
  newton_iterations_ += its;
  krylov_iterations_ += lits;
  *iterations = its;
  *converged  = last_reason_ > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (*converged) peak_reaction_ = std::max(peak_reaction_, reaction_norm_);
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode StaticSolver<D>::LoadStep(double t, PetscBool *converged, PetscInt *iterations)
{
  PetscFunctionBegin;
  PetscCall(VecCopy(u_, u_last_));
  c33_last_ = sim_.force_.warm_start(); // a cutback starts again from these (the capacity is kept)
  t_target_ = t;
  PetscCall(Predict(t));
  PetscCall(Newton(converged, iterations));
  if (*converged) {
    PetscCall(VecCopy(u_last_, u_before_));
    lambda_before_ = sim_.loading_.stretch_at(t_);
    secant_        = use_secant_;
    double *u;
    PetscCall(VecGetArray(u_, &u));
    HoldGrips(t, u); // exactly the prescribed values
    PetscCall(VecRestoreArray(u_, &u));
    t_ = t;
    ++load_steps_;
  } else {
    PetscCall(VecCopy(u_last_, u_));
    sim_.force_.warm_start() = c33_last_;
    secant_ = false; // the retry starts from the tangent predictor
    ++cutbacks_;
  }
  PetscFunctionReturn(0);
}

// From the current state to the schedule time t along one ramp: load steps of the
// current size in stretch, halved after a step that does not converge and grown after a
// fast one; a history row after each.
template <int D> PetscErrorCode StaticSolver<D>::SolveTo(double t, PetscBool *converged)
{
  const StaticOptions &o    = sim_.scene_.run.static_options;
  const Loading       &load = sim_.loading_;
  double              &step = step_; // the load step in stretch, kept from ramp to ramp

  PetscFunctionBegin;
  if (step == 0) step = o.stretch_step;
  *converged = PETSC_TRUE;
  while (t - t_ > 1e-12 * std::max(1.0, std::fabs(t))) {
    const double rate = std::fabs(load.schedule().rate_at(t_)); // d lambda / dt on this ramp
    double       next = rate > 0 ? std::min(t, t_ + step / rate) : t;
    if (t - next < 0.5 * (next - t_)) next = t; // no sliver of a step at the knot
    PetscBool    ok;
    PetscInt     its;
    const double t_before = t_;
    PetscCall(LoadStep(next, &ok, &its));
    if (!ok) {
      const double from = load.stretch_at(t_), to = load.stretch_at(next);
      step *= 0.5;
      // A linear solve that fails is the preconditioner's failure, not the load step's:
      // cutting back does not help after twice.
      linear_failures_ = last_reason_ == SNES_DIVERGED_LINEAR_SOLVE ? linear_failures_ + 1 : 0;
      if (linear_failures_ >= 3) step = 0.0;
      PetscCall(PetscPrintf(sim_.comm_, "Load step to stretch %.5f did not converge (%s): cut back to %.3g in stretch\n", to,
                            SNESConvergedReasons[last_reason_], step));
      if (step < o.stretch_step_min) {
        *converged = PETSC_FALSE;
        PetscCall(PetscInfo(snes_, "no static state beyond stretch %g\n", from));
        PetscFunctionReturn(0);
      }
      continue;
    }
    linear_failures_ = 0;
    const bool fast = reuse_tangent_ ? step_tangents_ <= 1 : its <= o.fast_iterations;
    bool       retry = false, stable = true;
    PetscCall(AfterLoadStep(t_before, its, &retry, &stable)); // its history row; with failure, the breaking
    if (!stable) {
      *converged = PETSC_FALSE;
      PetscFunctionReturn(0);
    }
    if (retry) continue;
    // Fast: converged on its first tangent (modified Newton), or in at most
    // -static_fast_iterations iterations (full Newton, -snes_lag_jacobian 1). Not while
    // the first break is being located (static_breaking.cpp): there the step only halves.
    // Nor after a step that broke bonds: the crack's growth is followed at the same step.
    if (fast && !onset_search_ && !crack_grew_) step = std::min(o.stretch_step_max, step * o.growth);
    if (sim_.scene_.time_stepping.end_step >= 0 && load_steps_ >= sim_.scene_.time_stepping.end_step) break;
  }
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode StaticSolver<D>::CopyToState()
{
  const double *u;
  double       *x;
  const PetscInt n = D * sim_.layout_.n_owned;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(u_, &u));
  PetscCall(VecGetArray(sim_.X_, &x));
  std::copy(u, u + n, x);
  std::fill(x + n, x + 2 * n, 0.0);
  PetscCall(VecRestoreArray(sim_.X_, &x));
  PetscCall(VecRestoreArrayRead(u_, &u));
  PetscFunctionReturn(0);
}

// A row of static_states.csv (the columns of the dynamic run's: kinetic energy 0), the
// probes on the screen, and a field file with -output_fields.
template <int D> PetscErrorCode StaticSolver<D>::WriteStaticState(double t)
{
  SimulationD<D> &s = sim_;

  PetscFunctionBegin;
  PetscCall(CopyToState());
  if (s.history_.last_step() != Solves()) PetscCall(s.WriteHistoryRow(Solves(), t, false));
  const double lambda = s.loading_.stretch_at(t);
  PetscCall(PetscPrintf(s.comm_, "Static at stretch %.5f: load step %" PetscInt_FMT, lambda, load_steps_));
  for (std::size_t p = 0; p < s.probes_.size(); ++p)
    PetscCall(PetscPrintf(s.comm_, "; %s ux = %.6e m", s.scene_.loading.probes[p].name.c_str(), s.last_probe_u_[D * p]));
  PetscCall(PetscPrintf(s.comm_, "\n"));
  PetscCall(s.history_.WriteStaticState(s.comm_, lambda, t, Solves(), 0.0, s.last_probe_u_.data(), s.last_reaction_.data()));
  if (s.output_.fields.enabled) PetscCall(s.WriteFields(Solves(), t));
  ++static_states_;
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode StaticSolver<D>::Run()
{
  const Schedule &schedule = sim_.loading_.schedule();
  const std::size_t K      = schedule.time.size();
  const std::clock_t start = std::clock();

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(sim_.stage_step_));
  bool stopped = false;
  for (std::size_t k = 0; k + 1 < K && !stopped; ++k) {
    const bool hold = schedule.stretch[k + 1] == schedule.stretch[k];
    if (hold) t_ = schedule.time[k + 1]; // the state holds: the next ramp starts at its own rate
    if (!hold) {
      PetscBool converged;
      PetscCall(SolveTo(schedule.time[k + 1], &converged));
      if (!converged) {
        const double from = sim_.loading_.stretch_at(t_), to = schedule.stretch[k + 1];
        PetscCall(PetscLogStagePop());
        sim_.stopped_on_error_ = true;
        PetscCheck(unstable_bonds_ == 0, sim_.comm_, PETSC_ERR_NOT_CONVERGED,
                   "-solver static: bonds broke at stretch %.5f (%" PetscInt_FMT " broken in all) and Newton found no static state "
                   "with them at this load (%s)%s. What was written is kept (history.csv up to step %" PetscInt_FMT
                   ", the last static state). Follow the crack with -solver dynamic, or try more Newton iterations (-snes_max_it 200)%s",
                   from, unstable_bonds_, SNESConvergedReasons[last_reason_],
                   last_reason_ == SNES_DIVERGED_FUNCTION_DOMAIN
                     ? ": on the way a bond at the crack passes its law's limit (the Gent chain limit), where the dynamic route "
                       "breaks it; the crack runs unstably here, with the grips held"
                     : ": the crack may run unstably here, with the grips held",
                   Solves(),
                   last_reason_ == SNES_DIVERGED_LINEAR_SOLVE ? ", or the direct solver (-ksp_type preonly -pc_type lu)" : "");
        SETERRQ(sim_.comm_, PETSC_ERR_NOT_CONVERGED,
                "-solver static: no static state found beyond stretch %.5f on the way to %.5f (Newton: %s, after %" PetscInt_FMT
                " cutbacks, the load step below -static_stretch_step_min %g). What was written is kept (history.csv up to load step %" PetscInt_FMT
                ")%s. Try a smaller -static_stretch_step_min, more Newton iterations (-snes_max_it 100), another line search "
                "(-snes_linesearch_type l2), or -solver dynamic (a body past its law's limit or buckling has no static state here)",
                from, to, SNESConvergedReasons[last_reason_], cutbacks_, sim_.scene_.run.static_options.stretch_step_min, Solves(),
                last_reason_ == SNES_DIVERGED_LINEAR_SOLVE
                  ? ". The linear solver failed (CG with GAMG: a nearly incompressible plane-strain or 3D body can defeat it): use "
                    "the direct solver, -ksp_type preonly -pc_type lu (-pc_factor_mat_solver_type mumps on several ranks)"
                  : "");
      }
      if (sim_.scene_.time_stepping.end_step >= 0 && load_steps_ >= sim_.scene_.time_stepping.end_step && t_ < schedule.time[k + 1]) {
        PetscCall(PetscPrintf(sim_.comm_, "\nStopped after load step %" PetscInt_FMT " (-end_step), at stretch %.5f\n", load_steps_,
                              sim_.loading_.stretch_at(t_)));
        stopped = true;
        break;
      }
    }
    // A static state where a hold begins and at the end of the schedule.
    const bool last = k + 2 == K, hold_next = !last && schedule.stretch[k + 2] == schedule.stretch[k + 1];
    if (!hold && (last || hold_next)) PetscCall(WriteStaticState(schedule.time[k + 1]));
  }
  PetscCall(PetscLogStagePop());
  if (sim_.history_.last_step() != Solves()) PetscCall(sim_.WriteHistoryRow(Solves(), t_, false));
  PetscCall(sim_.OutputAtEnd(Solves(), t_));
  if (sim_.scene_.output.final_state) PetscCall(sim_.WriteFinalState());
  PetscCall(Summary((double)(std::clock() - start) / CLOCKS_PER_SEC));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode StaticSolver<D>::Summary(double cpu)
{
  double total = 0;
  KSP    ksp;
  PC     pc;
  KSPType ksp_type;
  PCType  pc_type;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Allreduce(&cpu, &total, 1, MPI_DOUBLE, MPI_SUM, sim_.comm_));
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(KSPGetType(ksp, &ksp_type));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCGetType(pc, &pc_type));
  PetscCall(PetscPrintf(sim_.comm_,
                        "\nStatic solver (Newton, -solver static): %" PetscInt_FMT " load steps (%" PetscInt_FMT " cut back), %" PetscInt_FMT
                        " static states, %" PetscInt_FMT " Newton iterations, %" PetscInt_FMT " Krylov iterations (%s, %s), %" PetscInt_FMT
                        " tangents assembled; CPU time of the load steps %.3f s (all ranks)\n",
                        load_steps_, cutbacks_, static_states_, newton_iterations_, krylov_iterations_, ksp_type, pc_type, jacobians_, total));
  if (sim_.scene_.failure.enabled) {
    PetscInt broken;
    PetscCall(sim_.BrokenBondCount(&broken));
    if (onset_stretch_ > 0)
      PetscCall(PetscPrintf(sim_.comm_, "  bonds broken: %" PetscInt_FMT ", in %" PetscInt_FMT " re-equilibrations; the first at stretch %.5f (its load step %.2g wide)\n",
                            broken, reequilibrations_, onset_stretch_, onset_width_));
    else PetscCall(PetscPrintf(sim_.comm_, "  bonds broken: none\n"));
  }
  for (std::size_t l = 0; l < sim_.scene_.loading.sets.size(); ++l)
    PetscCall(PetscPrintf(sim_.comm_, "  %s reaction y at stretch %.5f: %.6e N\n", sim_.scene_.loading.sets[l].name.c_str(), sim_.loading_.stretch_at(t_),
                          sim_.last_reaction_[D * l + 1]));
  PetscCall(sim_.ListOutputFiles());
  PetscFunctionReturn(0);
}

template class StaticSolver<2>;
template class StaticSolver<3>;

} // namespace bapd
