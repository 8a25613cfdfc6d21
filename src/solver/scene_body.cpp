// The body section: the sheet, its holes and notches, and the horizon (-body_*,
// -horizon_factor). The checks see the body whole: every hole and notch inside it,
// none cutting it apart (FindCut), at least one material point left by the hole rule
// of lattice.hpp, the same rule make_lattice applies.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "bapd/lattice.hpp"
#include "bapd/options_reader.hpp"
#include "bapd/scene_input.hpp"

namespace bapd {

namespace {

// ---------------------------------------------------------------------------------
// Geometry for the body checks

double PointSegmentDistance(double px, double py, const Segment &s)
{
  const double ex = s.x1 - s.x0, ey = s.y1 - s.y0, len2 = ex * ex + ey * ey;
  double       t = len2 > 0 ? ((px - s.x0) * ex + (py - s.y0) * ey) / len2 : 0.0;
  t              = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (s.x0 + t * ex), py - (s.y0 + t * ey));
}

double Cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

double SegmentDistance(const Segment &a, const Segment &b)
{
  // Proper crossing: the end points of each lie strictly on both sides of the other.
  const double d1 = Cross(b.x1 - b.x0, b.y1 - b.y0, a.x0 - b.x0, a.y0 - b.y0);
  const double d2 = Cross(b.x1 - b.x0, b.y1 - b.y0, a.x1 - b.x0, a.y1 - b.y0);
  const double d3 = Cross(a.x1 - a.x0, a.y1 - a.y0, b.x0 - a.x0, b.y0 - a.y0);
  const double d4 = Cross(a.x1 - a.x0, a.y1 - a.y0, b.x1 - a.x0, b.y1 - a.y0);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0.0;
  return std::min({PointSegmentDistance(a.x0, a.y0, b), PointSegmentDistance(a.x1, a.y1, b), PointSegmentDistance(b.x0, b.y0, a),
                   PointSegmentDistance(b.x1, b.y1, a)});
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int Find(int i) { return parent[i] == i ? i : parent[i] = Find(parent[i]); }
  void Join(int a, int b) { parent[Find(a)] = Find(b); }
};

// The notches and holes, with the four edges, as a graph whose links are contacts
// closer than half a spacing (a gap that narrow holds no column of lattice points, so
// every bond across it is cut). Two edges in one connected group mean the body falls
// apart. Returns "" or the message for the first such pair.
std::string FindCut(const Body2D &b)
{
  const int   n_holes = static_cast<int>(b.holes.size()), n_notches = static_cast<int>(b.notches.size());
  const int   first_hole = 4, first_notch = 4 + n_holes;
  const double tol       = 0.5 * b.dx;
  UnionFind    groups(4 + n_holes + n_notches);
  enum { left = 0, right = 1, bottom = 2, top = 3 };
  for (int h = 0; h < n_holes; ++h) {
    const Circle &c = b.holes[h];
    if (c.cx - c.radius <= tol) groups.Join(first_hole + h, left);
    if (b.width - (c.cx + c.radius) <= tol) groups.Join(first_hole + h, right);
    if (c.cy - c.radius <= tol) groups.Join(first_hole + h, bottom);
    if (b.height - (c.cy + c.radius) <= tol) groups.Join(first_hole + h, top);
    for (int k = 0; k < h; ++k)
      if (std::hypot(c.cx - b.holes[k].cx, c.cy - b.holes[k].cy) - c.radius - b.holes[k].radius <= tol) groups.Join(first_hole + h, first_hole + k);
  }
  for (int s = 0; s < n_notches; ++s) {
    const Segment &g = b.notches[s];
    if (std::min(g.x0, g.x1) <= tol) groups.Join(first_notch + s, left);
    if (b.width - std::max(g.x0, g.x1) <= tol) groups.Join(first_notch + s, right);
    if (std::min(g.y0, g.y1) <= tol) groups.Join(first_notch + s, bottom);
    if (b.height - std::max(g.y0, g.y1) <= tol) groups.Join(first_notch + s, top);
    for (int h = 0; h < n_holes; ++h)
      if (PointSegmentDistance(b.holes[h].cx, b.holes[h].cy, g) - b.holes[h].radius <= tol) groups.Join(first_notch + s, first_hole + h);
    for (int k = 0; k < s; ++k)
      if (SegmentDistance(g, b.notches[k]) <= tol) groups.Join(first_notch + s, first_notch + k);
  }
  struct Pair {
    int         a, b;
    const char *edges, *result;
  };
  const Pair pairs[] = {
    {left, right, "the left and right edges", "cutting the body into a top and a bottom piece"},
    {bottom, top, "the bottom and top edges", "cutting the body into a left and a right piece"},
    {left, bottom, "the left and bottom edges", "cutting off the bottom-left corner"},
    {left, top, "the left and top edges", "cutting off the top-left corner"},
    {right, bottom, "the right and bottom edges", "cutting off the bottom-right corner"},
    {right, top, "the right and top edges", "cutting off the top-right corner"},
  };
  for (const Pair &p : pairs) {
    if (groups.Find(p.a) != groups.Find(p.b)) continue;
    std::string culprits;
    int         count = 0, notches = 0;
    for (int s = 0; s < n_notches; ++s)
      if (groups.Find(first_notch + s) == groups.Find(p.a)) {
        const Segment &g = b.notches[s];
        culprits += Format("%snotch %d (%g, %g)-(%g, %g)", count++ ? ", " : "", s + 1, g.x0, g.y0, g.x1, g.y1);
        ++notches;
      }
    for (int h = 0; h < n_holes; ++h)
      if (groups.Find(first_hole + h) == groups.Find(p.a)) culprits += Format("%shole %d", count++ ? ", " : "", h + 1);
    const char *options = notches == 0 ? "-body_holes" : notches == count ? "-body_notches" : "-body_notches and -body_holes";
    const char *fix     = notches == 0 ? "shrink or move a hole" : "shorten a notch so that it ends inside the body (an edge crack starts on one edge only)";
    return Format("%s: %s %s %s, %s (gaps under dx/2 = %g m count as closed): %s", options, culprits.c_str(), count > 1 ? "together join" : "joins",
                  p.edges, p.result, tol, fix);
  }
  return "";
}

} // namespace

