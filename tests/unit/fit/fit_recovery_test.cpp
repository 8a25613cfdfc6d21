// bapd-fit recovers known parameters from synthetic data with 1 % noise (fixed seed)
// within its reported uncertainty (|p - p_true| < 3 sigma, and over 100 draws as often
// within 1 and 2 sigma as a correct standard error allows), for these cases:
// Gent from pure shear, Mooney-Rivlin from uniaxial plus equibiaxial, Ogden (two terms)
// from all three tests, Gent from a synthetic machine export (extension in mm and force
// in N, read through fit_data.hpp); and the fit reports a law the data cannot determine.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

#include "fit_data.hpp"
#include "fit_run.hpp"
#include "number_text.hpp"
#include "bapd/core/materials/law_registry.hpp"

namespace bapd::fit {
namespace {

// N(0, 1) by Box-Muller from the raw engine output (independent of the library's
// distribution code, so the data are the same everywhere).
double normal(std::mt19937 &rng)
{
  const double u1 = (rng() + 0.5) / 4294967296.0, u2 = (rng() + 0.5) / 4294967296.0;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
}

// A curve of n points from 1 + step to top, stress from the law at p_true, times 1 + 1 % noise.
Curve synthetic(const FitLaw &law, const std::vector<double> &p_true, LoadMode mode, double top, int n, std::mt19937 &rng)
{
  Curve c;
  c.file = std::string("synthetic_") + to_string(mode);
  c.mode = mode;
  for (int i = 1; i <= n; ++i) {
    const double lambda = 1.0 + (top - 1.0) * i / n;
    double       P      = 0.0;
    EXPECT_TRUE(law.stress(p_true, mode, lambda, P));
    c.stretch.push_back(lambda);
    c.stress_Pa.push_back(P * (1.0 + 0.01 * normal(rng)));
  }
  return c;
}

void expect_recovered(const LawFit &fit, const std::vector<double> &p_true)
{
  ASSERT_EQ(fit.problem, "");
  ASSERT_TRUE(fit.ls.converged);
  for (std::size_t j = 0; j < p_true.size(); ++j) {
    const double p = fit.ls.p[j], sigma = fit.ls.standard_error[j];
    std::printf("  %s %s: fitted %.6g +- %.2g, true %.6g (%.2f sigma)\n", fit.law.name.c_str(), fit.law.parameters[j].c_str(), p,
                sigma, p_true[j], std::abs(p - p_true[j]) / sigma);
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(std::abs(p - p_true[j]), 3.0 * sigma) << fit.law.parameters[j];
    // and the uncertainty is informative: 1 % noise on ~20 points per curve
    EXPECT_LT(sigma, 0.3 * std::abs(p_true[j])) << fit.law.parameters[j];
  }
  // the weighted residual's RMS estimates the 1 % noise
  EXPECT_NEAR(fit.rms_weighted, 0.01, 0.004);
}

// bapd-fit's laws are the registry's (fit_law_names): each has its fit (parameters,
// starting points), a defined stress at its starting point and a scene section naming
// it, so that a law added to the registry without a fit fails here, not in a user's hands.
TEST(FitLaws, EveryRegisteredLawHasAFit)
{
  const std::vector<std::string> names = fit_law_names();
  ASSERT_EQ(names.size(), registered_laws().size());
  for (const std::string &name : names) {
    FitLaw law;
    ASSERT_NO_THROW(law = fit_law(name, 2)) << name;
    EXPECT_EQ(law.name.compare(0, name.size(), name), 0) << law.name;
    const std::vector<std::vector<double>> starts = law.starts(4550.0, 30.0);
    ASSERT_FALSE(starts.empty()) << name;
    ASSERT_EQ(starts[0].size(), law.parameters.size()) << name;
    double P = 0.0;
    EXPECT_TRUE(law.stress(starts[0], LoadMode::uniaxial, 1.5, P)) << name;
    EXPECT_GT(P, 0.0) << name; // a stretched rubber pulls back
    EXPECT_NE(law.yaml(starts[0]).find("model: " + name), std::string::npos) << law.yaml(starts[0]);
  }
}

// A law's fit recipe (law.hpp: fit_parameters, fit_values) puts each fitted value into
// the scene option of its name: the YAML written from the starting point carries it
// there, digit for digit. Ogden's terms are numbered in the scene (ogden_mu1) and have
// their own recipe; every other law is checked.
TEST(FitLaws, EveryFittedParameterGoesToTheSceneOptionOfItsName)
{
  for (const std::string &name : fit_law_names()) {
    if (name == "ogden") continue;
    const FitLaw              law  = fit_law(name, 2);
    const std::vector<double> p    = law.starts(4550.0, 30.0)[0];
    const std::string         yaml = law.yaml(p);
    for (std::size_t k = 0; k < law.parameters.size(); ++k)
      EXPECT_NE(yaml.find("\n  " + law.parameters[k] + ": " + number_text(p[k], 10) + "\n"), std::string::npos)
          << name << " " << law.parameters[k] << ":\n" << yaml;
  }
}

TEST(FitRecovery, GentFromPureShear)
{
  std::mt19937              rng(2026);
  const FitLaw              law    = fit_law("gent", 2);
  const std::vector<double> p_true = {4.55e3, 162.6}; // the paper's gel
  const std::vector<Curve>  data   = {synthetic(law, p_true, LoadMode::pure_shear, 6.0, 25, rng)};
  expect_recovered(fit_law_to_data(law, data, Weighting::relative), p_true);
}

TEST(FitRecovery, MooneyRivlinFromUniaxialAndEquibiaxial)
{
  std::mt19937              rng(7);
  const FitLaw              law    = fit_law("mooney_rivlin", 2);
  const std::vector<double> p_true = {1800.0, 450.0}; // C10, C01 [Pa]
  const std::vector<Curve>  data   = {synthetic(law, p_true, LoadMode::uniaxial, 4.0, 20, rng),
                                      synthetic(law, p_true, LoadMode::equibiaxial, 2.5, 20, rng)};
  expect_recovered(fit_law_to_data(law, data, Weighting::relative), p_true);
}

TEST(FitRecovery, OgdenTwoTermsFromAllThreeTests)
{
  std::mt19937              rng(11);
  const FitLaw              law    = fit_law("ogden", 2);
  const std::vector<double> p_true = {3000.0, 1.5, 20.0, 5.0}; // mu1, alpha1, mu2, alpha2
  const std::vector<Curve>  data   = {synthetic(law, p_true, LoadMode::uniaxial, 5.0, 20, rng),
                                      synthetic(law, p_true, LoadMode::pure_shear, 4.0, 20, rng),
                                      synthetic(law, p_true, LoadMode::equibiaxial, 3.0, 20, rng)};
  expect_recovered(fit_law_to_data(law, data, Weighting::relative), p_true);
}

TEST(FitRecovery, GentFromASyntheticMachineExport)
{
  // A uniaxial test as a machine writes it: Time (s),Extension (mm),Load (N) to 7
  // significant digits, the rest point and two preload rows at zero extension first.
  // Specimen: gauge length 25 mm, section 4 mm x 2 mm; the force is the Gent response
  // (the paper's gel) times 1 % noise.
  std::mt19937              rng(2027);
  const FitLaw              law    = fit_law("gent", 2);
  const std::vector<double> p_true = {4.55e3, 162.6};
  const double              gauge = 0.025, section = 0.004 * 0.002;
  const std::string         path  = ::testing::TempDir() + "gent_export.csv";
  {
    std::ofstream out(path);
    out << "Time (s),Extension (mm),Load (N)\n0,0,0\n0.5,0,0.0001\n1,0,-0.00005\n";
    for (int i = 1; i <= 30; ++i) {
      const double lambda = 1.0 + 5.0 * i / 30.0; // to stretch 6
      double       P      = 0.0;
      ASSERT_TRUE(law.stress(p_true, LoadMode::uniaxial, lambda, P));
      char row[96];
      std::snprintf(row, sizeof row, "%d,%.7g,%.7g\n", 1 + i, (lambda - 1.0) * gauge * 1e3, P * section * (1.0 + 0.01 * normal(rng)));
      out << row;
    }
  }
  const Curve c = read_curve(path, "uniaxial", Specimen{gauge, section});
  ASSERT_EQ(c.stretch.size(), 30u); // the rest point and the preload dropped
  expect_recovered(fit_law_to_data(law, {c}, Weighting::relative), p_true);
}

TEST(FitRecovery, StandardErrorsCoverTheTruthAsOftenAsTheyShould)
{
  // "Within the reported uncertainty" means coverage: over many noise draws, a fitted
  // parameter lies within 1 standard error of the truth 68.3 % of the time and within 2
  // 95.4 %. 100 fits per case (fixed seeds); binomial scatter of the 1-sigma fraction
  // over 200-400 values is ~2.5 % (the values of one fit are correlated: wider bands),
  // so standard errors off by a factor 1.3 (1 sigma: 55 % or 79 %) fail.
  struct Case {
    const char         *name;
    std::vector<double> p_true;
  };
  for (const Case &c : {Case{"gent", {4.55e3, 162.6}}, Case{"mooney_rivlin", {1800.0, 450.0}},
                        Case{"ogden", {3000.0, 1.5, 20.0, 5.0}}}) {
    const FitLaw law = fit_law(c.name, 2);
    int          within[2] = {0, 0}, values = 0;
    for (int draw = 0; draw < 100; ++draw) {
      std::mt19937       rng(1000 + draw);
      std::vector<Curve> data;
      if (law.name == "gent") data = {synthetic(law, c.p_true, LoadMode::pure_shear, 6.0, 25, rng)};
      else if (law.name == "mooney_rivlin")
        data = {synthetic(law, c.p_true, LoadMode::uniaxial, 4.0, 20, rng), synthetic(law, c.p_true, LoadMode::equibiaxial, 2.5, 20, rng)};
      else
        data = {synthetic(law, c.p_true, LoadMode::uniaxial, 5.0, 20, rng), synthetic(law, c.p_true, LoadMode::pure_shear, 4.0, 20, rng),
                synthetic(law, c.p_true, LoadMode::equibiaxial, 3.0, 20, rng)};
      const LawFit fit = fit_law_to_data(law, data, Weighting::relative);
      ASSERT_EQ(fit.problem, "") << c.name << " draw " << draw;
      for (std::size_t j = 0; j < c.p_true.size(); ++j, ++values) {
        const double z = std::abs(fit.ls.p[j] - c.p_true[j]) / fit.ls.standard_error[j];
        within[0] += z < 1.0;
        within[1] += z < 2.0;
      }
    }
    const double one = 100.0 * within[0] / values, two = 100.0 * within[1] / values;
    std::printf("  %s: %d parameter values within 1 / 2 standard errors: %.1f / %.1f %%\n", c.name, values, one, two);
    EXPECT_NEAR(one, 68.3, 8.0) << c.name;
    EXPECT_NEAR(two, 95.4, 4.0) << c.name;
  }
}

TEST(FitRecovery, MooneyRivlinFromPureShearAloneIsReportedUndetermined)
{
  // pure shear has I1 = I2: only C10 + C01 is determined
  std::mt19937             rng(3);
  const FitLaw             law  = fit_law("mooney_rivlin", 2);
  const std::vector<Curve> data = {synthetic(law, {1800.0, 450.0}, LoadMode::pure_shear, 4.0, 20, rng)};
  const LawFit             fit  = fit_law_to_data(law, data, Weighting::relative);
  EXPECT_NE(fit.problem.find("not determined"), std::string::npos) << fit.problem;
}

TEST(FitRecovery, LevenbergMarquardtGivesTheLinearLeastSquaresAnswerAndCovariance)
{
  // y = a + b x with exact normal-equation solution and covariance s^2 (X^T X)^{-1}
  const std::vector<double> x = {0, 1, 2, 3, 4}, y = {1.1, 2.9, 5.2, 6.8, 9.1};
  const Residuals           r = [&](const std::vector<double> &p, std::vector<double> &out) {
    out.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) out[i] = p[0] + p[1] * x[i] - y[i];
    return true;
  };
  const LeastSquaresResult ls = levenberg_marquardt(r, {0.0, 0.0}, {1.0, 1.0}, x.size());
  ASSERT_TRUE(ls.converged);
  // closed form: b = Sxy / Sxx, a = ybar - b xbar (xbar = 2, Sxx = 10)
  const double b = (0 * (1.1 - 5.02) + 1 * (2.9 - 5.02) * 0 + (-2) * (1.1 - 5.02) + (-1) * (2.9 - 5.02) + 0 + 1 * (6.8 - 5.02) +
                    2 * (9.1 - 5.02)) / 10.0;
  const double a = 5.02 - 2.0 * b;
  EXPECT_NEAR(ls.p[1], b, 1e-9);
  EXPECT_NEAR(ls.p[0], a, 1e-9);
  const double s2 = ls.cost / 3.0;
  EXPECT_NEAR(ls.covariance[1][1], s2 / 10.0, 1e-9 * s2);      // var b = s^2 / Sxx
  EXPECT_NEAR(ls.covariance[0][0], s2 * (1.0 / 5.0 + 4.0 / 10.0), 1e-9 * s2); // var a = s^2 (1/n + xbar^2/Sxx)
}

} // namespace
} // namespace bapd::fit
