// The dynamics: the acceleration the TS integrates (force operator, grips, mass) and
// the PETSc TS right-hand sides (velocity Verlet by default, any explicit TS by option).
#include "bapd/solver/driver/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace bapd {

// For output and tests: the operator reads the warm start without writing it back,
// so looking at the state never changes the dynamics.
template <int D> PetscErrorCode SimulationD<D>::ComputeForceDensity(const double *u_owned, double *force_density)
{
  PetscFunctionBegin;
  PetscCall(force_.Evaluate(u_owned, force_density, ForceOperator::WarmStart::keep));
  PetscFunctionReturn(0);
}

// The dynamics' evaluation: advances the warm starts (force_operator.hpp).
template <int D> PetscErrorCode SimulationD<D>::Acceleration(const double *u_owned, double *a_owned)
{
  PetscFunctionBegin;
  PetscCall(force_.Evaluate(u_owned, a_owned, ForceOperator::WarmStart::commit));
  budget_.RecordForce(a_owned); // the body's pull on the grips (energy_budget.hpp)
  const double inv_rho = 1.0 / scene_.material.density;
  for (PetscInt k = 0; k < D * layout_.n_owned; ++k) a_owned[k] *= inv_rho;
  for (const ConstrainedDof &d : loading_.constrained()) a_owned[d.dof] = 0.0; // the grip moves them
  relaxation_.Record(u_owned, a_owned); // -relaxation adaptive: the last two evaluations
  step_control_.Record(u_owned, a_owned); // the base point of the next re-estimate of the stable step
  PetscFunctionReturn(0);
}

