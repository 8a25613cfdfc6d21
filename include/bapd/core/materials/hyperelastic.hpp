#pragma once
// Compressible isotropic hyperelasticity from a law (law.hpp, docs/method.md section 4):
//
//   Psi(F) = Psi_iso(I1bar) + U(J),   I1bar = tr(C) J^{-2/3},  C = F^T F,  J = det F
//   U(J)   = (1/D) ((J^2 - 1)/2 - ln J)                         (paper eq 24)
//   P      = G J^{-2/3} (F - tr(C)/3 F^{-T}) + (1/D)(J^2 - 1) F^{-T}   (paper eq 26)
//
// with G = 2 dPsi_iso/dI1bar. This file turns a law into Compressible3D (3x3 F) and
// PlaneStrain (F33 = 1); plane_stress.hpp has PlaneStress (S33 = 0, C33 solved per
// call), numerical_tangent.hpp the tangent by differences. All of them are inline,
// allocate nothing and call nothing virtual: they run per bond per step. D must be
// > 0 (check_parameters, material.hpp).
//
// A law with uses_I2bar (Mooney-Rivlin) adds to P the term of Psi_iso's I2bar
// dependence, d I2bar/dF = 2 J^{-4/3} (I1 F - F C - (2/3) I2 F^{-T}):
//   P += H J^{-4/3} (I1 F - F C - (2/3) I2 F^{-T}),  H = 2 dPsi_iso/dI2bar,
// I1 = tr C, I2 = ((tr C)^2 - tr(C^2))/2. It is under `if constexpr`: laws of I1bar
// alone compile to exactly the code they had.
#include <cmath>

#include "bapd/core/materials/hyperelastic_numerics.hpp"
#include "bapd/core/materials/law.hpp"
#include "bapd/core/materials/stress_status.hpp"
#include "bapd/core/kernel/tensor.hpp"

namespace bapd {

// ---------------------------------------------------------------------------------
// 3D: the law as written in the paper (eqs 24, 26).
template <class Law> struct Compressible3D {
  static_assert(Law::variables == LawVariables::invariants,
                "Compressible3D: laws of invariants only (see the top of hyperelastic.hpp)");
  ParametersOf<Law> p;

  StressStatus stress(const Mat3 &F, Mat3 &P) const
  {
    const double J = det(F);
    if (!(J > 0.0)) return stress_failed(P, StressStatus::inverted);
    const double trC = frobenius_squared(F);
    const double q   = 1.0 / std::cbrt(J * J); // J^{-2/3}
    Modulus      G;
    if constexpr (Law::uses_I2bar) {
      Mat3 FC{}; // F C = F F^T F
      const double I2 = invariant_I2(F, FC);
      const Invariants inv{trC * q, I2 * q * q};
      if (!Law::modulus(p, inv, G)) return stress_failed(P, StressStatus::chain_limit);
      const Mat3   Finv_t = inverse_transpose(F);
      Modulus      H;
      Law::modulus_I2bar(p, inv, H);
      const double h = H[0] * q * q; // H J^{-4/3}
      const double a = G[0] * q + h * trC;
      const double b = (J * J - 1.0) / p.D - G[0] * q * trC / 3.0 - h * (2.0 / 3.0) * I2;
      for (int i = 0; i < 9; ++i) P[i] = a * F[i] - h * FC[i] + b * Finv_t[i];
      return StressStatus::ok;
    } else {
      if (!Law::modulus(p, Invariants{trC * q}, G)) return stress_failed(P, StressStatus::chain_limit);
      const Mat3   Finv_t = inverse_transpose(F);
      const double a      = G[0] * q;
      const double b      = (J * J - 1.0) / p.D - a * trC / 3.0;
      for (int i = 0; i < 9; ++i) P[i] = a * F[i] + b * Finv_t[i];
      return StressStatus::ok;
    }
  }

  StressStatus energy(const Mat3 &F, double &psi) const
  {
    const double J = det(F);
    if (!(J > 0.0)) return StressStatus::inverted;
    double     psi_iso;
    Invariants inv{frobenius_squared(F) / std::cbrt(J * J)};
    if constexpr (Law::uses_I2bar) {
      Mat3         FC{};
      const double q = 1.0 / std::cbrt(J * J);
      inv.I2bar      = invariant_I2(F, FC) * q * q;
    }
    if (!Law::energy(p, inv, psi_iso)) return StressStatus::chain_limit;
    psi = psi_iso + volumetric_energy_times_D(J) / p.D;
    return StressStatus::ok;
  }

private:
  // I2 = ((tr C)^2 - tr(C^2))/2 and F C, for laws of I2bar.
  static double invariant_I2(const Mat3 &F, Mat3 &FC)
  {
    Mat3 C{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) C[3 * i + j] += F[3 * k + i] * F[3 * k + j];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double v = 0.0;
        for (int k = 0; k < 3; ++k) v += F[3 * i + k] * C[3 * k + j];
        FC[3 * i + j] = v;
      }
    double trC = 0.0, trC2 = 0.0;
    for (int i = 0; i < 3; ++i) trC += C[4 * i];
    for (int i = 0; i < 9; ++i) trC2 += C[i] * C[i];
    return 0.5 * (trC * trC - trC2);
  }
};

