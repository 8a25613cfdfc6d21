// Rivlin and Thomas' toughness from a notched pure-shear curve (toughness.hpp).
#include "toughness.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fit_error.hpp"
#include "number_text.hpp"

namespace bapd::fit {
namespace {

std::size_t peak_index(const Curve &c)
{
  return static_cast<std::size_t>(std::max_element(c.stress_Pa.begin(), c.stress_Pa.end()) - c.stress_Pa.begin());
}

// "10250 Pa at stretch 3"
std::string peak_text(const Curve &c, std::size_t i)
{
  return number_text(c.stress_Pa[i], 6) + " Pa at stretch " + number_text(c.stretch[i], 6);
}

} // namespace

CrackOnset crack_onset(const Curve &notched, double given_stretch, double given_uncertainty)
{
  const std::vector<double> &l = notched.stretch;
  const std::size_t          i = peak_index(notched), last = l.size() - 1;
  const bool                 inside = i > 0 && i < last; // a peak with a sample on each side
  CrackOnset                 onset;
  if (given_stretch > 0.0) {
    onset = {given_stretch, given_uncertainty, true, "given by -fit_onset_stretch"};
    onset.rule += inside ? "; the notched curve's largest stress is " + peak_text(notched, i) : "";
    return onset;
  }
  if (i == last)
    throw FitError(notched.file + ": the notched curve's largest nominal stress is its last point (" + peak_text(notched, i) +
                   "): the crack's onset, after which the force falls, is not in the data; give the rows past the peak, or the "
                   "onset stretch the test measured with -fit_onset_stretch LAMBDA");
  if (i == 0)
    throw FitError(notched.file + ": the notched curve falls from its first point (" + peak_text(notched, i) +
                   "): the loading up to the crack's onset is not in the data; give the whole loading branch, or the onset "
                   "stretch the test measured with -fit_onset_stretch LAMBDA");
  // The maximum of the curve lies between the neighbouring samples; uniform over that
  // interval, its standard deviation is the width / sqrt(12) (a type B uncertainty).
  onset.stretch     = l[i];
  onset.uncertainty = (l[i + 1] - l[i - 1]) / std::sqrt(12.0);
  onset.rule        = "the notched curve's largest nominal stress, " + peak_text(notched, i) + "; +- from its neighbours at " +
               number_text(l[i - 1], 6) + " and " + number_text(l[i + 1], 6);
  return onset;
}

double notched_gauge_length(const Curve &notched, const std::vector<Curve> &fitted)
{
  std::vector<const Curve *> shear;
  for (const Curve &c : fitted)
    if (c.mode == LoadMode::pure_shear) shear.push_back(&c);
  if (shear.empty())
    throw FitError(notched.file + ": a notched pure-shear curve gives the toughness Gamma = W(lambda_c) H0, W the energy of the "
                                  "un-notched sheet in pure shear: give that sheet's curve too (e.g. pure_shear:unnotched.csv, "
                                  "the same height H0), which the law is fitted to");
  const double H0 = notched.gauge_length_m;
  if (!(H0 > 0.0))
    throw FitError(notched.file + ": Gamma = W(lambda_c) H0 needs the sheet's height H0, the clamps' separation: give "
                                  "-fit_gauge_length H0 in m before the notched file, e.g. -fit_gauge_length 0.01 for 10 mm");
  for (const Curve *c : shear)
    if (c->gauge_length_m > 0.0 && std::abs(c->gauge_length_m - H0) > 1e-9 * H0)
      throw FitError(notched.file + ": its gauge length H0 = " + number_text(H0, 6) + " m differs from the un-notched pure-shear "
                     "curve's (" + c->file + ": " + number_text(c->gauge_length_m, 6) + " m); Rivlin-Thomas compares sheets of "
                     "one height: give the notched and the un-notched tests of the same H0 (-fit_gauge_length before each file)");
  return H0;
}

Toughness rivlin_thomas(const LawFit &fit, const CrackOnset &onset, double H0)
{
  Toughness                  t;
  const FitLaw              &law = fit.law;
  const std::vector<double> &p   = fit.ls.p;
  const double               lc  = onset.stretch;
  double                     W = 0.0, P = 0.0;
  const std::string          undefined =
      "the law is not defined at lambda_c = " + number_text(lc, 6) + " (past its limit, or near it): no toughness from it";
  if (!law.energy(p, LoadMode::pure_shear, lc, W) || !law.stress(p, LoadMode::pure_shear, lc, P)) {
    t.problem = undefined;
    return t;
  }
  // dW/dp by central differences (W is smooth in p; step 1e-6 of the parameter or its scale)
  const std::size_t   n = p.size();
  std::vector<double> dW(n, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    const double        h = 1e-6 * std::max(std::abs(p[j]), law.scale[j]);
    std::vector<double> q = p;
    double              Wp = 0.0, Wm = 0.0;
    q[j] = p[j] + h;
    const bool up = law.energy(q, LoadMode::pure_shear, lc, Wp);
    q[j]          = p[j] - h;
    if (!up || !law.energy(q, LoadMode::pure_shear, lc, Wm)) {
      t.problem = undefined;
      return t;
    }
    dW[j] = (Wp - Wm) / (2.0 * h);
  }
  if (fit.ls.covariance.size() != n) {
    t.problem = "the fit has no covariance of its parameters: no uncertainty of Gamma from it";
    return t;
  }
  double variance = 0.0; // dW^T C dW, C the fitted parameters' covariance
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) variance += dW[a] * fit.ls.covariance[a][b] * dW[b];
  t.energy_J_m3      = W;
  t.gamma_J_m2       = W * H0;
  t.from_parameters  = H0 * std::sqrt(std::max(variance, 0.0));
  t.from_onset       = H0 * std::abs(P) * onset.uncertainty; // dW/dlambda = P in pure shear
  t.uncertainty_J_m2 = std::hypot(t.from_parameters, t.from_onset);
  return t;
}

