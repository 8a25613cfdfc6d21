// What breaking bonds do to the energy budget: the energy a breaking pass releases and
// the crack it leaves (energy_budget.hpp; docs/method.md section 5.3).
#include "bapd/solver/driver/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bapd/core/kernel/damage.hpp"
#include "bapd/solver/parallel/reproducible_sum.hpp"

namespace bapd {

// Exact for any force form and law, and cheap: W_i depends on the bonds of i alone
// (listed_strain_energies, ba_force.hpp), so only the owned points whose bonds the passes
// changed are evaluated, with the bonds after the passes, then with the bonds before them
// (intact_before_, copied by PostStep; their geometry recomputed for them), and the
// passes' state is put back. Only in a step that broke bonds somewhere (BreakFurther's
// reduction decides); no allocation (the scratch holds every owned point).
template <int D> PetscErrorCode SimulationD<D>::ReleasedEnergy(bool broke, double *released)
{
  PetscFunctionBegin;
  *released = 0;
  // Softening bonds: what the step's passes took from the bonds' (1 - d) Psi before any
  // broke (softening.hpp), every step (a bond softens in steps that break none).
  if (failure_.softening()) PetscCall(ReproducibleSum(comm_, 1, layout_.n_owned, failure_.softened(), released));
  if (!broke) PetscFunctionReturn(0);
  std::vector<std::size_t> &points = released_points_;
  points.clear();
  for (std::size_t p : failure_.touched())
    if (p < (std::size_t)layout_.n_owned) points.push_back(p);
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  const std::size_t count = points.size();
  double *after = released_terms_.data(), *before = point_energy_.data(); // (scratch, n_owned each)
  force_.ListedEnergies(points.data(), count, after);
  auto &intact = bond_state_.intact; // swapped in place: the operators keep pointers to it
  std::swap_ranges(intact.begin(), intact.end(), intact_before_.begin());
  nd::compute_bond_geometry<D>(layout_.cloud, families_, bond_state_, geometry_, points);
  force_.ListedEnergies(points.data(), count, before);
  std::swap_ranges(intact.begin(), intact.end(), intact_before_.begin());
  nd::compute_bond_geometry<D>(layout_.cloud, families_, bond_state_, geometry_, points);
  for (std::size_t k = 0; k < count; ++k) after[k] = before[k] - after[k];
  double broken_release = 0;
  PetscCall(ReproducibleSum(comm_, 1, (PetscInt)count, after, &broken_release));
  *released += broken_release;
  PetscFunctionReturn(0);
}

// A broken bond changes F_ij of the bonds of its two points whose BA family held its
// far end, and ω of the two points: at the same positions some of those bonds can now
// hold a pair energy past (5.2), the more so near a crack's opening, where F_ij then
// reads the opening as strain. Left for the next step, such a bond sits near the Gent
// chain limit, where the plane-stress sheet stiffens on the bulk scale: on the notched
// sheet the crack-tip search found the tip up to 2e5 x as stiff as the body at rest,
// beyond any step the control allows, and points at the tip were thrown off with
// energy that no term of (5.3) holds. Breaking them in the same step, at the same
// positions, is (5.2) applied to the state the pass leaves (docs/method.md 5.2).
// Every pass breaks at least one bond on some rank, so the passes end; each costs one
// evaluation of the bond energies, in the steps that break bonds only. Whether the
// first pass broke a bond on any rank is the step's one reduction of it, with any
// criterion: the released energy and the time-step control are handed it.
template <int D> PetscErrorCode SimulationD<D>::BreakFurther(bool *broke)
{
  PetscFunctionBegin;
  int any = failure_.broke() ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &any, 1, MPI_INT, MPI_LOR, comm_));
  *broke = any != 0;
  if (!failure_.by_energy()) PetscFunctionReturn(0);
  bool more = *broke;
  for (PetscInt pass = 1; more && (scene_.failure.passes == 0 || pass < scene_.failure.passes); ++pass) {
    force_.BondEnergies(failure_.bond_energies());
    PetscCall(failure_.Cascade<D>(bond_state_, geometry_, &more));
  }
  PetscFunctionReturn(0);
}

