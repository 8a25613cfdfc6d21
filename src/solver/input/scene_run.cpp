// The run section: where the output goes and how the time steps (-output_*,
// -time_step, -time_step_safety, -time_step_travel, -damping, -static_tolerance,
// -end_time, -progress_interval). Rank 0 checks that the output directory can be
// written before any work is done.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/io/output_directory.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

namespace {

// Why rank 0 could not create files in `dir`, or "": the nearest existing ancestor
// (dir itself when it exists) must be a directory this process may write into.
// Nothing is created here; the history file is opened after the setup.
std::string OutputDirProblem(const std::string &dir)
{
  std::filesystem::path path = dir;
  if (struct stat info; ::stat(path.c_str(), &info) != 0 && errno == ENAMETOOLONG)
    return Format("its path is %zu characters, more than the system allows (%s)", dir.size(), std::strerror(ENAMETOOLONG));
  while (true) {
    struct stat info;
    if (::stat(path.c_str(), &info) == 0) {
      if (!S_ISDIR(info.st_mode)) return "'" + ShortenedPath(path.string()) + "' is a file, not a directory";
      if (::access(path.c_str(), W_OK | X_OK) != 0)
        return "'" + ShortenedPath(path.string()) + "' is not writable (" + std::strerror(errno) + ")";
      return "";
    }
    if (!path.has_relative_path() || path.parent_path() == path) return "";
    path = path.parent_path();
    if (path.empty()) path = ".";
  }
}

// Refuses an end time whose time steps no run can count (PetscInt) or finish. The
// step is not known before the body is built (power iteration, docs/method.md section 5),
// so the count is bounded from below with a generous upper bound on the step: the
// stable step of the explicit scheme is about dx over the fastest wave speed, and the
// shear wave speed sqrt(mu / rho) is the slowest (measured: 1.1 dx / sqrt(mu / rho)
// on the tiny test scene); three times that bounds it.
PetscErrorCode CheckStepCount(MPI_Comm comm, const Scene &scene, bool end_time_set)
{
  PetscFunctionBeginUser;
  const double      max_steps  = static_cast<double>(std::numeric_limits<PetscInt>::max());
  const double      shear_wave = std::sqrt(scene.material.mu / scene.density);
  const bool        given      = scene.time_step > 0;
  const double      step_bound = given ? scene.time_step : 3.0 * scene.time_step_safety * scene.body.dx / shear_wave;
  const double      steps      = scene.end_time / step_bound;
  const std::string how        = given ? Format("-time_step %g s", scene.time_step)
                                       : Format("the step, at most about %g s here (3 x %g x dx / sqrt(mu / rho))", step_bound,
                                                scene.time_step_safety);
  const double      longest    = max_steps * step_bound;
  const std::string head       = end_time_set ? Format("-end_time %g s", scene.end_time)
                                              : Format("-load_schedule ends at %g s, which", scene.end_time);
  SceneCheck(steps <= max_steps, comm,
             "%s needs %s%.3g time steps with %s, more than a run can count (%.0f): end the run by %.3g s, e.g. -end_time %g",
             head.c_str(), given ? "" : "at least ", steps, how.c_str(), max_steps, longest, std::min(1.0, 0.5 * longest));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ReadOutputTime(MPI_Comm comm, Scene *scene, SceneInput *in)
{
  PetscFunctionBeginUser;
  PetscCall(ReadOptionBlock(comm, nullptr, "Output", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(r.String("-output_dir", "Directory for history and fields", &scene->output_dir));
    PetscCall(r.Int("-output_interval", "Time steps between history rows [-], >= 1; the static test (-static_tolerance) runs at these rows",
                    &scene->output_interval));
    PetscCall(r.Int("-output_history_rows",
                    "History rows by load [-]: also a row at the first step at or past each end time / N of simulated time, so that "
                    "a run has at least N rows whatever its step (0: only the -output_interval rows)",
                    &scene->output_history_rows));
    PetscCall(r.Bool("-output_final_state", "Also write final_state.csv (every point's displacement) and broken_bonds.csv at the end",
                     &scene->output_final_state));
    return 0;
  }));

  PetscCall(ReadOptionBlock(comm, nullptr, "Solver", [&](OptionReader &r) -> PetscErrorCode {
    std::string solver = "dynamic";
    PetscCall(r.String("-solver", "How the run reaches its states: dynamic (explicit dynamics, PETSc TS) or static (static states by Newton, "
                                  "PETSc SNES, load steps along -load_schedule)",
                       &solver));
    SceneCheck(solver == "dynamic" || solver == "static", comm,
               "-solver '%s' is not a solver: choose dynamic (explicit dynamics, the default) or static (static states by Newton)",
               solver.c_str());
    scene->solver = solver == "static" ? SolverKind::static_newton : SolverKind::dynamic;
    std::string partition = "metis";
    PetscCall(r.String("-partition_type",
                       "Who splits the body over the ranks: metis (rank 0 builds the whole body and bond graph, METIS splits it) or "
                       "ptscotch (PT-Scotch on every rank; a lattice body is built in slabs, one a rank, and no rank holds it whole; "
                       "given points and -force_patch_correction are still built on rank 0)",
                       &partition));
    SceneCheck(partition == "metis" || partition == "ptscotch", comm,
               "-partition_type '%s' is not a partitioner: choose metis (the default) or ptscotch (in parallel)", partition.c_str());
    scene->partition_type = partition == "ptscotch" ? PartitionType::ptscotch : PartitionType::metis;
    PetscCall(r.Bool("-log_setup_memory",
                     "Print the set-up's wall time and peak memory (VmHWM) of the largest rank, the mean rank and rank 0 once the "
                     "body is distributed",
                     &scene->log_setup_memory));
    StaticOptions &s = scene->static_options;
    PetscCall(r.Real("-static_stretch_step", "Static solver: the first load step [stretch], > 0", &s.stretch_step));
    PetscCall(r.Real("-static_stretch_step_max", "Static solver: the largest load step [stretch], > 0", &s.stretch_step_max));
    PetscCall(r.Real("-static_stretch_step_min",
                     "Static solver: a load step cut back below this ends the run with an error [stretch], > 0", &s.stretch_step_min));
    PetscCall(r.Real("-static_step_growth", "Static solver: the load step grows by this factor after a fast step [-], >= 1", &s.growth));
    PetscCall(r.Int("-static_fast_iterations", "Static solver: a load step that converged in at most this many Newton iterations is fast [-]",
                    &s.fast_iterations));
    PetscCall(r.Bool("-static_secant_predictor",
                     "Static solver: predict a load step by the secant through the last two states (no solve); false: one tangent "
                     "solve with the grips' increment every step",
                     &s.secant_predictor));
    PetscCall(r.Real("-static_residual_tolerance",
                     "Static solver: Newton ends once the free points' force norm is this fraction of the grips' reaction norm [-], > 0",
                     &s.residual_tolerance));
    return 0;
  }));

  PetscCall(ReadOptionBlock(comm, nullptr, "Time stepping (explicit dynamics)", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(r.Real("-time_step", "Time step [s]; 0: time_step_safety x the estimated stable step", &scene->time_step));
    PetscCall(r.Real("-time_step_safety", "Fraction of the estimated stable step [-], in (0, 1]", &scene->time_step_safety));
    PetscCall(r.Real("-time_step_travel", "Largest distance a point with bonds may move in one step [dx]; the step shrinks while points move fast (snapping bonds), 0: never, -1 (default): 0.1 with failure, off without", &scene->time_step_travel));
    PetscCall(r.Real("-damping", "Mass-proportional damping coefficient [1/s], >= 0", &scene->damping));
    PetscCall(r.Real("-static_tolerance", "A hold of the load schedule ends once kinetic/internal energy < this [-] (0: holds run their full length)", &scene->static_tolerance));
    PetscCall(r.Real("-end_time", "End of the run [s] (default: the schedule's last time)", &scene->end_time, &in->end_time_set));
    PetscCall(r.Int("-end_step",
                    "Stop after this time step [-] (a step number: a restart goes on counting), before -end_time, on purpose: a run in "
                    "parts, a test, a benchmark (-1: run to -end_time)",
                    &scene->end_step));
    PetscCall(r.Int("-progress_interval", "Time steps between progress lines [-] (0: every end time / 20 of simulated time)", &scene->progress_interval));
    PetscCall(r.Real("-progress_wall_interval", "Also a progress line once this much wall time has passed since the last one [s] (0: off)",
                     &scene->progress_wall_interval));
    return 0;
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckOutputTime(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  PetscFunctionBeginUser;
  SceneCheck(!scene->output_dir.empty(), comm, "-output_dir is empty: give a directory, e.g. -output_dir output");
  {
    // Rank 0 writes the output: it checks, every rank hears its verdict.
    PetscMPIInt rank;
    std::string problem;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (rank == 0) problem = OutputDirProblem(scene->output_dir);
    int length = static_cast<int>(problem.size());
    PetscCallMPI(MPI_Bcast(&length, 1, MPI_INT, 0, comm));
    problem.resize(static_cast<std::size_t>(length));
    PetscCallMPI(MPI_Bcast(problem.data(), length, MPI_CHAR, 0, comm));
    SceneCheck(problem.empty(), comm, "-output_dir %s cannot be created or written: %s; choose a writable directory, e.g. -output_dir output",
               ShortenedPath(scene->output_dir).c_str(), problem.c_str());
  }
  SceneCheck(scene->output_interval >= 1, comm,
             "-output_interval %" PetscInt_FMT ": history rows are written every N >= 1 time steps (default 100)", scene->output_interval);
  SceneCheck(scene->output_history_rows >= 0, comm,
             "-output_history_rows %" PetscInt_FMT ": give the number of history rows over the end time, N >= 1 (default 100), or 0 "
             "for the -output_interval rows only",
             scene->output_history_rows);

  SceneCheck(scene->time_step >= 0, comm,
             "-time_step %g: the time step must be > 0 s, or 0 for the automatic choice (safety x stable step)", scene->time_step);
  SceneCheck(scene->time_step_safety > 0, comm,
             "-time_step_safety %g must be > 0: it is the fraction of the estimated stable step that is taken (default 0.8)",
             scene->time_step_safety);
  if (scene->time_step_safety > 1)
    PetscCall(Warn(comm,
                   Format("-time_step_safety %g is above 1: the time step exceeds the estimated stable step and the explicit scheme "
                          "may blow up; use a value in (0, 1] (default 0.8)",
                          scene->time_step_safety),
                   true));
  SceneCheck(scene->time_step_travel >= 0 || scene->time_step_travel == -1, comm,
             "-time_step_travel %g must be >= 0: it is the largest distance, in dx, that a point with bonds may move in one step (0: off; -1, the default: 0.1 with failure, off without)",
             scene->time_step_travel);
  {
    const StaticOptions &s = scene->static_options;
    SceneCheck(s.stretch_step > 0 && s.stretch_step_max > 0 && s.stretch_step_min > 0 && s.stretch_step_min <= s.stretch_step &&
                   s.stretch_step <= s.stretch_step_max,
               comm,
               "-static_stretch_step %g, -static_stretch_step_min %g, -static_stretch_step_max %g: give 0 < min <= step <= max "
               "(defaults 1e-4, 0.25, 1)",
               s.stretch_step, s.stretch_step_min, s.stretch_step_max);
    SceneCheck(s.growth >= 1, comm, "-static_step_growth %g: give a factor >= 1 (1: the load step never grows; default 1.5)", s.growth);
    SceneCheck(s.fast_iterations >= 0, comm, "-static_fast_iterations %" PetscInt_FMT ": give N >= 0 (default 4)", s.fast_iterations);
    SceneCheck(s.residual_tolerance > 0 && s.residual_tolerance < 1, comm,
               "-static_residual_tolerance %g: give a small positive fraction such as 1e-10", s.residual_tolerance);
  }
  SceneCheck(scene->damping >= 0, comm, "-damping %g: the damping coefficient must be >= 0 1/s (0: undamped)", scene->damping);
  SceneCheck(scene->static_tolerance >= 0 && scene->static_tolerance < 1, comm,
             "-static_tolerance %g: use a small positive ratio such as 1e-6 (0: holds run their full length)", scene->static_tolerance);
  SceneCheck(scene->progress_interval >= 0, comm,
             "-progress_interval %" PetscInt_FMT ": give N >= 1 time steps between progress lines, or 0 for about 20 lines a run",
             scene->progress_interval);
  SceneCheck(scene->progress_wall_interval >= 0, comm,
             "-progress_wall_interval %g: give the wall time between progress lines in seconds, > 0 (default 10), or 0 for lines by "
             "simulated time (or -progress_interval) only",
             scene->progress_wall_interval);
  SceneCheck(scene->end_step >= -1, comm,
             "-end_step %" PetscInt_FMT ": give the step number after which the run stops (>= 0), or -1 to run to -end_time",
             scene->end_step);
  const double schedule_end = scene->schedule.end_time();
  if (in.end_time_set) {
    SceneCheck(scene->end_time > 0, comm, "-end_time %g: the run must end after t = 0 s", scene->end_time);
    if (scene->end_time < schedule_end)
      PetscCall(Warn(comm, Format("-end_time %g s stops the run before the end of -load_schedule (%g s)", scene->end_time, schedule_end)));
  } else {
    SceneCheck(schedule_end > 0, comm,
               "-end_time is required when -load_schedule does not end after t = 0: give the run's end in s, e.g. -end_time 1%s",
               (MisspeltHint("-end_time") + MisspeltHint("-load_schedule")).c_str());
    scene->end_time = schedule_end;
  }
  PetscCall(CheckStepCount(comm, *scene, in.end_time_set));
  PetscFunctionReturn(0);
}

} // namespace bapd
