// Adaptive dynamic relaxation (relaxation.hpp): the damping coefficient from the
// Rayleigh quotient of the latest displacement increment.
#include "bapd/solver/operators/relaxation.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <string>

#include "bapd/solver/parallel/reproducible_sum.hpp"

namespace bapd {

template <int D> void AdaptiveRelaxation<D>::Setup(RelaxationKind kind, std::size_t n_owned, const double *volume, const std::vector<PetscInt> &held_dofs,
                               double floor, double stable_dt)
{
  kind_   = kind;
  n_      = n_owned;
  volume_ = volume;
  floor_  = floor;
  // Velocity Verlet is stable for omega <= 2/dt_stable: no mode is faster, so no
  // Rayleigh quotient can honestly exceed it (round-off late in a hold can).
  cap_      = std::max(floor, 2.0 * 2.0 / stable_dt);
  last_     = floor;
  smallest_ = cap_;
  largest_  = floor;
  recorded_ = 0;
  if (!active()) return;
  free_.assign(D * n_, 1);
  for (PetscInt d : held_dofs) free_[(std::size_t)d] = 0;
  for (int k = 0; k < 2; ++k) {
    u_[k].assign(D * n_, 0.0);
    a_[k].assign(D * n_, 0.0);
  }
  terms_.assign(2 * n_, 0.0);
}

template <int D> void AdaptiveRelaxation<D>::Record(const double *u, const double *a)
{
  if (!active()) return;
  latest_ = 1 - latest_;
  std::memcpy(u_[latest_].data(), u, sizeof(double) * D * n_);
  std::memcpy(a_[latest_].data(), a, sizeof(double) * D * n_);
  recorded_ = std::min(recorded_ + 1, 2);
}

template <int D> PetscErrorCode AdaptiveRelaxation<D>::Damping(MPI_Comm comm, double *c)
{
  PetscFunctionBegin;
  *c = floor_;
  if (!active()) PetscFunctionReturn(0);
  if (recorded_ == 2) {
    const double *u1 = u_[latest_].data(), *u0 = u_[1 - latest_].data();
    const double *a1 = a_[latest_].data(), *a0 = a_[1 - latest_].data();
    for (std::size_t i = 0; i < n_; ++i) {
      double num = 0, den = 0;
      for (std::size_t k = D * i; k < D * i + D; ++k) {
        if (!free_[k]) continue;
        const double du = u1[k] - u0[k], da = a1[k] - a0[k];
        num -= du * da;
        den += du * du;
      }
      terms_[2 * i]     = volume_[i] * num;
      terms_[2 * i + 1] = volume_[i] * den;
    }
    double sums[2];
    PetscCall(ReproducibleSum(comm, 2, (PetscInt)n_, terms_.data(), sums));
    // omega^2 = du^T K du / du^T M du; not positive (no motion, round-off): the floor.
    if (sums[1] > 0 && sums[0] > 0 && std::isfinite(sums[0] / sums[1])) *c = std::clamp(2.0 * std::sqrt(sums[0] / sums[1]), floor_, cap_);
  }
  last_     = *c;
  smallest_ = std::min(smallest_, *c);
  largest_  = std::max(largest_, *c);
  PetscFunctionReturn(0);
}

template class AdaptiveRelaxation<2>;
template class AdaptiveRelaxation<3>;

} // namespace bapd
