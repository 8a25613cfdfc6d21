// 3D bodies: solids, Gmsh volumes and planar polygon notches (shape3d.hpp); the lattice
// they clip is solid_lattice.cpp.
#include "bapd/core/geometry/shape3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>

#include "bapd/core/enum_words.hpp"

namespace bapd::nd {

namespace {

using P3 = std::array<double, 3>;

double dot(const P3 &u, const P3 &v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }
P3     minus(const double *u, const double *v) { return {u[0] - v[0], u[1] - v[1], u[2] - v[2]}; }

std::string format(const char *fmt, double a)
{
  char text[200];
  std::snprintf(text, sizeof text, fmt, a);
  return text;
}

// A polygon prepared once for the cut test: its unit normal, the plane's offset, the
// two axes it is projected on (the normal's largest component dropped: the projection
// is one to one on the plane) and the projected vertices. The normal is that of the
// widest triangle of the vertices (v0, the vertex farthest from it, the vertex farthest
// from their line), not the area vector, which vanishes for a self-intersecting bow
// tie whose halves cancel (polygon_problem must see its projection to say so).
struct PreparedPolygon {
  P3                  normal{};
  double              offset = 0;     // normal . x on the plane
  double              scale  = 0;     // the largest vertex-to-vertex extent along an axis
  int                 u = 0, v = 1;   // the projection's axes
  std::vector<double> flat;           // 2 per vertex
};

P3 cross(const P3 &a, const P3 &b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }

PreparedPolygon prepare(const PlanarPolygon &polygon)
{
  PreparedPolygon   p;
  const auto       &w = polygon.vertices;
  const std::size_t n = w.size() / 3;
  P3                lo{w[0], w[1], w[2]}, hi = lo;
  std::size_t       far = 0;
  double            far2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (int r = 0; r < 3; ++r) lo[r] = std::min(lo[r], w[3 * i + r]), hi[r] = std::max(hi[r], w[3 * i + r]);
    const P3 d = minus(&w[3 * i], &w[0]);
    if (dot(d, d) > far2) far2 = dot(d, d), far = i;
  }
  const P3 e = minus(&w[3 * far], &w[0]);
  double   widest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const P3 c = cross(e, minus(&w[3 * i], &w[0]));
    if (dot(c, c) > widest) widest = dot(c, c), p.normal = c;
  }
  p.scale            = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double norm  = std::sqrt(dot(p.normal, p.normal));
  if (norm > 0)
    for (double &c : p.normal) c /= norm;
  // The centroid of the vertices lies on the plane of a planar polygon.
  P3 centre{0, 0, 0};
  for (std::size_t i = 0; i < n; ++i)
    for (int r = 0; r < 3; ++r) centre[r] += w[3 * i + r] / static_cast<double>(n);
  p.offset     = dot(p.normal, centre);
  const int dz = std::fabs(p.normal[0]) >= std::fabs(p.normal[1]) && std::fabs(p.normal[0]) >= std::fabs(p.normal[2]) ? 0
                 : std::fabs(p.normal[1]) >= std::fabs(p.normal[2])                                                ? 1
                                                                                                                   : 2;
  p.u = (dz + 1) % 3, p.v = (dz + 2) % 3;
  p.flat.resize(2 * n);
  for (std::size_t i = 0; i < n; ++i) p.flat[2 * i] = w[3 * i + p.u], p.flat[2 * i + 1] = w[3 * i + p.v];
  return p;
}

// Strictly inside the projected polygon: farther than tol from every edge, and inside by
// the even-odd rule.
bool strictly_inside(const std::vector<double> &f, double x, double y, double tol)
{
  const std::size_t n      = f.size() / 2;
  bool              inside = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double xi = f[2 * i], yi = f[2 * i + 1], xj = f[2 * j], yj = f[2 * j + 1];
    const double ex = xj - xi, ey = yj - yi, len2 = ex * ex + ey * ey;
    const double t  = std::clamp(((x - xi) * ex + (y - yi) * ey) / len2, 0.0, 1.0);
    const double qx = x - xi - t * ex, qy = y - yi - t * ey;
    if (qx * qx + qy * qy <= tol * tol) return false; // on the boundary: not cut
    if ((yi > y) != (yj > y) && x < ex * (y - yi) / ey + xi) inside = !inside;
  }
  return inside;
}

