#pragma once
// The Ogden law (up to three terms), written in the principal stretches, with the
// volumetric term of paper eq 24:
//   Psi = sum_k (mu_k / alpha_k) (lb1^a_k + lb2^a_k + lb3^a_k - 3) + U(J),
//   lb_i = J^{-1/3} lambda_i (isochoric principal stretches), mu = sum_k mu_k a_k / 2.
// The principal Kirchhoff stresses are
//   tau_i = lambda_i dPsi/dlambda_i = sum_k mu_k (lb_i^a_k - (1/3) sum_j lb_j^a_k) + (J^2 - 1)/D,
// and S = sum_i (tau_i / c_i) N_i N_i^T (c_i, N_i: eigenpairs of C), P = F S. Where two
// c_i coincide (at rest, equibiaxial) so do the tau_i, so S does not depend on the
// (arbitrary) eigenvectors in that plane: no special case, and near-repeated c_i are
// smooth (the eigenvector error ~ eps / |c_1 - c_2| is multiplied by tau_1/c_1 - tau_2/c_2
// ~ |c_1 - c_2|).
//
// The law declares LawVariables::principal_stretches and brings its own formulations
// (PlaneStrainModel, PlaneStressModel; Model3D = Ogden3D for a 3D body): the invariant-based
// Compressible3D / PlaneStrain / PlaneStress do not apply. In plane stress tau_3 = 0 is
// solved for s = ln lambda_3: d tau_3 / ds = sum_k mu_k a_k ((4/9) lb_3^a_k +
// (1/9)(lb_1^a_k + lb_2^a_k)) + 2 J^2 / D > 0 when every mu_k a_k > 0 (checked), so the
// root is unique; safeguarded Newton (bracketed, bisection on a bad step), from the warm
// start or the incompressible lambda_3 = 1/J~. Scalar only (no lanes): every bond
// evaluation pays a 2x2 eigen-decomposition and an exp() per term and stretch.
// The law interface is described in law.hpp; the registry line is in law_list.hpp.
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "bapd/core/materials/hyperelastic_numerics.hpp"
#include "bapd/core/materials/law.hpp"
#include "bapd/core/materials/stress_status.hpp"
#include "bapd/core/kernel/tensor.hpp"

namespace bapd {

struct OgdenPlaneStrain;
struct OgdenPlaneStress;
struct Ogden3D;

struct Ogden {
  static constexpr const char *name = "ogden", *title = "Ogden (up to 3 terms): sum (mu_k/alpha_k)(sum lb_i^alpha_k - 3), mu = sum mu_k alpha_k / 2";
  static constexpr int         max_terms = 3;

  struct Parameters { // a term with mu_k = 0 is unused
    double ogden_mu1 = 4500.0, ogden_alpha1 = 2.0;     // [Pa], [-]
    double ogden_mu2 = 50.0 / 3.0, ogden_alpha2 = 6.0; // 4500 + 50 = the default mu 4.55e3
    double ogden_mu3 = 0.0, ogden_alpha3 = 0.0;
  };
  static constexpr std::array<LawOption<Parameters>, 6> options = {
      {{"-material_ogden_mu1", "Ogden mu_1 [Pa] (default 4500; sum mu_k alpha_k / 2 = mu)", &Parameters::ogden_mu1},
       {"-material_ogden_alpha1", "Ogden alpha_1 [-], mu_1 alpha_1 > 0 (default 2)", &Parameters::ogden_alpha1},
       {"-material_ogden_mu2", "Ogden mu_2 [Pa] (0: no second term; default 16.667)", &Parameters::ogden_mu2},
       {"-material_ogden_alpha2", "Ogden alpha_2 [-] (default 6)", &Parameters::ogden_alpha2},
       {"-material_ogden_mu3", "Ogden mu_3 [Pa] (0: no third term, the default)", &Parameters::ogden_mu3},
       {"-material_ogden_alpha3", "Ogden alpha_3 [-] (default 0)", &Parameters::ogden_alpha3}}};

  static std::array<double, max_terms> mu_of(const ParametersOf<Ogden> &p) { return {p.ogden_mu1, p.ogden_mu2, p.ogden_mu3}; }
  static std::array<double, max_terms> alpha_of(const ParametersOf<Ogden> &p)
  {
    return {p.ogden_alpha1, p.ogden_alpha2, p.ogden_alpha3};
  }

