// 3D point cloud text files (point_cloud3d.hpp): columns in any order, comments,
// blocks, the errors, and a clipped lattice written out and read back giving the same
// points and families; per-point horizons of a cloud with two spacings (geometry.hpp's
// set_point_horizons in 3D, delta_i = factor cbrt(V_i), a bond where either reaches).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <tuple>

#include "bapd/core/geometry/geometry.hpp"
#include "bapd/core/geometry/family.hpp"
#include "bapd/core/geometry/point_cloud3d.hpp"
#include "bapd/core/geometry/shape3d.hpp"

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
  Body<3> body;
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

// A cloud file of cell-centred boxes: each box {origin, cells, spacing} one point a cell
// of volume spacing^3, written with %.17g (exact round trip) and read back.
struct Block {
  double x0;
  int    nx, ny, nz;
  double spacing;
};
PointCloud graded_cloud(const std::string &name, const std::vector<Block> &blocks)
{
  std::string text = "x y z volume\n";
  char        row[160];
  for (const Block &b : blocks)
    for (int k = 0; k < b.nz; ++k)
      for (int j = 0; j < b.ny; ++j)
        for (int i = 0; i < b.nx; ++i) {
          std::snprintf(row, sizeof row, "%.17g %.17g %.17g %.17g\n", b.x0 + (i + 0.5) * b.spacing, (j + 0.5) * b.spacing,
                        (k + 0.5) * b.spacing, b.spacing * b.spacing * b.spacing);
          text += row;
        }
  PointCloud           c;
  std::vector<int64_t> block;
  EXPECT_EQ(nd::read_point_cloud_3d(write(name, text), &c, &block), "");
  return c;
}

double distance(const PointCloud &c, std::size_t a, std::size_t b)
{
  return std::sqrt(std::pow(c.x[3 * b] - c.x[3 * a], 2) + std::pow(c.x[3 * b + 1] - c.x[3 * a + 1], 2) +
                   std::pow(c.x[3 * b + 2] - c.x[3 * a + 2], 2));
}

TEST(PointCloud3D, TwoSpacingsGetTheirOwnHorizonsAndABondWhereEitherReaches)
{
  // A coarse block (spacing 2 mm, 3 x 4 x 4 points, V = 8e-9 m^3) beside a fine one
  // (1 mm, 6 x 8 x 8, V = 1e-9 m^3) along x: delta = 6.03 mm and 3.015 mm.
  const double     h = 1e-3, factor = 3.015;
  PointCloud       c = graded_cloud("graded.txt", {{0.0, 3, 4, 4, 2 * h}, {6 * h, 6, 8, 8, h}});
  const std::size_t n = c.size(), coarse = 48;
  ASSERT_EQ(n, coarse + 384);
  set_point_horizons(&c, 3, factor, 0.0);
  ASSERT_EQ(c.horizon.size(), n);
  // (to round-off: cbrt(8e-9) is 0.0019999999999999996, an ulp below 2 mm)
  EXPECT_NEAR(c.horizon[0], factor * 2 * h, 1e-15);
  EXPECT_NEAR(c.horizon[n - 1], factor * h, 1e-15);
  const Families f = nd::build_families<3>(c, n, factor * h); // (the smallest horizon: not read with per-point ones)
  EXPECT_NEAR(f.horizon, factor * 2 * h, 1e-15);              // the cell list's reach: the largest

  // Every pair against the rule by a direct search: bonded iff |x_j - x_i| <= max(delta_i, delta_j).
  std::size_t coarse_beyond_fine = 0, fine_to_coarse_beyond_fine = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::int32_t> expected;
    for (std::size_t j = 0; j < n; ++j) {
      const double reach = std::max(c.horizon[i], c.horizon[j]);
      if (j != i && distance(c, i, j) * distance(c, i, j) <= reach * reach) expected.push_back(static_cast<std::int32_t>(j));
    }
    const std::vector<std::int32_t> got(f.neighbour.begin() + f.offsets[i], f.neighbour.begin() + f.offsets[i + 1]);
    ASSERT_EQ(got, expected) << "point " << i; // (natural id = index: both in index order)
    for (std::int32_t j : got) {
      const double r = distance(c, i, static_cast<std::size_t>(j));
      if (i < coarse && r > factor * h) ++coarse_beyond_fine; // a coarse family reaches its own 6.03 mm
      if (i >= coarse && static_cast<std::size_t>(j) < coarse && r > factor * h) ++fine_to_coarse_beyond_fine;
      if (i >= coarse && static_cast<std::size_t>(j) >= coarse) { // fine-fine: the fine horizon (to round-off)
        EXPECT_LE(r, factor * h * (1 + 1e-15));
      }
    }
    // A coarse point's family holds the ball of its own horizon: the farthest member
    // lies within one coarse spacing of delta_i = 6.03 mm.
    if (i < coarse) {
      double farthest = 0;
      for (std::int32_t j : got) farthest = std::max(farthest, distance(c, i, static_cast<std::size_t>(j)));
      EXPECT_GT(farthest, factor * 2 * h - 2 * h) << "coarse point " << i;
    }
  }
  EXPECT_GT(coarse_beyond_fine, 0u);
  // Fine points bonded to coarse ones beyond their own horizon (within the coarse one only).
  EXPECT_GT(fine_to_coarse_beyond_fine, 0u);
  // Symmetric: every bond has its reverse (every point has a family here).
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      ASSERT_GE(f.reverse[b], 0);
      EXPECT_EQ(f.neighbour[static_cast<std::size_t>(f.reverse[b])], static_cast<std::int32_t>(i));
    }
}

TEST(PointCloud3D, EqualVolumesGiveTheFamiliesOfTheOneHorizon)
{
  // All V equal: per-point horizons (delta_i = factor cbrt(V)) build exactly the
  // families the one horizon factor x cbrt(V) built before 3D clouds had their own.
  const double factor = 3.015;
  PointCloud   c      = graded_cloud("uniform.txt", {{0.0, 7, 7, 7, 1e-3}});
  const Families one  = nd::build_families<3>(c, c.size(), factor * std::cbrt(c.volume[0]));
  set_point_horizons(&c, 3, factor, 0.0);
  const Families own = nd::build_families<3>(c, c.size(), factor * std::cbrt(c.volume[0]));
  // Every array of the families bit for bit, and the cell list's reach.
  const auto whole = [](const Families &f) { return std::tie(f.horizon, f.offsets, f.neighbour, f.mask_words, f.ba_mask, f.reverse); };
  EXPECT_TRUE(whole(own) == whole(one)) << "reach " << own.horizon << " against " << one.horizon << ", bonds " << own.n_bonds()
                                        << " against " << one.n_bonds();
  EXPECT_EQ(own.max_family_size, 122u); // an interior point's 122 members at 3.015 (family_3d_test)
}

} // namespace
} // namespace bapd
