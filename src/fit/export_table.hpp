#pragma once
// The text of a test machine's export, cell by cell (fit_data.hpp reads the curve):
//
//   Time (s),Extension (mm),Load (N)          a comma CSV, the units in the header
//   Time (s);Extension (mm);Force [kN]         a ';' CSV, decimal commas: 0,125
//   Time<TAB>Extension<TAB>Load                a tab-separated export, whose units
//   (s)<TAB>(mm)<TAB>(N)                       may be a row of their own
//   stretch,nominal_stress_kPa                 the unit as a name's suffix
//
// The separator is the header line's: a tab if it has one, else ';' if it has one,
// else ','. Cells may be quoted ("Load (N)"). A number may have a decimal comma where
// the separator is not a comma (or the cell is quoted); a cell with both '.' and ','
// (a thousands separator) is not read. A header cell is a name and a unit: "Name
// (unit)", "Name [unit]" or "name_unit" (the suffix only if it is a unit bapd-fit
// knows); the name says which quantity the column holds.
#include <string>
#include <vector>

namespace bapd::fit {

enum class Quantity { none, time, stretch, strain, extension, stress, force };

struct ColumnName {
  std::string label;                  // the cell as written, quotes and spaces trimmed
  std::string name;                   // lower case, without the unit
  std::string unit;                   // as written; "" when the cell gives none
  Quantity    quantity = Quantity::none;
};

// Separator of a header line: '\t', ';' or ','.
// Text of a cell: without the surrounding blanks; in lower case (ASCII).
std::string trim(const std::string &s);
std::string lower(std::string s);

char detect_separator(const std::string &line);
// The cells of a line (trimmed, unquoted).
std::vector<std::string> split_cells(const std::string &line, char separator);
// A number, with a decimal point or a decimal comma; false for anything else
// (empty, text, "1.234,5", inf, nan).
bool parse_number(const std::string &cell, double &value);

// A header cell: its name, unit and quantity. The quantity is the first whose words the
// name contains, in this order: energy (none), stretch, stress (spannung), strain
// (dehnung), force (load, kraft), extension (displacement, elongation, crosshead,
// travel, weg), time (zeit).
ColumnName parse_column(const std::string &cell);
// A cell of a units row ("(mm)", "[N]", "mm", "%"): the unit, or "" if it is not one.
std::string unit_cell(const std::string &cell);

// The factor that turns a value of `quantity` in `unit` into SI (m, N, Pa, a strain as
// a fraction, s); 0 when the unit is not one of the quantity's. Units are compared
// without case (mpa is MPa, mn is mN).
double si_factor(Quantity quantity, const std::string &unit);
// The units si_factor knows for a quantity, for messages ("m, mm, cm, um, in").
std::string known_units(Quantity quantity);
const char *to_string(Quantity quantity);

} // namespace bapd::fit
