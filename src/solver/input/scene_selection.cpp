// The points the scene names, found among a rank's owned points at run time: the
// points a load set holds (LoadSetSelect) and the point a probe reads (ProbeLocate,
// the same point on any number of ranks). The solver and the tests call these.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bapd/solver/input/scene.hpp"

namespace bapd {

namespace {

// Squared distance from (px, py) to the segment (x0, y0)-(x1, y1) (a point when the
// two ends coincide).
double SegmentDistance2(const double *s, double px, double py)
{
  const double ex = s[2] - s[0], ey = s[3] - s[1], wx = px - s[0], wy = py - s[1], len2 = ex * ex + ey * ey;
  const double t  = len2 > 0 ? std::clamp((wx * ex + wy * ey) / len2, 0.0, 1.0) : 0.0;
  const double dx = wx - t * ex, dy = wy - t * ey;
  return dx * dx + dy * dy;
}

// Whether (px, py) lies closer than the set's depth to one of its segments.
bool NearSegments(const LoadSet &set, double px, double py)
{
  if (px < set.reach[0] || px > set.reach[2] || py < set.reach[1] || py > set.reach[3]) return false; // most points
  const double d2 = set.depth * set.depth;
  for (std::size_t k = 0; k + 4 <= set.segments.size(); k += 4)
    if (SegmentDistance2(&set.segments[k], px, py) < d2) return true;
  return false;
}

} // namespace

void SetCurveReach(LoadSet *set)
{
  double *r = set->reach;
  r[0] = r[1] = std::numeric_limits<double>::max();
  r[2] = r[3] = -std::numeric_limits<double>::max();
  for (std::size_t k = 0; k + 2 <= set->segments.size(); k += 2) {
    r[0] = std::min(r[0], set->segments[k] - set->depth), r[2] = std::max(r[2], set->segments[k] + set->depth);
    r[1] = std::min(r[1], set->segments[k + 1] - set->depth), r[3] = std::max(r[3], set->segments[k + 1] + set->depth);
  }
}

std::vector<double> BlockPoints(const Body2D &body, int64_t block)
{
  std::vector<std::pair<double, double>> found;
  if (body.given_points)
    for (std::size_t p = 0; p < body.given_points->size(); ++p)
      if (body.given_points->block[p] == block) found.emplace_back(body.given_points->x[2 * p], body.given_points->x[2 * p + 1]);
  std::sort(found.begin(), found.end());
  std::vector<double> out;
  out.reserve(2 * found.size());
  for (const auto &[x, y] : found) out.insert(out.end(), {x, y});
  return out;
}

std::string BlockIdList(const std::vector<int64_t> &block)
{
  std::vector<int64_t> ids(block);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::string list;
  for (std::size_t k = 0; k < ids.size() && k < 20; ++k) list += (k ? ", " : "") + std::to_string(ids[k]);
  return ids.size() > 20 ? list + ", ..." : list;
}

std::string BlockIdList(const Body2D &body) { return body.given_points ? BlockIdList(body.given_points->block) : ""; }

std::vector<double> BlockPoints3D(const std::vector<double> &x, const std::vector<int64_t> &block, int64_t id)
{
  std::vector<std::array<double, 3>> found;
  for (std::size_t p = 0; p < block.size(); ++p)
    if (block[p] == id) found.push_back({x[3 * p], x[3 * p + 1], x[3 * p + 2]});
  std::sort(found.begin(), found.end());
  std::vector<double> out;
  out.reserve(3 * found.size());
  for (const auto &q : found) out.insert(out.end(), q.begin(), q.end());
  return out;
}

namespace {

// Whether p (D coordinates) is one of the sorted D-tuples of `points`: a binary search,
// exact comparison (BlockPoints).
template <int D> bool AmongSorted(const std::vector<double> &points, const double *p)
{
  const auto less = [](const double *a, const double *b) { return std::lexicographical_compare(a, a + D, b, b + D); };
  const std::size_t n  = points.size() / D;
  std::size_t       lo = 0, hi = n;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (less(&points[D * mid], p)) lo = mid + 1;
    else hi = mid;
  }
  return lo < n && std::equal(p, p + D, &points[D * lo]);
}

// 3D: the face regions hold the points within `layers` rows of the body's extent
// (Body3D::lo, hi: lattice points sit (i + 1/2) dx inside it), as the 2D edges inside.
bool FaceContains(const Scene &scene, const LoadSet &set, const double *p)
{
  const Body3D &b = scene.body3d;
  const double  depth = set.layers * b.solid.dx;
  switch (set.region) {
  case LoadSet::Region::left: return p[0] < b.lo[0] + depth;
  case LoadSet::Region::right: return p[0] > b.hi[0] - depth;
  case LoadSet::Region::bottom: return p[1] < b.lo[1] + depth;
  case LoadSet::Region::top: return p[1] > b.hi[1] - depth;
  case LoadSet::Region::back: return p[2] < b.lo[2] + depth;
  case LoadSet::Region::front: return p[2] > b.hi[2] - depth;
  default: return false;
  }
}

} // namespace

