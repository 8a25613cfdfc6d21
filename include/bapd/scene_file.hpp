#pragma once
// Checks a scene file before PETSc reads it, so that a missing file or a YAML
// syntax error gets one clear message (with line and column) instead of a PETSc
// error stack from inside PetscInitialize.
#include <string>

namespace bapd {

// Looks for "-options_file_yaml FILE" in argv and checks FILE: readable, valid YAML,
// only mappings, scalars and sequences of scalars (what PETSc's reader takes).
// Returns an empty string when all is well, else the message to print.
std::string CheckSceneFileArgument(int argc, char **argv);

} // namespace bapd