bool prepared_cuts(const PreparedPolygon &p, const double *a, const double *b)
{
  // One order of the end points (lexicographic), so that (a, b) and (b, a) do the same
  // arithmetic: the answer is symmetric bit for bit.
  if (std::lexicographical_compare(b, b + 3, a, a + 3)) std::swap(a, b);
  const double tol = 1e-12 * p.scale;
  const double da  = p.normal[0] * a[0] + p.normal[1] * a[1] + p.normal[2] * a[2] - p.offset;
  const double db  = p.normal[0] * b[0] + p.normal[1] * b[1] + p.normal[2] * b[2] - p.offset;
  // Strictly on opposite sides (an end point within round-off of the plane is on it).
  if (!((da > tol && db < -tol) || (da < -tol && db > tol))) return false;
  const double t = da / (da - db);
  const double x = a[p.u] + t * (b[p.u] - a[p.u]), y = a[p.v] + t * (b[p.v] - a[p.v]);
  // The projection shrinks in-plane lengths by at most |n_dropped| >= 1/sqrt(3); the
  // boundary tolerance is round-off either way.
  return strictly_inside(p.flat, x, y, tol);
}

// Six times the signed volume of (a, b, c, d).
double orient(const double *a, const double *b, const double *c, const double *d)
{
  const P3 u = minus(b, a), v = minus(c, a), w = minus(d, a);
  return dot(u, cross(v, w));
}

// Faces inclusive, either orientation: the four sub-volumes' signs agree (zeros allowed).
bool tetrahedron_contains(const double *t, const double *p)
{
  const double d0 = orient(p, t + 3, t + 6, t + 9), d1 = orient(t, p, t + 6, t + 9);
  const double d2 = orient(t, t + 3, p, t + 9), d3 = orient(t, t + 3, t + 6, p);
  const double tol = 1e-12 * std::fabs(orient(t, t + 3, t + 6, t + 9));
  const bool   neg = d0 < -tol || d1 < -tol || d2 < -tol || d3 < -tol, pos = d0 > tol || d1 > tol || d2 > tol || d3 > tol;
  return !(neg && pos);
}

void tetrahedron_range(const TetrahedronSet &set, std::size_t t, std::array<int64_t, 3> &first, std::array<int64_t, 3> &last)
{
  const double *c = &set.corners[12 * t];
  for (int r = 0; r < 3; ++r) {
    const double lo = std::min({c[r], c[3 + r], c[6 + r], c[9 + r]}), hi = std::max({c[r], c[3 + r], c[6 + r], c[9 + r]});
    first[r] = std::clamp(static_cast<int64_t>(std::floor((lo - set.lo[r]) / set.cell)), int64_t{0}, set.count[r] - 1);
    last[r]  = std::clamp(static_cast<int64_t>(std::floor((hi - set.lo[r]) / set.cell)), int64_t{0}, set.count[r] - 1);
  }
}

} // namespace

void index_tetrahedra(TetrahedronSet &set)
{
  const std::size_t n = set.size();
  if (n == 0) return;
  P3 lo{set.corners[0], set.corners[1], set.corners[2]}, hi = lo;
  for (std::size_t k = 0; k < 4 * n; ++k)
    for (int r = 0; r < 3; ++r) lo[r] = std::min(lo[r], set.corners[3 * k + r]), hi[r] = std::max(hi[r], set.corners[3 * k + r]);
  P3 side;
  for (int r = 0; r < 3; ++r) side[r] = std::max(hi[r] - lo[r], 1e-300);
  set.cell = std::cbrt(side[0] * side[1] * side[2] / static_cast<double>(n));
  for (int r = 0; r < 3; ++r) set.count[r] = std::max<int64_t>(1, static_cast<int64_t>(std::ceil(side[r] / set.cell)));
  set.lo = lo;
  // Two passes over the tetrahedra's bounding boxes: count, then fill.
  std::vector<int64_t> count(static_cast<std::size_t>(set.count[0] * set.count[1] * set.count[2]) + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      set.offsets.assign(count.size(), 0);
      for (std::size_t k = 1; k < count.size(); ++k) set.offsets[k] = set.offsets[k - 1] + count[k - 1];
      set.members.assign(static_cast<std::size_t>(set.offsets.back()), 0);
      std::fill(count.begin(), count.end(), 0);
    }
    for (std::size_t t = 0; t < n; ++t) {
      std::array<int64_t, 3> a, b;
      tetrahedron_range(set, t, a, b);
      for (int64_t k = a[2]; k <= b[2]; ++k)
        for (int64_t j = a[1]; j <= b[1]; ++j)
          for (int64_t i = a[0]; i <= b[0]; ++i) {
            const std::size_t q = static_cast<std::size_t>((k * set.count[1] + j) * set.count[0] + i);
            if (pass == 1) set.members[static_cast<std::size_t>(set.offsets[q] + count[q])] = static_cast<int64_t>(t);
            ++count[q];
          }
    }
  }
}

