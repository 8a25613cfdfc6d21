#pragma once
// Shared helpers for the constitutive-model tests: reproducible random deformation
// gradients and finite-difference derivatives of an energy.
#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include "bapd/core/materials/material.hpp"
#include "bapd/core/materials/plane_stress.hpp"
#include "bapd/core/kernel/tensor.hpp"

namespace bapd::test {

// Uniform in [lo, hi) from the raw 32-bit engine output, so that the sequence does not
// depend on the standard library's distribution code.
inline double uniform(std::mt19937 &rng, double lo, double hi)
{
  return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967296.0);
}
// The paper's hydrogel parameters, or others, in the order the tests think of them.
inline MaterialParameters parameters(double mu, double Jm, double D)
{
  MaterialParameters p;
  p.mu = mu;
  p["-material_Jm"] = Jm;
  p.D  = D;
  return p;
}

// Stretch between 1/max and max, log-uniform, so compression and tension are equally likely.
inline double stretch(std::mt19937 &rng, double max) { return std::exp(uniform(rng, -std::log(max), std::log(max))); }

// The law of a plane-stress model (typed tests run over models, some checks need the law).
template <class Model> struct LawOf;
template <class Law> struct LawOf<PlaneStress<Law>> {
  using type = Law;
};

// The terms of C33 S33 that cancel at the plane-stress solution (plane_stress.hpp:
// Gbar t, Hbar t2 for a law of I2bar, (ck - 1)/D), over C33, + mu: the scale against
// which the round-off in S33 is measured.
template <class Law> double out_of_plane_stress_scale(const MaterialParameters &p, const Mat2 &F, double c)
{
  const double a = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3], k = det(F) * det(F);
  const double q = 1.0 / std::cbrt(c * k);
  Modulus      G{};
  Law::modulus(ParametersOf<Law>(p), Invariants{(a + c) * q}, G);
  double scale = std::abs(G[0] * q * (2.0 * c - a) / 3.0) / c + std::abs((c * k - 1.0) / p.D) / c + p.mu;
  if constexpr (Law::uses_I2bar) {
    Modulus H{};
    Law::modulus_I2bar(ParametersOf<Law>(p), Invariants{(a + c) * q, (k + a * c) * q * q}, H);
    scale += std::abs(H[0] * q * q * (a * c - 2.0 * k) / 3.0) / c;
  }
  return scale;
}

inline Mat2 rotation2(double theta) { return {std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta)}; }

// R(theta1) diag(s1, s2) R(theta2): principal stretches s1, s2 in [1/max, max].
inline Mat2 random_F2(std::mt19937 &rng, double max)
{
  const double s1 = stretch(rng, max), s2 = stretch(rng, max);
  const Mat2   D  = {s1, 0.0, 0.0, s2};
  return rotation2(uniform(rng, 0, 6.283185307179586)) * D * rotation2(uniform(rng, 0, 6.283185307179586));
}

inline Mat3 mul(const Mat3 &A, const Mat3 &B)
{
  Mat3 C{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) C[3 * i + j] += A[3 * i + k] * B[3 * k + j];
  return C;
}
// A rotation from a random unit quaternion.
inline Mat3 random_rotation3(std::mt19937 &rng)
{
  double q[4], n = 0.0;
  do {
    n = 0.0;
    for (double &v : q) {
      v = uniform(rng, -1, 1);
      n += v * v;
    }
  } while (n > 1.0 || n < 1e-4);
  n = std::sqrt(n);
  const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  return {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
          2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
          2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
}
inline Mat3 random_F3(std::mt19937 &rng, double max)
{
  const Mat3 D = {stretch(rng, max), 0, 0, 0, stretch(rng, max), 0, 0, 0, stretch(rng, max)};
  return mul(mul(random_rotation3(rng), D), random_rotation3(rng));
}

// Frobenius norm of A - B over max(|B|, floor).
template <std::size_t N>
double relative_difference(const std::array<double, N> &A, const std::array<double, N> &B, double floor)
{
  double d = 0.0, b = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    d += (A[i] - B[i]) * (A[i] - B[i]);
    b += B[i] * B[i];
  }
  return std::sqrt(d) / std::max(std::sqrt(b), floor);
}

// Central difference of energy(F) -> double in every component of F, step
// h = rel_step * max|F|.
template <std::size_t N, class Energy>
std::array<double, N> energy_gradient(const std::array<double, N> &F, Energy &&energy, double rel_step)
{
  double scale = 0.0;
  for (double v : F) scale = std::max(scale, std::abs(v));
  std::array<double, N> g{};
  for (std::size_t i = 0; i < N; ++i) {
    auto Fp = F, Fm = F;
    Fp[i] += rel_step * scale;
    Fm[i] -= rel_step * scale;
    g[i] = (energy(Fp) - energy(Fm)) / (Fp[i] - Fm[i]);
  }
  return g;
}

} // namespace bapd::test
