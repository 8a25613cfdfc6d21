#pragma once
// The Arruda-Boyce eight-chain law (Arruda and Boyce 1993), with the volumetric term of
// paper eq 24 (hyperelastic.hpp, plane_stress.hpp). The chain stretch is
// lambda_ch = sqrt(I1bar / 3); with x = lambda_ch / lambda_m and b = L^{-1}(x)
// (inverse_langevin.hpp),
//   Psi_iso = (mu lambda_m^2 / g0) [x b + ln(b / sinh b)] - (the same at rest),
//   G = 2 dPsi_iso/dI1bar = (mu / g0) b / (3 x)        (d/dx [x b + ln(b/sinh b)] = b),
// g0 = b0 / (3 x0) at rest (x0 = 1/lambda_m), so that G = mu at rest: mu is the shear
// modulus at rest as for every law (the classical form's mu_chain is mu / g0, and
// g0 = 1 + 3/(5 lambda_m^2) + ...). Finite for I1bar < 3 lambda_m^2 (x < 1, the chains
// fully extended): a limit like Gent's, and convex and increasing in I1bar below it
// (b/x is increasing and convex in x; lambda_ch is concave in I1bar, but G as a
// function of I1bar is increasing and convex: L^{-1} grows faster than any power near 1).
//
// The plane-stress solve needs G and four I1bar-derivatives. They are computed by
// Taylor series (degree 4) in the variable b: I1bar(b) = 3 lambda_m^2 L(b)^2 and
// G(b) = (mu/g0) b / (3 L(b)) from L's Taylor coefficients at b0 (langevin_taylor),
// then the series of I1bar - I1bar0 is reverted to b - b0 as a series in
// e = I1bar - I1bar0, and G composed with it. Each bond pays one inverse-Langevin
// solve (g0 is remembered per lambda_m); several bonds at a time (Lanes, HalfLanes) run lane by lane.
// The law interface is described in law.hpp; the registry line is in law_list.hpp.
#include <type_traits>

#include "bapd/core/materials/inverse_langevin.hpp"
#include "bapd/core/materials/invariant_law.hpp"

namespace bapd {

namespace arruda_boyce_detail {
using Series = std::array<double, 5>; // truncated Taylor series, degree 4

inline Series mul(const Series &a, const Series &b)
{
  Series c{};
  for (int i = 0; i < 5; ++i)
    for (int j = 0; i + j < 5; ++j) c[i + j] += a[i] * b[j];
  return c;
}
inline Series div(const Series &a, const Series &b) // a / b, b[0] != 0
{
  Series c{};
  for (int n = 0; n < 5; ++n) {
    double v = a[n];
    for (int k = 0; k < n; ++k) v -= c[k] * b[n - k];
    c[n] = v / b[0];
  }
  return c;
}
// f(d(e)) with d(0) = 0 (d[0] ignored)
inline Series compose(const Series &f, Series d)
{
  d[0] = 0.0;
  Series out{}, power{};
  power[0] = 1.0;
  for (int n = 0; n < 5; ++n) {
    for (int i = 0; i < 5; ++i) out[i] += f[n] * power[i];
    power = mul(power, d);
  }
  return out;
}
// the inverse series: a(d) = a1 d + a2 d^2 + ... -> d(e) = b1 e + b2 e^2 + ...
inline Series revert(const Series &a)
{
  const double a1 = a[1], a2 = a[2], a3 = a[3], a4 = a[4];
  const double r = 1.0 / a1, r2 = r * r, r3 = r2 * r;
  return {0.0, r, -a2 * r3, (2.0 * a2 * a2 - a1 * a3) * r3 * r2,
          (5.0 * a1 * a2 * a3 - a1 * a1 * a4 - 5.0 * a2 * a2 * a2) * r3 * r3 * r};
}
// ln(b / sinh b), b >= 0, without cancellation near 0 or overflow for large b.
inline double log_b_over_sinh(double b)
{
  if (b < 0.5) {
    double term = 1.0, sum = 0.0; // sinh b / b - 1 = sum_{k>=1} b^{2k} / (2k+1)!
    for (int k = 1; k <= 10; ++k) {
      term *= b * b / ((2.0 * k) * (2.0 * k + 1.0));
      sum += term;
    }
    return -std::log1p(sum);
  }
  // ln sinh b = b - ln 2 + ln(1 - e^{-2b})
  return std::log(b) - (b - std::log(2.0) + std::log1p(-std::exp(-2.0 * b)));
}
} // namespace arruda_boyce_detail

struct ArrudaBoyce {
  static constexpr const char *name = "arruda_boyce", *title = "Arruda-Boyce eight-chain: locking stretch lambda_m (G = mu at rest)";

  struct Parameters {
    double lambda_m = 7.54; // locking chain stretch [-]: 3 lambda_m^2 - 3 = 167.6, near Gent's Jm 162.6
  };
  static constexpr std::array<LawOption<Parameters>, 1> options = {
      {{"-material_lambda_m",
        "Arruda-Boyce locking chain stretch lambda_m [-], > 1 (default 7.54: I1bar limit 3 lambda_m^2 near Gent's Jm + 3)",
        &Parameters::lambda_m}}};
  static std::string check(const ParametersOf<ArrudaBoyce> &p)
  {
    std::ostringstream msg;
    if (!(p.lambda_m > 1.0) || !std::isfinite(p.lambda_m))
      msg << "-material_lambda_m " << p.lambda_m
          << ": the Arruda-Boyce locking stretch must be > 1 (the chain stretch is 1 at rest); gels: about 3 to 10\n";
    return msg.str();
  }

