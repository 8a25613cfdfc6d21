#pragma once
// Fitting one law to a set of curves (fit_data.hpp) by weighted least squares
// (levenberg_marquardt.hpp) on its incompressible homogeneous responses (fit_laws.hpp).
//
// Weights: "relative" (the default) divides each residual by max(|P_i|, 5 % of the
// curve's largest stress), which suits data whose scatter grows with the stress (a
// load cell's percent accuracy) and lets curves of different sizes count alike;
// "absolute" fits in Pa. The standard errors are from s^2 (J^T J)^{-1} at the optimum.
// Every start (fit_laws.hpp) is tried; the lowest misfit among the converged ones wins.
#include <string>
#include <vector>

#include "fit_data.hpp"
#include "fit_laws.hpp"
#include "levenberg_marquardt.hpp"

namespace bapd::fit {

enum class Weighting { relative, absolute };

struct LawFit {
  FitLaw              law;
  LeastSquaresResult  ls;
  std::vector<double> fitted;          // the model's stress at every data point [Pa]
  std::vector<double> weight;          // the residual divisor of every point
  std::size_t         points     = 0;
  double              rms_Pa     = 0.0; // sqrt(mean (P_fit - P)^2)
  double              rms_weighted = 0.0;
  double              aic        = 0.0; // m ln(|r|^2 / m) + 2 n (the weighted misfit)
  std::string         problem;          // "" or why this law cannot fit the data
};

// The neo-Hookean shear modulus of the data (linear least squares): the starting scale.
double neo_hookean_modulus(const std::vector<Curve> &curves, Weighting w);

// Throws FitError for too few points; a law that cannot fit is returned with problem set.
LawFit fit_law_to_data(const FitLaw &law, const std::vector<Curve> &curves, Weighting w);

} // namespace bapd::fit
