// Bond failure across ranks (failure.hpp).
#include "bapd/solver/operators/failure.hpp"

#include <algorithm>

#include "bapd/core/kernel/damage.hpp"

namespace bapd {

Failure::~Failure()
{
  PetscSFDestroy(&sf_);
  if (mask_ != MPI_DATATYPE_NULL) MPI_Type_free(&mask_);
  if (damage_type_ != MPI_DATATYPE_NULL) MPI_Type_free(&damage_type_);
}

PetscErrorCode Failure::SetupSoftening(Softening law, double fracture_energy, double fade_time, BondState &state)
{
  PetscFunctionBegin;
  softening_       = law;
  fracture_energy_ = fracture_energy;
  fade_time_       = fade_time;
  if (law == Softening::none) PetscFunctionReturn(0);
  // (The time law starts at the criterion and dissipates what the sheet gives up while
  // the bond fades: any kappa; the strain laws' branch must start below Gamma.)
  PetscCheck(by_energy() && (law == Softening::time ? fade_time > 0 : critical_release_ < fracture_energy), comm_,
             PETSC_ERR_ARG_WRONG, "softening needs the fracture-energy criterion with kappa < 1, the time law tau > 0");
  const Families &f = *families_;
  state.damage.assign(f.neighbour.size(), 0.0);
  unsigned long long largest = 0;
  for (std::size_t i = 0; i < f.n_family; ++i) largest = std::max<unsigned long long>(largest, f.size(i));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &largest, 1, MPI_UNSIGNED_LONG_LONG, MPI_MAX, comm_));
  stride_ = (std::size_t)std::max<unsigned long long>(largest, 1);
  PetscCallMPI(MPI_Type_contiguous((int)stride_, MPI_DOUBLE, &damage_type_));
  PetscCallMPI(MPI_Type_commit(&damage_type_));
  owned_damage_.assign((std::size_t)layout_->n_owned * stride_, 0.0);
  ghost_damage_.assign((std::size_t)layout_->n_ring1 * stride_, 0.0);
  softened_.assign((std::size_t)layout_->n_owned, 0.0);
  PetscFunctionReturn(0);
}

// As the masks (SynchroniseGhosts): a ring-1 ghost's bond towards a ring-2 ghost is the
// owner's to soften, and the ghost's d enters the forces t_ji of its owned neighbours.
PetscErrorCode Failure::SynchroniseDamage(BondState &state)
{
  const Families &f = *families_;

  PetscFunctionBegin;
  for (PetscInt i = 0; i < layout_->n_owned; ++i)
    std::copy(state.damage.begin() + (std::ptrdiff_t)f.offsets[i], state.damage.begin() + (std::ptrdiff_t)f.offsets[i + 1],
              owned_damage_.begin() + (std::ptrdiff_t)(i * stride_));
  PetscCall(PetscSFBcastBegin(sf_, damage_type_, owned_damage_.data(), ghost_damage_.data(), MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf_, damage_type_, owned_damage_.data(), ghost_damage_.data(), MPI_REPLACE));
  for (PetscInt g = 0; g < layout_->n_ring1; ++g) {
    const std::size_t p = (std::size_t)(layout_->n_owned + g);
    std::copy(ghost_damage_.begin() + (std::ptrdiff_t)(g * stride_), ghost_damage_.begin() + (std::ptrdiff_t)(g * stride_ + f.size(p)),
              state.damage.begin() + (std::ptrdiff_t)f.offsets[p]);
  }
  PetscFunctionReturn(0);
}

void Failure::EnergyPass(BondState &state, Fading fading)
{
  if (softening_ == Softening::none)
    break_bonds_by_energy(layout_->cloud, *families_, psi_.data(), crossing_.data(), critical_release_, state, stretched_);
  else
    soften_bonds(softening_, layout_->cloud, *families_, psi_.data(), crossing_.data(), critical_release_, fracture_energy_, fading,
                 state, stretched_, softened_.data(), softened_.size());
}

