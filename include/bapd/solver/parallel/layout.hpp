#pragma once
// Owned + ghost numbering of the points of one rank.
//
// Local point order: owned points, then ring-1 ghosts (family members of owned
// points: their bond forces t_ji enter the owned force sums), then ring-2 ghosts
// (family members of ring-1 ghosts: positions only). Each group is sorted by natural
// id. A point's PETSc index puts rank r's owned points in one contiguous block.
//
// The dimension D (2 or 3) is a template parameter of the functions
// that read coordinates or build D-vectors; the Layout itself, like the PointCloud and
// the Families it holds or serves, is the same type for every D (its cloud holds D
// coordinates a point), so that the driver's parts that only count points take it as
// it is. The rings are found on the bond graph, which knows no dimension.
#include <petscvec.h>
#include <vector>

#include "bapd/core/geometry/body.hpp"

namespace bapd {

struct Layout {
  int                  dimension = 2;    // D: coordinates a point in cloud.x (DistributePoints<D>)
  PetscInt             n_owned = 0, n_ring1 = 0, n_ring2 = 0;
  PetscInt             n_global = 0;     // points in the whole body
  PetscInt             owned_start = 0;  // PETSc index of the first owned point
  PetscInt             edge_cut = 0;     // METIS edge cut (bonds between ranks)
  std::vector<PetscInt> petsc_index;     // per local point
  PointCloud           cloud;            // local points, reference data

  PetscInt n_family() const { return n_owned + n_ring1; }
  PetscInt n_local() const { return n_owned + n_ring1 + n_ring2; }
  PetscInt n_ghost() const { return n_ring1 + n_ring2; }
};

// Rank 0 holds the whole body (global_cloud with family_volume set, D coordinates a
// point, and the bond graph in CSR form, both in natural order); every rank receives
// its Layout. Instantiated for D = 2 and 3.
template <int D>
PetscErrorCode DistributePoints(MPI_Comm comm, const PointCloud &global_cloud, const std::vector<int> &offsets,
                                const std::vector<int> &neighbours, Layout *layout);

// A Vec of block size D (D entries per owned point: a displacement, a force) with
// ghost slots for the ring-1 and ring-2 ghosts, in local order (VecGhostGetLocalForm
// gives [owned, ghosts]). layout.dimension must be D.
template <int D>
PetscErrorCode CreateGhostedVector(MPI_Comm comm, const Layout &layout, Vec *v);

} // namespace bapd