  // mu_k alpha_k > 0 for every term in use: the usual sufficient condition for
  // stability, and what makes the plane-stress tau_3 = 0 root unique.
  static std::string check(const ParametersOf<Ogden> &p)
  {
    std::ostringstream msg;
    const auto         mu = mu_of(p), alpha = alpha_of(p);
    double             sum = 0.0;
    bool               ok = true;
    for (int k = 0; k < max_terms; ++k) {
      const std::string n = std::to_string(k + 1);
      if (!std::isfinite(mu[k]) || !std::isfinite(alpha[k])) {
        msg << "-material_ogden_" << (std::isfinite(mu[k]) ? "alpha" : "mu") << n << " "
            << (std::isfinite(mu[k]) ? alpha[k] : mu[k]) << ": Ogden parameters must be finite numbers\n";
        ok = false;
      } else if (mu[k] != 0.0 && !(mu[k] * alpha[k] > 0.0)) {
        msg << "-material_ogden_alpha" << n << " " << alpha[k] << ": Ogden term " << n
            << " needs mu_k alpha_k > 0 (mu_k = " << mu[k] << " Pa; stability, and the plane-stress solve)\n";
        ok = false;
      } else sum += 0.5 * mu[k] * alpha[k];
    }
    if (ok && std::isfinite(p.mu) && !(std::abs(sum - p.mu) <= 1e-6 * p.mu))
      msg << "-material_ogden_mu1 " << p.ogden_mu1 << ": the Ogden shear modulus at rest sum mu_k alpha_k / 2 = " << sum
          << " Pa must equal -material_mu " << p.mu << "; give -material_mu " << sum << "\n";
    return msg.str();
  }

  static constexpr LawVariables variables         = LawVariables::principal_stretches;
  static constexpr bool         uses_I2bar        = false;
  static constexpr bool         convex_increasing = false; // (not a law of I1bar)
  static constexpr bool         has_limit         = false;
  using PlaneStrainModel                          = OgdenPlaneStrain;
  using PlaneStressModel                          = OgdenPlaneStress;
  using Model3D                                   = Ogden3D; // (a 3D body: with_model_3d)

  // Principal Kirchhoff stresses of the isochoric part from the logarithms of the
  // principal stretches (lb_i^a = exp(a (ln lambda_i - ln J / 3)): one exp per term and
  // stretch, no pow); slope33, if given: d tau_3 / d ln lambda_3 at fixed lambda_1, lambda_2.
  static void kirchhoff_iso(const ParametersOf<Ogden> &p, const double ln_l[3], double tau[3], double *slope33 = nullptr)
  {
    const auto   mu = mu_of(p), alpha = alpha_of(p);
    const double third_lnJ = (ln_l[0] + ln_l[1] + ln_l[2]) / 3.0;
    tau[0] = tau[1] = tau[2] = 0.0;
    if (slope33) *slope33 = 0.0;
    for (int k = 0; k < max_terms; ++k) {
      if (mu[k] == 0.0) continue;
      double A[3], mean = 0.0;
      for (int i = 0; i < 3; ++i) mean += (A[i] = std::exp(alpha[k] * (ln_l[i] - third_lnJ))) / 3.0;
      for (int i = 0; i < 3; ++i) tau[i] += mu[k] * (A[i] - mean);
      if (slope33) *slope33 += mu[k] * alpha[k] * ((4.0 / 9.0) * A[2] + (1.0 / 9.0) * (A[0] + A[1]));
    }
  }
  static double energy_iso(const ParametersOf<Ogden> &p, const double l[3], double J)
  {
    const auto mu = mu_of(p), alpha = alpha_of(p);
    double     psi = 0.0;
    for (int k = 0; k < max_terms; ++k) {
      if (mu[k] == 0.0) continue;
      // sum_i lb_i^a - 3 = sum_i expm1(a ln lb_i): no cancellation near rest
      const double lnJ3 = std::log(J) / 3.0;
      double       s    = 0.0;
      for (int i = 0; i < 3; ++i) s += std::expm1(alpha[k] * (std::log(l[i]) - lnJ3));
      psi += mu[k] / alpha[k] * s;
    }
    return psi;
  }
};

namespace ogden_detail {
// The eigenpairs of a symmetric 2x2 C: c[0] >= c[1], N[i] = (cos, sin) of eigenvector i.
inline void eigen2(const Mat2 &C, double c[2], double N[2][2])
{
  const double m = 0.5 * (C[0] + C[3]), r = std::hypot(0.5 * (C[0] - C[3]), C[1]);
  c[0]           = m + r;
  c[1]           = (C[0] * C[3] - C[1] * C[1]) / c[0]; // det / c0: no cancellation
  const double t = 0.5 * std::atan2(2.0 * C[1], C[0] - C[3]);
  N[0][0] = std::cos(t), N[0][1] = std::sin(t);
  N[1][0] = -N[0][1], N[1][1] = N[0][0];
}
// P~ = F~ S~, S~ = sum_i s_i N_i N_i^T.
inline Mat2 first_piola(const Mat2 &F, const double s[2], const double N[2][2])
{
  Mat2 S{};
  for (int i = 0; i < 2; ++i) {
    S[0] += s[i] * N[i][0] * N[i][0];
    S[1] += s[i] * N[i][0] * N[i][1];
    S[3] += s[i] * N[i][1] * N[i][1];
  }
  S[2] = S[1];
  return F * S;
}
} // namespace ogden_detail

// Plane strain: lambda_3 = 1.
struct OgdenPlaneStrain {
  ParametersOf<Ogden> p;

  StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const
  {
    c33            = 1.0;
    const double J = det(F);
    if (!(J > 0.0)) return stress_failed(P, StressStatus::inverted);
    double c[2], N[2][2], tau[3];
    ogden_detail::eigen2(right_cauchy_green(F), c, N);
    const double ln_l[3] = {0.5 * std::log(c[0]), 0.5 * std::log(c[1]), 0.0};
    Ogden::kirchhoff_iso(p, ln_l, tau);
    const double vol = (J * J - 1.0) / p.D, s[2] = {(tau[0] + vol) / c[0], (tau[1] + vol) / c[1]};
    P = ogden_detail::first_piola(F, s, N);
    return StressStatus::ok;
  }

  StressStatus energy(const Mat2 &F, double &c33, double &psi) const
  {
    c33            = 1.0;
    const double J = det(F);
    if (!(J > 0.0)) return StressStatus::inverted;
    double c[2], N[2][2];
    ogden_detail::eigen2(right_cauchy_green(F), c, N);
    const double l[3] = {std::sqrt(c[0]), std::sqrt(c[1]), 1.0};
    psi               = Ogden::energy_iso(p, l, J) + volumetric_energy_times_D(J) / p.D;
    return StressStatus::ok;
  }
};

// Plane stress: tau_3 = 0 solved for s = ln lambda_3 (see the top).
struct OgdenPlaneStress {
  ParametersOf<Ogden>  p;
  static constexpr int max_iterations = 100;

  // lambda_3 with tau_3 = 0 for in-plane stretches l1, l2 (J~ = l1 l2), warm start c33.
  // Newton on s = ln lambda_3 (tau_3 increases with s), steps limited to 0.5 until the
  // root is bracketed, bisection when a step leaves the bracket. A step below 1e-8
  // (quadratic convergence: what it leaves is ~1e-16) is taken as the last one, so a
  // warm start costs two evaluations.
  StressStatus solve(double l1, double l2, double c33_guess, double &lambda3) const
  {
    const double ln_l1 = std::log(l1), ln_l2 = std::log(l2), Jt = l1 * l2;
    double       s  = c33_guess > 0.0 ? 0.5 * std::log(c33_guess) : -(ln_l1 + ln_l2);
    double       lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    for (int it = 0; it < max_iterations; ++it) {
      const double ln_l[3] = {ln_l1, ln_l2, s}, J = Jt * std::exp(s);
      double       tau[3], slope;
      Ogden::kirchhoff_iso(p, ln_l, tau, &slope);
      const double g = tau[2] + (J * J - 1.0) / p.D;
      slope += 2.0 * J * J / p.D;
      if (!std::isfinite(g) || !(slope > 0.0)) return StressStatus::no_convergence;
      if (g == 0.0) break;
      (g < 0.0 ? lo : hi) = s;
      double step = -g / slope;
      if (!std::isfinite(lo) || !std::isfinite(hi)) step = std::max(-0.5, std::min(0.5, step));
      double next = s + step;
      // Outside the bracket: bisect. With one end still infinite that happens only when
      // the step is below the spacing of doubles (s + step == s, itself the end): s is
      // the root to round-off (a warm start at the root, a bond whose F did not change),
      // and bisecting towards the infinite end would leave it.
      if (!(next > lo && next < hi)) next = std::isfinite(lo) && std::isfinite(hi) ? 0.5 * (lo + hi) : s;
      const bool last = std::abs(next - s) <= 1e-8 * std::max(1.0, std::abs(s));
      s               = next;
      if (last) break;
      if (it + 1 == max_iterations) return StressStatus::no_convergence;
    }
    lambda3 = std::exp(s);
    return StressStatus::ok;
  }

  StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const
  {
    const double Jt = det(F);
    if (!(Jt > 0.0)) return stress_failed(P, StressStatus::inverted);
    double c[2], N[2][2], tau[3], lambda3 = 1.0;
    ogden_detail::eigen2(right_cauchy_green(F), c, N);
    const double l1 = std::sqrt(c[0]), l2 = std::sqrt(c[1]);
    const StressStatus st = solve(l1, l2, c33, lambda3);
    if (st != StressStatus::ok) {
      P = {};
      return st;
    }
    const double ln_l[3] = {0.5 * std::log(c[0]), 0.5 * std::log(c[1]), std::log(lambda3)}, J = Jt * lambda3;
    Ogden::kirchhoff_iso(p, ln_l, tau);
    const double vol = (J * J - 1.0) / p.D, s[2] = {(tau[0] + vol) / c[0], (tau[1] + vol) / c[1]};
    P   = ogden_detail::first_piola(F, s, N);
    c33 = lambda3 * lambda3;
    return StressStatus::ok;
  }

