#pragma once
// The material parameters a scene holds: the shared mu and D, and every registered
// law's own values in one compact store (every law's, so that -help lists them all and a
// file may carry them whatever the model). A model takes the part it reads,
// ParametersOf<Law> (law.hpp), from the law's place in the store, which the registry
// knows (law_registry.hpp); this header needs no law header.
#include <string>
#include <vector>

namespace bapd {

// What every law shares: the shear modulus at rest and the compressibility of U(J).
struct ElasticConstants {
  double mu = 4.55e3; // shear modulus at rest [Pa] (paper: 4.55e3)
  double D  = 0.0;    // compressibility [1/Pa]; bulk modulus at rest K = 2/D
};

struct MaterialParameters : ElasticConstants {
  // mu, D and every law's defaults (the initialisers of its Parameters members).
  MaterialParameters();
  // A law's own value by its option name ("-material_Jm"); std::out_of_range for a name
  // no registered law has.
  double       &operator[](const std::string &option);
  const double &operator[](const std::string &option) const;

  // Every registered law's own values, law after law in registry order, each law's in
  // its option order (LawOptionEntry::index).
  std::vector<double> values;
};

} // namespace bapd
