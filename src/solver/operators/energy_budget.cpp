// The run's energy budget (energy_budget.hpp).
#include "bapd/solver/operators/energy_budget.hpp"

#include <algorithm>

#include "bapd/solver/operators/relaxation.hpp"
#include "bapd/solver/parallel/reproducible_sum.hpp"

namespace bapd {

PetscErrorCode EnergyBudget::Setup(const Loading &loading, const Layout &layout, double density, std::size_t load_sets)
{
  PetscFunctionBegin;
  D_       = loading.dimension();
  n_       = layout.n_owned;
  volume_  = layout.cloud.volume.data();
  density_ = density;
  // ReproducibleSum's limit: 16 columns, the damping and one a load set.
  PetscCheck(load_sets + 1 <= 16, PETSC_COMM_SELF, PETSC_ERR_SUP, "The energy budget handles at most 15 load sets, the scene has %zu",
             load_sets);
  std::vector<std::size_t> set_of(n_, load_sets); // load_sets: none
  for (std::size_t s = 0; s < load_sets; ++s)
    for (PetscInt i : loading.load_set_points()[s].points)
      if (set_of[i] == load_sets) set_of[i] = s;
  grips_.clear();
  for (const ConstrainedDof &d : loading.constrained()) {
    const PetscInt i = d.dof / D_;
    // A dof held by no load set (none today) would do work no column reports.
    PetscCheck(set_of[i] < load_sets, PETSC_COMM_SELF, PETSC_ERR_PLIB, "A held dof outside every load set");
    grips_.push_back({d.dof, i, set_of[i], density * volume_[i]});
  }
  u_start_.assign(grips_.size(), 0.0);
  force_sum_.assign(grips_.size(), 0.0);
  v_damped_.assign(grips_.size(), 0.0);
  terms_.assign((std::size_t)n_ * (1 + load_sets), 0.0);
  work_.assign(load_sets, 0.0);
  sums_.assign(1 + load_sets, 0.0);
  damped_ = released_ = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode EnergyBudget::Start(MPI_Comm comm, const double *v_owned)
{
  const std::size_t columns = 1 + work_.size();

  PetscFunctionBegin;
  std::fill(terms_.begin(), terms_.end(), 0.0);
  for (const GripDof &g : grips_) terms_[columns * g.point + 1 + g.set] += 0.5 * g.mass * v_owned[g.dof] * v_owned[g.dof];
  PetscCall(ReproducibleSum(comm, (PetscInt)columns, n_, terms_.data(), sums_.data()));
  for (std::size_t s = 0; s < work_.size(); ++s) work_[s] = sums_[1 + s];
  PetscFunctionReturn(0);
}

void EnergyBudget::BeginStep(const double *u_owned)
{
  for (std::size_t k = 0; k < grips_.size(); ++k) u_start_[k] = u_owned[grips_[k].dof];
  std::fill(force_sum_.begin(), force_sum_.end(), 0.0);
  evaluations_ = 0;
}

void EnergyBudget::RecordForce(const double *force_density)
{
  for (std::size_t k = 0; k < grips_.size(); ++k) force_sum_[k] += force_density[grips_[k].dof];
  ++evaluations_;
}

void EnergyBudget::Damp(const double *v_owned, double decay)
{
  const std::size_t columns = 1 + work_.size();
  const double      lost    = 1.0 - decay * decay;
  for (PetscInt i = 0; i < n_; ++i) {
    const double m = density_ * volume_[i], *v = v_owned + D_ * i;
    terms_[columns * i] = lost * (D_ == 2 ? PointKineticEnergy<2>(m, v) : PointKineticEnergy<3>(m, v));
  }
  for (std::size_t k = 0; k < grips_.size(); ++k) v_damped_[k] = decay * v_owned[grips_[k].dof];
}

PetscErrorCode EnergyBudget::EndStep(MPI_Comm comm, const double *u_owned, const double *v_owned)
{
  const std::size_t columns = 1 + work_.size();

  PetscFunctionBegin;
  // Only the grips' points hold work terms (Start zeroed the rest for good).
  for (const GripDof &g : grips_) terms_[columns * g.point + 1 + g.set] = 0.0;
  const double inv_evaluations = evaluations_ > 0 ? 1.0 / evaluations_ : 0.0;
  for (std::size_t k = 0; k < grips_.size(); ++k) {
    const GripDof &g = grips_[k];
    const double   v = v_owned[g.dof];
    terms_[columns * g.point + 1 + g.set] += -force_sum_[k] * inv_evaluations * volume_[g.point] * (u_owned[g.dof] - u_start_[k]) +
                                             0.5 * g.mass * (v * v - v_damped_[k] * v_damped_[k]);
  }
  PetscCall(ReproducibleSum(comm, (PetscInt)columns, n_, terms_.data(), sums_.data()));
  damped_ += sums_[0];
  for (std::size_t s = 0; s < work_.size(); ++s) work_[s] += sums_[1 + s];
  PetscFunctionReturn(0);
}

double EnergyBudget::grip_work_total() const
{
  double total = 0;
  for (double w : work_) total += w;
  return total;
}

void EnergyBudget::totals(std::vector<double> *out) const
{
  out->resize(2 + work_.size());
  (*out)[0] = damped_;
  (*out)[1] = released_;
  std::copy(work_.begin(), work_.end(), out->begin() + 2);
}

void EnergyBudget::RestoreTotals(const std::vector<double> &totals)
{
  damped_   = totals[0];
  released_ = totals[1];
  std::copy(totals.begin() + 2, totals.end(), work_.begin());
}

} // namespace bapd
