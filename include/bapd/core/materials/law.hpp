#pragma once
// What a hyperelastic law is (docs/method.md section 4), for the formulations that turn it
// into a stress (hyperelastic.hpp: Compressible3D, PlaneStrain; plane_stress.hpp:
// PlaneStress) and for the registry that offers it to the user (law_registry.hpp).
//
//   Psi(F) = Psi_iso(I1bar, I2bar) + U(J),   C = F^T F,  J = det F,
//   I1bar = tr(C) J^{-2/3},  I2bar = ((tr C)^2 - tr(C^2))/2 J^{-4/3},
//   U(J)  = (1/D) ((J^2 - 1)/2 - ln J)       (paper eq 24, the same for every law)
//
// A law is a struct of static members, one header per law (gent.hpp, neo_hookean.hpp):
//
//   static constexpr const char *name;        // -material_model value, e.g. "gent"
//   static constexpr const char *title;       // one line for logs and -help
//   struct Parameters { double Jm = 162.6; }; // its own values, with their defaults
//                                             // (mu and D are shared: ElasticConstants)
//   static constexpr std::array<LawOption<Parameters>, N> options; // option name,
//                                             // help with units, member (its default)
//   static std::string check(const ParametersOf<Law> &); // one line per bad value
//   static constexpr std::array<FitParameter, N> fit_parameters; // what bapd-fit fits:
//                                             // name and unit (FitParameter below)
//   static void fit_values(const double *p, ElasticConstants &, Parameters &);
//                          // the law's values from fitted values p (fit_parameters'
//                          // order): mu and the own ones; the rest keep their defaults
//   static std::vector<std::vector<double>> fit_starts(double mu0, double I1max);
//                          // bapd-fit's starting points from the data: mu0 of a
//                          // neo-Hookean fit, I1max the largest I1 of the curves
//                          // (Ogden has none: its fitted terms are a count the user
//                          // picks, and bapd-fit writes its recipe itself)
//   static constexpr LawVariables variables = LawVariables::invariants;
//   static constexpr bool uses_I2bar;         // Psi_iso depends on I2bar
//   static constexpr bool convex_increasing;  // Psi_iso convex and increasing in I1bar
//                                             // (and, uses_I2bar, in I2bar) for every
//                                             // value check() accepts
//   static constexpr bool has_limit;          // Psi_iso finite only for I1bar < limit
//   static double I1bar_limit(const ParametersOf<Law> &);                (has_limit)
//   static constexpr const char *limit, *limit_option;                   (has_limit)
//                          // for messages: "the Gent chain limit (I1bar - 3 >= Jm)",
//                          // and the option that moves it, "-material_Jm"
//   template <class T> static MaskOf<T> modulus(const ParametersOf<Law> &,
//                                 const InvariantsOf<T> &, ModulusOf<T> &G);
//                          // G[n] = d^n G / dI1bar^n, n = 0..4, G = 2 dPsi_iso/dI1bar
//   static bool energy(const ParametersOf<Law> &, const Invariants &, double &psi_iso);
//   (uses_I2bar only) template <class T> static void modulus_I2bar(const ParametersOf<Law> &,
//                                 const InvariantsOf<T> &, ModulusOf<T> &H);
//                          // H[n] = d^n H / dI2bar^n, n = 0..4, H = 2 dPsi_iso/dI2bar
//
// A law of I2bar is separable, Psi_iso = W1(I1bar) + W2(I2bar): G depends on I1bar
// alone and H on I2bar alone (the plane-stress solve differentiates them along C33 one
// invariant at a time; Compressible3D and PlaneStrain read G[0] and H[0] only).
//
// modulus and energy return false where the law is locked (I1bar >= limit). modulus is
// a template over T = double (one bond) or Lanes (lane_count, lanes.hpp: PlaneStress runs
// that many bonds at a time in the bond kernel) and must keep the locked lanes finite.
// All of it is inline and allocation-free: it runs per bond per step. A formulation
// fills I2bar only for a law with uses_I2bar (it costs a tr(C^2) otherwise).
//
// What each formulation needs of a law is stated where it is written (PlaneStress:
// plane_stress.hpp); formulation_refusal() below says, in one message, why a law
// cannot be run in a formulation, and the registry refuses such a choice up front.
//
// The laws beyond Gent: Mooney-Rivlin (uses_I2bar, modulus_I2bar), Yeoh and
// Arruda-Boyce (I1bar only, like Gent) use this interface as it is. Ogden works on the
// principal stretches: it declares LawVariables::principal_stretches and brings its own
// formulations (PlaneStrainModel, PlaneStressModel, Model3D: has_own_formulations
// below), which with_model and with_model_3d (models.hpp) pick instead of the invariant ones.
#include <array>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "bapd/core/kernel/lanes.hpp"
#include "bapd/core/materials/law_list.hpp"
#include "bapd/core/materials/material_parameters.hpp"
#include "bapd/core/materials/stress_status.hpp"

