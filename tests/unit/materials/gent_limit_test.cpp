// Behaviour at the Gent chain-extension limit I1bar - 3 = Jm (docs/method.md section 4):
// beyond it every evaluation returns StressStatus::chain_limit and writes no stress
// (the bond kernel breaks the bond when failure is on, otherwise the run stops with
// describe(chain_limit), which names -material_Jm); just below it the stress is
// finite and large.
#include <gtest/gtest.h>

#include <cstring>

#include "bapd/core/materials/models.hpp"
#include "materials/deformations.hpp"

namespace bapd {
namespace {

constexpr double mu = 4.55e3, Jm = 162.6;

// Isochoric uniaxial stretch diag(l, l^-1/2, l^-1/2): I1bar = l^2 + 2/l. Returns the
// l where I1bar = Jm + 3 (bisection; I1bar increases for l > 1).
double uniaxial_limit_stretch()
{
  double lo = 1.0, hi = 100.0;
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (lo + hi);
    (m * m + 2.0 / m < Jm + 3.0 ? lo : hi) = m;
  }
  return lo;
}
Mat3 isochoric_uniaxial(double l) { return {l, 0, 0, 0, 1 / std::sqrt(l), 0, 0, 0, 1 / std::sqrt(l)}; }

TEST(GentLimit, Gent3DBeyondChainLimitReturnsChainLimit)
{
  const Gent3D model{test::parameters(mu, Jm, 2.0 / (1e4 * mu))};
  const double l = uniaxial_limit_stretch() * (1.0 + 1e-6);
  Mat3         P;
  P[0] = 1.0;
  double psi = 0.0;
  EXPECT_EQ(model.stress(isochoric_uniaxial(l), P), StressStatus::chain_limit);
  EXPECT_EQ(P[0], 0.0); // no stress is written
  EXPECT_EQ(model.energy(isochoric_uniaxial(l), psi), StressStatus::chain_limit);
}

TEST(GentLimit, Gent3DJustBelowChainLimitGivesFiniteLargeStress)
{
  const MaterialParameters p = test::parameters(mu, Jm, 2.0 / (1e4 * mu));
  const double             l = uniaxial_limit_stretch() * (1.0 - 1e-4);
  Mat3                     P, P_nh;
  ASSERT_EQ(Gent3D{p}.stress(isochoric_uniaxial(l), P), StressStatus::ok);
  ASSERT_EQ(NeoHookean3D{p}.stress(isochoric_uniaxial(l), P_nh), StressStatus::ok);
  EXPECT_TRUE(std::isfinite(P[0]));
  // G = mu Jm / (Jm + 3 - I1bar) with Jm + 3 - I1bar ~ 2 l^2 1e-4 ~ 0.03: ~5000 mu
  EXPECT_GT(P[0], 1000.0 * P_nh[0]);
  double psi = 0.0;
  EXPECT_EQ(Gent3D{p}.energy(isochoric_uniaxial(l), psi), StressStatus::ok);
  EXPECT_TRUE(std::isfinite(psi));
}

// Plane stress with finite D: the least I1bar over all thicknesses is
// 3 (trC~ / (2 J~))^{2/3}. For pure shear diag(1, l), r = trC~/(2 J~) = (1 + l^2)/(2 l),
// and the model is locked for every thickness once 27 r^2 >= (Jm + 3)^3.
double pure_shear_stretch_for(double r) { return r + std::sqrt(r * r - 1.0); }
const double r_limit = std::sqrt(std::pow(Jm + 3.0, 3) / 27.0);

TEST(GentLimit, PlaneStressBeyondLimitForEveryThicknessReturnsChainLimit)
{
  for (double K_over_mu : {10.0, 1e4}) {
    const GentPlaneStress model{test::parameters(mu, Jm, 2.0 / (K_over_mu * mu))};
    const double          l   = pure_shear_stretch_for(r_limit * (1.0 + 1e-6)); // about 820
    double                c33 = 0.3, psi = 0.0;
    Mat2                  P   = {1, 1, 1, 1};
    EXPECT_EQ(model.stress({1.0, 0.0, 0.0, l}, c33, P), StressStatus::chain_limit);
    EXPECT_EQ(c33, 0.3); // the warm start is kept for the next call
    for (double v : P) EXPECT_EQ(v, 0.0);
    EXPECT_EQ(model.energy({1.0, 0.0, 0.0, l}, c33, psi), StressStatus::chain_limit);
  }
}

TEST(GentLimit, PlaneStressJustBelowLimitGivesFiniteLargeStress)
{
  for (double K_over_mu : {10.0, 1e4}) {
    const MaterialParameters p = test::parameters(mu, Jm, 2.0 / (K_over_mu * mu));
    const Mat2               F = {1.0, 0.0, 0.0, pure_shear_stretch_for(r_limit * (1.0 - 1e-4))};
    double                   c33 = 0.0, c33_nh = 0.0;
    Mat2                     P, P_nh;
    const PlaneStressSolution s = GentPlaneStress{p}.solve(F, 0.0);
    ASSERT_EQ(s.status, StressStatus::ok);
    ASSERT_EQ(GentPlaneStress{p}.stress(F, c33, P), StressStatus::ok);
    ASSERT_EQ(NeoHookeanPlaneStress{p}.stress(F, c33_nh, P_nh), StressStatus::ok);
    EXPECT_TRUE(std::isfinite(P[3]));
    EXPECT_GT(P[3], 10.0 * P_nh[3]); // the admissible thickness range is narrow: G >> mu
    EXPECT_LT(s.evaluations, 60);
  }
}

TEST(GentLimit, PlaneStressPastIncompressibleLimitThickensAndStiffensOnBulkScale)
{
  // Incompressible pure shear locks at l^2 + l^-2 + 1 = Jm + 3 (l ~ 12.8). With a
  // finite D the sheet thickens instead (J > 1) and the stress is set by K = 2/D.
  const double l = 13.0, K = 1e4 * mu;
  const GentPlaneStress model{test::parameters(mu, Jm, 2.0 / K)};
  double                c33 = 0.0;
  Mat2                  P, P_below;
  ASSERT_EQ(model.stress({1.0, 0.0, 0.0, l}, c33, P), StressStatus::ok);
  const double J = std::sqrt(c33) * l;
  EXPECT_GT(J, 1.01);          // incompressible would need J = 1, which is locked here
  EXPECT_LT(P[3], K * J * J);  // finite, bounded by the volumetric stress scale
  double c_below = 0.0;
  ASSERT_EQ(model.stress({1.0, 0.0, 0.0, 5.125}, c_below, P_below), StressStatus::ok);
  EXPECT_GT(P[3], 10.0 * P_below[3]); // far stiffer than on the paper's loading range
}

TEST(GentLimit, ChainLimitMessageNamesTheOption)
{
  EXPECT_NE(std::strstr(describe(StressStatus::chain_limit), "-material_Jm"), nullptr);
  EXPECT_STREQ(to_string(StressStatus::chain_limit), "chain_limit");
}

} // namespace
} // namespace bapd
