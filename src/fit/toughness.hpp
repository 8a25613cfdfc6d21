#pragma once
// The toughness of a gel from Rivlin and Thomas' pure-shear test (docs/laws.md,
// "Toughness from a notched test"; docs/method.md 5.2 takes it as -failure_fracture_energy).
// A long sheet of height H0 (the clamps' separation) with a long edge notch starts to
// crack at the stretch lambda_c where
//
//   Gamma = W(lambda_c) H0,
//
// W the strain-energy density of the un-notched sheet in pure shear: the fitted law's
// incompressible W (FitLaw::energy), the energy whose derivative bapd-fit fitted to the
// un-notched curve (dW/dlambda = P in pure shear).
//
// lambda_c is the stretch of the notched curve's largest nominal stress (the force falls
// once the crack runs), or the one the test measured (-fit_onset_stretch, e.g. by
// video). The sampled peak only says that the curve's maximum lies between the
// neighbouring samples; taken as uniform over that interval, its standard uncertainty
// is the interval's width / sqrt(12). Gamma's uncertainty adds in quadrature the fitted
// parameters' (their covariance through dW/dp, by central differences) and lambda_c's
// (dW/dlambda = P(lambda_c)): the two come from different curves, so independent. H0 is
// taken as exact.
#include <ostream>
#include <string>
#include <vector>

#include "fit_data.hpp"
#include "fit_run.hpp"

namespace bapd::fit {

struct CrackOnset {
  double      stretch     = 0.0; // lambda_c
  double      uncertainty = 0.0; // its standard uncertainty
  bool        given       = false; // from -fit_onset_stretch
  std::string rule;                // how it was found, for the report
};

// lambda_c of the notched curve: its peak, or given_stretch when > 0 (with
// given_uncertainty). Throws FitError naming the file when the peak is the curve's first
// or last point and no onset is given: the crack's onset is then not in the data.
CrackOnset crack_onset(const Curve &notched, double given_stretch, double given_uncertainty);

// H0 for the notched curve: its -fit_gauge_length, checked against the un-notched
// pure-shear curves' (those that carry one). Throws FitError (no pure-shear curve to fit,
// no gauge length, a different one).
double notched_gauge_length(const Curve &notched, const std::vector<Curve> &fitted);

struct Toughness {
  double      gamma_J_m2       = 0.0; // W(lambda_c) H0
  double      uncertainty_J_m2 = 0.0; // standard uncertainty of gamma
  double      from_parameters  = 0.0; // its part from the law's parameters [J/m^2]
  double      from_onset       = 0.0; // its part from lambda_c [J/m^2]
  double      energy_J_m3      = 0.0; // W(lambda_c)
  std::string problem;                // "" or why this law gives no toughness
};

// Gamma for one fitted law (fit.problem empty).
Toughness rivlin_thomas(const LawFit &fit, const CrackOnset &onset, double H0);

// The notched test and each law's toughness (aligned with the fits).
struct ToughnessTest {
  Curve                  notched;
  CrackOnset             onset;
  double                 H0            = 0.0;
  double                 fitted_top    = 0.0; // the largest stretch of the pure-shear data
  std::vector<Toughness> per_law;
};

// The notched curve's test: H0 checked against the fitted curves and lambda_c found
// (given_stretch > 0: -fit_onset_stretch); throws FitError as the two functions above.
ToughnessTest prepare_toughness(const Curve &notched, const std::vector<Curve> &fitted, double given_stretch, double given_uncertainty);
// Each fit's Gamma into test.per_law.
void compute_toughness(ToughnessTest &test, const std::vector<LawFit> &fits);

void print_toughness(std::ostream &out, const ToughnessTest &test, const std::vector<LawFit> &fits);
// The scene's failure: section for one law (comment lines first).
std::string failure_yaml(const ToughnessTest &test, const Toughness &t);

} // namespace bapd::fit
