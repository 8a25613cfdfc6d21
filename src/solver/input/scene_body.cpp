// The body section: the sheet, its holes and notches, and the horizon (-body_*,
// -horizon_factor). The checks see the body whole: every hole and notch inside it,
// none cutting it apart (FindCut), at least one material point left by the hole rule
// of lattice.hpp, the same rule make_lattice applies. A 3D body (-body_dimension 3) is
// checked by scene_body3d.cpp, the memory the body needs by scene_body_memory.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "bapd/core/geometry/geometry.hpp"
#include "bapd/solver/input/gmsh_shape.hpp"
#include "bapd/core/geometry/lattice.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/point_cloud_file.hpp"
#include "bapd/solver/input/scene_input.hpp"

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
std::string FindCut(const Body<2> &b)
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

PetscErrorCode CheckHorizonFactor(MPI_Comm comm, const Scene &scene)
{
  PetscFunctionBeginUser;
  SceneCheck(scene.body.horizon_factor >= 1, comm,
             "-horizon_factor %g is below 1: the horizon delta = factor x dx must reach the nearest neighbours; use 3.015 (the paper's "
             "value), or a value in [2, 5]",
             scene.body.horizon_factor);
  if (scene.body.horizon_factor < 2 || scene.body.horizon_factor > 5)
    PetscCall(Warn(comm, Format("-horizon_factor %g is outside [2, 5]: too few neighbours make the shape tensor fragile, too many "
                                "smooth the solution and cost time; the paper uses 3.015",
                                scene.body.horizon_factor)));
  PetscFunctionReturn(0);
}

namespace {

// One shape's options (-body_NAME_...), in -help's order.
const OptionTable<ShapeInput> kShapeOptions = {
    {"-type",
     "rectangle | circle | ellipse | polygon | mesh (a Gmsh file); 3D: box | cylinder | sphere | mesh (a Gmsh "
     "volume) | notch (a planar polygon) (required)",
     &ShapeInput::type, &ShapeInput::type_set},
    {"-op",
     "What it does to the body so far: subtract | add (within the sheet) | intersect (default subtract; 3D: add "
     "for the first solid, which starts the body, subtract after it)",
     &ShapeInput::op, &ShapeInput::op_set},
    {"-box", "Rectangle xmin,ymin,xmax,ymax [m]; 3D box xmin,ymin,zmin,xmax,ymax,zmax [m]", &ShapeInput::box},
    {"-centre", "Circle or ellipse centre x,y [m]; 3D sphere x,y,z [m]", &ShapeInput::centre},
    {"-radius", "Circle, 3D sphere or cylinder radius [m]", &ShapeInput::radius, &ShapeInput::radius_set},
    {"-axis", "3D cylinder: its axis's end points (the end caps' centres) x0,y0,z0,x1,y1,z1 [m]", &ShapeInput::axis},
    {"-radii", "Ellipse semi-axes a,b [m] (a along -angle)", &ShapeInput::radii},
    {"-angle", "Ellipse: angle of the a axis from x [degrees]", &ShapeInput::angle},
    {"-points",
     "Polygon vertices x0,y0,x1,y1,... [m] (closed: the last joins the first); 3D notch: x0,y0,z0,x1,y1,z1,... in "
     "one plane",
     &ShapeInput::points},
    {"-file",
     "Mesh: a Gmsh .geo (meshed in 2D) or .msh file whose 2D elements are the shape [m]; 3D: a .geo with a volume "
     "(meshed in 3D) or a .msh of tetrahedra",
     &ShapeInput::file},
    {"-discretisation",
     "Mesh: lattice (the lattice clipped to the mesh) | centroids (one point per 2D element, volume = area x "
     "thickness; 3D: per tetrahedron, volume = its volume)",
     &ShapeInput::discretisation},
};

// The sheet's size: values in the Body<2>, whether each was given in the SceneInput
// (each is required).
const OptionTable<Body<2>, SceneInput> kSheetOptions = {
    {"-body_width", "Sheet width along x [m] (required)", &Body<2>::width, &SceneInput::width_set},
    {"-body_height", "Sheet height along y [m] (required)", &Body<2>::height, &SceneInput::height_set},
    {"-body_thickness", "Sheet thickness [m] (required)", &Body<2>::thickness, &SceneInput::thickness_set},
};

// The spacing (of the sheet or the solid, as the dimension says), what cuts the sheet,
// or replaces its lattice, and the dimension, as given (CheckBody).
const OptionTable<SceneInput> kBodyInputOptions = {
    {"-body_dx", "Lattice spacing of the material points [m] (required)", &SceneInput::dx, &SceneInput::dx_set},
    {"-body_holes", "Circular holes cx,cy,r,cx,cy,r,... [m] (default: none)", &SceneInput::holes},
    {"-body_notches", "Pre-notch segments x0,y0,x1,y1,... [m]; bonds crossing one are never created (default: none)", &SceneInput::notches},
    {"-body_cloud",
     "Point cloud file instead of the lattice: x, y, volume [, block_id] a point, .csv or .h5 [m, m^3] (default: "
     "the lattice); 3D: x, y, z, volume [, block_id], text",
     &SceneInput::cloud},
    {"-body_dimension",
     "2 (a plane sheet) or 3 (a solid body: -body_shapes of type box, cylinder, sphere, mesh (a Gmsh volume), notch) "
     "(default: 3 if a shape is a 3D solid or notch, else 2)",
     &SceneInput::dimension, &SceneInput::dimension_set},
    {"-body_shapes", "Shapes applied in order to the sheet, name1,name2,... (each shape S is set by -body_S_...)", &SceneInput::shape_names},
};

const OptionTable<BodySection> kHorizonOptions = {
    {"-horizon_factor",
     "Horizon over lattice spacing, delta/dx [-] (given points: over each one's spacing sqrt(V/t), 3D cbrt(V)) (paper: "
     "3.015; 2.515 and 3.515 also studied)",
     &BodySection::horizon_factor, nullptr, "3.015"},
};

} // namespace

