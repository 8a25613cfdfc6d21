#include "bapd/shape.hpp"

#include <cmath>
#include <cstdio>

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

} // namespace

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

const char *to_string(Shape::Kind kind)
{
  switch (kind) {
  case Shape::Kind::rectangle: return "rectangle";
  case Shape::Kind::circle: return "circle";
  case Shape::Kind::ellipse: return "ellipse";
  case Shape::Kind::polygon: return "polygon";
  }
  return "unknown";
}

const char *to_string(Shape::Op op)
{
  switch (op) {
  case Shape::Op::subtract: return "subtract";
  case Shape::Op::add: return "add";
  case Shape::Op::intersect: return "intersect";
  }
  return "unknown";
}

} // namespace bapd
