#pragma once
// METIS partition of the bond graph, from which the layout is built (layout.hpp).
#include <petscsys.h>
#include <vector>

namespace bapd {

// part[i] in [0, nparts) for every point of a graph given in CSR form (offsets,
// neighbours), k-way, balanced on bond count (vertex weight = family size), so that
// every rank does about the same force work. Deterministic for a given input.
PetscErrorCode PartitionBondGraph(const std::vector<int> &offsets, const std::vector<int> &neighbours, PetscInt nparts,
                                  std::vector<int> *part, PetscInt *edge_cut);

} // namespace bapd
