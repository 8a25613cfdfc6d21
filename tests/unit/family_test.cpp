// build_families, BA masks, reverse index, family volumes (docs/method.md sections 1-3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "bapd/core/geometry/family.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

// Lattice offsets (a, b) != 0 with a^2 + b^2 <= h^2 (h in units of dx).
std::size_t disc_count(double h)
{
  std::size_t n = 0;
  for (int a = -6; a <= 6; ++a)
    for (int b = -6; b <= 6; ++b) n += (a || b) && a * a + b * b <= h * h;
  return n;
}

TEST(Families, InteriorCountEqualsLatticePointsInTheHorizon)
{
  const double    dx = 0.5e-3;
  test::Discretisation d(test::plate(20, 20, dx));
  EXPECT_EQ(disc_count(3.015), 28u);
  for (std::size_t i = 0; i < d.size(); ++i) {
    const int ix = d.ix(i, dx), iy = d.iy(i, dx);
    const bool full = ix >= 3 && ix <= 16 && iy >= 3 && iy <= 16; // a whole disc fits
    if (full) EXPECT_EQ(d.families.size(i), 28u);
    else EXPECT_LT(d.families.size(i), 28u);
  }
  EXPECT_EQ(d.families.size(0), 10u); // corner: quarter disc, 0 <= a, b <= 3, a^2 + b^2 <= 9.09, minus self
  EXPECT_EQ(d.families.max_family_size, 28u);
  EXPECT_EQ(d.families.mask_words, 1u);
}

TEST(Families, AreSymmetricSortedAndReverseIndexIsConsistent)
{
  Body<2> body = test::plate(20, 20, 1.0);
  body.holes.push_back({8.0, 11.0, 3.2});
  test::Discretisation d(body);
  const Families &f = d.families;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t b = f.offsets[i]; b < f.offsets[i + 1]; ++b) {
      const std::size_t j = static_cast<std::size_t>(f.neighbour[b]);
      EXPECT_NE(j, i);
      if (b > f.offsets[i]) {
        EXPECT_LT(d.cloud.natural_id[static_cast<std::size_t>(f.neighbour[b - 1])], d.cloud.natural_id[j]);
      }
      ASSERT_GE(f.reverse[b], 0);
      const std::size_t r = static_cast<std::size_t>(f.reverse[b]);
      ASSERT_GE(r, f.offsets[j]);
      ASSERT_LT(r, f.offsets[j + 1]);
      EXPECT_EQ(static_cast<std::size_t>(f.neighbour[r]), i);
      EXPECT_EQ(static_cast<std::size_t>(f.reverse[r]), b);
    }
}

TEST(Families, CellSearchFindsExactlyThePointsWithinTheHorizon)
{
  // Random points (no lattice symmetry to hide a missed cell), brute force O(n^2).
  std::mt19937 rng(7);
  PointCloud   c;
  for (int i = 0; i < 600; ++i) {
    c.x.push_back(test::random_between(rng, -3.0, 11.0));
    c.x.push_back(test::random_between(rng, 2.0, 7.0));
    c.volume.push_back(1.0);
    c.natural_id.push_back(1000 - 3 * i); // ids in reverse of the local order
  }
  const double   h = 0.9;
  const Families f = build_families(c, 500, h, {}); // the last 100 points have no family
  ASSERT_EQ(f.n_family, 500u);
  for (std::size_t i = 0; i < 500; ++i) {
    std::vector<int64_t> expect, got;
    for (std::size_t j = 0; j < c.size(); ++j)
      if (j != i && std::hypot(c.x[2 * j] - c.x[2 * i], c.x[2 * j + 1] - c.x[2 * i + 1]) <= h)
        expect.push_back(c.natural_id[j]);
    std::sort(expect.begin(), expect.end());
    for (std::size_t b = f.offsets[i]; b < f.offsets[i + 1]; ++b) got.push_back(c.natural_id[static_cast<std::size_t>(f.neighbour[b])]);
    EXPECT_EQ(got, expect) << "point " << i;
    for (std::size_t b = f.offsets[i]; b < f.offsets[i + 1]; ++b)
      EXPECT_EQ(f.reverse[b] < 0, static_cast<std::size_t>(f.neighbour[b]) >= 500u);
  }
}

TEST(Families, BondAssociatedMasksHoldExactlyTheMembersWithinTheHorizonOfJ)
{
  test::Discretisation d(test::plate(20, 20, 1.0));
  const Families &f = d.families;
  const double    h = d.horizon;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < f.size(i); ++q) {
      const std::size_t b = f.offsets[i] + q, j = static_cast<std::size_t>(f.neighbour[b]);
      EXPECT_TRUE(f.ba(b)[q / 64] >> (q % 64) & 1u) << "j itself belongs to B_ij";
      for (std::size_t p = 0; p < f.size(i); ++p) {
        const std::size_t k   = static_cast<std::size_t>(f.neighbour[f.offsets[i] + p]);
        const bool        in  = std::hypot(d.cloud.x[2 * k] - d.cloud.x[2 * j], d.cloud.x[2 * k + 1] - d.cloud.x[2 * j + 1]) <= h;
        EXPECT_EQ(static_cast<bool>(f.ba(b)[p / 64] >> (p % 64) & 1u), in);
      }
      for (std::size_t p = f.size(i); p < 64 * f.mask_words; ++p) EXPECT_FALSE(f.ba(b)[p / 64] >> (p % 64) & 1u);
    }
}

