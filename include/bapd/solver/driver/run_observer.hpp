#pragma once
// The run's reporting as observers (docs/architecture.md). After each step's physics
// (PostStep: damping, grips, health checks, breaking, the next step) the driver hands
// the step to each observer in turn: the history, the field files, the checkpoints and
// the progress lines. Each owns its files, decides when it writes (its schedule) and
// how it goes on after -restart; none changes the state it reads, so adding or
// removing one leaves the results the same bits.
#include <petscsys.h>

namespace bapd {

// What every rank learns about a step in its one reduction: a signal on any rank, and
// the wall-clock schedules on rank 0's clock, so that every rank takes the same branch.
struct StepEvents {
  int  interrupt          = 0;     // SIGTERM or SIGINT on some rank (interrupts.hpp), else 0
  bool checkpoint_request = false; // SIGUSR1: a checkpoint now
  bool checkpoint_wall    = false; // -checkpoint_wall_interval has passed since the last checkpoint
  bool progress_wall      = false; // -progress_wall_interval has passed since the last progress line
};

class RunObserver {
public:
  virtual ~RunObserver() = default;
  // After a step, on every rank with the same arguments (collective).
  virtual PetscErrorCode AfterStep(PetscInt step, double t, const StepEvents &events) = 0;
};

} // namespace bapd
