// Time-step control (time_step_control.hpp).
#include "bapd/time_step_control.hpp"

#include <algorithm>
#include <cmath>

#include "bapd/reproducible_sum.hpp"

namespace bapd {

namespace {

// The acceleration of the free dofs, M^{-1} f, with the held ones zero.
PetscErrorCode ProbeAcceleration(ForceOperator &force, std::vector<double> &c33, double inv_rho, const std::vector<char> &held,
                                 const double *u, double *a)
{
  PetscFunctionBegin;
  PetscCall(force.EvaluateWithWarmStart(u, a, c33));
  for (std::size_t k = 0; k < held.size(); ++k) a[k] = held[k] ? 0.0 : a[k] * inv_rho;
  PetscFunctionReturn(0);
}

} // namespace

// Stable step of the linearised system at the reference state, by power iteration on
// M^{-1} K with K v = -(f(eps v) - f(0)) / eps (the bond kernel itself, so every
// model, horizon and formulation is covered). Velocity Verlet is stable for
// dt < 2 / sqrt(lambda_max). Norms are reproducible sums: dt is the same on any
// number of ranks.
PetscErrorCode TimeStepControl::EstimateStable(MPI_Comm comm, const Scene &scene, const Layout &layout, const Loading &loading,
                                               ForceOperator &force)
{
  const PetscInt      n = 2 * layout.n_owned;
  std::vector<double> v(n), Av(n), u(n, 0.0), a0(n);
  std::vector<char>   held(n, 0);
  std::vector<double> c33(force.warm_start().size(), 0.0); // the iteration's own warm starts
  const double        inv_rho = 1.0 / scene.density;

  PetscFunctionBegin;
  travel_ = scene.time_step_travel * scene.body.dx;
  for (const ConstrainedDof &d : loading.constrained()) held[d.dof] = 1;
  // A deterministic start with energy in every wavelength: a hash of the natural id.
  for (PetscInt i = 0; i < layout.n_owned; ++i)
    for (int c = 0; c < 2; ++c) {
      uint64_t h = (uint64_t)layout.cloud.natural_id[i] * 2 + c + 0x9E3779B97F4A7C15ULL;
      h ^= h >> 33;
      h *= 0xff51afd7ed558ccdULL;
      h ^= h >> 33;
      v[2 * i + c] = held[2 * i + c] ? 0.0 : (double)(h >> 11) / 9007199254740992.0 - 0.5;
    }
  PetscCall(ProbeAcceleration(force, c33, inv_rho, held, u.data(), a0.data()));
  const double        eps_scale = 1e-7 * scene.body.dx;
  double              lambda    = 0.0;
  std::vector<double> sq(n);
  const PetscInt      iterations = 60;
  for (PetscInt it = 0; it < iterations; ++it) {
    double norm2;
    for (PetscInt k = 0; k < n; ++k) sq[k] = v[k] * v[k];
    PetscCall(ReproducibleSum(comm, 1, n, sq.data(), &norm2));
    PetscCheck(norm2 > 0, comm, PETSC_ERR_USER, "Every degree of freedom is held by a load set: nothing moves");
    const double inv = 1.0 / std::sqrt(norm2);
    for (PetscInt k = 0; k < n; ++k) u[k] = eps_scale * v[k] * inv;
    PetscCall(ProbeAcceleration(force, c33, inv_rho, held, u.data(), Av.data()));
    for (PetscInt k = 0; k < n; ++k) Av[k] = held[k] ? 0.0 : -(Av[k] - a0[k]) / eps_scale;
    // Rayleigh quotient with the unit vector v/|v|.
    for (PetscInt k = 0; k < n; ++k) sq[k] = Av[k] * v[k] * inv;
    PetscCall(ReproducibleSum(comm, 1, n, sq.data(), &lambda));
    std::swap(v, Av);
  }
  PetscCheck(std::isfinite(lambda) && lambda > 0, comm, PETSC_ERR_USER,
             "Could not estimate a stable time step (lambda_max = %g): check -material_mu, -material_D and -material_density", lambda);
  // The Rayleigh quotient approaches lambda_max from below: pad it by 10 %.
  stable_dt_ = 2.0 / std::sqrt(1.1 * lambda);
  SetBaseStep(scene.time_step > 0 ? scene.time_step : scene.time_step_safety * stable_dt_);
  PetscCall(PetscPrintf(comm, "Stable time step %.4e s (power iteration, lambda_max = %.4e 1/s^2); using dt = %.4e s (%.3g x stable)\n",
                        stable_dt_, lambda, dt_, dt_ / stable_dt_));
  if (dt_ > stable_dt_)
    PetscCall(PetscPrintf(comm, "\n*** WARNING: dt = %.4e s is LARGER than the stable step %.4e s: expect the run to blow up.\n"
                                "*** Lower -time_step (or -time_step_safety below 1).\n\n",
                          dt_, stable_dt_));
  PetscFunctionReturn(0);
}

// The step for the next step. Bonds that snap at a large stretch fling their points at
// many times the wave speed at rest; a step that lets such a point travel a sizeable
// part of dx carries it past its neighbours, and the inverted bond-associated F that
// follows gives a huge stress and a blow-up within a step (docs/stability.md,
// section 5). So the step shrinks until no point that still has a bond moves more
// than -time_step_travel dx, and returns to base_dt_ once they slow down. Points
// without bonds move freely and do not count. The maximum is exact (MPI_MAX of
// doubles), so the step is the same on any number of ranks.
PetscErrorCode TimeStepControl::AdaptToTravel(MPI_Comm comm, const Layout &layout, const Families &families, const BondState &state,
                                              const double *v, TS ts)
{
  PetscFunctionBegin;
  if (travel_ <= 0) PetscFunctionReturn(0);
  const std::size_t W      = families.mask_words;
  double            v2_max = 0.0;
  for (PetscInt i = 0; i < layout.n_owned; ++i) {
    const std::uint64_t *intact = state.intact_mask((std::size_t)i);
    std::uint64_t        any    = 0;
    for (std::size_t w = 0; w < W; ++w) any |= intact[w];
    if (!any) continue;
    const double vx = v[2 * i], vy = v[2 * i + 1];
    v2_max = std::max(v2_max, vx * vx + vy * vy);
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &v2_max, 1, MPI_DOUBLE, MPI_MAX, comm));
  double dt = base_dt_;
  if (v2_max * dt * dt > travel_ * travel_) dt = travel_ / std::sqrt(v2_max);
  if (dt != dt_) {
    dt_ = dt;
    PetscCall(TSSetTimeStep(ts, dt_));
  }
  if (dt_ < base_dt_) {
    ++shortened_steps_;
    shortest_dt_ = shortest_dt_ > 0 ? std::min(shortest_dt_, dt_) : dt_;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TimeStepControl::ContinueShortened(double dt, TS ts)
{
  PetscFunctionBegin;
  if (travel_ > 0 && dt > 0 && dt < base_dt_) {
    dt_ = dt;
    PetscCall(TSSetTimeStep(ts, dt_));
  }
  PetscFunctionReturn(0);
}

} // namespace bapd
