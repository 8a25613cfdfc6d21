#pragma once
// The body set up on every rank (-partition_type ptscotch): each rank holds a block of
// the body, a contiguous range of natural ids with their reference data and their
// families as natural ids; PT-Scotch (PETSc's MatPartitioning) splits the distributed
// bond graph; the points move to their owners and each owner fetches its ring-1 and
// ring-2 ghosts from the blocks that hold them. No rank holds the whole body or graph,
// and the Layout is the one DistributePoints (layout.hpp) gives for the same partition:
// owned, ring-1 and ring-2 points each sorted by natural id, a ghost's PETSc index its
// owner's.
//
// A lattice body's blocks are slabs of lattice rows (2D) or layers (3D), one a rank,
// built where they are held (LatticeBlock): a slab's families need the rows within a
// horizon of it, which the lattice gives without communication. Given points (2D or
// 3D clouds, a mesh's centroids) start from each rank's block of natural ids and are cut
// into slabs along x for their families (CloudBlock, cloud_block.hpp); the scene still
// holds their whole file on every rank. The patch correction (a solve over the whole
// body) is built on rank 0 and cut into blocks (ScatterBody).
#include <functional>
#include <petscsys.h>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/geometry/shape3d.hpp"
#include "bapd/solver/parallel/layout.hpp"

namespace bapd {

struct BodyBlock {
  PetscInt              first = 0;      // natural id of the block's first point
  PointCloud            cloud;          // the block's points in natural order, family_volume set
  std::vector<PetscInt> offsets{0};     // the block's families (CSR over its points) ...
  std::vector<PetscInt> neighbours;     // ... as natural ids, sorted
  PetscInt size() const { return (PetscInt)cloud.size(); }
};

// Rank 0's whole body (global_cloud with family_volume set, the bond graph in CSR
// form, natural order) cut into one block a rank, of n / size points each (the
// first n % size ranks one more). The other ranks pass empty vectors.
template <int D>
PetscErrorCode ScatterBody(MPI_Comm comm, const PointCloud &global_cloud, const std::vector<int> &offsets,
                           const std::vector<int> &neighbours, BodyBlock *block);

// The families of the points [0, n_family) of a cloud, as the serial set-up builds
// them (the scene's horizon and notches): the one family code for every build.
using FamilyBuilder = std::function<Families(const PointCloud &cloud, std::size_t n_family)>;

// A lattice body's slab on this rank: rows (2D: Body<2>'s lattice rows, grips'
// included) or layers (3D: the solids' lattice, z) [rows * rank / size, rows * (rank
// + 1) / size), natural ids exactly the serial lattice's (each rank's row counts
// gathered: O(rows) numbers), its families built with the rows within a horizon on
// either side generated here, and family volumes. Not with given points (CloudBlock)
// or the patch correction (ScatterBody).
template <int D>
PetscErrorCode LatticeBlock(MPI_Comm comm, const Body<2> &body2d, const Body<3> &body3d, double horizon,
                            const FamilyBuilder &build_families, BodyBlock *block);

// The Layout of every rank from the blocks: PT-Scotch's partition (vertex weight =
// family size, as the METIS call), the points moved to their owners, the rings
// fetched by natural id from the blocks. edge_cut: the bonds between ranks.
template <int D> PetscErrorCode DistributeBlocks(MPI_Comm comm, const BodyBlock &block, Layout *layout);

// The peak resident memory of this process so far (VmHWM of /proc/self/status) [bytes];
// 0 where the system does not give it.
double PeakResidentBytes();

} // namespace bapd