TEST(Families, WideHorizonUsesSeveralMaskWords)
{
  // delta = 5.015 dx: 80 neighbours > 64, two mask words; masks still match the definition.
  test::Discretisation d(test::plate(24, 24, 1.0), 5.015);
  EXPECT_EQ(disc_count(5.015), 80u);
  EXPECT_EQ(d.families.max_family_size, 80u);
  EXPECT_EQ(d.families.mask_words, 2u);
  const std::size_t i = 12 * 24 + 12; // interior
  ASSERT_EQ(d.families.size(i), 80u);
  for (std::size_t q = 0; q < 80; ++q) {
    const std::size_t b = d.families.offsets[i] + q, j = static_cast<std::size_t>(d.families.neighbour[b]);
    std::size_t       members = 0, expected = 0;
    for (std::size_t p = 0; p < 80; ++p) {
      members += d.families.ba(b)[p / 64] >> (p % 64) & 1u;
      const std::size_t k = static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + p]);
      expected += std::hypot(d.cloud.x[2 * k] - d.cloud.x[2 * j], d.cloud.x[2 * k + 1] - d.cloud.x[2 * j + 1]) <= d.horizon;
    }
    EXPECT_EQ(members, expected);
    EXPECT_TRUE(d.state.is_intact(i, q));
  }
}

TEST(Families, NotchRemovesEveryCrossingBondAndShrinksNearbyFamilies)
{
  const double dx   = 1.0;
  Body<2>       body = test::plate(20, 20, dx);
  // Horizontal notch entering from the right edge to the middle, between rows 9 and 10.
  body.notches.push_back({20.0, 10.0, 10.0, 10.0});
  test::Discretisation d(body);
  const Families &f = d.families;
  for (std::size_t i = 0; i < d.size(); ++i) {
    // Independent check for this horizontal notch: a bond crosses it iff its ends are
    // on opposite sides of y = 10 and it meets y = 10 at 10 < x < 20.
    for (std::size_t j = 0; j < d.size(); ++j) {
      const double xi = d.cloud.x[2 * i], yi = d.cloud.x[2 * i + 1], xj = d.cloud.x[2 * j], yj = d.cloud.x[2 * j + 1];
      if (j == i || std::hypot(xj - xi, yj - yi) > d.horizon) continue;
      const bool opposite = (yi - 10.0) * (yj - 10.0) < 0;
      const double xc     = opposite ? xi + (xj - xi) * (10.0 - yi) / (yj - yi) : 0.0;
      const bool   cut    = opposite && xc > 10.0 && xc < 20.0;
      const bool   bonded = std::count(f.neighbour.begin() + f.offsets[i], f.neighbour.begin() + f.offsets[i + 1],
                                       static_cast<std::int32_t>(j)) == 1;
      EXPECT_EQ(bonded, !cut) << i << " " << j;
    }
  }
  // Point (15, 10) sits right above the notch: half its lower neighbours are gone.
  const std::size_t above = 10 * 20 + 15, away = 10 * 20 + 5;
  EXPECT_EQ(f.size(away), 28u);
  EXPECT_LT(f.size(above), 20u);
  // Notch bonds never existed: they are not damage and not in V(H).
  double v = 0;
  for (std::size_t b = f.offsets[above]; b < f.offsets[above + 1]; ++b) v += d.cloud.volume[static_cast<std::size_t>(f.neighbour[b])];
  EXPECT_EQ(d.cloud.family_volume[above], v);
}

TEST(Families, SegmentCrossingIsProperIntersection)
{
  const Segment s{0.0, 0.0, 2.0, 0.0};
  EXPECT_TRUE(segments_cross(1.0, -1.0, 1.0, 1.0, s));
  EXPECT_FALSE(segments_cross(3.0, -1.0, 3.0, 1.0, s)); // misses the end
  EXPECT_FALSE(segments_cross(2.0, -1.0, 2.0, 1.0, s)); // touches the end point only
  EXPECT_FALSE(segments_cross(1.0, 0.5, 1.0, 1.0, s));  // same side
  EXPECT_FALSE(segments_cross(0.5, 0.0, 1.5, 0.0, s));  // collinear overlap: not a crossing
}

TEST(Families, FamilyVolumeIsTheSumOfMemberVolumesAndGhostsAreMarkedMissing)
{
  test::Discretisation d(test::plate(12, 12, 0.5e-3));
  const double         v = d.cloud.volume[0];
  for (std::size_t i = 0; i < d.size(); ++i)
    EXPECT_NEAR(d.cloud.family_volume[i], v * static_cast<double>(d.families.size(i)), 1e-15 * v * 28); // sum of equal terms
  PointCloud     c = d.cloud;
  c.family_volume.clear();
  const Families f = build_families(c, 50, d.horizon, {});
  compute_family_volumes(c, f);
  EXPECT_EQ(c.family_volume.size(), c.size());
  EXPECT_TRUE(std::isnan(c.family_volume[60]));
}

} // namespace
} // namespace bapd
