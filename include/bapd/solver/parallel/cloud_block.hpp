#pragma once
// Given points (a 2D or 3D cloud) set up on every rank (-partition_type ptscotch): each
// rank starts from its share of the points, a contiguous range of natural ids, and ends
// with the BodyBlock of that range (distributed_body.hpp) for DistributeBlocks. On the
// way the points are cut into slabs along x, balanced by counts, each slab with the
// points within the largest horizon on either side, so that each slab's families are
// built whole where the slab is held (FamilyBuilder: the serial families, bit for bit);
// the check that the points hold together runs on the slabs with the cross-slab bonds
// joined on rank 0 (one number pair per component, not per point).
#include <cstdint>
#include <string>

#include "bapd/solver/parallel/distributed_body.hpp"

namespace bapd {

// The words when given points fall apart into pieces (the smallest piece: its point
// count, its first point's natural id and position x, `dimension` numbers), from
// `source` (the file or the option giving the points).
std::string PiecesMessage(const std::string &source, std::size_t n_pieces, std::size_t smallest_count, int64_t first_id, const double *x,
                          int dimension);

// The block of natural ids [first, first + chunk.size()) from this rank's `chunk` of the
// given points (natural order, their own horizons set; every rank's chunks in rank order
// cover the body): family volumes set, families as sorted natural ids. Refuses points in
// pieces with DescribePieces' message (every rank stops together).
template <int D>
PetscErrorCode CloudBlock(MPI_Comm comm, const PointCloud &chunk, PetscInt first, const FamilyBuilder &build_families,
                          const std::string &source, BodyBlock *block);

} // namespace bapd
