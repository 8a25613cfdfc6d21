#pragma once
// The Mooney-Rivlin law: the isochoric energy is linear in both invariants,
//   Psi_iso = C10 (I1bar - 3) + C01 (I2bar - 3),
//   G = 2 dPsi_iso/dI1bar = 2 C10,  H = 2 dPsi_iso/dI2bar = 2 C01,
// with the volumetric term of paper eq 24; the I2bar part of the stress is added by
// Compressible3D and PlaneStrain (hyperelastic.hpp). The shear modulus at rest is
// 2 (C10 + C01), so it must equal mu (checked: the time step and the default D are
// sized from mu). The plane-stress C33 solve differentiates along I1bar only and
// refuses the law (formulation_refusal, law.hpp). Interface: law.hpp; registry line:
// law_registry.hpp.
#include <array>
#include <cmath>
#include <sstream>
#include <string>

#include "bapd/hyperelastic.hpp"
#include "bapd/law.hpp"

namespace bapd {

struct MooneyRivlin {
  static constexpr const char *name  = "mooney_rivlin";
  static constexpr const char *title = "Mooney-Rivlin: C10 (I1bar-3) + C01 (I2bar-3), mu = 2 (C10 + C01)";

  struct Parameters {
    double C10 = 1820.0; // [Pa]; with C01: 2 (C10 + C01) = the default mu 4.55e3
    double C01 = 455.0;  // [Pa]
  };
  static constexpr std::array<LawOption<Parameters>, 2> options = {
      {{"-material_C10", "Mooney-Rivlin C10 [Pa], >= 0, with 2 (C10 + C01) = mu (default 1820)", &Parameters::C10},
       {"-material_C01", "Mooney-Rivlin C01 [Pa], >= 0, with 2 (C10 + C01) = mu (default 455)", &Parameters::C01}}};
  // C10 >= 0, C01 >= 0, C10 + C01 > 0: the usual sufficient condition for Drucker
  // stability (each invariant term convex in F's principal stretches).
  static std::string check(const ParametersOf<MooneyRivlin> &p)
  {
    std::ostringstream msg;
    bool               ok = true;
    if (!(p.C10 >= 0.0) || !std::isfinite(p.C10)) {
      msg << "-material_C10 " << p.C10 << ": the Mooney-Rivlin C10 must be >= 0 Pa (Drucker stability, sufficient condition)\n";
      ok = false;
    }
    if (!(p.C01 >= 0.0) || !std::isfinite(p.C01)) {
      msg << "-material_C01 " << p.C01 << ": the Mooney-Rivlin C01 must be >= 0 Pa (Drucker stability, sufficient condition)\n";
      ok = false;
    }
    const double mu = 2.0 * (p.C10 + p.C01);
    if (ok && !(mu > 0.0))
      msg << "-material_C10 " << p.C10 << ": Mooney-Rivlin needs C10 + C01 > 0 (the shear modulus at rest is 2 (C10 + C01))\n";
    else if (ok && std::isfinite(p.mu) && !(std::abs(mu - p.mu) <= 1e-6 * p.mu))
      msg << "-material_C10 " << p.C10 << ": the Mooney-Rivlin shear modulus at rest 2 (C10 + C01) = " << mu
          << " Pa must equal -material_mu " << p.mu << "; give -material_mu " << mu << "\n";
    return msg.str();
  }

  static constexpr LawVariables variables         = LawVariables::invariants;
  static constexpr bool         uses_I2bar        = true;
  static constexpr bool         convex_increasing = true; // in I1bar (linear, C10 >= 0)
  static constexpr bool         has_limit         = false;

  template <class T>
  static MaskOf<T> modulus(const ParametersOf<MooneyRivlin> &p, const InvariantsOf<T> &inv, ModulusOf<T> &G)
  {
    G = {T{} + 2.0 * p.C10, T{}, T{}, T{}, T{}};
    return (inv.I1bar == inv.I1bar) | (inv.I1bar != inv.I1bar); // never locked
  }
  static double modulus_I2bar(const ParametersOf<MooneyRivlin> &p, const Invariants &) { return 2.0 * p.C01; }

  static bool energy(const ParametersOf<MooneyRivlin> &p, const Invariants &inv, double &psi)
  {
    psi = p.C10 * (inv.I1bar - 3.0) + p.C01 * (inv.I2bar - 3.0);
    return true;
  }
};

using MooneyRivlin3D          = Compressible3D<MooneyRivlin>;
using MooneyRivlinPlaneStrain = PlaneStrain<MooneyRivlin>;

} // namespace bapd
