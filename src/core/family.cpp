#include "bapd/family.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace bapd {

namespace {

// |a - b|^2 with the differences taken as b - a: the same bits for (a, b) and (b, a),
// so "j in family(i)" and "i in family(j)" are decided identically.
inline double distance_squared(const double *x, std::size_t a, std::size_t b)
{
  const double d0 = x[2 * b] - x[2 * a];
  const double d1 = x[2 * b + 1] - x[2 * a + 1];
  return d0 * d0 + d1 * d1;
}

// Orientation of c relative to the directed line a -> b (twice the signed area).
inline double orientation(double ax, double ay, double bx, double by, double cx, double cy)
{
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

void check_cloud(const PointCloud &cloud)
{
  const std::size_t n = cloud.size();
  if (cloud.x.size() != 2 * n || cloud.natural_id.size() != n)
    throw std::invalid_argument("PointCloud: x must hold 2 and natural_id 1 entry per volume entry");
  if (!cloud.horizon.empty() && cloud.horizon.size() != n)
    throw std::invalid_argument("PointCloud: horizon must be empty or hold 1 entry per volume entry");
  for (double h : cloud.horizon)
    if (!(h > 0) || !std::isfinite(h))
      throw std::invalid_argument("build_families: a point's horizon must be a positive number (got " + std::to_string(h) + ")");
}

// The squared reach of bond (a, b): max(delta_a, delta_b)^2 with per-point horizons
// (geometry.hpp: a bond exists where either horizon reaches; symmetric in a and b),
// else the one horizon's square.
inline double reach_squared(const double *point_horizon, double h2, std::size_t a, std::size_t b)
{
  if (!point_horizon) return h2;
  const double r = std::max(point_horizon[a], point_horizon[b]);
  return r * r;
}

} // namespace

bool segments_cross(double ax, double ay, double bx, double by, const Segment &s)
{
  const double o1 = orientation(ax, ay, bx, by, s.x0, s.y0);
  const double o2 = orientation(ax, ay, bx, by, s.x1, s.y1);
  const double o3 = orientation(s.x0, s.y0, s.x1, s.y1, ax, ay);
  const double o4 = orientation(s.x0, s.y0, s.x1, s.y1, bx, by);
  return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

Families build_families(const PointCloud &cloud, std::size_t n_family, double horizon,
                        const std::vector<Segment> &notches)
{
  check_cloud(cloud);
  const std::size_t n = cloud.size();
  if (!(horizon > 0) || !std::isfinite(horizon))
    throw std::invalid_argument("build_families: the horizon must be a positive number (got " +
                                std::to_string(horizon) + ")");
  if (n_family > n)
    throw std::invalid_argument("build_families: n_family = " + std::to_string(n_family) +
                                " exceeds the number of points " + std::to_string(n));
  const double *x  = cloud.x.data();
  const double  h2 = horizon * horizon;
  // Per-point horizons (geometry.hpp): the largest sets the cell list's cells.
  const double *point_horizon = cloud.horizon.empty() ? nullptr : cloud.horizon.data();
  const double  reach         = point_horizon ? *std::max_element(cloud.horizon.begin(), cloud.horizon.end()) : horizon;

  Families fam;
  fam.n_family = n_family;
  fam.horizon  = reach;
  fam.offsets.assign(n_family + 1, 0);
  if (n == 0) return fam;

  // Cell list over ALL points (ghosts included), cells at least one horizon wide so
  // that a 3 x 3 block of cells covers a family; widened if the box is sparse.
  double xmin = x[0], xmax = x[0], ymin = x[1], ymax = x[1];
  for (std::size_t i = 0; i < n; ++i) {
    xmin = std::min(xmin, x[2 * i]);
    xmax = std::max(xmax, x[2 * i]);
    ymin = std::min(ymin, x[2 * i + 1]);
    ymax = std::max(ymax, x[2 * i + 1]);
  }
  double cell = reach;
  auto   cells_along = [&](double extent) { return static_cast<std::size_t>(extent / cell) + 1; };
  while (static_cast<double>(cells_along(xmax - xmin)) * static_cast<double>(cells_along(ymax - ymin)) >
         8.0 * static_cast<double>(n) + 64.0)
    cell *= 2.0;
  const std::size_t ncx = cells_along(xmax - xmin), ncy = cells_along(ymax - ymin);
  auto cell_of = [&](std::size_t i, std::size_t &cx, std::size_t &cy) {
    cx = std::min(ncx - 1, static_cast<std::size_t>((x[2 * i] - xmin) / cell));
    cy = std::min(ncy - 1, static_cast<std::size_t>((x[2 * i + 1] - ymin) / cell));
  };
  std::vector<std::size_t> cell_start(ncx * ncy + 1, 0), cell_points(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t cx, cy;
    cell_of(i, cx, cy);
    ++cell_start[cy * ncx + cx + 1];
  }
  for (std::size_t c = 0; c < ncx * ncy; ++c) cell_start[c + 1] += cell_start[c];
  {
    std::vector<std::size_t> fill(cell_start.begin(), cell_start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t cx, cy;
      cell_of(i, cx, cy);
      cell_points[fill[cy * ncx + cx]++] = i;
    }
  }

  // Families, sorted by natural id.
  std::vector<std::int32_t> candidates;
  for (std::size_t i = 0; i < n_family; ++i) {
    candidates.clear();
    std::size_t cx, cy;
    cell_of(i, cx, cy);
    for (std::size_t gy = (cy > 0 ? cy - 1 : 0); gy <= std::min(ncy - 1, cy + 1); ++gy)
      for (std::size_t gx = (cx > 0 ? cx - 1 : 0); gx <= std::min(ncx - 1, cx + 1); ++gx) {
        const std::size_t c = gy * ncx + gx;
        for (std::size_t s = cell_start[c]; s < cell_start[c + 1]; ++s) {
          const std::size_t j = cell_points[s];
          if (j == i || distance_squared(x, i, j) > reach_squared(point_horizon, h2, i, j)) continue;
          // Canonical order (lower natural id first) so that (i, j) and (j, i) get the
          // same crossing decision bit for bit.
          const bool   i_first = cloud.natural_id[i] < cloud.natural_id[j];
          const std::size_t a = i_first ? i : j, b = i_first ? j : i;
          bool cut = false;
          for (const Segment &s : notches)
            if (segments_cross(x[2 * a], x[2 * a + 1], x[2 * b], x[2 * b + 1], s)) { cut = true; break; }
          if (!cut) candidates.push_back(static_cast<std::int32_t>(j));
        }
      }
    std::sort(candidates.begin(), candidates.end(), [&](std::int32_t a, std::int32_t b) {
      return cloud.natural_id[static_cast<std::size_t>(a)] < cloud.natural_id[static_cast<std::size_t>(b)];
    });
    for (std::size_t p = 1; p < candidates.size(); ++p)
      if (cloud.natural_id[static_cast<std::size_t>(candidates[p])] ==
          cloud.natural_id[static_cast<std::size_t>(candidates[p - 1])])
        throw std::invalid_argument("build_families: natural id " +
                                    std::to_string(cloud.natural_id[static_cast<std::size_t>(candidates[p])]) +
                                    " appears twice in the point cloud");
    if (fam.neighbour.size() + candidates.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
      throw std::runtime_error("build_families: more than 2^31 bonds on this rank; use more ranks");
    fam.neighbour.insert(fam.neighbour.end(), candidates.begin(), candidates.end());
    fam.offsets[i + 1]  = fam.neighbour.size();
    fam.max_family_size = std::max(fam.max_family_size, candidates.size());
  }

  // BA masks: bit p of bond (i -> j) iff |x_k - x_j| <= horizon for the p-th member k
  // (max(delta_j, delta_k) with per-point horizons: k is in H_j).
  const std::size_t W = std::max<std::size_t>(1, (fam.max_family_size + 63) / 64);
  fam.mask_words      = W;
  fam.ba_mask.assign(fam.n_bonds() * W, 0);
  for (std::size_t i = 0; i < n_family; ++i) {
    const std::size_t o = fam.offsets[i], m = fam.size(i);
    for (std::size_t q = 0; q < m; ++q) {
      const std::size_t j    = static_cast<std::size_t>(fam.neighbour[o + q]);
      std::uint64_t    *mask = fam.ba_mask.data() + (o + q) * W;
      for (std::size_t p = 0; p < m; ++p) {
        const std::size_t k = static_cast<std::size_t>(fam.neighbour[o + p]);
        if (distance_squared(x, j, k) <= reach_squared(point_horizon, h2, j, k)) mask[p / 64] |= std::uint64_t{1} << (p % 64);
      }
    }
  }

  // Reverse index: bond (j -> i), found by natural id in j's sorted family.
  fam.reverse.assign(fam.n_bonds(), -1);
  for (std::size_t i = 0; i < n_family; ++i)
    for (std::size_t b = fam.offsets[i]; b < fam.offsets[i + 1]; ++b) {
      const std::size_t j = static_cast<std::size_t>(fam.neighbour[b]);
      if (j >= n_family) continue;
      const auto first = fam.neighbour.begin() + static_cast<std::ptrdiff_t>(fam.offsets[j]);
      const auto last  = fam.neighbour.begin() + static_cast<std::ptrdiff_t>(fam.offsets[j + 1]);
      const auto it    = std::lower_bound(first, last, cloud.natural_id[i], [&](std::int32_t k, int64_t id) {
        return cloud.natural_id[static_cast<std::size_t>(k)] < id;
      });
      if (it == last || static_cast<std::size_t>(*it) != i)
        throw std::runtime_error("build_families: point with natural id " + std::to_string(cloud.natural_id[j]) +
                                 " lacks the reverse bond to natural id " + std::to_string(cloud.natural_id[i]));
      fam.reverse[b] = static_cast<std::int32_t>(it - fam.neighbour.begin());
    }
  return fam;
}

void compute_family_volumes(PointCloud &cloud, const Families &families)
{
  if (cloud.family_volume.size() != cloud.size())
    cloud.family_volume.resize(cloud.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < families.n_family; ++i) {
    double v = 0.0;
    for (std::size_t b = families.offsets[i]; b < families.offsets[i + 1]; ++b)
      v += cloud.volume[static_cast<std::size_t>(families.neighbour[b])];
    cloud.family_volume[i] = v;
  }
}

} // namespace bapd
