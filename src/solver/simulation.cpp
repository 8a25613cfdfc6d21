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

Simulation::~Simulation()
{
  if (history_) std::fclose(history_);
  if (static_states_) std::fclose(static_states_);
  TSDestroy(&ts_);
  PetscSFDestroy(&bond_state_sf_);
  ISDestroy(&is_position_);
  ISDestroy(&is_momentum_);
  VecDestroy(&X_);
  VecDestroy(&u_ghosted_);
}

PetscErrorCode Simulation::Setup()
{
  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  PetscCallMPI(MPI_Comm_size(comm_, &size_));
  // -log_view stages, registered once per process (a test may build several runs).
  static PetscLogStage stages[6];
  static bool          registered = false;
  if (!registered) {
    const char *names[6] = {"Setup", "Partition", "Force", "Ghost exchange", "Time step", "Output"};
    for (int k = 0; k < 6; ++k) PetscCall(PetscLogStageRegister(names[k], &stages[k]));
    registered = true;
  }
  stage_setup_ = stages[0], stage_partition_ = stages[1], stage_force_ = stages[2];
  stage_ghost_ = stages[3], stage_step_ = stages[4], stage_output_ = stages[5];
  wall_start_ = MPI_Wtime();

  PetscCall(PetscLogStagePush(stage_setup_));
  PetscCall(CheckpointMergeOptions(comm_)); // -restart FILE: the checkpoint's options are the defaults
  PetscCall(SceneFromOptions(comm_, &scene_));
  PetscCall(ReadOutputOptions()); // -output_fields..., -checkpoint_..., -restart
  if (scene_.help_only) {
    // -help without a scene: list the time stepper's options too, and stop.
    PetscCall(TSCreate(comm_, &ts_));
    PetscCall(TSSetType(ts_, TSBASICSYMPLECTIC));
    PetscCall(TSSetFromOptions(ts_));
    PetscCall(PetscLogStagePop());
    PetscFunctionReturn(0);
  }
  PetscCall(PetscOptionsGetBool(nullptr, nullptr, "-output_final_state", &write_final_state_, nullptr));
  PetscCall(SceneView(comm_, scene_));
  PetscCall(BuildBody());
  PetscCall(BuildLoads());
  PetscCall(BuildProbes());
  PetscCall(EstimateStableTimeStep());
  PetscCall(SetupTimeStepper());
  PetscCall(CheckUnusedOptions(comm_));
  PetscCall(OpenHistory());
  PetscCall(SetupOutput()); // restores the state with -restart
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

// Body, partition, layout, families and reference bond geometry.
PetscErrorCode Simulation::BuildBody()
{
  const double       horizon = scene_.horizon();
  PointCloud         global;
  std::vector<int>   offsets, neighbours;

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_partition_));
  if (rank_ == 0) {
    // Rank 0 builds the whole bond graph; fine up to a few 10^7 points (README).
    global               = make_lattice(scene_.body);
    Families all         = build_families(global, global.size(), horizon, scene_.body.notches);
    compute_family_volumes(global, all);
    offsets.assign(all.offsets.begin(), all.offsets.end());
    neighbours.assign(all.neighbour.begin(), all.neighbour.end());
  }
  PetscCall(DistributePoints(comm_, global, offsets, neighbours, &layout_));
  PetscCall(PetscLogStagePop());

  // Every rank finds the same families for its owned and ring-1 points as rank 0
  // did: their whole neighbourhood lies in the two rings it holds.
  families_ = build_families(layout_.cloud, (std::size_t)layout_.n_family(), horizon, scene_.body.notches);
  bond_state_ = make_bond_state(families_);
  compute_bond_geometry(layout_.cloud, families_, bond_state_, geometry_);

  const std::size_t nbonds = families_.neighbour.size();
  c33_.assign(nbonds, 0.0);
  bond_force_.assign(2 * nbonds, 0.0);
  y_.assign(layout_.cloud.x.begin(), layout_.cloud.x.end());
  force_.assign(2 * layout_.n_owned, 0.0);

  // The constitutive model is chosen here, once; inside the closure it is a concrete
  // type and the bond loop is compiled for it.
  with_model(scene_.model, scene_.formulation, scene_.material, [&](const auto &model) {
    using Model    = std::decay_t<decltype(model)>;
    // -force_form: both forms write t_ij per bond, and assemble_force_density turns
    // either into f_i (the energy-consistent t_ij make it -(1/V_i) dW/dy_i).
    if (scene_.force_form == ForceForm::energy_consistent)
      bond_forces_ = [this, m = Model(model)](const double *y, double *c33) {
        return compute_energy_consistent_bond_forces(m, layout_.cloud, y, families_, geometry_, bond_state_, c33,
                                                     bond_force_.data(), workspace_);
      };
    else
      bond_forces_ = [this, m = Model(model)](const double *y, double *c33) {
        return compute_bond_forces(m, layout_.cloud, y, families_, geometry_, bond_state_, c33, bond_force_.data(), workspace_);
      };
    point_energies_ = [this, m = Model(model)](const double *y, double *energy) {
      strain_energy(m, layout_.cloud, y, families_, geometry_, bond_state_, c33_.data(), (std::size_t)layout_.n_owned,
                    workspace_, nullptr, energy);
    };
  });

  PetscCall(CreateGhostedVector(comm_, layout_, &u_ghosted_));
  if (scene_.failure) PetscCall(CreateBondStateExchange());
  PetscInt bonds_local = (PetscInt)families_.offsets[layout_.n_owned], bonds_global = 0;
  PetscCallMPI(MPI_Allreduce(&bonds_local, &bonds_global, 1, MPIU_INT, MPI_SUM, comm_));
  PetscInt ghost_max = layout_.n_ghost(), owned_min = layout_.n_owned;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ghost_max, 1, MPIU_INT, MPI_MAX, comm_));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &owned_min, 1, MPIU_INT, MPI_MIN, comm_));
  PetscCall(PetscPrintf(comm_, "Body: %" PetscInt_FMT " points, %" PetscInt_FMT " bonds, %d rank(s); edge cut %" PetscInt_FMT ", fewest owned %" PetscInt_FMT ", most ghosts %" PetscInt_FMT "\n",
                        layout_.n_global, bonds_global, size_, layout_.edge_cut, owned_min, ghost_max));
  PetscInt unusable = 0;
  for (PetscInt i = 0; i < layout_.n_owned; ++i)
    for (std::size_t q = 0; q < families_.size((std::size_t)i); ++q) unusable += !geometry_.is_usable((std::size_t)i, q);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &unusable, 1, MPIU_INT, MPI_SUM, comm_));
  if (unusable) PetscCall(PetscPrintf(comm_, "Bonds with a singular shape tensor (carry no force): %" PetscInt_FMT "\n", unusable));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::BuildLoads()
{
  PetscFunctionBegin;
  load_points_.assign(scene_.loads.size(), {});
  std::vector<int> claimed(2 * layout_.n_owned, -1);
  for (std::size_t s = 0; s < scene_.loads.size(); ++s) {
    const LoadSet        &set = scene_.loads[s];
    std::vector<PetscInt> selected;
    PetscCall(LoadSetSelect(scene_, set, layout_.cloud.x.data(), layout_.n_owned, &selected));
    PetscInt count = (PetscInt)selected.size();
    PetscCallMPI(MPI_Allreduce(&count, &load_points_[s].global_count, 1, MPIU_INT, MPI_SUM, comm_));
    if (load_points_[s].global_count == 0) {
      // Points sit at cell centres ((i + 1/2) dx, (j + 1/2) dx): a thin box can miss
      // them all, and a hole can empty an edge layer.
      const char *n = set.name.c_str();
      char        msg[512];
      if (set.region == LoadSet::Region::box)
        std::snprintf(msg, sizeof msg,
                      "-load_%s_box %g,%g,%g,%g selects no material point for load set '%s': widen it to hold a lattice point "
                      "(points sit at ((i + 1/2) dx, (j + 1/2) dx), dx = %g m)",
                      n, set.box[0], set.box[1], set.box[2], set.box[3], n, scene_.body.dx);
      else
        std::snprintf(msg, sizeof msg,
                      "-load_%s_region %s selects no material point for load set '%s' (its %d edge layer(s) hold none, e.g. cut away "
                      "by a hole): raise -load_%s_layers or move the hole",
                      n, to_string(set.region), n, set.layers, n);
      SETERRQ(comm_, PETSC_ERR_USER, "%s", msg);
    }
    load_points_[s].points = selected;
    for (PetscInt p : selected)
      for (int c = 0; c < 2; ++c) {
        const ComponentLoad kind = c == 0 ? set.x : set.y;
        if (kind == ComponentLoad::free) continue;
        claimed[2 * p + c] = (int)s;
        constrained_.push_back({2 * p + c, kind, c == 0 ? set.x_scale : set.y_scale});
      }
  }
  // A point in two sets is held by the one named last; keep one entry per dof.
  std::vector<ConstrainedDof> unique;
  for (const ConstrainedDof &d : constrained_) {
    auto it = std::find_if(unique.begin(), unique.end(), [&](const ConstrainedDof &e) { return e.dof == d.dof; });
    if (it == unique.end()) unique.push_back(d);
    else *it = d;
  }
  constrained_ = std::move(unique);
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::BuildProbes()
{
  PetscFunctionBegin;
  probes_.assign(scene_.probes.size(), {});
  for (std::size_t p = 0; p < scene_.probes.size(); ++p) {
    // Nearest owned point; ties go to the smaller natural id, so the choice does not
    // depend on the layout.
    struct {
      double  d2;
      int64_t id;
    } best = {std::numeric_limits<double>::max(), std::numeric_limits<int64_t>::max()};
    PetscInt best_local = -1;
    for (PetscInt i = 0; i < layout_.n_owned; ++i) {
      const double dx = layout_.cloud.x[2 * i] - scene_.probes[p].x, dy = layout_.cloud.x[2 * i + 1] - scene_.probes[p].y;
      const double d2 = dx * dx + dy * dy;
      const int64_t id = layout_.cloud.natural_id[i];
      if (d2 < best.d2 || (d2 == best.d2 && id < best.id)) {
        best       = {d2, id};
        best_local = i;
      }
    }
    double d2min = best.d2;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &d2min, 1, MPI_DOUBLE, MPI_MIN, comm_));
    long long id = best.d2 == d2min ? (long long)best.id : std::numeric_limits<long long>::max();
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &id, 1, MPI_LONG_LONG, MPI_MIN, comm_));
    ProbePoint &pp = probes_[p];
    pp.natural_id  = id;
    int mine = (best_local >= 0 && best.id == id) ? rank_ : -1;
    int owner = -1;
    PetscCallMPI(MPI_Allreduce(&mine, &owner, 1, MPI_INT, MPI_MAX, comm_));
    pp.owner_rank  = owner;
    pp.local_index = owner == rank_ ? best_local : -1;
    double xy[2]   = {0, 0};
    if (owner == rank_) {
      xy[0] = layout_.cloud.x[2 * best_local];
      xy[1] = layout_.cloud.x[2 * best_local + 1];
    }
    PetscCallMPI(MPI_Bcast(xy, 2, MPI_DOUBLE, owner, comm_));
    pp.x = xy[0];
    pp.y = xy[1];
    PetscCall(PetscPrintf(comm_, "Probe %s: point %lld at (%g, %g) m\n", scene_.probes[p].name.c_str(), id, pp.x, pp.y));
  }
  PetscFunctionReturn(0);
}

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

