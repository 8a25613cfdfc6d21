#pragma once
// The Yeoh law (three terms): the isochoric energy is a cubic in I1bar - 3,
//   Psi_iso = C1 (I1bar - 3) + C2 (I1bar - 3)^2 + C3 (I1bar - 3)^3,
//   G = 2 dPsi_iso/dI1bar = 2 C1 + 4 C2 (I1bar - 3) + 6 C3 (I1bar - 3)^2,
// with the volumetric term of paper eq 24 (hyperelastic.hpp, plane_stress.hpp). At rest
// G = 2 C1 is the shear modulus, so C1 = mu/2 (checked: mu is what the time step and the
// default D are sized from). The law interface is described in law.hpp; the registry
// line is in law_list.hpp.
#include "bapd/core/materials/invariant_law.hpp"

namespace bapd {

struct Yeoh {
  static constexpr const char *name = "yeoh", *title = "Yeoh (three terms): C1 (I1bar-3) + C2 (I1bar-3)^2 + C3 (I1bar-3)^3, C1 = mu/2";

  struct Parameters {
    double C1 = 2275.0; // [Pa] = mu/2 for the default mu 4.55e3
    double C2 = 7.0;    // [Pa]: mu / (4 Jm), Gent's series at the paper's mu, Jm
    double C3 = 0.0287; // [Pa]: mu / (6 Jm^2), the same
  };
  static constexpr std::array<LawOption<Parameters>, 3> options = {
      {{"-material_C1", "Yeoh C1 [Pa], = mu/2 (give -material_mu 2 C1 with it; default 2275)", &Parameters::C1},
       {"-material_C2", "Yeoh C2 [Pa], >= 0 (default 7.0 = mu/(4 Jm): Gent's series)", &Parameters::C2},
       {"-material_C3", "Yeoh C3 [Pa], >= 0 (default 0.0287 = mu/(6 Jm^2))", &Parameters::C3}}};
  // C1 > 0, C2 >= 0, C3 >= 0 is the usual sufficient condition for Drucker stability,
  // and makes Psi_iso convex and increasing in I1bar >= 3 (the plane-stress solve needs it).
  static std::string check(const ParametersOf<Yeoh> &p)
  {
    std::ostringstream msg;
    if (!(p.C1 > 0.0) || !std::isfinite(p.C1))
      msg << "-material_C1 " << p.C1 << ": the Yeoh C1 must be > 0 Pa (it is half the shear modulus at rest)\n";
    else if (std::isfinite(p.mu) && !(std::abs(2.0 * p.C1 - p.mu) <= 1e-6 * p.mu))
      msg << "-material_C1 " << p.C1 << ": the Yeoh shear modulus at rest 2 C1 = " << 2.0 * p.C1
          << " Pa must equal -material_mu " << p.mu << "; give -material_mu " << 2.0 * p.C1 << "\n";
    if (!(p.C2 >= 0.0) || !std::isfinite(p.C2))
      msg << "-material_C2 " << p.C2 << ": the Yeoh C2 must be >= 0 Pa (Drucker stability, sufficient condition)\n";
    if (!(p.C3 >= 0.0) || !std::isfinite(p.C3))
      msg << "-material_C3 " << p.C3 << ": the Yeoh C3 must be >= 0 Pa (Drucker stability, sufficient condition)\n";
    return msg.str();
  }

  // bapd-fit (law.hpp: fit_parameters): C1, C2, C3, mu = 2 C1 from them; the start is
  // the neo-Hookean fit.
  static constexpr std::array<FitParameter, 3> fit_parameters = {{{"C1", "Pa"}, {"C2", "Pa"}, {"C3", "Pa"}}};
  static void fit_values(const double *p, ElasticConstants &c, Parameters &own)
  {
    own.C1 = p[0], own.C2 = p[1], own.C3 = p[2], c.mu = 2.0 * p[0];
  }
  static std::vector<std::vector<double>> fit_starts(double mu0, double) { return {{0.5 * mu0, 0.0, 0.0}}; }

  static constexpr LawVariables variables         = LawVariables::invariants;
  static constexpr bool         uses_I2bar        = false;
  static constexpr bool         convex_increasing = true; // C1 > 0, C2, C3 >= 0 and I1bar >= 3
  static constexpr bool         has_limit         = false;

  template <class T> static MaskOf<T> modulus(const ParametersOf<Yeoh> &p, const InvariantsOf<T> &inv, ModulusOf<T> &G)
  {
    const T x = inv.I1bar - 3.0;
    G[0]      = 2.0 * p.C1 + x * (4.0 * p.C2 + x * (6.0 * p.C3));
    G[1]      = 4.0 * p.C2 + x * (12.0 * p.C3);
    G[2]      = T{} + 12.0 * p.C3;
    G[3]      = T{};
    G[4]      = T{};
    return (inv.I1bar == inv.I1bar) | (inv.I1bar != inv.I1bar); // never locked
  }

  static bool energy(const ParametersOf<Yeoh> &p, const Invariants &inv, double &psi)
  {
    const double x = inv.I1bar - 3.0;
    psi            = x * (p.C1 + x * (p.C2 + x * p.C3));
    return true;
  }
};

using Yeoh3D          = Compressible3D<Yeoh>;
using YeohPlaneStress = PlaneStress<Yeoh>;
using YeohPlaneStrain = PlaneStrain<Yeoh>;

} // namespace bapd
