// The body set up on every rank (distributed_body.hpp): blocks of natural ids,
// PT-Scotch's partition, the points moved to their owners, the rings fetched.
#include "bapd/solver/parallel/distributed_body.hpp"

#include <petscmat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "bapd/core/geometry/lattice.hpp"
#include "bapd/core/geometry/shape3d.hpp"
#include "bapd/solver/parallel/exchange.hpp"
#include "bapd/solver/parallel/point_reals.hpp"

namespace bapd {

namespace {

// part[i] in [0, size) for the block's points: PT-Scotch on the distributed bond graph,
// each rank its block's rows, vertex weight = family size (PartitionBondGraph's).
PetscErrorCode PartitionBlocks(MPI_Comm comm, const BodyBlock &block, PetscInt n_global, std::vector<PetscInt> *part)
{
  PetscMPIInt     size;
  PetscInt       *ia, *ja, *weight;
  Mat             adjacency;
  MatPartitioning partitioning;
  IS              is;
  const PetscInt *owner;
  const PetscInt  m = block.size();

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  part->assign(m, 0);
  if (size == 1) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(m + 1, &ia));
  PetscCall(PetscMalloc1(std::max<PetscInt>(1, block.offsets[m]), &ja));
  PetscCall(PetscMalloc1(std::max<PetscInt>(1, m), &weight));
  std::copy(block.offsets.begin(), block.offsets.end(), ia);
  std::copy(block.neighbours.begin(), block.neighbours.end(), ja);
  for (PetscInt i = 0; i < m; ++i) weight[i] = std::max<PetscInt>(1, ia[i + 1] - ia[i]);
  PetscCall(MatCreateMPIAdj(comm, m, n_global, ia, ja, nullptr, &adjacency)); // takes ia, ja
  PetscCall(MatPartitioningCreate(comm, &partitioning));
  PetscCall(MatPartitioningSetAdjacency(partitioning, adjacency));
  PetscCall(MatPartitioningSetNParts(partitioning, size));
  PetscCall(MatPartitioningSetType(partitioning, MATPARTITIONINGPTSCOTCH));
  PetscCall(MatPartitioningSetVertexWeights(partitioning, weight)); // takes weight
  PetscCall(MatPartitioningApply(partitioning, &is));
  PetscCall(ISGetIndices(is, &owner));
  std::copy(owner, owner + m, part->begin());
  PetscCall(ISRestoreIndices(is, &owner));
  PetscCall(ISDestroy(&is));
  PetscCall(MatPartitioningDestroy(&partitioning));
  PetscCall(MatDestroy(&adjacency));
  PetscFunctionReturn(0);
}

// What a rank learns of points it asked for by natural id: their PETSc indices, reals
// and (with_families) families as natural ids.
struct Fetched {
  std::vector<PetscInt> petsc, offsets{0}, neighbours;
  std::vector<double>   real;
};

// Points `ids` (sorted, none owned here) from the blocks that hold them; block_petsc is
// this rank's block's PETSc indices. Replies come in rank order, each rank's in the
// order asked: the order of ids.
template <int D>
PetscErrorCode FetchPoints(MPI_Comm comm, const std::vector<PetscInt> &starts, const BodyBlock &block, const std::vector<PetscInt> &block_petsc,
                           const PointReals<D> &reals, const std::vector<PetscInt> &ids, bool with_families, Fetched *got)
{
  const int                          size = (int)starts.size() - 1;
  std::vector<std::vector<PetscInt>> ask(size), answer_int(size);
  std::vector<std::vector<double>>   answer_real(size);
  std::vector<PetscInt>              asked, got_int;

  PetscFunctionBegin;
  for (PetscInt id : ids) ask[HolderOf(starts, id)].push_back(id);
  std::vector<PetscInt> from;
  PetscCall(Ask(comm, ask, &asked, &from));
  std::size_t k = 0;
  for (int r = 0; r < size; ++r)
    for (PetscInt q = 0; q < from[r]; ++q, ++k) {
      const PetscInt i = asked[k] - block.first; // this block's point
      answer_int[r].push_back(block_petsc[i]);
      if (with_families) {
        answer_int[r].push_back(block.offsets[i + 1] - block.offsets[i]);
        answer_int[r].insert(answer_int[r].end(), block.neighbours.begin() + block.offsets[i], block.neighbours.begin() + block.offsets[i + 1]);
      }
      const std::size_t at = answer_real[r].size();
      answer_real[r].resize(at + reals.R);
      reals.Pack(block.cloud, (int)i, answer_real[r].data() + at);
    }
  PetscCall(Exchange(comm, answer_int, &got_int));
  PetscCall(Exchange(comm, answer_real, &got->real));
  got->petsc.resize(ids.size());
  got->offsets.assign(1, 0);
  got->neighbours.clear();
  std::size_t p = 0;
  for (std::size_t q = 0; q < ids.size(); ++q) {
    got->petsc[q] = got_int[p++];
    if (!with_families) continue;
    const PetscInt m = got_int[p++];
    got->neighbours.insert(got->neighbours.end(), got_int.begin() + p, got_int.begin() + p + m);
    got->offsets.push_back((PetscInt)got->neighbours.size());
    p += m;
  }
  PetscFunctionReturn(0);
}

// The sorted distinct members of families [offsets] not in `exclude` (sorted lists).
std::vector<PetscInt> NextRing(const std::vector<PetscInt> &neighbours, const std::vector<const std::vector<PetscInt> *> &exclude)
{
  std::vector<PetscInt> ring(neighbours);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  ring.erase(std::remove_if(ring.begin(), ring.end(),
                            [&](PetscInt j) {
                              for (const std::vector<PetscInt> *e : exclude)
                                if (std::binary_search(e->begin(), e->end(), j)) return true;
                              return false;
                            }),
             ring.end());
  return ring;
}

// The points this rank owns after the partition: natural ids (sorted), their family
// members' natural ids (one family after another) and their reals.
struct OwnedPoints {
  std::vector<PetscInt> ids, neighbours;
  std::vector<double>   real;
};

// The block's points to their owners (part): natural id, family, reals. Blocks are in
// rank order and natural order inside, so each owner receives its points sorted.
template <int D>
PetscErrorCode SendToOwners(MPI_Comm comm, const BodyBlock &block, const std::vector<PetscInt> &part, const PointReals<D> &reals,
                            OwnedPoints *owned)
{
  PetscMPIInt size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<std::vector<PetscInt>> out_int(size);
  std::vector<std::vector<double>>   out_real(size);
  for (PetscInt i = 0; i < block.size(); ++i) {
    std::vector<PetscInt> &o = out_int[part[i]];
    o.push_back(block.first + i);
    o.push_back(block.offsets[i + 1] - block.offsets[i]);
    o.insert(o.end(), block.neighbours.begin() + block.offsets[i], block.neighbours.begin() + block.offsets[i + 1]);
    std::vector<double> &r  = out_real[part[i]];
    const std::size_t    at = r.size();
    r.resize(at + reals.R);
    reals.Pack(block.cloud, (int)i, r.data() + at);
  }
  std::vector<PetscInt> in_int;
  PetscCall(Exchange(comm, out_int, &in_int));
  PetscCall(Exchange(comm, out_real, &owned->real));
  for (auto &o : out_int) std::vector<PetscInt>().swap(o);
  for (std::size_t p = 0; p < in_int.size();) {
    owned->ids.push_back(in_int[p++]);
    const PetscInt k = in_int[p++];
    owned->neighbours.insert(owned->neighbours.end(), in_int.begin() + p, in_int.begin() + p + k);
    p += k;
  }
  PetscFunctionReturn(0);
}

// PETSc numbering: rank blocks in rank order, natural order inside a rank's. Each
// block learns its points' indices (*block_petsc), which it hands out with them as ghosts.
PetscErrorCode TellBlockIndices(MPI_Comm comm, const std::vector<PetscInt> &starts, const BodyBlock &block,
                                const std::vector<PetscInt> &owned, PetscInt owned_start, std::vector<PetscInt> *block_petsc)
{
  std::vector<std::vector<PetscInt>> tell(starts.size() - 1);
  std::vector<PetscInt>              told;

  PetscFunctionBegin;
  for (std::size_t k = 0; k < owned.size(); ++k) {
    std::vector<PetscInt> &t = tell[HolderOf(starts, owned[k])];
    t.push_back(owned[k]);
    t.push_back(owned_start + (PetscInt)k);
  }
  PetscCall(Exchange(comm, tell, &told));
  block_petsc->assign(block.size(), -1);
  for (std::size_t p = 0; p < told.size(); p += 2) (*block_petsc)[told[p] - block.first] = told[p + 1];
  PetscFunctionReturn(0);
}

} // namespace

