#pragma once
// The Gent law (paper eq 24, docs/method.md section 4): the isochoric energy
//   Psi_iso = -(mu Jm / 2) ln(1 - (I1bar - 3)/Jm),   G = 2 dPsi_iso/dI1bar = mu Jm / (Jm - I1bar + 3)
// finite only below the chain-extension limit I1bar - 3 < Jm. Put together with the
// volumetric term (1/D)((J^2 - 1)/2 - ln J) by hyperelastic.hpp and plane_stress.hpp;
// Gent3D's stress is paper eq 26 and GentPlaneStress's is eq 34. The law interface is
// described in law.hpp; the registry line is in law_list.hpp.
#include "bapd/core/materials/invariant_law.hpp"

namespace bapd {

struct Gent {
  static constexpr const char *name = "gent", *title = "Gent (paper eq 24): chain-extension limit Jm";

  struct Parameters {
    double Jm = 162.6; // chain-extension limit [-] (paper: 162.6)
  };
  static constexpr std::array<LawOption<Parameters>, 1> options = {
      {{"-material_Jm", "Gent chain-extension limit Jm [-] (paper: 162.6; unused by neo_hookean)", &Parameters::Jm}}};
  static std::string check(const ParametersOf<Gent> &p)
  {
    std::ostringstream msg;
    if (!(p.Jm > 0.0) || !std::isfinite(p.Jm))
      msg << "-material_Jm " << p.Jm << ": the Gent chain-extension limit must be > 0 (paper: 162.6)\n";
    return msg.str();
  }

  // bapd-fit (law.hpp: fit_parameters): mu and Jm; Jm starts beyond the data's largest
  // I1 - 3, so that the first iterate is not locked.
  static constexpr std::array<FitParameter, 2> fit_parameters = {{{"mu", "Pa"}, {"Jm", "-"}}};
  static void fit_values(const double *p, ElasticConstants &c, Parameters &own) { c.mu = p[0], own.Jm = p[1]; }
  static std::vector<std::vector<double>> fit_starts(double mu0, double I1max)
  {
    const double x = I1max - 3.0;
    return {{mu0, 1.5 * x + 1.0}, {mu0, 4.0 * x + 1.0}, {mu0, 20.0 * x + 10.0}};
  }

  static constexpr LawVariables variables         = LawVariables::invariants;
  static constexpr bool         uses_I2bar        = false;
  static constexpr bool         convex_increasing = true; // G > 0 and G' = G / gap > 0 below the limit
  static constexpr bool         has_limit         = true;
  static double                 I1bar_limit(const ParametersOf<Gent> &p) { return p.Jm + 3.0; }
  static constexpr const char  *limit        = "the Gent chain limit (I1bar - 3 >= Jm)";
  static constexpr const char  *limit_option = "-material_Jm";

  // G = mu Jm / gap, gap = Jm + 3 - I1bar: d^n G / dI1bar^n = n! G / gap^n. T = double
  // or Lanes; false where locked (or NaN), and there G is finite and meaningless.
  template <class T> static MaskOf<T> modulus(const ParametersOf<Gent> &p, const InvariantsOf<T> &inv, ModulusOf<T> &G)
  {
    const T    gap     = p.Jm + 3.0 - inv.I1bar;
    const auto ok      = gap > 0.0;
    const T    inv_gap = 1.0 / select(ok, gap, T{} + 1.0);
    G[0]               = p.mu * p.Jm * inv_gap;
    G[1]               = G[0] * inv_gap;
    G[2]               = 2.0 * G[1] * inv_gap;
    G[3]               = 3.0 * G[2] * inv_gap;
    G[4]               = 4.0 * G[3] * inv_gap;
    return ok;
  }

  static bool energy(const ParametersOf<Gent> &p, const Invariants &inv, double &psi)
  {
    if (!(p.Jm + 3.0 - inv.I1bar > 0.0)) return false;
    psi = -0.5 * p.mu * p.Jm * std::log1p(-(inv.I1bar - 3.0) / p.Jm);
    return true;
  }
};

using Gent3D          = Compressible3D<Gent>;
using GentPlaneStress = PlaneStress<Gent>;
using GentPlaneStrain = PlaneStrain<Gent>;

} // namespace bapd
