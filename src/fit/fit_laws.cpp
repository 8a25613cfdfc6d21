// The fittable laws (fit_laws.hpp).
#include "fit_laws.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "bapd/core/materials/law_registry.hpp"
#include "bapd/core/materials/material.hpp"
#include "fit_error.hpp"
#include "number_text.hpp"

namespace bapd::fit {
namespace {

// A registry law from the fitted values: set(m, p) puts them into MaterialParameters.
template <class Law>
FitLaw registry_law(std::vector<std::string> names, std::vector<std::string> units, std::vector<double> scale,
                    void (*set)(MaterialParameters &, const std::vector<double> &),
                    std::function<std::vector<std::vector<double>>(double, double)> starts)
{
  FitLaw f;
  f.name       = Law::name;
  f.parameters = std::move(names);
  f.units      = std::move(units);
  f.scale      = std::move(scale);
  f.starts     = std::move(starts);
  f.stress     = [set](const std::vector<double> &p, LoadMode mode, double lambda, double &P) {
    MaterialParameters m;
    set(m, p);
    return incompressible_nominal_stress<Law>(ParametersOf<Law>(m), mode, lambda, P) && std::isfinite(P);
  };
  f.check = [set](const std::vector<double> &p) {
    MaterialParameters m;
    set(m, p);
    m.D = 2.0 / (1000.0 * m.mu); // (the scene's default; the fit is incompressible)
    ModelKind kind{};
    parse(Law::name, kind);
    return check_parameters(kind, m);
  };
  f.yaml = [set](const std::vector<double> &p) {
    MaterialParameters m;
    set(m, p);
    ModelKind kind{};
    parse(Law::name, kind);
    std::ostringstream y;
    y << "material:\n  model: " << Law::name << "\n  mu: " << number_text(m.mu, 10) << "\n";
    for (const LawOptionEntry &o : law_entry(kind).options)
      y << "  " << std::string(o.name).substr(std::string("-material_").size()) << ": " << number_text(m.values[o.index], 10) << "\n";
    return y.str();
  };
  return f;
}

// Ogden with n terms: p = (mu_1, alpha_1, ..., mu_n, alpha_n); mu = sum mu_k alpha_k / 2.
FitLaw ogden(int n)
{
  if (n < 1 || n > 4) throw FitError("-ogden_terms " + std::to_string(n) + ": give 1 to 4 Ogden terms");
  FitLaw f;
  f.name    = "ogden";
  f.in_bapd = n <= Ogden::max_terms;
  for (int k = 1; k <= n; ++k) {
    f.parameters.push_back("mu" + std::to_string(k));
    f.units.push_back("Pa");
    f.scale.push_back(1.0); // (Pa parameters: scaled by mu0 in fit_law_to_data)
    f.parameters.push_back("alpha" + std::to_string(k));
    f.units.push_back("-");
    f.scale.push_back(1.0);
  }
  f.starts = [n](double mu0, double) {
    // exponents spread over the usual range (Treloar's rubber: 1.3, 5, -2), the shear
    // modulus at rest split 90 / 10 % between the first and the others
    const std::vector<std::vector<double>> alpha_sets = n == 1   ? std::vector<std::vector<double>>{{2.0}, {1.0}, {4.0}}
                                                       : n == 2 ? std::vector<std::vector<double>>{{1.5, 5.0}, {2.0, -2.0}, {1.0, 8.0}, {3.0, -1.0}}
                                                                : std::vector<std::vector<double>>{{1.3, 5.0, -2.0, 8.0}};
    std::vector<std::vector<double>> out;
    for (const auto &alpha : alpha_sets) {
      std::vector<double> p;
      for (int k = 0; k < n; ++k) {
        const double a     = alpha[k % alpha.size()] + (k >= static_cast<int>(alpha.size()) ? 1.0 : 0.0);
        const double share = k == 0 ? 0.9 : 0.1 / (n - 1);
        p.push_back(2.0 * share * mu0 / a);
        p.push_back(a);
      }
      out.push_back(p);
    }
    return out;
  };
  f.order = [n](const std::vector<double> &p) {
    std::vector<std::size_t> terms(n), out;
    for (int k = 0; k < n; ++k) terms[k] = k;
    std::stable_sort(terms.begin(), terms.end(), [&](std::size_t a, std::size_t b) { return p[2 * a + 1] < p[2 * b + 1]; });
    for (std::size_t k : terms) out.push_back(2 * k), out.push_back(2 * k + 1);
    return out;
  };
  f.stress = [n](const std::vector<double> &p, LoadMode mode, double lambda, double &P) {
    double mu[4], alpha[4];
    for (int k = 0; k < n; ++k) mu[k] = p[2 * k], alpha[k] = p[2 * k + 1];
    P = ogden_nominal_stress(mu, alpha, n, mode, lambda);
    return std::isfinite(P);
  };
  f.check = [n](const std::vector<double> &p) {
    std::ostringstream msg;
    double             sum = 0.0;
    for (int k = 0; k < n; ++k) {
      sum += p[2 * k] * p[2 * k + 1];
      if (!(p[2 * k] * p[2 * k + 1] > 0.0))
        msg << "ogden mu" << k + 1 << " alpha" << k + 1 << " = " << p[2 * k] * p[2 * k + 1]
            << " Pa: each term needs mu_k alpha_k > 0 (the usual sufficient condition for stability)\n";
    }
    if (!(sum > 0.0)) msg << "ogden: the shear modulus at rest sum mu_k alpha_k / 2 must be > 0\n";
    return msg.str();
  };
  f.yaml = [n](const std::vector<double> &p) {
    std::ostringstream y;
    double             mu = 0.0;
    for (int k = 0; k < n; ++k) mu += 0.5 * p[2 * k] * p[2 * k + 1];
    if (n > Ogden::max_terms) {
      y << "# Ogden (" << n << " terms): bapd's Ogden law has at most " << Ogden::max_terms << " terms; the values, for the record:\n";
      y << "#   shear modulus at rest mu = sum mu_k alpha_k / 2 = " << number_text(mu, 10) << " Pa\n";
      for (int k = 0; k < n; ++k) y << "#   mu" << k + 1 << " = " << number_text(p[2 * k], 10) << " Pa, alpha" << k + 1 << " = " << number_text(p[2 * k + 1], 10) << "\n";
      return y.str();
    }
    y << "material:\n  model: ogden\n  mu: " << number_text(mu, 10) << "\n";
    for (int k = 0; k < Ogden::max_terms; ++k) // unused terms: mu_k = 0
      y << "  ogden_mu" << k + 1 << ": " << number_text(k < n ? p[2 * k] : 0.0, 10) << "\n  ogden_alpha" << k + 1 << ": "
        << number_text(k < n ? p[2 * k + 1] : 0.0, 10) << "\n";
    return y.str();
  };
  return f;
}

} // namespace

std::vector<std::string> fit_law_names()
{
  std::vector<std::string> names;
  for (const LawEntry &law : registered_laws()) names.push_back(law.name);
  return names;
}

FitLaw fit_law(const std::string &name, int ogden_terms)
{
  // starting points: mu0 from the data, limits beyond the data's largest I1
  if (name == "neo_hookean")
    return registry_law<NeoHookean>({"mu"}, {"Pa"}, {1.0}, [](MaterialParameters &m, const std::vector<double> &p) { m.mu = p[0]; },
                                    [](double mu0, double) { return std::vector<std::vector<double>>{{mu0}}; });
  if (name == "gent")
    return registry_law<Gent>({"mu", "Jm"}, {"Pa", "-"}, {1.0, 1.0},
                              [](MaterialParameters &m, const std::vector<double> &p) { m.mu = p[0], m["-material_Jm"] = p[1]; },
                              [](double mu0, double I1max) {
                                const double x = I1max - 3.0;
                                return std::vector<std::vector<double>>{{mu0, 1.5 * x + 1.0}, {mu0, 4.0 * x + 1.0}, {mu0, 20.0 * x + 10.0}};
                              });
  if (name == "mooney_rivlin")
    return registry_law<MooneyRivlin>({"C10", "C01"}, {"Pa", "Pa"}, {1.0, 1.0},
                                      [](MaterialParameters &m, const std::vector<double> &p) {
                                        m["-material_C10"] = p[0], m["-material_C01"] = p[1], m.mu = 2.0 * (p[0] + p[1]);
                                      },
                                      [](double mu0, double) {
                                        return std::vector<std::vector<double>>{{0.4 * mu0, 0.1 * mu0}, {0.25 * mu0, 0.25 * mu0}};
                                      });
  if (name == "yeoh")
    return registry_law<Yeoh>({"C1", "C2", "C3"}, {"Pa", "Pa", "Pa"}, {1.0, 1.0, 1.0},
                              [](MaterialParameters &m, const std::vector<double> &p) {
                                m["-material_C1"] = p[0], m["-material_C2"] = p[1], m["-material_C3"] = p[2], m.mu = 2.0 * p[0];
                              },
                              [](double mu0, double) { return std::vector<std::vector<double>>{{0.5 * mu0, 0.0, 0.0}}; });
  if (name == "arruda_boyce")
    return registry_law<ArrudaBoyce>({"mu", "lambda_m"}, {"Pa", "-"}, {1.0, 1.0},
                                     [](MaterialParameters &m, const std::vector<double> &p) { m.mu = p[0], m["-material_lambda_m"] = p[1]; },
                                     [](double mu0, double I1max) {
                                       const double lc = std::sqrt(I1max / 3.0);
                                       return std::vector<std::vector<double>>{{mu0, 1.5 * lc}, {mu0, 3.0 * lc}, {mu0, 10.0 * lc}};
                                     });
  if (name == "ogden") return ogden(ogden_terms);
  std::string all;
  for (const std::string &n : fit_law_names()) all += (all.empty() ? "" : ", ") + n;
  throw FitError("-law " + name + ": not a law bapd-fit knows; choose from " + all);
}

} // namespace bapd::fit