template <int D>
PetscErrorCode ScatterBody(MPI_Comm comm, const PointCloud &global_cloud, const std::vector<int> &offsets,
                           const std::vector<int> &neighbours, BodyBlock *block)
{
  CloudShape<D> shape;

  PetscFunctionBegin;
  PetscCall(BroadcastCloudShape<D>(comm, global_cloud, &shape));
  const PetscMPIInt    rank = shape.rank, size = shape.size;
  const PetscInt       n     = shape.n;
  const PointReals<D> &reals = shape.reals;
  auto                first_of = [&](int r) { return BlockFirst(n, size, r); };
  std::vector<std::vector<PetscInt>> out_int(size);
  std::vector<std::vector<double>>   out_real(size);
  if (rank == 0)
    for (int r = 0; r < size; ++r)
      for (PetscInt i = first_of(r); i < first_of(r + 1); ++i) {
        out_int[r].push_back(offsets[i + 1] - offsets[i]);
        out_int[r].insert(out_int[r].end(), neighbours.begin() + offsets[i], neighbours.begin() + offsets[i + 1]);
        const std::size_t at = out_real[r].size();
        out_real[r].resize(at + reals.R);
        reals.Pack(global_cloud, (int)i, out_real[r].data() + at);
      }
  std::vector<PetscInt> in_int;
  std::vector<double>   in_real;
  PetscCall(Exchange(comm, out_int, &in_int));
  PetscCall(Exchange(comm, out_real, &in_real));
  block->first       = first_of(rank);
  const PetscInt m   = first_of(rank + 1) - block->first;
  std::vector<int> ids(m);
  for (PetscInt i = 0; i < m; ++i) ids[i] = (int)(block->first + i);
  reals.Unpack(ids, in_real, block->cloud);
  block->offsets.assign(1, 0);
  block->neighbours.clear();
  for (std::size_t p = 0; p < in_int.size();) {
    const PetscInt k = in_int[p++];
    block->neighbours.insert(block->neighbours.end(), in_int.begin() + p, in_int.begin() + p + k);
    block->offsets.push_back((PetscInt)block->neighbours.size());
    p += k;
  }
  PetscFunctionReturn(0);
}

