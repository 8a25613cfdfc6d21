#pragma once
// What the driver keeps for field output, checkpoints and restart: the options, the
// natural order (built on first use, so a run that asks for neither pays nothing),
// the field files so far and a copy of the last good state. The Simulation members
// that use it live in src/solver/driver/simulation_output.cpp.
#include <petscvec.h>

#include <vector>

#include "bapd/solver/io/cadence.hpp"
#include "bapd/solver/io/checkpoint.hpp"
#include "bapd/solver/io/fields.hpp"
#include "bapd/solver/io/output_directory.hpp"
#include "bapd/solver/parallel/natural_order.hpp"

namespace bapd {

struct SimulationOutput {
  OutputDirectoryLock lock; // the output directory, this run's alone for its life
  FieldOptions        fields;
  CheckpointOptions   checkpoint;
  NaturalOrder        order;    // created on the first field file or checkpoint
  GeometryFingerprint geometry; // with the order
  FieldSeries         series;
  Cadence             field_times; // -output_fields_interval 0: every end time / 20 of simulated time
  double              last_checkpoint_wall = 0;  // MPI_Wtime of the last checkpoint (rank 0's decides)
  PetscInt            last_checkpoint_step = -1;
  // The state after the last completed step (-checkpoint_on_error): a step that
  // diverges leaves X and c33 spoilt, but not the bond state (CheckHealth runs before
  // Failure::Break), so X is enough to write the last good state: its C33 is solved
  // again from a cold start when it is needed (OutputOnDivergence, DiagnoseDivergence),
  // the same values to the solve's tolerance, instead of a per-bond copy every step
  // (8 B a bond, ~220 B a point at delta = 3.015 dx, and its copy each step).
  Vec                 good_state = nullptr;
  PetscInt            good_step = -1;
  double              good_time = 0;
  std::vector<double> good_energy; // the energy budget's totals then (EnergyBudget::totals)
  // Two older states, every 10 steps in turn: for the diagnosis of a blow-up that has
  // already wrecked the last good state (DiagnoseDivergence), one 10 to 20 steps older.
  // Positions and velocities only: the diagnosis solves their C33 again (a function of
  // F, to the solve's tolerance) instead of keeping two per-bond copies (2 x 8 B a
  // bond, ~450 B a point at delta = 3.015 dx).
  static constexpr PetscInt earlier_interval = 10;
  Vec                 earlier_state[2] = {nullptr, nullptr};
  PetscInt            earlier_step[2] = {-1, -1};
  double              earlier_time[2] = {0, 0};
  bool                handlers  = false;

  SimulationOutput() = default;
  ~SimulationOutput()
  {
    VecDestroy(&good_state);
    VecDestroy(&earlier_state[0]);
    VecDestroy(&earlier_state[1]);
    if (handlers) RestoreInterruptHandlers();
  }
  SimulationOutput(const SimulationOutput &)            = delete;
  SimulationOutput &operator=(const SimulationOutput &) = delete;
};

} // namespace bapd