// The owner of a point evaluates every bond of it and every bond towards it, so its
// intact mask is the complete one; a rank holding the point as a ring-1 ghost may
// miss a failure of (j -> i) when j is a ring-2 ghost there (and, across a notch, j
// can still sit inside B_ik of an owned k). Copying the owners' masks to the ring-1
// ghosts after every breaking pass keeps every layout on the same bond state.
PetscErrorCode Failure::Setup(MPI_Comm comm, const Layout &layout, const Families &families, double critical_stretch,
                              double critical_release, int dimension, double horizon, double thickness)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  comm_             = comm;
  layout_           = &layout;
  families_         = &families;
  {
    // The criterion (failure.hpp): the critical stretch, or the critical energy release
    // with the bonds' energies and the family points' crossing densities.
    const PointCloud &cloud = layout.cloud;
    critical_stretch_       = critical_stretch;
    critical_release_       = critical_release;
    if (critical_release > 0) psi_.assign(families.neighbour.size(), -1.0);
    crossing_.resize(families.n_family);
    // Uniform lattices share one (volume, horizon): computed once.
    double last_volume = -1, last_horizon = -1, last = 0;
    for (std::size_t i = 0; i < families.n_family; ++i) {
      const double v = cloud.volume[i], h = cloud.horizon.empty() ? horizon : cloud.horizon[i];
      if (v != last_volume || h != last_horizon) last = crossing_density(dimension, v, h, thickness), last_volume = v, last_horizon = h;
      crossing_[i] = last;
    }
  }
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<PetscInt> starts(size + 1);
  PetscInt              mine = layout.owned_start;
  PetscCallMPI(MPI_Allgather(&mine, 1, MPIU_INT, starts.data(), 1, MPIU_INT, comm));
  starts[size] = layout.n_global;
  std::vector<PetscSFNode> remote(layout.n_ring1);
  for (PetscInt g = 0; g < layout.n_ring1; ++g) {
    const PetscInt p = layout.petsc_index[layout.n_owned + g];
    const int      r = (int)(std::upper_bound(starts.begin(), starts.end(), p) - starts.begin()) - 1;
    remote[g].rank   = r;
    remote[g].index  = p - starts[r];
  }
  PetscCall(PetscSFCreate(comm, &sf_));
  PetscCall(PetscSFSetGraph(sf_, layout.n_owned, layout.n_ring1, nullptr, PETSC_COPY_VALUES, remote.data(), PETSC_COPY_VALUES));
  PetscCall(PetscSFSetUp(sf_));
  PetscCallMPI(MPI_Type_contiguous((int)families.mask_words, MPI_UINT64_T, &mask_));
  PetscCallMPI(MPI_Type_commit(&mask_));
  ghost_masks_.resize(layout.n_ring1 * families.mask_words);
  // touched_ holds one entry a point after Break and after each Cascade pass (both make
  // it unique). Before that, Break lists each local point at most once for its failed
  // bonds (once their list, 2 entries a bond, is made unique), once a family point for
  // the criterion and once a ring-1 ghost for the exchange, and a pass adds to the
  // unique list at most one a family point and one a ring-1 ghost: n_local + n_family +
  // n_ring1 entries bound it however long the cascade. And the failed bonds' list fits
  // for up to 1.5 n_family bonds that fail in one step, as before.
  touched_.reserve((std::size_t)layout.n_local() + 2 * (std::size_t)layout.n_family());
  stretched_.reserve((std::size_t)layout.n_family());
  pass_.reserve((std::size_t)layout.n_family() + (std::size_t)layout.n_ring1); // a pass's family points and ring-1 ghosts
  PetscFunctionReturn(0);
}

// Sorted, one entry a point (in place: no allocation); its readers take it as a set.
void Failure::TouchedOnce()
{
  std::sort(touched_.begin(), touched_.end());
  touched_.erase(std::unique(touched_.begin(), touched_.end()), touched_.end());
}

