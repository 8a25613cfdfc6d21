#pragma once
// The Mooney-Rivlin law: the isochoric energy is linear in both invariants,
//   Psi_iso = C10 (I1bar - 3) + C01 (I2bar - 3),
//   G = 2 dPsi_iso/dI1bar = 2 C10,  H = 2 dPsi_iso/dI2bar = 2 C01,
// with the volumetric term of paper eq 24; the I2bar part of the stress is added by
// Compressible3D and PlaneStrain (hyperelastic.hpp) and PlaneStress (plane_stress.hpp:
// the C33 solve with the I2bar term Hbar t2). The shear modulus at rest is
// 2 (C10 + C01), so it must equal mu (checked: the time step and the default D are
// sized from mu).
//
// Stability. Incompressible, the nominal stresses are (homogeneous_response.hpp)
//   uniaxial    P = 2 (l - l^-2) (C10 + C01 / l),
//   equibiaxial P = 2 (l - l^-5) (C10 + C01 l^2):
// with C01 < 0 the equibiaxial stress falls back to zero at l = sqrt(C10 / -C01), with
// C10 < 0 the uniaxial one at l = C01 / -C10; before that the stress-stretch curve has
// turned down, i.e. the law is not Drucker-stable (and the plane-stress solve, which
// needs Psi_iso convex in both invariants, would lose its one root). C10 >= 0 and
// C01 >= 0 make each term convex: stable for every deformation. So the check refuses
// a negative coefficient and says where the law would have failed. Interface: law.hpp;
// registry line: law_list.hpp.
#include "bapd/core/materials/invariant_law.hpp"

namespace bapd {

struct MooneyRivlin {
  static constexpr const char *name = "mooney_rivlin", *title = "Mooney-Rivlin: C10 (I1bar-3) + C01 (I2bar-3), mu = 2 (C10 + C01)";

  struct Parameters {
    double C10 = 1820.0; // [Pa]; with C01: 2 (C10 + C01) = the default mu 4.55e3
    double C01 = 455.0;  // [Pa]
  };
  static constexpr std::array<LawOption<Parameters>, 2> options = {
      {{"-material_C10", "Mooney-Rivlin C10 [Pa], >= 0, with 2 (C10 + C01) = mu (default 1820)", &Parameters::C10},
       {"-material_C01", "Mooney-Rivlin C01 [Pa], >= 0, with 2 (C10 + C01) = mu (default 455)", &Parameters::C01}}};
  // C10 >= 0, C01 >= 0, C10 + C01 > 0: Drucker stability for every deformation (see
  // the top); a negative coefficient is refused with the stretch where it fails.
  static std::string check(const ParametersOf<MooneyRivlin> &p)
  {
    std::ostringstream msg;
    bool               ok = std::isfinite(p.C10) && std::isfinite(p.C01);
    if (!std::isfinite(p.C10)) msg << "-material_C10 " << p.C10 << ": the Mooney-Rivlin C10 must be a number >= 0 Pa\n";
    if (!std::isfinite(p.C01)) msg << "-material_C01 " << p.C01 << ": the Mooney-Rivlin C01 must be a number >= 0 Pa\n";
    if (ok && p.C10 < 0.0) {
      msg << "-material_C10 " << p.C10 << ": the Mooney-Rivlin C10 must be >= 0 Pa: with C10 < 0 the law is not "
          << "Drucker-stable (the uniaxial stress 2 (l - l^-2)(C10 + C01/l) turns down and is zero at stretch C01/-C10";
      if (p.C01 > 0.0) msg << " = " << p.C01 / -p.C10;
      msg << "); refit with C10 >= 0 or choose a law of I1bar (-material_model yeoh, gent)\n";
      ok = false;
    }
    if (ok && p.C01 < 0.0) {
      msg << "-material_C01 " << p.C01 << ": the Mooney-Rivlin C01 must be >= 0 Pa: with C01 < 0 the law is not "
          << "Drucker-stable (the equibiaxial stress 2 (l - l^-5)(C10 + C01 l^2) turns down and is zero at stretch "
          << "sqrt(C10/-C01)";
      if (p.C10 > 0.0) msg << " = " << std::sqrt(p.C10 / -p.C01);
      msg << "), and the plane-stress solve needs C01 >= 0; refit with C01 >= 0 or choose a law of I1bar "
          << "(-material_model yeoh, gent)\n";
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

  // bapd-fit (law.hpp: fit_parameters): C10 and C01, mu = 2 (C10 + C01) from them; the
  // starts split the neo-Hookean modulus between the two terms.
  static constexpr std::array<FitParameter, 2> fit_parameters = {{{"C10", "Pa"}, {"C01", "Pa"}}};
  static void fit_values(const double *p, ElasticConstants &c, Parameters &own)
  {
    own.C10 = p[0], own.C01 = p[1], c.mu = 2.0 * (p[0] + p[1]);
  }
  static std::vector<std::vector<double>> fit_starts(double mu0, double) { return {{0.4 * mu0, 0.1 * mu0}, {0.25 * mu0, 0.25 * mu0}}; }

  static constexpr LawVariables variables         = LawVariables::invariants;
  static constexpr bool         uses_I2bar        = true;
  static constexpr bool         convex_increasing = true; // linear in each invariant, C10, C01 >= 0
  static constexpr bool         has_limit         = false;

  template <class T>
  static MaskOf<T> modulus(const ParametersOf<MooneyRivlin> &p, const InvariantsOf<T> &inv, ModulusOf<T> &G)
  {
    G = {T{} + 2.0 * p.C10, T{}, T{}, T{}, T{}};
    return (inv.I1bar == inv.I1bar) | (inv.I1bar != inv.I1bar); // never locked
  }
  template <class T>
  static void modulus_I2bar(const ParametersOf<MooneyRivlin> &p, const InvariantsOf<T> &, ModulusOf<T> &H)
  {
    H = {T{} + 2.0 * p.C01, T{}, T{}, T{}, T{}};
  }

  static bool energy(const ParametersOf<MooneyRivlin> &p, const Invariants &inv, double &psi)
  {
    psi = p.C10 * (inv.I1bar - 3.0) + p.C01 * (inv.I2bar - 3.0);
    return true;
  }
};

using MooneyRivlin3D          = Compressible3D<MooneyRivlin>;
using MooneyRivlinPlaneStress = PlaneStress<MooneyRivlin>;
using MooneyRivlinPlaneStrain = PlaneStrain<MooneyRivlin>;

} // namespace bapd