// ---------------------------------------------------------------------------------
// Plane strain: F = diag(F~, 1), so J = J~ and tr C = tr C~ + 1. The in-plane block
// of the 3D P, written out in 2D (it equals Compressible3D at embed(F~, 1)).
template <class Law> struct PlaneStrain {
  static_assert(Law::variables == LawVariables::invariants,
                "PlaneStrain: laws of invariants only (see the top of hyperelastic.hpp)");
  ParametersOf<Law> p;

  StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const
  {
    c33            = 1.0;
    const double J = det(F);
    if (!(J > 0.0)) return stress_failed(P, StressStatus::inverted);
    const double trC = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3] + 1.0;
    const double q   = 1.0 / std::cbrt(J * J);
    Modulus      G;
    if constexpr (Law::uses_I2bar) {
      // C = diag(C~, 1): I2 = det C~ + tr C~ = J^2 + tr C - 1; F C = diag(F~ C~, 1)
      const double     I2 = J * J + trC - 1.0;
      const Invariants inv{trC * q, I2 * q * q};
      if (!Law::modulus(p, inv, G)) return stress_failed(P, StressStatus::chain_limit);
      const Mat2   FC = F * right_cauchy_green(F);
      Modulus      H;
      Law::modulus_I2bar(p, inv, H);
      const double h  = H[0] * q * q; // H J^{-4/3}
      const double a  = G[0] * q + h * trC;
      const double b  = ((J * J - 1.0) / p.D - G[0] * q * trC / 3.0 - h * (2.0 / 3.0) * I2) / J;
      P = {a * F[0] - h * FC[0] + b * F[3], a * F[1] - h * FC[1] - b * F[2], a * F[2] - h * FC[2] - b * F[1],
           a * F[3] - h * FC[3] + b * F[0]};
      return StressStatus::ok;
    }
    if (!Law::modulus(p, Invariants{trC * q}, G)) return stress_failed(P, StressStatus::chain_limit);
    const double a = G[0] * q;
    const double b = ((J * J - 1.0) / p.D - a * trC / 3.0) / J; // F^{-T} = cof(F)/J
    P              = {a * F[0] + b * F[3], a * F[1] - b * F[2], a * F[2] - b * F[1], a * F[3] + b * F[0]};
    return StressStatus::ok;
  }

  StressStatus energy(const Mat2 &F, double &c33, double &psi) const
  {
    c33            = 1.0;
    const double J = det(F);
    if (!(J > 0.0)) return StressStatus::inverted;
    const double trC = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3] + 1.0;
    double       psi_iso;
    Invariants   inv{trC / std::cbrt(J * J)};
    if constexpr (Law::uses_I2bar) inv.I2bar = (J * J + trC - 1.0) / std::cbrt(J * J * J * J);
    if (!Law::energy(p, inv, psi_iso)) return StressStatus::chain_limit;
    psi = psi_iso + volumetric_energy_times_D(J) / p.D;
    return StressStatus::ok;
  }
};

} // namespace bapd
