#pragma once
// A point's reference data as the set-up ships it between ranks (layout.cpp,
// distributed_body.cpp): a fixed count of reals a point.
#include <petscsys.h>

#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/kernel/ba_force.hpp"

namespace bapd {

// A point's reals as the set-up sends them: the D coordinates, V, V(H), and delta_i when
// the points have their own horizons, then from H the patch correction's L numbers
// with -force_patch_correction: lambda_i (D, on) or mu_i, S_i (D + D(D+1)/2, virial: 5
// in 2D; patch_correction.hpp, nd::patch_stride), the ring-1 points' included, which
// the kernel reads as neighbours.
template <int D> struct PointReals {
  static constexpr int kVolume = D, kFamilyVolume = D + 1, kHorizon = D + 2; // their places in a point's reals
  int                  R, L, H; // reals a point; the patch correction's numbers and where they start
  bool                 own_horizon;

  // Point i of the global cloud into its R reals at out.
  void Pack(const PointCloud &global_cloud, int i, double *out) const
  {
    for (int d = 0; d < D; ++d) out[d] = global_cloud.x[D * i + d];
    out[kVolume]       = global_cloud.volume[i];
    out[kFamilyVolume] = global_cloud.family_volume[i];
    if (own_horizon) out[kHorizon] = global_cloud.horizon[i];
    for (int l = 0; l < L; ++l) out[H + l] = global_cloud.patch_correction[L * i + l];
  }
  // The rank's cloud from its points' natural ids and reals.
  void Unpack(const std::vector<int> &ids, const std::vector<double> &real, PointCloud &c) const
  {
    const std::size_t m = ids.size();
    c.x.resize(D * m);
    c.volume.resize(m);
    c.family_volume.resize(m);
    c.natural_id.assign(ids.begin(), ids.end());
    c.horizon.resize(own_horizon ? m : 0);
    c.patch_correction.resize(L * m);
    c.patch_virial = L == (int)nd::patch_stride<D>(true);
    for (std::size_t k = 0; k < m; ++k) {
      for (int d = 0; d < D; ++d) c.x[D * k + d] = real[R * k + d];
      c.volume[k]        = real[R * k + kVolume];
      c.family_volume[k] = real[R * k + kFamilyVolume];
      if (own_horizon) c.horizon[k] = real[R * k + kHorizon];
      for (int l = 0; l < L; ++l) c.patch_correction[L * k + l] = real[R * k + H + l];
    }
  }
};

// What every rank knows before rank 0, which holds the whole cloud, sends it out: its
// rank, the rank count, the cloud's size and the reals a point has.
template <int D> struct CloudShape {
  PetscMPIInt   rank = 0, size = 1;
  PetscInt      n = 0;
  PointReals<D> reals;
};

// The cloud's shape (its size, its points' own horizons, the patch correction's
// numbers) from rank 0 to every rank, with this rank and the rank count.
template <int D> PetscErrorCode BroadcastCloudShape(MPI_Comm comm, const PointCloud &global_cloud, CloudShape<D> *shape)
{
  PetscInt *n = &shape->n;
  PetscFunctionBegin;
  PetscCallMPI(MPI_Comm_rank(comm, &shape->rank));
  PetscCallMPI(MPI_Comm_size(comm, &shape->size));
  *n = (PetscInt)global_cloud.size();
  PetscCallMPI(MPI_Bcast(n, 1, MPIU_INT, 0, comm));
  int R = global_cloud.horizon.empty() ? D + 2 : D + 3,
      L = global_cloud.patch_correction.empty() ? 0 : (int)nd::patch_stride<D>(global_cloud.patch_virial);
  PetscCallMPI(MPI_Bcast(&R, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&L, 1, MPI_INT, 0, comm));
  shape->reals = PointReals<D>{R + L, L, R, R == D + 3};
  PetscFunctionReturn(0);
}

} // namespace bapd
