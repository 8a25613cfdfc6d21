// Bond geometry: K_ij^{-1}, phi_xi / phi, usable K (paper eqs 8, 11, 15, 23; docs/method.md 2-3).
#include <gtest/gtest.h>

#include <cmath>

#include "bapd/core/kernel/ba_force.hpp"
#include "bapd/core/kernel/bond_geometry.hpp"
#include "unit/test_models.hpp"

namespace bapd {
namespace {

TEST(BondGeometry, ShapeTensorInverseInvertsTheBondAssociatedShapeTensor)
{
  Body<2> body = test::plate(16, 16, 0.5e-3);
  body.holes.push_back({8 * 0.5e-3, 8 * 0.5e-3, 2.2 * 0.5e-3});
  test::Discretisation d(body);
  const Families      &f = d.families;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < f.size(i); ++q) {
      const std::size_t b = f.offsets[i] + q;
      double            k00 = 0, k01 = 0, k11 = 0; // eq 8, straight from the definition
      for (std::size_t p = 0; p < f.size(i); ++p) {
        if (!(f.ba(b)[p / 64] >> (p % 64) & 1u)) continue;
        const std::size_t k  = static_cast<std::size_t>(f.neighbour[f.offsets[i] + p]);
        const double      d0 = d.cloud.x[2 * k] - d.cloud.x[2 * i], d1 = d.cloud.x[2 * k + 1] - d.cloud.x[2 * i + 1];
        k00 += d0 * d0 * d.cloud.volume[k], k01 += d0 * d1 * d.cloud.volume[k], k11 += d1 * d1 * d.cloud.volume[k];
      }
      const nd::BondShape<2> shape = nd::bond_shape<2>(d.cloud, f, d.state, i, q);
      ASSERT_TRUE(shape.usable);
      const auto &ki    = shape.shape_tensor_inv;
      const Mat2  KKinv = Mat2{k00, k01, k01, k11} * Mat2{ki[0], ki[1], ki[1], ki[2]};
      // cond(K) <= ~30 here: K K^{-1} = I to a few hundred eps
      EXPECT_LT(test::norm(KKinv - identity2()), 1e-13) << i << " " << q;
    }
}

TEST(BondGeometry, ForceScaleIsHalfTheVolumeFractionOverPhi)
{
  test::Discretisation d(test::plate(20, 20, 0.5e-3));
  const Families      &f = d.families;
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t q = 0; q < f.size(i); ++q) {
      const std::size_t b = f.offsets[i] + q, j = static_cast<std::size_t>(f.neighbour[b]);
      std::size_t       members = 0;
      for (std::size_t p = 0; p < f.size(i); ++p) members += f.ba(b)[p / 64] >> (p % 64) & 1u;
      const double    phi_xi = static_cast<double>(members) / static_cast<double>(f.size(i)); // equal volumes
      const double    phi    = static_cast<double>(f.size(i)) / static_cast<double>(f.size(i) + f.size(j));
      const nd::BondShape<2> shape  = nd::bond_shape<2>(d.cloud, f, d.state, i, q);
      EXPECT_NEAR(shape.force_scale, 0.5 * phi_xi / phi, 1e-15); // a few roundings of O(1) numbers
      EXPECT_NEAR(shape.volume_fraction, phi_xi, 1e-15);
    }
  // Interior: phi = 1/2, so the scale is the volume fraction itself (11 to 21 of 28).
  const std::size_t c = 10 * 20 + 10;
  for (std::size_t q = 0; q < 28; ++q) {
    const double s = nd::bond_shape<2>(d.cloud, f, d.state, c, q).force_scale * 28.0;
    EXPECT_NEAR(s, std::round(s), 1e-13);
    EXPECT_GE(std::round(s), 11.0);
    EXPECT_LE(std::round(s), 21.0);
  }
}

TEST(BondGeometry, KernelCatchesAShapeTensorThatWentSingularSinceTheGeometry)
{
  // Break bonds without recomputing the geometry: the kernel still must not divide by
  // a singular K (it repeats the test), and counts the bond as unusable.
  test::Discretisation d(test::plate(20, 20, 1.0));
  const std::size_t    i = 10 * 20 + 10;
  for (std::size_t q = 0; q < d.families.size(i); ++q) {
    const std::size_t j = static_cast<std::size_t>(d.families.neighbour[d.families.offsets[i] + q]);
    if (d.cloud.x[2 * j + 1] != d.cloud.x[2 * i + 1]) break_bond(d.families, d.state, i, q);
  }
  test::SaintVenantKirchhoff2D svk;
  std::vector<double>          t, f;
  const KernelStats            s = d.forces(svk, d.affine({1.1, 0.2, 0.0, 0.9}), t, f);
  EXPECT_EQ(s.unusable, 6u); // the 6 bonds along the row: collinear B_ij
  for (double v : t) EXPECT_TRUE(std::isfinite(v));
  EXPECT_EQ(d.geometry.count_unusable(d.size()), 0u); // stale, as set up
}

TEST(BondGeometry, MissingGhostFamilyVolumeIsReported)
{
  test::Discretisation d(test::plate(12, 12, 0.5e-3));
  PointCloud           c = d.cloud;
  c.family_volume.clear();
  const Families f = build_families(c, 50, d.horizon, {}); // ring-2 V(H) not shipped
  compute_family_volumes(c, f);
  nd::BondGeometry<2> g;
  EXPECT_THROW(nd::compute_bond_geometry<2>(c, f, BondState(f), g), std::invalid_argument);
}

} // namespace
} // namespace bapd
