// make_lattice: docs/method.md section 1.
#include <gtest/gtest.h>

#include <cmath>

#include "bapd/core/geometry/lattice.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

TEST(Lattice, PointsSitAtCellCentresRowByRow)
{
  const Body<2>     body  = test::plate(7, 4, 0.25, 2.0);
  const PointCloud cloud = make_lattice(body);
  ASSERT_EQ(cloud.size(), 28u);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const double ix = static_cast<double>(i % 7), iy = static_cast<double>(i / 7);
    EXPECT_EQ(cloud.x[2 * i], (ix + 0.5) * 0.25);     // exact: same arithmetic as the spec
    EXPECT_EQ(cloud.x[2 * i + 1], (iy + 0.5) * 0.25);
    EXPECT_EQ(cloud.volume[i], 0.25 * 0.25 * 2.0);
    EXPECT_EQ(cloud.natural_id[i], static_cast<int64_t>(i));
  }
  EXPECT_TRUE(cloud.family_volume.empty());
}

TEST(Lattice, GridSizeRoundsWidthOverDx)
{
  Body<2> body = test::plate(1, 1, 1.0, 1.0);
  body.width  = 10.4; // 10.4 cells -> 10
  body.height = 2.6;  // 2.6 cells -> 3
  EXPECT_EQ(make_lattice(body).size(), 30u);
}

TEST(Lattice, HoleRemovesPointsAndNaturalIdsStayCompact)
{
  Body<2> body = test::plate(20, 20, 1.0, 1.0);
  body.holes.push_back({10.0, 10.0, 3.0});
  const PointCloud cloud = make_lattice(body);
  std::size_t      removed = 0;
  for (int iy = 0; iy < 20; ++iy)
    for (int ix = 0; ix < 20; ++ix) removed += std::hypot(ix + 0.5 - 10.0, iy + 0.5 - 10.0) < 3.0;
  EXPECT_EQ(cloud.size(), 400u - removed);
  EXPECT_GT(removed, 20u);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_EQ(cloud.natural_id[i], static_cast<int64_t>(i));
    EXPECT_GE(std::hypot(cloud.x[2 * i] - 10.0, cloud.x[2 * i + 1] - 10.0), 3.0);
  }
}

TEST(Lattice, PointOnAHoleRimIsMaterial)
{
  Body<2> body = test::plate(4, 4, 1.0, 1.0);
  body.holes.push_back({2.0, 2.0, 1.0});
  body.holes.push_back({2.0, 2.0, 1.5}); // overlaps the first: the first one is named
  EXPECT_EQ(hole_containing(body, 2.5, 2.0), 0);
  EXPECT_EQ(hole_containing(body, 3.25, 2.0), 1);
  EXPECT_EQ(hole_containing(body, 3.5, 2.0), -1); // distance == radius: on the rim
  EXPECT_EQ(hole_containing(body, 0.5, 0.5), -1);
}

TEST(Lattice, PointCountMatchesWhatIsBuilt)
{
  Body<2> body = test::plate(20, 20, 1.0, 1.0);
  EXPECT_EQ(lattice_point_count(body), 400);
  body.holes.push_back({10.0, 10.0, 3.0});
  body.holes.push_back({4.0, 15.0, 2.5});
  EXPECT_EQ(lattice_point_count(body), static_cast<int64_t>(make_lattice(body).size()));
  EXPECT_LT(lattice_point_count(body), 400 - 20);
}

TEST(Lattice, PointCountMatchesWithOverlappingHolesOnCellCentres)
{
  // Radii that put cell centres exactly on rims (distance == radius keeps the point),
  // overlapping holes and holes touching the edges: the row-by-row count must agree
  // with the cell-by-cell rule to the last point.
  Body<2> body = test::plate(37, 23, 0.5, 1.0);
  body.holes  = {{5.0, 5.0, 2.5}, {6.25, 5.25, 1.5}, {12.0, 8.0, 3.5}, {2.25, 9.25, 2.25}, {17.0, 2.0, 1.0}, {9.0, 6.0, 0.1}};
  EXPECT_EQ(lattice_point_count(body), static_cast<int64_t>(make_lattice(body).size()));
}

TEST(Lattice, CellCountsAre64Bit)
{
  // 1e5 x 1e5 cells: 1e10 points, beyond int32; counted, never built.
  Body<2> body = test::plate(1, 1, 1.0, 1.0);
  body.width = body.height = 1.0;
  body.dx                  = 1e-5;
  const LatticeCells cells = lattice_cells(body);
  EXPECT_EQ(cells.nx, 100000);
  EXPECT_EQ(cells.ny, 100000);
  EXPECT_EQ(lattice_point_count(body), int64_t{10000000000});
}

TEST(Lattice, RejectsNonPositiveSpacing)
{
  Body<2> body = test::plate(4, 4);
  body.dx     = 0.0;
  EXPECT_THROW(make_lattice(body), std::invalid_argument);
}

} // namespace
} // namespace bapd
