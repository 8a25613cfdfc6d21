// The health checks that stop a run that diverged: NaN, inverted bonds, the Gent
// limit without failure, and runaway energy (divergence.hpp).
#include "bapd/simulation.hpp"

#include <cmath>
#include <cstdio>

namespace bapd {

// Stops every rank together on NaN, an inverted bond or the Gent limit without failure.
PetscErrorCode Simulation::CheckHealth(PetscInt step, double t, PetscBool *diverged)
{
  const double *x;
  const PetscInt n = 4 * layout_.n_owned;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(X_, &x));
  PetscInt worst = -1;
  for (PetscInt k = 0; k < n; ++k)
    if (!std::isfinite(x[k])) {
      worst = (k % (2 * layout_.n_owned)) / 2;
      break;
    }
  PetscCall(VecRestoreArrayRead(X_, &x));
  // With failure enabled, a bond whose model fails (inverted or at the chain limit)
  // breaks (Failure::Break, failure.hpp); without it, the run cannot go on.
  const KernelStats &stats = force_.stats();
  int flags[3] = {worst >= 0, (int)stats.inverted, (int)stats.chain_limit};
  int global[3];
  PetscCallMPI(MPI_Allreduce(flags, global, 3, MPI_INT, MPI_SUM, comm_));
  // Where: the first bad owned point (NaN) or the first failed bond's point, reported
  // by the lowest rank that has one.
  double where[3] = {-1, 0, 0};
  if (worst >= 0) where[0] = (double)layout_.cloud.natural_id[worst], where[1] = layout_.cloud.x[2 * worst], where[2] = layout_.cloud.x[2 * worst + 1];
  else if (stats.first_point != KernelStats::none) {
    const std::size_t i = stats.first_point;
    where[0] = (double)layout_.cloud.natural_id[i], where[1] = layout_.cloud.x[2 * i], where[2] = layout_.cloud.x[2 * i + 1];
  }
  int have = where[0] >= 0 ? rank_ : size_, first = size_;
  PetscCallMPI(MPI_Allreduce(&have, &first, 1, MPI_INT, MPI_MIN, comm_));
  if (first < size_) PetscCallMPI(MPI_Bcast(where, 3, MPI_DOUBLE, first, comm_));
  char at[160] = "";
  if (first < size_) std::snprintf(at, sizeof at, " First at point %.0f, reference position (%.6g, %.6g) m.", where[0], where[1], where[2]);
  *diverged = PETSC_FALSE;
  if (global[0] || ((global[1] || global[2]) && !scene_.failure)) {
    *diverged = PETSC_TRUE;
    char msg[512];
    if (global[0])
      std::snprintf(msg, sizeof msg, "the solution became NaN/Inf at step %" PetscInt_FMT " (t = %.6e s). The time step %.4e s is probably too large: lower -time_step or -time_step_safety (stable estimate %.4e s).", step, t, step_control_.current(), step_control_.stable());
    else if (global[1])
      std::snprintf(msg, sizeof msg, "%d bond(s) inverted (det F <= 0) at step %" PetscInt_FMT " (t = %.6e s): the run is unstable; lower -time_step or -time_step_safety (stable estimate %.4e s).", global[1], step, t, step_control_.stable());
    else
      std::snprintf(msg, sizeof msg, "%d bond(s) reached the Gent chain-extension limit (I1bar - 3 >= Jm) at step %" PetscInt_FMT " (t = %.6e s), where the model has no finite energy: raise -material_Jm, lower the load, or enable failure (-failure_critical_stretch) so such bonds break.", global[2], step, t);
    stop_reason_      = std::string(msg) + at;
    stopped_on_error_ = true;
  }
  PetscFunctionReturn(0);
}

// Runaway energy (divergence.hpp), handed what it reads.
PetscErrorCode Simulation::CheckRunaway(PetscInt step, double t, std::string *message)
{
  PetscReal dt;

  PetscFunctionBegin;
  PetscCall(TSGetTimeStep(ts_, &dt));
  RunawayInputs inputs;
  inputs.comm      = comm_;
  inputs.scene     = &scene_;
  inputs.schedule  = &loading_.schedule();
  inputs.layout    = &layout_;
  inputs.state     = X_;
  inputs.dt        = dt;
  inputs.stable_dt = step_control_.stable();
  inputs.energies  = [this](double *kinetic, double *internal) { return Energies(kinetic, internal); };
  PetscCall(CheckRunawayEnergy(inputs, energy_monitor_, step, t, message));
  PetscFunctionReturn(0);
}

} // namespace bapd
