// Bond failure across ranks, and the health checks that stop a run that diverged.
#include "bapd/simulation.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "bapd/ba_force_energy.hpp"
#include "bapd/damage.hpp"
#include "bapd/models.hpp"
#include "bapd/lattice.hpp"
#include "bapd/reproducible_sum.hpp"

namespace bapd {

// The owner of a point evaluates every bond of it and every bond towards it, so its
// intact mask is the complete one; a rank holding the point as a ring-1 ghost may
// miss a failure of (j -> i) when j is a ring-2 ghost there (and, across a notch, j
// can still sit inside B_ik of an owned k). Copying the owners' masks to the ring-1
// ghosts after every breaking pass keeps every layout on the same bond state.
PetscErrorCode Simulation::CreateBondStateExchange()
{
  std::vector<PetscInt> starts(size_ + 1);
  PetscInt              mine = layout_.owned_start;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Allgather(&mine, 1, MPIU_INT, starts.data(), 1, MPIU_INT, comm_));
  starts[size_] = layout_.n_global;
  std::vector<PetscSFNode> remote(layout_.n_ring1);
  for (PetscInt g = 0; g < layout_.n_ring1; ++g) {
    const PetscInt p = layout_.petsc_index[layout_.n_owned + g];
    const int      r = (int)(std::upper_bound(starts.begin(), starts.end(), p) - starts.begin()) - 1;
    remote[g].rank   = r;
    remote[g].index  = p - starts[r];
  }
  PetscCall(PetscSFCreate(comm_, &bond_state_sf_));
  PetscCall(PetscSFSetGraph(bond_state_sf_, layout_.n_owned, layout_.n_ring1, nullptr, PETSC_COPY_VALUES, remote.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(bond_state_sf_));
  ghost_masks_.resize(layout_.n_ring1 * families_.mask_words);
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::SynchroniseGhostBondState(std::vector<std::size_t> *touched)
{
  MPI_Datatype   unit;
  const std::size_t W = families_.mask_words;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Type_contiguous((int)W, MPI_UINT64_T, &unit));
  PetscCallMPI(MPI_Type_commit(&unit));
  PetscCall(PetscSFBcastBegin(bond_state_sf_, unit, bond_state_.intact.data(), ghost_masks_.data(), MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(bond_state_sf_, unit, bond_state_.intact.data(), ghost_masks_.data(), MPI_REPLACE));
  PetscCallMPI(MPI_Type_free(&unit));
  std::uint64_t *ghost = bond_state_.intact.data() + layout_.n_owned * W;
  for (PetscInt g = 0; g < layout_.n_ring1; ++g)
    if (!std::equal(ghost + g * W, ghost + (g + 1) * W, ghost_masks_.data() + g * W)) {
      std::copy(ghost_masks_.data() + g * W, ghost_masks_.data() + (g + 1) * W, ghost + g * W);
      touched->push_back((std::size_t)(layout_.n_owned + g));
    }
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::BreakBonds()
{
  PetscFunctionBegin;
  std::vector<std::size_t> touched;
  // Bonds whose model hit the Gent chain limit in the last force evaluation break
  // too (the polymer chains rupture). A rank may miss the failure of a copy (j -> i)
  // when it holds j only as a ring-2 ghost; then j lies beyond one horizon of every
  // owned point and the stale bit never enters an owned force (see README).
  break_failed_bonds(families_, bond_state_, workspace_.failed, touched);
  workspace_.failed.clear();
  std::vector<std::size_t> stretched;
  break_bonds(layout_.cloud, y_.data(), families_, scene_.critical_stretch, bond_state_, stretched);
  touched.insert(touched.end(), stretched.begin(), stretched.end());
  PetscCall(SynchroniseGhostBondState(&touched));
  if (!touched.empty()) compute_bond_geometry(layout_.cloud, families_, bond_state_, geometry_, touched);
  PetscFunctionReturn(0);
}

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
  // breaks (BreakBonds); without it, the run cannot go on.
  int flags[3] = {worst >= 0, (int)last_stats_.inverted, (int)last_stats_.chain_limit};
  int global[3];
  PetscCallMPI(MPI_Allreduce(flags, global, 3, MPI_INT, MPI_SUM, comm_));
  // Where: the first bad owned point (NaN) or the first failed bond's point, reported
  // by the lowest rank that has one.
  double where[3] = {-1, 0, 0};
  if (worst >= 0) where[0] = (double)layout_.cloud.natural_id[worst], where[1] = layout_.cloud.x[2 * worst], where[2] = layout_.cloud.x[2 * worst + 1];
  else if (last_stats_.first_point != KernelStats::none) {
    const std::size_t i = last_stats_.first_point;
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
      std::snprintf(msg, sizeof msg, "the solution became NaN/Inf at step %" PetscInt_FMT " (t = %.6e s). The time step %.4e s is probably too large: lower -time_step or -time_step_safety (stable estimate %.4e s).", step, t, dt_, stable_dt_);
    else if (global[1])
      std::snprintf(msg, sizeof msg, "%d bond(s) inverted (det F <= 0) at step %" PetscInt_FMT " (t = %.6e s): the run is unstable; lower -time_step or -time_step_safety (stable estimate %.4e s).", global[1], step, t, stable_dt_);
    else
      std::snprintf(msg, sizeof msg, "%d bond(s) reached the Gent chain-extension limit (I1bar - 3 >= Jm) at step %" PetscInt_FMT " (t = %.6e s), where the model has no finite energy: raise -material_Jm, lower the load, or enable failure (-failure_critical_stretch) so such bonds break.", global[2], step, t);
    stop_reason_      = std::string(msg) + at;
    stopped_on_error_ = true;
  }
  PetscFunctionReturn(0);
}

} // namespace bapd