// The mouth of a 2D notch is the end nearer the body's bounding box (the notch cuts in
// from there); the crack then runs on from the inner end.
template <int D> PetscErrorCode SimulationD<D>::SetupCrackAxis()
{
  const PointCloud &cloud = layout_.cloud;
  double            lo[D], hi[D];

  PetscFunctionBegin;
  for (int r = 0; r < D; ++r) lo[r] = std::numeric_limits<double>::infinity(), hi[r] = -lo[r];
  for (PetscInt i = 0; i < layout_.n_owned; ++i)
    for (int r = 0; r < D; ++r) lo[r] = std::min(lo[r], cloud.x[D * i + r]), hi[r] = std::max(hi[r], cloud.x[D * i + r]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, lo, D, MPI_DOUBLE, MPI_MIN, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, hi, D, MPI_DOUBLE, MPI_MAX, comm_));
  tips_.assign(4 * (std::size_t)size_, 0.0); // CrackExtent's gather
  std::fill(crack_axis_, crack_axis_ + 6, 0.0);
  crack_axis_[0] = lo[0], crack_axis_[3] = 1.0; // +x from the smallest x
  if constexpr (D == 2) {
    if (!scene_.body.sheet.notches.empty()) {
      const Segment &s = scene_.body.sheet.notches.front();
      auto inset = [&](double x, double y) { return std::min({x - lo[0], hi[0] - x, y - lo[1], hi[1] - y}); };
      const bool   first_is_mouth = inset(s.x0, s.y0) <= inset(s.x1, s.y1);
      const double mx = first_is_mouth ? s.x0 : s.x1, my = first_is_mouth ? s.y0 : s.y1;
      const double dx = (first_is_mouth ? s.x1 : s.x0) - mx, dy = (first_is_mouth ? s.y1 : s.y0) - my, length = std::hypot(dx, dy);
      if (length > 0) crack_axis_[0] = mx, crack_axis_[1] = my, crack_axis_[3] = dx / length, crack_axis_[4] = dy / length;
    }
  }
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::CrackExtent(double *area, double tip[4])
{
  const auto  n = (std::size_t)layout_.n_owned;
  PetscMPIInt size;

  PetscFunctionBegin;
  crack_extent(D, layout_.cloud, families_, bond_state_, failure_.crossing(), n, crack_axis_, crack_axis_ + 3,
               point_energy_.data(), tip); // (point_energy_: scratch)
  PetscCall(ReproducibleSum(comm_, 1, (PetscInt)n, point_energy_.data(), area));
  // The lexicographically largest of the ranks' tips: the same on any layout.
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  PetscCallMPI(MPI_Allgather(tip, 4, MPI_DOUBLE, tips_.data(), 4, MPI_DOUBLE, comm_));
  for (PetscMPIInt r = 0; r < size; ++r)
    if (std::lexicographical_compare(tip, tip + 1 + D, &tips_[4 * r], &tips_[4 * r] + 1 + D)) std::copy(&tips_[4 * r], &tips_[4 * r] + 4, tip);
  if (!std::isfinite(tip[0])) std::fill(tip, tip + 4, std::numeric_limits<double>::quiet_NaN());
  PetscFunctionReturn(0);
}

template PetscErrorCode SimulationD<2>::ReleasedEnergy(bool, double *);
template PetscErrorCode SimulationD<3>::ReleasedEnergy(bool, double *);
template PetscErrorCode SimulationD<2>::BreakFurther(bool *);
template PetscErrorCode SimulationD<3>::BreakFurther(bool *);
template PetscErrorCode SimulationD<2>::SetupCrackAxis();
template PetscErrorCode SimulationD<3>::SetupCrackAxis();
template PetscErrorCode SimulationD<2>::CrackExtent(double *, double *);
template PetscErrorCode SimulationD<3>::CrackExtent(double *, double *);

} // namespace bapd
