// Cells, numbers and header names of a test export (export_table.hpp).
#include "export_table.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace bapd::fit {

std::string trim(const std::string &s)
{
  const auto b = s.find_first_not_of(" \t\r\n"), e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}
std::string lower(std::string s)
{
  for (char &c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

namespace {

bool contains(const std::string &s, const char *word) { return s.find(word) != std::string::npos; }

struct Unit {
  const char *name; // lower case
  double      factor;
};
// "\xc2\xb5" and "\xce\xbc" are the micro sign and mu in UTF-8, "\xb5" the micro sign
// in Latin-1; "\xc2\xb2" is a superscript 2 in UTF-8.
const Unit kLength[] = {{"m", 1.0},     {"mm", 1e-3},         {"cm", 1e-2},         {"um", 1e-6},
                        {"\xc2\xb5m", 1e-6}, {"\xce\xbcm", 1e-6}, {"\xb5m", 1e-6}, {"in", 0.0254}, {"inch", 0.0254}};
const Unit kForce[]  = {{"n", 1.0}, {"kn", 1e3}, {"mn", 1e-3}, {"lbf", 4.4482216152605}};
const Unit kStress[] = {{"pa", 1.0},     {"kpa", 1e3},   {"mpa", 1e6},        {"n/mm2", 1e6},  {"n/mm^2", 1e6},
                        {"n/mm\xc2\xb2", 1e6}, {"n/m2", 1.0}, {"n/m^2", 1.0}, {"psi", 6894.757293168361}};
const Unit kStrain[] = {{"%", 0.01}, {"-", 1.0}, {"mm/mm", 1.0}, {"m/m", 1.0}};
const Unit kStretch[] = {{"", 1.0}, {"-", 1.0}};
const Unit kTime[]   = {{"s", 1.0}, {"ms", 1e-3}, {"min", 60.0}, {"h", 3600.0}};

template <std::size_t N> double look_up(const Unit (&table)[N], const std::string &unit)
{
  const std::string u = lower(trim(unit));
  for (const Unit &entry : table)
    if (u == entry.name) return entry.factor;
  return 0.0;
}
bool is_unit(const std::string &unit)
{
  for (Quantity q : {Quantity::extension, Quantity::force, Quantity::stress, Quantity::strain, Quantity::time})
    if (si_factor(q, unit) > 0.0) return true;
  return false;
}

// "Name (unit)" or "Name [unit]" -> {Name, unit}; otherwise {cell, ""}.
std::pair<std::string, std::string> bracketed_unit(const std::string &cell)
{
  if (cell.size() < 2) return {cell, ""};
  const char close = cell.back(), open = close == ')' ? '(' : close == ']' ? '[' : '\0';
  if (!open) return {cell, ""};
  const auto at = cell.rfind(open);
  if (at == std::string::npos) return {cell, ""};
  return {trim(cell.substr(0, at)), trim(cell.substr(at + 1, cell.size() - at - 2))};
}

} // namespace

char detect_separator(const std::string &line)
{
  if (line.find('\t') != std::string::npos) return '\t';
  if (line.find(';') != std::string::npos) return ';';
  return ',';
}

std::vector<std::string> split_cells(const std::string &line, char separator)
{
  std::vector<std::string> cells;
  std::string              cell;
  bool                     quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') cell += '"', ++i; // "" inside quotes
      else quoted = !quoted;
    } else if (c == separator && !quoted) {
      cells.push_back(trim(cell));
      cell.clear();
    } else cell += c;
  }
  cells.push_back(trim(cell));
  return cells;
}

bool parse_number(const std::string &cell, double &value)
{
  std::string text = trim(cell);
  if (text.empty()) return false;
  const auto comma = text.find(',');
  if (comma != std::string::npos) {
    if (text.find('.') != std::string::npos || text.find(',', comma + 1) != std::string::npos) return false;
    text[comma] = '.';
  }
  char *end = nullptr;
  value     = std::strtod(text.c_str(), &end);
  return *end == '\0' && std::isfinite(value) && text.find_first_of("xXpP") == std::string::npos; // no hex floats
}

ColumnName parse_column(const std::string &cell)
{
  ColumnName c;
  c.label = trim(cell);
  auto [name, unit] = bracketed_unit(c.label);
  if (unit.empty()) { // a unit as the name's suffix: nominal_stress_kPa, time_s
    const auto underscore = name.rfind('_');
    if (underscore != std::string::npos && underscore + 1 < name.size() && is_unit(name.substr(underscore + 1)))
      unit = name.substr(underscore + 1), name = name.substr(0, underscore);
  }
  c.name = lower(trim(name));
  c.unit = unit;
  const std::string &n = c.name;
  if (contains(n, "energy")) c.quantity = Quantity::none;
  else if (contains(n, "stretch")) c.quantity = Quantity::stretch;
  else if (contains(n, "stress") || contains(n, "spannung")) c.quantity = Quantity::stress;
  else if (contains(n, "strain") || contains(n, "dehnung")) c.quantity = Quantity::strain;
  else if (contains(n, "force") || contains(n, "load") || contains(n, "kraft")) c.quantity = Quantity::force;
  else if (contains(n, "extension") || contains(n, "displacement") || contains(n, "elongation") || contains(n, "crosshead") ||
           contains(n, "travel") || contains(n, "weg"))
    c.quantity = Quantity::extension;
  else if (contains(n, "time") || contains(n, "zeit")) c.quantity = Quantity::time;
  return c;
}

std::string unit_cell(const std::string &cell)
{
  const std::string text = trim(cell);
  std::string       unit = text;
  if (text.size() >= 2 && ((text.front() == '(' && text.back() == ')') || (text.front() == '[' && text.back() == ']')))
    unit = trim(text.substr(1, text.size() - 2));
  return is_unit(unit) ? unit : "";
}

double si_factor(Quantity quantity, const std::string &unit)
{
  switch (quantity) {
  case Quantity::extension: return look_up(kLength, unit);
  case Quantity::force: return look_up(kForce, unit);
  case Quantity::stress: return look_up(kStress, unit);
  case Quantity::strain: return look_up(kStrain, unit);
  case Quantity::stretch: return look_up(kStretch, unit);
  case Quantity::time: return look_up(kTime, unit);
  case Quantity::none: return 0.0;
  }
  return 0.0;
}

std::string known_units(Quantity quantity)
{
  switch (quantity) {
  case Quantity::extension: return "m, mm, cm, um, in";
  case Quantity::force: return "N, kN, mN, lbf";
  case Quantity::stress: return "Pa, kPa, MPa, N/mm2, psi";
  case Quantity::strain: return "%, - or mm/mm";
  case Quantity::stretch: return "none or -";
  case Quantity::time: return "s, ms, min, h";
  case Quantity::none: return "";
  }
  return "";
}

const char *to_string(Quantity quantity)
{
  switch (quantity) {
  case Quantity::none: return "other";
  case Quantity::time: return "time";
  case Quantity::stretch: return "stretch";
  case Quantity::strain: return "strain";
  case Quantity::extension: return "extension";
  case Quantity::stress: return "stress";
  case Quantity::force: return "force";
  }
  return "other";
}

} // namespace bapd::fit
