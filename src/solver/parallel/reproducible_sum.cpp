#include "bapd/solver/parallel/reproducible_sum.hpp"

#include <cmath>
#include <cstring>

namespace bapd {

namespace {

constexpr int kMaxComponents = 16;
constexpr int kFractionBits  = 100; // grid spacing relative to the largest term

void SumInt128(void *in, void *inout, int *len, MPI_Datatype *)
{
  auto *a = static_cast<__int128 *>(in);
  auto *b = static_cast<__int128 *>(inout);
  for (int i = 0; i < *len; ++i) b[i] += a[i];
}

} // namespace

PetscErrorCode ReproducibleSum(MPI_Comm comm, PetscInt ncomp, PetscInt nitems, const double *values, double *result)
{
  double    local_max[kMaxComponents] = {0}, global_max[kMaxComponents];
  __int128  local_sum[kMaxComponents] = {0}, global_sum[kMaxComponents];
  int       exponent[kMaxComponents];
  long long global_items = 0, items = nitems;

  PetscFunctionBegin;
  PetscCheck(ncomp > 0 && ncomp <= kMaxComponents, comm, PETSC_ERR_ARG_OUTOFRANGE, "ReproducibleSum: ncomp %" PetscInt_FMT " out of range", ncomp);
  for (PetscInt i = 0; i < nitems; ++i)
    for (PetscInt c = 0; c < ncomp; ++c) local_max[c] = std::fmax(local_max[c], std::fabs(values[i * ncomp + c]));
  PetscCallMPI(MPI_Allreduce(local_max, global_max, (int)ncomp, MPI_DOUBLE, MPI_MAX, comm));
  PetscCallMPI(MPI_Allreduce(&items, &global_items, 1, MPI_LONG_LONG, MPI_SUM, comm));
  // Headroom for the count of terms keeps the 128-bit sum from overflowing.
  PetscCheck(global_items < (1LL << 24), comm, PETSC_ERR_SUP, "ReproducibleSum: too many terms");
  for (PetscInt c = 0; c < ncomp; ++c) {
    PetscCheck(std::isfinite(global_max[c]), comm, PETSC_ERR_FP, "ReproducibleSum: non-finite term");
    exponent[c] = global_max[c] > 0 ? std::ilogb(global_max[c]) : 0;
  }
  for (PetscInt i = 0; i < nitems; ++i)
    for (PetscInt c = 0; c < ncomp; ++c) {
      const double scaled = std::ldexp(values[i * ncomp + c], kFractionBits - exponent[c]); // |scaled| < 2^101
      local_sum[c] += (__int128)scaled;
    }
  MPI_Datatype int128;
  MPI_Op       op;
  PetscCallMPI(MPI_Type_contiguous(16, MPI_BYTE, &int128));
  PetscCallMPI(MPI_Type_commit(&int128));
  PetscCallMPI(MPI_Op_create(SumInt128, 1, &op));
  PetscCallMPI(MPI_Allreduce(local_sum, global_sum, (int)ncomp, int128, op, comm));
  PetscCallMPI(MPI_Op_free(&op));
  PetscCallMPI(MPI_Type_free(&int128));
  for (PetscInt c = 0; c < ncomp; ++c) result[c] = std::ldexp((double)global_sum[c], exponent[c] - kFractionBits);
  PetscFunctionReturn(0);
}

} // namespace bapd
