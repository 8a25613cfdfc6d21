// Time-step control: the crack-tip search (time_step_control.hpp).
//
// A bond that breaks leaves its two points with families that are no longer whole.
// The bond-associated deformation gradients of the bonds that remain there rest on
// smaller, lopsided shape tensors, so their forces answer a small motion of such a
// point several times as stiffly as at rest. That mode lives on a handful of points at
// the crack tip. The re-estimate, warm-started from the body's own mode with a white
// start vector mixed in, sees next to nothing of it. Measured on the notched sheet
// (dx = 0.5 mm, Gamma = 165 J/m^2, -time_step_monitor_reference 30): once the crack
// ran, the converged lambda_max was 2.4 to 7.7 x its value at rest while the
// estimates in use stayed at 1.0 x. A step of 0.8 x the stable one at rest is
// unstable for such a mode, and single points ahead of the tip were thrown off at
// 15-800 m/s with energy from nowhere (docs/validation.md 3.3).
//
// So a step whose breaking pass broke bonds is followed by a Krylov search that
// starts where they broke: the start vector restricted to the points of the broken
// bonds. Each Krylov step spreads the space by a horizon or two, so a few steps
// cover the neighbourhood of the tip, and the Rayleigh-Ritz value over that space is
// that neighbourhood's stiffest mode (a lower bound of lambda_max, like every
// estimate here). The search costs 1 + options_.tip force evaluations, and only in
// the steps that break bonds.
#include "bapd/solver/operators/time_step_control.hpp"

#include <algorithm>
#include <cmath>

namespace bapd {

PetscErrorCode TimeStepControl::CrackTipSearch(MPI_Comm comm, ForceOperator &force, const std::vector<std::size_t> &touched, PetscInt n_owned,
                                               bool *raised)
{
  const int D = dimension_;

  PetscFunctionBegin;
  *raised           = false;
  const double wall = MPI_Wtime();
  // The start vector on the owned points of the broken bonds (the same points on any
  // number of ranks: both copies of a bond break together), zero elsewhere; seed_ is
  // zero on the held dofs.
  std::copy(v_.begin(), v_.end(), v_kept_.begin());
  std::fill(v_.begin(), v_.end(), 0.0);
  for (std::size_t i : touched)
    if ((PetscInt)i < n_owned)
      for (int c = 0; c < D; ++c) v_[D * i + c] = seed_[D * i + c];
  double norm2;
  PetscCall(Dot(comm, v_.data(), v_.data(), &norm2));
  if (!(norm2 > 0)) { // only held points lost bonds: nothing to search
    std::copy(v_kept_.begin(), v_kept_.end(), v_.begin());
    PetscFunctionReturn(0);
  }
  // The base point with the bonds as they are now (Reestimate explains why a stale
  // one reads the broken bonds' forces as a stiffness).
  const std::vector<double> &committed = force.warm_start();
  PetscCall(ProbeAcceleration(force, committed, nullptr, inv_rho_, held_, u_rec_.data(), a_rec_.data()));
  ++evaluations_;
  PetscCall(KrylovStart(comm));
  double   lambda = 0;
  PetscInt steps  = 0;
  bool     exhausted = false;
  while (steps < options_.tip && !exhausted) {
    PetscCall(KrylovStep(comm, force, committed, u_rec_.data(), a_rec_.data(), steps, &lambda, &exhausted));
    ++steps;
    if (!std::isfinite(lambda)) break;
  }
  ++tip_searches_;
  bool accept = std::isfinite(lambda) && lambda > (1.0 + options_.band) * lambda_;
  if (accept) {
    // Every quotient that would shorten the step is measured from both sides (two
    // evaluations, a few times a run): bonds at a crack tip sit at switches of the
    // force (near failure, in compression) far more often than in the body.
    KrylovFinish(steps); // the Ritz vector: Kink reads it, and the next re-estimates start from it
    bool kink = false;
    PetscCall(Kink(comm, force, committed, lambda, &kink));
    if (kink) ++kinks_, accept = false;
  }
  if (accept) {
    lambda_         = lambda;
    lambda_largest_ = std::max(lambda_largest_, lambda_);
    stable_now_     = 2.0 / std::sqrt(1.1 * lambda_);
    *raised         = true;
  } else std::copy(v_kept_.begin(), v_kept_.end(), v_.begin());
  if (options_.monitor)
    PetscCall(PetscPrintf(comm, "crack-tip search (%" PetscInt_FMT " Krylov steps): lambda_max %.6e 1/s^2 (%.4g x at rest)%s\n", steps, lambda,
                          lambda / lambda_rest_, accept ? ": the estimate in use" : ""));
  estimate_wall_ += MPI_Wtime() - wall;
  PetscFunctionReturn(0);
}

PetscErrorCode TimeStepControl::FollowCrackTip(MPI_Comm comm, ForceOperator &force, const std::vector<std::size_t> &touched, PetscInt n_owned,
                                               PetscInt step)
{
  bool raised = false;

  PetscFunctionBegin;
  PetscCall(CrackTipSearch(comm, force, touched, n_owned, &raised));
  // A stiffer tip shortens the step at once; the re-estimates then follow its mode
  // (the warm start), soon and at the option's pace, and let the step grow back as
  // they would after any shortening.
  if (raised && StiffnessTarget() < (1.0 - options_.band) * stiffness_dt_) {
    stiffness_dt_ = StiffnessTarget();
    ++tip_shortenings_;
    next_estimate_ = std::min(next_estimate_, step + std::max<PetscInt>(1, options_.interval / 5));
    interval_now_  = options_.interval;
    stretch_now_   = options_.stretch;
  }
  PetscFunctionReturn(0);
}

} // namespace bapd
