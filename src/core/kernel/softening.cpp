// Softening bonds (softening.hpp; docs/method.md section 5.4).
#include "bapd/core/kernel/softening.hpp"

#include <algorithm>
#include <cmath>

namespace bapd {

double softening_damage(Softening law, double r, double r0, double gamma)
{
  if (!(r >= r0)) return 0.0;
  switch (law) {
  case Softening::none:
  case Softening::time: return 1.0; // (time: fading_damage; soften_bonds never asks)
  case Softening::linear: return std::min(1.0, (r - r0) / (2.0 * (gamma - r0)));
  case Softening::exponential: {
    const double rest = std::exp(-(r - r0) / (gamma - r0));
    return rest < exponential_cut ? 1.0 : 1.0 - rest;
  }
  }
  return 1.0;
}

double fading_damage(double d, double r, double r0, Fading fading)
{
  if (d > 0.0) return std::min(1.0, d + fading.advance);
  return r >= r0 ? std::min(1.0, fading.start) : 0.0;
}

std::size_t soften_bonds(Softening law, const PointCloud &cloud, const Families &families, const double *psi,
                         const double *crossing, double onset_release, double fracture_energy, Fading fading,
                         BondState &state, std::vector<std::size_t> &touched_points, double *dissipated,
                         std::size_t n_dissipated)
{
  touched_points.clear();
  const std::size_t W      = state.mask_words;
  std::size_t       broken = 0;
  double           *d      = state.damage.data();
  for (std::size_t i = 0; i < families.n_family; ++i) {
    const std::size_t o = families.offsets[i], m = families.size(i);
    bool              any = false;
    double            taken = 0.0, volume = 0.0; // sum_j V_j Psi_ij (d_new - d_old); sum_j V_j over the bonds with energy (1 / omega_i)
    for (std::size_t q = 0; q < m; ++q) {
      const std::size_t b  = o + q;
      const auto        j  = static_cast<std::size_t>(families.neighbour[b]);
      const double      vj = cloud.volume[j];
      if (psi[b] >= 0.0) volume += vj;
      std::uint64_t      &word = state.intact[i * W + q / 64];
      const std::uint64_t bit  = std::uint64_t{1} << (q % 64);
      const std::int32_t  back = families.reverse[b];
      if (!(word & bit) || back < 0) continue; // j's owner decides (failure.hpp)
      const double e = std::max(psi[b], 0.0) / cloud.family_volume[i] +
                       std::max(psi[static_cast<std::size_t>(back)], 0.0) / cloud.family_volume[j];
      const double r    = 0.5 * e * (crossing[i] + crossing[j]);
      const double next = law == Softening::time ? fading_damage(d[b], r, onset_release, fading)
                                                 : softening_damage(law, r, onset_release, fracture_energy);
      if (!(next > d[b])) continue;
      if (psi[b] > 0.0) taken += vj * psi[b] * (next - d[b]);
      d[b] = next;
      if (next >= 1.0) {
        word &= ~bit;
        broken += i < n_dissipated;
        any = true;
      }
    }
    if (any) touched_points.push_back(i);
    if (i < n_dissipated && volume > 0.0) dissipated[i] += cloud.volume[i] * taken / volume;
  }
  return broken;
}

} // namespace bapd
