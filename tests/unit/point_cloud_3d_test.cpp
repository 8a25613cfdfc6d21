// 3D point cloud text files (nd/point_cloud3d.hpp): columns in any order, comments,
// blocks, the errors, and a clipped lattice written out and read back giving the same
// points and families.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "bapd/nd/family.hpp"
#include "bapd/nd/point_cloud3d.hpp"
#include "bapd/nd/shape3d.hpp"

namespace bapd {
namespace {

std::string write(const std::string &name, const std::string &text)
{
  const std::string path = ::testing::TempDir() + "bapd_cloud3d_" + name;
  std::ofstream(path) << text;
  return path;
}

std::string read_error(const std::string &text)
{
  PointCloud           c;
  std::vector<int64_t> block;
  return nd::read_point_cloud_3d(write("bad.csv", text), &c, &block);
}

TEST(PointCloud3D, ReadsColumnsInAnyOrderWithCommentsAndBlocks)
{
  // Peridigm's header order, blanks and commas mixed, a comment line, an extra column.
  const std::string path = write("ok.txt", "\n# x y z block_id volume extra\n1 2 3 2 1e-9 7\n# a comment\n4,5,6,1,2e-9,8\n");
  PointCloud           c;
  std::vector<int64_t> block;
  ASSERT_EQ(nd::read_point_cloud_3d(path, &c, &block), "");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c.x, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(c.volume, (std::vector<double>{1e-9, 2e-9}));
  EXPECT_EQ(c.natural_id, (std::vector<int64_t>{0, 1}));
  EXPECT_EQ(block, (std::vector<int64_t>{2, 1}));
  // Without a block column every point is in block 1.
  ASSERT_EQ(nd::read_point_cloud_3d(write("noblock.csv", "volume,z,y,x\n1e-9,3,2,1\n"), &c, &block), "");
  EXPECT_EQ(c.x, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(block, (std::vector<int64_t>{1}));
}

TEST(PointCloud3D, BadFilesNameTheLineAndTheFix)
{
  auto has = [](const std::string &text, const char *word) {
    return text.find(word) != std::string::npos ? ::testing::AssertionSuccess() : ::testing::AssertionFailure() << text;
  };
  PointCloud           c;
  std::vector<int64_t> block;
  EXPECT_TRUE(has(nd::read_point_cloud_3d("/nonexistent/cloud.csv", &c, &block), "cannot open"));
  EXPECT_TRUE(has(read_error("1,2,3,1e-9\n"), "line 1: the first line must name the columns"));
  EXPECT_TRUE(has(read_error("x,y,volume\n1,2,1e-9\n"), "names no column 'z'"));
  EXPECT_TRUE(has(read_error("x,y,z,x,volume\n"), "names column 'x' twice"));
  EXPECT_TRUE(has(read_error("x,y,z,volume\n1,2,3\n"), "line 2 holds 3 values"));
  EXPECT_TRUE(has(read_error("x,y,z,volume\n1,2,a,1e-9\n"), "'a' (column z) is not a number"));
  EXPECT_TRUE(has(read_error("x,y,z,volume\n1,2,3,0\n"), "line 2 (at (1, 2, 3) m): volume 0 m^3"));
  EXPECT_TRUE(has(read_error("x,y,z,volume\n1,2,3,-1\n"), "must be > 0"));
  EXPECT_TRUE(has(read_error("x,y,z,volume\n1,2,3,1e-9\n5,5,5,1e-9\n1,2,3,1e-9\n"), "lines 2 and 4 are the same point"));
  // Same x and y, another z: not a duplicate.
  EXPECT_EQ(read_error("x,y,z,volume\n1,2,3,1e-9\n1,2,4,1e-9\n"), "");
  EXPECT_TRUE(has(read_error("x,y,z,volume\n# only a comment\n"), "holds no point"));
}

TEST(PointCloud3D, AClippedLatticeReadBackGivesTheSameFamilies)
{
  const double  dx = 1e-3;
  nd::SolidBody body;
  body.dx     = dx;
  body.solids = {nd::make_box({0, 0, 0}, {8 * dx, 7 * dx, 6 * dx}),
                 nd::make_sphere({4 * dx, 3.5 * dx, 3 * dx}, 2.2 * dx, nd::Solid::Op::subtract)};
  const PointCloud lattice = nd::make_solid_points(body);
  std::string      text    = "x,y,z,volume\n";
  char             row[160];
  for (std::size_t i = 0; i < lattice.size(); ++i) {
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g,%.17g\n", lattice.x[3 * i], lattice.x[3 * i + 1], lattice.x[3 * i + 2],
                  lattice.volume[i]);
    text += row;
  }
  PointCloud           c;
  std::vector<int64_t> block;
  ASSERT_EQ(nd::read_point_cloud_3d(write("lattice.csv", text), &c, &block), "");
  EXPECT_EQ(c.x, lattice.x); // %.17g round-trips a double exactly
  EXPECT_EQ(c.volume, lattice.volume);
  EXPECT_EQ(c.natural_id, lattice.natural_id);
  const Families a = nd::build_families<3>(lattice, lattice.size(), 3.015 * dx);
  const Families b = nd::build_families<3>(c, c.size(), 3.015 * dx);
  EXPECT_EQ(a.offsets, b.offsets);
  EXPECT_EQ(a.neighbour, b.neighbour);
}

} // namespace
} // namespace bapd