template <int D>
PetscErrorCode LatticeBlock(MPI_Comm comm, const Body<2> &body2d, const Body<3> &body3d, double horizon,
                            const FamilyBuilder &build_families, BodyBlock *block)
{
  PetscMPIInt rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const int64_t rows    = D == 2 ? lattice_rows(body2d) : nd::solid_layers(body3d);
  const double  spacing = D == 2 ? body2d.dx : body3d.dx;
  auto          append  = [&](int64_t from, int64_t to, PointCloud *c, std::vector<int64_t> *counts) {
    if constexpr (D == 2) append_lattice_rows(body2d, from, to, c, counts);
    else nd::append_solid_layers(body3d, from, to, c, counts);
  };
  const int64_t row_begin = rows * rank / size, row_end = rows * (rank + 1) / size;

  // The slab's points, then every rank's row counts: a point's natural id is the points
  // of the rows below it plus its place in its row (the serial lattice's order).
  PointCloud           local;
  std::vector<int64_t> my_counts;
  append(row_begin, row_end, &local, &my_counts);
  std::vector<int> gather_count(size), gather_at(size + 1, 0);
  int              mine = (int)my_counts.size();
  PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, gather_count.data(), 1, MPI_INT, comm));
  for (int r = 0; r < size; ++r) gather_at[r + 1] = gather_at[r] + gather_count[r];
  std::vector<int64_t> row_count(rows);
  PetscCallMPI(MPI_Allgatherv(my_counts.data(), mine, MPI_INT64_T, row_count.data(), gather_count.data(), gather_at.data(),
                              MPI_INT64_T, comm));
  std::vector<int64_t> row_start(rows + 1, 0);
  for (int64_t r = 0; r < rows; ++r) row_start[r + 1] = row_start[r] + row_count[r];
  PetscCheck(row_start[rows] < (int64_t)std::numeric_limits<PetscInt>::max() / 2, comm, PETSC_ERR_SUP,
             "The body has %lld points, more than PETSc's 32-bit indices number: make -body_dx larger",
             (long long)row_start[rows]);

  // The rows within a horizon of the slab, below and above it (a row k rows away is at
  // least k spacings away: beyond the horizon from floor(horizon / spacing) + 1 on).
  const auto        n_own = local.size();
  const int64_t     halo  = (int64_t)std::floor(horizon / spacing) + 1;
  const int64_t     below = std::max<int64_t>(0, row_begin - halo), above = std::min<int64_t>(rows, row_end + halo);
  append(below, row_begin, &local, nullptr);
  const auto n_below = local.size() - n_own;
  append(row_end, above, &local, nullptr);
  for (std::size_t i = 0; i < local.size(); ++i) {
    const int64_t base = i < n_own ? row_start[row_begin] : i < n_own + n_below ? row_start[below] - (int64_t)n_own
                                                                                 : row_start[row_end] - (int64_t)(n_own + n_below);
    local.natural_id[i] = base + (int64_t)i;
  }

  const Families families = build_families(local, n_own);
  compute_family_volumes(local, families);
  block->first = (PetscInt)row_start[row_begin];
  block->cloud.x.assign(local.x.begin(), local.x.begin() + D * n_own);
  block->cloud.volume.assign(local.volume.begin(), local.volume.begin() + n_own);
  block->cloud.family_volume.assign(local.family_volume.begin(), local.family_volume.begin() + n_own);
  block->cloud.natural_id.assign(local.natural_id.begin(), local.natural_id.begin() + n_own);
  block->offsets.assign(families.offsets.begin(), families.offsets.end());
  block->neighbours.resize(families.n_bonds());
  for (std::size_t b = 0; b < families.n_bonds(); ++b) block->neighbours[b] = (PetscInt)local.natural_id[families.neighbour[b]];
  PetscFunctionReturn(0);
}

