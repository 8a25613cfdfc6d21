// A program that fails on purpose, for local_error.sh: how bapd's error handling ends
// a run (src/solver/driver/errors.cpp) when one rank fails alone while the others wait for it
// in a collective call (without FinishRun: a hang), and when every rank fails with
// the same rank-local error (the message must appear once, not once per rank).
//
//   mpiexec -n 2 input_local_error -mode alone|all
#include <petscsys.h>

#include <cstring>

#include "bapd/solver/driver/errors.hpp"

static PetscErrorCode Fail(const char *mode)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  if (std::strcmp(mode, "all") == 0 || rank == 1)
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_USER, "-mode %s: a rank-local input error (rank-independent text)", mode);
  PetscCallMPI(MPI_Barrier(PETSC_COMM_WORLD)); // rank 1 never comes
  PetscFunctionReturn(0);
}

int main(int argc, char **argv)
{
  char mode[16] = "alone";
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscCall(bapd::PushUserErrorHandler());
  PetscCall(PetscOptionsGetString(nullptr, nullptr, "-mode", mode, sizeof mode, nullptr));
  const PetscErrorCode status    = Fail(mode);
  const int            exit_code = bapd::FinishRun(status, 2.0);
  PetscCall(PetscFinalize());
  return exit_code;
}
