// The output section: where the output goes (-output_dir), the history rows
// (-output_interval, -output_history_rows), the final state, the field files
// (-output_fields*) and checkpoints (-checkpoint_*, -restart*). Each block is one option
// table. Rank 0 checks that the output directory can be written before any work is done.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"
#include "bapd/solver/io/output_directory.hpp"

namespace bapd {

namespace {

const OptionTable<OutputSection> kOutputOptions = {
    {"-output_dir", "Directory for history and fields", &OutputSection::dir},
    {"-output_interval", "Time steps between history rows [-], >= 1; the static test (-static_tolerance) runs at these rows",
     &OutputSection::interval},
    {"-output_history_rows",
     "History rows by load [-]: also a row at the first step at or past each end time / N of simulated time, so that "
     "a run has at least N rows whatever its step (0: only the -output_interval rows)",
     &OutputSection::history_rows},
    {"-output_final_state", "Also write final_state.csv (every point's displacement) and broken_bonds.csv at the end",
     &OutputSection::final_state},
};

// Field files (fields.hpp): whether and how often; where the XDMF draws the points is
// a choice, kept as given for the check (SceneInput::field_geometry).
const OptionTable<FieldOptions> kFieldFileOptions = {
    {"-output_fields", "Write the point fields (<output_dir>/fields/*.h5 and fields.xdmf)", &FieldOptions::enabled},
    {"-output_fields_interval", "Time steps between field files [-]; 0: every end time / 20 of simulated time", &FieldOptions::interval},
};

const OptionTable<SceneInput> kFieldGeometryOptions = {
    {"-output_fields_geometry", "Where fields.xdmf draws the points: current (deformed) or reference positions",
     &SceneInput::field_geometry},
};

// Checkpoints and restart (checkpoint.hpp); whether -restart was given in the SceneInput.
const OptionTable<CheckpointOptions, SceneInput> kCheckpointOptionRows = {
    {"-checkpoint_interval",
     "Between checkpoints (<output_dir>/checkpoint.h5, also written at the end): steps (1000) or wall-clock "
     "time (600s, 10min, 2h); absent: only on a signal (SIGTERM, SIGINT, SIGUSR1) or an error",
     &CheckpointOptions::interval},
    {"-checkpoint_on_error", "On divergence, write the last good state as a checkpoint (keeps a copy of the state every step)",
     &CheckpointOptions::on_error},
    {"-restart", "Continue from this checkpoint file (its options are the defaults)", &CheckpointOptions::restart, &SceneInput::restart_set},
    {"-restart_discard_newer",
     "With -restart: drop what the output directory holds after the checkpoint (history rows, a later "
     "checkpoint.h5, field files) instead of refusing to replace it",
     &CheckpointOptions::discard_newer},
};

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

// "600s", "10min", "2h" -> seconds; "1000" -> steps. False if neither.
bool ParseInterval(const std::string &text, PetscInt *steps, double *seconds)
{
  *steps   = 0;
  *seconds = 0;
  if (text.empty()) return true;
  char        *end   = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !(value >= 0) || !std::isfinite(value)) return false;
  std::string unit(end);
  unit.erase(std::remove_if(unit.begin(), unit.end(), [](unsigned char c) { return std::isspace(c); }), unit.end());
  if (unit.empty()) {
    if (value != std::floor(value) || value > 1e15) return false;
    *steps = (PetscInt)value;
    return true;
  }
  if (unit == "s") *seconds = value;
  else if (unit == "min") *seconds = 60 * value;
  else if (unit == "h") *seconds = 3600 * value;
  else return false;
  return true;
}


PetscErrorCode CheckFields(MPI_Comm comm, const SceneInput &in, FieldOptions *fields)
{
  PetscFunctionBeginUser;
  SceneCheck(fields->interval >= 0, comm, "-output_fields_interval %" PetscInt_FMT ": give a number of steps >= 1 (or 0 for about 20 files a run)",
             fields->interval);
  const std::string geometry = Lower(in.field_geometry);
  SceneCheck(geometry == "current" || geometry == "reference", comm,
             "-output_fields_geometry '%s' is not a geometry: choose current (the deformed positions) or reference (the undeformed "
             "ones; warp by displacement in ParaView to see the deformation)",
             in.field_geometry.c_str());
  fields->geometry = geometry == "reference" ? FieldGeometry::reference : FieldGeometry::current;
  PetscFunctionReturn(0);
}

PetscErrorCode CheckCheckpoints(MPI_Comm comm, const SceneInput &in, CheckpointOptions *checkpoint)
{
  PetscFunctionBeginUser;
  SceneCheck(ParseInterval(checkpoint->interval, &checkpoint->step_interval, &checkpoint->wall_interval), comm,
             "-checkpoint_interval %s: give a number of steps (e.g. 1000) or a wall-clock time with a unit (600s, 10min or 2h)",
             checkpoint->interval.c_str());
  SceneCheck(!in.restart_set || !checkpoint->restart.empty(), comm,
             "-restart needs the checkpoint file to continue from (e.g. -restart output/checkpoint.h5)");
  PetscFunctionReturn(0);
}

} // namespace

std::string OutputText(const OutputSection &o)
{
  std::string text = Format("  output    %s/, history every %ld steps", o.dir.c_str(), (long)o.interval);
  if (o.history_rows > 0) text += Format(" and at each 1/%ld of the end time", (long)o.history_rows);
  return text + "\n";
}

PetscErrorCode ReadOutput(MPI_Comm comm, OutputSection *output, SceneInput *in)
{
  PetscFunctionBeginUser;
  PetscCall(ReadOptionTable(comm, "Output", kOutputOptions, output));
  PetscCall(ReadOptionBlock(comm, nullptr, "Field output (HDF5 + XDMF for ParaView)", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(ReadOptionRows(r, kFieldFileOptions, &output->fields));
    return ReadOptionRows(r, kFieldGeometryOptions, in);
  }));
  PetscCall(ReadOptionTable(comm, "Checkpoints and restart", kCheckpointOptionRows, &output->checkpoint, in));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckOutput(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  PetscFunctionBeginUser;
  SceneCheck(!scene->output.dir.empty(), comm, "-output_dir is empty: give a directory, e.g. -output_dir output");
  {
    // Rank 0 writes the output: it checks, every rank hears its verdict.
    PetscMPIInt rank;
    std::string problem;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (rank == 0) problem = OutputDirProblem(scene->output.dir);
    int length = static_cast<int>(problem.size());
    PetscCallMPI(MPI_Bcast(&length, 1, MPI_INT, 0, comm));
    problem.resize(static_cast<std::size_t>(length));
    PetscCallMPI(MPI_Bcast(problem.data(), length, MPI_CHAR, 0, comm));
    SceneCheck(problem.empty(), comm, "-output_dir %s cannot be created or written: %s; choose a writable directory, e.g. -output_dir output",
               ShortenedPath(scene->output.dir).c_str(), problem.c_str());
  }
  SceneCheck(scene->output.interval >= 1, comm,
             "-output_interval %" PetscInt_FMT ": history rows are written every N >= 1 time steps (default 100)", scene->output.interval);
  SceneCheck(scene->output.history_rows >= 0, comm,
             "-output_history_rows %" PetscInt_FMT ": give the number of history rows over the end time, N >= 1 (default 100), or 0 "
             "for the -output_interval rows only",
             scene->output.history_rows);
  PetscCall(CheckFields(comm, in, &scene->output.fields));
  PetscCall(CheckCheckpoints(comm, in, &scene->output.checkpoint));
  PetscFunctionReturn(0);
}

} // namespace bapd
