// The dynamics: ghosted positions, bond forces, loading, the stable step, and the
// PETSc TS right-hand sides (velocity Verlet by default, any explicit TS by option).
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

PetscErrorCode Simulation::UpdateGhostedPositions(const double *u_owned)
{
  Vec          local;
  const double *u;

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_ghost_));
  double *ug;
  PetscCall(VecGetArray(u_ghosted_, &ug));
  std::memcpy(ug, u_owned, sizeof(double) * 2 * layout_.n_owned);
  PetscCall(VecRestoreArray(u_ghosted_, &ug));
  PetscCall(VecGhostUpdateBegin(u_ghosted_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGhostUpdateEnd(u_ghosted_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(PetscLogStagePop());
  PetscCall(VecGhostGetLocalForm(u_ghosted_, &local));
  PetscCall(VecGetArrayRead(local, &u));
  const std::size_t n = 2 * (std::size_t)layout_.n_local();
  const double     *x = layout_.cloud.x.data();
  for (std::size_t k = 0; k < n; ++k) y_[k] = x[k] + u[k];
  PetscCall(VecRestoreArrayRead(local, &u));
  PetscCall(VecGhostRestoreLocalForm(u_ghosted_, &local));
  PetscFunctionReturn(0);
}

// The force density of the dynamics: advances the plane-stress warm start c33.
PetscErrorCode Simulation::InternalForce(const double *u_owned, double *force_density, double *c33)
{
  PetscFunctionBegin;
  PetscCall(UpdateGhostedPositions(u_owned));
  PetscCall(PetscLogStagePush(stage_force_));
  last_stats_ = bond_forces_(y_.data(), c33);
  assemble_force_density(families_, layout_.cloud, bond_force_.data(), (std::size_t)layout_.n_owned, force_density);
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

// For output and tests: reads the warm start without writing it back, so looking at
// the state never changes the dynamics (the converged C33 depends on its start at the
// round-off level).
PetscErrorCode Simulation::ComputeForceDensity(const double *u_owned, double *force_density)
{
  PetscFunctionBegin;
  const KernelStats keep = last_stats_;
  workspace_.keep_warm_start = true;
  const PetscErrorCode ierr = InternalForce(u_owned, force_density, c33_.data());
  workspace_.keep_warm_start = false;
  PetscCall(ierr);
  last_stats_ = keep;
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::Acceleration(const double *u_owned, double *a_owned)
{
  PetscFunctionBegin;
  PetscCall(InternalForce(u_owned, a_owned, c33_.data()));
  const double inv_rho = 1.0 / scene_.density;
  for (PetscInt k = 0; k < 2 * layout_.n_owned; ++k) a_owned[k] *= inv_rho;
  for (const ConstrainedDof &d : constrained_) a_owned[d.dof] = 0.0; // the grip moves them
  relaxation_.Record(u_owned, a_owned); // -relaxation adaptive: the last two evaluations
  PetscFunctionReturn(0);
}

// Holds the loaded components at their prescribed values: exact for any TS type.
PetscErrorCode Simulation::ApplyLoading(double t, double *u, double *v)
{
  PetscFunctionBegin;
  const double L = scene_.reference_length, lambda = scene_.schedule.stretch_at(t), rate = scene_.schedule.rate_at(t);
  for (const ConstrainedDof &d : constrained_) {
    if (d.kind == ComponentLoad::fixed) {
      u[d.dof] = 0.0;
      if (v) v[d.dof] = 0.0;
    } else {
      u[d.dof] = d.scale * (lambda - 1.0) * L;
      if (v) v[d.dof] = d.scale * rate * L;
    }
  }
  PetscFunctionReturn(0);
}

// Stable step of the linearised system at the reference state, by power iteration on
// M^{-1} K with K v = -(f(eps v) - f(0)) / eps (the bond kernel itself, so every
// model, horizon and formulation is covered). Velocity Verlet is stable for
// dt < 2 / sqrt(lambda_max). Norms are reproducible sums: dt is the same on any
// number of ranks.
PetscErrorCode Simulation::EstimateStableTimeStep()
{
  const PetscInt      n = 2 * layout_.n_owned;
  std::vector<double> v(n), Av(n), u(n, 0.0), a0(n);
  std::vector<char>   held(n, 0);

  PetscFunctionBegin;
  for (const ConstrainedDof &d : constrained_) held[d.dof] = 1;
  // A deterministic start with energy in every wavelength: a hash of the natural id.
  for (PetscInt i = 0; i < layout_.n_owned; ++i)
    for (int c = 0; c < 2; ++c) {
      uint64_t h = (uint64_t)layout_.cloud.natural_id[i] * 2 + c + 0x9E3779B97F4A7C15ULL;
      h ^= h >> 33;
      h *= 0xff51afd7ed558ccdULL;
      h ^= h >> 33;
      v[2 * i + c] = held[2 * i + c] ? 0.0 : (double)(h >> 11) / 9007199254740992.0 - 0.5;
    }
  PetscCall(Acceleration(u.data(), a0.data()));
  const double eps_scale = 1e-7 * scene_.body.dx;
  double       lambda    = 0.0;
  std::vector<double> sq(n);
  const PetscInt      iterations = 60;
  for (PetscInt it = 0; it < iterations; ++it) {
    double norm2;
    for (PetscInt k = 0; k < n; ++k) sq[k] = v[k] * v[k];
    PetscCall(ReproducibleSum(comm_, 1, n, sq.data(), &norm2));
    PetscCheck(norm2 > 0, comm_, PETSC_ERR_USER, "Every degree of freedom is held by a load set: nothing moves");
    const double inv = 1.0 / std::sqrt(norm2);
    for (PetscInt k = 0; k < n; ++k) u[k] = eps_scale * v[k] * inv;
    PetscCall(Acceleration(u.data(), Av.data()));
    for (PetscInt k = 0; k < n; ++k) Av[k] = held[k] ? 0.0 : -(Av[k] - a0[k]) / eps_scale;
    // Rayleigh quotient with the unit vector v/|v|.
    for (PetscInt k = 0; k < n; ++k) sq[k] = Av[k] * v[k] * inv;
    PetscCall(ReproducibleSum(comm_, 1, n, sq.data(), &lambda));
    std::swap(v, Av);
  }
  std::fill(c33_.begin(), c33_.end(), 0.0); // the probes leave no trace in the dynamics
  last_stats_ = KernelStats{};
  PetscCheck(std::isfinite(lambda) && lambda > 0, comm_, PETSC_ERR_USER,
             "Could not estimate a stable time step (lambda_max = %g): check -material_mu, -material_D and -material_density", lambda);
  // The Rayleigh quotient approaches lambda_max from below: pad it by 10 %.
  stable_dt_ = 2.0 / std::sqrt(1.1 * lambda);
  dt_        = scene_.time_step > 0 ? scene_.time_step : scene_.time_step_safety * stable_dt_;
  base_dt_   = dt_;
  PetscCall(PetscPrintf(comm_, "Stable time step %.4e s (power iteration, lambda_max = %.4e 1/s^2); using dt = %.4e s (%.3g x stable)\n",
                        stable_dt_, lambda, dt_, dt_ / stable_dt_));
  if (dt_ > stable_dt_)
    PetscCall(PetscPrintf(comm_, "\n*** WARNING: dt = %.4e s is LARGER than the stable step %.4e s: expect the run to blow up.\n"
                                 "*** Lower -time_step (or -time_step_safety below 1).\n\n",
                          dt_, stable_dt_));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::RHSPosition(TS, PetscReal, Vec V, Vec Udot, void *)
{
  PetscFunctionBegin;
  PetscCall(VecCopy(V, Udot));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::RHSMomentum(TS, PetscReal, Vec U, Vec Vdot, void *ctx)
{
  auto         *sim = static_cast<Simulation *>(ctx);
  const double *u;
  double       *a;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(VecGetArray(Vdot, &a));
  PetscCall(sim->Acceleration(u, a));
  PetscCall(VecRestoreArray(Vdot, &a));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscFunctionReturn(0);
}

// X = [u, v], Xdot = [v, a(u)]: for the general explicit TS types (-ts_type rk, ...).
PetscErrorCode Simulation::RHSFull(TS, PetscReal, Vec X, Vec F, void *ctx)
{
  auto         *sim = static_cast<Simulation *>(ctx);
  const PetscInt n  = 2 * sim->layout_.n_owned;
  const double *x;
  double       *f;

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(F, &f));
  std::memcpy(f, x + n, sizeof(double) * n);
  PetscCall(sim->Acceleration(x, f + n));
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::SetupTimeStepper()
{
  const PetscInt n = 2 * layout_.n_owned;
  PetscInt       start;

  PetscFunctionBegin;
  PetscCall(VecCreateMPI(comm_, 2 * n, PETSC_DECIDE, &X_));
  PetscCall(VecGetOwnershipRange(X_, &start, nullptr));
  PetscCall(ISCreateStride(comm_, n, start, 1, &is_position_));
  PetscCall(ISCreateStride(comm_, n, start + n, 1, &is_momentum_));
  {
    double *x;
    PetscCall(VecSet(X_, 0.0));
    PetscCall(VecGetArray(X_, &x));
    PetscCall(ApplyLoading(0.0, x, x + n));
    PetscCall(VecRestoreArray(X_, &x));
  }
  PetscCall(TSCreate(comm_, &ts_));
  PetscCall(TSSetProblemType(ts_, TS_NONLINEAR));
  PetscCall(TSSetType(ts_, TSBASICSYMPLECTIC));
  PetscCall(TSBasicSymplecticSetType(ts_, TSBASICSYMPLECTICVELVERLET));
  PetscCall(TSRHSSplitSetIS(ts_, "position", is_position_));
  PetscCall(TSRHSSplitSetIS(ts_, "momentum", is_momentum_));
  PetscCall(TSRHSSplitSetRHSFunction(ts_, "position", nullptr, RHSPosition, this));
  PetscCall(TSRHSSplitSetRHSFunction(ts_, "momentum", nullptr, RHSMomentum, this));
  PetscCall(TSSetRHSFunction(ts_, nullptr, RHSFull, this));
  PetscCall(TSSetTimeStep(ts_, dt_));
  const double end_time = scene_.end_time;
  PetscCall(TSSetMaxTime(ts_, end_time));
  PetscCall(TSSetMaxSteps(ts_, PETSC_MAX_INT));
  PetscCall(TSSetExactFinalTime(ts_, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetPostStep(ts_, PostStep));
  PetscCall(TSSetApplicationContext(ts_, this));
  PetscCall(TSSetSolution(ts_, X_));
  PetscCall(TSSetFromOptions(ts_));
  {
    TSType type;
    PetscCall(TSGetType(ts_, &type));
    PetscReal dt;
    PetscCall(TSGetTimeStep(ts_, &dt));
    if (dt != dt_) {
      dt_ = base_dt_ = dt;
      PetscCall(PetscPrintf(comm_, "Time step set by -ts_dt: %.4e s (%.3g x stable)\n", dt_, dt_ / stable_dt_));
      if (dt_ > stable_dt_)
        PetscCall(PetscPrintf(comm_, "\n*** WARNING: -ts_dt %.4e s is LARGER than the stable step %.4e s: expect the run to blow up.\n\n", dt_, stable_dt_));
    }
    const PetscInt steps = (PetscInt)std::ceil(end_time / dt_ - 1e-9);
    PetscCall(PetscPrintf(comm_, "Time stepping: %s, dt = %.4e s, end time %.4e s, about %" PetscInt_FMT " steps\n", type, dt_, end_time, steps));
    if (scene_.progress_interval <= 0) scene_.progress_interval = std::max<PetscInt>(1, steps / 20);
  }
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
PetscErrorCode Simulation::AdaptTimeStep()
{
  PetscFunctionBegin;
  if (scene_.time_step_travel <= 0) PetscFunctionReturn(0);
  Vec           X;
  const double *x;
  const PetscInt n = 2 * layout_.n_owned;
  PetscCall(TSGetSolution(ts_, &X));
  PetscCall(VecGetArrayRead(X, &x));
  const std::size_t W = families_.mask_words;
  double            v2_max = 0.0;
  for (PetscInt i = 0; i < layout_.n_owned; ++i) {
    const std::uint64_t *intact = bond_state_.intact_mask((std::size_t)i);
    std::uint64_t        any    = 0;
    for (std::size_t w = 0; w < W; ++w) any |= intact[w];
    if (!any) continue;
    const double vx = x[n + 2 * i], vy = x[n + 2 * i + 1];
    v2_max = std::max(v2_max, vx * vx + vy * vy);
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &v2_max, 1, MPI_DOUBLE, MPI_MAX, comm_));
  const double travel = scene_.time_step_travel * scene_.body.dx;
  double       dt     = base_dt_;
  if (v2_max * dt * dt > travel * travel) dt = travel / std::sqrt(v2_max);
  if (dt != dt_) {
    dt_ = dt;
    PetscCall(TSSetTimeStep(ts_, dt_));
  }
  if (dt_ < base_dt_) {
    ++shortened_steps_;
    shortest_dt_ = shortest_dt_ > 0 ? std::min(shortest_dt_, dt_) : dt_;
  }
  PetscFunctionReturn(0);
}

} // namespace bapd
