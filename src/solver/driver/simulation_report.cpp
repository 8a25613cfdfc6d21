// The driver's reporting after a step: the observers of run_observer.hpp, in the order
// PostStep hands them the step (history, fields, checkpoints, progress), and the one
// reduction a step that tells every rank about signals and wall clocks.
#include "bapd/solver/driver/simulation.hpp"

#include <cstdio>

namespace bapd {

namespace {

// What every observer of the driver holds: the driver whose state it reads, handed to
// its Observe with each step (the observers are SimulationD's nested classes, so they
// read its private members; WallDue, outside a step, reads sim_).
template <class Simulation> class DriverObserver : public RunObserver {
public:
  explicit DriverObserver(Simulation &sim) : sim_(sim) {}
  PetscErrorCode AfterStep(PetscInt step, double t, const StepEvents &events) final { return Observe(sim_, step, t, events); }

protected:
  virtual PetscErrorCode Observe(Simulation &sim, PetscInt step, double t, const StepEvents &events) = 0;
  Simulation &sim_;
};

} // namespace

// history.csv: a row every -output_interval steps and by load (HistoryReport decides);
// the static-hold test reads the -output_interval rows, so it runs with them (the
// schedule it moves is Loading's), before any checkpoint of this step.
template <int D> class SimulationD<D>::HistoryObserver final : public DriverObserver<SimulationD<D>> {
public:
  using DriverObserver<SimulationD<D>>::DriverObserver;
  PetscErrorCode Observe(SimulationD &sim, PetscInt step, double t, const StepEvents &) override
  {
    bool interval_row;

    PetscFunctionBegin;
    if (sim.history_.Due(step, t, &interval_row)) PetscCall(sim.WriteHistoryRow(step, t, interval_row));
    if (interval_row) PetscCall(sim.CheckStaticHold(step, t));
    PetscFunctionReturn(0);
  }
};

// The field files: every -output_fields_interval steps or every end time / 20 of
// simulated time (SimulationOutput::field_times), and one at the step a signal stops
// the run, before its checkpoint.
template <int D> class SimulationD<D>::FieldObserver final : public DriverObserver<SimulationD<D>> {
public:
  using DriverObserver<SimulationD<D>>::DriverObserver;
  PetscErrorCode Observe(SimulationD &sim, PetscInt step, double t, const StepEvents &events) override
  {
    SimulationOutput &out = sim.output_;

    PetscFunctionBegin;
    const bool due = out.fields.interval > 0 ? step % out.fields.interval == 0 : out.field_times.Due(t);
    if (out.fields.enabled && due) PetscCall(sim.WriteFields(step, t));
    if (events.interrupt && out.fields.enabled && (out.series.frames.empty() || out.series.frames.back().step != step))
      PetscCall(sim.WriteFields(step, t));
    PetscFunctionReturn(0);
  }
};

// checkpoint.h5: on SIGTERM/SIGINT (and the run stops), on SIGUSR1, every
// -checkpoint_interval steps or -checkpoint_wall_interval seconds; and the last good
// state kept for -checkpoint_on_error.
template <int D> class SimulationD<D>::CheckpointObserver final : public DriverObserver<SimulationD<D>> {
public:
  using DriverObserver<SimulationD<D>>::DriverObserver;
  PetscErrorCode Observe(SimulationD &sim, PetscInt step, double t, const StepEvents &events) override
  {
    const CheckpointOptions &options = sim.output_.checkpoint;

    PetscFunctionBegin;
    if (events.interrupt) {
      PetscCall(sim.WriteCheckpointFile(step, t, "interrupted"));
      const std::string path = sim.paths_.checkpoint();
      char              msg[1024];
      std::snprintf(msg, sizeof msg, "interrupted by %s at step %" PetscInt_FMT " (t = %.6e s); the state is saved in %s: continue with -restart %s",
                    InterruptName(events.interrupt).c_str(), step, t, path.c_str(), path.c_str());
      sim.stop_reason_      = msg;
      sim.stopped_on_error_ = true;
      PetscCall(TSSetConvergedReason(sim.ts_, TS_CONVERGED_USER));
      PetscFunctionReturn(0);
    }
    if (events.checkpoint_request) PetscCall(sim.WriteCheckpointFile(step, t, "SIGUSR1"));
    else if ((options.step_interval > 0 && step % options.step_interval == 0) || events.checkpoint_wall)
      PetscCall(sim.WriteCheckpointFile(step, t, "interval"));
    if (options.on_error) PetscCall(sim.SaveGoodState(step, t));
    PetscFunctionReturn(0);
  }
  // Rank 0: is the wall-clock interval since the last checkpoint over?
  bool WallDue(double now) const
  {
    const SimulationOutput &out = this->sim_.output_;
    return out.checkpoint.wall_interval > 0 && now - out.last_checkpoint_wall >= out.checkpoint.wall_interval;
  }
};

// The progress lines: every -progress_interval steps, or (0) every end time / 20 of
// simulated time, and once -progress_wall_interval seconds of wall time have passed
// since the last line (a slow run says where it is).
template <int D> class SimulationD<D>::ProgressObserver final : public DriverObserver<SimulationD<D>> {
public:
  ProgressObserver(SimulationD &sim, double period, double t0) : DriverObserver<SimulationD<D>>(sim)
  {
    times_.Start(period, t0);
    last_wall_ = MPI_Wtime() - sim.wall_start_;
  }
  PetscErrorCode Observe(SimulationD &sim, PetscInt step, double t, const StepEvents &events) override
  {
    PetscFunctionBegin;
    const PetscInt interval = sim.scene_.time_stepping.progress_interval;
    const bool     by_steps = interval > 0 ? step % interval == 0 : times_.Due(t);
    if (!by_steps && !events.progress_wall) PetscFunctionReturn(0);
    last_wall_ = MPI_Wtime() - sim.wall_start_;
    PetscCall(sim.ProgressLine(step, t, last_wall_));
    PetscFunctionReturn(0);
  }
  // Rank 0: is the wall-clock interval since the last line over?
  bool WallDue(double now) const
  {
    const double interval = this->sim_.scene_.time_stepping.progress_wall_interval;
    return interval > 0 && now - this->sim_.wall_start_ - last_wall_ >= interval;
  }

private:
  Cadence      times_;         // -progress_interval 0: a line every end time / 20 of simulated time
  double       last_wall_ = 0; // wall time (since the start) of the last line (rank 0's decides)
};

// After Setup has restored a checkpoint: the observers, from time t on.
template <int D> PetscErrorCode SimulationD<D>::SetupObservers(double t)
{
  PetscFunctionBegin;
  auto checkpoints = std::make_unique<CheckpointObserver>(*this);
  auto progress    = std::make_unique<ProgressObserver>(*this, loading_.end_time() / 20, t);
  checkpoints_     = checkpoints.get();
  progress_        = progress.get();
  observers_.clear();
  observers_.push_back(std::make_unique<HistoryObserver>(*this));
  observers_.push_back(std::make_unique<FieldObserver>(*this));
  observers_.push_back(std::move(checkpoints));
  observers_.push_back(std::move(progress));
  PetscFunctionReturn(0);
}

// One reduction a step: did any rank get SIGTERM/SIGINT or a new SIGUSR1, and is rank 0's
// clock past the checkpoints' or the progress lines' wall-clock interval? Every rank
// then takes the same branch.
template <int D> PetscErrorCode SimulationD<D>::Report(PetscInt step, double t)
{
  PetscFunctionBegin;
  const double now      = MPI_Wtime();
  int          flags[4] = {PendingInterrupt(), rank_ == 0 && checkpoints_->WallDue(now), CheckpointRequestsReceived(),
                           rank_ == 0 && progress_->WallDue(now)};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, flags, 4, MPI_INT, MPI_MAX, comm_));
  StepEvents events;
  events.interrupt          = flags[0];
  events.checkpoint_wall    = flags[1] != 0;
  events.checkpoint_request = flags[2] > checkpoint_requests_served_;
  checkpoint_requests_served_ = flags[2];
  events.progress_wall      = flags[3] != 0;
  for (const std::unique_ptr<RunObserver> &observer : observers_) PetscCall(observer->AfterStep(step, t, events));
  PetscFunctionReturn(0);
}

// The driver at D = 2 and 3 (main.cpp chooses one from the scene): the members defined
// here, one by one. simulation.cpp instantiates the class, which covers only what it
// defines; a class may be explicitly instantiated once in a program.
#define BAPD_SIMULATION_REPORT(D) \
  template PetscErrorCode SimulationD<D>::SetupObservers(double t); \
  template PetscErrorCode SimulationD<D>::Report(PetscInt step, double t);
BAPD_SIMULATION_REPORT(2)
BAPD_SIMULATION_REPORT(3)
#undef BAPD_SIMULATION_REPORT

} // namespace bapd
