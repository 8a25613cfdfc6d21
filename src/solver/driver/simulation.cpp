#include "bapd/solver/driver/simulation.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>

#include "bapd/solver/driver/static_solver.hpp"
#include "bapd/solver/input/help.hpp"

namespace bapd {

template <int D> SimulationD<D>::~SimulationD()
{
  TSDestroy(&ts_);
  ISDestroy(&is_position_);
  ISDestroy(&is_momentum_);
  VecDestroy(&X_);
}

namespace {
// The driver's -log_view stages, one set per process for both dimensions.
PetscErrorCode LogStages(const PetscLogStage **stages)
{
  static PetscLogStage registered[6];
  static bool          done = false;

  PetscFunctionBegin;
  if (!done) {
    const char *names[6] = {"Setup", "Partition", "Force", "Ghost exchange", "Time step", "Output"};
    for (int k = 0; k < 6; ++k) PetscCall(PetscLogStageRegister(names[k], &registered[k]));
    done = true;
  }
  *stages = registered;
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode ReadScene(MPI_Comm comm, Scene *scene)
{
  PetscFunctionBegin;
  PetscCall(CheckpointMergeOptions(comm)); // -restart FILE: the checkpoint's options are the defaults
  PetscCall(SceneFromOptions(comm, scene));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::Setup()
{
  Scene scene;

  PetscFunctionBegin;
  PetscCall(ReadScene(comm_, &scene));
  PetscCall(Setup(std::move(scene)));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::Setup(Scene scene)
{
  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
  PetscCallMPI(MPI_Comm_size(comm_, &size_));
  // -log_view stages, registered once per process (a test may build several runs, of
  // either dimension).
  const PetscLogStage *stages;
  PetscCall(LogStages(&stages));
  stage_setup_ = stages[0], stage_partition_ = stages[1], stage_force_ = stages[2];
  stage_ghost_ = stages[3], stage_step_ = stages[4], stage_output_ = stages[5];
  wall_start_ = MPI_Wtime();

  PetscCall(PetscLogStagePush(stage_setup_));
  scene_ = std::move(scene);
  paths_ = OutputPaths(scene_.output.dir);
  PetscCheck(scene_.help_only || scene_.body.dimension == D, comm_, PETSC_ERR_PLIB,
             "SimulationD<%d> was given a scene of dimension %d: build the driver of the scene's dimension (main.cpp)", D, scene_.body.dimension);
  PetscCall(TakeOutputOptions()); // the scene's -output_fields..., -checkpoint_..., -restart
  if (scene_.help_only) {
    // -help all: list the time stepper's options too (PETSc's), and stop.
    if (CurrentHelpMode() != HelpMode::bapd) {
      PetscCall(TSCreate(comm_, &ts_));
      PetscCall(TSSetType(ts_, TSBASICSYMPLECTIC));
      PetscCall(TSSetFromOptions(ts_));
    }
    PetscCall(PetscLogStagePop());
    PetscFunctionReturn(0);
  }
  PetscCall(CheckOptionsEarly());
  PetscCall(StaticSolverCheckScene(comm_, scene_.run, scene_.failure, scene_.material.force_form, scene_.loading.schedule, output_.checkpoint)); // -solver static: what it refuses
  PetscCall(SceneView(comm_, scene_));
  PetscCall(ClaimOutputDirectory()); // before anything is written: locked; a restart's newer results
  PetscCall(BuildBody());
  PetscCall(loading_.Setup(comm_, scene_.loading, scene_.time_stepping.end_time, BodyExtentOf(scene_), layout_));
  PetscCall(BuildProbes());
  last_reaction_.assign(D * scene_.loading.sets.size(), 0.0);
  last_probe_u_.assign(D * scene_.loading.probes.size(), 0.0);
  grip_u_.assign(D * scene_.loading.sets.size(), 0.0);
  {
    std::size_t most = 0;
    for (const LoadSetPoints &set : loading_.load_set_points()) most = std::max(most, set.points.size());
    grip_terms_.assign(D * most, 0.0);
  }
  // -solver static takes no time step: the stable-step estimate (a Krylov search of 10-60
  // force evaluations) and the relaxation are the dynamic route's alone. The TS is still
  // made (it holds the state and the time that the output reads) but never stepped.
  if (scene_.run.solver != SolverKind::static_newton) {
    PetscCall(step_control_.EstimateStable(comm_, scene_.time_stepping, scene_.material, scene_.failure.enabled, scene_.body.dx(), layout_,
                                          loading_, force_));
    PetscCall(SetupRelaxation());
  }
  PetscCall(SetupTimeStepper());
  PetscCall(budget_.Setup(loading_, layout_, scene_.material.density, scene_.loading.sets.size()));
  {
    const double *x;
    PetscCall(VecGetArrayRead(X_, &x));
    PetscCall(budget_.Start(comm_, x + D * layout_.n_owned)); // the grips' speeds at t = 0
    PetscCall(VecRestoreArrayRead(X_, &x));
  }
  // The rows by load: every end time / -output_history_rows of simulated time, the end
  // time as the scene gives it (before a restart or an ended hold moves it), so that a
  // continuation writes the rows the uninterrupted run writes.
  const double history_end = loading_.end_time_original() > 0 ? loading_.end_time_original() : loading_.schedule().end_time();
  const double history_period = scene_.output.history_rows > 0 ? history_end / (double)scene_.output.history_rows : 0.0;
  history_.Setup(scene_.loading, scene_.failure, scene_.output, BodyExtentOf(scene_), paths_);
  history_.StartRowsByLoad(history_period, 0.0); // (HistoryReport::Restore reads its period)
  PetscCall(OpenHistory());
  PetscCall(SetupOutput()); // restores the state with -restart
  {
    PetscReal t;
    PetscCall(TSGetTime(ts_, &t));
    history_.StartRowsByLoad(history_period, t);
    PetscCall(SetupObservers(t)); // history, fields, checkpoints, progress from t on
  }
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

// Every option is checked before any work (docs/options.md): the time stepper's on a
// throw-away TS (a bad -ts_type or -ts_max_steps value fails here, not after the body
// and the stable step are built), then an option nothing read (a typo) is refused.
template <int D> PetscErrorCode SimulationD<D>::CheckOptionsEarly()
{
  TS     probe;
  TSType type = nullptr;

  PetscFunctionBegin;
  PetscCall(TSCreate(comm_, &probe));
  PetscErrorCode ierr = TSSetType(probe, TSBASICSYMPLECTIC);
  if (!ierr) ierr = TSSetFromOptions(probe);
  std::string type_name;
  if (!ierr) ierr = TSGetType(probe, &type);
  if (!ierr && type) type_name = type;
  PetscCall(TSDestroy(&probe));
  PetscCall(ierr);
  // The dynamics are explicit: the TS gets right-hand sides only (u' = v, v' = a(u)),
  // no implicit function and no Jacobian, and the step control (the stable step, the
  // re-estimates, the travel limit) assumes an explicit scheme. An implicit type would
  // fail inside its first nonlinear solve, or never end it.
  static const char *const explicit_types[] = {TSBASICSYMPLECTIC, TSEULER, TSRK, TSSSP};
  bool supported = false;
  for (const char *t : explicit_types) supported |= type_name == t;
  // -ts_max_time would end the run before -end_time (a result far short of the load
  // asked for, reported as finished) or let it run past it: the run's length is bapd's.
  PetscBool max_time = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-ts_max_time", &max_time));
  PetscCheck(!max_time, comm_, PETSC_ERR_USER,
             "-ts_max_time is not read: the run's length is -end_time (default: the end of -load_schedule). Remove -ts_max_time and "
             "give -end_time instead (or -end_step N to stop after step N)");
  PetscCheck(supported, comm_, PETSC_ERR_USER,
             "-ts_type %s is not supported: bapd integrates its equations of motion with an explicit time stepper (it gives PETSc "
             "the right-hand side only, no Jacobian, and its step control assumes an explicit scheme). Use basicsymplectic "
             "(velocity Verlet, the default: leave -ts_type out), rk, euler or ssp",
             type_name.c_str());
  PetscCall(CheckUnusedOptions(comm_));
  PetscFunctionReturn(0);
}

// Each probe reads the point ProbeLocate picks (scene.hpp: nearest, ties to the
// lowest natural id, so the same point on any layout).
template <int D> PetscErrorCode SimulationD<D>::BuildProbes()
{
  PetscFunctionBegin;
  probes_.assign(scene_.loading.probes.size(), {});
  for (std::size_t p = 0; p < scene_.loading.probes.size(); ++p) {
    ProbeLocation where;
    PetscCall(ProbeLocate<D>(comm_, scene_.loading.probes[p], layout_.cloud.x.data(), layout_.cloud.natural_id.data(), layout_.n_owned, &where));
    ProbePoint &pp = probes_[p];
    pp.natural_id  = where.natural_id;
    pp.owner_rank  = where.owner;
    pp.local_index = where.local_index;
    double xyz[3]  = {0, 0, 0};
    if (where.owner == rank_)
      for (int c = 0; c < D; ++c) xyz[c] = layout_.cloud.x[D * where.local_index + c];
    PetscCallMPI(MPI_Bcast(xyz, D, MPI_DOUBLE, where.owner, comm_));
    pp.x = xyz[0], pp.y = xyz[1], pp.z = xyz[2];
    if (D == 2)
      PetscCall(PetscPrintf(comm_, "Probe %s: point %lld at (%g, %g) m\n", scene_.loading.probes[p].name.c_str(), (long long)pp.natural_id, pp.x, pp.y));
    else
      PetscCall(PetscPrintf(comm_, "Probe %s: point %lld at (%g, %g, %g) m\n", scene_.loading.probes[p].name.c_str(), (long long)pp.natural_id, pp.x, pp.y,
                            pp.z));
  }
  PetscFunctionReturn(0);
}

// -relaxation adaptive: the damping coefficient follows the slowest mode (relaxation.hpp).
template <int D> PetscErrorCode SimulationD<D>::SetupRelaxation()
{
  PetscFunctionBegin;
  const double stable_dt = step_control_.stable();
  relaxation_.Setup(scene_.time_stepping.relaxation, (std::size_t)layout_.n_owned, layout_.cloud.volume.data(), loading_.held_dofs(), scene_.time_stepping.damping,
                    stable_dt);
  if (relaxation_.active()) {
    char range[96]; // PETSc's %g would print "50."
    std::snprintf(range, sizeof range, "between %g (-damping) and %.4g 1/s", scene_.time_stepping.damping, 4.0 / stable_dt);
    PetscCall(PetscPrintf(comm_, "Relaxation: adaptive, damping c = 2 omega every step (Rayleigh quotient of the latest increment), %s\n", range));
    // With bonds breaking, the state depends on the loading path and on the dynamics:
    // a route that shortcuts both answers another question.
    if (scene_.failure.enabled)
      PetscCall(PetscFPrintf(comm_, PETSC_STDERR,
                             "bapd: warning: -relaxation adaptive with failure (-failure_critical_stretch): the fast route assumes a "
                             "static state that does not depend on the loading path, which breaking bonds make false; use it "
                             "for runs without failure\n"));
  }
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::PostStep(TS ts)
{
  SimulationD *sim;
  PetscInt    step;
  PetscReal   t;
  Vec         X;
  double     *x;

  PetscFunctionBegin;
  PetscCall(TSGetApplicationContext(ts, &sim));
  PetscCall(TSGetStepNumber(ts, &step));
  PetscCall(TSGetTime(ts, &t));
  PetscCall(TSGetSolution(ts, &X));
  const PetscInt n = D * sim->layout_.n_owned;
  PetscCall(VecGetArray(X, &x));
  double damping = sim->scene_.time_stepping.damping;
  PetscCall(sim->relaxation_.Damping(sim->comm_, &damping)); // -relaxation adaptive: recomputed every step
  // Mass-proportional damping, integrated exactly over the step (operator split):
  // works with every TS type and never destabilises the step. The grips' speeds
  // are set again just below.
  const double decay = damping > 0 ? std::exp(-damping * sim->step_control_.current()) : 1.0;
  sim->budget_.Damp(x + n, decay); // (also without damping: the grips' speeds before they are set)
  if (damping > 0)
    for (PetscInt k = 0; k < n; ++k) x[n + k] *= decay;
  sim->loading_.Apply(t, x, x + n);
  PetscCall(sim->budget_.EndStep(sim->comm_, x, x + n));
  PetscCall(VecRestoreArray(X, &x));

  PetscBool diverged = PETSC_FALSE;
  PetscCall(sim->CheckHealth(step, t, &diverged));
  if (!diverged) {
    // A state outside the law's validity (the chain limit reached in I1): the run is not
    // unstable, its stress is no longer the material's. The message is whole; the last
    // good state is saved as for a divergence.
    std::string invalid;
    PetscCall(sim->CheckLawValidity(step, t, &invalid));
    if (!invalid.empty()) {
      sim->stop_reason_ = invalid, sim->stopped_on_error_ = true;
      PetscCall(sim->OutputOnDivergence());
      PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_NONLINEAR_SOLVE));
      PetscFunctionReturn(0);
    }
  }
  if (!diverged) {
    // Runaway energy: an unstable time step caught before NaN or shattering (divergence.hpp).
    std::string runaway;
    PetscCall(sim->CheckRunaway(step, t, &runaway));
    if (!runaway.empty()) sim->stop_reason_ = runaway, sim->stopped_on_error_ = true, diverged = PETSC_TRUE;
  }
  if (diverged) {
    PetscCall(sim->DiagnoseDivergence()); // the cause, from the last good state
    PetscCall(sim->OutputOnDivergence()); // checkpoint of the last good state
    PetscCall(TSSetConvergedReason(ts, TS_DIVERGED_NONLINEAR_SOLVE));
    PetscFunctionReturn(0);
  }
  bool broke = false; // bonds broke on some rank in this step (BreakFurther)
  if (sim->scene_.failure.enabled) {
    PetscCall(VecGetArray(X, &x));
    PetscCall(sim->force_.UpdatePositions(x));
    PetscCall(VecRestoreArray(X, &x));
    if (sim->failure_.by_energy()) sim->force_.BondEnergies(sim->failure_.bond_energies());
    std::copy(sim->bond_state_.intact.begin(), sim->bond_state_.intact.end(), sim->intact_before_.begin());
    PetscCall(sim->failure_.Break(sim->force_.positions(), sim->step_control_.current(), sim->force_.failed_bonds(), sim->bond_state_,
                                  sim->geometry_));
    PetscCall(sim->BreakFurther(&broke));
    double released;
    PetscCall(sim->ReleasedEnergy(broke, &released));
    sim->budget_.Release(released);
  }
  {
    // Before any checkpoint: a restart takes the same next step (re-estimated about the
  // latest evaluation when due, shortened while points fly: time_step_control.hpp).
    const double *xr;
    PetscCall(VecGetArrayRead(X, &xr));
    PetscCall(sim->step_control_.AfterStep(sim->comm_, step, sim->loading_.stretch_at(t), sim->layout_, sim->families_, sim->bond_state_, sim->force_, xr + n,
                                           sim->scene_.failure.enabled ? &sim->failure_.touched() : nullptr, broke, ts));
    PetscCall(VecRestoreArrayRead(X, &xr));
    sim->relaxation_.FollowStableStep(sim->step_control_.stable_now()); // its cap, 2 omega_max
  }
  // The reporting (a row, a file or a line only reads the state: the results stay the
  // same bits): history.csv and the static-hold test, field files, checkpoints and
  // SIGTERM/SIGINT, progress lines (run_observer.hpp).
  PetscCall(sim->Report(step, t));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::Run()
{
  PetscFunctionBegin;
  if (scene_.help_only) PetscFunctionReturn(0);
  if (scene_.run.solver == SolverKind::static_newton) { // static states by Newton (static_solver.hpp)
    StaticSolver<D> solver(*this);
    PetscCall(solver.Setup());
    PetscCall(solver.Run());
    PetscFunctionReturn(0);
  }
  PetscCall(PetscLogStagePush(stage_step_));
  PetscCall(TSSolve(ts_, X_));
  PetscCall(PetscLogStagePop());
  PetscInt  step;
  PetscReal t;
  PetscCall(TSGetStepNumber(ts_, &step));
  PetscCall(TSGetTime(ts_, &t));
  std::string cut_short;
  if (!stopped_on_error_) PetscCall(StoppedShort(step, t, &cut_short));
  if (history_.last_step() != step && !stopped_on_error_) PetscCall(WriteHistoryRow(step, t)); // the end-of-run row
  PetscCall(OutputAtEnd(step, t)); // the last field file (and checkpoint)
  if (scene_.output.final_state) PetscCall(WriteFinalState());
  // Stopped short of the end time by a PETSc limit: everything a normal end writes is
  // written (above), and then the run fails (below), so that no script takes it for whole.
  if (!cut_short.empty()) stop_reason_ = cut_short, stopped_on_error_ = true;
  PetscCall(Summary());
  PetscCheck(!stopped_on_error_, comm_, PETSC_ERR_NOT_CONVERGED, "%s", stop_reason_.c_str());
  PetscFunctionReturn(0);
}

// The TS stopped at its step limit before the end time: after -end_step (on purpose:
// a note, exit 0), or at -ts_max_steps (PETSc's limit, maybe from a checkpoint's
// options: *message says so, and the run fails). TS_EXACTFINALTIME_MATCHSTEP lands the
// last step on the end time; a run within 1e-9 of it is whole.
template <int D> PetscErrorCode SimulationD<D>::StoppedShort(PetscInt step, double t, std::string *message)
{
  TSConvergedReason reason;
  PetscReal         end;
  PetscInt          max_steps;

  PetscFunctionBegin;
  message->clear();
  PetscCall(TSGetConvergedReason(ts_, &reason));
  PetscCall(TSGetMaxTime(ts_, &end));
  PetscCall(TSGetMaxSteps(ts_, &max_steps));
  if (reason != TS_CONVERGED_ITS || !(end - t > 1e-9 * end)) PetscFunctionReturn(0);
  if (scene_.time_stepping.end_step >= 0 && step >= scene_.time_stepping.end_step) {
    PetscCall(PetscPrintf(comm_, "\nStopped after step %" PetscInt_FMT " (-end_step), at t = %.6e s of the end time %.6e s%s\n", step, t, end,
                          output_.checkpoint.periodic() ? ": continue with -restart and a later -end_step (or -end_step -1)" : ""));
    PetscFunctionReturn(0);
  }
  char text[768];
  std::snprintf(text, sizeof text,
                "the run stopped at step %" PetscInt_FMT " (t = %.6e s), short of its end time %.6e s (%.3g %% of it), because PETSc's "
                "-ts_max_steps %" PetscInt_FMT " ended the time stepping%s. Remove -ts_max_steps: the run's length is -end_time (give "
                "an earlier -end_time to end sooner, or -end_step N to stop after step N on purpose). What was written is kept "
                "(history.csv up to step %" PetscInt_FMT ")",
                step, t, end, 100.0 * t / end, max_steps, output_.checkpoint.restart.empty() ? "" : " (a checkpoint's stored options count)",
                step);
  *message = text;
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::Advance(PetscInt steps)
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

// The driver at D = 2 and 3, chosen once from the scene (main.cpp); every file of
// the driver instantiates the members it defines (the others one by one).
template class SimulationD<2>;
template class SimulationD<3>;

} // namespace bapd