template <int D> PetscErrorCode DistributeBlocks(MPI_Comm comm, const BodyBlock &block, Layout *layout)
{
  PetscMPIInt rank, size;

  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const PetscInt m = block.size();
  PetscInt       n_global;
  PetscCallMPI(MPI_Allreduce(&m, &n_global, 1, MPIU_INT, MPI_SUM, comm));
  PetscCheck(n_global >= size, comm, PETSC_ERR_USER, "The body has %" PetscInt_FMT " points, fewer than the %d ranks: run on fewer ranks or refine -body_dx", n_global, size);
  std::vector<PetscInt> starts(size + 1);
  PetscCallMPI(MPI_Allgather(&block.first, 1, MPIU_INT, starts.data(), 1, MPIU_INT, comm));
  starts[size] = n_global;
  // An empty block holds no id: its start is the next block's (HolderOf skips it).
  for (int r = size - 1; r >= 0; --r) starts[r] = std::min(starts[r], starts[r + 1]);
  int shape[2] = {block.cloud.horizon.empty() ? 0 : 1, block.cloud.patch_correction.empty() ? 0 : (int)(block.cloud.patch_correction.size() / std::max<PetscInt>(1, m))};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, shape, 2, MPI_INT, MPI_MAX, comm));
  const int           H = shape[0] ? D + 3 : D + 2, L = shape[1];
  const PointReals<D> reals{H + L, L, H, shape[0] == 1};

  std::vector<PetscInt> part;
  PetscCall(PartitionBlocks(comm, block, n_global, &part));

  OwnedPoints own;
  PetscCall(SendToOwners<D>(comm, block, part, reals, &own));
  const std::vector<PetscInt> &owned = own.ids, &owned_neighbours = own.neighbours;
  const std::vector<double>   &owned_real = own.real;
  PetscInt n_owned = (PetscInt)owned.size(), owned_start = 0, fewest = n_owned;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &fewest, 1, MPIU_INT, MPI_MIN, comm));
  PetscCheck(fewest > 0, comm, PETSC_ERR_USER, "The partition left a rank without points: run on fewer ranks");
  PetscCallMPI(MPI_Exscan(&n_owned, &owned_start, 1, MPIU_INT, MPI_SUM, comm));
  if (rank == 0) owned_start = 0;

  std::vector<PetscInt> block_petsc;
  PetscCall(TellBlockIndices(comm, starts, block, owned, owned_start, &block_petsc));

  // Ring 1: the owned points' family members owned elsewhere; ring 2: the ring-1
  // points' members in neither (CollectRings, layout.cpp).
  const std::vector<PetscInt> ring1 = NextRing(owned_neighbours, {&owned});
  Fetched                     got1, got2;
  PetscCall(FetchPoints<D>(comm, starts, block, block_petsc, reals, ring1, true, &got1));
  const std::vector<PetscInt> ring2 = NextRing(got1.neighbours, {&owned, &ring1});
  PetscCall(FetchPoints<D>(comm, starts, block, block_petsc, reals, ring2, false, &got2));

  PetscInt cut = 0; // bonds from an owned point to another rank's, each bond counted from both ends
  for (PetscInt j : owned_neighbours) cut += !std::binary_search(owned.begin(), owned.end(), j);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &cut, 1, MPIU_INT, MPI_SUM, comm));

  const std::size_t n_local = owned.size() + ring1.size() + ring2.size();
  std::vector<int>  ids;
  ids.reserve(n_local);
  ids.insert(ids.end(), owned.begin(), owned.end());
  ids.insert(ids.end(), ring1.begin(), ring1.end());
  ids.insert(ids.end(), ring2.begin(), ring2.end());
  std::vector<double> real;
  real.reserve(reals.R * n_local);
  real.insert(real.end(), owned_real.begin(), owned_real.end());
  real.insert(real.end(), got1.real.begin(), got1.real.end());
  real.insert(real.end(), got2.real.begin(), got2.real.end());
  layout->dimension   = D;
  layout->n_owned     = n_owned;
  layout->n_ring1     = (PetscInt)ring1.size();
  layout->n_ring2     = (PetscInt)ring2.size();
  layout->n_global    = n_global;
  layout->edge_cut    = cut / 2;
  layout->owned_start = owned_start;
  layout->petsc_index.resize(n_local);
  for (PetscInt k = 0; k < n_owned; ++k) layout->petsc_index[k] = owned_start + k;
  std::copy(got1.petsc.begin(), got1.petsc.end(), layout->petsc_index.begin() + n_owned);
  std::copy(got2.petsc.begin(), got2.petsc.end(), layout->petsc_index.begin() + n_owned + ring1.size());
  reals.Unpack(ids, real, layout->cloud);
  PetscFunctionReturn(0);
}

