// Shapes that cut a body out of its sheet (shape.hpp) and the lattice they leave
// (lattice.hpp: is_material, lattice_point_count, lattice_pieces).
#include <gtest/gtest.h>

#include <cmath>

#include "bapd/core/geometry/lattice.hpp"
#include "bapd/core/geometry/shape.hpp"

using namespace bapd;

namespace {

Shape Rectangle(double x0, double y0, double x1, double y1, Shape::Op op = Shape::Op::subtract)
{
  Shape s;
  s.kind = Shape::Kind::rectangle, s.op = op;
  s.box[0] = x0, s.box[1] = y0, s.box[2] = x1, s.box[3] = y1;
  return s;
}
Shape Circle(double cx, double cy, double r, Shape::Op op = Shape::Op::subtract)
{
  Shape s;
  s.kind = Shape::Kind::circle, s.op = op, s.cx = cx, s.cy = cy, s.a = s.b = r;
  return s;
}
Body<2> Sheet(double w, double h, double dx)
{
  Body<2> b;
  b.width = w, b.height = h, b.thickness = 1, b.dx = dx;
  return b;
}

TEST(Shape, Contains)
{
  EXPECT_TRUE(shape_contains(Rectangle(0, 0, 1, 1), 1, 0.5)); // boundary inside
  EXPECT_FALSE(shape_contains(Rectangle(0, 0, 1, 1), 1.01, 0.5));
  EXPECT_FALSE(shape_contains(Circle(0, 0, 1), 1, 0)); // rim is material, as a hole's
  EXPECT_TRUE(shape_contains(Circle(0, 0, 1), 0.99, 0));
  Shape e;
  e.kind = Shape::Kind::ellipse, e.cx = 1, e.cy = 1, e.a = 2, e.b = 0.5, e.angle = M_PI / 2; // long axis along y
  EXPECT_TRUE(shape_contains(e, 1, 2.9));
  EXPECT_FALSE(shape_contains(e, 2.9, 1));
  Shape p;
  p.kind     = Shape::Kind::polygon;
  p.vertices = {0, 0, 2, 0, 2, 2, 1, 1, 0, 2}; // a notched square (concave)
  EXPECT_TRUE(shape_contains(p, 0.5, 1.2));
  EXPECT_FALSE(shape_contains(p, 1.0, 1.5)); // in the notch
  EXPECT_TRUE(shape_contains(p, 2, 1));      // on an edge
  EXPECT_NEAR(shape_area(p), 3.0, 1e-15);
}

TEST(Shape, OperationsApplyInOrder)
{
  // Sheet minus a big square plus a small disc inside it, then intersected with a disc.
  const std::vector<Shape> shapes = {Rectangle(0, 0, 2, 2), Circle(1, 1, 0.5, Shape::Op::add), Circle(1, 1, 5, Shape::Op::intersect)};
  EXPECT_EQ(shape_removing(shapes, 1.9, 1.9), 0);  // removed by the square
  EXPECT_EQ(shape_removing(shapes, 1.0, 1.2), -1); // added back by the small disc
  EXPECT_EQ(shape_removing(shapes, 3.0, 3.0), -1); // untouched
  EXPECT_EQ(shape_removing(shapes, 9.0, 0.0), 2);  // outside the intersecting disc
}

TEST(Shape, PolygonProblems)
{
  EXPECT_EQ(polygon_problem({0, 0, 1, 0, 1, 1, 0, 1}), "");
  EXPECT_NE(polygon_problem({0, 0, 1, 1, 1, 0, 0, 1}).find("cross"), std::string::npos); // a bow tie
  EXPECT_NE(polygon_problem({0, 0, 1, 0}).find("at least 3"), std::string::npos);
  EXPECT_NE(polygon_problem({0, 0, 1, 1, 2, 2}).find("area is zero"), std::string::npos);
  EXPECT_NE(polygon_problem({0, 0, 1, 0, 1, 0, 0, 1}).find("same point"), std::string::npos);
  // Collinear edges that do not overlap are fine (a U shape's arms end on one line).
  EXPECT_EQ(polygon_problem({0, 0, 3, 0, 3, 2, 2, 2, 2, 1, 1, 1, 1, 2, 0, 2}), "");
}

TEST(ShapedLattice, CountMatchesTheLatticeAndTheArea)
{
  // A waisted sheet: two discs that reach outside the sides.
  Body<2> b = Sheet(0.02, 0.06, 0.0005);
  b.shapes = {Circle(-0.008, 0.03, 0.012), Circle(0.028, 0.03, 0.012)};
  const PointCloud cloud = make_lattice(b);
  EXPECT_EQ(lattice_point_count(b), (int64_t)cloud.size());
  EXPECT_LT(cloud.size(), 40u * 120u);
  // Area: sheet less the two circular segments inside it.
  const double r = 0.012, d = 0.008, segment = r * r * std::acos(d / r) - d * std::sqrt(r * r - d * d);
  const double area = 0.02 * 0.06 - 2 * segment;
  EXPECT_NEAR(cloud.size() * b.dx * b.dx, area, 0.01 * area);
  for (std::size_t i = 0; i < cloud.size(); ++i) EXPECT_TRUE(is_material(b, cloud.x[2 * i], cloud.x[2 * i + 1]));
  EXPECT_EQ(lattice_pieces(b).count, 1);
}

TEST(ShapedLattice, PiecesFindACutAndAStrayIsland)
{
  Body<2> b = Sheet(0.01, 0.01, 0.001);
  b.shapes = {Rectangle(-1, 0.004, 1, 0.006)}; // a band across the whole width
  LatticePieces pieces = lattice_pieces(b);
  EXPECT_EQ(pieces.count, 2);
  EXPECT_EQ(pieces.smallest_points, 40); // 10 columns x 4 rows below (and above) the band
  // An island: a ring removed around the centre leaves a disc alone.
  b.shapes = {Circle(0.005, 0.005, 0.004), Circle(0.005, 0.005, 0.0015, Shape::Op::add)};
  pieces   = lattice_pieces(b);
  EXPECT_EQ(pieces.count, 2);
  EXPECT_NEAR(pieces.smallest_x, 0.0045, 1e-12);
  // A notch across the sheet parts it as well.
  b.shapes  = {Rectangle(0.0, 0.0, 0.0009, 0.0009)}; // a corner, harmless
  b.notches = {{-0.001, 0.005, 0.011, 0.005}};
  EXPECT_EQ(lattice_pieces(b).count, 2);
  b.notches = {{-0.001, 0.005, 0.006, 0.005}};
  EXPECT_EQ(lattice_pieces(b).count, 1);
}

TEST(ShapedLattice, WithoutShapesNothingChanges)
{
  Body<2> b = Sheet(0.01, 0.01, 0.0005);
  b.holes  = {{0.005, 0.005, 0.002}};
  const PointCloud cloud = make_lattice(b);
  EXPECT_EQ(lattice_point_count(b), (int64_t)cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) EXPECT_GE(std::hypot(cloud.x[2 * i] - 0.005, cloud.x[2 * i + 1] - 0.005), 0.002);
}

} // namespace

