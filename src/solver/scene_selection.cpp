// The points the scene names, found among a rank's owned points at run time: the
// points a load set holds (LoadSetSelect) and the point a probe reads (ProbeLocate,
// the same point on any number of ranks). The solver and the tests call these.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "bapd/scene.hpp"

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

std::string BlockIdList(const Body2D &body)
{
  if (!body.given_points) return "";
  std::vector<int64_t> ids(body.given_points->block);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::string list;
  for (std::size_t k = 0; k < ids.size() && k < 20; ++k) list += (k ? ", " : "") + std::to_string(ids[k]);
  return ids.size() > 20 ? list + ", ..." : list;
}

bool LoadSetContains(const Scene &scene, const LoadSet &set, double px, double py)
{
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
  case LoadSet::Region::block: {
    // Binary search over the sorted (x, y) pairs; exact comparison (BlockPoints).
    const std::size_t n = set.block_points.size() / 2;
    std::size_t       lo = 0, hi = n;
    while (lo < hi) {
      const std::size_t mid = (lo + hi) / 2;
      const double      mx = set.block_points[2 * mid], my = set.block_points[2 * mid + 1];
      if (mx < px || (mx == px && my < py)) lo = mid + 1;
      else hi = mid;
    }
    return lo < n && set.block_points[2 * lo] == px && set.block_points[2 * lo + 1] == py;
  }
  }
  return false;
}

PetscErrorCode LoadSetSelect(const Scene &scene, const LoadSet &set, const double *x, PetscInt n, std::vector<PetscInt> *selected)
{
  PetscFunctionBeginUser;
  selected->clear();
  for (PetscInt i = 0; i < n; ++i)
    if (LoadSetContains(scene, set, x[2 * i], x[2 * i + 1])) selected->push_back(i);
  PetscFunctionReturn(0);
}

PetscErrorCode ProbeLocate(MPI_Comm comm, const Probe &probe, const double *x, const int64_t *natural_id, PetscInt n, ProbeLocation *location)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  double   best_d2 = std::numeric_limits<double>::max();
  int64_t  best_id = std::numeric_limits<int64_t>::max();
  PetscInt best    = -1;
  for (PetscInt i = 0; i < n; ++i) {
    const double dx = x[2 * i] - probe.x, dy = x[2 * i + 1] - probe.y, d2 = dx * dx + dy * dy;
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

} // namespace bapd
