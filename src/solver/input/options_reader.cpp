// The options framework behind the scene: the OptionReader (well-formed values,
// named in the message, read through PETSc so that -help lists them), the registry of
// every name read, warnings, and the name checks of load sets and probes.
#include "bapd/solver/input/options_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>

#include "bapd/solver/input/options.hpp"
#include "bapd/solver/input/scene.hpp"

namespace bapd {

namespace {

std::vector<std::string> SplitList(const std::string &text)
{
  std::vector<std::string> items;
  if (text.empty()) return items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    items.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

// strtod/strtoll over the whole text, finite values only: what PETSc's own parsers
// accept for a plain number, so a text that passes here never trips them.
bool ParseReal(const std::string &text, double *value)
{
  if (text.empty()) return false;
  char        *end = nullptr;
  const double v   = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(v)) return false;
  *value = v;
  return true;
}

bool ParseInt(const std::string &text, PetscInt *value)
{
  if (text.empty()) return false;
  char           *end = nullptr;
  const long long v   = std::strtoll(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0') return false;
  if (v < std::numeric_limits<PetscInt>::min() || v > std::numeric_limits<PetscInt>::max()) return false;
  *value = static_cast<PetscInt>(v);
  return true;
}

// Load set and probe names become parts of option names (-load_NAME_region).
bool IsName(const std::string &name)
{
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return false;
  return std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// ---------------------------------------------------------------------------------
// Registry of every option name bapd reads (lower case -> spelling as documented),
// warnings of the last SceneFromOptions.

std::map<std::string, std::string> &Registry()
{
  static std::map<std::string, std::string> names;
  return names;
}

std::vector<std::string> &Warnings()
{
  static std::vector<std::string> warnings;
  return warnings;
}
} // namespace

std::string Lower(std::string s)
{
  for (char &c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string Format(const char *format, ...)
{
  va_list args, copy;
  va_start(args, format);
  va_copy(copy, args);
  const int   length = std::vsnprintf(nullptr, 0, format, copy);
  std::string text(length > 0 ? static_cast<std::size_t>(length) : 0, '\0');
  if (length > 0) std::vsnprintf(text.data(), text.size() + 1, format, args);
  va_end(copy);
  va_end(args);
  return text;
}

PetscErrorCode Warn(MPI_Comm comm, const std::string &message, bool loud)
{
  PetscFunctionBeginUser;
  Warnings().push_back(message);
  if (loud) PetscCall(PetscFPrintf(comm, PETSC_STDERR, "\nbapd: WARNING: %s\n\n", message.c_str()));
  else PetscCall(PetscFPrintf(comm, PETSC_STDERR, "bapd: warning: %s\n", message.c_str()));
  PetscFunctionReturn(0);
}

void ClearWarnings() { Warnings().clear(); }

const std::vector<std::string> &SceneWarnings() { return Warnings(); }

void RegisterOptionName(const std::string &name) { Registry().emplace(Lower(name), name); }

std::vector<std::string> KnownOptionNames()
{
  std::vector<std::string> known;
  for (const auto &entry : Registry()) known.push_back(entry.second);
  return known;
}

PetscErrorCode CheckNames(MPI_Comm comm, const std::vector<std::string> &names, const char *option, const char *what)
{
  PetscFunctionBeginUser;
  for (std::size_t i = 0; i < names.size(); ++i) {
    SceneCheck(IsName(names[i]), comm,
               "%s: %s name '%s' must start with a letter and hold only letters, digits and '_' (it becomes part of option names)",
               option, what, names[i].c_str());
    for (std::size_t j = 0; j < i; ++j)
      SceneCheck(Lower(names[i]) != Lower(names[j]), comm, "%s lists %s '%s' twice: give each %s a different name", option,
                 what, names[i].c_str(), what);
  }
  PetscFunctionReturn(0);
}

namespace {

bool IsReal(const std::string &text)
{
  double v = 0;
  return ParseReal(text, &v);
}
bool IsInt(const std::string &text)
{
  PetscInt v = 0;
  return ParseInt(text, &v);
}

// PETSc's reader of one number, by type (so that -help lists it with its default).
PetscErrorCode ReadNumber(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, double *value, PetscBool *flg)
{
  PetscReal v = *value;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal(name, help, "docs/options.md", *value, &v, flg));
  *value = v;
  PetscFunctionReturn(0);
}
PetscErrorCode ReadNumber(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, PetscInt *value, PetscBool *flg)
{
  return PetscOptionsInt(name, help, "docs/options.md", *value, value, flg);
}

} // namespace

template <class T>
PetscErrorCode OptionReader::Number(const char *name, const char *help, T *value, bool *set, bool (*parses)(const std::string &),
                                    const Wording &w)
{
  std::string text;
  bool        present = false;
  PetscFunctionBeginUser;
  PetscCall(Raw(name, &text, &present));
  const std::string full = Full(name);
  if (present && text.empty()) {
    Fail(Format("%s needs a value: %s, e.g. %s %s", full.c_str(), w.needs, full.c_str(), w.example));
    PetscFunctionReturn(0);
  }
  if (present && !parses(text)) {
    // strtod reads "inf" and "nan", which no option takes: say why they are refused.
    char        *end       = nullptr;
    const double v         = std::strtod(text.c_str(), &end);
    const bool   infinite  = end != text.c_str() && *end == '\0' && !std::isfinite(v);
    const char  *qualifier = infinite ? " finite" : "";
    Fail(Format("%s '%s' is not a%s %s: %s, e.g. %s %s", full.c_str(), text.c_str(), qualifier, w.kind, w.fix, full.c_str(),
                w.example));
    PetscFunctionReturn(0);
  }
  PetscBool flg = PETSC_FALSE;
  PetscCall(ReadNumber(items_, name, help, value, &flg));
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionReader::Real(const char *name, const char *help, double *value, bool *set, const char *example)
{
  return Number(name, help, value, set, IsReal, {"give a number in SI units", "number", "give one value in SI units", example});
}

PetscErrorCode OptionReader::Int(const char *name, const char *help, PetscInt *value, bool *set)
{
  return Number(name, help, value, set, IsInt, {"give a whole number", "whole number", "give an integer", "10"});
}

PetscErrorCode OptionReader::String(const char *name, const char *help, std::string *value, bool *set)
{
  PetscOptionItems *PetscOptionsObject = items_;
  std::string       text;
  bool              present = false;
  PetscFunctionBeginUser;
  PetscCall(Raw(name, &text, &present));
  char      buffer[PETSC_MAX_PATH_LEN];
  PetscBool flg = PETSC_FALSE;
  PetscCall(PetscStrncpy(buffer, value->c_str(), sizeof(buffer)));
  PetscCall(PetscOptionsString(name, help, "docs/options.md", value->c_str(), buffer, sizeof(buffer), &flg));
  if (flg) *value = buffer;
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionReader::Bool(const char *name, const char *help, bool *value)
{
  PetscOptionItems *PetscOptionsObject = items_;
  std::string       text;
  bool              present = false;
  PetscFunctionBeginUser;
  PetscCall(Raw(name, &text, &present));
  PetscBool v = *value ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(PetscOptionsBool(name, help, "docs/options.md", v, &v, nullptr));
  *value = v;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionReader::RealArray(const char *name, const char *help, std::vector<double> *values, bool *set)
{
  PetscOptionItems *PetscOptionsObject = items_;
  ListText          list;
  PetscFunctionBeginUser;
  PetscCall(List(name, &list));
  for (const std::string &item : list.items) {
    double parsed = 0;
    if (!ParseReal(item, &parsed)) {
      Fail(Format("%s '%s': '%s' is not a number: give comma-separated numbers in SI units (YAML: a list [a, b, ...])",
                  Full(name).c_str(), list.text.c_str(), item.c_str()));
      PetscFunctionReturn(0);
    }
  }
  // PETSc reads at most n values: size the buffer from the text. Absent, it holds
  // the current values, which -help shows.
  std::vector<PetscReal> buffer(list.present ? list.items.size() : values->size());
  if (!list.present) std::copy(values->begin(), values->end(), buffer.begin());
  PetscInt n = static_cast<PetscInt>(buffer.size());
  buffer.push_back(0.0); // never empty: -help prints the first entry
  PetscBool flg = PETSC_FALSE;
  PetscCall(PetscOptionsRealArray(name, help, "docs/options.md", buffer.data(), &n, &flg));
  if (flg) values->assign(buffer.begin(), buffer.begin() + n);
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

PetscErrorCode OptionReader::StringArray(const char *name, const char *help, std::vector<std::string> *values, bool *set)
{
  PetscOptionItems *PetscOptionsObject = items_;
  ListText          list;
  PetscFunctionBeginUser;
  PetscCall(List(name, &list));
  std::vector<char *> buffer(list.items.size() + 1, nullptr);
  PetscInt            n   = static_cast<PetscInt>(list.items.size());
  PetscBool           flg = PETSC_FALSE;
  PetscCall(PetscOptionsStringArray(name, help, "docs/options.md", buffer.data(), &n, &flg));
  if (flg) {
    values->clear();
    for (PetscInt i = 0; i < n; ++i) {
      values->push_back(buffer[i] ? buffer[i] : "");
      PetscCall(PetscFree(buffer[i]));
    }
  }
  if (set) *set = flg;
  PetscFunctionReturn(0);
}

std::string OptionReader::Full(const char *name) const
{
  return std::string("-") + (items_->prefix ? items_->prefix : "") + (name + 1);
}

void OptionReader::Fail(const std::string &message)
{
  if (problem_.empty()) problem_ = message;
}

PetscErrorCode ReadOptionBlock(MPI_Comm comm, const char *prefix, const char *title,
                               const std::function<PetscErrorCode(OptionReader &)> &read)
{
  std::string problem;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, prefix, title, "bapd");
  {
    OptionReader r(PetscOptionsObject);
    PetscCall(read(r));
    problem = r.problem();
  }
  PetscOptionsEnd();
  BAPD_CHECK_READ(problem, comm);
  PetscFunctionReturn(0);
}

// Registers the name; returns the text the database holds for it.
PetscErrorCode OptionReader::Raw(const char *name, std::string *text, bool *present)
{
  PetscFunctionBeginUser;
  RegisterOptionName(Full(name));
  const char *value = nullptr;
  PetscBool   flg   = PETSC_FALSE;
  PetscCall(PetscOptionsFindPair(items_->options, items_->prefix, name, &value, &flg));
  *present = flg;
  *text    = value ? value : "";
  PetscFunctionReturn(0);
}

PetscErrorCode OptionReader::List(const char *name, ListText *list)
{
  PetscFunctionBeginUser;
  PetscCall(Raw(name, &list->text, &list->present));
  list->items = SplitList(list->text);
  PetscFunctionReturn(0);
}

} // namespace bapd