ToughnessTest prepare_toughness(const Curve &notched, const std::vector<Curve> &fitted, double given_stretch, double given_uncertainty)
{
  ToughnessTest test;
  test.notched = notched;
  test.H0      = notched_gauge_length(notched, fitted);
  test.onset   = crack_onset(notched, given_stretch, given_uncertainty);
  for (const Curve &c : fitted)
    if (c.mode == LoadMode::pure_shear) test.fitted_top = std::max(test.fitted_top, c.stretch.back());
  return test;
}

void compute_toughness(ToughnessTest &test, const std::vector<LawFit> &fits)
{
  test.per_law.clear();
  for (const LawFit &fit : fits) {
    Toughness t;
    if (fit.problem.empty()) t = rivlin_thomas(fit, test.onset, test.H0);
    else t.problem = "no fit";
    test.per_law.push_back(t);
  }
}

void print_toughness(std::ostream &out, const ToughnessTest &test, const std::vector<LawFit> &fits)
{
  out << "toughness (Rivlin-Thomas, Gamma = W(lambda_c) H0, W the fitted law's in pure shear): " << test.notched.file
      << ", H0 = " << number_text(test.H0, 6) << " m\n";
  out << "  lambda_c = " << number_text(test.onset.stretch, 6) << " +- " << number_text(test.onset.uncertainty, 2) << " ("
      << test.onset.rule << ")\n";
  if (test.onset.stretch > test.fitted_top)
    out << "  note: lambda_c is beyond the pure-shear data (stretch up to " << number_text(test.fitted_top, 6)
        << "): W(lambda_c) is each law's extrapolation, and the laws may disagree there\n";
  for (std::size_t k = 0; k < fits.size() && k < test.per_law.size(); ++k) {
    const Toughness &t = test.per_law[k];
    out << "  " << fits[k].law.name << ": ";
    if (!t.problem.empty()) {
      out << t.problem << "\n";
      continue;
    }
    out << "Gamma = " << number_text(t.gamma_J_m2, 5) << " +- " << number_text(t.uncertainty_J_m2, 2) << " J/m^2 (W = "
        << number_text(t.energy_J_m3, 6) << " J/m^3; +- " << number_text(t.from_parameters, 2) << " from the parameters, "
        << number_text(t.from_onset, 2) << " from lambda_c)\n";
  }
}

std::string failure_yaml(const ToughnessTest &test, const Toughness &t)
{
  std::ostringstream y;
  y << "# Rivlin-Thomas: Gamma = W(lambda_c) H0 = " << number_text(t.gamma_J_m2, 5) << " +- " << number_text(t.uncertainty_J_m2, 2)
    << " J/m^2, W = " << number_text(t.energy_J_m3, 6) << " J/m^3 this law's in pure shear,\n"
    << "# lambda_c = " << number_text(test.onset.stretch, 6) << " +- " << number_text(test.onset.uncertainty, 2) << " ("
    << (test.onset.given ? "-fit_onset_stretch" : "the peak") << " of " << test.notched.file << "), H0 = " << number_text(test.H0, 6)
    << " m. A scene takes one failure\n"
    << "# criterion: include this after a scene without failure: critical_stretch (e.g. examples/notched_pure_shear_gamma.yaml).\n"
    << "failure:\n  fracture_energy: " << number_text(t.gamma_J_m2, 6) << "\n";
  return y.str();
}

} // namespace bapd::fit
