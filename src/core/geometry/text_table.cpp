// A comma- or blank-separated text table (text_table.hpp).
#include "bapd/core/geometry/text_table.hpp"

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

bool table_number(const std::string &token, double *value)
{
  char *end = nullptr;
  *value    = std::strtod(token.c_str(), &end);
  return end && *end == '\0' && end != token.c_str();
}

} // namespace bapd
