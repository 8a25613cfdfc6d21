#pragma once
// How bapd reports errors to a user: one clear message, a non-zero exit, no stack
// trace for mistakes in the input, and no hang when only some ranks fail.
#include <petscsys.h>

namespace bapd {

// Prints input errors (PETSC_ERR_USER and the argument/file classes) as one line
// "bapd: error: ..." once, and leaves internal errors to PETSc's traceback handler.
// An error raised on a whole communicator is printed by its first rank. One raised
// on a single process (PETSC_COMM_SELF, e.g. PETSc's parser of an option value,
// which every rank runs) is printed at once by world rank 0 and kept on the others,
// for FinishRun to print if rank 0 did not fail. A PETSc message about a malformed
// option value ("Input string abc has no numeric value") is completed with the
// option that holds the value. Push it right after PetscInitialize (collective: it
// also sets up the communicator FinishRun agrees on).
PetscErrorCode PushUserErrorHandler();

// True for the error classes that PushUserErrorHandler reports as user errors.
bool IsUserError(PetscErrorCode code);

// Call on every rank after the run, with its status, before PetscFinalize. Returns
// the exit code (1 on every rank when any rank failed, else 0). When every rank
// arrives, they agree and each returns; the message of an error only some ranks saw
// is printed once. When a rank failed and the others do not arrive within
// `wait_seconds` (they wait in a collective call for it), it prints its message and
// calls MPI_Abort, so a run never hangs on an error.
int FinishRun(PetscErrorCode status, double wait_seconds = 10.0);

} // namespace bapd
