#pragma once
// Test data for bapd-fit: one curve of nominal stress against stretch per file, tagged
// with its homogeneous test (uniaxial | pure_shear | equibiaxial) or as the notched
// pure-shear test that gives the toughness (notched_pure_shear: not fitted, read for its
// crack onset, toughness.hpp). A file is either
// bapd-fit's own format or a test machine's export (export_table.hpp reads the cells):
//
//   # mode: pure_shear            (or the command-line tag MODE:FILE, which wins)
//   stretch,nominal_stress_kPa    a stretch column and a nominal stress with its unit
//   1.1,1.83
//
//   Time (s),Extension (mm),Load (N)      an export: the extension over the gauge
//   0,0,0                                 length and the force over the section at
//   1.5,2.5,0.061                         rest (Specimen) give the curve
//
// The header is the first line naming a deformation column (stretch; else strain,
// engineering, "Strain (%)"; else extension, "Extension (mm)") and a load column
// (nominal stress with its unit; else force, "Load (N)"); lines before it (an
// export's preamble) are skipped, and a row of units may follow it. Then
//   stretch = the stretch, 1 + strain, or 1 + extension / gauge length;
//   nominal stress = the stress, or force / cross-section at rest.
// Lines starting with '#' are comments. The rows before loading starts (up to the
// first with stretch > 1 and stress > 0: the rest point (1, 0), a slack or a preload
// at zero extension) are dropped with a note. read_curve refuses, with one FitError
// naming the file (the line, the column or the missing option): no mode, an unknown
// mode, no such columns, a column without a unit it knows, a true (Cauchy,
// logarithmic) stress or strain, an extension without the gauge length or a force
// without the section, a value that is not a number, a stretch that does not
// increase strictly or is <= 1 after loading starts, a negative stress (in a notched
// curve, before its largest: past it the sheet is cut through and a load cell's offset
// may read below zero), fewer than two points.
#include <string>
#include <vector>

#include "bapd/core/materials/homogeneous_response.hpp"

namespace bapd::fit {

struct Curve {
  std::string              file;
  LoadMode                 mode = LoadMode::uniaxial;
  bool                     notched = false; // a notched pure-shear curve (mode pure_shear): not fitted
  double                   gauge_length_m = 0.0; // -fit_gauge_length given before the file (0: none)
  std::vector<double>      stretch;   // [-]
  std::vector<double>      stress_Pa; // nominal stress [Pa]
  std::vector<std::string> notes;     // what was read and dropped, one line each
};

// The specimen at rest, for an export of extension and force (SI); 0: not given.
struct Specimen {
  double gauge_length_m   = 0.0; // the clamps' separation (-fit_gauge_length)
  double cross_section_m2 = 0.0; // width x thickness (-fit_cross_section, or -fit_width x -fit_thickness)
};

bool parse_mode(const std::string &text, LoadMode &mode);
// parse_mode, and notched_pure_shear (mode pure_shear, notched true).
bool parse_test(const std::string &text, LoadMode &mode, bool &notched);

// mode_tag: "" (the file's "# mode:" line) or a mode name.
Curve read_curve(const std::string &path, const std::string &mode_tag, const Specimen &specimen = {});

} // namespace bapd::fit
