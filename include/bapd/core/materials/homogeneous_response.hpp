#pragma once
// The analytic nominal stress of an incompressible hyperelastic sheet in the three
// homogeneous tests a gel is calibrated with (Treloar; Ogden, Non-linear elastic
// deformations, section 7.2), for bapd-fit (src/fit/) and for the tests that check the
// compressible laws against them at a large bulk modulus (tests/unit/materials/).
//
// Principal stretches (lambda_3 = 1 / (lambda_1 lambda_2), the load along 1, the
// faces normal to 2 (uniaxial, equibiaxial: 2 also loaded) and 3 stress-free):
//   uniaxial     (lambda, lambda^{-1/2}, lambda^{-1/2}):
//                 I1 = lambda^2 + 2/lambda,        I2 = 2 lambda + lambda^{-2}
//                 P  = 2 (lambda - lambda^{-2}) (W1 + W2 / lambda)
//   pure shear   (lambda, 1, 1/lambda):   I1 = I2 = lambda^2 + 1 + lambda^{-2}
//                 P  = 2 (lambda - lambda^{-3}) (W1 + W2)
//   equibiaxial  (lambda, lambda, lambda^{-2}):
//                 I1 = 2 lambda^2 + lambda^{-4},   I2 = lambda^4 + 2 lambda^{-2}
//                 P  = 2 (lambda - lambda^{-5}) (W1 + lambda^2 W2)
// with W1 = dW/dI1 = G/2, W2 = dW/dI2 = H/2 (law.hpp; incompressible: I1bar = I1).
// Gent in pure shear is then paper eq 36: P = mu Jm (lambda - lambda^{-3}) /
// (Jm - lambda^2 - lambda^{-2} + 2). For Ogden, W = sum_k (mu_k / alpha_k)
// (lambda_1^a_k + lambda_2^a_k + lambda_3^a_k - 3), and P = dW/dlambda along the path:
//   uniaxial     P = sum_k mu_k (lambda^{a_k - 1} - lambda^{-a_k/2 - 1})
//   pure shear   P = sum_k mu_k (lambda^{a_k - 1} - lambda^{-a_k - 1})
//   equibiaxial  P = sum_k mu_k (lambda^{a_k - 1} - lambda^{-2 a_k - 1})
// (shear modulus at rest: mu = sum_k mu_k alpha_k / 2).
#include <cmath>
#include <cstddef>

#include "bapd/core/enum_words.hpp"
#include "bapd/core/materials/law.hpp"

namespace bapd {

enum class LoadMode { uniaxial, pure_shear, equibiaxial };
inline constexpr EnumWords<LoadMode::equibiaxial> load_mode_words{"uniaxial", "pure_shear", "equibiaxial"};

inline const char *to_string(LoadMode m) { return load_mode_words(m); }

// The principal stretches of the incompressible test at stretch lambda.
inline void principal_stretches(LoadMode m, double lambda, double s[3])
{
  s[0] = lambda;
  switch (m) {
  case LoadMode::uniaxial: s[1] = s[2] = 1.0 / std::sqrt(lambda); return;
  case LoadMode::pure_shear: s[1] = 1.0, s[2] = 1.0 / lambda; return;
  case LoadMode::equibiaxial: s[1] = lambda, s[2] = 1.0 / (lambda * lambda); return;
  }
}

inline Invariants incompressible_invariants(LoadMode m, double lambda)
{
  double s[3] = {1.0, 1.0, 1.0};
  principal_stretches(m, lambda, s);
  const double c0 = s[0] * s[0], c1 = s[1] * s[1], c2 = s[2] * s[2];
  return {c0 + c1 + c2, c0 * c1 + c1 * c2 + c2 * c0};
}

// P from W1 = dW/dI1 and W2 = dW/dI2 at the mode's invariants (see the top).
inline double nominal_stress_from_W(LoadMode m, double lambda, double W1, double W2)
{
  const double l = lambda;
  switch (m) {
  case LoadMode::uniaxial: return 2.0 * (l - 1.0 / (l * l)) * (W1 + W2 / l);
  case LoadMode::pure_shear: return 2.0 * (l - 1.0 / (l * l * l)) * (W1 + W2);
  case LoadMode::equibiaxial: return 2.0 * (l - 1.0 / (l * l * l * l * l)) * (W1 + l * l * W2);
  }
  return 0.0;
}

// The incompressible response of a registered law of invariants (p: its parameters
// with mu; D unused). False where the law is locked (beyond its limit).
template <class Law> bool incompressible_nominal_stress(const ParametersOf<Law> &p, LoadMode m, double lambda, double &P)
{
  static_assert(Law::variables == LawVariables::invariants, "incompressible_nominal_stress: a law of invariants");
  const Invariants inv = incompressible_invariants(m, lambda);
  Modulus          G;
  if (!Law::modulus(p, inv, G)) return false;
  double W2 = 0.0;
  if constexpr (Law::uses_I2bar) {
    Modulus H;
    Law::modulus_I2bar(p, inv, H);
    W2 = 0.5 * H[0];
  }
  P = nominal_stress_from_W(m, lambda, 0.5 * G[0], W2);
  return true;
}

// Ogden with n terms (mu[k], alpha[k]).
inline double ogden_nominal_stress(const double *mu, const double *alpha, std::size_t n, LoadMode m, double lambda)
{
  double P = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double a = alpha[k];
    double       back = 0.0; // the exponent of the second term
    switch (m) {
    case LoadMode::uniaxial: back = -0.5 * a - 1.0; break;
    case LoadMode::pure_shear: back = -a - 1.0; break;
    case LoadMode::equibiaxial: back = -2.0 * a - 1.0; break;
    }
    P += mu[k] * (std::pow(lambda, a - 1.0) - std::pow(lambda, back));
  }
  return P;
}

// Paper eq 36: the Gent sheet in pure shear.
inline double gent_pure_shear_eq36(double mu, double Jm, double lambda)
{
  const double l2 = lambda * lambda;
  return mu * Jm * (lambda - 1.0 / (l2 * lambda)) / (Jm - l2 - 1.0 / l2 + 2.0);
}

} // namespace bapd
