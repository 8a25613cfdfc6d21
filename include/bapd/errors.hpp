#pragma once
// How bapd reports errors to a user: one clear message, a non-zero exit, no stack
// trace for mistakes in the input (STYLE.md, "Errors and output").
#include <petscsys.h>

namespace bapd {

// Prints input errors (PETSC_ERR_USER and the argument/file classes) as one line
// "bapd: error: ..." on the first rank of the failing communicator, and leaves
// internal errors to PETSc's traceback handler. Push it right after PetscInitialize.
PetscErrorCode PushUserErrorHandler();

// True for the error classes that PushUserErrorHandler reports as user errors.
bool IsUserError(PetscErrorCode code);

} // namespace bapd