namespace {

// A 40 x 30 grid of squares, each split into two triangles, with the square (12, 7)
// left out: the bucket index answers as a test of every triangle would.
TEST(TriangleSet, IndexAnswersAsBruteForce)
{
  TriangleSet set;
  const double h = 0.25;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 40; ++i) {
      if (i == 12 && j == 7) continue;
      const double x = i * h, y = j * h;
      for (double v : {x, y, x + h, y, x + h, y + h, x, y, x + h, y + h, x, y + h}) set.corners.push_back(v);
    }
  index_triangles(set);
  Shape s;
  s.kind      = Shape::Kind::mesh;
  s.triangles = set;
  EXPECT_NEAR(shape_area(s), (40 * 30 - 1) * h * h, 1e-12);
  EXPECT_TRUE(triangles_contain(set, 0, 0));           // a corner of the domain
  EXPECT_TRUE(triangles_contain(set, 10, 7.5));        // the far corner
  EXPECT_FALSE(triangles_contain(set, 10.001, 7.5));   // just outside
  EXPECT_FALSE(triangles_contain(set, 3.1, 1.9));      // in the missing square
  EXPECT_TRUE(triangles_contain(set, 3.0, 1.9));       // on its edge
  int disagreements = 0;
  for (int k = 0; k < 1000; ++k) {
    const double x = -0.5 + 11.0 * ((k * 7919) % 4001) / 4000.0, y = -0.5 + 8.5 * ((k * 104729) % 3989) / 3988.0;
    bool brute = false;
    for (std::size_t t = 0; t < set.size() && !brute; ++t) {
      TriangleSet one;
      one.corners.assign(set.corners.begin() + 6 * t, set.corners.begin() + 6 * t + 6);
      index_triangles(one);
      brute = triangles_contain(one, x, y);
    }
    disagreements += brute != triangles_contain(set, x, y);
  }
  EXPECT_EQ(disagreements, 0);
}

} // namespace
