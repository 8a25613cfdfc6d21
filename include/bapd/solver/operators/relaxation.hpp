#pragma once
// Adaptive dynamic relaxation: a faster route to the static states of a slowly loaded
// body (docs/method.md section 6; docs/options_run.md, "Static states faster").
//
// Damped explicit dynamics reaches a static state fastest when its slowest mode is
// critically damped, c = 2 omega_min (mass-proportional damping: every underdamped
// mode then decays at c/2 as well). omega_min changes as the body deforms and is not
// known in advance, so adaptive dynamic relaxation (Underwood 1983; Kilic & Madenci
// 2010, eq 25: c = 2 sqrt(u^T K u / u^T u) with a local stiffness from consecutive
// force densities) estimates it from the motion itself. Here the estimate is the
// Rayleigh quotient of the secant stiffness along the latest displacement increment,
// from the last two force evaluations (velocity Verlet: this step's and the last one's):
//
//     omega^2 = - sum_i V_i (du_i . da_i) / sum_i V_i |du_i|^2     (free dofs only)
//
// (du^T K du / du^T M du with K du = -M da.) Late in a hold the motion that is left
// is the slowest mode, so omega -> omega_min and c -> 2 omega_min; early on the
// quotient is larger (faster modes), the body is over-damped and the faster modes go
// first. The coefficient is c = clamp(2 omega, c_floor, 2 omega_max), with c_floor =
// -damping (which keeps the bond-only form's edge flutter down, docs/stability.md)
// and omega_max = 2/dt_stable; c = c_floor when the quotient is not positive (no
// motion, round-off). Both sums are reproducible sums, so c is the same on any
// number of ranks. PETSc's velocity Verlet evaluates the force once a step (at the
// half-step position), so the pair spans two steps: the latest evaluation is saved in
// checkpoints (/relaxation, checkpoint.hpp) and a restart continues bit for bit.
// The dimension D (2 or 3) is the number of dofs a point: du_i and
// da_i have D components, held dofs are D i + c.
#include <petscsys.h>

#include <algorithm>
#include <vector>

#include "bapd/solver/input/scene_time_stepping.hpp"

namespace bapd {


// The kinetic energy of a point of mass m and velocity v (D components),
// 1/2 m v.v, v.v summed from its first term (for D = 2 the history's arithmetic).
template <int D> inline double PointKineticEnergy(double m, const double *v)
{
  double vv = v[0] * v[0];
  for (int c = 1; c < D; ++c) vv = vv + v[c] * v[c];
  return 0.5 * m * vv;
}

template <int D> class AdaptiveRelaxation {
public:
  // n_owned points with volumes `volume` (kept by pointer), held dofs (D i + c) of
  // the grips, the damping floor (1/s) and the stable step (caps c at 4/dt_stable).
  void Setup(RelaxationKind kind, std::size_t n_owned, const double *volume, const std::vector<PetscInt> &held_dofs,
             double floor, double stable_dt);
  bool active() const { return kind_ == RelaxationKind::adaptive; }
  // The stable step re-estimated during the run (time_step_control.hpp): the cap
  // follows it, 2 omega_max = 4 / dt_stable, so a stiffer material may be damped harder.
  void FollowStableStep(double stable_dt) { cap_ = std::max(floor_, 2.0 * 2.0 / stable_dt); }
  // Every acceleration the dynamics evaluates (owned u and a, D per point): keeps the
  // last two. A copy, no allocation.
  void Record(const double *u, const double *a);
  // The damping coefficient for this step (1/s). Collective.
  PetscErrorCode Damping(MPI_Comm comm, double *c);
  // Range of the coefficient so far (for the summary).
  // Checkpoints: the latest evaluation is the state carried from step to step (the
  // next step's quotient is formed against it). RestoreLatest: latest_u()/latest_a()
  // were filled from a checkpoint that had `records` evaluations.
  int     records() const { return recorded_; }
  double *latest_u() { return u_[latest_].data(); }
  double *latest_a() { return a_[latest_].data(); }
  void    RestoreLatest(int records) { recorded_ = records > 0 ? 1 : 0; }
  double last() const { return last_; }
  double smallest() const { return smallest_; }
  double largest() const { return largest_; }

private:
  RelaxationKind      kind_ = RelaxationKind::none;
  std::size_t         n_    = 0;
  const double       *volume_ = nullptr;
  std::vector<char>   free_;      // D per point: 1 unless a grip holds it
  std::vector<double> u_[2], a_[2];
  std::vector<double> terms_;     // 2 per point: V du.(-da), V |du|^2
  int                 latest_ = 1, recorded_ = 0;
  double              floor_ = 0, cap_ = 0;
  double              last_ = 0, smallest_ = 0, largest_ = 0;
};

extern template class AdaptiveRelaxation<2>;
extern template class AdaptiveRelaxation<3>;

} // namespace bapd
