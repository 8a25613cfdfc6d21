// Families (family.hpp): one cell-list builder for D = 2 and 3 (nd::build_families<D>,
// instantiated for both); the 2D entry point is it with the notch segments as its bond
// cut. Then the family volumes.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "bapd/core/geometry/family.hpp"

namespace bapd {

namespace {

// Orientation of c relative to the directed line a -> b (twice the signed area).
inline double orientation(double ax, double ay, double bx, double by, double cx, double cy)
{
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
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
  nd::BondCut cut; // empty without notches: no call per bond
  if (!notches.empty())
    cut = [&notches](const double *a, const double *b) {
      for (const Segment &s : notches)
        if (segments_cross(a[0], a[1], b[0], b[1], s)) return true;
      return false;
    };
  return nd::build_families<2>(cloud, n_family, horizon, cut);
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

namespace bapd::nd {

namespace {

// |x_b - x_a|^2 with the differences taken as b - a, summed axis by axis: for D = 2 the
// arithmetic of family.cpp, so both builders decide every bond identically.
template <int D> inline double distance_squared(const double *x, std::size_t a, std::size_t b)
{
  double s = 0.0;
  for (int r = 0; r < D; ++r) {
    const double d = x[D * b + r] - x[D * a + r];
    s += d * d;
  }
  return s;
}

inline double reach_squared(const double *point_horizon, double h2, std::size_t a, std::size_t b)
{
  if (!point_horizon) return h2;
  const double r = std::max(point_horizon[a], point_horizon[b]);
  return r * r;
}

template <int D> void check_cloud(const PointCloud &cloud, std::size_t n_family, double horizon)
{
  const std::size_t n = cloud.size();
  if (cloud.x.size() != D * n || cloud.natural_id.size() != n)
    throw std::invalid_argument("build_families: x must hold " + std::to_string(D) +
                                " and natural_id 1 entry per volume entry");
  if (!cloud.horizon.empty() && cloud.horizon.size() != n)
    throw std::invalid_argument("build_families: horizon must be empty or hold 1 entry per volume entry");
  for (double h : cloud.horizon)
    if (!(h > 0) || !std::isfinite(h))
      throw std::invalid_argument("build_families: a point's horizon must be a positive number (got " +
                                  std::to_string(h) + ")");
  if (!(horizon > 0) || !std::isfinite(horizon))
    throw std::invalid_argument("build_families: the horizon must be a positive number (got " +
                                std::to_string(horizon) + ")");
  if (n_family > n)
    throw std::invalid_argument("build_families: n_family = " + std::to_string(n_family) +
                                " exceeds the number of points " + std::to_string(n));
}

// Cell list over all points, cells one reach wide (widened while the box is sparse,
// so that the cell array stays within ~8 cells a point): the points of cell k are
// points[start[k] .. start[k + 1]).
template <int D> struct CellList {
  const double              *x;
  std::array<double, D>      lo, hi;
  double                     cell;
  std::array<std::size_t, D> nc;
  std::vector<std::size_t>   start, points;

  CellList(const double *x_, std::size_t n, double reach) : x(x_), cell(reach)
  {
    for (int r = 0; r < D; ++r) lo[r] = hi[r] = x[r];
    for (std::size_t i = 0; i < n; ++i)
      for (int r = 0; r < D; ++r) lo[r] = std::min(lo[r], x[D * i + r]), hi[r] = std::max(hi[r], x[D * i + r]);
    auto count_cells = [&]() {
      double total = 1.0;
      for (int r = 0; r < D; ++r) {
        nc[r] = static_cast<std::size_t>((hi[r] - lo[r]) / cell) + 1;
        total *= static_cast<double>(nc[r]);
      }
      return total;
    };
    while (count_cells() > 8.0 * static_cast<double>(n) + 64.0) cell *= 2.0;
    std::size_t n_cells = 1;
    for (int r = 0; r < D; ++r) n_cells *= nc[r];
    start.assign(n_cells + 1, 0);
    points.resize(n);
    std::vector<std::size_t> cell_of(n);
    for (std::size_t i = 0; i < n; ++i) {
      std::array<std::size_t, D> c;
      for (int r = 0; r < D; ++r) c[r] = coord(i, r);
      cell_of[i] = index(c);
      ++start[cell_of[i] + 1];
    }
    for (std::size_t c = 0; c < n_cells; ++c) start[c + 1] += start[c];
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) points[fill[cell_of[i]]++] = i;
  }
  std::size_t coord(std::size_t i, int r) const
  {
    return std::min(nc[r] - 1, static_cast<std::size_t>((x[D * i + r] - lo[r]) / cell));
  }
  std::size_t index(const std::array<std::size_t, D> &c) const
  {
    std::size_t k = 0;
    for (int r = D - 1; r >= 0; --r) k = k * nc[r] + c[r];
    return k;
  }
};

// BA masks (paper eq 8: B_ij = H_i and H_j), as many 64-bit words as the largest family needs.
template <int D> void fill_ba_masks(Families &fam, const double *x, const double *point_horizon, double h2)
{
  const std::size_t W = std::max<std::size_t>(1, (fam.max_family_size + 63) / 64);
  fam.mask_words      = W;
  fam.ba_mask.assign(fam.n_bonds() * W, 0);
  for (std::size_t i = 0; i < fam.n_family; ++i) {
    const std::size_t o = fam.offsets[i], m = fam.size(i);
    for (std::size_t q = 0; q < m; ++q) {
      const std::size_t j    = static_cast<std::size_t>(fam.neighbour[o + q]);
      std::uint64_t    *mask = fam.ba_mask.data() + (o + q) * W;
      for (std::size_t p = 0; p < m; ++p) {
        const std::size_t k = static_cast<std::size_t>(fam.neighbour[o + p]);
        if (distance_squared<D>(x, j, k) <= reach_squared(point_horizon, h2, j, k))
          mask[p / 64] |= std::uint64_t{1} << (p % 64);
      }
    }
  }
}

// Reverse index: bond (j -> i), found by natural id in j's sorted family.
void fill_reverse_index(Families &fam, const PointCloud &cloud)
{
  const std::size_t n_family = fam.n_family;
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
}

} // namespace

template <int D>
Families build_families(const PointCloud &cloud, std::size_t n_family, double horizon, const BondCut &cut)
{
  check_cloud<D>(cloud, n_family, horizon);
  const std::size_t n = cloud.size();
  const double     *x = cloud.x.data(), h2 = horizon * horizon;
  const double     *point_horizon = cloud.horizon.empty() ? nullptr : cloud.horizon.data();
  const double reach = point_horizon ? *std::max_element(cloud.horizon.begin(), cloud.horizon.end()) : horizon;

  Families fam;
  fam.n_family = n_family;
  fam.horizon  = reach;
  fam.offsets.assign(n_family + 1, 0);
  if (n == 0) return fam;

  const CellList<D> cells(x, n, reach);

  std::vector<std::int32_t> candidates;
  for (std::size_t i = 0; i < n_family; ++i) {
    candidates.clear();
    std::array<std::size_t, D> c, first, last, g;
    for (int r = 0; r < D; ++r) {
      c[r]     = cells.coord(i, r);
      first[r] = c[r] > 0 ? c[r] - 1 : 0;
      last[r]  = std::min(cells.nc[r] - 1, c[r] + 1);
    }
    g = first;
    for (;;) { // the 3^D block of cells around i (clipped to the grid)
      const std::size_t k = cells.index(g);
      for (std::size_t s = cells.start[k]; s < cells.start[k + 1]; ++s) {
        const std::size_t j = cells.points[s];
        if (j == i || distance_squared<D>(x, i, j) > reach_squared(point_horizon, h2, i, j)) continue;
        if (cut) {
          const bool        i_first = cloud.natural_id[i] < cloud.natural_id[j];
          const std::size_t a = i_first ? i : j, b = i_first ? j : i;
          if (cut(x + D * a, x + D * b)) continue;
        }
        candidates.push_back(static_cast<std::int32_t>(j));
      }
      int r = 0;
      while (r < D && g[r] == last[r]) g[r] = first[r], ++r;
      if (r == D) break;
      ++g[r];
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

  fill_ba_masks<D>(fam, x, point_horizon, h2);
  fill_reverse_index(fam, cloud);
  return fam;
}

template <int D> PointCloud box_lattice(const std::array<int, D> &cells, double dx, double thickness)
{
  if (!(dx > 0) || !(thickness > 0))
    throw std::invalid_argument("nd::box_lattice: dx and thickness must be > 0");
  std::size_t n = 1;
  for (int r = 0; r < D; ++r) {
    if (cells[r] < 1) throw std::invalid_argument("nd::box_lattice: every axis needs at least one cell");
    n *= static_cast<std::size_t>(cells[r]);
  }
  PointCloud c;
  c.x.resize(D * n);
  c.volume.assign(n, D == 2 ? dx * dx * thickness : dx * dx * dx);
  c.natural_id.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t rest = i;
    for (int r = 0; r < D; ++r) {
      const std::size_t k = rest % static_cast<std::size_t>(cells[r]);
      rest /= static_cast<std::size_t>(cells[r]);
      c.x[D * i + r] = (static_cast<double>(k) + 0.5) * dx;
    }
    c.natural_id[i] = static_cast<int64_t>(i);
  }
  return c;
}

template Families build_families<2>(const PointCloud &, std::size_t, double, const BondCut &);
template Families build_families<3>(const PointCloud &, std::size_t, double, const BondCut &);
template PointCloud box_lattice<2>(const std::array<int, 2> &, double, double);
template PointCloud box_lattice<3>(const std::array<int, 3> &, double, double);

} // namespace bapd::nd