bool tetrahedra_contain(const TetrahedronSet &set, const double *p)
{
  if (set.offsets.empty()) return false;
  std::array<int64_t, 3> b;
  for (int r = 0; r < 3; ++r) {
    const int64_t i = static_cast<int64_t>(std::floor((p[r] - set.lo[r]) / set.cell));
    // A point on the grid's far face belongs to the last bucket.
    b[r] = i == set.count[r] && p[r] <= set.lo[r] + static_cast<double>(set.count[r]) * set.cell ? i - 1 : i;
    if (b[r] < 0 || b[r] >= set.count[r]) return false;
  }
  const std::size_t q = static_cast<std::size_t>((b[2] * set.count[1] + b[1]) * set.count[0] + b[0]);
  for (int64_t k = set.offsets[q]; k < set.offsets[q + 1]; ++k)
    if (tetrahedron_contains(&set.corners[12 * static_cast<std::size_t>(set.members[static_cast<std::size_t>(k)])], p))
      return true;
  return false;
}

Solid make_mesh(std::shared_ptr<const TetrahedronSet> mesh, Solid::Op op)
{
  Solid s;
  s.kind = Solid::Kind::mesh, s.op = op, s.mesh = std::move(mesh);
  return s;
}

Solid make_box(const P3 &lo, const P3 &hi, Solid::Op op)
{
  Solid s;
  s.kind = Solid::Kind::box, s.op = op, s.lo = lo, s.hi = hi;
  return s;
}

Solid make_cylinder(const P3 &a, const P3 &b, double radius, Solid::Op op)
{
  Solid s;
  s.kind = Solid::Kind::cylinder, s.op = op, s.a = a, s.b = b, s.radius = radius;
  return s;
}

Solid make_sphere(const P3 &centre, double radius, Solid::Op op)
{
  Solid s;
  s.kind = Solid::Kind::sphere, s.op = op, s.a = centre, s.radius = radius;
  return s;
}

bool solid_contains(const Solid &s, const double *p)
{
  switch (s.kind) {
  case Solid::Kind::box:
    for (int r = 0; r < 3; ++r)
      if (p[r] < std::min(s.lo[r], s.hi[r]) || p[r] > std::max(s.lo[r], s.hi[r])) return false;
    return true;
  case Solid::Kind::cylinder: {
    const P3     axis = minus(s.b.data(), s.a.data()), q = minus(p, s.a.data());
    const double len2 = dot(axis, axis), along = dot(q, axis);
    if (along < 0 || along > len2) return false; // beyond a cap (a point on a cap is inside)
    const double t    = along / len2;
    const P3     off  = {q[0] - t * axis[0], q[1] - t * axis[1], q[2] - t * axis[2]};
    return dot(off, off) < s.radius * s.radius;
  }
  case Solid::Kind::sphere: {
    const P3 q = minus(p, s.a.data());
    return dot(q, q) < s.radius * s.radius;
  }
  case Solid::Kind::mesh: return tetrahedra_contain(*s.mesh, p);
  }
  return false;
}

bool body_contains(const std::vector<Solid> &solids, const double *p)
{
  bool inside = false;
  for (const Solid &s : solids) switch (s.op) {
    case Solid::Op::add: inside = inside || solid_contains(s, p); break;
    case Solid::Op::subtract: inside = inside && !solid_contains(s, p); break;
    case Solid::Op::intersect: inside = inside && solid_contains(s, p); break;
    }
  return inside;
}

double solid_volume(const Solid &s)
{
  switch (s.kind) {
  case Solid::Kind::box: return std::fabs((s.hi[0] - s.lo[0]) * (s.hi[1] - s.lo[1]) * (s.hi[2] - s.lo[2]));
  case Solid::Kind::cylinder: {
    const P3 axis = minus(s.b.data(), s.a.data());
    return M_PI * s.radius * s.radius * std::sqrt(dot(axis, axis));
  }
  case Solid::Kind::sphere: return 4.0 / 3.0 * M_PI * s.radius * s.radius * s.radius;
  case Solid::Kind::mesh: {
    double v = 0;
    for (std::size_t t = 0; t < s.mesh->size(); ++t) {
      const double *c = &s.mesh->corners[12 * t];
      v += std::fabs(orient(c, c + 3, c + 6, c + 9)) / 6;
    }
    return v;
  }
  }
  return 0;
}

