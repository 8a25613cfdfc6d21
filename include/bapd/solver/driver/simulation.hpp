#pragma once
// The program a user runs, as a class whose Run() reads like the method:
// read the scene, build the body and its families, partition, set up the ghosted
// state, pick the stable time step, then step with PETSc TS while loading, breaking
// bonds and writing the history. The concerns are
// objects with their own data (docs/architecture.md): the force operator
// (force_operator.hpp), loading (loading.hpp), failure (failure.hpp) and time-step
// control (time_step_control.hpp); the Simulation holds the body's data, which they
// share, and the reporting and output that read it. The scene is read once and only
// read afterwards.
//
// One code path for D = 2 (a plane sheet) and D = 3 (a solid body): SimulationD<D>,
// instantiated twice; main.cpp reads the scene (ReadScene) and builds the one its
// dimension asks for. u and v hold D values a point; the history has z columns in 3D
// only.
#include <petscsf.h>
#include <petscts.h>

#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/solver/io/cadence.hpp"
#include "bapd/solver/operators/divergence.hpp"
#include "bapd/solver/operators/energy_budget.hpp"
#include "bapd/solver/operators/failure.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/solver/operators/force_operator.hpp"
#include "bapd/solver/parallel/layout.hpp"
#include "bapd/solver/operators/loading.hpp"
#include "bapd/solver/operators/relaxation.hpp"
#include "bapd/solver/input/scene.hpp"
#include "bapd/solver/driver/history_report.hpp"
#include "bapd/solver/driver/run_observer.hpp"
#include "bapd/solver/driver/simulation_output.hpp"
#include "bapd/solver/operators/time_step_control.hpp"