PetscErrorCode ReadBody(MPI_Comm comm, Scene *scene, SceneInput *in)
{
  Body2D     &b = scene->body;
  PetscFunctionBeginUser;
  PetscCall(ReadOptionBlock(comm, nullptr, "Body: a plane sheet [0, width] x [0, height] cut by holes and notches", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(r.Real("-body_width", "Sheet width along x [m] (required)", &b.width, &in->width_set));
    PetscCall(r.Real("-body_height", "Sheet height along y [m] (required)", &b.height, &in->height_set));
    PetscCall(r.Real("-body_thickness", "Sheet thickness [m] (required)", &b.thickness, &in->thickness_set));
    PetscCall(r.Real("-body_dx", "Lattice spacing of the material points [m] (required)", &b.dx, &in->dx_set));
    PetscCall(r.RealArray("-body_holes", "Circular holes cx,cy,r,cx,cy,r,... [m] (default: none)", &in->holes));
    PetscCall(r.RealArray("-body_notches", "Pre-notch segments x0,y0,x1,y1,... [m]; bonds crossing one are never created (default: none)", &in->notches));
    return 0;
  }));

  PetscCall(ReadOptionBlock(comm, nullptr, "Horizon", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(r.Real("-horizon_factor", "Horizon over lattice spacing, delta/dx [-] (paper: 3.015; 2.515 and 3.515 also studied)",
                     &scene->horizon_factor));
    return 0;
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckBody(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  Body2D &b = scene->body;
  PetscFunctionBeginUser;
  const struct {
    bool        set;
    double      value;
    const char *name, *what, *yaml;
  } sizes[] = {
    {in.width_set, b.width, "-body_width", "the sheet width along x", "width: 0.08"},
    {in.height_set, b.height, "-body_height", "the sheet height along y", "height: 0.16"},
    {in.thickness_set, b.thickness, "-body_thickness", "the sheet thickness", "thickness: 0.001"},
    {in.dx_set, b.dx, "-body_dx", "the lattice spacing", "dx: 0.001"},
  };
  for (const auto &s : sizes) {
    SceneCheck(s.set, comm, "%s is required: give %s in metres (YAML: body: {%s})%s", s.name, s.what, s.yaml, MisspeltHint(s.name).c_str());
    SceneCheck(s.value > 0, comm, "%s %g: %s must be > 0 m", s.name, s.value, s.what);
  }
  SceneCheck(b.dx <= b.width && b.dx <= b.height, comm,
             "-body_dx %g m is larger than the body (%g m x %g m): choose a spacing well below the smaller side, e.g. -body_dx %g", b.dx,
             b.width, b.height, std::min(b.width, b.height) / 20);
  const double tol = 1e-12 * std::max(b.width, b.height); // round-off in the input numbers

  SceneCheck(in.holes.size() % 3 == 0, comm,
             "-body_holes holds %zu numbers, not a multiple of 3: give each hole as cx,cy,r (e.g. -body_holes 0.04,0.08,0.01)", in.holes.size());
  b.holes.clear();
  for (std::size_t h = 0; 3 * h < in.holes.size(); ++h) {
    const Circle c = {in.holes[3 * h], in.holes[3 * h + 1], in.holes[3 * h + 2]};
    SceneCheck(c.radius > 0, comm, "-body_holes: hole %zu has radius %g m: a radius must be > 0", h + 1, c.radius);
    double far = 0; // distance from the centre to the farthest corner
    for (double x : {0.0, b.width})
      for (double y : {0.0, b.height}) far = std::max(far, std::hypot(x - c.cx, y - c.cy));
    SceneCheck(c.radius < far, comm,
               "-body_holes: hole %zu (centre (%g, %g) m, radius %g m) covers the whole body and leaves no material: reduce its radius",
               h + 1, c.cx, c.cy, c.radius);
    SceneCheck(c.cx - c.radius >= -tol && c.cx + c.radius <= b.width + tol && c.cy - c.radius >= -tol && c.cy + c.radius <= b.height + tol,
               comm,
               "-body_holes: hole %zu (centre (%g, %g) m, radius %g m) is not entirely inside the body [0, %g] x [0, %g] m: move its "
               "centre or reduce its radius",
               h + 1, c.cx, c.cy, c.radius, b.width, b.height);
    b.holes.push_back(c);
  }

  SceneCheck(in.notches.size() % 4 == 0, comm,
             "-body_notches holds %zu numbers, not a multiple of 4: give each notch as x0,y0,x1,y1 (e.g. -body_notches 0.05,0.005,0.07,0.005)",
             in.notches.size());
  b.notches.clear();
  for (std::size_t s = 0; 4 * s < in.notches.size(); ++s) {
    const Segment g = {in.notches[4 * s], in.notches[4 * s + 1], in.notches[4 * s + 2], in.notches[4 * s + 3]};
    for (int end = 0; end < 2; ++end) {
      const double x = end ? g.x1 : g.x0, y = end ? g.y1 : g.y0;
      SceneCheck(x >= -tol && x <= b.width + tol && y >= -tol && y <= b.height + tol, comm,
                 "-body_notches: notch %zu ends at (%g, %g) m, outside the body [0, %g] x [0, %g] m: move that end inside (an edge crack "
                 "ends on the edge)",
                 s + 1, x, y, b.width, b.height);
    }
    SceneCheck(std::hypot(g.x1 - g.x0, g.y1 - g.y0) > tol, comm,
               "-body_notches: notch %zu has zero length (both ends at (%g, %g) m): give two different end points", s + 1, g.x0, g.y0);
    b.notches.push_back(g);
  }
  const std::string cut = FindCut(b);
  PetscCheck(cut.empty(), comm, PETSC_ERR_USER, "%s", cut.c_str());
  SceneCheck(ScenePointEstimate(*scene) > 0, comm,
             "-body_holes: the holes leave no material point on the lattice of spacing -body_dx %g m: reduce their radii or dx", b.dx);

  SceneCheck(scene->horizon_factor >= 1, comm,
             "-horizon_factor %g is below 1: the horizon delta = factor x dx must reach the nearest neighbours; use 3.015 (the paper's "
             "value), or a value in [2, 5]",
             scene->horizon_factor);
  if (scene->horizon_factor < 2 || scene->horizon_factor > 5)
    PetscCall(Warn(comm, Format("-horizon_factor %g is outside [2, 5]: too few neighbours make the shape tensor fragile, too many "
                                "smooth the solution and cost time; the paper uses 3.015",
                                scene->horizon_factor)));
  PetscFunctionReturn(0);
}

PetscInt ScenePointEstimate(const Scene &scene) { return static_cast<PetscInt>(lattice_point_count(scene.body)); }

} // namespace bapd
