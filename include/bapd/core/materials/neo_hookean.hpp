#pragma once
// The compressible neo-Hookean law: Psi_iso = (mu/2)(I1bar - 3), G = mu, with the
// same volumetric term as Gent. It is Gent's Jm -> infinity limit, which makes it the
// reference for small strains and for checks that must not see the chain limit. The
// law interface is described in law.hpp; the registry line is in law_list.hpp.
#include "bapd/core/materials/invariant_law.hpp"

namespace bapd {

struct NeoHookean {
  static constexpr const char *name = "neo_hookean", *title = "compressible neo-Hookean (Gent with Jm -> infinity)";

  struct Parameters {}; // mu and D only
  static constexpr std::array<LawOption<Parameters>, 0> options = {};
  static std::string check(const ParametersOf<NeoHookean> &) { return ""; }

  // bapd-fit (law.hpp: fit_parameters): mu alone, which the neo-Hookean start already is.
  static constexpr std::array<FitParameter, 1> fit_parameters = {{{"mu", "Pa"}}};
  static void fit_values(const double *p, ElasticConstants &c, Parameters &) { c.mu = p[0]; }
  static std::vector<std::vector<double>> fit_starts(double mu0, double) { return {{mu0}}; }

  static constexpr LawVariables variables         = LawVariables::invariants;
  static constexpr bool         uses_I2bar        = false;
  static constexpr bool         convex_increasing = true; // linear in I1bar with G = mu > 0
  static constexpr bool         has_limit         = false;

  template <class T> static MaskOf<T> modulus(const ParametersOf<NeoHookean> &p, const InvariantsOf<T> &inv, ModulusOf<T> &G)
  {
    G = {T{} + p.mu, T{}, T{}, T{}, T{}};
    return (inv.I1bar == inv.I1bar) | (inv.I1bar != inv.I1bar); // never locked
  }

  static bool energy(const ParametersOf<NeoHookean> &p, const Invariants &inv, double &psi)
  {
    psi = 0.5 * p.mu * (inv.I1bar - 3.0);
    return true;
  }
};

using NeoHookean3D          = Compressible3D<NeoHookean>;
using NeoHookeanPlaneStress = PlaneStress<NeoHookean>;
using NeoHookeanPlaneStrain = PlaneStrain<NeoHookean>;

} // namespace bapd
