#pragma once
// Checkpoints: one HDF5 file with everything a run needs to go on, bit for bit, on
// any number of ranks. docs/options.md,
// "Checkpoints and restart", is the user's view.
//
// File layout, format version 7, D the dimension of the body (2 or 3; every array in
// natural order, natural_order.hpp). Version 6 is version 7 without /run/energy (the
// continuation starts its energy budget from the state it reads), version 5 version 6 without the dimension
// attribute (always D = 2), version 4 version 5 without /time_step's indicator,
// version 3 version 4 without the back-off attributes of /time_step, version 2
// version 3 without text_hash and /time_step, version 1 version 2 without /relaxation;
// all are still read, as 2D checkpoints.
//   /                 attributes format = "bapd checkpoint", format_version, dimension,
//                     step, time_s, time_step_s, stretch, reason, ranks, content_hash,
//                     text_hash
//   /geometry         attributes points, bonds, dx_m, horizon_m, hash
//   /points/displacement   (points, D) m        /points/velocity (points, D) m/s
//   /points/family_size    (points) int32
//   /bonds/intact          (bonds) uint8: 1 intact, 0 broken; bond order = (point,
//                          then the natural order of its neighbours)
//   /bonds/c33             (bonds): plane-stress warm start C33 of every bond; always
//                          in 2D, absent in 3D when the run has no warm start
//   /bonds/damage          (bonds): d of every bond with -failure_softening (softening.hpp),
//                          absent otherwise (and in older files: they read as before)
//   /run/options           text: the options database (PetscOptionsGetAll)
//   /run/history           text: history.csv up to this step
//   /run/field_frames      (frames, 2): step and time of the field files so far
//   /run/static_states     text: static_states.csv up to this step
//   /run/schedule_original, /run/schedule_current (knots): the schedule's knot times
//                          as the run read them and as static holds have moved them;
//                          attributes end_time_original_s, end_time_s, static_hold_done
//   /run/energy            (2 + load sets): the energy budget's totals [J]: damping,
//                          released by broken bonds, the work of each load set
//                          (energy_budget.hpp)
//   /relaxation            only with -relaxation adaptive (relaxation.hpp): attribute
//                          records; /relaxation/displacement, /relaxation/acceleration
//                          (points, D): the latest force evaluation, which the next
//                          step's damping coefficient is computed against
//   /time_step             only while the step is re-estimated (time_step_control.hpp):
//                          attributes lambda_per_s2, stiffness_dt_s, next_estimate,
//                          by_stiffness, by_travel, shortest_dt_s, stretch, and
//                          (version 4) interval_now, stretch_increment: the back-off;
//                          /time_step/eigenvector (points, D): the power iteration's
//                          vector, which the next re-estimate starts from
// content_hash is an order-independent checksum of the arrays and of the step, time
// and schedule attributes; text_hash one of /run/options, /run/history,
// /run/static_states, /run/field_frames and reason: a damaged file is refused instead
// of silently continuing from wrong data (checkpoint_checksum.hpp). A checkpoint
// continues only in its own dimension: ReadCheckpointState<D> refuses another one.
//
// The dimension is a template parameter of what reads or writes D-vectors
// (ComputeGeometryFingerprint, WriteCheckpoint, ReadCheckpointState), instantiated for
// D = 2 and 3; the header and the options are the same for every D.
#include <petscsys.h>

#include <cstdint>
#include <string>
#include <vector>

#include "bapd/core/kernel/bond_state.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/solver/input/scene_output.hpp"
#include "bapd/solver/parallel/layout.hpp"
#include "bapd/solver/parallel/natural_order.hpp"

