#pragma once
// Exactly incompressible plane stress of a law of invariants (docs/method.md section 4,
// "Incompressible plane stress"): -material_formulation plane_stress_incompressible.
//
// With J = 1 the out-of-plane stretch follows from F~ alone: C33 = 1/det C~ = 1/J~^2.
// With a = tr C~, k = J~^2 and c = 1/k, the invariants are I1 = a + c and
// I2 = k + a c (I1bar = I1, I2bar = I2 since J = 1), and the reduced energy
// W(F~) = Psi_iso(I1, I2) (U(J) = 0: D does not enter). Its derivative, with
// dc/dF~ = -2 c F~^{-T}, da/dF~ = 2 F~ and dk/dF~ = 2 k F~^{-T}, is
//
//   P~ = dW/dF~ = (G + c H) F~ - (c G + (a c - k) H) F~^{-T},
//   G = 2 dPsi_iso/dI1, H = 2 dPsi_iso/dI2 (0 for a law of I1 alone),
//
// which is the 3D incompressible P = G F + H (I1 F - F C) - p F^{-T} restricted to the
// plane, with the pressure p = c (G + H (I1 - c)) that makes P33 = 0 (the 2x2
// Cayley-Hamilton F~ C~ = a F~ - k F~^{-T} turns one into the other). It is
// PlaneStress's P~ (plane_stress.hpp) at Gbar = G, Hbar = H and C33 = 1/J~^2, the
// limit D -> 0 of its solve, reached without one: no Newton iteration, no cube root.
// Being the derivative of W(F~), it keeps the energy-consistent force exactly -dW/dy.
//
// Any law of invariants runs in it (no convexity is needed: nothing is solved). A law
// with a limit is locked once I1 >= I1bar_limit: chain_limit, as in the other forms.
#include <array>
#include <cmath>

#include "bapd/core/kernel/lanes.hpp"
#include "bapd/core/kernel/tensor.hpp"
#include "bapd/core/materials/law.hpp"

namespace bapd {

template <class Law> struct PlaneStressIncompressible {
  static_assert(Law::variables == LawVariables::invariants,
                "PlaneStressIncompressible: laws of invariants only (a law of principal stretches is refused by "
                "formulation_refusal, law.hpp)");
  ParametersOf<Law> p;
  // stress_lanes() exists: the bond kernel hands this model lane_count bonds at a time.
  static constexpr bool has_lanes = true;

  // c33 is written (1/J~^2) when the status is ok; its value on entry is not read.
  StressStatus stress(const Mat2 &F, double &c33, Mat2 &P) const
  {
    if (!(det(F) > 0.0)) return stress_failed(P, StressStatus::inverted);
    double c = 0.0;
    if (!evaluate(F, c, P)) return stress_failed(P, StressStatus::chain_limit);
    c33 = c;
    return StressStatus::ok;
  }

  // lane_count bonds at once (T = Lanes), or half as many (HalfLanes): the arithmetic
  // of stress(), so a lane's P and c33 are bit for bit stress()'s. The lanes it does
  // not finish (det F~ <= 0, a locked law) must go through stress() for their status;
  // their arithmetic is kept finite.
  template <class T> MaskOf<T> stress_lanes(const std::array<T, 4> &F, T &c33, std::array<T, 4> &P) const
  {
    T          c    = T{};
    const auto done = (F[0] * F[3] - F[1] * F[2] > 0.0) & evaluate(F, c, P);
    c33             = select(done, c, c33);
    return done;
  }

  // The exact tangent A[4 (2i + j) + (2k + l)] = dP~_ij / dF~_kl of a law of I1 alone
  // (has_tangent; the static solver's Hessian, ba_tangent.hpp). With N = F~^{-T} and
  // M = F~ - c N = dI1/dF~ / 2, P~ = G M, and dG = 2 G' M : dF~, dc = -2 c N : dF~,
  // dN_ij = -N_il N_kj dF~_kl:
  //   A_ijkl = G d_ik d_jl + 2 G' M_ij M_kl + 2 G c N_ij N_kl + G c N_il N_kj.
  // A law of I2 too takes central differences of P (tangent_of, ba_tangent.hpp).
  static constexpr bool has_tangent = !Law::uses_I2bar;
  StressStatus          tangent(const Mat2 &F, double, std::array<double, 16> &A) const
  {
    static_assert(has_tangent, "PlaneStressIncompressible::tangent: a law of I1 only");
    const double Jt = det(F);
    if (!(Jt > 0.0)) return StressStatus::inverted;
    const double inv_Jt = 1.0 / Jt, c = inv_Jt * inv_Jt;
    Modulus      G;
    if (!Law::modulus(p, Invariants{F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3] + c}, G))
      return StressStatus::chain_limit;
    const Mat2 N = {F[3] * inv_Jt, -F[2] * inv_Jt, -F[1] * inv_Jt, F[0] * inv_Jt}; // cof F~ / J~
    Mat2       M;
    for (int ij = 0; ij < 4; ++ij) M[ij] = F[ij] - c * N[ij];
    const double Gc = G[0] * c;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k)
          for (int l = 0; l < 2; ++l) {
            const int ij = 2 * i + j, kl = 2 * k + l;
            A[4 * ij + kl] = (i == k && j == l ? G[0] : 0.0) + 2.0 * G[1] * M[ij] * M[kl] + 2.0 * Gc * N[ij] * N[kl] +
                             Gc * N[2 * i + l] * N[2 * k + j];
          }
    return StressStatus::ok;
  }

  // W(F~) = Psi_iso(I1, I2) per unit reference volume; c33 = 1/J~^2 written when ok.
  StressStatus energy(const Mat2 &F, double &c33, double &psi) const
  {
    const double Jt = det(F);
    if (!(Jt > 0.0)) return StressStatus::inverted;
    const double a = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3], c = 1.0 / (Jt * Jt);
    Invariants   inv{a + c};
    if constexpr (Law::uses_I2bar) inv.I2bar = Jt * Jt + a * c;
    if (!Law::energy(p, inv, psi)) return StressStatus::chain_limit;
    c33 = c;
    return StressStatus::ok;
  }

private:
  // P~ and c = 1/J~^2 (see above) for T = double or lanes; false where the law is
  // locked. det F~ <= 0 is the caller's to test: there the result is finite and
  // meaningless (J~ taken as 1).
  template <class T> MaskOf<T> evaluate(const std::array<T, 4> &F, T &c, std::array<T, 4> &P) const
  {
    const T    Jt = F[0] * F[3] - F[1] * F[2];
    const T    inv_Jt = 1.0 / select(Jt > 0.0, Jt, T{} + 1.0);
    const T    a      = F[0] * F[0] + F[1] * F[1] + F[2] * F[2] + F[3] * F[3];
    c                 = inv_Jt * inv_Jt;
    ModulusOf<T> G;
    InvariantsOf<T> inv{a + c};
    if constexpr (Law::uses_I2bar) inv.I2bar = Jt * Jt + a * c;
    const auto admissible = Law::modulus(p, inv, G);
    T          g = G[0], b = G[0] * c * inv_Jt; // c G F~^{-T} = (c G / J~) cof F~
    if constexpr (Law::uses_I2bar) {
      ModulusOf<T> H;
      Law::modulus_I2bar(p, inv, H);
      g = G[0] + c * H[0];
      b = (c * G[0] + (a * c - Jt * Jt) * H[0]) * inv_Jt;
    }
    P = {g * F[0] - b * F[3], g * F[1] + b * F[2], g * F[2] + b * F[1], g * F[3] - b * F[0]};
    return admissible;
  }
};

} // namespace bapd
