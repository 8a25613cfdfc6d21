#pragma once
// Global sums that give the same bits on any number of ranks.
//
// A floating-point sum depends on the order of its terms, and the order depends on
// the rank layout. Anything that feeds back into the dynamics (a stable time step, a
// damping coefficient) or is compared across layouts must not. Each term is rounded
// once onto a fixed-point grid 2^-100 below the largest term (the same grid on every
// rank, from an exact MPI max), and the integers are summed exactly in 128 bits. The
// result is exact up to that one rounding, whatever the order.
#include <mpi.h>
#include <petscsys.h>

namespace bapd {

// result[c] = sum over items of values[item * ncomp + c], for c < ncomp (ncomp <= 16).
PetscErrorCode ReproducibleSum(MPI_Comm comm, PetscInt ncomp, PetscInt nitems, const double *values, double *result);

} // namespace bapd
