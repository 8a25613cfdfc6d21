// The driver's output after a step: field files, checkpoints (periodic, on a signal,
// on divergence, at the end) and restart from a checkpoint. The formats live in
// fields.cpp and checkpoint_*.cpp; this file only moves the Simulation's state in and
// out of them.
#include <petscts.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bapd/core/kernel/damage.hpp"
#include "bapd/core/kernel/point_quantities.hpp"
#include "bapd/solver/driver/simulation.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/io/derived_fields.hpp"

namespace bapd {

namespace {

PetscLogEvent event_fields = 0, event_checkpoint = 0, event_restart = 0;

PetscErrorCode RegisterEvents()
{
  static bool registered = false;
  PetscFunctionBegin;
  if (!registered) {
    PetscClassId id;
    PetscCall(PetscClassIdRegister("bapd output", &id));
    PetscCall(PetscLogEventRegister("FieldOutput", id, &event_fields));
    PetscCall(PetscLogEventRegister("Checkpoint", id, &event_checkpoint));
    PetscCall(PetscLogEventRegister("Restart", id, &event_restart));
    registered = true;
  }
  PetscFunctionReturn(0);
}

} // namespace

template <int D> PetscErrorCode SimulationD<D>::TakeOutputOptions()
{
  PetscFunctionBegin;
  output_.fields     = scene_.output.fields;
  output_.checkpoint = scene_.output.checkpoint;
  if (!output_.handlers) InstallInterruptHandlers(); // a signal during the set-up acts at the first step
  output_.handlers = true;
  PetscFunctionReturn(0);
}

// Before anything is written into the output directory: it is locked for this run's
// life (a second run into it stops at once), and a restart that would replace newer
// results there is refused (output_directory.hpp, docs/faults.md).
template <int D> PetscErrorCode SimulationD<D>::ClaimOutputDirectory()
{
  PetscFunctionBegin;
  PetscCall(output_.lock.Acquire(comm_, scene_.output.dir));
  if (!output_.checkpoint.restart.empty()) {
    CheckpointHeader header; // (read again by RestoreCheckpoint, after the body is built)
    PetscCall(ReadCheckpointHeader(comm_, output_.checkpoint.restart, &header));
    PetscCall(CheckNewerResults(comm_, scene_.output.dir, output_.checkpoint.restart, header.step, header.time,
                                output_.checkpoint.discard_newer));
  }
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::SetupOutput()
{
  PetscFunctionBegin;
  PetscCall(RegisterEvents());
  output_.series.output_dir = scene_.output.dir;
  output_.series.geometry   = output_.fields.geometry; // -output_fields_geometry (fields.hpp)
  // The end time as the scene gives it (before a restart or an ended hold moves it), so
  // that a continuation writes the field files the uninterrupted run writes.
  const double end_time = loading_.end_time() > 0 ? loading_.end_time() : loading_.schedule().end_time();
  output_.last_checkpoint_wall = MPI_Wtime();
  PetscInt  step = 0;
  PetscReal t    = 0;
  if (!output_.checkpoint.restart.empty()) {
    PetscCall(RestoreCheckpoint());
    PetscCall(TSGetStepNumber(ts_, &step));
    PetscCall(TSGetTime(ts_, &t));
  }
  if (output_.fields.interval == 0) output_.field_times.Start(end_time / 20, t);
  if (output_.checkpoint.restart.empty() && output_.fields.enabled) {
    PetscCall(WriteFields(0, 0.0));
  }
  if (output_.checkpoint.on_error) {
    PetscCall(VecDuplicate(X_, &output_.good_state));
    for (Vec &earlier : output_.earlier_state) PetscCall(VecDuplicate(X_, &earlier));
    PetscCall(SaveGoodState(step, t));
  }
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::CreateNaturalOrder()
{
  PetscFunctionBegin;
  if (output_.order.created()) PetscFunctionReturn(0);
  PetscCall(NaturalOrderCreate(comm_, layout_, families_, &output_.order));
  PetscCall(ComputeGeometryFingerprint<D>(comm_, layout_, families_, scene_.body.dx(), scene_.body.horizon(), &output_.geometry));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::SaveGoodState(PetscInt step, double t)
{
  PetscFunctionBegin;
  PetscCall(VecCopy(X_, output_.good_state));
  output_.good_step = step;
  output_.good_time = t;
  budget_.totals(&output_.good_energy);
  if (step % SimulationOutput::earlier_interval == 0) {
    const int slot = (int)((step / SimulationOutput::earlier_interval) % 2);
    PetscCall(VecCopy(X_, output_.earlier_state[slot]));
    output_.earlier_step[slot] = step;
    output_.earlier_time[slot] = t;
  }
  PetscFunctionReturn(0);
}

// CheckHealth stopped the run: put the last good state back, write it as a
// checkpoint (and a field file), and say so in the stop message.
template <int D> PetscErrorCode SimulationD<D>::OutputOnDivergence()
{
  PetscFunctionBegin;
  if (!output_.checkpoint.on_error || output_.good_step < 0) PetscFunctionReturn(0);
  PetscCall(VecCopy(output_.good_state, X_));
  {
    // Its C33, solved again from a cold start (simulation_output.hpp); the bond state
    // is the good state's already.
    const double *x;
    std::fill(force_.warm_start().begin(), force_.warm_start().end(), 0.0);
    PetscCall(VecGetArrayRead(X_, &x));
    PetscCall(force_.EvaluateWithWarmStart(x, force_density_.data(), force_.warm_start()));
    PetscCall(VecRestoreArrayRead(X_, &x));
  }
  PetscCall(TSSetStepNumber(ts_, output_.good_step));
  PetscCall(TSSetTime(ts_, output_.good_time));
  if (output_.fields.enabled) PetscCall(WriteFields(output_.good_step, output_.good_time));
  PetscCall(WriteCheckpointFile(output_.good_step, output_.good_time, "last good state"));
  const std::string path = paths_.checkpoint();
  char              msg[512];
  std::snprintf(msg, sizeof msg, " The last good state (step %" PetscInt_FMT ", t = %.6e s) is saved in %s: continue from it with -restart %s and the change above.",
                output_.good_step, output_.good_time, path.c_str(), path.c_str());
  stop_reason_ += msg;
  PetscFunctionReturn(0);
}

// Run() after the last step: the last field file and, with periodic checkpoints, a
// final checkpoint (to extend the run later with a later -end_time).
template <int D> PetscErrorCode SimulationD<D>::OutputAtEnd(PetscInt step, double t)
{
  PetscFunctionBegin;
  if (stopped_on_error_) PetscFunctionReturn(0);
  if (output_.fields.enabled && (output_.series.frames.empty() || output_.series.frames.back().step != step)) PetscCall(WriteFields(step, t));
  if (output_.checkpoint.periodic() && output_.last_checkpoint_step != step) PetscCall(WriteCheckpointFile(step, t, "end"));
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::WriteFields(PetscInt step, double t)
{
  const PetscInt n = layout_.n_owned;
  const double  *x;

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_output_));
  PetscCall(PetscLogEventBegin(event_fields, 0, 0, 0, 0));
  PetscCall(CreateNaturalOrder());
  std::vector<double> damage(n), largest(n);
  PetscCall(VecGetArrayRead(X_, &x));
  PetscCall(force_.UpdatePositions(x)); // y for the stretch; the next force evaluation sets it again
  point_damage(layout_.cloud, families_, bond_state_, (std::size_t)n, damage.data());
  largest_bond_stretch<D>(layout_.cloud, force_.positions(), families_, bond_state_, (std::size_t)n, largest.data());
  PointFields fields;
  fields.reference        = layout_.cloud.x.data();
  fields.displacement     = x;
  fields.velocity         = x + D * n;
  fields.damage           = damage.data();
  fields.max_bond_stretch = largest.data();
  // Force density, volume, stress, F, lambda_3, W (point_quantities.hpp): read the
  // state (and the C33 warm start) without changing it.
  std::vector<double> force(D * n);
  PointQuantities     quantities;
  PetscCall(ComputePointQuantities(x, force.data(), &quantities)); // leaves the warm starts as they were
  fields.volume                = layout_.cloud.volume.data();
  fields.force_density         = force.data();
  fields.nominal_stress        = quantities.nominal_stress.data();
  fields.cauchy_stress         = quantities.cauchy_stress.data();
  fields.deformation_gradient  = quantities.deformation_gradient.data();
  fields.thickness_stretch     = D == 2 ? quantities.thickness_stretch.data() : nullptr; // (3D: none)
  fields.strain_energy_density = quantities.strain_energy_density.data();
  // von Mises stress and principal stretches from sigma_i, F_i and lambda_3 (derived_fields.hpp).
  std::vector<double> von_mises(n), principal(3 * n);
  derived_fields<D>((std::size_t)n, quantities.cauchy_stress.data(), quantities.deformation_gradient.data(),
                    D == 2 ? quantities.thickness_stretch.data() : nullptr, von_mises.data(), principal.data());
  fields.von_mises_stress  = von_mises.data();
  fields.principal_stretch = principal.data();
  // The grips apart from the specimen: the (1-based) load set holding each point, the
  // first in the scene's order where sets overlap.
  std::vector<double> load_set(n, 0.0);
  const auto         &sets = loading_.load_set_points();
  for (std::size_t k = sets.size(); k-- > 0;)
    for (PetscInt i : sets[k].points) load_set[i] = (double)(k + 1);
  fields.load_set = load_set.data();
  const PetscErrorCode written = WriteFieldFrame<D>(comm_, output_.order, &output_.series, step, t, loading_.stretch_at(t), fields);
  PetscCall(VecRestoreArrayRead(X_, &x)); // also when the file could not be written
  PetscCall(written);
  PetscCall(PetscLogEventEnd(event_fields, 0, 0, 0, 0));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode SimulationD<D>::ComputePointQuantities(const double *u_owned, double *force_density, PointQuantities *quantities)
{
  PetscFunctionBegin;
  PetscCall(ComputeForceDensity(u_owned, force_density)); // sets the positions, ghosts included
  point_quantities(scene_.material.model, scene_.material.formulation, scene_.material.parameters, layout_.cloud, force_.positions(), families_, geometry_,
                   bond_state_, force_.warm_start().data(), (std::size_t)layout_.n_owned,
                   scene_.material.force_form == ForceForm::energy_consistent ? StressWeights::bond_energy : StressWeights::bond_force,
                   *quantities, scene_.material.volumetric,
                   scene_.material.volumetric_stabilisation * scene_.material.parameters.mu);
  PetscFunctionReturn(0);
}

// What a checkpoint holds of the state X = [u, v] (owned, D per point each): written
// from it, or read back into it.
template <int D> CheckpointState SimulationD<D>::CheckpointView(double *x)
{
  CheckpointState state;
  state.u     = x;
  state.v     = x + D * layout_.n_owned;
  state.bonds = &bond_state_;
  state.c33   = force_.warm_start().empty() ? nullptr : force_.warm_start().data(); // (3D: no C33)
  return state;
}

template <int D> PetscErrorCode SimulationD<D>::WriteCheckpointFile(PetscInt step, double t, const char *reason)
{
  double        *x;

  PetscFunctionBegin;
  PetscCall(PetscLogStagePush(stage_output_));
  PetscCall(PetscLogEventBegin(event_checkpoint, 0, 0, 0, 0));
  const double wall = MPI_Wtime();
  PetscCall(CreateNaturalOrder());
  CheckpointHeader header;
  header.step      = step;
  header.time      = t;
  header.time_step = step_control_.current();
  header.stretch   = loading_.stretch_at(t);
  header.reason    = reason;
  header.geometry  = output_.geometry;
  if (rank_ == 0) {
    char *all = nullptr;
    PetscCall(PetscOptionsGetAll(nullptr, &all));
    header.options = all ? all : "";
    PetscCall(PetscFree(all));
    history_.Texts(&header.history, &header.static_states); // (history_report.hpp)
  }
  header.schedule_original = loading_.schedule_original();
  header.schedule_current  = loading_.schedule().time;
  header.end_time_original = loading_.end_time_original();
  header.end_time          = loading_.end_time();
  header.static_hold_done  = loading_.hold_done();
  if (std::strcmp(reason, "last good state") == 0) header.energy_totals = output_.good_energy;
  else budget_.totals(&header.energy_totals);
  for (const FieldFrame &frame : output_.series.frames) {
    header.field_frames.push_back((double)frame.step);
    header.field_frames.push_back(frame.time);
  }
  const std::string path = paths_.checkpoint();
  PetscCall(VecGetArray(X_, &x));
  CheckpointState state = CheckpointView(x);
  // -relaxation adaptive: the latest force evaluation, which the next step's damping
  // is computed against (not for the last good state of a diverged run: the
  // continuation then starts the estimate afresh, at the -damping floor for one step).
  if (relaxation_.active() && std::strcmp(reason, "last good state") != 0) {
    header.relaxation_records = relaxation_.records();
    state.relaxation_u        = relaxation_.latest_u();
    state.relaxation_a        = relaxation_.latest_a();
  }
  // The re-estimated step: its state and eigenvector (time_step_control.hpp); not for
  // the last good state either (the continuation starts from the estimate at rest).
  if (step_control_.reestimating() && std::strcmp(reason, "last good state") != 0) {
    const TimeStepState s    = step_control_.state();
    header.step_lambda        = s.lambda;
    header.step_stiffness_dt  = s.stiffness_dt;
    header.step_shortest      = s.shortest;
    header.step_next_estimate = s.next_estimate;
    header.step_by_stiffness  = s.by_stiffness;
    header.step_by_travel     = s.by_travel;
    header.step_stretch       = s.stretch;
    header.step_interval_now  = s.interval_now;
    header.step_stretch_increment = s.stretch_increment;
    header.step_indicator     = s.indicator;
    state.step_eigenvector    = step_control_.eigenvector();
  }
  const PetscErrorCode written = WriteCheckpoint<D>(comm_, path, output_.order, families_, &header, state);
  PetscCall(VecRestoreArray(X_, &x)); // also when the checkpoint could not be written
  PetscCall(written);
  output_.last_checkpoint_step = step;
  output_.last_checkpoint_wall = MPI_Wtime();
  double megabytes = 0;
  if (rank_ == 0) {
    std::error_code ec;
    megabytes = (double)std::filesystem::file_size(path, ec) / 1e6;
  }
  PetscCall(PetscPrintf(comm_, "Checkpoint (%s): step %" PetscInt_FMT ", t = %.6e s -> %s (%.2f MB, %.3f s)\n", reason, step, t, path.c_str(),
                        megabytes, MPI_Wtime() - wall));
  PetscCall(PetscLogEventEnd(event_checkpoint, 0, 0, 0, 0));
  PetscCall(PetscLogStagePop());
  PetscFunctionReturn(0);
}

// The schedule as the checkpoint left it (Loading::Restore), and the TS's end time.
template <int D> PetscErrorCode SimulationD<D>::RestoreSchedule(const CheckpointHeader &header)
{
  PetscFunctionBegin;
  PetscCall(loading_.Restore(header.schedule_original, header.schedule_current, header.end_time_original, header.end_time, header.time,
                             (PetscInt)header.static_hold_done));
  PetscCall(TSSetMaxTime(ts_, loading_.end_time()));
  if (loading_.end_time() <= header.time)
    PetscCall(PetscPrintf(comm_, "\n*** WARNING: the checkpoint is at t = %.6e s, already at the end time %.6e s: this run takes no step. "
                                 "Give a later -end_time to go on.\n\n", header.time, loading_.end_time()));
  PetscFunctionReturn(0);
}

// A restart's field files: those of the checkpoint's list that are here, listed again
// (a run killed after the checkpoint may have written later ones), and fields.xdmf.
template <int D> PetscErrorCode SimulationD<D>::RestoreFieldSeries(const CheckpointHeader &header)
{
  PetscFunctionBegin;
  std::vector<int> present(header.field_frames.size() / 2, 0);
  if (rank_ == 0)
    for (std::size_t k = 0; k < present.size(); ++k) {
      std::error_code ec;
      present[k] = std::filesystem::exists(paths_.field_file((long long)header.field_frames[2 * k]), ec);
    }
  if (!present.empty()) PetscCallMPI(MPI_Bcast(present.data(), (int)present.size(), MPI_INT, 0, comm_));
  output_.series.frames.clear();
  for (std::size_t k = 0; k < present.size(); ++k)
    if (present[k]) output_.series.frames.push_back({(PetscInt)header.field_frames[2 * k], header.field_frames[2 * k + 1]});
  if (output_.fields.enabled) PetscCall(WriteFieldIndex<D>(comm_, output_.series, layout_.n_global));
  PetscFunctionReturn(0);
}

// -restart FILE: the options were merged before the scene was read
// (CheckpointMergeOptions); here the state replaces the initial one.
template <int D> PetscErrorCode SimulationD<D>::RestoreCheckpoint()
{
  const std::string &path = output_.checkpoint.restart;
  double            *x;

  PetscFunctionBegin;
  PetscCall(PetscLogEventBegin(event_restart, 0, 0, 0, 0));
  CheckpointHeader header;
  PetscCall(ReadCheckpointHeader(comm_, path, &header));
  PetscCall(CreateNaturalOrder());
  PetscCall(VecGetArray(X_, &x));
  CheckpointState state = CheckpointView(x);
  if (relaxation_.active()) {
    state.relaxation_u = relaxation_.latest_u();
    state.relaxation_a = relaxation_.latest_a();
  }
  if (step_control_.reestimating()) state.step_eigenvector = step_control_.eigenvector();
  PetscCall(ReadCheckpointState<D>(comm_, path, output_.order, families_, header, output_.geometry, state));
  if (relaxation_.active()) relaxation_.RestoreLatest((int)header.relaxation_records);
  PetscCall(VecRestoreArray(X_, &x));
  // The reference geometry of the families with their broken bonds, as the run had it.
  nd::compute_bond_geometry<D>(layout_.cloud, families_, bond_state_, geometry_);
  force_.ForgetStats();
  PetscCall(TSSetStepNumber(ts_, header.step));
  PetscCall(TSSetTime(ts_, header.time));
  PetscCall(RestoreSchedule(header));
  // The energy budget goes on from the checkpoint's totals; a checkpoint without them
  // (format 6 and older) or with other load sets starts it afresh at the restart.
  if (header.energy_totals.size() == 2 + budget_.load_sets()) budget_.RestoreTotals(header.energy_totals);
  else {
    PetscCall(PetscPrintf(comm_, "Note: the checkpoint holds no energy budget for these load sets: the work, dissipation and balance "
                                 "columns of history.csv count from the restart\n"));
    warned_balance_ = true; // its residual now starts off by the energy at the restart
  }
  {
    PetscInt max_steps;
    PetscCall(TSGetMaxSteps(ts_, &max_steps));
    const char *limit = scene_.time_stepping.end_step >= 0 && scene_.time_stepping.end_step == max_steps ? "-end_step" : "-ts_max_steps";
    if (max_steps <= header.step)
      PetscCall(PetscPrintf(comm_, "\n*** WARNING: the checkpoint is at step %" PetscInt_FMT ", already at %s %" PetscInt_FMT
                                   " (the options stored in the checkpoint count): this run takes no step. Give a larger %s.\n\n",
                            (PetscInt)header.step, limit, max_steps, limit));
  }
  // A step shortened by stiffness or -time_step_travel goes on as it was, and so does
  // the re-estimate: the continuation is then the uninterrupted run. A new, shorter
  // base step (a smaller -time_step_safety) wins.
  {
    TimeStepState s;
    s.lambda        = step_control_.reestimating() ? header.step_lambda : 0;
    s.stiffness_dt  = header.step_stiffness_dt;
    s.shortest      = header.step_shortest;
    s.next_estimate = (PetscInt)header.step_next_estimate;
    s.by_stiffness  = (PetscInt)header.step_by_stiffness;
    s.by_travel     = (PetscInt)header.step_by_travel;
    s.stretch       = header.step_stretch;
    s.interval_now  = (PetscInt)header.step_interval_now;
    s.stretch_increment = header.step_stretch_increment;
    s.indicator         = header.step_indicator;
    PetscCall(step_control_.Restore(header.time_step, s, ts_));
  }
  if (header.time_step != step_control_.current())
    PetscCall(PetscPrintf(comm_, "Note: the checkpoint was written with dt = %.6e s; this run uses dt = %.6e s\n", header.time_step,
                          step_control_.current()));
  PetscCall(BrokenBondCount(&total_broken_));

  PetscCall(history_.Restore(comm_, header)); // history.csv and static_states.csv from the checkpoint

  PetscCall(RestoreFieldSeries(header));

  PetscCall(PetscPrintf(comm_, "Restart from %s: step %" PetscInt_FMT ", t = %.6e s, stretch %.5f, %" PetscInt_FMT " broken bonds (written by %lld rank(s), %s)\n",
                        path.c_str(), header.step, header.time, loading_.stretch_at(header.time), total_broken_,
                        (long long)header.ranks, header.reason.c_str()));
  PetscCall(PetscLogEventEnd(event_restart, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// The driver at D = 2 and 3 (main.cpp chooses one from the scene): the members defined
// here, one by one. simulation.cpp instantiates the class, which covers only what it
// defines; a class may be explicitly instantiated once in a program.
#define BAPD_SIMULATION_OUTPUT(D) \
  template PetscErrorCode SimulationD<D>::TakeOutputOptions(); \
  template PetscErrorCode SimulationD<D>::ClaimOutputDirectory(); \
  template PetscErrorCode SimulationD<D>::SetupOutput(); \
  template PetscErrorCode SimulationD<D>::CreateNaturalOrder(); \
  template PetscErrorCode SimulationD<D>::SaveGoodState(PetscInt step, double t); \
  template PetscErrorCode SimulationD<D>::OutputOnDivergence(); \
  template PetscErrorCode SimulationD<D>::OutputAtEnd(PetscInt step, double t); \
  template PetscErrorCode SimulationD<D>::WriteFields(PetscInt step, double t); \
  template PetscErrorCode SimulationD<D>::ComputePointQuantities(const double *u_owned, double *force_density, PointQuantities *quantities); \
  template CheckpointState SimulationD<D>::CheckpointView(double *x); \
  template PetscErrorCode SimulationD<D>::WriteCheckpointFile(PetscInt step, double t, const char *reason); \
  template PetscErrorCode SimulationD<D>::RestoreSchedule(const CheckpointHeader &header); \
  template PetscErrorCode SimulationD<D>::RestoreFieldSeries(const CheckpointHeader &header); \
  template PetscErrorCode SimulationD<D>::RestoreCheckpoint();
BAPD_SIMULATION_OUTPUT(2)
BAPD_SIMULATION_OUTPUT(3)
#undef BAPD_SIMULATION_OUTPUT

} // namespace bapd