// For output and tests: starts from a copy of the warm start, so looking at the
// state never changes the dynamics (the converged C33 depends on its start at the
// round-off level).
PetscErrorCode Simulation::ComputeForceDensity(const double *u_owned, double *force_density)
{
  PetscFunctionBegin;
  c33_scratch_ = c33_;
  const KernelStats keep = last_stats_;
  PetscCall(InternalForce(u_owned, force_density, c33_scratch_.data()));
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
      dt_ = dt;
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

PetscErrorCode Simulation::OpenHistory()
{
  PetscFunctionBegin;
  int         ok = 1;
  std::string why; // rank 0, which prints the message
  if (rank_ == 0) {
    std::error_code ec;
    std::filesystem::create_directories(scene_.output_dir, ec);
    const std::string path = scene_.output_dir + "/history.csv";
    history_               = ec ? nullptr : std::fopen(path.c_str(), "w");
    ok                     = history_ != nullptr;
    if (!ok) why = ec ? "cannot create the directory: " + ec.message() : std::string(std::strerror(errno));
  }
  PetscCallMPI(MPI_Bcast(&ok, 1, MPI_INT, 0, comm_));
  PetscCheck(ok, comm_, PETSC_ERR_FILE_OPEN, "-output_dir %s: cannot write %s/history.csv (%s): choose a writable directory, e.g. -output_dir output",
             scene_.output_dir.c_str(), scene_.output_dir.c_str(), why.c_str());
  if (rank_ == 0) {
    std::fprintf(history_, "step,time_s,stretch");
    for (const LoadSet &s : scene_.loads)
      std::fprintf(history_, ",%s_reaction_x_N,%s_reaction_y_N,%s_nominal_stress_Pa", s.name.c_str(), s.name.c_str(), s.name.c_str());
    for (const Probe &p : scene_.probes) std::fprintf(history_, ",%s_ux_m,%s_uy_m", p.name.c_str(), p.name.c_str());
    std::fprintf(history_, ",kinetic_energy_J,internal_energy_J,broken_bonds\n");
  }
  PetscCall(WriteHistoryRow(0, 0.0));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::Energies(double *kinetic, double *internal)
{
  const PetscInt n = layout_.n_owned;
  const double  *x;
  std::vector<double> per_point(2 * n);

  PetscFunctionBegin;
  PetscCall(VecGetArrayRead(X_, &x));
  PetscCall(UpdateGhostedPositions(x));
  const double *v = x + 2 * n;
  for (PetscInt i = 0; i < n; ++i) {
    const double m = scene_.density * layout_.cloud.volume[i];
    per_point[2 * i] = 0.5 * m * (v[2 * i] * v[2 * i] + v[2 * i + 1] * v[2 * i + 1]);
  }
  PetscCall(VecRestoreArrayRead(X_, &x));
  std::vector<double> energy(n);
  point_energies_(y_.data(), energy.data());
  for (PetscInt i = 0; i < n; ++i) per_point[2 * i + 1] = energy[i];
  double sums[2];
  PetscCall(ReproducibleSum(comm_, 2, n, per_point.data(), sums));
  *kinetic  = sums[0];
  *internal = sums[1];
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::BrokenBondCount(PetscInt *count)
{
  PetscFunctionBegin;
  PetscInt local = (PetscInt)count_broken_bonds(families_, bond_state_, (std::size_t)layout_.n_owned);
  PetscCallMPI(MPI_Allreduce(&local, count, 1, MPIU_INT, MPI_SUM, comm_));
  *count /= 2; // each broken bond is seen from both of its end points
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::WriteHistoryRow(PetscInt step, double t)
{
  const double *x;

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_output_));
  PetscCall(VecGetArrayRead(X_, &x));
  PetscCall(ComputeForceDensity(x, force_.data()));
  // Reactions: the grip holds its points still, so it supplies minus the internal force.
  std::vector<double> reaction(2 * scene_.loads.size(), 0.0);
  for (std::size_t s = 0; s < scene_.loads.size(); ++s) {
    const std::vector<PetscInt> &pts = load_points_[s].points;
    std::vector<double>          terms(2 * pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      terms[2 * k]     = -force_[2 * pts[k]] * layout_.cloud.volume[pts[k]];
      terms[2 * k + 1] = -force_[2 * pts[k] + 1] * layout_.cloud.volume[pts[k]];
    }
    PetscCall(ReproducibleSum(comm_, 2, (PetscInt)pts.size(), terms.data(), &reaction[2 * s]));
  }
  std::vector<double> probe_u(2 * probes_.size(), 0.0);
  for (std::size_t p = 0; p < probes_.size(); ++p) {
    if (probes_[p].owner_rank == rank_) {
      probe_u[2 * p]     = x[2 * probes_[p].local_index];
      probe_u[2 * p + 1] = x[2 * probes_[p].local_index + 1];
    }
    PetscCallMPI(MPI_Bcast(&probe_u[2 * p], 2, MPI_DOUBLE, probes_[p].owner_rank, comm_));
  }
  PetscCall(VecRestoreArrayRead(X_, &x));
  double kinetic, internal;
  PetscCall(Energies(&kinetic, &internal));
  PetscInt broken;
  PetscCall(BrokenBondCount(&broken));
  last_kinetic_  = kinetic;
  last_internal_ = internal;
  last_reaction_ = reaction;
  last_probe_u_  = probe_u;
  if (rank_ == 0) {
    const double area = scene_.body.width * scene_.body.thickness;
    std::fprintf(history_, "%" PetscInt_FMT ",%.17g,%.17g", step, t, scene_.schedule.stretch_at(t));
    for (std::size_t s = 0; s < scene_.loads.size(); ++s)
      std::fprintf(history_, ",%.17g,%.17g,%.17g", reaction[2 * s], reaction[2 * s + 1], reaction[2 * s + 1] / area);
    for (std::size_t p = 0; p < probes_.size(); ++p) std::fprintf(history_, ",%.17g,%.17g", probe_u[2 * p], probe_u[2 * p + 1]);
    std::fprintf(history_, ",%.17g,%.17g,%" PetscInt_FMT "\n", kinetic, internal, broken);
    std::fflush(history_);
  }
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

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

PetscErrorCode Simulation::PostStep(TS ts)
{
  Simulation *sim;
  PetscInt    step;
  PetscReal   t;
  Vec         X;
  double     *x;

  PetscFunctionBegin;
  PetscCall(TSGetApplicationContext(ts, &sim));
  PetscCall(TSGetStepNumber(ts, &step));
  PetscCall(TSGetTime(ts, &t));
  PetscCall(TSGetSolution(ts, &X));
  const PetscInt n = 2 * sim->layout_.n_owned;
  PetscCall(VecGetArray(X, &x));
  PetscCall(sim->ApplyLoading(t, x, x + n));
  if (sim->scene_.damping > 0) {
    // Mass-proportional damping, integrated exactly over the step (operator split):
    // works with every TS type and never destabilises the step.
    const double decay = std::exp(-sim->scene_.damping * sim->dt_);
    std::vector<char> held(n, 0);
    for (const ConstrainedDof &d : sim->constrained_) held[d.dof] = 1;
    for (PetscInt k = 0; k < n; ++k)
      if (!held[k]) x[n + k] *= decay;
  }
  PetscCall(VecRestoreArray(X, &x));

  PetscBool diverged = PETSC_FALSE;
  PetscCall(sim->CheckHealth(step, t, &diverged));
  if (!diverged) {
    // Runaway energy: an unstable time step caught before NaN or shattering (divergence.hpp).
    std::string runaway;
    PetscCall(CheckRunawayEnergy(*sim, sim->energy_monitor_, step, t, &runaway));
    if (!runaway.empty()) sim->stop_reason_ = runaway, sim->stopped_on_error_ = true, diverged = PETSC_TRUE;
  }
  if (diverged) {
    PetscCall(sim->OutputOnDivergence()); // checkpoint of the last good state
    PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_NONLINEAR_SOLVE));
    PetscFunctionReturn(0);
  }
  if (sim->scene_.failure) {
    PetscCall(VecGetArray(X, &x));
    PetscCall(sim->UpdateGhostedPositions(x));
    PetscCall(VecRestoreArray(X, &x));
    PetscCall(sim->BreakBonds());
  }
  if (step % sim->scene_.output_interval == 0) {
    PetscCall(sim->WriteHistoryRow(step, t));
    PetscCall(sim->CheckStaticHold(step, t));
  }
  PetscCall(sim->Progress(step, t, PETSC_FALSE));
  PetscCall(sim->OutputAfterStep(step, t)); // fields, checkpoints, SIGTERM/SIGINT
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

// Ends a hold of the load schedule once the body is static (kinetic energy below
// -static_tolerance times the internal energy, at a history row): records the static
// state in static_states.csv and moves the rest of the schedule earlier, so that the
// next ramp starts now. Every input to the test is a reproducible sum, so the same
// steps end the same holds on any number of ranks.
PetscErrorCode Simulation::CheckStaticHold(PetscInt step, double t)
{
  Schedule &s = scene_.schedule;

  PetscFunctionBegin;
  if (scene_.static_tolerance <= 0 || s.time.empty() || s.rate_at(t) != 0.0 || t < s.time.front()) PetscFunctionReturn(0);
  PetscInt k = (PetscInt)(std::upper_bound(s.time.begin(), s.time.end(), t) - s.time.begin()) - 1; // t in [time[k], time[k+1])
  if (k == static_hold_done_ || !(last_kinetic_ < scene_.static_tolerance * last_internal_)) PetscFunctionReturn(0);
  static_hold_done_ = k;
  const double lambda = s.stretch_at(t);
  PetscCall(PetscPrintf(comm_, "Static at stretch %.5f: t = %.6e s, step %" PetscInt_FMT ", kinetic/internal energy %.3e < %.3e", lambda, t, step,
                        last_kinetic_ / last_internal_, scene_.static_tolerance));
  for (std::size_t p = 0; p < probes_.size(); ++p)
    PetscCall(PetscPrintf(comm_, "; %s ux = %.6e m", scene_.probes[p].name.c_str(), last_probe_u_[2 * p]));
  PetscCall(PetscPrintf(comm_, "\n"));
  if (rank_ == 0) {
    if (!static_states_) {
      static_states_ = std::fopen((scene_.output_dir + "/static_states.csv").c_str(), "w");
      PetscCheck(static_states_, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot write %s/static_states.csv: choose a writable -output_dir", scene_.output_dir.c_str());
      std::fprintf(static_states_, "stretch,time_s,step,kinetic_over_internal");
      for (const Probe &p : scene_.probes) std::fprintf(static_states_, ",%s_ux_m,%s_uy_m", p.name.c_str(), p.name.c_str());
      for (const LoadSet &l : scene_.loads) std::fprintf(static_states_, ",%s_reaction_y_N", l.name.c_str());
      std::fprintf(static_states_, "\n");
    }
    std::fprintf(static_states_, "%.17g,%.17g,%" PetscInt_FMT ",%.6e", lambda, t, step, last_kinetic_ / last_internal_);
    for (std::size_t p = 0; p < probes_.size(); ++p) std::fprintf(static_states_, ",%.17g,%.17g", last_probe_u_[2 * p], last_probe_u_[2 * p + 1]);
    for (std::size_t l = 0; l < scene_.loads.size(); ++l) std::fprintf(static_states_, ",%.17g", last_reaction_[2 * l + 1]);
    std::fprintf(static_states_, "\n");
    std::fflush(static_states_);
  }
  // Skip what is left of the hold.
  const double hold_end  = k + 1 < (PetscInt)s.time.size() ? s.time[k + 1] : scene_.end_time;
  const double remaining = std::max(0.0, hold_end - t);
  for (std::size_t j = (std::size_t)k + 1; j < s.time.size(); ++j) s.time[j] -= remaining;
  scene_.end_time = std::max(t, scene_.end_time - remaining);
  PetscCall(TSSetMaxTime(ts_, scene_.end_time));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::Progress(PetscInt step, double t, PetscBool force)
{
  PetscFunctionBegin;
  if (!force && step % scene_.progress_interval != 0) PetscFunctionReturn(0);
  const double end_time = scene_.end_time;
  const double wall     = MPI_Wtime() - wall_start_;
  if (scene_.failure) PetscCall(BrokenBondCount(&total_broken_));
  const double left     = t > 0 ? wall * (end_time - t) / t : 0.0;
  PetscCall(PetscPrintf(comm_, "step %8" PetscInt_FMT "  t %.4e s  stretch %.4f  broken %" PetscInt_FMT "  wall %.1f s  left ~%.1f s\n", step, t,
                        scene_.schedule.stretch_at(t), total_broken_, wall, left));
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::Run()
{
  PetscFunctionBegin;
  if (scene_.help_only) PetscFunctionReturn(0);
  PetscCall(PetscLogStagePush(stage_step_));
  PetscCall(TSSolve(ts_, X_));
  PetscCall(PetscLogStagePop());
  PetscInt  step;
  PetscReal t;
  PetscCall(TSGetStepNumber(ts_, &step));
  PetscCall(TSGetTime(ts_, &t));
  if (step % scene_.output_interval != 0 && !stopped_on_error_) PetscCall(WriteHistoryRow(step, t));
  PetscCall(OutputAtEnd(step, t)); // the last field file (and checkpoint)
  PetscCall(Summary());
  if (write_final_state_) PetscCall(WriteFinalState());
  PetscCheck(!stopped_on_error_, comm_, PETSC_ERR_NOT_CONVERGED, "%s", stop_reason_.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::Advance(PetscInt steps)
{
  PetscInt step;

  PetscFunctionBegin;
  PetscCall(TSGetStepNumber(ts_, &step));
  PetscCall(TSSetMaxSteps(ts_, step + steps));
  PetscCall(TSSetMaxTime(ts_, PETSC_MAX_REAL));
  PetscCall(PetscLogStagePush(stage_step_));
  PetscCall(TSSolve(ts_, X_));
  PetscCall(PetscLogStagePop());
  PetscCheck(!stopped_on_error_, comm_, PETSC_ERR_NOT_CONVERGED, "%s", stop_reason_.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::Summary()
{
  PetscInt  step;
  PetscReal t;

  PetscFunctionBegin;
  PetscCall(TSGetStepNumber(ts_, &step));
  PetscCall(TSGetTime(ts_, &t));
  const double *x;
  std::vector<double> probe_u(2 * probes_.size(), 0.0);
  PetscCall(VecGetArrayRead(X_, &x));
  for (std::size_t p = 0; p < probes_.size(); ++p) {
    if (probes_[p].owner_rank == rank_) {
      probe_u[2 * p]     = x[2 * probes_[p].local_index];
      probe_u[2 * p + 1] = x[2 * probes_[p].local_index + 1];
    }
    PetscCallMPI(MPI_Bcast(&probe_u[2 * p], 2, MPI_DOUBLE, probes_[p].owner_rank, comm_));
  }
  PetscCall(ComputeForceDensity(x, force_.data()));
  PetscCall(VecRestoreArrayRead(X_, &x));
  PetscCall(PetscPrintf(comm_, "\n%s: %" PetscInt_FMT " steps, t = %.6e s, stretch %.5f, wall %.1f s\n",
                        stopped_on_error_ ? "Stopped (see the error below)" : "Finished", step, t, scene_.schedule.stretch_at(t),
                        MPI_Wtime() - wall_start_));
  for (std::size_t p = 0; p < probes_.size(); ++p)
    PetscCall(PetscPrintf(comm_, "probe %-16s ux = %+.6e m  uy = %+.6e m\n", scene_.probes[p].name.c_str(), probe_u[2 * p], probe_u[2 * p + 1]));
  for (std::size_t s = 0; s < scene_.loads.size(); ++s) {
    std::vector<double> terms(2 * load_points_[s].points.size());
    for (std::size_t k = 0; k < load_points_[s].points.size(); ++k) {
      const PetscInt i = load_points_[s].points[k];
      terms[2 * k]     = -force_[2 * i] * layout_.cloud.volume[i];
      terms[2 * k + 1] = -force_[2 * i + 1] * layout_.cloud.volume[i];
    }
    double r[2];
    PetscCall(ReproducibleSum(comm_, 2, (PetscInt)load_points_[s].points.size(), terms.data(), r));
    PetscCall(PetscPrintf(comm_, "load set %-12s reaction y = %+.6e N  nominal stress = %+.6e Pa\n", scene_.loads[s].name.c_str(), r[1],
                          r[1] / (scene_.body.width * scene_.body.thickness)));
  }
  PetscInt broken;
  PetscCall(BrokenBondCount(&broken));
  if (scene_.failure) PetscCall(PetscPrintf(comm_, "broken bonds: %" PetscInt_FMT "\n", broken));
  PetscCall(PetscPrintf(comm_, "history: %s/history.csv\n", scene_.output_dir.c_str()));
  PetscFunctionReturn(0);
}

// final_state.csv (natural id, reference position, displacement) and
// broken_bonds.csv (directed pairs of natural ids), in natural order: files that do
// not depend on the rank layout, for comparisons across runs.
PetscErrorCode Simulation::WriteFinalState()
{
  std::vector<double>                      u;
  std::vector<std::pair<int64_t, int64_t>> broken;

  PetscFunctionBegin;
  PetscCall(GatherDisplacement(&u));
  PetscCall(GatherBrokenBonds(&broken));
  if (rank_ == 0) {
    const PointCloud global = make_lattice(scene_.body);
    FILE            *f      = std::fopen((scene_.output_dir + "/final_state.csv").c_str(), "w");
    PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot write %s/final_state.csv", scene_.output_dir.c_str());
    std::fprintf(f, "natural_id,x_m,y_m,ux_m,uy_m\n");
    for (std::size_t i = 0; i < global.size(); ++i)
      std::fprintf(f, "%zu,%.17g,%.17g,%.17g,%.17g\n", i, global.x[2 * i], global.x[2 * i + 1], u[2 * i], u[2 * i + 1]);
    std::fclose(f);
    f = std::fopen((scene_.output_dir + "/broken_bonds.csv").c_str(), "w");
    PetscCheck(f, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "Cannot write %s/broken_bonds.csv", scene_.output_dir.c_str());
    std::fprintf(f, "i,j\n");
    for (const auto &b : broken) std::fprintf(f, "%lld,%lld\n", (long long)b.first, (long long)b.second);
    std::fclose(f);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::GatherDisplacement(std::vector<double> *u_natural)
{
  const PetscInt n = layout_.n_owned;
  const double  *x;

  PetscFunctionBegin;
  std::vector<double> mine(3 * n);
  PetscCall(VecGetArrayRead(X_, &x));
  for (PetscInt i = 0; i < n; ++i) {
    mine[3 * i]     = (double)layout_.cloud.natural_id[i];
    mine[3 * i + 1] = x[2 * i];
    mine[3 * i + 2] = x[2 * i + 1];
  }
  PetscCall(VecRestoreArrayRead(X_, &x));
  std::vector<int> counts(size_), displs(size_);
  int              m = (int)mine.size();
  PetscCallMPI(MPI_Gather(&m, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_));
  std::vector<double> all;
  if (rank_ == 0) {
    int total = 0;
    for (int r = 0; r < size_; ++r) {
      displs[r] = total;
      total += counts[r];
    }
    all.resize(total);
  }
  PetscCallMPI(MPI_Gatherv(mine.data(), m, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, comm_));
  u_natural->clear();
  if (rank_ == 0) {
    u_natural->assign(2 * layout_.n_global, 0.0);
    for (std::size_t k = 0; k < all.size(); k += 3) {
      const std::size_t id = (std::size_t)all[k];
      (*u_natural)[2 * id]     = all[k + 1];
      (*u_natural)[2 * id + 1] = all[k + 2];
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Simulation::GatherBrokenBonds(std::vector<std::pair<int64_t, int64_t>> *bonds)
{
  PetscFunctionBegin;
  std::vector<long long> mine;
  for (PetscInt i = 0; i < layout_.n_owned; ++i)
    for (std::size_t b = families_.offsets[i]; b < families_.offsets[i + 1]; ++b)
      if (!bond_state_.is_intact((std::size_t)i, (std::size_t)(b - families_.offsets[i]))) {
        mine.push_back(layout_.cloud.natural_id[i]);
        mine.push_back(layout_.cloud.natural_id[families_.neighbour[b]]);
      }
  std::vector<int> counts(size_), displs(size_);
  int              m = (int)mine.size();
  PetscCallMPI(MPI_Gather(&m, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_));
  std::vector<long long> all;
  if (rank_ == 0) {
    int total = 0;
    for (int r = 0; r < size_; ++r) {
      displs[r] = total;
      total += counts[r];
    }
    all.resize(total);
  }
  PetscCallMPI(MPI_Gatherv(mine.data(), m, MPI_LONG_LONG, all.data(), counts.data(), displs.data(), MPI_LONG_LONG, 0, comm_));
  bonds->clear();
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) bonds->push_back({all[k], all[k + 1]});
  std::sort(bonds->begin(), bonds->end());
  PetscFunctionReturn(0);
}

} // namespace bapd
