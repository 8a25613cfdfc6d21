// A Gmsh 3D volume as a mesh solid (gmsh_volume3d.hpp, shape3d.hpp): an extruded L
// meshed by Gmsh clips the lattice to exactly the points of the same L built from two
// boxes; its tetrahedra fill the L's volume; missing files and surface-only files are
// errors that say so.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <string>

#include "bapd/solver/input/gmsh_volume3d.hpp"
#include "bapd/core/geometry/shape3d.hpp"

namespace bapd {
namespace {

constexpr double kMm = 1e-3;

TEST(GmshVolume3D, AnExtrudedLClipsTheLatticeLikeTheSameLFromBoxes)
{
  auto        mesh = std::make_shared<nd::TetrahedronSet>();
  std::string e    = ReadGmshTetrahedra(std::string(BAPD_TEST_SOURCE_DIR) + "/data/geometry/l_block.geo", mesh.get());
  ASSERT_EQ(e, "");
  ASSERT_GT(mesh->size(), 20u);
  // The tetrahedra fill the L: 39 mm^2 x 4 mm, to round-off.
  EXPECT_NEAR(nd::solid_volume(nd::make_mesh(mesh)), 39 * 4 * kMm * kMm * kMm, 1e-12 * 156 * kMm * kMm * kMm);

  Body<3> from_mesh, from_boxes;
  from_mesh.dx = from_boxes.dx = kMm;
  from_mesh.solids             = {nd::make_mesh(mesh)};
  from_boxes.solids            = {nd::make_box({0, 0, 0}, {8 * kMm, 8 * kMm, 4 * kMm}),
                                  nd::make_box({3 * kMm, 3 * kMm, -kMm}, {9 * kMm, 9 * kMm, 5 * kMm}, nd::Solid::Op::subtract)};
  const PointCloud a = nd::make_solid_points(from_mesh), b = nd::make_solid_points(from_boxes);
  EXPECT_EQ(a.size(), 156u); // (64 - 25) cells a layer x 4 layers
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.natural_id, b.natural_id);

  // A mesh solid combines with the others: a spherical hole in the L's corner.
  from_mesh.solids.push_back(nd::make_sphere({1.5 * kMm, 1.5 * kMm, 2 * kMm}, 1.2 * kMm, nd::Solid::Op::subtract));
  from_boxes.solids.push_back(from_mesh.solids.back());
  EXPECT_EQ(nd::make_solid_points(from_mesh).x, nd::make_solid_points(from_boxes).x);
  EXPECT_LT(nd::make_solid_points(from_mesh).size(), 156u);
}

TEST(GmshVolume3D, FilesWithoutAVolumeAreErrors)
{
  nd::TetrahedronSet set;
  EXPECT_NE(ReadGmshTetrahedra("/nonexistent/block.geo", &set).find("cannot open"), std::string::npos);
  // The 2D L (a Plane Surface only): no volume to mesh.
  const std::string e = ReadGmshTetrahedra(std::string(BAPD_TEST_SOURCE_DIR) + "/data/geometry/l_shape.geo", &set);
  EXPECT_NE(e.find("holds no volume and no 3D element"), std::string::npos) << e;
  // A mesh solid with no tetrahedra is a bad solid.
  Body<3> body;
  body.dx     = kMm;
  body.solids = {nd::make_mesh(std::make_shared<nd::TetrahedronSet>())};
  EXPECT_THROW(nd::make_solid_points(body), std::invalid_argument);
}

} // namespace
} // namespace bapd
