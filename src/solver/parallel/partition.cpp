#include "bapd/solver/parallel/partition.hpp"

#include <metis.h>

#include <algorithm>

namespace bapd {

PetscErrorCode PartitionBondGraph(const std::vector<int> &offsets, const std::vector<int> &neighbours, PetscInt nparts,
                                  std::vector<int> *part, PetscInt *edge_cut)
{
  idx_t n = (idx_t)offsets.size() - 1;

  PetscFunctionBegin;
  part->assign(n, 0);
  *edge_cut = 0;
  if (nparts <= 1 || n == 0) PetscFunctionReturn(0);
  PetscCheck(nparts <= n, PETSC_COMM_SELF, PETSC_ERR_USER, "Cannot split %" PetscInt_FMT " points over %" PetscInt_FMT " ranks: run on fewer ranks or refine -body_dx", (PetscInt)n, nparts);
  std::vector<idx_t> xadj(offsets.begin(), offsets.end()), adjncy(neighbours.begin(), neighbours.end());
  std::vector<idx_t> vwgt(n), result(n);
  for (idx_t i = 0; i < n; ++i) vwgt[i] = std::max<idx_t>(1, xadj[i + 1] - xadj[i]);
  idx_t ncon = 1, np = (idx_t)nparts, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1; // the same partition on every run
  const int status = METIS_PartGraphKway(&n, &ncon, xadj.data(), adjncy.data(), vwgt.data(), nullptr, nullptr, &np, nullptr,
                                         nullptr, options, &objval, result.data());
  PetscCheck(status == METIS_OK, PETSC_COMM_SELF, PETSC_ERR_LIB, "METIS_PartGraphKway failed with status %d", status);
  part->assign(result.begin(), result.end());
  *edge_cut = (PetscInt)objval;
  PetscFunctionReturn(0);
}

} // namespace bapd
