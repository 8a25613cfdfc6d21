// Every model's stress is the derivative of its energy, vanishes at rest, is
// objective, and reports inverted deformations (docs/method.md section 4, "checks that
// must hold").
#include <gtest/gtest.h>

#include "bapd/core/materials/models.hpp"
#include "materials/deformations.hpp"
#include "materials/law_types.hpp"

namespace bapd {
namespace {

constexpr double mu = 4.55e3, Jm = 162.6;
// Bulk moduli K = 2/D from soft (100 mu) to nearly incompressible (1e4 mu).
const double compressibilities[] = {2.0 / (100.0 * mu), 2.0 / (1e4 * mu)};

MaterialParameters parameters(double D) { return test::parameters(mu, Jm, D); }

// ---------------------------------------------------------------------------------
// The 2D models, as the bond kernel sees them.
template <class Model> class MaterialStress2D : public ::testing::Test {};
using Models2D = test::Models2D;
TYPED_TEST_SUITE(MaterialStress2D, Models2D);

TYPED_TEST(MaterialStress2D, StressIsDerivativeOfEnergyAtRandomLargeStretches)
{
  std::mt19937 rng(20240611);
  for (double D : compressibilities) {
    const TypeParam model{parameters(D)};
    for (int sample = 0; sample < 200; ++sample) {
      // principal stretches in [1/8, 8]; the first samples pin the extremes
      Mat2 F = test::random_F2(rng, 8.0);
      if (sample == 0) F = {8.0, 0.0, 0.0, 1.0};
      if (sample == 1) F = test::rotation2(0.3) * Mat2{8.0, 0.0, 0.0, 8.0};
      if (sample == 2) F = {1.0, 7.0, 0.0, 1.0}; // simple shear
      double c33 = 0.0;
      Mat2   P;
      ASSERT_EQ(model.stress(F, c33, P), StressStatus::ok) << "sample " << sample;
      const double c33_solved = c33;
      auto         energy     = [&](const Mat2 &G) {
        double c = c33_solved, psi = 0.0; // the plane-stress energy re-solves C33 at G
        EXPECT_EQ(model.energy(G, c, psi), StressStatus::ok);
        return psi;
      };
      const Mat2 P_fd = test::energy_gradient(F, energy, 1e-6);
      // central difference, h = 1e-6 max|F|: truncation (h/s_min)^2 ~ 1e-9, round-off
      // eps |psi| / h ~ 1e-9 of |P|; the C33 solve error enters psi only at second order.
      EXPECT_LT(test::relative_difference(P, P_fd, mu), 1e-6) << "sample " << sample << " D " << D;
    }
  }
}

TYPED_TEST(MaterialStress2D, StressVanishesAtRest)
{
  for (double D : compressibilities) {
    const TypeParam model{parameters(D)};
    double          c33 = 0.0;
    Mat2            P;
    ASSERT_EQ(model.stress(identity2(), c33, P), StressStatus::ok);
    for (double v : P) EXPECT_LT(std::abs(v), 1e-12 * mu); // round-off of O(mu) and O(1/D) terms
    EXPECT_NEAR(c33, 1.0, 1e-14);                          // C33 = 1 solves S33 = 0 exactly at rest
  }
}

TYPED_TEST(MaterialStress2D, StressIsObjective)
{
  std::mt19937 rng(7);
  for (double D : compressibilities) {
    const TypeParam model{parameters(D)};
    for (int sample = 0; sample < 50; ++sample) {
      const Mat2 F = test::random_F2(rng, 8.0), Q = test::rotation2(test::uniform(rng, 0, 6.283185307179586));
      double     c1 = 0.0, c2 = 0.0;
      Mat2       P, PQ;
      ASSERT_EQ(model.stress(F, c1, P), StressStatus::ok);
      ASSERT_EQ(model.stress(Q * F, c2, PQ), StressStatus::ok);
      // P(QF) = Q P(F); the two C33 solves each stop within 1e-12 of the stress scale
      EXPECT_LT(test::relative_difference(PQ, Q * P, mu), 1e-10) << "sample " << sample;
      EXPECT_NEAR(c1, c2, 1e-10 * c1);
    }
  }
}

TYPED_TEST(MaterialStress2D, InvertedDeformationIsReported)
{
  const TypeParam model{parameters(compressibilities[0])};
  for (const Mat2 &F : {Mat2{1.0, 0.0, 0.0, -1.0}, Mat2{0.0, 0.0, 0.0, 0.0}, Mat2{1.0, 2.0, 1.0, 2.0}}) {
    double c33 = 0.7;
    Mat2   P   = {1, 1, 1, 1};
    EXPECT_EQ(model.stress(F, c33, P), StressStatus::inverted);
    for (double v : P) EXPECT_EQ(v, 0.0);
    double psi = 0.0;
    EXPECT_EQ(model.energy(F, c33, psi), StressStatus::inverted);
  }
}

// ---------------------------------------------------------------------------------
// The 3D laws (paper eq 26).
template <class Model> class Material3D : public ::testing::Test {};
using Models3D = test::Models3D;
TYPED_TEST_SUITE(Material3D, Models3D);

TYPED_TEST(Material3D, StressIsDerivativeOfEnergyAtRandomLargeStretches)
{
  std::mt19937 rng(12345);
  for (double D : compressibilities) {
    const TypeParam model{parameters(D)};
    for (int sample = 0; sample < 200; ++sample) {
      Mat3 F = test::random_F3(rng, 8.0);
      if (sample == 0) F = {8.0, 0, 0, 0, 1.0 / std::sqrt(8.0), 0, 0, 0, 1.0 / std::sqrt(8.0)};
      Mat3 P;
      ASSERT_EQ(model.stress(F, P), StressStatus::ok) << "sample " << sample;
      auto energy = [&](const Mat3 &G) {
        double psi = 0.0;
        EXPECT_EQ(model.energy(G, psi), StressStatus::ok);
        return psi;
      };
      // central difference, h = 1e-6 max|F|: truncation and round-off ~ 1e-9 of |P|
      EXPECT_LT(test::relative_difference(P, test::energy_gradient(F, energy, 1e-6), mu), 1e-6)
          << "sample " << sample;
    }
  }
}

TYPED_TEST(Material3D, StressVanishesAtRestAndIsObjective)
{
  std::mt19937    rng(99);
  const TypeParam model{parameters(compressibilities[1])};
  Mat3            P;
  ASSERT_EQ(model.stress(identity3(), P), StressStatus::ok);
  for (double v : P) EXPECT_LT(std::abs(v), 1e-12 * mu); // round-off of O(mu) and O(1/D) terms
  for (int sample = 0; sample < 50; ++sample) {
    const Mat3 F = test::random_F3(rng, 8.0), Q = test::random_rotation3(rng);
    Mat3       PQ;
    ASSERT_EQ(model.stress(F, P), StressStatus::ok);
    ASSERT_EQ(model.stress(test::mul(Q, F), PQ), StressStatus::ok);
    // only round-off differs: a few eps times the largest term, incl. (1/D) J^2
    EXPECT_LT(test::relative_difference(PQ, test::mul(Q, P), mu), 1e-11) << "sample " << sample;
  }
}

TYPED_TEST(Material3D, InvertedDeformationIsReported)
{
  const TypeParam model{parameters(compressibilities[0])};
  Mat3            P;
  double          psi = 0.0;
  const Mat3      mirror = {1, 0, 0, 0, 1, 0, 0, 0, -1};
  EXPECT_EQ(model.stress(mirror, P), StressStatus::inverted);
  EXPECT_EQ(model.energy(mirror, psi), StressStatus::inverted);
}

// ---------------------------------------------------------------------------------
// Plane strain is the 3D law at F33 = 1.
template <class Law> class MaterialPlaneStrain : public ::testing::Test {};
using Laws = test::InvariantLawTypes;
TYPED_TEST_SUITE(MaterialPlaneStrain, Laws);

TYPED_TEST(MaterialPlaneStrain, EqualsInPlaneBlockOf3DLawWithUnitThicknessStretch)
{
  std::mt19937 rng(3);
  for (double D : compressibilities) {
    const PlaneStrain<TypeParam>    model2{parameters(D)};
    const Compressible3D<TypeParam> model3{parameters(D)};
    for (int sample = 0; sample < 50; ++sample) {
      const Mat2 F   = test::random_F2(rng, 8.0);
      double     c33 = 0.0, psi2 = 0.0, psi3 = 0.0;
      Mat2       P2;
      Mat3       P3;
      ASSERT_EQ(model2.stress(F, c33, P2), StressStatus::ok);
      EXPECT_EQ(c33, 1.0);
      ASSERT_EQ(model3.stress(embed(F, 1.0), P3), StressStatus::ok);
      // same formula, different operation order: round-off only
      EXPECT_LT(test::relative_difference(P2, Mat2{P3[0], P3[1], P3[3], P3[4]}, mu), 1e-12);
      ASSERT_EQ(model2.energy(F, c33, psi2), StressStatus::ok);
      ASSERT_EQ(model3.energy(embed(F, 1.0), psi3), StressStatus::ok);
      EXPECT_NEAR(psi2, psi3, 1e-13 * std::max(std::abs(psi3), mu));
    }
  }
}

} // namespace
} // namespace bapd
