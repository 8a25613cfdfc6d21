// Body outlines from Gmsh files (gmsh_shape.hpp): the meshed domain clips the lattice
// exactly as the same outline given as a polygon; files Gmsh cannot use are refused
// with a message naming the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bapd/solver/input/gmsh_shape.hpp"
#include "bapd/core/geometry/lattice.hpp"
#include "bapd/solver/input/scene.hpp"

namespace {

const std::string dir = BAPD_TEST_SOURCE_DIR "/data/geometry/";

TEST(GmshShape, LShapeClipsTheLatticeAsItsPolygonDoes)
{
  bapd::Shape mesh;
  mesh.kind = bapd::Shape::Kind::mesh, mesh.op = bapd::Shape::Op::intersect;
  ASSERT_EQ(bapd::ReadGmshTriangles(dir + "l_shape.geo", &mesh.triangles), "");
  EXPECT_GT(mesh.triangles.size(), 2u);
  bapd::Shape polygon;
  polygon.kind = bapd::Shape::Kind::polygon, polygon.op = bapd::Shape::Op::intersect;
  polygon.vertices = {0.0001, 0.0001, 0.0079, 0.0001, 0.0079, 0.0031, 0.0031, 0.0031, 0.0031, 0.0079, 0.0001, 0.0079};
  EXPECT_NEAR(bapd::shape_area(mesh), bapd::shape_area(polygon), 1e-12 * bapd::shape_area(polygon));

  bapd::Body<2> body;
  body.width = body.height = 0.008, body.thickness = 0.001, body.dx = 0.0005;
  body.shapes = {mesh};
  const bapd::PointCloud from_mesh = bapd::make_lattice(body);
  body.shapes = {polygon};
  const bapd::PointCloud from_polygon = bapd::make_lattice(body);
  EXPECT_EQ(from_mesh.x, from_polygon.x); // the same points, in the same order
  EXPECT_EQ(from_mesh.size(), 16u * 16u - 10u * 10u);
}

TEST(GmshShape, DogboneExampleAreaMatchesItsGeometry)
{
  bapd::TriangleSet triangles;
  ASSERT_EQ(bapd::ReadGmshTriangles(BAPD_TEST_SOURCE_DIR "/../examples/geometry/dogbone.geo", &triangles), "");
  bapd::Shape s;
  s.kind      = bapd::Shape::Kind::mesh;
  s.triangles = triangles;
  // 20 x 60 mm less two 5 x 24 mm strips and four quarter discs of radius 5 mm; the
  // mesh's chords cut the arcs short, by well under 0.1 %.
  const double r = 0.005, area = 0.02 * 0.06 - 2 * 0.005 * 0.024 - 4 * M_PI * r * r / 4;
  EXPECT_NEAR(bapd::shape_area(s), area, 1e-3 * area);
  EXPECT_GE(bapd::shape_area(s), area);
}

const std::string examples = BAPD_TEST_SOURCE_DIR "/../examples/geometry/";

TEST(GmshGroup, PhysicalSurfaceIsItsElementsAndCurveItsSegments)
{
  // examples/geometry/double_edge_notched.geo: grip_top is the tab [0, 20] x [38.5, 40]
  // mm; notch_right the right notch's flanks (5 mm each less the 0.5 mm tip radius) and
  // its semicircular tip of radius 0.5 mm, as Gmsh's chords.
  bapd::GmshGroup group;
  ASSERT_EQ(bapd::ReadGmshGroup(examples + "double_edge_notched.geo", "grip_top", &group), "");
  EXPECT_EQ(group.dim, 2);
  EXPECT_TRUE(group.segments.empty());
  bapd::Shape tab;
  tab.kind      = bapd::Shape::Kind::mesh;
  tab.triangles = group.triangles;
  EXPECT_NEAR(bapd::shape_area(tab), 0.02 * 0.0015, 1e-12); // straight edges: exact to round-off
  EXPECT_TRUE(bapd::shape_contains(tab, 0.01, 0.039));
  EXPECT_FALSE(bapd::shape_contains(tab, 0.01, 0.038));

  ASSERT_EQ(bapd::ReadGmshGroup(examples + "double_edge_notched.geo", "notch_right", &group), "");
  EXPECT_EQ(group.dim, 1);
  double length = 0;
  for (std::size_t k = 0; k < group.segments.size(); k += 4)
    length += std::hypot(group.segments[k + 2] - group.segments[k], group.segments[k + 3] - group.segments[k + 1]);
  const double exact = 2 * 0.0045 + M_PI * 0.0005; // chords fall short of the arc by well under 1 %
  EXPECT_LT(length, exact);
  EXPECT_GT(length, 0.99 * exact);
}

TEST(GmshGroup, DogboneEndLinesGripTheSameRowsAsEdgeGrips)
{
  // examples/dogbone.yaml grips the points within 2 mm of the physical curves top_end
  // and bottom_end: on its 0.5 mm lattice, exactly the 4 edge rows inside the sheet
  // that its earlier edge grips held (-load_S_region top|bottom, layers 4, inside).
  bapd::Scene scene;
  scene.body.sheet.width = 0.02, scene.body.sheet.height = 0.06, scene.body.sheet.thickness = 0.002, scene.body.sheet.dx = 0.0005;
  bapd::Shape outline;
  outline.kind = bapd::Shape::Kind::mesh, outline.op = bapd::Shape::Op::intersect;
  ASSERT_EQ(bapd::ReadGmshTriangles(examples + "dogbone.geo", &outline.triangles), "");
  scene.body.sheet.shapes = {outline};
  const bapd::PointCloud cloud = bapd::make_lattice(scene.body.sheet);
  for (const auto &[name, region] : {std::pair{"top_end", bapd::LoadSet::Region::top}, {"bottom_end", bapd::LoadSet::Region::bottom}}) {
    bapd::GmshGroup group;
    ASSERT_EQ(bapd::ReadGmshGroup(examples + "dogbone.geo", name, &group), "");
    ASSERT_EQ(group.dim, 1);
    bapd::LoadSet by_name;
    by_name.region = bapd::LoadSet::Region::group, by_name.segments = group.segments, by_name.depth = 0.002;
    bapd::SetCurveReach(&by_name);
    bapd::LoadSet by_edge;
    by_edge.region = region, by_edge.layers = 4, by_edge.placement = bapd::GripPlacement::inside;
    std::vector<PetscInt> a, b;
    ASSERT_EQ(bapd::LoadSetSelect(bapd::BodyExtentOf(scene), by_name, cloud.x.data(), (PetscInt)cloud.size(), &a), 0);
    ASSERT_EQ(bapd::LoadSetSelect(bapd::BodyExtentOf(scene), by_edge, cloud.x.data(), (PetscInt)cloud.size(), &b), 0);
    EXPECT_EQ(a, b) << name;
    EXPECT_EQ(a.size(), 4u * 40u) << name; // the tabs are the sheet's full 20 mm width
  }
}

TEST(GmshGroup, AMissingGroupIsNamedWithTheGroupsTheFileHas)
{
  bapd::GmshGroup   group;
  const std::string message = bapd::ReadGmshGroup(examples + "double_edge_notched.geo", "grip", &group);
  EXPECT_NE(message.find("has no physical group named 'grip'"), std::string::npos) << message;
  EXPECT_NE(message.find("'grip_top' (surface)"), std::string::npos) << message;
  EXPECT_NE(message.find("'notch_left' (curve)"), std::string::npos) << message;
  const std::string none = bapd::ReadGmshGroup(dir + "l_shape.geo", "grip", &group);
  EXPECT_NE(none.find("it names none"), std::string::npos) << none;
  EXPECT_NE(bapd::ReadGmshGroup(dir + "no_such_file.geo", "grip", &group).find("cannot open"), std::string::npos);
  EXPECT_NE(bapd::ReadGmshGroup(dir + "broken.geo", "grip", &group).find("Gmsh cannot read"), std::string::npos);
}

TEST(GmshShape, FilesGmshCannotUseAreNamed)
{
  bapd::TriangleSet t;
  EXPECT_NE(bapd::ReadGmshTriangles(dir + "no_such_file.geo", &t).find("cannot open"), std::string::npos);
  EXPECT_NE(bapd::ReadGmshTriangles(dir + "lines_only.geo", &t).find("holds no surface"), std::string::npos);
  EXPECT_NE(bapd::ReadGmshTriangles(dir + "broken.geo", &t).find("Gmsh cannot read"), std::string::npos);
  // After a failure Gmsh is usable again (each read is its own session).
  EXPECT_EQ(bapd::ReadGmshTriangles(dir + "l_shape.geo", &t), "");
}

} // namespace
