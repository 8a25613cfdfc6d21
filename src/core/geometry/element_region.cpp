// Element regions (shape3d.hpp): the distance of a point to a segment or a triangle,
// and whether a region of a mesh's elements (tetrahedra, or triangles and segments
// grown by a depth) holds a point.
#include <algorithm>
#include <array>
#include <limits>

#include "bapd/core/geometry/shape3d.hpp"

namespace bapd::nd {

namespace {

using P3 = std::array<double, 3>;

double dot(const P3 &u, const P3 &v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }
P3     minus(const double *u, const double *v) { return {u[0] - v[0], u[1] - v[1], u[2] - v[2]}; }

} // namespace

double point_segment_distance2(const double *p, const double *a, const double *b)
{
  const P3     e = minus(b, a), w = minus(p, a);
  const double len2 = dot(e, e);
  const double t    = len2 > 0 ? std::clamp(dot(w, e) / len2, 0.0, 1.0) : 0.0;
  const P3     d    = {w[0] - t * e[0], w[1] - t * e[1], w[2] - t * e[2]};
  return dot(d, d);
}

double point_triangle_distance2(const double *p, const double *a, const double *b, const double *c)
{
  // The closest point by the Voronoi regions of the vertices, edges and face.
  const P3     ab = minus(b, a), ac = minus(c, a), ap = minus(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return dot(ap, ap); // vertex a
  const P3     bp = minus(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dot(bp, bp); // vertex b
  const P3     cp = minus(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dot(cp, cp); // vertex c
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return point_segment_distance2(p, a, b); // edge ab
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return point_segment_distance2(p, a, c); // edge ac
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return point_segment_distance2(p, b, c); // edge bc
  const double sum = va + vb + vc;
  if (!(sum > 0)) // a degenerate triangle: its nearest edge
    return std::min({point_segment_distance2(p, a, b), point_segment_distance2(p, a, c), point_segment_distance2(p, b, c)});
  const double v = vb / sum, w = vc / sum; // the face: a + v ab + w ac
  const P3     d = {ap[0] - v * ab[0] - w * ac[0], ap[1] - v * ab[1] - w * ac[1], ap[2] - v * ab[2] - w * ac[2]};
  return dot(d, d);
}

void set_reach(ElementRegion &region)
{
  const std::vector<double> &v = region.dim == 3 ? region.tetrahedra->corners : region.dim == 2 ? region.triangles : region.segments;
  const double grow = region.dim == 3 ? 0.0 : region.depth;
  region.lo.fill(std::numeric_limits<double>::max());
  region.hi.fill(-std::numeric_limits<double>::max());
  for (std::size_t k = 0; k + 3 <= v.size(); k += 3)
    for (int r = 0; r < 3; ++r) region.lo[r] = std::min(region.lo[r], v[k + r] - grow), region.hi[r] = std::max(region.hi[r], v[k + r] + grow);
}

bool region_contains(const ElementRegion &region, const double *p)
{
  for (int r = 0; r < 3; ++r)
    if (p[r] < region.lo[r] || p[r] > region.hi[r]) return false; // most points
  if (region.dim == 3) return tetrahedra_contain(*region.tetrahedra, p);
  const double d2 = region.depth * region.depth;
  const auto   near_box = [&](const double *c, int corners) { // the element's box grown by depth
    for (int r = 0; r < 3; ++r) {
      double lo = c[r], hi = c[r];
      for (int k = 1; k < corners; ++k) lo = std::min(lo, c[3 * k + r]), hi = std::max(hi, c[3 * k + r]);
      if (p[r] < lo - region.depth || p[r] > hi + region.depth) return false;
    }
    return true;
  };
  if (region.dim == 2) {
    for (std::size_t k = 0; k + 9 <= region.triangles.size(); k += 9) {
      const double *t = &region.triangles[k];
      if (near_box(t, 3) && point_triangle_distance2(p, t, t + 3, t + 6) < d2) return true;
    }
    return false;
  }
  for (std::size_t k = 0; k + 6 <= region.segments.size(); k += 6) {
    const double *s = &region.segments[k];
    if (near_box(s, 2) && point_segment_distance2(p, s, s + 3) < d2) return true;
  }
  return false;
}

} // namespace bapd::nd
