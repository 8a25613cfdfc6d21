#pragma once
// The Gent law (paper eq 24, METHOD.md section 4): the isochoric energy
//   Psi_iso = -(mu Jm / 2) ln(1 - (I1bar - 3)/Jm),   G = 2 dPsi_iso/dI1bar = mu Jm / (Jm - I1bar + 3)
// finite only below the chain-extension limit I1bar - 3 < Jm. Put together with the
// volumetric term (1/D)((J^2 - 1)/2 - ln J) by hyperelastic.hpp; Gent3D's stress is
// paper eq 26 and GentPlaneStress's is eq 34.
#include "bapd/hyperelastic.hpp"

namespace bapd {

struct Gent {
  static constexpr bool has_limit = true;
  static double         I1bar_limit(const MaterialParameters &p) { return p.Jm + 3.0; }

  // G = mu Jm / gap, gap = Jm + 3 - I1bar: d^n G / dI1bar^n = n! G / gap^n. T = double
  // or Lanes; false where locked (or NaN), and there G is finite and meaningless.
  template <class T> static MaskOf<T> modulus(const MaterialParameters &p, T I1bar, ModulusOf<T> &G)
  {
    const T    gap     = p.Jm + 3.0 - I1bar;
    const auto ok      = gap > 0.0;
    const T    inv_gap = 1.0 / select(ok, gap, T{} + 1.0);
    G[0]               = p.mu * p.Jm * inv_gap;
    G[1]               = G[0] * inv_gap;
    G[2]               = 2.0 * G[1] * inv_gap;
    G[3]               = 3.0 * G[2] * inv_gap;
    G[4]               = 4.0 * G[3] * inv_gap;
    return ok;
  }

  static bool energy(const MaterialParameters &p, double I1bar, double &psi)
  {
    if (!(p.Jm + 3.0 - I1bar > 0.0)) return false;
    psi = -0.5 * p.mu * p.Jm * std::log1p(-(I1bar - 3.0) / p.Jm);
    return true;
  }
};

using Gent3D          = Compressible3D<Gent>;
using GentPlaneStress = PlaneStress<Gent>;
using GentPlaneStrain = PlaneStrain<Gent>;

} // namespace bapd
