// Incompressible plane stress (plane_stress_incompressible.hpp, docs/method.md section 4):
// C33 = 1/J~^2, P~ = dW/dF~ - p F~^{-T} with p from P33 = 0. Its stress is the
// derivative of its energy, the 3D law's at J = 1 with the pressure that clears P33,
// the limit of the compressible solve as K grows, objective, zero at rest, the
// paper's pure-shear curve; its lanes give the scalar bits, its tangent is dP/dF, and
// a law of principal stretches is refused.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "bapd/core/materials/models.hpp"
#include "materials/deformations.hpp"
#include "materials/law_types.hpp"

namespace bapd {
namespace {

constexpr double mu = 4.55e3, Jm = 162.6;
MaterialParameters parameters() { return test::parameters(mu, Jm, 2.0 / (1e4 * mu)); }

template <class Law> struct IncompressibleOf {
  using type = PlaneStressIncompressible<Law>;
};
template <class Model> struct LawOfModel;
template <class Law> struct LawOfModel<PlaneStressIncompressible<Law>> {
  using type = Law;
};
using Models = test::GTestTypes<typename test::MapOf<IncompressibleOf, test::InvariantLaws>::type>;

template <class Model> class IncompressiblePlaneStress : public ::testing::Test {};
TYPED_TEST_SUITE(IncompressiblePlaneStress, Models);

// Principal stretches in [1/2.5, 2.5] (C33 <= 39: below every law's default limit), and
// the extremes the solver meets: pure shear to 5, simple shear 3, equibiaxial 2.5.
std::vector<Mat2> samples(int n)
{
  std::mt19937      rng(20261207);
  std::vector<Mat2> out = {{1.0, 0.0, 0.0, 5.0}, {1.0, 3.0, 0.0, 1.0}, test::rotation2(0.3) * Mat2{2.5, 0.0, 0.0, 2.5}};
  while (static_cast<int>(out.size()) < n) out.push_back(test::random_F2(rng, 2.5));
  return out;
}

TYPED_TEST(IncompressiblePlaneStress, StressIsDerivativeOfEnergy)
{
  const TypeParam model{parameters()};
  int             k = 0;
  for (const Mat2 &F : samples(200)) {
    double c33 = 0.0;
    Mat2   P;
    ASSERT_EQ(model.stress(F, c33, P), StressStatus::ok) << "sample " << k;
    const double inv_Jt = 1.0 / det(F);
    EXPECT_EQ(c33, inv_Jt * inv_Jt) << "sample " << k; // C33 = 1/J~^2, as the model rounds it
    auto energy = [&](const Mat2 &G) {
      double c = 0.0, psi = 0.0;
      EXPECT_EQ(model.energy(G, c, psi), StressStatus::ok);
      return psi;
    };
    // central difference, h = 1e-6 max|F|: truncation (h / s_min)^2 ~ 1e-11, round-off
    // eps |psi| / h ~ 1e-10 of |P| (no solve: nothing else)
    EXPECT_LT(test::relative_difference(P, test::energy_gradient(F, energy, 1e-6), mu), 1e-7) << "sample " << k;
    ++k;
  }
}

TYPED_TEST(IncompressiblePlaneStress, IsThe3DLawAtUnitVolumeWithThePressureThatClearsP33)
{
  using Law = typename LawOfModel<TypeParam>::type;
  const TypeParam           model{parameters()};
  const Compressible3D<Law> solid{parameters()};
  int                       k = 0;
  for (const Mat2 &F : samples(100)) {
    double c33 = 0.0;
    Mat2   P;
    ASSERT_EQ(model.stress(F, c33, P), StressStatus::ok);
    // J = 1: U'(1) = 0, so the 3D P is the isochoric part alone; adding -p F^{-T}, with
    // p = P33 lambda_3 (F^{-T}_33 = 1/lambda_3), clears P33 and leaves the in-plane block.
    const double lambda3 = 1.0 / det(F);
    Mat3         P3;
    ASSERT_EQ(solid.stress(embed(F, lambda3), P3), StressStatus::ok);
    const double p     = P3[8] * lambda3;
    const Mat2   FinvT = {F[3] / det(F), -F[2] / det(F), -F[1] / det(F), F[0] / det(F)};
    const Mat2   ref   = {P3[0] - p * FinvT[0], P3[1] - p * FinvT[1], P3[3] - p * FinvT[2], P3[4] - p * FinvT[3]};
    // two formulas of O(G I1) terms that cancel to O(G): round-off ~1e-14 of G I1
    EXPECT_LT(test::relative_difference(P, ref, mu), 1e-12) << "sample " << k;
    ++k;
  }
}

TYPED_TEST(IncompressiblePlaneStress, IsTheLimitOfTheCompressibleSolveAtFirstOrderInOneOverK)
{
  using Law = typename LawOfModel<TypeParam>::type;
  if constexpr (accepts_plane_stress<Law>) {
    const TypeParam model{parameters()};
    int             k = 0;
    for (const Mat2 &F : samples(50)) {
      double c = 0.0, c4 = 0.0, c6 = 0.0;
      Mat2   P, P4, P6;
      ASSERT_EQ(model.stress(F, c, P), StressStatus::ok);
      ASSERT_EQ(PlaneStress<Law>{test::parameters(mu, Jm, 2.0 / (1e4 * mu))}.stress(F, c4, P4), StressStatus::ok);
      ASSERT_EQ(PlaneStress<Law>{test::parameters(mu, Jm, 2.0 / (1e6 * mu))}.stress(F, c6, P6), StressStatus::ok);
      // J - 1 ~ sigma / K: the compressible P moves by O(mu / K) relative, 1e-4 at K = 1e4 mu
      // and 100 x less at 1e6 mu (first order; the solve's own error is 1e-12)
      const double d4 = test::relative_difference(P4, P, mu), d6 = test::relative_difference(P6, P, mu);
      EXPECT_LT(d4, 1e-2) << "sample " << k;
      EXPECT_NEAR(d4 / std::max(d6, 1e-300), 100.0, 10.0) << "sample " << k;
      EXPECT_NEAR(c6, c, 1e-4 * c) << "sample " << k;
      ++k;
    }
  }
}

TYPED_TEST(IncompressiblePlaneStress, StressVanishesAtRestAndIsObjective)
{
  const TypeParam model{parameters()};
  double          c33 = 0.0;
  Mat2            P;
  ASSERT_EQ(model.stress(identity2(), c33, P), StressStatus::ok);
  EXPECT_EQ(c33, 1.0);
  for (double v : P) EXPECT_LT(std::abs(v), 1e-12 * mu); // G (1 - 1): round-off of O(mu)
  std::mt19937 rng(3);
  for (const Mat2 &F : samples(50)) {
    const Mat2 Q = test::rotation2(test::uniform(rng, 0, 6.283185307179586));
    double     c1 = 0.0, c2 = 0.0;
    Mat2       P1, PQ;
    ASSERT_EQ(model.stress(F, c1, P1), StressStatus::ok);
    ASSERT_EQ(model.stress(Q * F, c2, PQ), StressStatus::ok);
    EXPECT_LT(test::relative_difference(PQ, Q * P1, mu), 1e-13); // round-off of Q F's entries
    EXPECT_NEAR(c1, c2, 1e-14 * c1);
  }
}

TYPED_TEST(IncompressiblePlaneStress, InvertedAndLockedDeformationsAreReported)
{
  using Law = typename LawOfModel<TypeParam>::type;
  const TypeParam model{parameters()};
  double          c33 = 0.25, psi = 0.0;
  Mat2            P;
  EXPECT_EQ(model.stress(Mat2{1.0, 0.0, 0.0, -1.0}, c33, P), StressStatus::inverted);
  EXPECT_EQ(model.energy(Mat2{0.0, 0.0, 0.0, 1.0}, c33, psi), StressStatus::inverted);
  for (double v : P) EXPECT_EQ(v, 0.0);
  EXPECT_EQ(c33, 0.25); // a failed call leaves c33 alone
  if constexpr (Law::has_limit) {
    // equibiaxial compression to 1/4: C33 = 256 is beyond every limit (Gent: Jm + 3)
    EXPECT_EQ(model.stress(Mat2{0.25, 0.0, 0.0, 0.25}, c33, P), StressStatus::chain_limit);
    EXPECT_EQ(c33, 0.25);
  }
}

TYPED_TEST(IncompressiblePlaneStress, LanesGiveTheScalarBitsAndLeaveFailuresToIt)
{
  const TypeParam   model{parameters()};
  std::vector<Mat2> F = samples(4 * lane_count);
  F[1]                = {1.0, 0.0, 0.0, -1.0};  // inverted
  F[lane_count + 2]   = {0.2, 0.0, 0.0, 0.2};   // locked where the law has a limit
  for (std::size_t b = 0; b + lane_count <= F.size(); b += lane_count) {
    std::array<Lanes, 4> FL, PL;
    Lanes                cL = Lanes{} + 7.0; // a lane not done keeps its c33
    for (int l = 0; l < lane_count; ++l)
      for (int k = 0; k < 4; ++k) FL[k][l] = F[b + l][k];
    const LaneMask done = model.stress_lanes(FL, cL, PL);
    for (int l = 0; l < lane_count; ++l) {
      double             c = 0.0;
      Mat2               P;
      const StressStatus s = model.stress(F[b + l], c, P);
      EXPECT_EQ(done[l] != 0, s == StressStatus::ok) << "bond " << b + l;
      if (s != StressStatus::ok) {
        EXPECT_EQ(cL[l], 7.0);
        continue;
      }
      EXPECT_EQ(cL[l], c) << "bond " << b + l; // bit for bit (tolerance 0)
      for (int k = 0; k < 4; ++k) EXPECT_EQ(PL[k][l], P[k]) << "bond " << b + l;
    }
  }
}

TYPED_TEST(IncompressiblePlaneStress, TangentIsTheDerivativeOfTheStress)
{
  if constexpr (TypeParam::has_tangent) {
    const TypeParam model{parameters()};
    int             n = 0;
    for (const Mat2 &F : samples(100)) {
      std::array<double, 16> A{}, A_fd{};
      ASSERT_EQ(model.tangent(F, 0.0, A), StressStatus::ok);
      double scale = 0.0;
      for (double f : F) scale = std::max(scale, std::abs(f));
      const double h = 1e-6 * scale;
      for (int kl = 0; kl < 4; ++kl) {
        Mat2   Fp = F, Fm = F, Pp, Pm;
        double c  = 0.0;
        Fp[kl] += h;
        Fm[kl] -= h;
        ASSERT_EQ(model.stress(Fp, c, Pp), StressStatus::ok);
        ASSERT_EQ(model.stress(Fm, c, Pm), StressStatus::ok);
        for (int ij = 0; ij < 4; ++ij) A_fd[4 * ij + kl] = (Pp[ij] - Pm[ij]) / (Fp[kl] - Fm[kl]);
      }
      // central differences: truncation (h / s_min)^2 ~ 1e-11, round-off eps |P| / h ~ 1e-10
      EXPECT_LT(test::relative_difference(A, A_fd, mu), 1e-7) << "sample " << n;
      ++n;
    }
  }
}

TEST(IncompressiblePlaneStressGent, ReproducesThePapersPureShearCurveToRoundOff)
{
  const PlaneStressIncompressible<Gent> model{parameters()};
  for (double l : {1.1, 2.0, 3.0, 5.125, 10.0}) {
    double c33 = 0.0;
    Mat2   P;
    ASSERT_EQ(model.stress(Mat2{1.0, 0.0, 0.0, l}, c33, P), StressStatus::ok);
    // paper eq 36, incompressible pure shear: lambda_x = 1, lambda_3 = 1/lambda
    const double s = mu * Jm * (l - std::pow(l, -3)) / (Jm - l * l - 1.0 / (l * l) + 2.0);
    EXPECT_NEAR(P[3], s, 1e-13 * s) << "stretch " << l;
    EXPECT_EQ(P[1], 0.0);
    EXPECT_EQ(P[2], 0.0);
  }
}

TEST(IncompressiblePlaneStressRefusal, EveryLawOfInvariantsRunsAndOneOfPrincipalStretchesIsRefused)
{
  for (const LawEntry &law : registered_laws()) {
    const std::string refusal = law.refusal(Formulation::plane_stress_incompressible);
    bool              called  = false;
    auto              run     = [&] {
      with_model(law.kind, Formulation::plane_stress_incompressible, parameters(), [&](const auto &) { called = true; });
    };
    if (law.kind == ModelKind::ogden) {
      EXPECT_NE(refusal.find("-material_formulation plane_stress_incompressible"), std::string::npos) << refusal;
      EXPECT_NE(refusal.find("use -material_formulation plane_stress"), std::string::npos) << refusal;
      EXPECT_THROW(run(), std::invalid_argument);
      EXPECT_FALSE(called);
    } else {
      EXPECT_EQ(refusal, "") << law.name;
      run();
      EXPECT_TRUE(called) << law.name;
    }
  }
  Formulation f = Formulation::plane_stress;
  ASSERT_TRUE(parse("plane_stress_incompressible", f));
  EXPECT_EQ(f, Formulation::plane_stress_incompressible);
  EXPECT_STREQ(to_string(f), "plane_stress_incompressible");
}

} // namespace
} // namespace bapd
