// The laws beyond Gent and neo-Hookean (Mooney-Rivlin, Yeoh, Arruda-Boyce, Ogden): the
// inverse Langevin function over its whole range, the small-strain limit (shear
// modulus mu, Young's modulus 9 K mu / (3K + mu) -> 3 mu) in 3D and in plane stress,
// the compressible laws (3D and plane-stress sheets) against the analytic
// incompressible homogeneous responses (homogeneous_response.hpp) at a large bulk
// modulus, and one message per bad parameter. Stress = d Psi/dF, S33 = 0 and
// objectivity are checked for every law by the typed suites (stress_energy_test.cpp,
// plane_stress_test.cpp) and the registry test.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>

#include "bapd/core/materials/homogeneous_response.hpp"
#include "bapd/core/materials/models.hpp"
#include "materials/deformations.hpp"
#include "materials/law_types.hpp"

namespace bapd {
namespace {

constexpr double eps = std::numeric_limits<double>::epsilon();

TEST(InverseLangevin, InvertsTheLangevinFunctionToRoundOffOverTheWholeRange)
{
  double worst_rational = 0.0;
  for (double t = -8.0; t <= 0.0; t += 0.01) {
    // x from 1e-8 to 1 - 1e-9, dense near both ends: x = 1 - 10^t and x = 10^t
    for (double x : {std::pow(10.0, t), 1.0 - std::pow(10.0, t) * (t < -0.001 ? 1.0 : 0.5)}) {
      if (!(x > 0.0 && x < 1.0 - 1e-9)) continue;
      const double b = inverse_langevin(x);
      // L(b) to a few ulps of x: the Newton refinement stops at a step of 2 eps b, and
      // L' b / L <= 1, so the residual is at most a few eps x (plus L's own round-off)
      EXPECT_LE(std::abs(langevin(b) - x), 8.0 * eps * x) << "x = " << x;
      worst_rational = std::max(worst_rational, std::abs(inverse_langevin_rational(x) - b) / b);
    }
  }
  std::printf("Jedynak's rational approximation: largest relative error %.3g\n", worst_rational);
  EXPECT_LT(worst_rational, 0.016); // published: about 1.5 %; Newton makes up the rest
  EXPECT_EQ(inverse_langevin(0.0), 0.0);
  EXPECT_TRUE(std::isnan(inverse_langevin(1.0)));
  EXPECT_TRUE(std::isnan(inverse_langevin(-0.1)));
}

TEST(InverseLangevin, RoundTripsTheArgumentWithinItsConditionNumber)
{
  for (double t = -6.0; t <= 6.0; t += 0.01) {
    const double b = std::pow(10.0, t), x = langevin(b), back = inverse_langevin(x);
    if (!(x < 1.0)) continue; // (b > 1e16: L(b) rounds to 1)
    // condition of L^{-1}: |d ln b / d ln x| = x / (b L'(b)); x itself carries eps x
    const double condition = x / (b * langevin_derivative(b));
    EXPECT_LE(std::abs(back - b), 16.0 * eps * b * std::max(1.0, condition)) << "b = " << b;
  }
}

TEST(InverseLangevin, TaylorCoefficientsMatchDifferencesOfLangevinOnBothSidesOfTheSeriesSwitch)
{
  for (double b : {0.01, 0.3, 0.999, 1.001, 2.0, 4.0, 30.0}) {
    const std::array<double, 5> l = langevin_taylor(b);
    EXPECT_NEAR(l[0], langevin(b), 4 * eps * langevin(b));
    EXPECT_NEAR(l[1], langevin_derivative(b), 1e-14 * std::max(1.0, l[1] * 10)) << b;
    // l[n+1] = (d l[n] / db) / (n + 1), by central differences (h = 1e-4 b):
    // truncation (h)^2 l[3] ~ 1e-8 of the scale, round-off eps / h
    const double h = 1e-4 * b, d2 = (langevin_taylor(b + h)[1] - langevin_taylor(b - h)[1]) / (2 * h) / 2.0;
    EXPECT_NEAR(l[2], d2, 1e-7 * (std::abs(l[1]) / b + std::abs(l[2]))) << b;
    const double d3 = (langevin_taylor(b + h)[2] - langevin_taylor(b - h)[2]) / (2 * h) / 3.0;
    EXPECT_NEAR(l[3], d3, 1e-6 * (std::abs(l[2]) / b + std::abs(l[3]))) << b;
    const double d4 = (langevin_taylor(b + h)[3] - langevin_taylor(b - h)[3]) / (2 * h) / 4.0;
    EXPECT_NEAR(l[4], d4, 1e-5 * (std::abs(l[3]) / b + std::abs(l[4]))) << b;
  }
}

// The moduli of Arruda-Boyce are series reverted at each I1bar: check them against
// differences of G itself (the plane-stress solve's fourth-order step uses all four).
TEST(ArrudaBoyceModulus, DerivativesMatchDifferencesOfTheModulus)
{
  MaterialParameters m;
  m["-material_lambda_m"] = 4.0;
  const ParametersOf<ArrudaBoyce> p(m);
  for (double I : {3.0, 3.5, 10.0, 30.0, 45.0, 47.5}) {
    Modulus G, Gp, Gm;
    ASSERT_TRUE(ArrudaBoyce::modulus(p, Invariants{I}, G));
    const double h = 1e-5 * std::min(I, 48.0 - I);
    ASSERT_TRUE(ArrudaBoyce::modulus(p, Invariants{I + h}, Gp));
    ASSERT_TRUE(ArrudaBoyce::modulus(p, Invariants{I - h}, Gm));
    for (int n = 0; n < 4; ++n) {
      // central difference: truncation h^2 G^(n+3)/6, round-off ~ 1e-14 G^(n) / h
      const double fd = (Gp[n] - Gm[n]) / (2 * h);
      EXPECT_NEAR(G[n + 1], fd, 1e-6 * std::abs(G[n + 1]) + 1e-9 * std::abs(G[n]) / h) << "I1bar " << I << " n " << n;
    }
  }
  Modulus G;
  ASSERT_TRUE(ArrudaBoyce::modulus(p, Invariants{3.0}, G));
  EXPECT_NEAR(G[0], p.mu, 1e-14 * p.mu); // mu is the shear modulus at rest
  EXPECT_FALSE(ArrudaBoyce::modulus(p, Invariants{48.0}, G)); // the locking stretch, I1bar = 3 lambda_m^2
}

// ---------------------------------------------------------------------------------
// Homogeneous tests of the compressible 3D law, F = diag(s0, s1, s2), with the
// stress-free stretch(es) solved by bisection in ln s (P there is increasing in s).
template <class Model> double compressible_nominal_stress(const Model &model, LoadMode mode, double lambda)
{
  double s_inc[3] = {1.0, 1.0, 1.0};
  principal_stretches(mode, lambda, s_inc);
  auto F_of = [&](double t) -> Mat3 {
    switch (mode) {
    case LoadMode::uniaxial: return {lambda, 0, 0, 0, t, 0, 0, 0, t};
    case LoadMode::pure_shear: return {lambda, 0, 0, 0, 1, 0, 0, 0, t};
    case LoadMode::equibiaxial: return {lambda, 0, 0, 0, lambda, 0, 0, 0, t};
    }
    return {};
  };
  auto lateral = [&](double t) {
    Mat3 P;
    EXPECT_EQ(model.stress(F_of(t), P), StressStatus::ok);
    return P[8]; // P33 (uniaxial: P22 = P33 by symmetry)
  };
  double lo = std::log(s_inc[2]) - 0.2, hi = std::log(s_inc[2]) + 0.2;
  EXPECT_LT(lateral(std::exp(lo)), 0.0);
  EXPECT_GT(lateral(std::exp(hi)), 0.0);
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (lateral(std::exp(mid)) < 0.0 ? lo : hi) = mid;
  }
  Mat3 P;
  EXPECT_EQ(model.stress(F_of(std::exp(0.5 * (lo + hi))), P), StressStatus::ok);
  return P[0];
}

MaterialParameters law_parameters(double K_over_mu)
{
  MaterialParameters m; // each law's defaults, consistent with the default mu
  m.D = 2.0 / (K_over_mu * m.mu);
  return m;
}

template <class Law> class NewLaw : public ::testing::Test {};
using NewLaws = test::InvariantLawTypes;
TYPED_TEST_SUITE(NewLaw, NewLaws);

TYPED_TEST(NewLaw, CompressibleLawApproachesTheIncompressibleHomogeneousResponses)
{
  MaterialParameters m = law_parameters(1e5);
  m["-material_C01"] = 0.4 * m.mu / 2, m["-material_C10"] = 0.6 * m.mu / 2; // (Mooney-Rivlin: a large I2bar part)
  m["-material_C2"] = 100.0, m["-material_C3"] = 2.0;                        // (Yeoh: visible higher terms)
  m["-material_lambda_m"] = 4.0;                                // (Arruda-Boyce: near locking at 3)
  const ParametersOf<TypeParam>   p(m);
  const Compressible3D<TypeParam> model{p};
  for (LoadMode mode : {LoadMode::uniaxial, LoadMode::pure_shear, LoadMode::equibiaxial})
    for (double lambda : {1.05, 1.5, 2.0, 3.0}) {
      if (mode == LoadMode::equibiaxial && lambda > 2.0) continue; // (I1bar 18: past AB's lock at 16 x 3)
      double P_inc = 0.0;
      ASSERT_TRUE(incompressible_nominal_stress<TypeParam>(p, mode, lambda, P_inc));
      const double P = compressible_nominal_stress(model, mode, lambda);
      // the sheet's volume changes by O(sigma / K): the stress by O(tangent / K),
      // tangent <= ~30 mu here, K = 1e5 mu: < 1e-3 relative with a margin
      EXPECT_NEAR(P, P_inc, 1e-3 * std::abs(P_inc)) << TypeParam::name << " " << to_string(mode) << " " << lambda;
    }
}

TYPED_TEST(NewLaw, SmallStrainGivesShearModulusMuAndYoungsModulusNear3Mu)
{
  const double                    K_over_mu = 1e4;
  const ParametersOf<TypeParam>   p(law_parameters(K_over_mu));
  const Compressible3D<TypeParam> model{p};
  // simple shear gamma: P12 = mu gamma + O(gamma^3); round-off eps mu / gamma
  const double gamma = 1e-5;
  Mat3         P;
  ASSERT_EQ(model.stress({1, gamma, 0, 0, 1, 0, 0, 0, 1}, P), StressStatus::ok);
  EXPECT_NEAR(P[1] / gamma, p.mu, 1e-8 * p.mu) << TypeParam::name;
  // uniaxial: dP/dlambda at rest = E = 9 K mu / (3K + mu) = 3 mu (1 - 3.3e-5), by a
  // central difference (truncation e^2 = 1e-8; round-off of the bulk term K eps / (mu e)
  // ~ 1e-8): the 1e-6 tolerance resolves the compressible correction
  const double e = 1e-4, K = K_over_mu * p.mu, E = 9.0 * K * p.mu / (3.0 * K + p.mu);
  const double slope = (compressible_nominal_stress(model, LoadMode::uniaxial, 1.0 + e) -
                        compressible_nominal_stress(model, LoadMode::uniaxial, 1.0 - e)) / (2.0 * e);
  EXPECT_NEAR(slope, E, 1e-6 * E) << TypeParam::name;
  EXPECT_GT(std::abs(slope - 3.0 * p.mu), 1e-5 * p.mu) << "resolves 3 mu - E = mu^2 / K";
}

TEST(HomogeneousResponse, GentPureShearIsPaperEq36)
{
  MaterialParameters m;
  const ParametersOf<Gent> p(m);
  for (double lambda : {1.01, 2.0, 5.125, 10.0}) {
    double P = 0.0;
    ASSERT_TRUE(incompressible_nominal_stress<Gent>(p, LoadMode::pure_shear, lambda, P));
    EXPECT_NEAR(P, gent_pure_shear_eq36(p.mu, p.Jm, lambda), 1e-13 * P);
  }
}

TEST(HomogeneousResponse, OgdenWithOneTermOfAlpha2IsNeoHookean)
{
  // W = (mu/2)(I1 - 3) is Ogden with alpha = 2, mu_1 = mu (mu = mu_1 alpha_1 / 2)
  const double mu = 4.55e3, alpha = 2.0;
  const ParametersOf<NeoHookean> p{MaterialParameters{}};
  for (LoadMode mode : {LoadMode::uniaxial, LoadMode::pure_shear, LoadMode::equibiaxial})
    for (double lambda : {1.1, 2.0, 4.0}) {
      double P = 0.0;
      ASSERT_TRUE(incompressible_nominal_stress<NeoHookean>(p, mode, lambda, P));
      EXPECT_NEAR(ogden_nominal_stress(&mu, &alpha, 1, mode, lambda), P, 1e-13 * P) << to_string(mode);
    }
}

// ---------------------------------------------------------------------------------
// Ogden (principal stretches, its own formulations: ogden.hpp).
MaterialParameters ogden_parameters(double K_over_mu)
{
  MaterialParameters m = law_parameters(K_over_mu); // defaults: (4500, 2), (16.667, 6)
  m["-material_ogden_mu3"] = -20.0, m["-material_ogden_alpha3"] = -2.0;        // a third term of negative alpha
  m["-material_ogden_mu1"] = 4500.0 - 20.0;                       // keeping sum mu_k alpha_k / 2 = mu
  return m;
}

TEST(Ogden, CompressibleSheetApproachesTheIncompressibleOgdenResponses)
{
  const ParametersOf<Ogden> p(ogden_parameters(1e5));
  const Ogden3D             model3{p};
  const OgdenPlaneStress    sheet{p};
  const double mu[3] = {p.ogden_mu1, p.ogden_mu2, p.ogden_mu3}, alpha[3] = {p.ogden_alpha1, p.ogden_alpha2, p.ogden_alpha3};
  for (LoadMode mode : {LoadMode::uniaxial, LoadMode::pure_shear, LoadMode::equibiaxial})
    for (double lambda : {1.05, 1.5, 2.0, 3.0}) {
      const double P_inc = ogden_nominal_stress(mu, alpha, 3, mode, lambda);
      // as for the other laws: O(tangent / K) with K = 1e5 mu
      EXPECT_NEAR(compressible_nominal_stress(model3, mode, lambda), P_inc, 1e-3 * std::abs(P_inc)) << to_string(mode) << " " << lambda;
      if (mode == LoadMode::uniaxial) continue;
      const Mat2 F   = mode == LoadMode::pure_shear ? Mat2{lambda, 0, 0, 1} : Mat2{lambda, 0, 0, lambda};
      double     c33 = 0.0;
      Mat2       P;
      ASSERT_EQ(sheet.stress(F, c33, P), StressStatus::ok);
      EXPECT_NEAR(P[0], P_inc, 1e-3 * std::abs(P_inc)) << "plane stress " << to_string(mode) << " " << lambda;
    }
}

TEST(Ogden, PlaneStressIsThe3DLawAtTheSolvedThicknessWithZeroS33)
{
  std::mt19937              rng(5);
  const ParametersOf<Ogden> p(ogden_parameters(1000.0));
  const Ogden3D             model3{p};
  const OgdenPlaneStress    sheet{p};
  const OgdenPlaneStrain    strain{p};
  for (int sample = 0; sample < 100; ++sample) {
    const Mat2 F   = test::random_F2(rng, 4.0);
    double     c33 = 0.0, one = 0.0;
    Mat2       P, Pe;
    Mat3       P3;
    ASSERT_EQ(sheet.stress(F, c33, P), StressStatus::ok);
    ASSERT_EQ(model3.stress(embed(F, std::sqrt(c33)), P3), StressStatus::ok);
    // P33 = tau_3 / lambda_3 = 0 to the solve's round-off (terms of size mu and K)
    EXPECT_LT(std::abs(P3[8]), 1e-9 * p.mu) << sample;
    EXPECT_LT(test::relative_difference(P, Mat2{P3[0], P3[1], P3[3], P3[4]}, p.mu), 1e-10) << sample;
    ASSERT_EQ(strain.stress(F, one, Pe), StressStatus::ok);
    ASSERT_EQ(model3.stress(embed(F, 1.0), P3), StressStatus::ok);
    EXPECT_LT(test::relative_difference(Pe, Mat2{P3[0], P3[1], P3[3], P3[4]}, p.mu), 1e-10) << sample;
  }
}

TEST(Ogden, RepeatedPrincipalStretchesNeedNoSpecialCase)
{
  const ParametersOf<Ogden> p(ogden_parameters(1000.0));
  const OgdenPlaneStress    sheet{p};
  const Ogden3D             model3{p};
  double                    c33 = 0.0;
  Mat2                      P;
  ASSERT_EQ(sheet.stress(identity2(), c33, P), StressStatus::ok);
  EXPECT_LT(test::relative_difference(P, Mat2{}, p.mu), 1e-13); // at rest: no stress
  EXPECT_NEAR(c33, 1.0, 1e-14);
  // equibiaxial (c_1 = c_2), rotated, against a split of 1e-9: P moves by O(1e-9) only
  const Mat2 R = test::rotation2(0.7);
  for (double lambda : {0.8, 1.5, 3.0}) {
    Mat2   Pe, Ps;
    double c_a = 0.0, c_b = 0.0;
    ASSERT_EQ(sheet.stress(R * Mat2{lambda, 0, 0, lambda}, c_a, Pe), StressStatus::ok);
    ASSERT_EQ(sheet.stress(R * Mat2{lambda, 0, 0, lambda * (1.0 + 1e-9)}, c_b, Ps), StressStatus::ok);
    EXPECT_LT(test::relative_difference(Pe, Ps, p.mu), 1e-8) << lambda;
    // and equibiaxial P is R times a multiple of the identity
    const Mat2 back = transpose(R) * Pe;
    EXPECT_NEAR(back[1], 0.0, 1e-12 * std::abs(back[0]));
    EXPECT_NEAR(back[0], back[3], 1e-12 * std::abs(back[0]));
  }
  Mat3 P3;
  ASSERT_EQ(model3.stress({1.3, 0, 0, 0, 1.3, 0, 0, 0, 1.3}, P3), StressStatus::ok); // all three equal
  EXPECT_NEAR(P3[0], P3[8], 1e-12 * std::abs(P3[0]));
}

TEST(Ogden, SmallStrainGivesShearModulusMu)
{
  const ParametersOf<Ogden> p(ogden_parameters(1e4));
  const Ogden3D             model{p};
  const double              gamma = 1e-5;
  Mat3                      P;
  ASSERT_EQ(model.stress({1, gamma, 0, 0, 1, 0, 0, 0, 1}, P), StressStatus::ok);
  EXPECT_NEAR(P[1] / gamma, p.mu, 1e-8 * p.mu);
  const double e = 1e-4, K = 1e4 * p.mu, E = 9.0 * K * p.mu / (3.0 * K + p.mu);
  const double slope = (compressible_nominal_stress(model, LoadMode::uniaxial, 1.0 + e) -
                        compressible_nominal_stress(model, LoadMode::uniaxial, 1.0 - e)) / (2.0 * e);
  EXPECT_NEAR(slope, E, 1e-6 * E);
}

// ---------------------------------------------------------------------------------
// Every registered law in plane stress, the formulation the paper's sheets run in: the
// three homogeneous tests of a thin sheet (uniaxial with its in-plane sides free, pure
// shear, equibiaxial) at K = 1e5 mu against the incompressible responses, and the
// small-strain limit (a sheet in uniaxial tension is the 3D uniaxial test: E).
MaterialParameters sheet_parameters(double K_over_mu)
{
  MaterialParameters m = ogden_parameters(K_over_mu);
  m["-material_C01"] = 0.4 * m.mu / 2, m["-material_C10"] = 0.6 * m.mu / 2; // (Mooney-Rivlin: a large I2bar part)
  m["-material_C2"] = 100.0, m["-material_C3"] = 2.0;                        // (Yeoh: visible higher terms)
  m["-material_lambda_m"] = 4.0;                                // (Arruda-Boyce: near locking at 3)
  return m;
}

template <class Model> double incompressible_sheet_stress(const MaterialParameters &m, LoadMode mode, double lambda)
{
  if constexpr (std::is_same_v<Model, OgdenPlaneStress>) {
    const double mu[3] = {m["-material_ogden_mu1"], m["-material_ogden_mu2"], m["-material_ogden_mu3"]}, alpha[3] = {m["-material_ogden_alpha1"], m["-material_ogden_alpha2"], m["-material_ogden_alpha3"]};
    return ogden_nominal_stress(mu, alpha, 3, mode, lambda);
  } else {
    using Law = typename test::LawOf<Model>::type;
    double P  = 0.0;
    EXPECT_TRUE(incompressible_nominal_stress<Law>(ParametersOf<Law>(m), mode, lambda, P));
    return P;
  }
}

// P~_11 of the sheet stretched lambda along x: pure shear F~ = diag(lambda, 1),
// equibiaxial diag(lambda, lambda), uniaxial diag(lambda, t) with t solved for P~_22 = 0
// by bisection in ln t (P~_22 increases with t).
template <class Model> double sheet_stress(const Model &model, LoadMode mode, double lambda)
{
  double c33 = 0.0;
  Mat2   P;
  auto   at = [&](double t) {
    const double warm = c33;
    EXPECT_EQ(model.stress(Mat2{lambda, 0, 0, t}, c33, P), StressStatus::ok) << lambda << " " << t << " from C33 " << warm;
    return P;
  };
  if (mode == LoadMode::pure_shear) return at(1.0)[0];
  if (mode == LoadMode::equibiaxial) return at(lambda)[0];
  double lo = -0.5 * std::log(lambda) - 0.2, hi = -0.5 * std::log(lambda) + 0.2;
  EXPECT_LT(at(std::exp(lo))[3], 0.0);
  EXPECT_GT(at(std::exp(hi))[3], 0.0);
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (at(std::exp(mid))[3] < 0.0 ? lo : hi) = mid;
  }
  return at(std::exp(0.5 * (lo + hi)))[0];
}

