// Region curve (2D): the points closer than the set's depth (-load_NAME_depth, or
// -load_NAME_layers x dx) to an open polyline (-load_NAME_points).
#include <algorithm>
#include <limits>

#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/regions/region_registry.hpp"
#include "bapd/solver/input/scene_input.hpp"

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

PetscErrorCode CheckCurve2D(const RegionInput &r, LoadSet *set)
{
  const LoadInput &li = r.li;
  PetscFunctionBeginUser;
  PetscCall(CheckOwnPoints2D(r, set));
  PetscCall(CheckVertices2D(r, *set, 2));
  for (std::size_t k = 0; k + 4 <= li.points.size(); k += 2) set->segments.insert(set->segments.end(), &li.points[k], &li.points[k + 4]);
  PetscCall(CheckVerticesOnBody2D(r, *set, set->depth));
  PetscFunctionReturn(0);
}

bool CurveContains2D(const BodyExtent &, const LoadSet &set, const double *p) { return NearSegments(set, p[0], p[1]); }

std::string CurveText(const BodyExtent &, const LoadSet &l)
{
  return Format("within %g m of a polyline of %zu segments", l.depth, l.segments.size() / 4);
}

std::string CurveEmpty(const BodyExtent &s, const LoadSet &set)
{
  return VerticesEmpty2D(s, set, "raise -load_" + set.name + "_depth or move it onto the body");
}

} // namespace

bool NearSegments(const LoadSet &set, double px, double py)
{
  if (px < set.reach[0] || px > set.reach[2] || py < set.reach[1] || py > set.reach[3]) return false; // most points
  const double d2 = set.depth * set.depth;
  for (std::size_t k = 0; k + 4 <= set.segments.size(); k += 4)
    if (SegmentDistance2(&set.segments[k], px, py) < d2) return true;
  return false;
}

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

RegionType curve_region(LoadSet::Region id, const char *word, const char *alias)
{
  return {id, word, alias, false, uses_points | uses_layers | uses_depth, 0, CheckCurve2D, nullptr, CurveContains2D, nullptr, CurveText, CurveEmpty, "points near a polyline"};
}

} // namespace bapd
