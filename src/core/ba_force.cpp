#include "bapd/ba_force.hpp"

#include <stdexcept>
#include <string>

namespace bapd {

void assemble_force_density(const Families &families, const PointCloud &ref, const double *bond_force,
                            std::size_t n_owned, double *force_density)
{
  if (n_owned > families.n_family)
    throw std::logic_error("assemble_force_density: n_owned = " + std::to_string(n_owned) +
                           " exceeds the family points " + std::to_string(families.n_family));
  const std::int32_t *nb = families.neighbour.data(), *rev = families.reverse.data();
  const double       *vol = ref.volume.data();
  for (std::size_t i = 0; i < n_owned; ++i) {
    double f0 = 0.0, f1 = 0.0;
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b) {
      const std::int32_t r = rev[b];
      if (r < 0)
        throw std::logic_error("assemble_force_density: point with natural id " + std::to_string(ref.natural_id[i]) +
                               " has a neighbour without a family here; owned points need ring-1 ghosts "
                               "(and ring-1 ghosts need ring-2) in the local cloud");
      const double v = vol[nb[b]];
      f0 += (bond_force[2 * b] - bond_force[2 * r]) * v;
      f1 += (bond_force[2 * b + 1] - bond_force[2 * r + 1]) * v;
    }
    force_density[2 * i]     = f0;
    force_density[2 * i + 1] = f1;
  }
}

Mat2 bond_deformation_gradient(const PointCloud &ref, const double *y, const Families &families,
                               const BondGeometry &geometry, const BondState &state, std::size_t i, std::size_t q)
{
  if (!state.is_intact(i, q) || !geometry.is_usable(i, q)) return {0.0, 0.0, 0.0, 0.0};
  PointScratch s;
  s.reserve(families.max_family_size);
  const std::uint64_t *intact = state.intact_mask(i);
  const std::size_t    b = families.offsets[i] + q, W = families.mask_words;
  // the same arithmetic as the kernel, bit for bit
  const PointTotals    totals = W == 1 ? detail::gather_point<1>(ref, y, families, i, intact, s)
                                       : detail::gather_point<0>(ref, y, families, i, intact, s);
  const BondKinematics k = W == 1 ? detail::bond_kinematics<1>(families.ba(b), intact, 1, s, totals)
                                  : detail::bond_kinematics<0>(families.ba(b), intact, W, s, totals);
  return k.usable ? k.F : Mat2{0.0, 0.0, 0.0, 0.0};
}

} // namespace bapd
