#pragma once
// Compressible isotropic hyperelasticity from a law (law.hpp, METHOD.md section 4):
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
// Both formulations take laws of I1bar alone for now: a law with uses_I2bar
// (Mooney-Rivlin) adds the term H J^{-4/3} (I1 F - F C - (2/3) I2 F^{-T}) to P,
// H = 2 dPsi_iso/dI2bar, where the static_asserts below stand.
#include <cmath>

#include "bapd/hyperelastic_numerics.hpp"
#include "bapd/law.hpp"
#include "bapd/tensor.hpp"

namespace bapd {

// ---------------------------------------------------------------------------------
// 3D: the law as written in the paper (eqs 24, 26).
template <class Law> struct Compressible3D {
  static_assert(Law::variables == LawVariables::invariants && !Law::uses_I2bar,
                "Compressible3D: laws of I1bar only (see the top of hyperelastic.hpp)");
  ParametersOf<Law> p;

  StressStatus stress(const Mat3 &F, Mat3 &P) const
  {
    const double J = det(F);
    if (!(J > 0.0)) return fail(P, StressStatus::inverted);
    const double trC = frobenius_squared(F);
    const double q   = 1.0 / std::cbrt(J * J); // J^{-2/3}
    Modulus      G;
    if (!Law::modulus(p, Invariants{trC * q}, G)) return fail(P, StressStatus::chain_limit);
    const Mat3   Finv_t = inverse_transpose(F);
    const double a      = G[0] * q;
    const double b      = (J * J - 1.0) / p.D - a * trC / 3.0;
    for (int i = 0; i < 9; ++i) P[i] = a * F[i] + b * Finv_t[i];
    return StressStatus::ok;
  }

  StressStatus energy(const Mat3 &F, double &psi) const
  {
    const double J = det(F);
    if (!(J > 0.0)) return StressStatus::inverted;
    double psi_iso;
    if (!Law::energy(p, Invariants{frobenius_squared(F) / std::cbrt(J * J)}, psi_iso)) return StressStatus::chain_limit;
    psi = psi_iso + volumetric_energy_times_D(J) / p.D;
    return StressStatus::ok;
  }

private:
  static StressStatus fail(Mat3 &P, StressStatus s)
  {
    P = {};
    return s;
  }
};

// ---------------------------------------------------------------------------------
// Plane strain: F = diag(F~, 1), so J = J~ and tr C = tr C~ + 1. The in-plane block
// of the 3D P, written out in 2D (it equals Compressible3D at embed(F~, 1)).
template <class Law> struct PlaneStrain {
  static_assert(Law::variables == LawVariables::invariants && !Law::uses_I2bar,
                "PlaneStrain: laws of I1bar only (see the top of hyperelastic.hpp)");
  ParametersOf<Law> p;

  StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const
  {
    c33            = 1.0;
    const double J = det(F);
    if (!(J > 0.0)) {
      P = {};
      return StressStatus::inverted;
    }
    const double trC = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3] + 1.0;
    const double q   = 1.0 / std::cbrt(J * J);
    Modulus      G;
    if (!Law::modulus(p, Invariants{trC * q}, G)) {
      P = {};
      return StressStatus::chain_limit;
    }
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
    if (!Law::energy(p, Invariants{trC / std::cbrt(J * J)}, psi_iso)) return StressStatus::chain_limit;
    psi = psi_iso + volumetric_energy_times_D(J) / p.D;
    return StressStatus::ok;
  }
};

} // namespace bapd
