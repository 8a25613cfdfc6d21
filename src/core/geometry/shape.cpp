#include "bapd/core/geometry/shape.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bapd/core/enum_words.hpp"

namespace bapd {

namespace {

// Even-odd rule, boundary inclusive: a point on an edge is inside.
bool polygon_contains(const std::vector<double> &v, double x, double y)
{
  const std::size_t n      = v.size() / 2;
  bool              inside = false;
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double xi = v[2 * i], yi = v[2 * i + 1], xj = v[2 * j], yj = v[2 * j + 1];
    // On the edge (i, j): collinear and within its box.
    const double cross = (xj - xi) * (y - yi) - (yj - yi) * (x - xi);
    const double scale = std::fabs(xj - xi) + std::fabs(yj - yi);
    if (std::fabs(cross) <= 1e-12 * scale * scale && x >= std::fmin(xi, xj) && x <= std::fmax(xi, xj) && y >= std::fmin(yi, yj) &&
        y <= std::fmax(yi, yj))
      return true;
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

// Edges inclusive, either orientation: the signs of the three edge functions agree
// (zeros allowed), to a round-off tolerance relative to the triangle's size.
bool triangle_contains(const double *t, double x, double y)
{
  const double d1 = cross(t[2] - t[0], t[3] - t[1], x - t[0], y - t[1]);
  const double d2 = cross(t[4] - t[2], t[5] - t[3], x - t[2], y - t[3]);
  const double d3 = cross(t[0] - t[4], t[1] - t[5], x - t[4], y - t[5]);
  const double area = std::fabs(cross(t[2] - t[0], t[3] - t[1], t[4] - t[0], t[5] - t[1]));
  const double tol  = 1e-12 * area;
  const bool   neg  = d1 < -tol || d2 < -tol || d3 < -tol, pos = d1 > tol || d2 > tol || d3 > tol;
  return !(neg && pos);
}

} // namespace

void index_triangles(TriangleSet &set)
{
  const std::size_t n = set.size();
  if (n == 0) return;
  double xmin = set.corners[0], xmax = xmin, ymin = set.corners[1], ymax = ymin;
  for (std::size_t k = 0; k < 3 * n; ++k) {
    xmin = std::fmin(xmin, set.corners[2 * k]), xmax = std::fmax(xmax, set.corners[2 * k]);
    ymin = std::fmin(ymin, set.corners[2 * k + 1]), ymax = std::fmax(ymax, set.corners[2 * k + 1]);
  }
  const double w = std::fmax(xmax - xmin, 1e-300), h = std::fmax(ymax - ymin, 1e-300);
  set.cell = std::sqrt(w * h / (double)n);
  set.nx = std::max(1L, (long)std::ceil(w / set.cell)), set.ny = std::max(1L, (long)std::ceil(h / set.cell));
  set.x0 = xmin, set.y0 = ymin;
  // Two passes over the triangles' bounding boxes: count, then fill.
  std::vector<int> count((std::size_t)(set.nx * set.ny) + 1, 0);
  auto             range = [&](std::size_t t, long *i0, long *i1, long *j0, long *j1) {
    const double *c = &set.corners[6 * t];
    const double  a = std::fmin(c[0], std::fmin(c[2], c[4])), b = std::fmax(c[0], std::fmax(c[2], c[4]));
    const double  d = std::fmin(c[1], std::fmin(c[3], c[5])), e = std::fmax(c[1], std::fmax(c[3], c[5]));
    *i0 = std::clamp((long)std::floor((a - set.x0) / set.cell), 0L, set.nx - 1), *i1 = std::clamp((long)std::floor((b - set.x0) / set.cell), 0L, set.nx - 1);
    *j0 = std::clamp((long)std::floor((d - set.y0) / set.cell), 0L, set.ny - 1), *j1 = std::clamp((long)std::floor((e - set.y0) / set.cell), 0L, set.ny - 1);
  };
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      set.offsets.assign(count.size(), 0);
      for (std::size_t k = 1; k < count.size(); ++k) set.offsets[k] = set.offsets[k - 1] + count[k - 1];
      set.members.assign((std::size_t)set.offsets.back(), 0);
      std::fill(count.begin(), count.end(), 0);
    }
    for (std::size_t t = 0; t < n; ++t) {
      long i0, i1, j0, j1;
      range(t, &i0, &i1, &j0, &j1);
      for (long j = j0; j <= j1; ++j)
        for (long i = i0; i <= i1; ++i) {
          const std::size_t b = (std::size_t)(j * set.nx + i);
          if (pass == 1) set.members[(std::size_t)set.offsets[b] + count[b]] = (int)t;
          ++count[b];
        }
    }
  }
}

bool triangles_contain(const TriangleSet &set, double x, double y)
{
  if (set.offsets.empty()) return false;
  const long i = (long)std::floor((x - set.x0) / set.cell), j = (long)std::floor((y - set.y0) / set.cell);
  // A point on the grid's far edge belongs to the last bucket.
  const long ii = i == set.nx && x <= set.x0 + set.nx * set.cell ? i - 1 : i, jj = j == set.ny && y <= set.y0 + set.ny * set.cell ? j - 1 : j;
  if (ii < 0 || jj < 0 || ii >= set.nx || jj >= set.ny) return false;
  const std::size_t b = (std::size_t)(jj * set.nx + ii);
  for (int k = set.offsets[b]; k < set.offsets[b + 1]; ++k)
    if (triangle_contains(&set.corners[6 * (std::size_t)set.members[(std::size_t)k]], x, y)) return true;
  return false;
}

