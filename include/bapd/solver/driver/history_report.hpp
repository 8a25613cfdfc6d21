#pragma once
// history.csv and static_states.csv, owned here alone: their columns, their rows,
// when a row is due, what a checkpoint keeps of them and how a restart writes them
// again. The driver measures a row (HistoryRow: reactions, probes, energies, the
// crack) and hands it over; nothing here reads the state (docs/architecture.md).
//
// Rows (docs/options_run.md, "Output"): every -output_interval steps, where the
// static-hold test runs, and by load, at the first step at or past each end time /
// -output_history_rows (Cadence). Rank 0 writes; every rank learns how it went, so
// every rank stops alike on a full disk or a deleted directory.
#include <petscsys.h>

#include <cstdio>
#include <string>

#include "bapd/solver/input/scene.hpp"
#include "bapd/solver/io/cadence.hpp"
#include "bapd/solver/io/checkpoint.hpp"
#include "bapd/solver/io/output_directory.hpp"
#include "bapd/solver/operators/energy_budget.hpp"

namespace bapd {

// The area the nominal stress of a load set divides its y reaction by: the sheet's
// width x thickness (2D), the x-z section of the body's extent (3D).
double NominalArea(const BodyExtent &body);

// One row of history.csv, as measured on every rank (reproducible sums: the same
// values everywhere). D = the scene's dimension.
struct HistoryRow {
  PetscInt      step = 0;
  double        time = 0, stretch = 1;
  const double *reaction = nullptr; // D per load set (N)
  const double *probe_u  = nullptr; // D per probe (m)
  double        kinetic = 0, internal = 0;
  PetscInt      broken_bonds = 0;
  double        next_dt      = 0;       // the next step (time_step_control.hpp)
  const EnergyBudget *budget = nullptr; // the grips' work, damping, fracture (energy_budget.hpp)
  double        residual  = 0;          // the energy balance's residual
  double        crack_area = 0;         // with failure
  const double *crack_tip = nullptr;    // with failure: {length along the axis, x, y[, z]}
  const double *grip_u    = nullptr;    // D per load set: the grips' mean displacement
};

class HistoryReport {
public:
  HistoryReport() = default;
  ~HistoryReport(); // closes the files
  HistoryReport(const HistoryReport &)            = delete;
  HistoryReport &operator=(const HistoryReport &) = delete;

  // The columns of the load sets and probes (loading), of the crack (failure) and of
  // the body's dimension; the rows every -output_interval steps (output); the nominal
  // stress over the body's NominalArea. Kept: `loading` outlives the report.
  void Setup(const LoadingSection &loading, const FailureSection &failure, const OutputSection &output, const BodyExtent &body,
             const OutputPaths &paths);
  // Rows by load every `load_period` of simulated time from t0 (0: none). Called again
  // at a restart's time (the period stays).
  void StartRowsByLoad(double load_period, double t0) { by_load_.Start(load_period, t0); }

  std::string Header() const;             // history.csv's columns for this scene
  std::string StaticStatesHeader() const; // static_states.csv's

  // A fresh run: creates the directory and history.csv with its header (collective; a
  // restart writes the file in Restore instead).
  PetscErrorCode Open(MPI_Comm comm);
  // After a step: is a row due, and is it a row of the -output_interval grid (the
  // static test's)? Every step: the rows by load count the steps they pass.
  bool Due(PetscInt step, double t, bool *interval_row);
  // One row (collective: rank 0 writes). No allocation.
  PetscErrorCode WriteRow(MPI_Comm comm, const HistoryRow &row);
  // One row of static_states.csv (collective): the stretch, time, step, the ratio of
  // kinetic to internal energy, the probes' displacement and the load sets' y reaction.
  PetscErrorCode WriteStaticState(MPI_Comm comm, double stretch, double t, PetscInt step, double ratio, const double *probe_u,
                                  const double *reaction);
  // Rank 0: both files' text, for a checkpoint (WriteCheckpointFile).
  void Texts(std::string *history, std::string *static_states) const;
  // -restart: history.csv and static_states.csv from the checkpoint's rows, to which
  // this run's are appended (collective).
  PetscErrorCode Restore(MPI_Comm comm, const CheckpointHeader &header);

  PetscInt last_step() const { return last_step_; } // the step of the last row (-1: none)
  bool     has_static_states() const { return static_states_ != nullptr; }

private:
  const LoadingSection *loading_ = nullptr;
  bool                  failure_  = false;
  PetscInt              interval_ = 1;   // -output_interval
  double                area_     = 0.0; // NominalArea
  OutputPaths           paths_;
  int                   dim_ = 2;
  Cadence      by_load_;           // the rows by load
  PetscInt     last_step_ = -1;    // the end-of-run row is not written twice
  FILE        *history_ = nullptr, *static_states_ = nullptr; // rank 0
};

} // namespace bapd
