// Names, parameter checks and the run-time model choice (material.hpp, models.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

#include "bapd/core/materials/models.hpp"
#include "bapd/core/materials/numerical_tangent.hpp"
#include "materials/deformations.hpp"

namespace bapd {
namespace {

TEST(Material, NamesRoundTrip)
{
  for (ModelKind k : {ModelKind::gent, ModelKind::neo_hookean}) {
    ModelKind back = k == ModelKind::gent ? ModelKind::neo_hookean : ModelKind::gent;
    EXPECT_TRUE(parse(to_string(k), back));
    EXPECT_EQ(back, k);
  }
  for (Formulation f : {Formulation::plane_stress, Formulation::plane_strain}) {
    Formulation back = f == Formulation::plane_stress ? Formulation::plane_strain : Formulation::plane_stress;
    EXPECT_TRUE(parse(to_string(f), back));
    EXPECT_EQ(back, f);
  }
  ModelKind k = ModelKind::gent;
  EXPECT_FALSE(parse("mooney", k));
  EXPECT_EQ(k, ModelKind::gent);
  for (StressStatus s : {StressStatus::ok, StressStatus::chain_limit, StressStatus::inverted,
                         StressStatus::no_convergence}) {
    EXPECT_STRNE(to_string(s), "unknown");
    EXPECT_STRNE(describe(s), "unknown stress status");
  }
}

TEST(Material, CheckParametersNamesEveryBadOption)
{
  EXPECT_EQ(check_parameters(ModelKind::gent, test::parameters(4.55e3, 162.6, 4.4e-6)), "");
  const std::string zero_D = check_parameters(ModelKind::gent, test::parameters(4.55e3, 162.6, 0.0));
  EXPECT_NE(zero_D.find("-material_D"), std::string::npos);
  const std::string all_bad = check_parameters(ModelKind::gent, test::parameters(-1.0, 0.0, -1.0));
  // one line per bad value, in option order
  EXPECT_LT(all_bad.find("-material_mu"), all_bad.find("-material_Jm"));
  EXPECT_LT(all_bad.find("-material_Jm"), all_bad.find("-material_D"));
  EXPECT_NE(all_bad.find("-material_D"), std::string::npos);
  // neo-Hookean ignores Jm
  EXPECT_EQ(check_parameters(ModelKind::neo_hookean, test::parameters(4.55e3, 0.0, 4.4e-6)), "");
  // check_model adds the formulation: both registered laws run in both
  for (Formulation f : {Formulation::plane_stress, Formulation::plane_strain}) {
    EXPECT_EQ(check_model(ModelKind::gent, f, test::parameters(4.55e3, 162.6, 4.4e-6)), "");
    EXPECT_EQ(check_model(ModelKind::gent, f, test::parameters(4.55e3, 0.0, 4.4e-6)),
              check_parameters(ModelKind::gent, test::parameters(4.55e3, 0.0, 4.4e-6)));
  }
}

TEST(Material, WithModelBuildsTheChosenConcreteModel)
{
  const MaterialParameters p = test::parameters(4.55e3, 162.6, 4.4e-6);
  auto which = [](const auto &model) {
    using M = std::decay_t<decltype(model)>;
    if (std::is_same_v<M, GentPlaneStress>) return 0;
    if (std::is_same_v<M, GentPlaneStrain>) return 1;
    if (std::is_same_v<M, NeoHookeanPlaneStress>) return 2;
    if (std::is_same_v<M, NeoHookeanPlaneStrain>) return 3;
    return -1;
  };
  EXPECT_EQ(with_model(ModelKind::gent, Formulation::plane_stress, p, which), 0);
  EXPECT_EQ(with_model(ModelKind::gent, Formulation::plane_strain, p, which), 1);
  EXPECT_EQ(with_model(ModelKind::neo_hookean, Formulation::plane_stress, p, which), 2);
  EXPECT_EQ(with_model(ModelKind::neo_hookean, Formulation::plane_strain, p, which), 3);
  // the parameters travel with the model
  const double mu = with_model(ModelKind::gent, Formulation::plane_stress, p, [](const auto &m) { return m.p.mu; });
  EXPECT_EQ(mu, 4.55e3);
}

TEST(Material, VolumetricEnergyIsAccurateNearUnitJacobian)
{
  // Near J = 1 the direct formula loses digits as eps / (J - 1); the reference sums
  // e^2/2 + sum_{n>=2} (-1)^n e^n / n (the Taylor series of e - ln(1 + e)) in long
  // double there, and uses the direct formula in long double elsewhere.
  for (double e : {1e-6, -1e-6, 1e-4, -3e-4, 0.01, -0.05, 0.0999, 0.1001, 0.5, 2.0}) {
    const double      J = 1.0 + e;
    const long double x = static_cast<long double>(J) - 1.0L; // exact
    long double       exact;
    if (std::abs(e) <= 0.1) {
      long double power = x * x, series = 0.0L;
      for (int n = 2; n < 60; ++n, power *= -x) series += power / n;
      exact = 0.5L * x * x + series;
    } else {
      exact = 0.5L * (x + 2.0L) * x - logl(1.0L + x);
    }
    // a few eps of each: the series terms are all of one sign pattern, no cancellation
    EXPECT_NEAR(volumetric_energy_times_D(J), static_cast<double>(exact), 1e-14 * static_cast<double>(exact))
        << "e " << e;
  }
}

TEST(Material, NumericalTangentIsSymmetricAndMatchesPlaneStrainAtRest)
{
  // At rest the plane-strain tangent is the small-strain elasticity tensor with
  // lambda = K - 2mu/3, K = 2/D (U''(1) = 2/D): A_xxxx = lambda + 2 mu, A_xxyy = lambda, A_xyxy = mu.
  const MaterialParameters p = test::parameters(4.55e3, 162.6, 2.0 / (100.0 * 4.55e3));
  Tangent2                 A;
  ASSERT_EQ(numerical_tangent(GentPlaneStrain{p}, identity2(), 1.0, A), StressStatus::ok);
  const double K = 2.0 / p.D, lambda = K - 2.0 * p.mu / 3.0;
  const double tol = 1e-7 * K; // central difference, h = 1e-4: O(h^2) truncation
  EXPECT_NEAR(A[0], lambda + 2.0 * p.mu, tol);
  EXPECT_NEAR(A[3], lambda, tol);
  EXPECT_NEAR(A[4 * 1 + 1], p.mu, tol);
  EXPECT_NEAR(A[4 * 1 + 2], p.mu, tol);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(A[4 * i + j], A[4 * j + i], tol); // hyperelastic: major symmetry
  // Plane stress at rest, D -> 0: E = 3 mu, nu = 1/2, A_xxxx = E/(1 - nu^2) = 4 mu.
  ASSERT_EQ(numerical_tangent(NeoHookeanPlaneStress{test::parameters(p.mu, p["-material_Jm"], 2.0 / (1e6 * p.mu))}, identity2(), 0.0, A),
            StressStatus::ok);
  EXPECT_NEAR(A[0], 4.0 * p.mu, 1e-5 * 4.0 * p.mu); // + O(mu/K) = 1e-6 compressible correction
  EXPECT_NEAR(A[3], 2.0 * p.mu, 1e-5 * 4.0 * p.mu);
}

} // namespace
} // namespace bapd