namespace bapd {

constexpr std::int64_t kCheckpointFormatVersion       = 7;
constexpr std::int64_t kCheckpointOldestFormatVersion = 1; // still read

// What identifies the body: a checkpoint only fits the same points and bonds.
struct GeometryFingerprint {
  std::int64_t  points = 0, bonds = 0;
  double        dx = 0, horizon = 0;
  std::uint64_t hash = 0; // of natural ids, reference positions and every family
};
// Collective; layout.dimension must be D.
template <int D>
PetscErrorCode ComputeGeometryFingerprint(MPI_Comm comm, const Layout &layout, const Families &families, double dx,
                                          double horizon, GeometryFingerprint *fingerprint);
bool SameGeometry(const GeometryFingerprint &a, const GeometryFingerprint &b);

// The small part of a checkpoint, the same on every rank after ReadCheckpointHeader.
struct CheckpointHeader {
  std::int64_t        format_version = kCheckpointFormatVersion;
  std::int64_t        dimension = 2;  // D of the body (version 6; 2 in older files)
  bool                has_c33   = true; // the file has /bonds/c33 (always in 2D)
  bool                has_damage = false; // the file has /bonds/damage (a run with -failure_softening)
  PetscInt            step = 0;
  double              time = 0, time_step = 0, stretch = 1;
  std::string         reason; // "interval", "interrupted", "last good state", "end"
  std::int64_t        ranks = 1;
  std::uint64_t       content_hash = 0;
  GeometryFingerprint geometry;
  std::string         options, history, static_states;
  std::vector<double> field_frames; // step, time pairs
  // Where the load schedule stands: static holds that end early move the later
  // knots and the end time (Loading::EndHold, loading.hpp).
  std::vector<double> schedule_original, schedule_current;
  double              end_time_original = 0, end_time = 0;
  std::int64_t        static_hold_done  = -1;
  // The energy budget's totals (EnergyBudget::totals; version 7, empty in older files).
  std::vector<double> energy_totals;
  // -relaxation adaptive: force evaluations recorded (0: no /relaxation group).
  std::int64_t        relaxation_records = 0;
  // The re-estimated stable step (TimeStepState, time_step_control.hpp); step_lambda 0:
  // no /time_step group (format 1 and 2, or -time_step_reestimate 0).
  double              step_lambda = 0, step_stiffness_dt = 0, step_shortest = 0, step_stretch = 1;
  std::int64_t        step_next_estimate = 0, step_by_stiffness = 0, step_by_travel = 0;
  // Its back-off (version 4; 0 in older files: the continuation starts it again).
  std::int64_t        step_interval_now = 0;
  double              step_stretch_increment = 0;
  // The stiffening indicator at the last search (version 5; 0 in older files: the
  // continuation's next estimate searches, as at the start).
  double              step_indicator = 0;
};

// The state of the rank layout, read from (written to) a checkpoint; D-vectors hold
// D numbers a point.
struct CheckpointState {
  double          *u = nullptr, *v = nullptr; // owned points, D each
  BondState       *bonds = nullptr;           // family points (write: owned ones used)
  // Bonds of family points. nullptr: the run has no C33 warm start (a 3D model; write:
  // the file gets no /bonds/c33, which only a 3D checkpoint may lack).
  double          *c33 = nullptr;
  // -relaxation adaptive: the latest recorded evaluation, owned points, D each
  // (write: used when header.relaxation_records > 0; read: filled when the file has it).
  double          *relaxation_u = nullptr, *relaxation_a = nullptr;
  // The power iteration's vector, owned points, D each (write: used when
  // header.step_lambda > 0; read: filled when the file has it).
  double          *step_eigenvector = nullptr;
};

// Collective. Writes `path` through `path.tmp` and a rename, so the last good
// checkpoint survives a crash while writing. header.content_hash, dimension and
// has_c33 are filled in.
template <int D>
PetscErrorCode WriteCheckpoint(MPI_Comm comm, const std::string &path, const NaturalOrder &order, const Families &families,
                               CheckpointHeader *header, const CheckpointState &state);

// Collective. Checks that `path` is a readable bapd checkpoint of a version this
// program reads and returns its header on every rank; refuses anything else with one
// message (PETSC_ERR_FILE_OPEN / PETSC_ERR_FILE_UNEXPECTED).
PetscErrorCode ReadCheckpointHeader(MPI_Comm comm, const std::string &path, CheckpointHeader *header);

// Collective. Reads the state into the rank layout after checking the dimension and
// the geometry (PETSC_ERR_USER if the file's differs from D or from `geometry`) and
// the checksum. A file without /bonds/c33 (3D) leaves state.c33 at 0, the cold start.
template <int D>
PetscErrorCode ReadCheckpointState(MPI_Comm comm, const std::string &path, const NaturalOrder &order,
                                   const Families &families, const CheckpointHeader &header,
                                   const GeometryFingerprint &geometry, const CheckpointState &state);

// -restart FILE, before the scene is read: the options stored in the checkpoint
// become the defaults, so `bapd -restart FILE` alone continues the run; every option
// given on the command line still wins. Collective; does nothing without -restart.
PetscErrorCode CheckpointMergeOptions(MPI_Comm comm);

// Signals. SIGTERM / SIGINT / SIGQUIT / SIGHUP / SIGUSR2: write a checkpoint and stop;
// SIGUSR1: write a checkpoint and go on. Open MPI's mpiexec passes SIGUSR1 and SIGUSR2 on to the
// ranks at once; SIGINT it passes on as SIGTERM, and after SIGTERM it kills the ranks
// 1 s later. So run_mpi.sh turns the SIGINT / SIGTERM it gets into SIGUSR2 and names
// the real signal in the file $BAPD_SIGNAL_FILE (InterruptName). The handlers only
// record the signal; the driver asks, once per step and collectively, whether any
// rank got one (SimulationD::Report, simulation_report.cpp). A second SIGTERM / SIGINT / SIGUSR2
// 2 s or more after the first, while it is pending, ends the process the default way
// (one sooner is the same request arriving twice, e.g. through `timeout`). SIGXFSZ is ignored:
// a file past a size limit (ulimit -f) is then a write error that bapd reports.
// A stop the driver has not taken 10 s after the signal (it came during the set-up,
// or inside a step that lasts) ends the process there, with one line saying so and
// what is kept (SIGALRM).
void InstallInterruptHandlers();
void RestoreInterruptHandlers();
// SIGSEGV, SIGBUS, SIGILL, SIGFPE (in place of PETSc's handler and its stack): one
// line `bapd: error: rank R stopped by SIGSEGV ...`, telling a fault from a signal
// sent with kill, and an exit without MPI_Finalize, so that mpiexec stops the other
// ranks. Installed by PushUserErrorHandler (errors.hpp).
void InstallFatalSignalHandlers();
int  PendingInterrupt();      // the stop signal if one came, else 0 (a step has ended: asked once a step)
// How many SIGUSR1 this rank has had. mpiexec passes one SIGUSR1 on to every rank, but
// the ranks may see it at different steps: the driver reduces the count (max over ranks)
// and writes a checkpoint when it grows, so one signal makes one checkpoint.
int CheckpointRequestsReceived();
// "SIGINT", "SIGTERM", or for SIGUSR2 the signal run_mpi.sh got ("SIGUSR2" if none).
std::string InterruptName(int signal);

} // namespace bapd