  // bapd-fit (law.hpp: fit_parameters): mu and lambda_m; lambda_m starts beyond the
  // chain stretch sqrt(I1 / 3) of the data's largest I1, so that the first iterate is
  // not locked.
  static constexpr std::array<FitParameter, 2> fit_parameters = {{{"mu", "Pa"}, {"lambda_m", "-"}}};
  static void fit_values(const double *p, ElasticConstants &c, Parameters &own) { c.mu = p[0], own.lambda_m = p[1]; }
  static std::vector<std::vector<double>> fit_starts(double mu0, double I1max)
  {
    const double lc = std::sqrt(I1max / 3.0);
    return {{mu0, 1.5 * lc}, {mu0, 3.0 * lc}, {mu0, 10.0 * lc}};
  }

  static constexpr LawVariables variables         = LawVariables::invariants;
  static constexpr bool         uses_I2bar        = false;
  static constexpr bool         convex_increasing = true; // see the top of this file
  static constexpr bool         has_limit         = true;
  static double I1bar_limit(const ParametersOf<ArrudaBoyce> &p) { return 3.0 * p.lambda_m * p.lambda_m; }
  static constexpr const char *limit        = "the Arruda-Boyce locking stretch (I1bar >= 3 lambda_m^2: chains fully extended)";
  static constexpr const char *limit_option = "-material_lambda_m";

  // g0 = b0 / (3 x0), x0 = 1 / lambda_m: G = (mu / g0) b / (3x) is mu at rest.
  // It depends on lambda_m alone: solved once per value and thread, not per bond
  // (the same number either way).
  static double rest_factor(const ParametersOf<ArrudaBoyce> &p)
  {
    thread_local double lambda_m = 0.0, g0 = 1.0;
    if (p.lambda_m != lambda_m) {
      const double x0 = 1.0 / p.lambda_m;
      g0              = inverse_langevin(x0) / (3.0 * x0);
      lambda_m        = p.lambda_m;
    }
    return g0;
  }

  // One bond: G and its I1bar-derivatives (see the top); false where locked or NaN.
  static bool modulus_one(const ParametersOf<ArrudaBoyce> &p, double I1bar, Modulus &G)
  {
    using namespace arruda_boyce_detail;
    const double x = std::sqrt(I1bar / 3.0) / p.lambda_m;
    if (!(x > 0.0 && x < 1.0)) {
      G = {p.mu, 0.0, 0.0, 0.0, 0.0}; // finite, meaningless
      return false;
    }
    const double b     = inverse_langevin(x);
    const Series L     = langevin_taylor(b);
    const Series I     = mul(L, L);         // I1bar(b) / (3 lambda_m^2)
    const Series g     = div({b, 1.0, 0.0, 0.0, 0.0}, L); // b / L(b)
    Series       a     = I;
    for (double &v : a) v *= 3.0 * p.lambda_m * p.lambda_m;
    const Series d     = revert(a); // b - b0 in powers of I1bar - I1bar0
    const Series ge    = compose(g, d);
    const double scale = p.mu / (3.0 * rest_factor(p));
    const double factorial[5] = {1.0, 1.0, 2.0, 6.0, 24.0};
    for (int n = 0; n < 5; ++n) G[n] = scale * factorial[n] * ge[n];
    return true;
  }

  template <class T>
  static MaskOf<T> modulus(const ParametersOf<ArrudaBoyce> &p, const InvariantsOf<T> &inv, ModulusOf<T> &G)
  {
    if constexpr (std::is_same_v<T, double>) {
      return modulus_one(p, inv.I1bar, G);
    } else {
      MaskOf<T> ok{};
      for (int lane = 0; lane < static_cast<int>(sizeof(T) / sizeof(double)); ++lane) { // Lanes or HalfLanes
        Modulus g;
        ok[lane] = modulus_one(p, inv.I1bar[lane], g) ? -1 : 0;
        for (int n = 0; n < 5; ++n) G[n][lane] = g[n];
      }
      return ok;
    }
  }

  static bool energy(const ParametersOf<ArrudaBoyce> &p, const Invariants &inv, double &psi)
  {
    using arruda_boyce_detail::log_b_over_sinh;
    const double x = std::sqrt(inv.I1bar / 3.0) / p.lambda_m, x0 = 1.0 / p.lambda_m;
    if (!(x >= 0.0 && x < 1.0)) return false;
    const double b = inverse_langevin(x), b0 = inverse_langevin(x0);
    const double g0 = b0 / (3.0 * x0);
    psi = p.mu * p.lambda_m * p.lambda_m / g0 * ((x * b + log_b_over_sinh(b)) - (x0 * b0 + log_b_over_sinh(b0)));
    return true;
  }
};

using ArrudaBoyce3D          = Compressible3D<ArrudaBoyce>;
using ArrudaBoycePlaneStress = PlaneStress<ArrudaBoyce>;
using ArrudaBoycePlaneStrain = PlaneStrain<ArrudaBoyce>;

} // namespace bapd
