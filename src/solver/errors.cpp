#include "bapd/errors.hpp"

#include <cstdio>

namespace bapd {

namespace {

PetscErrorCode UserErrorHandler(MPI_Comm comm, int line, const char *func, const char *file, PetscErrorCode n,
                                PetscErrorType p, const char *mess, void *ctx)
{
  if (!IsUserError(n)) return PetscTraceBackErrorHandler(comm, line, func, file, n, p, mess, ctx);
  if (p != PETSC_ERROR_INITIAL) return n; // only the first report carries the message
  int rank = 0, initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized && comm != MPI_COMM_NULL) MPI_Comm_rank(comm, &rank);
  if (rank == 0) {
    std::fprintf(stderr, "bapd: error: %s\n", mess ? mess : "(no message)");
    std::fflush(stderr);
  }
  return n;
}

} // namespace

bool IsUserError(PetscErrorCode code)
{
  switch (code) {
  case PETSC_ERR_USER:
  case PETSC_ERR_USER_INPUT:
  case PETSC_ERR_ARG_WRONG:
  case PETSC_ERR_ARG_OUTOFRANGE:
  case PETSC_ERR_ARG_INCOMP:
  case PETSC_ERR_ARG_UNKNOWN_TYPE:
  case PETSC_ERR_ARG_BADPTR:
  case PETSC_ERR_FILE_OPEN:
  case PETSC_ERR_FILE_READ:
  case PETSC_ERR_FILE_WRITE:
  case PETSC_ERR_FILE_UNEXPECTED:
  case PETSC_ERR_NOT_CONVERGED:
  case PETSC_ERR_FP:
    return true;
  default:
    return false;
  }
}

PetscErrorCode PushUserErrorHandler()
{
  PetscFunctionBegin;
  PetscCall(PetscPushErrorHandler(UserErrorHandler, nullptr));
  PetscFunctionReturn(0);
}

} // namespace bapd
