// Cells, numbers and header names of a test export (export_table.hpp).
#include "export_table.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iterator>
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

// Each quantity's name, the units bapd-fit reads as its messages list them, and their
// factors to SI.
struct QuantityUnits {
  Quantity    quantity;
  const char *name, *listed;
  const Unit *units;
  std::size_t count;
};
const QuantityUnits kQuantities[] = {
    {Quantity::none, "other", "", nullptr, 0},
    {Quantity::time, "time", "s, ms, min, h", kTime, std::size(kTime)},
    {Quantity::stretch, "stretch", "none or -", kStretch, std::size(kStretch)},
    {Quantity::strain, "strain", "%, - or mm/mm", kStrain, std::size(kStrain)},
    {Quantity::extension, "extension", "m, mm, cm, um, in", kLength, std::size(kLength)},
    {Quantity::stress, "stress", "Pa, kPa, MPa, N/mm2, psi", kStress, std::size(kStress)},
    {Quantity::force, "force", "N, kN, mN, lbf", kForce, std::size(kForce)},
};
const QuantityUnits &units_of(Quantity quantity)
{
  for (const QuantityUnits &q : kQuantities)
    if (q.quantity == quantity) return q;
  return kQuantities[0];
}

double look_up(const QuantityUnits &quantity, const std::string &unit)
{
  const std::string u = lower(trim(unit));
  for (std::size_t k = 0; k < quantity.count; ++k)
    if (u == quantity.units[k].name) return quantity.units[k].factor;
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

double si_factor(Quantity quantity, const std::string &unit) { return look_up(units_of(quantity), unit); }

std::string known_units(Quantity quantity) { return units_of(quantity).listed; }

const char *to_string(Quantity quantity) { return units_of(quantity).name; }

} // namespace bapd::fit