std::string solid_problem(const Solid &s)
{
  auto finite = [](const P3 &p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); };
  switch (s.kind) {
  case Solid::Kind::box:
    if (!finite(s.lo) || !finite(s.hi)) return "its corners must be finite numbers";
    for (int r = 0; r < 3; ++r)
      if (!(s.hi[r] > s.lo[r]))
        return std::string("its side along ") + "xyz"[r] +
               format(" must be > 0 (got %g; give hi > lo on every axis)", s.hi[r] - s.lo[r]);
    return "";
  case Solid::Kind::cylinder: {
    if (!finite(s.a) || !finite(s.b)) return "its axis's end points must be finite numbers";
    const P3 axis = minus(s.b.data(), s.a.data());
    if (!(dot(axis, axis) > 0)) return "its axis's two end points are the same point: give two distinct cap centres";
    if (!(s.radius > 0) || !std::isfinite(s.radius)) return format("its radius must be > 0 (got %g)", s.radius);
    return "";
  }
  case Solid::Kind::sphere:
    if (!finite(s.a)) return "its centre must be finite numbers";
    if (!(s.radius > 0) || !std::isfinite(s.radius)) return format("its radius must be > 0 (got %g)", s.radius);
    return "";
  case Solid::Kind::mesh:
    if (!s.mesh || s.mesh->size() == 0 || s.mesh->offsets.empty())
      return "it holds no tetrahedron (read a Gmsh 3D volume into it and index it)";
    return "";
  }
  return "unknown kind";
}

std::string planar_polygon_problem(const PlanarPolygon &polygon)
{
  const auto &w = polygon.vertices;
  if (w.size() % 3 != 0) return "its vertices must be given as x,y,z triples";
  if (w.size() < 9) return "a polygon needs at least 3 vertices";
  for (double c : w)
    if (!std::isfinite(c)) return "its vertices must be finite numbers";
  const PreparedPolygon p = prepare(polygon);
  if (!(p.scale > 0)) return "its vertices are all the same point";
  // No widest triangle with an area: the vertices are collinear, there is no plane.
  if (!(dot(p.normal, p.normal) > 0.5)) return "its area is zero (the vertices lie on one line)";
  const std::size_t n = w.size() / 3;
  for (std::size_t i = 0; i < n; ++i) {
    const double off = dot(p.normal, {w[3 * i], w[3 * i + 1], w[3 * i + 2]}) - p.offset;
    if (std::fabs(off) > 1e-9 * p.scale) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "vertex %zu lies %g off the plane of the others: a notch polygon must be planar", i + 1, off);
      return text;
    }
  }
  return polygon_problem(p.flat); // crossing edges, repeated vertices, zero area
}

bool polygon_cuts(const PlanarPolygon &polygon, const double *a, const double *b)
{
  return prepared_cuts(prepare(polygon), a, b);
}

BondCut polygon_notches(const std::vector<PlanarPolygon> &polygons)
{
  if (polygons.empty()) return {};
  std::vector<PreparedPolygon> prepared;
  for (std::size_t k = 0; k < polygons.size(); ++k) {
    const std::string problem = planar_polygon_problem(polygons[k]);
    if (!problem.empty())
      throw std::invalid_argument("3D body: notch " + std::to_string(k + 1) + ": " + problem);
    prepared.push_back(prepare(polygons[k]));
  }
  return [prepared = std::move(prepared)](const double *a, const double *b) {
    for (const PreparedPolygon &p : prepared)
      if (prepared_cuts(p, a, b)) return true;
    return false;
  };
}

PointCloud tetrahedron_centroids(const TetrahedronSet &mesh)
{
  PointCloud points;
  points.x.reserve(3 * mesh.size());
  for (std::size_t t = 0; t < mesh.size(); ++t) {
    const double *c = &mesh.corners[12 * t];
    for (int r = 0; r < 3; ++r) points.x.push_back(0.25 * (c[r] + c[3 + r] + c[6 + r] + c[9 + r]));
    points.volume.push_back(std::fabs(orient(c, c + 3, c + 6, c + 9)) / 6.0);
    points.natural_id.push_back(static_cast<int64_t>(t));
  }
  return points;
}

const char *to_string(Solid::Kind kind)
{
  static constexpr EnumWords<Solid::Kind::mesh> words{"box", "cylinder", "sphere", "mesh"};
  return words(kind);
}

} // namespace bapd::nd
