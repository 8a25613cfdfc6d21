#pragma once
// The laws bapd-fit can fit, each with its parameters (names, units, a scale for the
// finite differences), starting points from the data, its incompressible homogeneous
// response (homogeneous_response.hpp: for the registry's laws through their own
// modulus(), so what is fitted is what bapd runs) and energy (the law's own energy()),
// the checks bapd applies to its values
// (the registry's, law_registry.hpp), and its YAML material section for a scene.
#include <functional>
#include <string>
#include <vector>

#include "bapd/core/materials/homogeneous_response.hpp"

namespace bapd::fit {

struct FitLaw {
  std::string              name; // gent, mooney_rivlin, ..., ogden (N terms)
  std::vector<std::string> parameters, units;
  std::vector<double>      scale; // typical size of each parameter
  // starting points, from mu0 (a neo-Hookean fit) and I1max (the largest I1 in the data)
  std::function<std::vector<std::vector<double>>(double mu0, double I1max)> starts;
  // nominal stress [Pa]; false where undefined (locked, or parameters out of range)
  std::function<bool(const std::vector<double> &, LoadMode, double, double &)> stress;
  // the strain-energy density W [J/m^3] of the same incompressible test, whose
  // derivative along the stretch is stress (the toughness of toughness.hpp reads it)
  std::function<bool(const std::vector<double> &, LoadMode, double, double &)> energy;
  // "" when bapd accepts the values, else one line per problem (bapd's own messages)
  std::function<std::string(const std::vector<double> &)> check;
  // the scene's material: section (the shear modulus at rest included)
  std::function<std::string(const std::vector<double> &)> yaml;
  // the canonical order of the parameters (Ogden: terms by increasing alpha, since the
  // terms are interchangeable); empty: as they are
  std::function<std::vector<std::size_t>(const std::vector<double> &)> order;
  // false: not a -material_model of bapd (yaml() says so in a comment)
  bool in_bapd = true;
};

// The names -law accepts: gent, neo_hookean, mooney_rivlin, yeoh, arruda_boyce, ogden.
std::vector<std::string> fit_law_names();
// ogden_terms: N for "ogden". Throws FitError for an unknown name.
FitLaw fit_law(const std::string &name, int ogden_terms);

} // namespace bapd::fit