double PeakResidentBytes()
{
  std::FILE *status = std::fopen("/proc/self/status", "r");
  if (!status) return 0;
  char   line[256];
  double kib = 0;
  while (std::fgets(line, sizeof line, status))
    if (std::strncmp(line, "VmHWM:", 6) == 0) {
      kib = std::atof(line + 6);
      break;
    }
  std::fclose(status);
  return 1024.0 * kib;
}

template PetscErrorCode ScatterBody<2>(MPI_Comm, const PointCloud &, const std::vector<int> &, const std::vector<int> &, BodyBlock *);
template PetscErrorCode ScatterBody<3>(MPI_Comm, const PointCloud &, const std::vector<int> &, const std::vector<int> &, BodyBlock *);
template PetscErrorCode LatticeBlock<2>(MPI_Comm, const Body<2> &, const Body<3> &, double, const FamilyBuilder &, BodyBlock *);
template PetscErrorCode LatticeBlock<3>(MPI_Comm, const Body<2> &, const Body<3> &, double, const FamilyBuilder &, BodyBlock *);
template PetscErrorCode DistributeBlocks<2>(MPI_Comm, const BodyBlock &, Layout *);
template PetscErrorCode DistributeBlocks<3>(MPI_Comm, const BodyBlock &, Layout *);

} // namespace bapd