template <int D> bool LoadSetContains(const Scene &scene, const LoadSet &set, const double *p)
{
  const double px = p[0], py = p[1];
  if constexpr (D == 3) {
    switch (set.region) {
    case LoadSet::Region::box:
      for (int r = 0; r < 3; ++r)
        if (!(p[r] >= set.box[r] && p[r] <= set.box[3 + r])) return false;
      return true;
    case LoadSet::Region::block: return AmongSorted<3>(set.block_points, p);
    case LoadSet::Region::group: return nd::region_contains(set.elements, p);
    default: return FaceContains(scene, set, p); // (polygon, curve: refused in 3D by CheckLoading)
    }
  }
  const Body2D &b     = scene.body;
  const double  depth = set.layers * b.dx; // layer boundaries fall half-way between lattice rows
  if (set.placement == GripPlacement::outside) switch (set.region) {
    case LoadSet::Region::top: return py > b.height && py < b.height + depth;
    case LoadSet::Region::bottom: return py < 0 && py > -depth;
    case LoadSet::Region::left: return px < 0 && px > -depth;
    case LoadSet::Region::right: return px > b.width && px < b.width + depth;
    default: return false; // (only edge grips are placed outside)
    }
  switch (set.region) {
    // (not the rows of other grips placed outside the sheet)
  case LoadSet::Region::top: return py > b.height - depth && py < b.height;
  case LoadSet::Region::bottom: return py < depth && py > 0;
  case LoadSet::Region::left: return px < depth && px > 0;
  case LoadSet::Region::right: return px > b.width - depth && px < b.width;
  case LoadSet::Region::box: return px >= set.box[0] && px <= set.box[2] && py >= set.box[1] && py <= set.box[3];
  case LoadSet::Region::polygon: return shape_contains(set.area, px, py);
  case LoadSet::Region::curve: return NearSegments(set, px, py);
  case LoadSet::Region::group: return set.segments.empty() ? shape_contains(set.area, px, py) : NearSegments(set, px, py);
  case LoadSet::Region::block: return AmongSorted<2>(set.block_points, p);
  case LoadSet::Region::front:
  case LoadSet::Region::back: return false; // (3D only: CheckLoading refuses them in 2D)
  }
  return false;
}
template bool LoadSetContains<2>(const Scene &, const LoadSet &, const double *);
template bool LoadSetContains<3>(const Scene &, const LoadSet &, const double *);

namespace {
template <int D> void Select(const Scene &scene, const LoadSet &set, const double *x, PetscInt n, std::vector<PetscInt> *selected)
{
  selected->clear();
  for (PetscInt i = 0; i < n; ++i)
    if (LoadSetContains<D>(scene, set, x + D * i)) selected->push_back(i);
}
} // namespace

PetscErrorCode LoadSetSelect(const Scene &scene, const LoadSet &set, const double *x, PetscInt n, std::vector<PetscInt> *selected)
{
  PetscFunctionBeginUser;
  if (scene.dimension == 3) Select<3>(scene, set, x, n, selected);
  else Select<2>(scene, set, x, n, selected);
  PetscFunctionReturn(0);
}

template <int D>
PetscErrorCode ProbeLocate(MPI_Comm comm, const Probe &probe, const double *x, const int64_t *natural_id, PetscInt n, ProbeLocation *location)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  double   best_d2 = std::numeric_limits<double>::max();
  int64_t  best_id = std::numeric_limits<int64_t>::max();
  PetscInt best    = -1;
  for (PetscInt i = 0; i < n; ++i) {
    const double dx = x[D * i] - probe.x, dy = x[D * i + 1] - probe.y;
    double       d2 = dx * dx + dy * dy;
    if constexpr (D == 3) {
      const double dz = x[D * i + 2] - probe.z;
      d2              = d2 + dz * dz;
    }
    if (d2 < best_d2 || (d2 == best_d2 && natural_id[i] < best_id)) {
      best_d2 = d2;
      best_id = natural_id[i];
      best    = i;
    }
  }
  // The smallest distance, then the smallest id among the points at that distance:
  // exact comparisons are safe because every rank compares the same stored values.
  double d2min = best_d2;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &d2min, 1, MPI_DOUBLE, MPI_MIN, comm));
  int64_t id = best_d2 == d2min ? best_id : std::numeric_limits<int64_t>::max();
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &id, 1, MPI_INT64_T, MPI_MIN, comm));
  PetscMPIInt mine = (best >= 0 && best_id == id && best_d2 == d2min) ? rank : -1, owner = -1;
  PetscCallMPI(MPI_Allreduce(&mine, &owner, 1, MPI_INT, MPI_MAX, comm));
  PetscCheck(owner >= 0, comm, PETSC_ERR_ARG_WRONG, "ProbeLocate: probe '%s' found no material point: no rank passed any point",
             probe.name.c_str());
  location->owner       = owner;
  location->natural_id  = id;
  location->local_index = owner == rank ? best : -1;
  location->distance    = std::sqrt(d2min);
  PetscFunctionReturn(0);
}
template PetscErrorCode ProbeLocate<2>(MPI_Comm, const Probe &, const double *, const int64_t *, PetscInt, ProbeLocation *);
template PetscErrorCode ProbeLocate<3>(MPI_Comm, const Probe &, const double *, const int64_t *, PetscInt, ProbeLocation *);

} // namespace bapd