bool shape_contains(const Shape &s, double x, double y)
{
  switch (s.kind) {
  case Shape::Kind::rectangle: return x >= s.box[0] && x <= s.box[2] && y >= s.box[1] && y <= s.box[3];
  case Shape::Kind::circle: return std::hypot(x - s.cx, y - s.cy) < s.a;
  case Shape::Kind::ellipse: {
    const double c = std::cos(s.angle), sn = std::sin(s.angle);
    const double u = ((x - s.cx) * c + (y - s.cy) * sn) / s.a, w = (-(x - s.cx) * sn + (y - s.cy) * c) / s.b;
    return u * u + w * w < 1.0;
  }
  case Shape::Kind::polygon: return polygon_contains(s.vertices, x, y);
  case Shape::Kind::mesh: return triangles_contain(s.triangles, x, y);
  }
  return false;
}

int shape_removing(const std::vector<Shape> &shapes, double x, double y)
{
  bool inside = true;
  int  who    = -1;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const bool in = shape_contains(shapes[k], x, y);
    switch (shapes[k].op) {
    case Shape::Op::subtract:
      if (inside && in) inside = false, who = (int)k;
      break;
    case Shape::Op::add:
      if (in) inside = true;
      break;
    case Shape::Op::intersect:
      if (inside && !in) inside = false, who = (int)k;
      break;
    }
  }
  return inside ? -1 : who;
}

double shape_area(const Shape &s)
{
  switch (s.kind) {
  case Shape::Kind::rectangle: return std::fabs((s.box[2] - s.box[0]) * (s.box[3] - s.box[1]));
  case Shape::Kind::circle: return M_PI * s.a * s.a;
  case Shape::Kind::ellipse: return M_PI * s.a * s.b;
  case Shape::Kind::polygon: {
    double            twice = 0;
    const std::size_t n     = s.vertices.size() / 2;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++)
      twice += s.vertices[2 * j] * s.vertices[2 * i + 1] - s.vertices[2 * i] * s.vertices[2 * j + 1];
    return 0.5 * std::fabs(twice);
  }
  case Shape::Kind::mesh: {
    double area = 0;
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
      const double *c = &s.triangles.corners[6 * t];
      area += 0.5 * std::fabs(cross(c[2] - c[0], c[3] - c[1], c[4] - c[0], c[5] - c[1]));
    }
    return area;
  }
  }
  return 0;
}

std::string polygon_problem(const std::vector<double> &v)
{
  const std::size_t n = v.size() / 2;
  char              text[160];
  if (n < 3) return "a polygon needs at least 3 vertices";
  Shape s;
  s.kind     = Shape::Kind::polygon;
  s.vertices = v;
  double extent = 0;
  for (double c : v) extent = std::fmax(extent, std::fabs(c));
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t i1 = (i + 1) % n;
    if (v[2 * i] == v[2 * i1] && v[2 * i + 1] == v[2 * i1 + 1]) {
      std::snprintf(text, sizeof text, "vertices %zu and %zu are the same point (%g, %g)", i + 1, i1 + 1, v[2 * i], v[2 * i + 1]);
      return text;
    }
  }
  // Two edges that do not share a vertex must not touch.
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t i1 = (i + 1) % n;
    const double      ax = v[2 * i], ay = v[2 * i + 1], bx = v[2 * i1], by = v[2 * i1 + 1];
    for (std::size_t j = i + 1; j < n; ++j) {
      const std::size_t j1 = (j + 1) % n;
      if (j == i1 || j1 == i) continue; // neighbouring edges share a vertex
      const double cx = v[2 * j], cy = v[2 * j + 1], dx = v[2 * j1], dy = v[2 * j1 + 1];
      const double d1 = cross(dx - cx, dy - cy, ax - cx, ay - cy), d2 = cross(dx - cx, dy - cy, bx - cx, by - cy);
      const double d3 = cross(bx - ax, by - ay, cx - ax, cy - ay), d4 = cross(bx - ax, by - ay, dx - ax, dy - ay);
      const bool collinear = d1 == 0 && d2 == 0 && d3 == 0 && d4 == 0;
      if (collinear && (std::fmax(ax, bx) < std::fmin(cx, dx) || std::fmax(cx, dx) < std::fmin(ax, bx) ||
                        std::fmax(ay, by) < std::fmin(cy, dy) || std::fmax(cy, dy) < std::fmin(ay, by)))
        continue; // on one line, apart
      if (((d1 >= 0 && d2 <= 0) || (d1 <= 0 && d2 >= 0)) && ((d3 >= 0 && d4 <= 0) || (d3 <= 0 && d4 >= 0))) {
        const double t = d1 != d2 ? d1 / (d1 - d2) : 0.0;
        std::snprintf(text, sizeof text, "edges %zu and %zu cross at (%g, %g): the polygon must not intersect itself", i + 1, j + 1,
                      ax + t * (bx - ax), ay + t * (by - ay));
        return text;
      }
    }
  }
  if (shape_area(s) <= 1e-12 * extent * extent) return "its area is zero (the vertices lie on one line)";
  return "";
}

namespace {

// The enumerators' names, in their order in shape.hpp.
constexpr EnumWords<Shape::Kind::mesh>    kind_words{"rectangle", "circle", "ellipse", "polygon", "mesh"};
constexpr EnumWords<Shape::Op::intersect> op_words{"subtract", "add", "intersect"};

} // namespace

const char *to_string(Shape::Kind kind) { return kind_words(kind); }

const char *to_string(Shape::Op op) { return op_words(op); }

} // namespace bapd
