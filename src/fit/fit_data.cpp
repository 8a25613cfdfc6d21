// Reading and checking one test curve (fit_data.hpp).
#include "fit_data.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "fit_error.hpp"

namespace bapd::fit {
namespace {

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
std::vector<std::string> split(const std::string &line)
{
  std::vector<std::string> out;
  std::stringstream        ss(line);
  std::string              item;
  while (std::getline(ss, item, ',')) out.push_back(trim(item));
  return out;
}
bool ends_with(const std::string &s, const std::string &tail)
{
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

} // namespace

bool parse_mode(const std::string &text, LoadMode &mode)
{
  std::string t = lower(trim(text));
  std::replace(t.begin(), t.end(), '-', '_');
  std::replace(t.begin(), t.end(), ' ', '_');
  for (LoadMode m : {LoadMode::uniaxial, LoadMode::pure_shear, LoadMode::equibiaxial})
    if (t == to_string(m)) {
      mode = m;
      return true;
    }
  return false;
}

Curve read_curve(const std::string &path, const std::string &mode_tag)
{
  std::ifstream in(path);
  if (!in) throw FitError(path + ": cannot open the data file; give CSV files of stretch and nominal stress");
  Curve       c;
  c.file = path;
  std::string file_mode, line;
  int         stretch_col = -1, stress_col = -1, line_no = 0;
  double      unit = 0.0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = trim(line);
    if (t.empty()) continue;
    if (t[0] == '#') {
      const std::string body = lower(trim(t.substr(1)));
      if (body.rfind("mode:", 0) == 0) file_mode = trim(t.substr(t.find(':') + 1));
      continue;
    }
    const std::vector<std::string> cells = split(t);
    if (stretch_col < 0) { // the header
      for (int i = 0; i < static_cast<int>(cells.size()); ++i) {
        const std::string name = lower(cells[i]);
        if (name.find("stretch") != std::string::npos && stretch_col < 0) stretch_col = i;
        if (ends_with(name, "stress_kpa")) stress_col = i, unit = 1e3;
        else if (ends_with(name, "stress_pa")) stress_col = i, unit = 1.0;
      }
      if (stretch_col < 0 || stress_col < 0)
        throw FitError(path + ":" + std::to_string(line_no) + ": the header '" + t +
                       "' needs a stretch column and a stress column named with its unit, e.g. stretch,nominal_stress_kPa "
                       "(or ..._stress_Pa)");
      continue;
    }
    const int need = std::max(stretch_col, stress_col);
    if (static_cast<int>(cells.size()) <= need)
      throw FitError(path + ":" + std::to_string(line_no) + ": '" + t + "' has too few columns for the header");
    double v[2];
    int    cols[2] = {stretch_col, stress_col};
    for (int k = 0; k < 2; ++k) {
      char *end = nullptr;
      v[k]      = std::strtod(cells[cols[k]].c_str(), &end);
      if (cells[cols[k]].empty() || *end != '\0' || !std::isfinite(v[k]))
        throw FitError(path + ":" + std::to_string(line_no) + ": '" + cells[cols[k]] + "' is not a number");
    }
    c.stretch.push_back(v[0]);
    c.stress_Pa.push_back(v[1] * unit);
  }
  const std::string mode_text = mode_tag.empty() ? file_mode : mode_tag;
  if (mode_text.empty())
    throw FitError(path + ": which test is it? add a line '# mode: uniaxial' (or pure_shear, equibiaxial) or tag the "
                          "file on the command line, e.g. pure_shear:" + path);
  if (!parse_mode(mode_text, c.mode))
    throw FitError(path + ": mode '" + mode_text + "' is not a test: choose uniaxial, pure_shear or equibiaxial");
  if (c.stretch.size() < 2) throw FitError(path + ": " + std::to_string(c.stretch.size()) + " data point(s); a curve needs at least 2");
  for (std::size_t i = 0; i < c.stretch.size(); ++i) {
    std::ostringstream at;
    at << path << ": point " << i + 1 << " (stretch " << c.stretch[i] << ")";
    if (!(c.stretch[i] > 1.0))
      throw FitError(at.str() + ": a " + to_string(c.mode) +
                     " test in tension has stretches > 1; drop the point at rest and any compression");
    if (i > 0 && !(c.stretch[i] > c.stretch[i - 1]))
      throw FitError(at.str() + ": the stretch must increase strictly down the file (loading branch only; sort it, "
                                "drop repeated or unloading points)");
    if (c.stress_Pa[i] < 0.0)
      throw FitError(at.str() + ": negative nominal stress " + std::to_string(c.stress_Pa[i]) +
                     " Pa in tension; check the sign and the offset of the load cell");
  }
  return c;
}

} // namespace bapd::fit
