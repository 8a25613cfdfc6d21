// A comma- or blank-separated text table (text_table.hpp).
#include "bapd/core/geometry/text_table.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

namespace bapd {

bool next_table_line(std::istream &in, bool header, long *number, std::string *trimmed)
{
  std::string line;
  while (std::getline(in, line)) {
    ++*number;
    *trimmed = line;
    trimmed->erase(0, trimmed->find_first_not_of(" \t\r"));
    if (trimmed->empty()) continue;
    if (header) {
      if ((*trimmed)[0] == '#') trimmed->erase(0, 1);
    } else if ((*trimmed)[0] == '#') continue;
    return true;
  }
  return false;
}

std::vector<std::string> table_tokens(const std::string &line, bool lower)
{
  std::vector<std::string> out;
  std::string              token;
  for (char c : line) {
    if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
      if (!token.empty()) out.push_back(token), token.clear();
    } else token += lower ? static_cast<char>(std::tolower(static_cast<unsigned char>(c))) : c;
  }
  if (!token.empty()) out.push_back(token);
  return out;
}

namespace {

// The column of each of columns in header (-1 where none is); "" or the lower-case name
// of a column given twice.
std::string find_columns(const std::vector<std::string> &header, const std::vector<std::string> &columns, std::vector<int> *at)
{
  at->assign(columns.size(), -1);
  for (std::size_t c = 0; c < header.size(); ++c) {
    std::string name = header[c];
    for (char &ch : name) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    for (std::size_t k = 0; k < columns.size(); ++k) {
      bool named = false; // name is one of the '|'-separated names of columns[k]
      for (std::size_t from = 0; !named && from <= columns[k].size();) {
        const std::size_t to = std::min(columns[k].find('|', from), columns[k].size());
        named                = columns[k].compare(from, to - from, name) == 0;
        from                 = to + 1;
      }
      if (!named) continue;
      if ((*at)[k] >= 0) return name;
      (*at)[k] = static_cast<int>(c);
    }
  }
  return "";
}

std::string first_name(const std::string &aliases) { return aliases.substr(0, aliases.find('|')); }

} // namespace

std::string table_header(const std::string &file, long line, const std::vector<std::string> &header, const std::string &quoted,
                         const std::vector<std::string> &columns, std::size_t required, std::vector<int> *at)
{
  // "x, y, z and volume", "x, y, z, volume and optionally block_id", "x,y,z,volume"
  std::string listed, example, optional;
  for (std::size_t k = 0; k < required; ++k) {
    listed += (k == 0 ? "" : k + 1 == required ? " and " : ", ") + first_name(columns[k]);
    example += (k == 0 ? "" : ",") + first_name(columns[k]);
  }
  for (std::size_t k = required; k < columns.size(); ++k) optional += (k == required ? "" : ", ") + first_name(columns[k]);
  const std::string where = "'" + file + "', line " + std::to_string(line) + ": ";
  double            value;
  if (!header.empty() && table_number(header[0], &value)) {
    std::string names;
    for (std::size_t k = 0; k < required; ++k) names += (k == 0 ? "" : ", ") + first_name(columns[k]);
    return where + "the first line must name the columns (" + names + " and optionally " + optional + ", e.g. '" + example +
           "'), not hold numbers";
  }
  const std::string twice = find_columns(header, columns, at);
  if (!twice.empty()) return where + "the header names column '" + twice + "' twice";
  for (std::size_t k = 0; k < required; ++k)
    if ((*at)[k] < 0)
      return where + "the header " + (quoted.empty() ? "" : "'" + quoted + "' ") + "names no column '" + first_name(columns[k]) +
             "': the columns must include " + listed + " (" + optional + " optional), e.g. '" + example + "'";
  return "";
}

bool table_number(const std::string &token, double *value)
{
  char *end = nullptr;
  *value    = std::strtod(token.c_str(), &end);
  return end && *end == '\0' && end != token.c_str();
}

} // namespace bapd
