#pragma once
// Tangent by central differences of the stress, for checks, time-step estimates and
// anything outside the hot loop (no analytic tangent is provided).
#include <algorithm>
#include <array>
#include <cmath>

#include "bapd/core/materials/hyperelastic.hpp"
#include "bapd/core/kernel/tensor.hpp"

namespace bapd {

// A[4 (2i + j) + (2k + l)] = dP_ij / dF_kl (2D); A[9 (3i + j) + (3k + l)] (3D).
// Step h = rel_step * max(1, max |F_kl|). Error: O(h^2) truncation plus the stress
// noise over h; the plane-stress solve leaves about 1e-12 relative noise in P, so the
// default 1e-4 gives about 1e-8 relative. Plane-stress c33 is a warm start only.
using Tangent2 = std::array<double, 16>;
using Tangent3 = std::array<double, 81>;

template <class Model>
StressStatus numerical_tangent(const Model &model, const Mat2 &F, double c33, Tangent2 &A, double rel_step = 1e-4)
{
  double scale = 1.0;
  for (double v : F) scale = std::max(scale, std::abs(v));
  const double h = rel_step * scale;
  for (int kl = 0; kl < 4; ++kl) {
    Mat2   Fp = F, Fm = F, Pp, Pm;
    double cp = c33, cm = c33;
    Fp[kl] += h;
    Fm[kl] -= h;
    StressStatus s = model.stress(Fp, cp, Pp);
    if (s != StressStatus::ok) return s;
    if ((s = model.stress(Fm, cm, Pm)) != StressStatus::ok) return s;
    for (int ij = 0; ij < 4; ++ij) A[4 * ij + kl] = (Pp[ij] - Pm[ij]) / (Fp[kl] - Fm[kl]);
  }
  return StressStatus::ok;
}

template <class Law>
StressStatus numerical_tangent(const Compressible3D<Law> &model, const Mat3 &F, Tangent3 &A, double rel_step = 1e-4)
{
  double scale = 1.0;
  for (double v : F) scale = std::max(scale, std::abs(v));
  const double h = rel_step * scale;
  for (int kl = 0; kl < 9; ++kl) {
    Mat3 Fp = F, Fm = F, Pp, Pm;
    Fp[kl] += h;
    Fm[kl] -= h;
    StressStatus s = model.stress(Fp, Pp);
    if (s != StressStatus::ok) return s;
    if ((s = model.stress(Fm, Pm)) != StressStatus::ok) return s;
    for (int ij = 0; ij < 9; ++ij) A[9 * ij + kl] = (Pp[ij] - Pm[ij]) / (Fp[kl] - Fm[kl]);
  }
  return StressStatus::ok;
}

} // namespace bapd
