// 3D families and BA families of the generic core (family.hpp): family sizes and
// mask words at the paper's three horizons, the cell search against a direct search,
// and the BA mask symmetry the energy-consistent form relies on.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>
#include <set>

#include "unit/kernel_fixtures_3d.hpp"

namespace bapd {
namespace {

using test3d::kDx;

// Lattice offsets o != 0 with |o| <= factor (in dx): an interior point's family.
int interior_members(double factor)
{
  int n = 0;
  for (int a = -4; a <= 4; ++a)
    for (int b = -4; b <= 4; ++b)
      for (int c = -4; c <= 4; ++c) n += (a || b || c) && a * a + b * b + c * c <= factor * factor;
  return n;
}

TEST(Family3D, InteriorFamilySizeAndMaskWordsAtThePapersHorizons)
{
  // Lattice points in a ball of radius delta (the origin left out): 80, 122 and 178
  // members (81, 123 and 179 with the origin), hence 2, 2 and 3 words a mask.
  const double      factors[] = {2.515, 3.015, 3.515};
  const int         members[] = {80, 122, 178};
  const std::size_t words[]   = {2, 2, 3};
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(interior_members(factors[k]), members[k]); // the counting above, by hand
    const test3d::Body3D b(9, factors[k]); // the centre is 4 dx >= delta from every face
    const std::size_t    centre = 4 + 9 * 4 + 81 * 4;
    EXPECT_EQ(b.families.size(centre), static_cast<std::size_t>(members[k])) << factors[k];
    EXPECT_EQ(b.families.max_family_size, static_cast<std::size_t>(members[k]));
    EXPECT_EQ(b.families.mask_words, words[k]);
    EXPECT_EQ(b.families.mask_words, (b.families.max_family_size + 63) / 64);
    // The BA family of an interior bond: every member within delta of j, plus j.
    std::size_t smallest = 1000, largest = 0;
    for (std::size_t q = 0; q < b.families.size(centre); ++q) {
      std::size_t n = 0;
      for (std::size_t w = 0; w < b.families.mask_words; ++w)
        n += static_cast<std::size_t>(__builtin_popcountll(b.families.ba(b.families.offsets[centre] + q)[w]));
      smallest = std::min(smallest, n), largest = std::max(largest, n);
    }
    EXPECT_GT(smallest, 0.25 * members[k]); // the lens of two balls delta apart: 5/16 of one
    EXPECT_LT(largest, static_cast<std::size_t>(members[k]));
  }
}

TEST(Family3D, CellSearchFindsWhatADirectSearchFinds)
{
  // A jittered 7 x 6 x 5 lattice with scrambled natural ids, per-point horizons on
  // half of the points: families, order, BA masks and reverse bonds against O(n^2).
  std::mt19937     rng(5);
  const PointCloud box = nd::box_lattice<3>({7, 6, 5}, kDx);
  PointCloud       c   = box;
  for (double &x : c.x) x += (static_cast<double>(rng()) / 4294967296.0 - 0.5) * 0.3 * kDx;
  std::vector<int64_t> ids(c.size());
  std::iota(ids.begin(), ids.end(), 0);
  std::shuffle(ids.begin(), ids.end(), rng);
  c.natural_id = ids;
  c.horizon.assign(c.size(), 2.515 * kDx);
  for (std::size_t i = 0; i < c.size(); i += 2) c.horizon[i] = 3.015 * kDx;
  const std::size_t n_family = c.size() - 20; // the last 20 points: ghosts without a family
  const Families    f        = nd::build_families<3>(c, n_family, 3.015 * kDx);
  auto              within   = [&](std::size_t a, std::size_t b) {
    double d2 = 0;
    for (int r = 0; r < 3; ++r) d2 += (c.x[3 * b + r] - c.x[3 * a + r]) * (c.x[3 * b + r] - c.x[3 * a + r]);
    const double h = std::max(c.horizon[a], c.horizon[b]);
    return d2 <= h * h;
  };
  std::size_t bonds = 0;
  for (std::size_t i = 0; i < n_family; ++i) {
    std::vector<std::size_t> expected;
    for (std::size_t j = 0; j < c.size(); ++j)
      if (j != i && within(i, j)) expected.push_back(j);
    std::sort(expected.begin(), expected.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
    ASSERT_EQ(f.size(i), expected.size()) << "point " << i;
    for (std::size_t q = 0; q < expected.size(); ++q) {
      const std::size_t b = f.offsets[i] + q, j = expected[q];
      ASSERT_EQ(static_cast<std::size_t>(f.neighbour[b]), j);
      for (std::size_t p = 0; p < expected.size(); ++p)
        ASSERT_EQ((f.ba(b)[p / 64] >> (p % 64)) & 1u, within(j, expected[p]) ? 1u : 0u);
      if (j < n_family) ASSERT_EQ(static_cast<std::size_t>(f.neighbour[static_cast<std::size_t>(f.reverse[b])]), i);
      else ASSERT_EQ(f.reverse[b], -1);
    }
    bonds += expected.size();
  }
  EXPECT_GT(bonds, 10000u); // not vacuous
}

TEST(Family3D, BaMasksAreSymmetricWithinAFamily)
{
  // p in B_iq iff q in B_ip: the premise of the energy-consistent form (ba_force.hpp).
  const test3d::Body3D b(8, 3.015);
  std::size_t          checked = 0;
  for (std::size_t i = 0; i < b.size(); i += 7)
    for (std::size_t p = 0; p < b.families.size(i); ++p)
      for (std::size_t q = 0; q < b.families.size(i); ++q) {
        const bool pq = (b.families.ba(b.families.offsets[i] + q)[p / 64] >> (p % 64)) & 1u;
        const bool qp = (b.families.ba(b.families.offsets[i] + p)[q / 64] >> (q % 64)) & 1u;
        ASSERT_EQ(pq, qp);
        checked += pq;
      }
  EXPECT_GT(checked, 100000u);
}

} // namespace
} // namespace bapd
