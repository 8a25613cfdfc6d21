#pragma once
// Shapes that cut a body out of its sheet (body.hpp, docs/options.md "Body"): the
// sheet [0, width] x [0, height] is the start; each shape, in the order the scene lists
// them, subtracts from the body, adds to it (within the sheet) or intersects it. A
// waisted sheet is the sheet minus two discs that reach outside it, a dogbone the sheet
// minus four rectangles and plus four fillet quarter-discs, a disc the sheet
// intersected with a circle.
#include <string>
#include <vector>

namespace bapd {

// Triangles (6 numbers each: x0,y0,x1,y1,x2,y2) with a bucket grid over their
// bounding box, so that a point finds the few triangles that may hold it: the domain
// of a Gmsh mesh (gmsh_shape.hpp reads it).
struct TriangleSet {
  std::vector<double> corners;        // 6 per triangle [m]
  double              x0 = 0, y0 = 0; // the grid's lower-left corner [m]
  double              cell = 1;       // bucket size [m]
  long                nx = 0, ny = 0; // buckets
  std::vector<int>    offsets, members; // CSR: triangles overlapping each bucket
  std::vector<std::size_t> element;     // the 2D element each triangle came from (a quadrangle gives two)
  std::size_t         size() const { return corners.size() / 6; }
};
// Builds the bucket grid of `set` (about one triangle a bucket).
void index_triangles(TriangleSet &set);
// Whether (x, y) lies in one of the triangles (edges inclusive).
bool triangles_contain(const TriangleSet &set, double x, double y);

struct Shape {
  enum class Kind { rectangle, circle, ellipse, polygon, mesh };
  enum class Op { subtract, add, intersect };
  std::string name;
  Kind        kind = Kind::rectangle;
  Op          op   = Op::subtract;
  double      box[4] = {0, 0, 0, 0}; // rectangle: xmin, ymin, xmax, ymax [m]
  double      cx = 0, cy = 0;        // circle, ellipse: centre [m]
  double      a = 0, b = 0;          // circle: radius a; ellipse: semi-axes a (along the angle) and b [m]
  double      angle = 0;             // ellipse: angle of the a axis from x [rad]
  std::vector<double> vertices;      // polygon: x0,y0,x1,y1,... (closed implicitly)
  std::string         file;          // mesh: the Gmsh file it came from
  bool                centroids = false; // mesh: its element centroids are the body's points (geometry.hpp)
  TriangleSet         triangles;     // mesh: its 2D elements, as triangles
};

// Whether (x, y) lies inside the shape. A point on the boundary counts as inside for
// a polygon, a mesh and a rectangle, outside for a circle and an ellipse (as the hole rule of
// lattice.hpp: a point on a hole's rim is material).
bool shape_contains(const Shape &shape, double x, double y);

// The shapes applied in order to a point of the sheet: -1 when it stays material, else
// the index of the shape that removed it last (a subtract that contains it or an
// intersect that does not).
int shape_removing(const std::vector<Shape> &shapes, double x, double y);

// The shape's area [m^2] (for estimates).
double shape_area(const Shape &shape);

// "" for a polygon whose edges do not cross and whose area is not zero, else what is
// wrong with it ("edges 2 and 4 cross at (x, y)").
std::string polygon_problem(const std::vector<double> &vertices);

const char *to_string(Shape::Kind kind);
const char *to_string(Shape::Op op);

} // namespace bapd
