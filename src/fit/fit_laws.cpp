// The fittable laws (fit_laws.hpp).
#include "fit_laws.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>
#include <type_traits>

#include "bapd/core/materials/law_registry.hpp"
#include "bapd/core/materials/material.hpp"
#include "fit_error.hpp"
#include "number_text.hpp"

namespace bapd::fit {
namespace {

// The law's values from fitted values p (Law::fit_values, law.hpp), in the scene's store.
template <class Law> void set_fitted(MaterialParameters &m, const std::vector<double> &p)
{
  typename Law::Parameters own;
  Law::fit_values(p.data(), m, own);
  const std::size_t first = law_value_offset<Law>();
  for (std::size_t i = 0; i < Law::options.size(); ++i) m.values[first + i] = own.*(Law::options[i].value);
}

// A registry law's fit from its header's recipe (fit_parameters, fit_values, fit_starts).
template <class Law> FitLaw registry_law()
{
  FitLaw f;
  f.name = Law::name;
  for (const FitParameter &q : Law::fit_parameters) {
    f.parameters.push_back(q.name);
    f.units.push_back(q.unit);
    f.scale.push_back(1.0); // (Pa parameters: scaled by mu0 in fit_law_to_data)
  }
  f.starts = &Law::fit_starts;
  f.stress = [](const std::vector<double> &p, LoadMode mode, double lambda, double &P) {
    MaterialParameters m;
    set_fitted<Law>(m, p);
    return incompressible_nominal_stress<Law>(ParametersOf<Law>(m), mode, lambda, P) && std::isfinite(P);
  };
  f.energy = [](const std::vector<double> &p, LoadMode mode, double lambda, double &W) {
    MaterialParameters m;
    set_fitted<Law>(m, p);
    // incompressible: J = 1, U(J) = 0, and the invariants are the isochoric ones
    return Law::energy(ParametersOf<Law>(m), incompressible_invariants(mode, lambda), W) && std::isfinite(W);
  };
  f.check = [](const std::vector<double> &p) {
    MaterialParameters m;
    set_fitted<Law>(m, p);
    m.D = 2.0 / (1000.0 * m.mu); // (the scene's default; the fit is incompressible)
    return check_parameters(law_kind<Law>(), m);
  };
  f.yaml = [](const std::vector<double> &p) {
    MaterialParameters m;
    set_fitted<Law>(m, p);
    std::ostringstream y;
    y << "material:\n  model: " << Law::name << "\n  mu: " << number_text(m.mu, 10) << "\n";
    for (const LawOptionEntry &o : law_entry(law_kind<Law>()).options)
      y << "  " << std::string(o.name).substr(std::string("-material_").size()) << ": " << number_text(m.values[o.index], 10) << "\n";
    return y.str();
  };
  return f;
}

// Whether Law's header carries a fit recipe (law.hpp: fit_parameters).
template <class Law, class = void> struct HasFitRecipe : std::false_type {};
template <class Law> struct HasFitRecipe<Law, std::void_t<decltype(Law::fit_parameters)>> : std::true_type {};

// Every registered law has its fit: its header's recipe, or (Ogden) one below.
template <class... Laws> constexpr bool every_law_has_a_fit(std::tuple<Laws...> *)
{
  return ((HasFitRecipe<Laws>::value || std::is_same_v<Laws, Ogden>) && ...);
}
static_assert(every_law_has_a_fit(static_cast<RegisteredLaws *>(nullptr)),
              "a registered law needs a fit recipe in its header: fit_parameters, fit_values, fit_starts (law.hpp)");

// The fit of the registered law called name; false if there is none.
template <class... Laws> bool registry_fit(const std::string &name, FitLaw &f, std::tuple<Laws...> *)
{
  bool found = false;
  auto try_law = [&](auto *law) {
    using Law = std::remove_pointer_t<decltype(law)>;
    if constexpr (HasFitRecipe<Law>::value)
      if (!found && name == Law::name) f = registry_law<Law>(), found = true;
  };
  (try_law(static_cast<Laws *>(nullptr)), ...);
  return found;
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
  f.energy = [n](const std::vector<double> &p, LoadMode mode, double lambda, double &W) {
    double l[3];
    principal_stretches(mode, lambda, l);
    W = 0.0;
    for (int k = 0; k < n; ++k) { // sum_i l_i^a - 3 = sum_i expm1(a ln l_i): no cancellation near rest
      double s = 0.0;
      for (double li : l) s += std::expm1(p[2 * k + 1] * std::log(li));
      W += p[2 * k] / p[2 * k + 1] * s;
    }
    return std::isfinite(W);
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
  if (name == Ogden::name) return ogden(ogden_terms);
  FitLaw f;
  if (registry_fit(name, f, static_cast<RegisteredLaws *>(nullptr))) return f;
  std::string all;
  for (const std::string &n : fit_law_names()) all += (all.empty() ? "" : ", ") + n;
  throw FitError("-law " + name + ": not a law bapd-fit knows; choose from " + all);
}

} // namespace bapd::fit