// The step's start: where the grips stand (the energy budget's work over the step).
template <int D> PetscErrorCode SimulationD<D>::PreStep(TS ts)
{
  SimulationD  *sim;
  Vec           X;
  const double *x;

  PetscFunctionBegin;
  PetscCall(TSGetApplicationContext(ts, &sim));
  PetscCall(TSGetSolution(ts, &X));
  PetscCall(VecGetArrayRead(X, &x));
  sim->budget_.BeginStep(x);
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::RHSPosition(TS, PetscReal, Vec V, Vec Udot, void *)
{
  PetscFunctionBegin;
  PetscCall(VecCopy(V, Udot));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::RHSMomentum(TS, PetscReal, Vec U, Vec Vdot, void *ctx)
{
  auto         *sim = static_cast<SimulationD *>(ctx);
  const double *u;
  double       *a;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(Vdot, &a));
  PetscCall(sim->Acceleration(u, a));
  PetscCall(VecRestoreArray(Vdot, &a));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}

// X = [u, v], Xdot = [v, a(u)]: for the general explicit TS types (-ts_type rk, ...).
template <int D> PetscErrorCode SimulationD<D>::RHSFull(TS, PetscReal, Vec X, Vec F, void *ctx)
{
  auto         *sim = static_cast<SimulationD *>(ctx);
  const PetscInt n  = D * sim->layout_.n_owned;
  const double *x;
  double       *f;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(F, &f));
  std::memcpy(f, x + n, sizeof(double) * n);
  PetscCall(sim->Acceleration(x, f + n));
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::SetupTimeStepper()
{
  const PetscInt n = D * layout_.n_owned;
  PetscInt       start;

  PetscFunctionBegin;
  PetscCall(VecCreateMPI(comm_, 2 * n, PETSC_DECIDE, &X_));
  PetscCall(VecGetOwnershipRange(X_, &start, nullptr));
  PetscCall(ISCreateStride(comm_, n, start, 1, &is_position_));
  PetscCall(ISCreateStride(comm_, n, start + n, 1, &is_momentum_));
  {
    double *x;
    PetscCall(VecSet(X_, 0.0));
    PetscCall(VecGetArray(X_, &x));
    loading_.Apply(0.0, x, x + n);
    PetscCall(VecRestoreArray(X_, &x));
  }
  PetscCall(TSCreate(comm_, &ts_));
  PetscCall(TSSetProblemType(ts_, TS_NONLINEAR));
  PetscCall(TSSetType(ts_, TSBASICSYMPLECTIC));
  PetscCall(TSBasicSymplecticSetType(ts_, TSBASICSYMPLECTICVELVERLET));
  PetscCall(TSRHSSplitSetIS(ts_, "position", is_position_));
  PetscCall(TSRHSSplitSetIS(ts_, "momentum", is_momentum_));
  PetscCall(TSRHSSplitSetRHSFunction(ts_, "position", nullptr, RHSPosition, this));
  PetscCall(TSRHSSplitSetRHSFunction(ts_, "momentum", nullptr, RHSMomentum, this));
  PetscCall(TSSetRHSFunction(ts_, nullptr, RHSFull, this));
  PetscCall(TSSetTimeStep(ts_, step_control_.current()));
  const double end_time = loading_.end_time();
  PetscCall(TSSetMaxTime(ts_, end_time));
  PetscCall(TSSetMaxSteps(ts_, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts_, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetPreStep(ts_, PreStep));
  PetscCall(TSSetPostStep(ts_, PostStep));
  PetscCall(TSSetApplicationContext(ts_, this));
  PetscCall(TSSetSolution(ts_, X_));
  PetscCall(TSSetFromOptions(ts_));
  // -end_step: the run stops after that step on purpose (Run tells it from a stop by
  // PETSc's -ts_max_steps, which is an error short of the end time).
  if (scene_.time_stepping.end_step >= 0) {
    PetscInt max_steps;
    PetscCall(TSGetMaxSteps(ts_, &max_steps));
    if (scene_.time_stepping.end_step < max_steps) PetscCall(TSSetMaxSteps(ts_, scene_.time_stepping.end_step));
  }
  if (scene_.run.solver != SolverKind::static_newton) { // (a static run has no time step)
    TSType type;
    PetscCall(TSGetType(ts_, &type));
    PetscReal dt;
    PetscCall(TSGetTimeStep(ts_, &dt));
    const double stable = step_control_.stable();
    if (dt != step_control_.current()) {
      step_control_.SetBaseStep(dt);
      PetscCall(PetscPrintf(comm_, "Time step set by -ts_dt: %.4e s (%.3g x stable)\n", dt, dt / stable));
      PetscCall(step_control_.CheckFixedStep(comm_, "-ts_dt", dt)); // (refused well above the stable step)
    }
    const PetscInt steps = (PetscInt)std::ceil(end_time / step_control_.current() - 1e-9);
    PetscCall(PetscPrintf(comm_, "Time stepping: %s, dt = %.4e s, end time %.4e s, about %" PetscInt_FMT " steps\n", type, step_control_.current(),
                          end_time, steps));
  }
  PetscFunctionReturn(0);
}

// The driver at D = 2 and 3 (main.cpp chooses one from the scene): the members defined
// here, one by one. simulation.cpp instantiates the class, which covers only what it
// defines; a class may be explicitly instantiated once in a program.
#define BAPD_SIMULATION_DYNAMICS(D) \
  template PetscErrorCode SimulationD<D>::ComputeForceDensity(const double *u_owned, double *force_density); \
  template PetscErrorCode SimulationD<D>::Acceleration(const double *u_owned, double *a_owned); \
  template PetscErrorCode SimulationD<D>::PreStep(TS ts); \
  template PetscErrorCode SimulationD<D>::RHSPosition(TS, PetscReal, Vec V, Vec Udot, void *); \
  template PetscErrorCode SimulationD<D>::RHSMomentum(TS, PetscReal, Vec U, Vec Vdot, void *ctx); \
  template PetscErrorCode SimulationD<D>::RHSFull(TS, PetscReal, Vec X, Vec F, void *ctx); \
  template PetscErrorCode SimulationD<D>::SetupTimeStepper();
BAPD_SIMULATION_DYNAMICS(2)
BAPD_SIMULATION_DYNAMICS(3)
#undef BAPD_SIMULATION_DYNAMICS

} // namespace bapd