template <class Model> class PlaneStressSheet : public ::testing::Test {};
using SheetModels = test::PlaneStressModels;
TYPED_TEST_SUITE(PlaneStressSheet, SheetModels);

TYPED_TEST(PlaneStressSheet, MatchesTheIncompressibleUniaxialPureShearAndEquibiaxialResponses)
{
  const MaterialParameters m = sheet_parameters(1e5);
  const TypeParam          model{m};
  for (LoadMode mode : {LoadMode::uniaxial, LoadMode::pure_shear, LoadMode::equibiaxial})
    for (double lambda : {1.05, 1.5, 2.0, 3.0}) {
      if (mode == LoadMode::equibiaxial && lambda > 2.0) continue; // (I1bar 18: past AB's lock at 16 x 3)
      const double P_inc = incompressible_sheet_stress<TypeParam>(m, mode, lambda);
      // the sheet's volume changes by O(sigma / K): the stress by O(tangent / K),
      // tangent <= ~30 mu here, K = 1e5 mu: < 1e-3 relative with a margin
      EXPECT_NEAR(sheet_stress(model, mode, lambda), P_inc, 1e-3 * std::abs(P_inc)) << to_string(mode) << " " << lambda;
    }
}

TYPED_TEST(PlaneStressSheet, WarmStartAtItsOwnSolutionReturnsIt)
{
  // A bond whose F did not change since the last step restarts at the root: the step
  // there is below the spacing of doubles (Ogden's solve once bisected to -inf from it).
  const TypeParam model{sheet_parameters(1e5)};
  std::mt19937    rng(3);
  for (int sample = 0; sample < 200; ++sample) {
    const Mat2 F = sample == 0 ? Mat2{3.0, 0, 0, 1.0 / std::sqrt(3.0)} : test::random_F2(rng, 3.0);
    double     c33 = 0.0;
    Mat2       P, P_again;
    ASSERT_EQ(model.stress(F, c33, P), StressStatus::ok) << sample;
    const double solved = c33;
    ASSERT_EQ(model.stress(F, c33, P_again), StressStatus::ok) << sample;
    // both stop within the solves' tolerances (1e-13 of the cancelling terms, or a last
    // Newton step of 1e-8 leaving ~1e-16): the same root
    EXPECT_NEAR(c33, solved, 1e-12 * solved) << sample;
    EXPECT_LT(test::relative_difference(P_again, P, 4.55e3), 1e-9) << sample;
  }
}

