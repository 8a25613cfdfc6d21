#pragma once
// Checks the command line and the scene file before PETSc reads them, so that a
// missing file, a YAML syntax error or a stray word gets one clear message (with
// line and column) instead of a PETSc error stack from inside PetscInitialize, or
// nothing at all.
#include <string>

namespace bapd {

// Looks for "-options_file_yaml FILE" in argv and checks FILE: readable, valid YAML,
// only mappings, scalars and sequences of scalars (what PETSc's reader takes). A
// plain "-options_file FILE" must be readable. Returns an empty string when all is
// well, else the message to print.
std::string CheckSceneFileArgument(int argc, char **argv);

// The whole command line: every word is an option name or the one value after it
// (PETSc ignores any other word), then CheckSceneFileArgument. "" or the message.
std::string CheckArguments(int argc, char **argv);

} // namespace bapd
