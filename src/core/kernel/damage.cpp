// Bond failure and damage (damage.hpp), for D = 2 and 3.
#include <algorithm>
#include <cmath>
#include <limits>

#include "bapd/core/kernel/damage.hpp"

namespace bapd {

namespace {
void sort_unique(std::vector<std::size_t> &v)
{
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}
} // namespace

namespace detail {
// Breaks, for good, every intact bond (i -> j) of the family points for which
// breaks(i, bond index, j) holds; touched_points (cleared): the points with a newly
// broken bond, ascending, one entry each ((j, i) breaks in j's own pass when j has a
// family here). Returns the directed bonds broken at points [0, n_counted).
template <class Breaks>
std::size_t break_intact_bonds(const Families &families, BondState &state, std::vector<std::size_t> &touched_points,
                               std::size_t n_counted, Breaks &&breaks)
{
  touched_points.clear();
  const std::size_t W      = state.mask_words;
  std::size_t       broken = 0;
  for (std::size_t i = 0; i < families.n_family; ++i) {
    const std::size_t o = families.offsets[i], m = families.size(i);
    bool              any = false;
    for (std::size_t q = 0; q < m; ++q) {
      std::uint64_t      &word = state.intact[i * W + q / 64];
      const std::uint64_t bit  = std::uint64_t{1} << (q % 64);
      if (!(word & bit) || !breaks(i, o + q, static_cast<std::size_t>(families.neighbour[o + q]))) continue;
      word &= ~bit;
      broken += i < n_counted;
      any = true;
    }
    if (any) touched_points.push_back(i);
  }
  return broken;
}
} // namespace detail

// Each failed bond appends its two end points, so a step in which many bonds fail
// (a whole sheet at the chain limit: up to n_family * family size of them) would
// outgrow any reserve sized by points before the list is made unique. It is made
// unique whenever it is full instead: it then holds each point at most once, plus the
// next bond's two, so a reserve of the points touched plus two is never outgrown (no
// allocation in a time step; the solver reserves n_local + 2 n_family). Only a list
// reserved for fewer points than the step touches grows, by doubling.
std::size_t break_failed_bonds(const Families &families, BondState &state, const std::vector<FailedBond> &failed,
                               std::vector<std::size_t> &touched_points)
{
  std::size_t broken = 0;
  for (const FailedBond &f : failed) {
    if (touched_points.capacity() - touched_points.size() < 2) {
      sort_unique(touched_points);
      if (2 * touched_points.size() > touched_points.capacity()) touched_points.reserve(2 * touched_points.capacity() + 2);
    }
    broken += break_bond(families, state, f.point, f.position, &touched_points);
  }
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

void crack_extent(int dimension, const PointCloud &cloud, const Families &families, const BondState &state,
                  const double *crossing, std::size_t n_points, const double *origin, const double *direction,
                  double *point_area, double tip[4])
{
  std::fill(tip, tip + 4, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n_points; ++i) {
    const std::size_t o = families.offsets[i];
    point_area[i]       = 0.0;
    for (std::size_t q = 0; q < families.size(i); ++q) {
      if (state.is_intact(i, q)) continue;
      const auto j = static_cast<std::size_t>(families.neighbour[o + q]);
      point_area[i] += cloud.volume[i] * cloud.volume[j] / (crossing[i] + crossing[j]); // 1/2 V_i V_j / ((c_i + c_j) / 2)
      double m[4] = {0, 0, 0, 0};
      for (int r = 0; r < dimension; ++r) {
        m[1 + r] = 0.5 * (cloud.x[dimension * i + r] + cloud.x[dimension * j + r]);
        m[0] += (m[1 + r] - origin[r]) * direction[r];
      }
      if (std::lexicographical_compare(tip, tip + 1 + dimension, m, m + 1 + dimension)) std::copy(m, m + 4, tip);
    }
  }
}

double crossing_density(int dimension, double volume, double horizon, double thickness)
{
  const double h = dimension == 2 ? std::sqrt(volume / thickness) : std::cbrt(volume);
  const int    R = static_cast<int>(std::floor(horizon / h)); // |xi_k| <= R h on a lattice axis
  const double reach2 = horizon * horizon;
  double       sum    = 0.0; // sum over the lattice vectors xi = h (a, b[, c]) of |xi . e_1|
  for (int a = -R; a <= R; ++a)
    for (int b = -R; b <= R; ++b)
      for (int c = dimension == 3 ? -R : 0; c <= (dimension == 3 ? R : 0); ++c) {
        const double r2 = h * h * (double(a) * a + double(b) * b + double(c) * c);
        if (r2 > 0 && r2 <= reach2) sum += h * std::abs(a);
      }
  return 0.5 * sum * volume;
}

std::size_t break_bonds_by_energy(const PointCloud &cloud, const Families &families, const double *psi,
                                  const double *crossing, double critical_release, BondState &state,
                                  std::vector<std::size_t> &touched_points, std::size_t n_counted)
{
  return detail::break_intact_bonds(families, state, touched_points, n_counted,
                                    [&](std::size_t i, std::size_t b, std::size_t j) {
                                      const std::int32_t back = families.reverse[b];
                                      if (back < 0) return false; // j's owner decides (failure.hpp)
                                      const double e = std::max(psi[b], 0.0) / cloud.family_volume[i] +
                                                       std::max(psi[static_cast<std::size_t>(back)], 0.0) / cloud.family_volume[j];
                                      return e * (crossing[i] + crossing[j]) >= 2.0 * critical_release;
                                    });
}

} // namespace bapd

namespace bapd::nd {

template <int D>
std::size_t break_bonds(const PointCloud &cloud, const double *y, const Families &families, double critical_stretch,
                        BondState &state, std::vector<std::size_t> &touched_points, std::size_t n_counted)
{
  const double *x   = cloud.x.data();
  const double  sc2 = critical_stretch * critical_stretch;
  return detail::break_intact_bonds(families, state, touched_points, n_counted,
                                    [&](std::size_t i, std::size_t, std::size_t j) {
                                      double reference = 0.0, current = 0.0; // |x_j - x_i|^2, |y_j - y_i|^2, axis by axis
                                      for (int r = 0; r < D; ++r) {
                                        const double d = x[D * j + r] - x[D * i + r], e = y[D * j + r] - y[D * i + r];
                                        reference += d * d;
                                        current += e * e;
                                      }
                                      return current > sc2 * reference;
                                    });
}

template std::size_t break_bonds<2>(const PointCloud &, const double *, const Families &, double, BondState &,
                                    std::vector<std::size_t> &, std::size_t);
template std::size_t break_bonds<3>(const PointCloud &, const double *, const Families &, double, BondState &,
                                    std::vector<std::size_t> &, std::size_t);

} // namespace bapd::nd
