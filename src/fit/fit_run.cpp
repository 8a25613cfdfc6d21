// Fitting one law (fit_run.hpp).
#include "fit_run.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "fit_error.hpp"

namespace bapd::fit {
namespace {

std::vector<double> weights(const std::vector<Curve> &curves, Weighting w)
{
  std::vector<double> out;
  for (const Curve &c : curves) {
    const double top = *std::max_element(c.stress_Pa.begin(), c.stress_Pa.end());
    for (double P : c.stress_Pa) out.push_back(w == Weighting::absolute ? 1.0 : std::max(std::abs(P), 0.05 * top));
  }
  return out;
}

std::size_t count_points(const std::vector<Curve> &curves)
{
  std::size_t m = 0;
  for (const Curve &c : curves) m += c.stretch.size();
  return m;
}

} // namespace

double neo_hookean_modulus(const std::vector<Curve> &curves, Weighting w)
{
  // P = mu f(lambda), f the neo-Hookean response per unit mu: mu = sum f P / w^2 / sum f^2 / w^2
  const std::vector<double> wt = weights(curves, w);
  double                    num = 0.0, den = 0.0;
  std::size_t               i   = 0;
  for (const Curve &c : curves)
    for (std::size_t k = 0; k < c.stretch.size(); ++k, ++i) {
      const double f = nominal_stress_from_W(c.mode, c.stretch[k], 0.5, 0.0);
      num += f * c.stress_Pa[k] / (wt[i] * wt[i]);
      den += f * f / (wt[i] * wt[i]);
    }
  return den > 0.0 ? num / den : 0.0;
}

LawFit fit_law_to_data(const FitLaw &law_in, const std::vector<Curve> &curves, Weighting w)
{
  LawFit fit;
  fit.law             = law_in;
  const std::size_t m = count_points(curves), n = law_in.parameters.size();
  fit.points          = m;
  if (m <= n)
    throw FitError("-law " + law_in.name + ": " + std::to_string(m) + " data point(s) for " + std::to_string(n) +
                   " parameter(s); a fit with uncertainties needs more points than parameters (give more data or a law with fewer parameters)");
  fit.weight       = weights(curves, w);
  const double mu0 = neo_hookean_modulus(curves, w);
  if (!(mu0 > 0.0)) throw FitError("the data carry no stress (every nominal stress is 0): nothing to fit");
  double I1max = 3.0;
  for (const Curve &c : curves) I1max = std::max(I1max, incompressible_invariants(c.mode, c.stretch.back()).I1bar);
  for (std::size_t j = 0; j < n; ++j)
    if (fit.law.units[j] == "Pa") fit.law.scale[j] = mu0;

  const Residuals res = [&](const std::vector<double> &p, std::vector<double> &r) {
    r.resize(m);
    std::size_t i = 0;
    for (const Curve &c : curves)
      for (std::size_t k = 0; k < c.stretch.size(); ++k, ++i) {
        double P = 0.0;
        if (!fit.law.stress(p, c.mode, c.stretch[k], P)) return false;
        r[i] = (P - c.stress_Pa[k]) / fit.weight[i];
      }
    return true;
  };
  bool               any = false;
  LeastSquaresResult best;
  std::string        last_why;
  for (const std::vector<double> &start : fit.law.starts(mu0, I1max)) {
    LeastSquaresResult r = levenberg_marquardt(res, start, fit.law.scale, m);
    if (!r.converged) {
      last_why = r.why;
      continue;
    }
    if (!any || r.cost < best.cost) best = r, any = true;
  }
  if (!any) {
    fit.problem = "the fit did not converge from any start (" + last_why + "): this law cannot fit these data";
    return fit;
  }
  if (fit.law.order) {
    // the canonical order (interchangeable terms): permute p, its errors and covariance
    const std::vector<std::size_t> o = fit.law.order(best.p);
    LeastSquaresResult             r = best;
    for (std::size_t a = 0; a < n; ++a) {
      r.p[a] = best.p[o[a]];
      if (!best.standard_error.empty()) r.standard_error[a] = best.standard_error[o[a]];
      if (!best.covariance.empty())
        for (std::size_t b = 0; b < n; ++b) r.covariance[a][b] = best.covariance[o[a]][o[b]];
    }
    best = r;
  }
  fit.ls = best;
  fit.fitted.resize(m);
  std::size_t i   = 0;
  double      ss  = 0.0;
  for (const Curve &c : curves)
    for (std::size_t k = 0; k < c.stretch.size(); ++k, ++i) {
      fit.law.stress(best.p, c.mode, c.stretch[k], fit.fitted[i]);
      ss += (fit.fitted[i] - c.stress_Pa[k]) * (fit.fitted[i] - c.stress_Pa[k]);
    }
  fit.rms_Pa       = std::sqrt(ss / m);
  fit.rms_weighted = std::sqrt(best.cost / m);
  fit.aic          = m * std::log(std::max(best.cost, std::numeric_limits<double>::min()) / m) + 2.0 * n;
  const std::string refused = fit.law.check(best.p);
  if (!refused.empty()) {
    std::string line = refused.substr(0, refused.find('\n'));
    fit.problem      = "the best fit is outside what the law allows (" + line + "): this law cannot fit these data";
  } else if (best.singular)
    fit.problem = "the parameters are not determined by these data (J^T J is singular at the optimum): add data "
                  "(another mode, larger stretches) or choose a law with fewer parameters";
  return fit;
}

} // namespace bapd::fit