TYPED_TEST(PlaneStressSheet, SmallStrainUniaxialSlopeIsYoungsModulusNear3Mu)
{
  const double             K_over_mu = 1e4;
  const MaterialParameters m         = sheet_parameters(K_over_mu);
  const TypeParam          model{m};
  // as the 3D test above: E = 9 K mu / (3K + mu) = 3 mu (1 - 3.3e-5); central difference
  // e = 1e-4 (truncation e^2 = 1e-8), S33 = 0 solved to 1e-13 of its terms
  const double e = 1e-4, K = K_over_mu * m.mu, E = 9.0 * K * m.mu / (3.0 * K + m.mu);
  const double slope = (sheet_stress(model, LoadMode::uniaxial, 1.0 + e) - sheet_stress(model, LoadMode::uniaxial, 1.0 - e)) / (2.0 * e);
  EXPECT_NEAR(slope, E, 1e-6 * E);
  EXPECT_GT(std::abs(slope - 3.0 * m.mu), 1e-5 * m.mu) << "resolves 3 mu - E = mu^2 / K";
}

// ---------------------------------------------------------------------------------
TEST(NewLawChecks, EachBadValueGetsOneLineNamingItsOption)
{
  auto problems = [](ModelKind k, const std::function<void(MaterialParameters &)> &change) {
    MaterialParameters m = law_parameters(1000.0);
    change(m);
    return check_parameters(k, m);
  };
  auto one_line_naming = [](const std::string &s, const std::string &option) {
    return s.find(option) == 0 && s.find('\n') == s.size() - 1;
  };
  const std::string c01 = problems(ModelKind::mooney_rivlin, [](auto &m) { m["-material_C01"] = -455.0, m["-material_C10"] = m.mu / 2 + 455.0; });
  EXPECT_TRUE(one_line_naming(c01, "-material_C01")) << c01;
  EXPECT_NE(c01.find("Drucker-stable"), std::string::npos) << c01;
  EXPECT_NE(c01.find("sqrt(C10/-C01) = 2.449"), std::string::npos) << c01; // sqrt(2730 / 455) = sqrt(6)
  const std::string c10 = problems(ModelKind::mooney_rivlin, [](auto &m) { m["-material_C10"] = -455.0, m["-material_C01"] = m.mu / 2 + 455.0; });
  EXPECT_TRUE(one_line_naming(c10, "-material_C10")) << c10;
  EXPECT_NE(c10.find("C01/-C10 = 6"), std::string::npos) << c10; // 2730 / 455
  EXPECT_TRUE(one_line_naming(problems(ModelKind::mooney_rivlin, [](auto &m) { m["-material_C01"] = NAN; }), "-material_C01"));
  EXPECT_TRUE(one_line_naming(problems(ModelKind::mooney_rivlin, [](auto &m) { m["-material_C10"] = m["-material_C01"] = 0.0; }), "-material_C10"));
  const std::string mismatch = problems(ModelKind::mooney_rivlin, [](auto &m) { m["-material_C10"] = 3000.0; });
  EXPECT_TRUE(one_line_naming(mismatch, "-material_C10")) << mismatch;
  EXPECT_NE(mismatch.find("give -material_mu 6910"), std::string::npos) << mismatch;
  EXPECT_TRUE(one_line_naming(problems(ModelKind::yeoh, [](auto &m) { m["-material_C2"] = -1.0; }), "-material_C2"));
  EXPECT_TRUE(one_line_naming(problems(ModelKind::yeoh, [](auto &m) { m["-material_C3"] = -1.0; }), "-material_C3"));
  EXPECT_TRUE(one_line_naming(problems(ModelKind::yeoh, [](auto &m) { m["-material_C1"] = 0.0; }), "-material_C1"));
  EXPECT_TRUE(one_line_naming(problems(ModelKind::yeoh, [](auto &m) { m.mu = 5000.0; }), "-material_C1"));
  EXPECT_TRUE(one_line_naming(problems(ModelKind::arruda_boyce, [](auto &m) { m["-material_lambda_m"] = 1.0; }), "-material_lambda_m"));
  EXPECT_EQ(problems(ModelKind::mooney_rivlin, [](auto &m) { m["-material_C10"] = 0.0, m["-material_C01"] = m.mu / 2; }), ""); // pure I2bar is fine
  EXPECT_TRUE(one_line_naming(problems(ModelKind::ogden, [](auto &m) { m["-material_ogden_mu3"] = 10.0, m["-material_ogden_alpha3"] = -2.0; }), "-material_ogden_alpha3"));
  EXPECT_TRUE(one_line_naming(problems(ModelKind::ogden, [](auto &m) { m["-material_ogden_mu1"] = 4000.0; }), "-material_ogden_mu1"));
  EXPECT_EQ(problems(ModelKind::ogden, [](auto &m) { m = ogden_parameters(1000.0); }), "");
}

} // namespace
} // namespace bapd
