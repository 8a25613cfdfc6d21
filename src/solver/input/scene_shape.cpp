// The 2D body's shapes (-body_shapes, -body_NAME_*): each checked and converted into a
// Shape of shape.hpp (angles to radians), in the order given.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bapd/core/geometry/lattice.hpp"
#include "bapd/solver/input/gmsh_shape.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

namespace {

// The shape's kind (-body_NAME_type) and how it combines with the sheet (-body_NAME_op).
PetscErrorCode CheckShapeKind(MPI_Comm comm, const ShapeInput &in, Shape *shape)
{
  Shape      &s = *shape;
  const char *n = in.name.c_str();
  PetscFunctionBeginUser;
  const std::string type = Lower(in.type), op = Lower(in.op);
  if (type == "rectangle") s.kind = Shape::Kind::rectangle;
  else if (type == "circle") s.kind = Shape::Kind::circle;
  else if (type == "ellipse") s.kind = Shape::Kind::ellipse;
  else if (type == "polygon") s.kind = Shape::Kind::polygon;
  else if (type == "mesh") s.kind = Shape::Kind::mesh;
  else SceneCheck(false, comm, "-body_%s_type '%s' is not a shape: give rectangle, circle, ellipse, polygon or mesh", n, in.type.c_str());
  if (op == "subtract") s.op = Shape::Op::subtract;
  else if (op == "add") s.op = Shape::Op::add;
  else if (op == "intersect") s.op = Shape::Op::intersect;
  else SceneCheck(false, comm, "-body_%s_op '%s': give subtract, add or intersect", n, in.op.c_str());
  PetscFunctionReturn(0);
}

// The parameters of the shape's kind (and no other kind's), into *shape.
PetscErrorCode CheckShapeParameters(MPI_Comm comm, const ShapeInput &in, TriangleSet *read_mesh, Shape *shape)
{
  Shape      &s = *shape;
  const char *n = in.name.c_str();
  PetscFunctionBeginUser;
  const bool has_box = !in.box.empty(), has_centre = !in.centre.empty(), has_radii = !in.radii.empty(), has_points = !in.points.empty();
  const bool wanted_box = s.kind == Shape::Kind::rectangle, wanted_points = s.kind == Shape::Kind::polygon;
  const bool wanted_centre = s.kind == Shape::Kind::circle || s.kind == Shape::Kind::ellipse;
  const struct {
    bool        given, wanted;
    const char *option;
  } parameters[] = {{has_box, wanted_box, "box"},
                    {has_centre, wanted_centre, "centre"},
                    {in.radius_set, s.kind == Shape::Kind::circle, "radius"},
                    {has_radii, s.kind == Shape::Kind::ellipse, "radii"},
                    {in.angle != 0, s.kind == Shape::Kind::ellipse, "angle"},
                    {has_points, wanted_points, "points"},
                    {!in.file.empty(), s.kind == Shape::Kind::mesh, "file"},
                    {Lower(in.discretisation) != "lattice", s.kind == Shape::Kind::mesh, "discretisation"}};
  for (const auto &p : parameters)
    SceneCheck(!p.given || p.wanted, comm, "-body_%s_%s is not a parameter of a %s: remove it, or change -body_%s_type", n, p.option,
               to_string(s.kind), n);
  switch (s.kind) {
  case Shape::Kind::rectangle:
    SceneCheck(in.box.size() == 4, comm, "-body_%s_box holds %zu numbers: give xmin,ymin,xmax,ymax in m", n, in.box.size());
    SceneCheck(in.box[2] > in.box[0] && in.box[3] > in.box[1], comm,
               "-body_%s_box %g,%g,%g,%g: give xmin,ymin,xmax,ymax with xmax > xmin and ymax > ymin", n, in.box[0], in.box[1], in.box[2],
               in.box[3]);
    std::copy(in.box.begin(), in.box.end(), s.box);
    break;
  case Shape::Kind::circle:
  case Shape::Kind::ellipse:
    SceneCheck(in.centre.size() == 2, comm, "-body_%s_centre holds %zu numbers: give x,y in m", n, in.centre.size());
    s.cx = in.centre[0], s.cy = in.centre[1];
    if (s.kind == Shape::Kind::circle) {
      SceneCheck(in.radius_set && in.radius > 0, comm, "-body_%s_radius: give the circle's radius in m, > 0", n);
      s.a = s.b = in.radius;
    } else {
      SceneCheck(in.radii.size() == 2 && in.radii[0] > 0 && in.radii[1] > 0, comm,
                 "-body_%s_radii: give the ellipse's two semi-axes a,b in m, both > 0", n);
      s.a = in.radii[0], s.b = in.radii[1], s.angle = in.angle * M_PI / 180.0;
    }
    break;
  case Shape::Kind::polygon: {
    SceneCheck(in.points.size() % 2 == 0, comm, "-body_%s_points holds %zu numbers: give vertex pairs x0,y0,x1,y1,... in m", n,
               in.points.size());
    s.vertices = in.points;
    const std::string problem = polygon_problem(s.vertices);
    SceneCheck(problem.empty(), comm, "-body_%s_points: %s", n, problem.c_str());
    break;
  }
  case Shape::Kind::mesh: {
    SceneCheck(!in.file.empty(), comm, "-body_%s_file: give the Gmsh .geo or .msh file of shape '%s'", n, n);
    // Every rank reads the (small) outline: the scene checks and probes use it too.
    s.file      = in.file;
    s.centroids = Lower(in.discretisation) == "centroids";
    if (read_mesh) s.triangles = std::move(*read_mesh); // (read by CheckBody for its centroids)
    else {
      const std::string problem = ReadGmshTriangles(in.file, &s.triangles);
      SceneCheck(problem.empty(), comm, "-body_%s_file: %s", n, problem.c_str());
    }
    break;
  }
  }
  PetscFunctionReturn(0);
}

// A shape that does not touch the sheet does nothing: surely a mistake in a number.
PetscErrorCode CheckShapeTouchesBody(MPI_Comm comm, const Shape &s, const Body<2> &b)
{
  const char *n = s.name.c_str();
  PetscFunctionBeginUser;
  // (With given points: none of them; the mesh whose centroids they are holds them all.)
  bool touches = s.centroids;
  if (b.given_points) {
    const GivenPoints &g = *b.given_points;
    for (std::size_t p = 0; p < g.size() && !touches; ++p) touches = shape_contains(s, g.x[2 * p], g.x[2 * p + 1]);
  } else {
    const LatticeCells cells = lattice_cells(b);
    const int64_t      step  = std::max<int64_t>(1, std::max(cells.nx, cells.ny) / 2000);
    for (int64_t iy = 0; iy < cells.ny && !touches; iy += step)
      for (int64_t ix = 0; ix < cells.nx && !touches; ix += step)
        touches = shape_contains(s, (ix + 0.5) * b.dx, (iy + 0.5) * b.dx);
  }
  SceneCheck(touches || s.op == Shape::Op::intersect, comm,
             "-body_%s: the %s holds no %s point of the sheet [0, %g] x [0, %g] m (spacing %g m), so it changes nothing: check "
             "its position and size",
             n, to_string(s.kind), b.given_points ? "given" : "lattice", b.width, b.height, b.dx);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode CheckShape(MPI_Comm comm, const ShapeInput &in, const Body<2> &b, TriangleSet *read_mesh, std::vector<Shape> *shapes)
{
  Shape       s;
  const char *n = in.name.c_str();
  PetscFunctionBeginUser;
  s.name = in.name;
  static const char *reserved[] = {"width", "height", "thickness", "dx", "holes", "notches", "shapes"};
  for (const char *word : reserved)
    SceneCheck(Lower(in.name) != word, comm, "-body_shapes: '%s' is the name of a body option (-body_%s): give the shape another name", n, word);
  SceneCheck(in.type_set, comm, "-body_%s_type is required for shape '%s': rectangle, circle, ellipse, polygon or mesh%s", n, n,
             MisspeltHint("-body_" + in.name + "_type").c_str());
  PetscCall(CheckShapeKind(comm, in, &s));
  // Each type takes its own parameters and no other's (a stray one is a mistake).
  PetscCall(CheckShapeParameters(comm, in, read_mesh, &s));
  PetscCall(CheckShapeTouchesBody(comm, s, b));
  shapes->push_back(s);
  PetscFunctionReturn(0);
}

} // namespace bapd