  StressStatus energy(const Mat2 &F, double &c33, double &psi) const
  {
    const double Jt = det(F);
    if (!(Jt > 0.0)) return StressStatus::inverted;
    double c[2], N[2][2], lambda3 = 1.0;
    ogden_detail::eigen2(right_cauchy_green(F), c, N);
    const double l1 = std::sqrt(c[0]), l2 = std::sqrt(c[1]);
    const StressStatus st = solve(l1, l2, c33, lambda3);
    if (st != StressStatus::ok) return st;
    const double l[3] = {l1, l2, lambda3}, J = Jt * lambda3;
    psi = Ogden::energy_iso(p, l, J) + volumetric_energy_times_D(J) / p.D;
    c33 = lambda3 * lambda3;
    return StressStatus::ok;
  }
};

// 3D (tests): C's eigenpairs by cyclic Jacobi rotations.
struct Ogden3D {
  ParametersOf<Ogden> p;

  // C = V diag(c) V^T, V's columns the eigenvectors (Golub & Van Loan, section 8.5).
  static void eigen3(const Mat3 &C_in, double c[3], Mat3 &V)
  {
    Mat3 A = C_in;
    V      = identity3();
    for (int sweep = 0; sweep < 50; ++sweep) {
      const double off = A[1] * A[1] + A[2] * A[2] + A[5] * A[5];
      if (!(off > 1e-36 * (A[0] * A[0] + A[4] * A[4] + A[8] * A[8]))) break;
      for (int pq = 0; pq < 3; ++pq) {
        const int a = pq == 2 ? 1 : 0, b = pq == 0 ? 1 : 2;
        const double apq = A[3 * a + b];
        if (apq == 0.0) continue;
        const double theta = (A[3 * b + b] - A[3 * a + a]) / (2.0 * apq);
        const double t     = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double cs = 1.0 / std::sqrt(t * t + 1.0), sn = t * cs;
        for (int k = 0; k < 3; ++k) { // A <- A J (columns a, b)
          const double x = A[3 * k + a], y = A[3 * k + b];
          A[3 * k + a] = cs * x - sn * y, A[3 * k + b] = sn * x + cs * y;
        }
        for (int k = 0; k < 3; ++k) { // A <- J^T A (rows a, b)
          const double x = A[3 * a + k], y = A[3 * b + k];
          A[3 * a + k] = cs * x - sn * y, A[3 * b + k] = sn * x + cs * y;
        }
        for (int k = 0; k < 3; ++k) {
          const double x = V[3 * k + a], y = V[3 * k + b];
          V[3 * k + a] = cs * x - sn * y, V[3 * k + b] = sn * x + cs * y;
        }
      }
    }
    for (int i = 0; i < 3; ++i) c[i] = A[4 * i];
  }

  static Mat3 right_cauchy_green3(const Mat3 &F)
  {
    Mat3 C{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) C[3 * i + j] += F[3 * k + i] * F[3 * k + j];
    return C;
  }

  StressStatus stress(const Mat3 &F, Mat3 &P) const
  {
    const double J = det(F);
    if (!(J > 0.0)) return stress_failed(P, StressStatus::inverted);
    double c[3], tau[3];
    Mat3   V;
    eigen3(right_cauchy_green3(F), c, V);
    const double ln_l[3] = {0.5 * std::log(c[0]), 0.5 * std::log(c[1]), 0.5 * std::log(c[2])};
    Ogden::kirchhoff_iso(p, ln_l, tau);
    const double vol = (J * J - 1.0) / p.D;
    Mat3         S{};
    for (int n = 0; n < 3; ++n)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) S[3 * i + j] += (tau[n] + vol) / c[n] * V[3 * i + n] * V[3 * j + n];
    P = {};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) P[3 * i + j] += F[3 * i + k] * S[3 * k + j];
    return StressStatus::ok;
  }

  StressStatus energy(const Mat3 &F, double &psi) const
  {
    const double J = det(F);
    if (!(J > 0.0)) return StressStatus::inverted;
    double c[3];
    Mat3   V;
    eigen3(right_cauchy_green3(F), c, V);
    const double l[3] = {std::sqrt(c[0]), std::sqrt(c[1]), std::sqrt(c[2])};
    psi               = Ogden::energy_iso(p, l, J) + volumetric_energy_times_D(J) / p.D;
    return StressStatus::ok;
  }
};

} // namespace bapd
