#pragma once
// Failure: bonds break past the critical stretch (paper eq 7), past the critical pair
// energy set by the fracture energy Gamma (damage.hpp; docs/method.md section 5.2), or
// when their model fails (the Gent chain limit), and the owners' bond states are copied to their
// ring-1 ghosts so every rank layout holds the same bond state (README, "Parallel
// design"). Everything a breaking pass uses is allocated at set-up (the geometry's
// recomputation uses the work space of BondGeometry), so a step in which bonds break
// allocates nothing, however long its cascade of passes (touched_ keeps one entry a
// point), as long as the bonds whose model failed in one step are fewer than 1.5 times
// the local family points (their list holds both ends of each before it is made unique).
#include <petscsf.h>

#include <vector>

#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/solver/parallel/layout.hpp"
#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/kernel/softening.hpp"

namespace bapd {

class Failure {
public:
  Failure() = default;
  ~Failure();
  Failure(const Failure &)            = delete;
  Failure &operator=(const Failure &) = delete;

  // Collective: the exchange of intact masks from owners to ring-1 ghosts. One
  // criterion: critical_stretch > 0 (eq 7), or critical_release = kappa Gamma > 0
  // [J/m^2] (docs/method.md (5.2); then the crossing densities of the family points,
  // with the points' horizons, cloud.horizon or horizon for all, and the 2D sheet's
  // thickness).
  PetscErrorCode Setup(MPI_Comm comm, const Layout &layout, const Families &families, double critical_stretch,
                       double critical_release, int dimension, double horizon, double thickness);
  // -failure_softening (softening.hpp; after Setup, with the fracture-energy criterion):
  // bonds soften from the criterion's onset and break at d = 1; sizes state.damage (0:
  // intact) and what the owners' damage copies to their ring-1 ghosts. fade_time: tau [s]
  // of the time law (a bond fades from d = 0 to 1 in tau). Collective.
  PetscErrorCode SetupSoftening(Softening law, double fracture_energy, double fade_time, BondState &state);
  bool           softening() const { return softening_ != Softening::none; }
  // The energy the softening of the last Break and its Cascades took, a value an owned
  // point (softening.hpp's dissipated; 0 without softening): summed reproducibly by the caller.
  const double  *softened() const { return softened_.data(); }
  // The fracture-energy criterion weighs Psi(F_ij): the caller fills bond_energies()
  // (ForceOperator::BondEnergies) at the positions Break is given, before it.
  bool    by_energy() const { return critical_release_ > 0; }
  double *bond_energies() { return psi_.data(); }
  // One breaking pass after a step of length dt [s] at positions y (every local point),
  // with the bonds whose model failed in the step's force evaluation (cleared here);
  // updates the bond state and the geometry of the points whose bonds broke (dt: how
  // far the time law's bonds fade in the step). Collective.
  // D: the body's (y and the geometry D a point; the masks know no dimension).
  template <int D>
  PetscErrorCode Break(const double *y, double dt, std::vector<FailedBond> &failed, BondState &state, nd::BondGeometry<D> &geometry);
  // The fracture-energy criterion again at the same positions, on bond_energies()
  // refilled after the last pass: a broken bond changes F_ij of its neighbours, and
  // those that now meet (5.2) break in this pass, not a step later (docs/method.md
  // section 5.2). touched() gains this pass's points; *more: whether any rank broke a
  // bond in it. Collective.
  template <int D> PetscErrorCode Cascade(BondState &state, nd::BondGeometry<D> &geometry, bool *more);
  // Whether the last Break broke bonds on this rank (owned or ghost copies). Local.
  bool broke() const { return !touched_.empty(); }
  // The points whose bonds the last Break and its Cascades changed (owned and ghost),
  // their geometry recomputed: ascending, one entry a point.
  const std::vector<std::size_t> &touched() const { return touched_; }
  // c_i of every family point (damage.hpp), for either criterion: the crack's area.
  const double *crossing() const { return crossing_.data(); }

private:
  PetscErrorCode SynchroniseGhosts(BondState &state);
  PetscErrorCode SynchroniseDamage(BondState &state);
  // The criterion's pass: breaking at once, or softening (softening.hpp).
  void           EnergyPass(BondState &state, Fading fading);
  void           TouchedOnce(); // touched_ sorted, one entry a point (Setup's reserve counts on it)

  MPI_Comm                 comm_     = MPI_COMM_NULL;
  const Layout            *layout_   = nullptr;
  const Families          *families_ = nullptr;
  double                   critical_stretch_ = 0, critical_release_ = 0;
  std::vector<double>      psi_, crossing_;   // Psi(F_ij) a bond; c_i a family point (damage.hpp)
  PetscSF                  sf_   = nullptr;      // owners' intact masks -> their ring-1 ghost copies
  MPI_Datatype             mask_ = MPI_DATATYPE_NULL; // one point's intact mask
  std::vector<std::uint64_t> ghost_masks_;
  std::vector<std::size_t> touched_, stretched_, pass_; // reserved at set-up
  Softening                softening_       = Softening::none;
  double                   fracture_energy_ = 0, fade_time_ = 0; // Gamma [J/m^2]; tau [s] of the time law
  double                   step_fade_       = 0;                 // dt / tau of the step being broken (Cascade starts bonds with it)
  std::size_t              stride_          = 0;          // the largest family over the ranks: one point's damage in the exchange
  MPI_Datatype             damage_type_     = MPI_DATATYPE_NULL; // stride_ doubles
  std::vector<double>      owned_damage_, ghost_damage_, softened_; // stride_ an owned point, a ring-1 ghost; 1 an owned point
};

} // namespace bapd