SetFamily ShapeFamily() { return {"-body_", "-body_shapes", OptionRowSuffixes(kShapeOptions)}; }

PetscErrorCode ReadBody(MPI_Comm comm, BodySection *body, SceneInput *in)
{
  PetscFunctionBeginUser;
  PetscCall(ReadOptionBlock(comm, nullptr, "Body: a plane sheet [0, width] x [0, height] cut by holes, shapes and notches", [&](OptionReader &r) -> PetscErrorCode {
    PetscCall(ReadOptionRows(r, kSheetOptions, &body->sheet, in));
    return ReadOptionRows(r, kBodyInputOptions, in);
  }));
  PetscCall(CheckNames(comm, in->shape_names, "-body_shapes", "shape"));
  for (const std::string &name : in->shape_names) {
    ShapeInput        shape;
    const std::string prefix = "body_" + name + "_", title = "Shape " + name;
    shape.name               = name;
    PetscCall(ReadOptionBlock(comm, prefix.c_str(), title.c_str(), [&](OptionReader &r) { return ReadOptionRows(r, kShapeOptions, &shape); }));
    in->shapes.push_back(shape);
  }
  PetscCall(ReadOptionTable(comm, "Horizon", kHorizonOptions, body));
  PetscFunctionReturn(0);
}

