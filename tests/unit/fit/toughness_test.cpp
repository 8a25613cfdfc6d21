// bapd-fit's toughness from a notched pure-shear curve (toughness.hpp): every law's
// energy is the integral of the stress it is fitted with; Gamma = W(lambda_c) H0 is
// recovered from synthetic data (a Gent pure-shear curve with 1 % noise, a notched curve
// whose force falls past a chosen lambda_c) within its reported uncertainty, which is
// not too large and covers the truth as often as it claims; the failure: section gives
// Gamma back digit for digit; the notched test's errors name the file and the fix.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>

#include "fit_error.hpp"
#include "number_text.hpp"
#include "toughness.hpp"

namespace bapd::fit {
namespace {

double normal(std::mt19937 &rng) // N(0, 1), Box-Muller on the raw engine (the same everywhere)
{
  const double u1 = (rng() + 0.5) / 4294967296.0, u2 = (rng() + 0.5) / 4294967296.0;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

const std::vector<double> gent_true = {4.55e3, 162.6}; // the paper's gel
const double              H0        = 0.01;             // m, the paper's sheet

// The Gent pure-shear curve of the paper's gel, 25 points to stretch 6, times 1 + 1 % noise.
Curve pure_shear(const FitLaw &gent, std::mt19937 &rng)
{
  Curve c;
  c.file           = "synthetic_pure_shear";
  c.mode           = LoadMode::pure_shear;
  c.gauge_length_m = H0;
  for (int i = 1; i <= 25; ++i) {
    const double lambda = 1.0 + 5.0 * i / 25;
    double       P      = 0.0;
    EXPECT_TRUE(gent.stress(gent_true, LoadMode::pure_shear, lambda, P));
    c.stretch.push_back(lambda);
    c.stress_Pa.push_back(P * (1.0 + 0.01 * normal(rng)));
  }
  return c;
}

// A notched curve sampled every `step` of stretch from first: 0.73 x the pure-shear
// stress (the ligament's share) up to the crack's onset at lambda_c, then the force
// falls to 30 % and 5 % of it and the sheet is cut through; noise 1 % (or as given).
Curve notched(const FitLaw &gent, double lambda_c, double first, double step, std::mt19937 &rng, double noise = 0.01)
{
  Curve c;
  c.file           = "synthetic_notched";
  c.mode           = LoadMode::pure_shear;
  c.notched        = true;
  c.gauge_length_m = H0;
  double Pc = 0.0;
  EXPECT_TRUE(gent.stress(gent_true, LoadMode::pure_shear, lambda_c, Pc));
  int after = 0;
  for (double lambda = first; after < 5; lambda += step) {
    double P = 0.0;
    if (lambda <= lambda_c) EXPECT_TRUE(gent.stress(gent_true, LoadMode::pure_shear, lambda, P));
    else P = Pc * (after == 0 ? 0.30 : after == 1 ? 0.05 : 0.0), ++after;
    c.stretch.push_back(lambda);
    c.stress_Pa.push_back(0.73 * P * (1.0 + noise * normal(rng)));
  }
  return c;
}

// Gamma of the true law: W(lambda_c) H0 with the Gent energy in pure shear written out
// (docs/fracture_reference.md: W = -(mu Jm / 2) ln(1 - (l^2 + l^-2 - 2) / Jm)).
double true_gamma(double lambda_c)
{
  const double l2 = lambda_c * lambda_c;
  return -0.5 * gent_true[0] * gent_true[1] * std::log(1.0 - (l2 + 1.0 / l2 - 2.0) / gent_true[1]) * H0;
}

// Every law's energy (FitLaw::energy) is the integral of the stress it is fitted with:
// W(1) = 0 and dW/dlambda = P in each test (2 P in equibiaxial tension: both in-plane
// directions are stretched and loaded), by central differences (h = 1e-5: truncation
// ~1e-10 of P, round-off ~1e-16 W / h ~ 1e-11 W).
TEST(FitLaws, EnergyIsTheIntegralOfTheFittedStress)
{
  for (const std::string &name : fit_law_names()) {
    const FitLaw              law = fit_law(name, 2);
    const std::vector<double> p   = law.starts(4550.0, 30.0)[0];
    for (LoadMode mode : {LoadMode::uniaxial, LoadMode::pure_shear, LoadMode::equibiaxial}) {
      double W1 = -1.0;
      ASSERT_TRUE(law.energy(p, mode, 1.0, W1)) << name;
      EXPECT_NEAR(W1, 0.0, 1e-12 * 4550.0) << name << " " << to_string(mode);
      for (double lambda : {1.1, 1.5, 2.2, 3.0}) {
        const double h  = 1e-5;
        double       Wp = 0.0, Wm = 0.0, P = 0.0;
        ASSERT_TRUE(law.energy(p, mode, lambda + h, Wp) && law.energy(p, mode, lambda - h, Wm) && law.stress(p, mode, lambda, P))
            << name << " " << to_string(mode) << " " << lambda;
        const double loaded = mode == LoadMode::equibiaxial ? 2.0 : 1.0;
        EXPECT_NEAR((Wp - Wm) / (2.0 * h), loaded * P, 1e-7 * std::abs(P)) << name << " " << to_string(mode) << " at " << lambda;
      }
    }
  }
}

TEST(Toughness, GentGammaFromAPureShearCurveAndANotchedPeak)
{
  std::mt19937             rng(2026);
  const FitLaw             gent   = fit_law("gent", 2);
  const std::vector<Curve> fitted = {pure_shear(gent, rng)};
  const LawFit             fit    = fit_law_to_data(gent, fitted, Weighting::relative);
  ASSERT_EQ(fit.problem, "");
  // the peak at a sample (3.0), and between two (the crack runs at 3.02: the last sample
  // before it, 3.0, is the peak)
  for (double lambda_c : {3.0, 3.02}) {
    ToughnessTest test = prepare_toughness(notched(gent, lambda_c, 1.05, 0.05, rng), fitted, 0.0, 0.0);
    compute_toughness(test, {fit});
    const Toughness &t = test.per_law[0];
    ASSERT_EQ(t.problem, "");
    EXPECT_NEAR(test.onset.stretch, 3.0, 1e-9);
    EXPECT_NEAR(test.onset.uncertainty, 0.1 / std::sqrt(12.0), 1e-9); // neighbours 2.95 and 3.05
    const double truth = true_gamma(lambda_c);
    std::printf("  lambda_c %.2f: Gamma %.2f +- %.2f J/m^2 (%.2f from the parameters), true %.2f (%.2f sigma)\n", lambda_c,
                t.gamma_J_m2, t.uncertainty_J_m2, t.from_parameters, truth, std::abs(t.gamma_J_m2 - truth) / t.uncertainty_J_m2);
    EXPECT_LT(std::abs(t.gamma_J_m2 - truth), t.uncertainty_J_m2);
    // not absurdly large: the sampling's part is H0 P(3) 0.029 (~4 J/m^2, 2.5 %), the
    // parameters' of 1 % noise on 25 points well under 1 %
    EXPECT_LT(t.uncertainty_J_m2, 0.03 * truth);
    EXPECT_LT(t.from_parameters, 0.01 * truth);
    EXPECT_GT(t.from_parameters, 0.0);
  }
}

TEST(Toughness, UncertaintyCoversTheTruthAsOftenAsItShould)
{
  // 100 draws: fresh noise on the pure-shear curve and the crack's onset anywhere in
  // [2.9, 3.1] against notched samples every 0.05. The sampled peak is the last sample
  // before the onset, up to 0.05 = 1.7 sigma_lambda below it: within 2 sigma always,
  // and within 1 sigma 58 % of the time from the sampling alone. Sigma too small by 1.5
  // fails the first, too large by 1.5 (1 sigma: 87 %) the second. With 1 % noise on the
  // notched curve too, the peak is sometimes its neighbour (2 % below it here), which the
  // sampling's uncertainty does not count: fewer within 2 sigma (docs/laws.md).
  const FitLaw gent = fit_law("gent", 2);
  for (double noise : {0.0, 0.01}) {
    int within[2] = {0, 0};
    for (int draw = 0; draw < 100; ++draw) {
      std::mt19937                           rng(5000 + draw);
      std::uniform_real_distribution<double> where(2.9, 3.1);
      const double                           lambda_c = where(rng);
      const std::vector<Curve>               fitted   = {pure_shear(gent, rng)};
      const LawFit                           fit      = fit_law_to_data(gent, fitted, Weighting::relative);
      ASSERT_EQ(fit.problem, "");
      ToughnessTest test = prepare_toughness(notched(gent, lambda_c, 1.05, 0.05, rng, noise), fitted, 0.0, 0.0);
      compute_toughness(test, {fit});
      const double z = std::abs(test.per_law[0].gamma_J_m2 - true_gamma(lambda_c)) / test.per_law[0].uncertainty_J_m2;
      within[0] += z < 1.0;
      within[1] += z < 2.0;
    }
    std::printf("  notched noise %.0f %%: Gamma within 1 / 2 standard uncertainties: %d / %d %%\n", 100 * noise, within[0], within[1]);
    EXPECT_GE(within[1], noise > 0.0 ? 85 : 99) << noise;
    EXPECT_GE(within[0], 45) << noise;
    EXPECT_LE(within[0], 80) << noise;
  }
}

// Gent fitted to a pure-shear curve (seed) and the toughness of a notched curve that
// cracks at 3 (onset given when given_stretch > 0).
struct GentToughness {
  LawFit        fit;
  ToughnessTest test;
};
GentToughness gent_toughness(unsigned seed, double given_stretch, double given_uncertainty)
{
  std::mt19937             rng(seed);
  const FitLaw             gent   = fit_law("gent", 2);
  const std::vector<Curve> fitted = {pure_shear(gent, rng)};
  GentToughness            g{fit_law_to_data(gent, fitted, Weighting::relative), {}};
  g.test = prepare_toughness(notched(gent, 3.0, 1.05, 0.05, rng), fitted, given_stretch, given_uncertainty);
  compute_toughness(g.test, {g.fit});
  return g;
}

TEST(Toughness, AGivenOnsetIsUsedWithItsUncertainty)
{
  const GentToughness g = gent_toughness(3, 2.8, 0.01);
  const LawFit       &fit = g.fit;
  const ToughnessTest &test = g.test;
  EXPECT_TRUE(test.onset.given);
  EXPECT_EQ(test.onset.stretch, 2.8);
  double W = 0.0, P = 0.0;
  ASSERT_TRUE(fit.law.energy(fit.ls.p, LoadMode::pure_shear, 2.8, W) && fit.law.stress(fit.ls.p, LoadMode::pure_shear, 2.8, P));
  EXPECT_NEAR(test.per_law[0].gamma_J_m2, W * H0, 1e-12 * W * H0);
  EXPECT_NEAR(test.per_law[0].from_onset, H0 * P * 0.01, 1e-12 * H0 * P); // dW/dlambda = P
}

// The failure: section bapd reads (-failure_fracture_energy) carries Gamma as printed,
// and reads back to it within its 6 digits.
TEST(Toughness, FailureSectionGivesGammaBack)
{
  const ToughnessTest test = gent_toughness(4, 0.0, 0.0).test;
  const std::string yaml = failure_yaml(test, test.per_law[0]);
  const std::string key  = "\nfailure:\n  fracture_energy: ";
  const auto        at   = yaml.find(key);
  ASSERT_NE(at, std::string::npos) << yaml;
  const double back = std::strtod(yaml.c_str() + at + key.size(), nullptr);
  EXPECT_NEAR(back, test.per_law[0].gamma_J_m2, 1e-5 * back) << yaml;
  EXPECT_EQ(yaml.substr(yaml.size() - 1), "\n");
  for (std::size_t line = 0; line < at; line = yaml.find('\n', line) + 1) EXPECT_EQ(yaml[line], '#') << yaml; // comments above
}

// A message that names the file and says what to give.
void expect_refused(const std::function<void()> &f, const std::string &part)
{
  try {
    f();
    ADD_FAILURE() << "no error; wanted '" << part << "'";
  } catch (const FitError &e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("synthetic_notched"), std::string::npos) << e.what();
  }
}

TEST(Toughness, ANotchedTestItCannotReadIsRefusedWithTheFix)
{
  std::mt19937             rng(5);
  const FitLaw             gent = fit_law("gent", 2);
  const std::vector<Curve> shear = {pure_shear(gent, rng)};
  const Curve              n     = notched(gent, 3.0, 1.05, 0.05, rng);
  Curve                    uniaxial = shear[0];
  uniaxial.mode                     = LoadMode::uniaxial;
  expect_refused([&] { prepare_toughness(n, {uniaxial}, 0.0, 0.0); }, "give that sheet's curve too");
  Curve no_h0 = n;
  no_h0.gauge_length_m = 0.0;
  expect_refused([&] { prepare_toughness(no_h0, shear, 0.0, 0.0); }, "-fit_gauge_length H0");
  Curve other_h0 = n;
  other_h0.gauge_length_m = 0.02;
  expect_refused([&] { prepare_toughness(other_h0, shear, 0.0, 0.0); }, "differs from the un-notched");
  Curve rising = n; // stopped before the crack ran: the peak is the last point
  while (rising.stress_Pa.back() < 0.5 * rising.stress_Pa[rising.stress_Pa.size() - 6]) rising.stretch.pop_back(), rising.stress_Pa.pop_back();
  expect_refused([&] { crack_onset(rising, 0.0, 0.0); }, "is not in the data");
  EXPECT_NO_THROW(crack_onset(rising, 3.0, 0.0)); // unless the onset is given
  Curve falling = n;
  falling.stress_Pa[0] = 2.0 * *std::max_element(n.stress_Pa.begin(), n.stress_Pa.end());
  expect_refused([&] { crack_onset(falling, 0.0, 0.0); }, "falls from its first point");
}

} // namespace
} // namespace bapd::fit