namespace bapd {

struct PointQuantities;
template <int D> class StaticSolver; // -solver static (static_solver.hpp)

struct ProbePoint {
  PetscInt owner_rank  = -1; // rank that owns the point
  PetscInt local_index = -1; // on the owner
  double   x = 0, y = 0, z = 0; // reference position of the chosen point (z: 3D)
  int64_t  natural_id = -1;
};

// The scene as the driver reads it: a checkpoint's options merged first (-restart),
// then SceneFromOptions. main.cpp reads it once to choose D.
PetscErrorCode ReadScene(MPI_Comm comm, Scene *scene);

template <int D> class SimulationD {
  static_assert(D == 2 || D == 3, "SimulationD: a plane sheet (2) or a solid body (3)");

public:
  explicit SimulationD(MPI_Comm comm) : comm_(comm) {}
  ~SimulationD();
  SimulationD(const SimulationD &)            = delete;
  SimulationD &operator=(const SimulationD &) = delete;

  // Reads the scene from the options database (ReadScene) and builds everything up to the TS.
  PetscErrorCode Setup();
  // The same with the scene already read (its dimension must be D).
  PetscErrorCode Setup(Scene scene);
  // Steps to the end time, writing history and progress; prints a summary.
  PetscErrorCode Run();
  // Takes exactly `steps` more time steps (tests, tools); no summary.
  PetscErrorCode Advance(PetscInt steps);

  // Accessors for tests and tools.
  const Scene  &scene() const { return scene_; }
  const Layout &layout() const { return layout_; }
  const EnergyBudget &energy_budget() const { return budget_; } // where the grips' work went (energy_budget.hpp)
  Vec           state() const { return X_; } // [u (D per owned point), v (D per owned point)]
  TS            ts() const { return ts_; }
  double        stable_time_step() const { return step_control_.stable(); }
  // Force density (D per owned point) for the owned displacements u_owned.
  PetscErrorCode ComputeForceDensity(const double *u_owned, double *force_density);
  // Force density as above and the per-point stress, F, lambda_3 and W of the owned
  // points (point_quantities.hpp), as the field output forms them.
  PetscErrorCode ComputePointQuantities(const double *u_owned, double *force_density, PointQuantities *quantities);
  // Total energy pieces and broken bonds, reproducible across rank layouts.
  PetscErrorCode Energies(double *kinetic, double *internal, Vec state = nullptr); // state: X_ if nullptr
  PetscErrorCode BrokenBondCount(PetscInt *count);
  // Displacement of every point, gathered on rank 0 in natural order (tests, output).
  PetscErrorCode GatherDisplacement(std::vector<double> *u_natural);
  // Directed broken bonds as (natural id i, natural id j) pairs on rank 0, sorted.
  PetscErrorCode GatherBrokenBonds(std::vector<std::pair<int64_t, int64_t>> *bonds);

private:
  friend class StaticSolver<D>; // reuses the set-up, the history and the output (static_solver.hpp)

  PetscErrorCode CheckOptionsEarly(); // before the body is built
  PetscErrorCode BuildBody();
  PetscErrorCode BuildProbes();
  PetscErrorCode SetupTimeStepper();
  PetscErrorCode OpenHistory(); // history.csv with its first row (history_report.hpp)
  PetscErrorCode SetupRelaxation(); // -relaxation (relaxation.hpp)

  // The acceleration of the owned points for displacement u (owned, D per point).
  PetscErrorCode Acceleration(const double *u_owned, double *a_owned);
  PetscErrorCode CheckHealth(PetscInt step, double t, PetscBool *diverged);
  PetscErrorCode CheckRunaway(PetscInt step, double t, std::string *message);
  // Without failure: bonds past their law's limit in I1 = tr C for past_limit_steps
  // consecutive steps (the kernel's largest tr C as the trigger, the bonds counted and
  // located once it fires): *message is the stop.
  PetscErrorCode CheckLawValidity(PetscInt step, double t, std::string *message);
  PetscErrorCode DiagnoseDivergence(); // the cause and its fix, appended to stop_reason_ (divergence.hpp)
  // The largest chain reach of a state's bonds and that bond's largest principal stretch
  // (DivergenceFacts::chain_reach, bond_stretch); span: the law's I1bar limit - 3.
  PetscErrorCode ChainReach(const double *u_owned, const std::vector<double> &c33, double span, double reach[2]);
  PetscErrorCode DiagnoseEarlierState(std::size_t c33_size, double span, DivergenceFacts *f); // the state 10 to 20 steps before
  PetscErrorCode ReadProbes(const double *u_owned, double *probe_u);
  PetscErrorCode GatherNatural(const double *values, std::vector<double> *natural);
  // checks: a row of the -output_interval grid (or the first or last), where the
  // energy-balance warning is checked; the rows by load only write.
  PetscErrorCode WriteHistoryRow(PetscInt step, double t, bool checks = true);
  // The grips' displacement: the mean of each load set's points, D components per set
  // (every component; history.csv writes the loaded ones). Collective, reproducible.
  PetscErrorCode GripDisplacements(const double *u_owned, double *mean);
  PetscErrorCode WarnEnergyBalance(PetscInt step, double t, double work, double residual); // once, past 1 % of the work
  PetscErrorCode ProgressLine(PetscInt step, double t, double wall); // one progress line (ProgressObserver decides when)
  PetscErrorCode Summary();
  // After TSSolve: the TS stopped at its step limit before the end time (-end_step: a
  // note; -ts_max_steps: *message, the error the run ends with).
  PetscErrorCode StoppedShort(PetscInt step, double t, std::string *message);
  PetscErrorCode ListOutputFiles(); // rank 0: every file written, with its size
  PetscErrorCode TimeStepSummary(PetscInt steps); // steps shortened and why, re-estimates' cost
  PetscErrorCode WriteFinalState();
  PetscErrorCode CheckStaticHold(PetscInt step, double t);

  static PetscErrorCode RHSPosition(TS, PetscReal, Vec, Vec, void *);
  static PetscErrorCode RHSMomentum(TS, PetscReal, Vec, Vec, void *);
  static PetscErrorCode RHSFull(TS, PetscReal, Vec, Vec, void *);
  static PetscErrorCode PreStep(TS);
  static PetscErrorCode PostStep(TS);
  // The reporting observers (run_observer.hpp, simulation_report.cpp), in the order a
  // step is handed to them: history, field files, checkpoints, progress.
  class HistoryObserver;
  class FieldObserver;
  class CheckpointObserver;
  class ProgressObserver;
  PetscErrorCode SetupObservers(double t); // after a restart's state is restored
  PetscErrorCode Report(PetscInt step, double t); // after PostStep's physics: the step's one reduction, then each observer
  // After the step's breaking passes, broke: whether they broke bonds on some rank
  // (BreakFurther's): the internal energy they released, E(bonds before) - E(bonds
  // after) at the same positions (0 if none broke). Collective.
  PetscErrorCode ReleasedEnergy(bool broke, double *released);
  // After the step's first breaking pass: *broke, whether it broke bonds on any rank
  // (the step's one reduction of it); with the fracture-energy criterion, more passes at
  // the same positions while the last one broke bonds somewhere (at most
  // -failure_passes in all; docs/method.md 5.2). Collective.
  PetscErrorCode BreakFurther(bool *broke);
  // The axis the crack's tip is measured along (crack_axis_): from the mouth of the
  // scene's first 2D notch towards its inner end; else +x from the body's smallest x.
  PetscErrorCode SetupCrackAxis();
  // The crack of the broken bonds (history.csv): its area and its tip, {length along the
  // axis, x, y[, z]} (NaN while no bond is broken). Collective; reproducible.
  PetscErrorCode CrackExtent(double *area, double tip[4]);

  // Field output, checkpoints and restart (simulation_output.cpp).
  PetscErrorCode TakeOutputOptions(); // the scene's output section into output_
  PetscErrorCode ClaimOutputDirectory(); // locked; a restart's newer results refused (output_directory.hpp)
  PetscErrorCode SetupOutput();
  PetscErrorCode OutputOnDivergence();
  PetscErrorCode OutputAtEnd(PetscInt step, double t);
  PetscErrorCode CreateNaturalOrder();
  PetscErrorCode SaveGoodState(PetscInt step, double t);
  PetscErrorCode WriteFields(PetscInt step, double t);
  PetscErrorCode WriteCheckpointFile(PetscInt step, double t, const char *reason);
  CheckpointState CheckpointView(double *x); // u, v, bond states and C33 as a checkpoint holds them
  PetscErrorCode RestoreCheckpoint();
  PetscErrorCode RestoreSchedule(const CheckpointHeader &header);
  PetscErrorCode RestoreFieldSeries(const CheckpointHeader &header); // the field files the checkpoint lists, and fields.xdmf

  MPI_Comm    comm_;
  PetscMPIInt rank_ = 0, size_ = 1;
  Scene       scene_; // read once in Setup, only read afterwards
  OutputPaths paths_; // every file in -output_dir (output_directory.hpp)
  Layout      layout_;

  // The body's bonds, shared by the objects below (failure changes the last two).
  Families            families_;
  BondState           bond_state_;
  nd::BondGeometry<D> geometry_; // the dimension-generic core (bond_geometry.hpp)

  ForceOperator   force_;        // u -> f (force_operator.hpp)
  Loading         loading_;      // grips, schedule, reactions (loading.hpp)
  Failure         failure_;      // breaking and its exchange (failure.hpp)
  std::vector<std::uint64_t> intact_before_; // the bond state before a breaking pass (ReleasedEnergy)
  EnergyBudget    budget_;       // where the grips' work goes (energy_budget.hpp)
  double          crack_axis_[6] = {0, 0, 0, 1, 0, 0}; // origin, unit direction (SetupCrackAxis)
  std::vector<double> tips_;     // every rank's crack tip (CrackExtent)
  std::vector<std::size_t> released_points_; // ReleasedEnergy's scratch (capacity n_owned)
  std::vector<double>      released_terms_;  // n_owned
  TimeStepControl step_control_;      // stable step, its re-estimate, travel limit (time_step_control.hpp)
  std::vector<ProbePoint> probes_;

  Vec X_         = nullptr; // TS state
  IS  is_position_ = nullptr, is_momentum_ = nullptr;
  TS  ts_        = nullptr;

  // Reporting: scratch sized at set-up, so a history row allocates nothing.
  std::vector<double> force_density_;   // D per owned point
  std::vector<double> per_point_;       // 2 per owned point: kinetic, internal energy
  std::vector<double> point_energy_;    // 1 per owned point
  double wall_start_ = 0;
  // history.csv and static_states.csv: their rows, their schedule, their restart.
  HistoryReport history_;
  std::vector<double> grip_terms_;  // GripDisplacements' scratch, D per point of the largest load set
  std::vector<double> grip_u_;      // D per load set
  PetscInt total_broken_ = 0;
  bool   stopped_on_error_ = false;
  bool   warned_balance_   = false; // WarnEnergyBalance said it
  // CheckLawValidity: the first of the consecutive steps past the law's limit in I1 so
  // far (-1: none), and how many it waits for before it stops the run.
  PetscInt past_limit_since_ = -1;
  double   past_limit_stretch_ = 1; // ...and the applied stretch at its first
  static constexpr PetscInt past_limit_steps = 2;
  // The latest history row, for the static-hold test.
  double              last_kinetic_ = 0, last_internal_ = 0;
  std::vector<double> last_reaction_, last_probe_u_;
  std::string stop_reason_;
  RunawayEnergyMonitor energy_monitor_; // divergence by runaway energy (divergence.hpp)
  SimulationOutput output_; // fields, checkpoints, restart
  std::vector<std::unique_ptr<RunObserver>> observers_; // SetupObservers
  CheckpointObserver *checkpoints_ = nullptr; // (in observers_) its wall clock, read in Report's reduction
  ProgressObserver   *progress_    = nullptr; // (in observers_) likewise
  int checkpoint_requests_served_ = 0; // SIGUSR1 counted so far (max over ranks): Report
  AdaptiveRelaxation<D> relaxation_;                          // its damping coefficient (relaxation.hpp)

  PetscLogStage stage_setup_ = 0, stage_partition_ = 0, stage_force_ = 0, stage_ghost_ = 0, stage_step_ = 0,
                stage_output_ = 0;
};

// The plane-sheet driver (tests and tools that build a 2D scene).
using Simulation = SimulationD<2>;

} // namespace bapd
