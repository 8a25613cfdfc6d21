#include "bapd/solver/parallel/layout.hpp"

#include <algorithm>

#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/solver/parallel/partition.hpp"
#include "bapd/solver/parallel/point_reals.hpp"

namespace bapd {

namespace {

// Per-rank lists of natural ids, built on rank 0.
struct RankPoints {
  std::vector<int> owned, ring1, ring2;
};

void CollectRings(int nranks, const std::vector<int> &part, const std::vector<int> &offsets,
                  const std::vector<int> &neighbours, std::vector<RankPoints> *ranks)
{
  const int        n = (int)part.size();
  std::vector<int> mark(n, -1); // rank that last claimed the point, per pass
  ranks->assign(nranks, RankPoints{});
  for (int i = 0; i < n; ++i) (*ranks)[part[i]].owned.push_back(i);
  for (int r = 0; r < nranks; ++r) {
    RankPoints &rp = (*ranks)[r];
    for (int i : rp.owned) mark[i] = 2 * r; // owned
    for (int i : rp.owned)
      for (int b = offsets[i]; b < offsets[i + 1]; ++b) {
        const int j = neighbours[b];
        if (mark[j] != 2 * r) {
          mark[j] = 2 * r;
          rp.ring1.push_back(j);
        }
      }
    for (int i : rp.ring1) mark[i] = 2 * r + 1;
    for (int i : rp.owned) mark[i] = 2 * r + 1;
    for (int i : rp.ring1)
      for (int b = offsets[i]; b < offsets[i + 1]; ++b) {
        const int j = neighbours[b];
        if (mark[j] != 2 * r + 1) {
          mark[j] = 2 * r + 1;
          rp.ring2.push_back(j);
        }
      }
    std::sort(rp.ring1.begin(), rp.ring1.end());
    std::sort(rp.ring2.begin(), rp.ring2.end());
  }
}

} // namespace

template <int D>
PetscErrorCode DistributePoints(MPI_Comm comm, const PointCloud &global_cloud, const std::vector<int> &offsets,
                                const std::vector<int> &neighbours, Layout *layout)
{
  CloudShape<D> shape;
  PetscInt      edge_cut = 0;

  PetscFunctionBegin;
  PetscCall(BroadcastCloudShape<D>(comm, global_cloud, &shape));
  const PetscMPIInt    rank = shape.rank, size = shape.size;
  const PetscInt       n_global = shape.n;
  const PointReals<D> &reals    = shape.reals;
  const int            R        = reals.R;
  PetscCheck(n_global >= size, comm, PETSC_ERR_USER, "The body has %" PetscInt_FMT " points, fewer than the %d ranks: run on fewer ranks or refine -body_dx", n_global, size);

  std::vector<int>      my_ids;
  std::vector<PetscInt> my_petsc;
  std::vector<double>   my_real;
  PetscInt              my_counts[3];

  if (rank == 0) {
    std::vector<int> part;
    PetscCall(PartitionBondGraph(offsets, neighbours, size, &part, &edge_cut));
    std::vector<RankPoints> ranks;
    CollectRings(size, part, offsets, neighbours, &ranks);
    // PETSc numbering: rank blocks in rank order, natural order inside a block.
    std::vector<PetscInt> petsc_index(n_global);
    PetscInt              next = 0;
    for (int r = 0; r < size; ++r) {
      PetscCheck(!ranks[r].owned.empty(), PETSC_COMM_SELF, PETSC_ERR_USER, "The partition left rank %d without points: run on fewer ranks", r);
      for (int i : ranks[r].owned) petsc_index[i] = next++;
    }
    for (int r = size - 1; r >= 0; --r) { // rank 0 last, so its buffers stay
      const RankPoints &rp = ranks[r];
      std::vector<int>  ids;
      ids.reserve(rp.owned.size() + rp.ring1.size() + rp.ring2.size());
      ids.insert(ids.end(), rp.owned.begin(), rp.owned.end());
      ids.insert(ids.end(), rp.ring1.begin(), rp.ring1.end());
      ids.insert(ids.end(), rp.ring2.begin(), rp.ring2.end());
      std::vector<PetscInt> pidx(ids.size());
      std::vector<double>   real(R * ids.size());
      for (std::size_t k = 0; k < ids.size(); ++k) {
        pidx[k] = petsc_index[ids[k]];
        reals.Pack(global_cloud, ids[k], real.data() + R * k);
      }
      PetscInt c[3] = {(PetscInt)rp.owned.size(), (PetscInt)rp.ring1.size(), (PetscInt)rp.ring2.size()};
      if (r == 0) {
        std::copy(c, c + 3, my_counts);
        my_ids   = std::move(ids);
        my_petsc = std::move(pidx);
        my_real  = std::move(real);
      } else {
        const int m = (int)ids.size();
        PetscCallMPI(MPI_Send(c, 3, MPIU_INT, r, 0, comm));
        PetscCallMPI(MPI_Send(ids.data(), m, MPI_INT, r, 1, comm));
        PetscCallMPI(MPI_Send(pidx.data(), m, MPIU_INT, r, 2, comm));
        PetscCallMPI(MPI_Send(real.data(), R * m, MPI_DOUBLE, r, 3, comm));
      }
    }
  } else {
    PetscCallMPI(MPI_Recv(my_counts, 3, MPIU_INT, 0, 0, comm, MPI_STATUS_IGNORE));
    const int m = (int)(my_counts[0] + my_counts[1] + my_counts[2]);
    my_ids.resize(m);
    my_petsc.resize(m);
    my_real.resize(R * m);
    PetscCallMPI(MPI_Recv(my_ids.data(), m, MPI_INT, 0, 1, comm, MPI_STATUS_IGNORE));
    PetscCallMPI(MPI_Recv(my_petsc.data(), m, MPIU_INT, 0, 2, comm, MPI_STATUS_IGNORE));
    PetscCallMPI(MPI_Recv(my_real.data(), R * m, MPI_DOUBLE, 0, 3, comm, MPI_STATUS_IGNORE));
  }
  PetscCallMPI(MPI_Bcast(&edge_cut, 1, MPIU_INT, 0, comm));

  layout->dimension   = D;
  layout->n_owned     = my_counts[0];
  layout->n_ring1     = my_counts[1];
  layout->n_ring2     = my_counts[2];
  layout->n_global    = n_global;
  layout->edge_cut    = edge_cut;
  layout->owned_start = my_counts[0] > 0 ? my_petsc[0] : 0;
  layout->petsc_index = std::move(my_petsc);
  reals.Unpack(my_ids, my_real, layout->cloud);
  PetscFunctionReturn(0);
}

template <int D>
PetscErrorCode CreateGhostedVector(MPI_Comm comm, const Layout &layout, Vec *v)
{
  PetscFunctionBegin;
  PetscCheck(layout.dimension == D, comm, PETSC_ERR_PLIB, "CreateGhostedVector<%d> on a layout of dimension %d", D, layout.dimension);
  const PetscInt *ghosts = layout.petsc_index.data() + layout.n_owned;
  PetscCall(VecCreateGhostBlock(comm, D, D * layout.n_owned, PETSC_DECIDE, layout.n_ghost(), ghosts, v));
  PetscFunctionReturn(0);
}

template PetscErrorCode DistributePoints<2>(MPI_Comm, const PointCloud &, const std::vector<int> &, const std::vector<int> &, Layout *);
template PetscErrorCode DistributePoints<3>(MPI_Comm, const PointCloud &, const std::vector<int> &, const std::vector<int> &, Layout *);
template PetscErrorCode CreateGhostedVector<2>(MPI_Comm, const Layout &, Vec *);
template PetscErrorCode CreateGhostedVector<3>(MPI_Comm, const Layout &, Vec *);

} // namespace bapd
