#pragma once
// The patch correction's term h_ij of the bond kernel (ba_force.hpp).
#include <cstddef>

#include "bapd/core/kernel/bond_geometry.hpp"

namespace bapd::nd {

// -force_patch_correction (patch_correction.hpp): h_ij = c_ij xi added to g_ij, from
// patch_stride<D>(virial) numbers a point. on: lambda (D), c_ij = (lambda_i - lambda_j) . xi;
// virial: (mu, S_i upper triangle by sym_index), c_ij = (mu_i - mu_j) . xi + xi . S_i xi.
// For D = 2 the operations of the 2D add_patch_term and virial_patch_coefficient in their order.
template <int D> constexpr std::size_t patch_stride(bool virial) { return virial ? D + sym_size<D> : D; }
template <int D>
inline void add_patch_term(const double *lambda_i, const double *lambda_j, const double *xi, double *g, bool virial = false)
{
  double s = (lambda_i[0] - lambda_j[0]) * xi[0];
  for (int r = 1; r < D; ++r) s = s + (lambda_i[r] - lambda_j[r]) * xi[r];
  if (virial)
    for (int r = 0; r < D; ++r)
      for (int c = r; c < D; ++c) s = s + (r == c ? 1.0 : 2.0) * lambda_i[D + sym_index<D>(r, c)] * xi[r] * xi[c];
  for (int r = 0; r < D; ++r) g[r] += s * xi[r];
}

} // namespace bapd::nd
