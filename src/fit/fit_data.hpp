#pragma once
// Test data for bapd-fit: one curve of nominal stress against stretch per CSV file,
// tagged with its homogeneous test (uniaxial | pure_shear | equibiaxial).
//
//   # mode: pure_shear            (or the command-line tag MODE:FILE, which wins)
//   stretch,nominal_stress_kPa    (a column whose name contains "stretch", and one
//   1.1,1.83                       ending in stress_Pa or stress_kPa: the unit)
//
// Lines starting with '#' are comments. read_curve refuses, with one FitError naming the
// file (and the line): no mode, an unknown mode, no such columns, a value that is not a
// number, a stretch that does not increase strictly, a stretch <= 1, a negative stress,
// fewer than two points.
#include <string>
#include <vector>

#include "bapd/core/materials/homogeneous_response.hpp"

namespace bapd::fit {

struct Curve {
  std::string         file;
  LoadMode            mode = LoadMode::uniaxial;
  std::vector<double> stretch;   // [-]
  std::vector<double> stress_Pa; // nominal stress [Pa]
};

bool parse_mode(const std::string &text, LoadMode &mode);

// mode_tag: "" (the file's "# mode:" line) or a mode name.
Curve read_curve(const std::string &path, const std::string &mode_tag);

} // namespace bapd::fit
