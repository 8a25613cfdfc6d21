#include "bapd/damage.hpp"

#include <algorithm>

namespace bapd {

namespace {
void sort_unique(std::vector<std::size_t> &v)
{
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}
} // namespace

std::size_t break_failed_bonds(const Families &families, BondState &state, const std::vector<FailedBond> &failed,
                               std::vector<std::size_t> &touched_points)
{
  std::size_t broken = 0;
  for (const FailedBond &f : failed) broken += break_bond(families, state, f.point, f.position, &touched_points);
  sort_unique(touched_points);
  return broken;
}

void point_damage(const PointCloud &cloud, const Families &families, const BondState &state, std::size_t n_points,
                  double *damage)
{
  for (std::size_t i = 0; i < n_points; ++i) {
    double            intact = 0.0;
    const std::size_t o      = families.offsets[i];
    for (std::size_t q = 0; q < families.size(i); ++q)
      if (state.is_intact(i, q)) intact += cloud.volume[static_cast<std::size_t>(families.neighbour[o + q])];
    const double vh = cloud.family_volume[i];
    damage[i]       = vh > 0 ? 1.0 - intact / vh : 0.0;
  }
}

} // namespace bapd
