#pragma once
// The compressible neo-Hookean law: Psi_iso = (mu/2)(I1bar - 3), G = mu, with the
// same volumetric term as Gent. It is Gent's Jm -> infinity limit, which makes it the
// reference for small strains and for checks that must not see the chain limit.
#include "bapd/hyperelastic.hpp"

namespace bapd {

struct NeoHookean {
  static constexpr bool has_limit = false;

  template <class T> static MaskOf<T> modulus(const MaterialParameters &p, T I1bar, ModulusOf<T> &G)
  {
    G = {T{} + p.mu, T{}, T{}, T{}, T{}};
    return (I1bar == I1bar) | (I1bar != I1bar); // never locked
  }

  static bool energy(const MaterialParameters &p, double I1bar, double &psi)
  {
    psi = 0.5 * p.mu * (I1bar - 3.0);
    return true;
  }
};

using NeoHookean3D          = Compressible3D<NeoHookean>;
using NeoHookeanPlaneStress = PlaneStress<NeoHookean>;
using NeoHookeanPlaneStrain = PlaneStrain<NeoHookean>;

} // namespace bapd
