// f_i = sum_j (t_ij - t_ji) V_j in D dimensions (ba_force.hpp), for D = 2 and 3.
#include "bapd/core/kernel/ba_force.hpp"

#include <stdexcept>
#include <string>

namespace bapd::nd {

template <int D>
void assemble_force_density(const Families &families, const PointCloud &ref, const double *bond_force,
                            std::size_t n_owned, double *force_density)
{
  if (n_owned > families.n_family)
    throw std::logic_error("nd::assemble_force_density: n_owned = " + std::to_string(n_owned) +
                           " exceeds the family points " + std::to_string(families.n_family));
  const std::int32_t *nb = families.neighbour.data(), *rev = families.reverse.data();
  const double       *vol = ref.volume.data();
  // 128 bonds (~4.6 points at 3.015 dx): 1e5 points, assemble per bond without / with
  // the prefetch: 1.41 x at 16 places, 1.24 x more at 32, 1.33 x more at 64, 1.25 x more at 128 (1i).
  const std::size_t   n_bonds = families.neighbour.size(), ahead = 128;
  for (std::size_t i = 0; i < n_owned; ++i) {
    double f[D] = {};
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      // The reads of t_ji (through the reverse index, in j's block) and V_j wait on memory
      // (docs/notes/performance-kernel-2.md 1c, performance-kernel-3.md 1i): ask for those of
      // the bond `ahead` places on now. A prefetch changes no value, so the sums and their
      // order are those without it, bit for bit.
      if (b + ahead < n_bonds) {
        const std::int32_t rp = rev[b + ahead];
        if (rp >= 0) __builtin_prefetch(bond_force + D * static_cast<std::size_t>(rp));
        __builtin_prefetch(vol + nb[b + ahead]);
      }
      const std::int32_t r = rev[b];
      if (r < 0)
        throw std::logic_error("nd::assemble_force_density: point with natural id " +
                               std::to_string(ref.natural_id[i]) +
                               " has a neighbour without a family here; owned points need ring-1 ghosts "
                               "(and ring-1 ghosts need ring-2) in the local cloud");
      const double      v  = vol[nb[b]];
      const std::size_t rb = static_cast<std::size_t>(r);
      for (int k = 0; k < D; ++k) f[k] += (bond_force[D * b + k] - bond_force[D * rb + k]) * v;
    }
    for (int k = 0; k < D; ++k) force_density[D * i + k] = f[k];
  }
}

template void assemble_force_density<2>(const Families &, const PointCloud &, const double *, std::size_t, double *);
template void assemble_force_density<3>(const Families &, const PointCloud &, const double *, std::size_t, double *);

} // namespace bapd::nd