PetscErrorCode Failure::SynchroniseGhosts(BondState &state)
{
  const std::size_t W = families_->mask_words;

  PetscFunctionBegin;
  PetscCall(PetscSFBcastBegin(sf_, mask_, state.intact.data(), ghost_masks_.data(), MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf_, mask_, state.intact.data(), ghost_masks_.data(), MPI_REPLACE));
  std::uint64_t *ghost = state.intact.data() + layout_->n_owned * W;
  for (PetscInt g = 0; g < layout_->n_ring1; ++g)
    if (!std::equal(ghost + g * W, ghost + (g + 1) * W, ghost_masks_.data() + g * W)) {
      std::copy(ghost_masks_.data() + g * W, ghost_masks_.data() + (g + 1) * W, ghost + g * W);
      touched_.push_back((std::size_t)(layout_->n_owned + g));
    }
  PetscFunctionReturn(0);
}

template <int D>
PetscErrorCode Failure::Break(const double *y, double dt, std::vector<FailedBond> &failed, BondState &state,
                              nd::BondGeometry<D> &geometry)
{
  PetscFunctionBegin;
  touched_.clear();
  // Bonds whose model hit the Gent chain limit in the last force evaluation break
  // too (the polymer chains rupture). A rank may miss the failure of a copy (j -> i)
  // when it holds j only as a ring-2 ghost; then j lies beyond one horizon of every
  // owned point and the stale bit never enters an owned force (see README).
  break_failed_bonds(*families_, state, failed, touched_);
  failed.clear();
  std::fill(softened_.begin(), softened_.end(), 0.0);
  // The time law: the bonds fading since an earlier step fade by dt / tau here, once a
  // step; a bond that meets the criterion in this pass or a Cascade starts at dt / tau.
  step_fade_ = softening_ == Softening::time ? dt / fade_time_ : 0.0;
  if (by_energy()) EnergyPass(state, Fading{step_fade_, step_fade_});
  else nd::break_bonds<D>(layout_->cloud, y, *families_, critical_stretch_, state, stretched_);
  touched_.insert(touched_.end(), stretched_.begin(), stretched_.end());
  PetscCall(SynchroniseGhosts(state));
  if (softening()) PetscCall(SynchroniseDamage(state));
  if (!touched_.empty()) nd::compute_bond_geometry<D>(layout_->cloud, *families_, state, geometry, touched_);
  TouchedOnce();
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode Failure::Cascade(BondState &state, nd::BondGeometry<D> &geometry, bool *more)
{
  PetscFunctionBegin;
  const std::size_t first = touched_.size();
  EnergyPass(state, Fading{step_fade_, 0.0});
  touched_.insert(touched_.end(), stretched_.begin(), stretched_.end());
  PetscCall(SynchroniseGhosts(state));
  if (softening()) PetscCall(SynchroniseDamage(state));
  int any = touched_.size() > first ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_LOR, comm_));
  *more = any != 0;
  if (touched_.size() > first) {
    pass_.assign(touched_.begin() + (std::ptrdiff_t)first, touched_.end());
    nd::compute_bond_geometry<D>(layout_->cloud, *families_, state, geometry, pass_);
    TouchedOnce();
  }
  PetscFunctionReturn(0);
}

template PetscErrorCode Failure::Cascade<2>(BondState &, nd::BondGeometry<2> &, bool *);
template PetscErrorCode Failure::Cascade<3>(BondState &, nd::BondGeometry<3> &, bool *);
template PetscErrorCode Failure::Break<2>(const double *, double, std::vector<FailedBond> &, BondState &, nd::BondGeometry<2> &);
template PetscErrorCode Failure::Break<3>(const double *, double, std::vector<FailedBond> &, BondState &, nd::BondGeometry<3> &);

} // namespace bapd