namespace bapd {

// The values a model of one law reads: the shared constants and the law's own, taken
// from the scene's store (MaterialParameters, material_parameters.hpp) at the law's
// place in it (law_value_offset, defined by the registry for every registered law).
template <class Law> std::size_t law_value_offset();

template <class Law> struct ParametersOf : ElasticConstants, Law::Parameters {
  ParametersOf() = default;
  ParametersOf(const MaterialParameters &all) : ElasticConstants(all)
  {
    const std::size_t first = law_value_offset<Law>();
    for (std::size_t i = 0; i < Law::options.size(); ++i) this->*(Law::options[i].value) = all.values[first + i];
  }
};

// One parameter of a law as an option: its name, its help text (with units and the
// paper's value) and where its value lives. The default is the member's initialiser.
template <class Parameters> struct LawOption {
  const char *name;
  const char *help;
  double Parameters::*value;
};

// One parameter bapd-fit fits (fit_parameters): its name in the report and its unit,
// "Pa" or "-" (the fit scales a Pa parameter by the data's modulus, a "-" one by 1).
struct FitParameter {
  const char *name;
  const char *unit;
};

// The law's own parameters for the scene summary, appended to "mu 4.55e3 Pa": by default
// each option as its name and value, ", Jm 162.6"; a law may print them its own way
// with `static std::string summary(const ParametersOf<Law> &)`.
template <class Law, class = void> struct HasSummary : std::false_type {};
template <class Law>
struct HasSummary<Law, std::void_t<decltype(Law::summary(std::declval<const ParametersOf<Law> &>()))>> : std::true_type {};

template <class Law> std::string law_summary(const ParametersOf<Law> &p)
{
  if constexpr (HasSummary<Law>::value) return Law::summary(p);
  else {
    std::string text;
    for (const auto &o : Law::options) {
      char value[32];
      std::snprintf(value, sizeof value, "%g", p.*(o.value));
      text += std::string(", ") + (o.name + std::strlen("-material_")) + " " + value;
    }
    return text;
  }
}

// What a law's energy is written in.
enum class LawVariables { invariants, principal_stretches };

// The invariants a law is evaluated at (T = double or Lanes). I2bar is 0 unless the
// law uses it (uses_I2bar).
template <class T> struct InvariantsOf {
  T I1bar{};
  T I2bar{};
};
using Invariants = InvariantsOf<double>;

// G = 2 dPsi_iso/dI1bar and its first four I1bar-derivatives (the plane-stress solve
// uses them; Compressible3D and PlaneStrain read G[0] only).
template <class T> using ModulusOf = std::array<T, 5>; // T = double or Lanes (lane_count bonds)
using Modulus                      = ModulusOf<double>;

// Empty when Law can be run in formulation f, else why not (one sentence, naming the
// requirement and the formulation that would do). Plane stress: see plane_stress.hpp.
// A law of principal stretches may bring its own formulations (Ogden: ogden.hpp),
// as the member types PlaneStrainModel and PlaneStressModel.
template <class Law, class = void> struct HasOwnFormulations : std::false_type {};
template <class Law>
struct HasOwnFormulations<Law, std::void_t<typename Law::PlaneStrainModel, typename Law::PlaneStressModel>> : std::true_type {};
template <class Law> inline constexpr bool has_own_formulations = HasOwnFormulations<Law>::value;

template <class Law> std::string formulation_refusal(Formulation f)
{
  const std::string law = Law::name;
  // Incompressible plane stress (plane_stress_incompressible.hpp) takes C33 = 1/J~^2 and
  // the invariants I1, I2 from it: any law of invariants, and none of principal stretches.
  if (f == Formulation::plane_stress_incompressible && Law::variables != LawVariables::invariants)
    return "-material_model " + law +
           " with -material_formulation plane_stress_incompressible: the incompressible plane stress is written for "
           "laws of the invariants I1, I2, and this law is written in principal stretches; use -material_formulation "
           "plane_stress with a large -material_bulk_ratio (e.g. 1e4)";
  if constexpr (has_own_formulations<Law>) return "";
  if (Law::variables != LawVariables::invariants)
    return "-material_model " + law +
           ": the law is written in principal stretches and brings no formulations of its own (PlaneStrainModel, "
           "PlaneStressModel: see ogden.hpp)";
  if (f != Formulation::plane_stress) return "";
  if (!Law::convex_increasing)
    return "-material_model " + law +
           " with -material_formulation plane_stress: the plane-stress C33 solve (S33 = 0) needs an isochoric "
           "energy that is convex and increasing in I1bar and I2bar (then S33 = 0 has one root, bracketed), and this "
           "law's is not; use -material_formulation plane_strain";
  if (Law::uses_I2bar && Law::has_limit)
    return "-material_model " + law +
           " with -material_formulation plane_stress: the plane-stress C33 solve (S33 = 0) brackets a locked law "
           "along I1bar only, and this law depends on I2bar too; use -material_formulation plane_strain";
  return "";
}

// The same as a constant, for `if constexpr` (models.hpp instantiates PlaneStress<Law>
// only where it holds).
template <class Law>
inline constexpr bool accepts_plane_stress =
    Law::variables == LawVariables::invariants && Law::convex_increasing && !(Law::uses_I2bar && Law::has_limit);

} // namespace bapd
