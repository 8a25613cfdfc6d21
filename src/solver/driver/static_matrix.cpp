// The static solver's preconditioner matrix (static_solver.hpp): the AIJ copy of the
// BAIJ tangent that GAMG, hypre and the factorisations take, refreshed after each assembly.
#include "bapd/solver/driver/static_solver.hpp"

namespace bapd {

namespace {

// The preconditioner's AIJ copy of the BAIJ tangent, value by value (MatConvert with
// MAT_REUSE_MATRIX builds a new matrix every time). `to` is a MatConvert of `from`, which
// keeps every entry of a block (zeros too), so AIJ row bs I + r holds block row I's blocks
// in order, bs entries each; a block's entries are column-major in BAIJ. *same false:
// the patterns do not match that way (nothing is copied).
PetscErrorCode CopyBlocks(Mat from, Mat to, PetscInt bs, bool check, bool *same)
{
  const PetscInt *bi, *bj, *ai, *aj;
  PetscInt        nb, n;
  PetscBool       got_b, got_a;
  PetscScalar    *a, *b;

  PetscFunctionBegin;
  *same = false;
  PetscCall(MatGetRowIJ(from, 0, PETSC_FALSE, PETSC_TRUE, &nb, &bi, &bj, &got_b));
  PetscCall(MatGetRowIJ(to, 0, PETSC_FALSE, PETSC_FALSE, &n, &ai, &aj, &got_a));
  bool ok = got_b && got_a && n == bs * nb;
  for (PetscInt I = 0; ok && check && I < nb; ++I)
    for (PetscInt r = 0; ok && r < bs; ++r) {
      const PetscInt row = bs * I + r;
      ok = ai[row + 1] - ai[row] == bs * (bi[I + 1] - bi[I]);
      for (PetscInt k = bi[I]; ok && k < bi[I + 1]; ++k)
        for (PetscInt c = 0; ok && c < bs; ++c) ok = aj[ai[row] + bs * (k - bi[I]) + c] == bs * bj[k] + c;
    }
  if (ok) {
    PetscCall(MatSeqBAIJGetArray(from, &b));
    PetscCall(MatSeqAIJGetArrayWrite(to, &a));
    for (PetscInt I = 0; I < nb; ++I)
      for (PetscInt r = 0; r < bs; ++r) {
        PetscScalar *out = a + ai[bs * I + r];
        for (PetscInt k = bi[I]; k < bi[I + 1]; ++k)
          for (PetscInt c = 0; c < bs; ++c) *out++ = b[bs * bs * k + bs * c + r];
      }
    PetscCall(MatSeqAIJRestoreArrayWrite(to, &a));
    PetscCall(MatSeqBAIJRestoreArray(from, &b));
  }
  PetscCall(MatRestoreRowIJ(from, 0, PETSC_FALSE, PETSC_TRUE, &nb, &bi, &bj, &got_b));
  PetscCall(MatRestoreRowIJ(to, 0, PETSC_FALSE, PETSC_FALSE, &n, &ai, &aj, &got_a));
  *same = ok;
  PetscFunctionReturn(0);
}

} // namespace

// P_ = H_ (values) after an assembly: block by block where P_ is H_'s AIJ copy in the
// layout CopyBlocks expects (checked at the first copy), else by MatConvert.
template <int D> PetscErrorCode StaticSolver<D>::CopyToPreconditioner()
{
  PetscFunctionBegin;
  if (P_ == H_) PetscFunctionReturn(0);
  if (block_copy_ != 0) {
    PetscBool seq, mpi;
    PetscCall(PetscObjectTypeCompare((PetscObject)H_, MATSEQBAIJ, &seq));
    PetscCall(PetscObjectTypeCompare((PetscObject)H_, MATMPIBAIJ, &mpi));
    bool same = false;
    if (seq) PetscCall(CopyBlocks(H_, P_, D, block_copy_ < 0, &same));
    else if (mpi) {
      Mat             hd, ho, pd, po;
      const PetscInt *hmap, *pmap;
      bool            same_off = false;
      PetscCall(MatMPIBAIJGetSeqBAIJ(H_, &hd, &ho, &hmap));
      PetscCall(MatMPIAIJGetSeqAIJ(P_, &pd, &po, &pmap));
      PetscCall(CopyBlocks(hd, pd, D, block_copy_ < 0, &same));
      if (same) PetscCall(CopyBlocks(ho, po, D, block_copy_ < 0, &same_off));
      same = same && same_off;
    }
    int mine = same ? 1 : 0, all = 0;
    PetscCallMPI(MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, sim_.comm_));
    block_copy_ = all; // checked once: 1 from now on, or 0 (MatConvert)
    if (all) {
      PetscCall(MatAssemblyBegin(P_, MAT_FINAL_ASSEMBLY)); // its state moves on: the preconditioner sees the new values
      PetscCall(MatAssemblyEnd(P_, MAT_FINAL_ASSEMBLY));
      PetscFunctionReturn(0);
    }
  }
  PetscCall(MatConvert(H_, MATAIJ, MAT_REUSE_MATRIX, &P_));
  PetscFunctionReturn(0);
}

template PetscErrorCode StaticSolver<2>::CopyToPreconditioner();
template PetscErrorCode StaticSolver<3>::CopyToPreconditioner();

} // namespace bapd
