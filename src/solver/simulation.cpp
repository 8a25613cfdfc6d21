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
  PetscCall(RelaxationFromOptions(comm_, &relaxation_kind_)); // -relaxation
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
  PetscCall(SetupRelaxation());
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
  // Below delta = sqrt(2) dx every bond-associated family of a square lattice is
  // collinear: no bond carries force, and the stable-step estimate would fail with a
  // misleading message (docs/stability.md, section 6).
  char factor[32];
  std::snprintf(factor, sizeof factor, "%g", scene_.horizon_factor); // PETSc's %g would print "1."
  PetscCheck(bonds_global == 0 || unusable < bonds_global, comm_, PETSC_ERR_USER,
             "-horizon_factor %s: every bond's shape tensor is singular (its bond-associated family is collinear), so no bond "
             "carries force: raise -horizon_factor (at least 1.5; the paper uses 3.015)",
             factor);
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

// -relaxation adaptive: the damping coefficient follows the slowest mode (relaxation.hpp).
PetscErrorCode Simulation::SetupRelaxation()
{
  PetscFunctionBegin;
  std::vector<PetscInt> held;
  for (const ConstrainedDof &d : constrained_) held.push_back(d.dof);
  relaxation_.Setup(relaxation_kind_, (std::size_t)layout_.n_owned, layout_.cloud.volume.data(), held, scene_.damping, stable_dt_);
  if (relaxation_.active()) {
    char range[96]; // PETSc's %g would print "50."
    std::snprintf(range, sizeof range, "between %g (-damping) and %.4g 1/s", scene_.damping, 4.0 / stable_dt_);
    PetscCall(PetscPrintf(comm_, "Relaxation: adaptive, damping c = 2 omega every step (Rayleigh quotient of the latest increment), %s\n", range));
    // With bonds breaking, the state depends on the loading path and on the dynamics:
    // a route that shortcuts both answers another question.
    if (scene_.failure)
      PetscCall(PetscFPrintf(comm_, PETSC_STDERR,
                             "bapd: warning: -relaxation adaptive with failure (-failure_critical_stretch): the fast route assumes a "
                             "static state that does not depend on the loading path, which breaking bonds make false; use it "
                             "for runs without failure\n"));
  }
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
  double damping = sim->scene_.damping;
  PetscCall(sim->relaxation_.Damping(sim->comm_, &damping)); // -relaxation adaptive: recomputed every step
  if (damping > 0) {
    // Mass-proportional damping, integrated exactly over the step (operator split):
    // works with every TS type and never destabilises the step. The grips' speeds
    // are set again just below.
    const double decay = std::exp(-damping * sim->dt_);
    for (PetscInt k = 0; k < n; ++k) x[n + k] *= decay;
  }
  PetscCall(sim->ApplyLoading(t, x, x + n));
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
  PetscCall(sim->AdaptTimeStep()); // before any checkpoint: a restart takes the same next step
  if (step % sim->scene_.output_interval == 0) {
    PetscCall(sim->WriteHistoryRow(step, t));
    PetscCall(sim->CheckStaticHold(step, t));
  }
  PetscCall(sim->Progress(step, t, PETSC_FALSE));
  PetscCall(sim->OutputAfterStep(step, t)); // fields, checkpoints, SIGTERM/SIGINT
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

} // namespace bapd
