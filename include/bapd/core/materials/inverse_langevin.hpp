#pragma once
// The Langevin function L(b) = coth b - 1/b, its Taylor coefficients, and its inverse
// b = L^{-1}(x) on [0, 1), for the eight-chain law (arruda_boyce.hpp). Scalar, inline,
// allocation-free.
//
// L near 0: coth b - 1/b cancels (to O(b)), so for b < 1 it is summed as its series
//   L(b) = sum_{n>=1} 4^n B_2n b^{2n-1} / (2n)!          (B_2n: Bernoulli numbers)
// whose terms fall by ~(b/pi)^2 = 0.1 per term at b = 1: 18 terms leave < 1e-17.
// Beyond, coth b - 1/b loses less than a bit (at b = 1: 1.313 - 1). The Taylor
// coefficients there lose more (the fourth about two digits at b = 1, from 24/b^5
// minus the fourth derivative of coth); they only bound the plane-stress step.
//
// L^{-1}: Jedynak's rational approximation (Rheol. Acta 54, 2015; relative error
// < 1.5 % on [0, 1)) x (3 - 2.6 x + 0.7 x^2) / ((1 - x)(1 + 0.1 x)), refined by Newton
// steps on L(b) = x. L is increasing and concave on b > 0, so from below Newton climbs
// monotonically to the root and from above its first step lands below it; it stops
// when the step is below 2 eps b (quadratic convergence: about four steps from 1.5 %).
// tests/unit/materials/hyperelastic_laws_test.cpp (InverseLangevin) checks L(L^{-1}(x)) = x
// over [1e-8, 1 - 1e-9].
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

namespace bapd {

namespace langevin_detail {
// a_n = 4^n B_2n / (2n)! = (-1)^{n+1} 2 zeta(2n) / pi^{2n}, n = 1..18: exact rationals
// for n <= 6; beyond, zeta(2n) = sum_{k<=12} k^{-2n} (the rest is below 13^{-14} = 1e-16).
inline constexpr int terms = 18;
constexpr std::array<double, terms> make_series()
{
  constexpr double          pi = 3.14159265358979323846;
  std::array<double, terms> a{};
  a[0] = 1.0 / 3.0, a[1] = -1.0 / 45.0, a[2] = 2.0 / 945.0;
  a[3] = -1.0 / 4725.0, a[4] = 2.0 / 93555.0, a[5] = -1382.0 / 638512875.0;
  double pi2n = 1.0;
  for (int n = 1; n <= terms; ++n) {
    pi2n *= pi * pi;
    if (n <= 6) continue;
    double zeta = 0.0;
    for (int k = 1; k <= 12; ++k) {
      double t = 1.0;
      for (int j = 0; j < 2 * n; ++j) t /= k;
      zeta += t;
    }
    a[n - 1] = (n % 2 ? 2.0 : -2.0) * zeta / pi2n;
  }
  return a;
}
inline constexpr std::array<double, terms> series = make_series();
inline constexpr double                    series_limit = 1.0;
} // namespace langevin_detail

// l[n] = L^(n)(b) / n!, n = 0..4 (the Taylor coefficients of L at b), b > 0.
inline std::array<double, 5> langevin_taylor(double b)
{
  std::array<double, 5> l{};
  if (b < langevin_detail::series_limit) {
    // d^m/db^m of b^p / m! = binom(p, m) b^{p-m}, term by term (powers by products)
    std::array<double, 2 * langevin_detail::terms> power{};
    power[0] = 1.0;
    for (std::size_t q = 1; q < power.size(); ++q) power[q] = power[q - 1] * b;
    for (int n = 1; n <= langevin_detail::terms; ++n) {
      const int p = 2 * n - 1;
      double    binom = 1.0;
      for (int m = 0; m <= 4 && m <= p; ++m) {
        l[m] += langevin_detail::series[n - 1] * binom * power[p - m];
        binom = binom * (p - m) / (m + 1);
      }
    }
    return l;
  }
  // coth derivatives as polynomials in c = coth b, s = 1 - c^2 (= -1/sinh^2 b):
  // c' = s, c'' = -2cs, c''' = 4c^2 s - 2s^2, c'''' = 16 c s^2 - 8 c^3 s;
  // (1/b)^(n) = (-1)^n n! / b^{n+1}
  const double c = 1.0 / std::tanh(b), s = 1.0 - c * c, r = 1.0 / b;
  l[0] = c - r;
  l[1] = s + r * r;
  l[2] = (-2.0 * c * s - 2.0 * r * r * r) / 2.0;
  l[3] = (4.0 * c * c * s - 2.0 * s * s + 6.0 * r * r * r * r) / 6.0;
  l[4] = (16.0 * c * s * s - 8.0 * c * c * c * s - 24.0 * r * r * r * r * r) / 24.0;
  return l;
}

inline double langevin(double b)
{
  if (b < langevin_detail::series_limit) {
    const double b2 = b * b;
    double       sum = 0.0;
    for (int n = langevin_detail::terms - 1; n >= 0; --n) sum = sum * b2 + langevin_detail::series[n];
    return sum * b;
  }
  return 1.0 / std::tanh(b) - 1.0 / b;
}

// L'(b), without the cancellation of 1/b^2 - 1/sinh^2 b near 0.
inline double langevin_derivative(double b)
{
  if (b < langevin_detail::series_limit) {
    const double b2 = b * b;
    double       sum = 0.0;
    for (int n = langevin_detail::terms - 1; n >= 0; --n) sum = sum * b2 + (2 * n + 1) * langevin_detail::series[n];
    return sum;
  }
  const double sh = std::sinh(b);
  return 1.0 / (b * b) - 1.0 / (sh * sh);
}

// Jedynak's rational approximation of L^{-1} (relative error < 1.5 %).
inline double inverse_langevin_rational(double x)
{
  return x * (3.0 - 2.6 * x + 0.7 * x * x) / ((1.0 - x) * (1.0 + 0.1 * x));
}

// b = L^{-1}(x), 0 <= x < 1; NaN outside.
inline double inverse_langevin(double x)
{
  if (!(x >= 0.0 && x < 1.0)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0.0) return 0.0;
  double b = inverse_langevin_rational(x);
  for (int it = 0; it < 20; ++it) {
    const double step = (x - langevin(b)) / langevin_derivative(b);
    double       next = b + step;
    if (!(next > 0.0)) next = 0.5 * b; // (never from the rational start; a guard)
    const bool done = std::abs(next - b) <= 2.0 * std::numeric_limits<double>::epsilon() * b;
    b               = next;
    if (done) break;
  }
  return b;
}

} // namespace bapd