namespace {

// The dimension: -body_dimension, else 3 if a shape is a 3D solid or notch.
PetscErrorCode CheckDimension(MPI_Comm comm, const SceneInput &in, int *dimension)
{
  PetscFunctionBeginUser;
  const ShapeInput *solid = nullptr;
  for (const ShapeInput &si : in.shapes)
    if (!solid && IsShape3D(si.type)) solid = &si;
  if (in.dimension_set) {
    SceneCheck(in.dimension == 2 || in.dimension == 3, comm, "-body_dimension %" PetscInt_FMT ": give 2 (a plane sheet) or 3 (a solid body)",
               in.dimension);
    SceneCheck(in.dimension == 3 || !solid, comm,
               "-body_%s_type %s is a shape of a 3D body, but -body_dimension is 2: use the sheet's shapes (rectangle, circle, ellipse, "
               "polygon, mesh), or -body_dimension 3",
               solid ? solid->name.c_str() : "", solid ? solid->type.c_str() : "");
  }
  *dimension = in.dimension_set ? static_cast<int>(in.dimension) : solid ? 3 : 2;
  PetscFunctionReturn(0);
}

// The mesh shape whose element centroids are the body's points
// (-body_NAME_discretisation centroids), or null.
PetscErrorCode FindCentroidShape(MPI_Comm comm, const SceneInput &in, const ShapeInput **found)
{
  PetscFunctionBeginUser;
  const ShapeInput *centroid_shape = nullptr;
  for (const ShapeInput &si : in.shapes) {
    const char *n = si.name.c_str();
    if (Lower(si.discretisation) == "lattice") continue;
    SceneCheck(Lower(si.discretisation) == "centroids", comm, "-body_%s_discretisation '%s' is not a choice: choose lattice or centroids", n,
               si.discretisation.c_str());
    SceneCheck(Lower(si.type) == "mesh", comm,
               "-body_%s_discretisation centroids: only a mesh shape (-body_%s_type mesh) has elements whose centroids can be the points; "
               "remove it, or make the shape a Gmsh mesh",
               n, n);
    SceneCheck(!centroid_shape, comm,
               "-body_%s_discretisation and -body_%s_discretisation are both centroids: the body's points come from one mesh; keep one",
               centroid_shape ? centroid_shape->name.c_str() : "", n);
    SceneCheck(in.cloud.empty(), comm, "-body_%s_discretisation centroids and -body_cloud both give the body's points: keep one", n);
    centroid_shape = &si;
  }
  *found = centroid_shape;
  PetscFunctionReturn(0);
}

// Given points (geometry.hpp) instead of the lattice: a cloud file, or the element
// centroids of one mesh shape (its mesh read into *centroid_mesh). They fix the spacing
// (dx: the smallest), and the sheet's size unless it is given (the points' extent, half
// a spacing beyond them).
PetscErrorCode GivenPoints2D(MPI_Comm comm, const SceneInput &in, const ShapeInput *centroid_shape, Body<2> *body, TriangleSet *centroid_mesh)
{
  Body<2> &b = *body;
  PetscFunctionBeginUser;
  const std::string source = centroid_shape ? "-body_" + centroid_shape->name + "_discretisation centroids" : "-body_cloud";
  SceneCheck(in.thickness_set && b.thickness > 0, comm,
             "-body_thickness is required and must be > 0 m: %s turns volumes into spacings with it (YAML: body: {thickness: 0.001})",
             source.c_str());
  auto points = std::make_shared<GivenPoints>();
  if (centroid_shape) {
    const char       *n       = centroid_shape->name.c_str();
    SceneCheck(!centroid_shape->file.empty(), comm, "-body_%s_file: give the Gmsh .geo or .msh file of shape '%s'", n, n);
    const std::string problem = ReadGmshTriangles(centroid_shape->file, centroid_mesh);
    SceneCheck(problem.empty(), comm, "-body_%s_file: %s", n, problem.c_str());
    *points        = element_centroids(*centroid_mesh, b.thickness);
    points->source = centroid_shape->file;
    for (std::size_t p = 0; p < points->size(); ++p)
      SceneCheck(points->volume[p] > 0, comm,
                 "-body_%s_file: 2D element %zu of '%s' has zero area, so its centroid point would have no volume: fix the mesh", n, p + 1,
                 centroid_shape->file.c_str());
  } else {
    const std::string problem = ReadPointCloud(in.cloud, points.get());
    SceneCheck(problem.empty(), comm, "-body_cloud: %s", problem.c_str());
  }
  double right = 0, top = 0;
  for (std::size_t p = 0; p < points->size(); ++p) {
    const double h = point_spacing(points->volume[p], b.thickness);
    right          = std::max(right, points->x[2 * p] + 0.5 * h);
    top            = std::max(top, points->x[2 * p + 1] + 0.5 * h);
  }
  if (!in.width_set) b.width = right;
  if (!in.height_set) b.height = top;
  for (std::size_t p = 0; p < points->size(); ++p) {
    const double x = points->x[2 * p], y = points->x[2 * p + 1];
    SceneCheck(x >= 0 && x <= b.width && y >= 0 && y <= b.height, comm,
               "%s: point %zu at (%g, %g) m lies outside the sheet [0, %g] x [0, %g] m: shift the points into x >= 0, y >= 0%s", source.c_str(),
               p + 1, x, y, b.width, b.height, in.width_set || in.height_set ? ", or enlarge -body_width / -body_height" : "");
  }
  SceneCheck(!in.dx_set, comm,
             "-body_dx is the lattice spacing, but %s gives the body's points, each with its own volume (its spacing is sqrt(volume / "
             "thickness)): remove -body_dx",
             source.c_str());
  b.dx           = smallest_spacing(*points, b.thickness);
  b.given_points = points;
  PetscFunctionReturn(0);
}

// The sheet's size and spacing: each given (or set by given points) and > 0.
PetscErrorCode CheckSheetSize(MPI_Comm comm, const SceneInput &in, const Body<2> &b)
{
  PetscFunctionBeginUser;
  const bool given = b.given_points != nullptr;
  const struct {
    bool        set;
    double      value;
    const char *name, *what, *yaml;
  } sizes[] = {
    {in.width_set || given, b.width, "-body_width", "the sheet width along x", "width: 0.08"},
    {in.height_set || given, b.height, "-body_height", "the sheet height along y", "height: 0.16"},
    {in.thickness_set, b.thickness, "-body_thickness", "the sheet thickness", "thickness: 0.001"},
    {in.dx_set || given, b.dx, "-body_dx", "the lattice spacing", "dx: 0.001"},
  };
  for (const auto &s : sizes) {
    SceneCheck(s.set, comm, "%s is required: give %s in metres (YAML: body: {%s})%s", s.name, s.what, s.yaml, MisspeltHint(s.name).c_str());
    SceneCheck(s.value > 0, comm, "%s %g: %s must be > 0 m", s.name, s.value, s.what);
  }
  SceneCheck(b.dx <= b.width && b.dx <= b.height, comm,
             "-body_dx %g m is larger than the body (%g m x %g m): choose a spacing well below the smaller side, e.g. -body_dx %g", b.dx,
             b.width, b.height, std::min(b.width, b.height) / 20);
  // Past 1e15 points (-body_width 1e308, -body_dx 1e-300) the 64-bit count overflows.
  SceneCheck(given || (b.width / b.dx) * (b.height / b.dx) <= 1e15, comm, "-body_width %g m and -body_height %g m at -body_dx %g m make a "
             "lattice of %g points, beyond any machine: give the sizes in metres and a -body_dx of about a hundredth of the smaller side",
             b.width, b.height, b.dx, (b.width / b.dx) * (b.height / b.dx));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckHoles(MPI_Comm comm, const SceneInput &in, Body<2> *body)
{
  Body<2> &b = *body;
  PetscFunctionBeginUser;
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
    // A hole may reach outside the sheet (a waisted sheet is a sheet less two discs
    // that cross its sides), but it must cut into it.
    const double near = std::hypot(c.cx - std::clamp(c.cx, 0.0, b.width), c.cy - std::clamp(c.cy, 0.0, b.height));
    SceneCheck(near < c.radius, comm,
               "-body_holes: hole %zu (centre (%g, %g) m, radius %g m) does not reach the body [0, %g] x [0, %g] m: move its centre "
               "or enlarge its radius",
               h + 1, c.cx, c.cy, c.radius, b.width, b.height);
    b.holes.push_back(c);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckNotches(MPI_Comm comm, const SceneInput &in, Body<2> *body)
{
  Body<2>      &b   = *body;
  const double tol = 1e-12 * std::max(b.width, b.height); // round-off in the input numbers
  PetscFunctionBeginUser;
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
  PetscFunctionReturn(0);
}

// No scene at all: no scene or options file on the command line, and not one body
// option from anywhere (`mpiexec bapd` alone, or options meant to go on top of a scene
// that was left out). Said as such, rather than as the first size that is missing.
PetscErrorCode CheckSceneGiven(MPI_Comm comm, const SceneInput &in)
{
  PetscFunctionBeginUser;
  const bool body = in.width_set || in.height_set || in.thickness_set || in.dx_set || in.dimension_set || !in.holes.empty() ||
                    !in.notches.empty() || !in.shape_names.empty() || !in.cloud.empty();
  if (body) PetscFunctionReturn(0);
  int    argc = 0;
  char **args = nullptr;
  PetscCall(PetscGetArgs(&argc, &args));
  bool file = false;
  for (int a = 1; a < argc; ++a) file = file || !std::strcmp(args[a], "-options_file_yaml") || !std::strcmp(args[a], "-options_file");
  SceneCheck(file, comm,
             "no scene was given: give a scene file, e.g. mpiexec -n 2 bapd -options_file_yaml examples/default.yaml [options] "
             "(./run_mpi.sh with options but no scene runs that one), or the body's options (-body_width, -body_height, "
             "-body_thickness, -body_dx; docs/options.md)%s",
             MisspeltHint("-body_width").c_str());
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckBody(MPI_Comm comm, const SceneInput &in, Scene *scene)
{
  Body<2> &b = scene->body.sheet;
  PetscFunctionBeginUser;
  PetscCall(CheckSceneGiven(comm, in));
  PetscCall(CheckDimension(comm, in, &scene->body.dimension));
  if (scene->body.dimension == 3) {
    PetscCall(CheckBody3D(comm, in, scene));
    PetscFunctionReturn(0);
  }
  // Given points (geometry.hpp) instead of the lattice: a cloud file, or the element
  // centroids of one mesh shape.
  const ShapeInput *centroid_shape = nullptr;
  PetscCall(FindCentroidShape(comm, in, &centroid_shape));
  b.dx = in.dx; // (given points: their smallest spacing, GivenPoints2D)
  b.given_points.reset();
  TriangleSet centroid_mesh; // the centroid shape's mesh, read once (CheckShape takes it)
  if (!in.cloud.empty() || centroid_shape) PetscCall(GivenPoints2D(comm, in, centroid_shape, &b, &centroid_mesh));
  const bool given = b.given_points != nullptr;
  PetscCall(CheckSheetSize(comm, in, b));
  PetscCall(CheckHoles(comm, in, &b));
  PetscCall(CheckNotches(comm, in, &b));
  b.shapes.clear();
  for (const ShapeInput &si : in.shapes) PetscCall(CheckShape(comm, si, b, &si == centroid_shape ? &centroid_mesh : nullptr, &b.shapes));
  const std::string cut = FindCut(b);
  PetscCheck(cut.empty(), comm, PETSC_ERR_USER, "%s", cut.c_str());
  const int64_t points = ScenePointEstimate(*scene);
  SceneCheck(points > 0, comm, "%s leave no material point %s %g m: %s",
             b.shapes.empty() ? "-body_holes: the holes" : "-body_holes and -body_shapes: the holes and shapes",
             given ? "of the given points, smallest spacing" : "on the lattice of spacing -body_dx", b.dx,
             b.shapes.empty() ? "reduce their radii or dx" : "check each shape's -body_NAME_op (subtract removes what it covers)");
  if (!b.shapes.empty() && !given) {
    // The holes and notches are checked above edge by edge (FindCut); shapes can make
    // any outline, so the lattice itself is looked at.
    const LatticePieces pieces = lattice_pieces(b);
    SceneCheck(pieces.count <= 1, comm,
               "-body_shapes: the body falls apart into %lld pieces on the lattice of spacing %g m (the smallest, %lld point(s), at "
               "(%g, %g) m): change the shapes so that the body is one piece, or remove the stray one",
               (long long)pieces.count, b.dx, (long long)pieces.smallest_points, pieces.smallest_x, pieces.smallest_y);
  }

  PetscCall(CheckHorizonFactor(comm, *scene));
  PetscFunctionReturn(0);
}

int64_t ScenePointEstimate(const Scene &scene) { return scene.body.dimension == 3 ? scene.body.solid_summary.points : body_point_count(scene.body.sheet); }

} // namespace bapd
