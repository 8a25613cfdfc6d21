#pragma once
// A number as printf's %g gives it: bapd-fit's notes, reports and YAML print every
// value this way, so the digits a file shows are the digits another file reads back.
#include <cstdio>
#include <string>

namespace bapd::fit {

inline std::string number_text(double v, int digits)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

} // namespace bapd::fit
