// Checkpoints: a restart's options taken from the checkpoint (their own options are
// the scene's output section, scene_output.cpp; checkpoint.hpp; writing in
// checkpoint_write.cpp, reading in checkpoint_read.cpp,
// checksums in checkpoint_checksum.cpp).
#include "bapd/solver/io/checkpoint.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "bapd/solver/input/scene.hpp"

namespace bapd {

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
