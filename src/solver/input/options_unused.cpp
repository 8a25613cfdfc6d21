// Options that nothing read: a typo is refused with the nearest real name
// (CheckUnusedOptions), and a missing required option whose misspelling was given is
// pointed at (MisspeltHint). PETSc's own options may go unread.
#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "bapd/solver/input/option_suggest.hpp"
#include "bapd/solver/input/options.hpp"
#include "bapd/solver/input/options_reader.hpp"
#include "bapd/solver/input/scene_input.hpp"

namespace bapd {

namespace {

// PETSc's own run-time options, which may legitimately go unread (a TS type that
// ignores an option, -log_view read at the end, ...).
bool IsPetscOption(const std::string &name)
{
  static const char *const exact[]    = {"help", "h", "version", "info", "options_left", "nox", "nox_warning", "history", "checkstack",
                                         "objects_dump", "fp_trap", "no_signal_handler", "start_in_debugger", "stop_for_debugger",
                                         "display", "skip_petscrc", "petsc_ci", "use_gpu_aware_mpi", "memory_view", "x_virtual"};
  static const char *const prefixes[] = {"options_", "log_", "malloc", "on_error_", "info_", "ts_", "vec_", "mat_", "snes_", "ksp_",
                                         "pc_", "dm_", "viewer", "draw_", "saws_", "debugger_", "device_", "cuda", "hip", "sycl",
                                         "kokkos", "petsc", "is_", "sf_", "tao_", "mpi_", "check_pointer", "error_output", "memory_",
                                         "citations", "blas_", "omp_", "timeout", "sys_", "matload_", "pointer_", "fp_",
                                         "mg_levels_", "mg_coarse_"}; // PCMG's (and GAMG's) levels, read at the first solve
  for (const char *e : exact)
    if (name == e) return true;
  for (const char *p : prefixes)
    if (name.compare(0, std::char_traits<char>::length(p), p) == 0) return true;
  return false;
}

// "grip" for -load_grip_region: the name between a family's head and one of its
// suffixes (the longest that fits), else "".
std::string UndeclaredName(const std::string &name, const SetFamily &family)
{
  const std::string &head = family.head;
  if (name.compare(0, head.size(), head) != 0) return "";
  std::string found;
  for (const std::string &tail : family.suffixes) {
    if (name.size() > head.size() + tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0) {
      const std::string set = name.substr(head.size(), name.size() - head.size() - tail.size());
      if (found.empty() || set.size() < found.size()) found = set;
    }
  }
  return found;
}

// A YAML value written as a mapping (dx: {value: 0.001}) reaches PETSc as the option
// -body_dx_value. "in YAML, 'value' is nested ..." when `given` is a known option, an
// underscore and more; the longest such option is named. "" otherwise.
std::string NestedKeyHint(const std::string &given, const std::vector<std::string> &known)
{
  const std::string lower = Lower(given);
  std::string       parent;
  for (const std::string &option : known) {
    const std::string o = Lower(option);
    if (lower.size() > o.size() + 1 && lower.compare(0, o.size(), o) == 0 && lower[o.size()] == '_' && option.size() > parent.size())
      parent = option;
  }
  if (parent.empty()) return "";
  const std::string key = given.substr(parent.size() + 1);
  return "in YAML, '" + key + "' is nested under the key of " + parent + ", which takes one value: write key: 0.001, not key: {" + key +
         ": 0.001}";
}

std::string UnusedMessage(const std::string &name)
{
  const std::string suggestion = SuggestOption(name, KnownOptionNames());
  std::string       message    = name + " is not a bapd option.";
  for (const SetFamily &family : SetFamilies()) // (the options of a set that -load_sets, -probes or -body_shapes lacks)
    if (const std::string set = UndeclaredName(Lower(name), family); !set.empty()) {
      message += " '" + set + "' is not one of " + family.list_option + ": add it there, or fix the name.";
      break;
    }
  if (!suggestion.empty()) message += " Did you mean " + suggestion + "?";
  else if (std::string nested = NestedKeyHint(name, KnownOptionNames()); !nested.empty()) {
    nested[0] = 'I'; // "In YAML, ..." starts a sentence here
    message += " " + nested + ".";
  }
  return message;
}

} // namespace

// " (-body_widht was given: is it a misspelling of -body_width?)" when an option that
// nothing has read lies within typo distance of `option`, which is missing: a misspelt
// required option otherwise reads as a forgotten one. "" when there is none.
std::string MisspeltHint(const std::string &option)
{
  PetscInt    n      = 0;
  char      **names  = nullptr;
  char      **values = nullptr;
  std::string hint;
  if (PetscOptionsLeftGet(nullptr, &n, &names, &values)) return "";
  for (PetscInt i = 0; i < n && hint.empty(); ++i) {
    const std::string given = std::string("-") + names[i];
    if (Lower(given) != Lower(option) && !SuggestOption(given, {option}).empty())
      hint = " (" + given + " was given: is it a misspelling of " + option + "?)";
    else if (!NestedKeyHint(given, {option}).empty())
      hint = " (" + given + " was given: " + NestedKeyHint(given, {option}) + ")";
  }
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
  return hint;
}


PetscErrorCode CheckUnusedOptions(MPI_Comm comm)
{
  PetscInt    n      = 0;
  char      **names  = nullptr;
  char      **values = nullptr;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::vector<std::string> unused; // "-name", as the database holds it
  for (PetscInt i = 0; i < n; ++i)
    if (!IsPetscOption(Lower(names[i]))) unused.push_back(std::string("-") + names[i]);
  PetscCall(PetscOptionsLeftRestore(nullptr, &n, &names, &values));

  // An option is unused only if no rank read it: rank 0's list, kept where every rank
  // agrees, so that every rank reaches the same verdict.
  std::string joined;
  for (const std::string &u : unused) joined += u + '\n';
  int length = static_cast<int>(joined.size());
  PetscCallMPI(MPI_Bcast(&length, 1, MPI_INT, 0, comm));
  joined.resize(static_cast<std::size_t>(length));
  PetscCallMPI(MPI_Bcast(joined.data(), length, MPI_CHAR, 0, comm));
  std::vector<std::string> candidates;
  for (std::size_t start = 0; start < joined.size();) {
    const std::size_t end = joined.find('\n', start);
    candidates.push_back(joined.substr(start, end - start));
    start = end + 1;
  }
  std::vector<int> here(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) here[i] = std::find(unused.begin(), unused.end(), candidates[i]) != unused.end();
  if (!here.empty()) PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, here.data(), static_cast<int>(here.size()), MPI_INT, MPI_LAND, comm));

  std::string message;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (here[i]) message += (message.empty() ? "" : "\n") + UnusedMessage(candidates[i]);
  PetscCheck(message.empty(), comm, PETSC_ERR_USER, "%s (run with -help to list every option)", message.c_str());
  PetscFunctionReturn(0);
}

} // namespace bapd
