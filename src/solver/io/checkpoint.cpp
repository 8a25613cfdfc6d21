// Checkpoints: their options, and a restart's options taken from the checkpoint
// (checkpoint.hpp; writing in checkpoint_write.cpp, reading in checkpoint_read.cpp,
// checksums in checkpoint_checksum.cpp).
#include "bapd/solver/io/checkpoint.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "bapd/solver/input/scene.hpp"

namespace bapd {

namespace {

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

} // namespace

PetscErrorCode CheckpointOptionsFromOptions(MPI_Comm comm, CheckpointOptions *options)
{
  char      interval[128] = "", restart[PETSC_MAX_PATH_LEN] = "";
  PetscBool has_interval = PETSC_FALSE, has_restart = PETSC_FALSE;

  PetscFunctionBegin;
  for (const char *name : {"-checkpoint_interval", "-checkpoint_on_error", "-restart", "-restart_discard_newer"}) RegisterOptionName(name);
  PetscOptionsBegin(comm, nullptr, "Checkpoints and restart", "bapd");
  PetscCall(PetscOptionsString("-checkpoint_interval",
                               "Between checkpoints (<output_dir>/checkpoint.h5, also written at the end): steps (1000) or wall-clock "
                               "time (600s, 10min, 2h); absent: only on a signal (SIGTERM, SIGINT, SIGUSR1) or an error",
                               "docs/options.md", "", interval, sizeof interval, &has_interval));
  PetscCall(PetscOptionsBool("-checkpoint_on_error", "On divergence, write the last good state as a checkpoint (keeps a copy of the state every step)",
                             "docs/options.md", options->on_error, &options->on_error, nullptr));
  PetscCall(PetscOptionsString("-restart", "Continue from this checkpoint file (its options are the defaults)", "docs/options.md", "", restart,
                               sizeof restart, &has_restart));
  PetscCall(PetscOptionsBool("-restart_discard_newer",
                             "With -restart: drop what the output directory holds after the checkpoint (history rows, a later "
                             "checkpoint.h5, field files) instead of refusing to replace it",
                             "docs/options.md", options->discard_newer, &options->discard_newer, nullptr));
  PetscOptionsEnd();
  const bool ok = ParseInterval(interval, &options->step_interval, &options->wall_interval);
  PetscCheck(ok, comm, PETSC_ERR_USER,
             "-checkpoint_interval %s: give a number of steps (e.g. 1000) or a wall-clock time with a unit (600s, 10min or 2h)", interval);
  PetscCheck(!has_restart || restart[0], comm, PETSC_ERR_USER, "-restart needs the checkpoint file to continue from (e.g. -restart output/checkpoint.h5)");
  options->restart = has_restart ? restart : "";
  PetscFunctionReturn(0);
}

PetscErrorCode CheckpointMergeOptions(MPI_Comm comm)
{
  char      path[PETSC_MAX_PATH_LEN] = "";
  PetscBool has                      = PETSC_FALSE;

  PetscFunctionBegin;
  RegisterOptionName("-restart");
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-restart", path, sizeof path, &has));
  if (!has) PetscFunctionReturn(0);
  PetscCheck(path[0], comm, PETSC_ERR_USER, "-restart needs the checkpoint file to continue from (e.g. -restart output/checkpoint.h5)");
  CheckpointHeader header;
  PetscCall(ReadCheckpointHeader(comm, path, &header));
  // A scene of the other dimension would meet the stored options first (a 2D sheet's
  // -body_width in a 3D body) and be refused for them: name the dimension instead.
  // (Read as text: a value that is no number is the scene reader's to report.)
  char      given_dimension[32] = "";
  PetscBool has_dimension       = PETSC_FALSE;
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-body_dimension", given_dimension, sizeof given_dimension, &has_dimension));
  const long dimension = has_dimension && (!std::strcmp(given_dimension, "2") || !std::strcmp(given_dimension, "3"))
                           ? std::strtol(given_dimension, nullptr, 10)
                           : (long)header.dimension;
  PetscCheck(dimension == header.dimension, comm, PETSC_ERR_USER,
             "Checkpoint '%s' holds a %lldD body and this scene is %dD (-body_dimension %d): a run continues only in the dimension "
             "that wrote it. Restart with the scene that wrote it: its options are stored in the checkpoint and apply unless the "
             "command line overrides them",
             path, (long long)header.dimension, (int)dimension, (int)dimension);
  // The stored database, parsed by PETSc itself; each of its options that the
  // command line does not set is added.
  PetscOptions stored;
  PetscInt     n      = 0;
  char       **names  = nullptr;
  char       **values = nullptr;
  PetscCall(PetscOptionsCreate(&stored));
  PetscCall(PetscOptionsInsertString(stored, header.options.c_str()));
  PetscCall(PetscOptionsLeftGet(stored, &n, &names, &values));
  for (PetscInt k = 0; k < n; ++k) {
    const std::string name = std::string("-") + names[k];
    if (name == "-restart" || name == "-restart_discard_newer") continue; // (this run's own choice, never inherited)
    PetscBool given = PETSC_FALSE;
    PetscCall(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &given));
    if (!given) PetscCall(PetscOptionsSetValue(nullptr, name.c_str(), values[k]));
  }
  PetscCall(PetscOptionsLeftRestore(stored, &n, &names, &values));
  PetscCall(PetscOptionsDestroy(&stored));
  PetscFunctionReturn(0);
}

} // namespace bapd
