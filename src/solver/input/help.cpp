// -help: bapd's options alone, tidied (help.hpp).
#include "bapd/solver/input/help.hpp"

#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace bapd {

namespace {

HelpMode mode = HelpMode::none;

// Where -help lines come from in PETSc 3.18 (src/sys/objects/aoptions.c):
//   reals   "  -NAME <CURRENT : DEFAULT>: TEXT (MAN)"
//   others  "  -NAME <now CURRENT : formerly DEFAULT>: TEXT (MAN)"
//   bools   "  -NAME: <CURRENT : DEFAULT> TEXT (MAN)"
//   lists   "  -NAME <FIRST>: TEXT (MAN)" (the first entry, or string1,string2,...)
struct OptionLine {
  std::string name, current, fallback, text;
  bool        list = false;
};

bool ParseOptionLine(const std::string &line, OptionLine *o)
{
  if (line.compare(0, 3, "  -") != 0) return false;
  const std::size_t open = line.find('<'), close = line.find('>', open == std::string::npos ? 0 : open);
  if (open == std::string::npos || close == std::string::npos) return false;
  o->name = line.substr(2, open - 2);
  while (!o->name.empty() && (o->name.back() == ' ' || o->name.back() == ':')) o->name.pop_back();
  if (o->name.find(' ') != std::string::npos) return false;
  std::string value = line.substr(open + 1, close - open - 1);
  std::size_t rest  = close + 1;
  if (rest < line.size() && line[rest] == ':') ++rest;
  while (rest < line.size() && line[rest] == ' ') ++rest;
  o->text = line.substr(rest);
  while (!o->text.empty() && (o->text.back() == '\n' || o->text.back() == ' ')) o->text.pop_back();
  const char *man = " (docs/options.md)";
  if (o->text.size() >= std::strlen(man) && o->text.compare(o->text.size() - std::strlen(man), std::string::npos, man) == 0)
    o->text.resize(o->text.size() - std::strlen(man));
  const std::size_t colon = value.find(" : ");
  if (colon == std::string::npos) {
    o->list    = true;
    o->current = value;
    return true;
  }
  o->current  = value.substr(0, colon);
  o->fallback = value.substr(colon + 3);
  if (o->current.compare(0, 4, "now ") == 0) o->current.erase(0, 4);
  if (o->fallback.compare(0, 9, "formerly ") == 0) o->fallback.erase(0, 9);
  return true;
}

// PETSc's %g writes 4550 as "4550." and 0 as "0.".
std::string Plain(std::string v)
{
  if (v.size() > 1 && v.back() == '.') v.pop_back();
  if (v == "TRUE") return "true";
  if (v == "FALSE") return "false";
  return v;
}

PetscErrorCode TidyHelpPrintf(MPI_Comm comm, const char format[], ...)
{
  va_list args, copy;
  va_start(args, format);
  va_copy(copy, args);
  const int   length = std::vsnprintf(nullptr, 0, format, copy);
  std::string text(length > 0 ? (std::size_t)length : 0, '\0');
  if (length > 0) std::vsnprintf(text.data(), text.size() + 1, format, args);
  va_end(copy);
  va_end(args);
  // PETSc writes a list option's line in pieces (one call per entry): tidy whole lines.
  static std::string pending;
  pending += text;
  std::string out;
  for (std::size_t end; (end = pending.find('\n')) != std::string::npos; pending.erase(0, end + 1))
    out += TidyHelpLine(pending.substr(0, end + 1));
  return out.empty() ? 0 : PetscPrintf(comm, "%s", out.c_str());
}

} // namespace

std::string TidyHelpLine(const std::string &line)
{
  OptionLine o;
  if (!ParseOptionLine(line, &o)) {
    // Block titles: a blank line between groups instead of PETSc's dashes.
    if (line.compare(0, 10, "----------") == 0) return "\n";
    // PETSc's viewer syntax, listed at PetscFinalize for -log_view: -help all has it.
    if (line.find("(PetscOptionsGetViewer)") != std::string::npos || line.compare(0, 8, "Viewer (") == 0) return "";
    return line;
  }
  std::string value;
  const char *required = " (required)";
  if (const std::size_t at = o.text.find(required); at != std::string::npos) {
    o.text.erase(at, std::strlen(required));
    value = (o.current.empty() || Plain(o.current) == "0") ? "required" : Plain(o.current);
  } else if (o.list) {
    // A real list shows its entries (a lone 0 is PETSc's placeholder for none given);
    // a string list shows PETSc's placeholder, which says nothing.
    value = o.current == "string1,string2,..." ? "names" : o.current;
    for (std::size_t dot; (dot = value.find(".,")) != std::string::npos;) value.erase(dot, 1);
    value = Plain(value);
    if (value == "0") value = "none";
  }
  else {
    value = Plain(o.current);
    if (value.empty()) value = "none";
    const std::string fallback = Plain(o.fallback);
    if (fallback != value && !(fallback.empty() && value == "none")) value += ", default " + (fallback.empty() ? std::string("none") : fallback);
  }
  std::string head = "  " + o.name + " <" + value + ">";
  if (head.size() < 40) head.append(40 - head.size(), ' ');
  else head += "  ";
  return head + o.text + "\n";
}

HelpMode TakeHelpArguments(int *argc, char ***argv)
{
  char           **a = *argv;
  std::vector<int> keep;
  mode = HelpMode::none;
  for (int k = 0; k < *argc; ++k) {
    const bool help = k > 0 && (!std::strcmp(a[k], "-help") || !std::strcmp(a[k], "-h") || !std::strcmp(a[k], "--help"));
    if (!help) {
      keep.push_back(k);
      continue;
    }
    const bool all = k + 1 < *argc && !std::strcmp(a[k + 1], "all");
    if (all) {
      mode = HelpMode::all; // PETSc's own -help, which takes no value
      static char petsc_help[] = "-help";
      a[k]                     = petsc_help;
      keep.push_back(k++);
    } else if (mode != HelpMode::all) mode = HelpMode::bapd;
  }
  for (std::size_t k = 0; k < keep.size(); ++k) a[k] = a[keep[k]];
  *argc    = (int)keep.size();
  a[*argc] = nullptr;
  return mode;
}

PetscErrorCode BeginHelp(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  if (mode != HelpMode::bapd) PetscFunctionReturn(0);
  PetscCall(PetscPrintf(comm, "bapd: bond-associated NOSB peridynamics for soft materials (hydrogels)\n"
                              "Usage: mpiexec -n N bapd -options_file_yaml SCENE.yaml [-option value ...]\n"
                              "       ./run_mpi.sh -n N SCENE.yaml [-option value ...]\n"
                              "Options of bapd, by group, with units and <current value> (the scene's, if one is given, else the "
                              "default). docs/options.md explains each.\n"
                              "bapd -help all also lists PETSc's options (time stepper -ts_*, -log_view, viewers).\n"));
  PetscHelpPrintf = TidyHelpPrintf;
  PetscCall(PetscOptionsSetValue(nullptr, "-help", nullptr));
  PetscFunctionReturn(0);
}

HelpMode CurrentHelpMode() { return mode; }

} // namespace bapd
