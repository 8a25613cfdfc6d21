#pragma once
// The options framework behind the scene (internal to src/solver/scene*.cpp and
// options_*.cpp): one OptionReader per PetscOptionsBegin block, the registry of names
// it fills, warnings, and the message helpers every section shares.
#include <petscsys.h>
#include <functional>
#include <string>
#include <variant>
#include <vector>

namespace bapd {

// Lower-case copy (option names and choices are case-insensitive).
std::string Lower(std::string s);
// printf into a std::string (the C library's %g: PETSc's printf writes 4550 as "4550.").
std::string Format(const char *format, ...) __attribute__((format(printf, 1, 2)));

// Records a warning for SceneWarnings() and prints it on rank 0, to stderr; `loud`
// sets it off with blank lines and capitals for a warning that may cost the run.
PetscErrorCode Warn(MPI_Comm comm, const std::string &message, bool loud = false);
// Forgets the warnings of the previous SceneFromOptions.
void ClearWarnings();

// Every option name registered so far, as documented (sorted case-insensitively).
std::vector<std::string> KnownOptionNames();

// Rejects names (of load sets, probes) that cannot be part of an option name or that
// repeat, naming `option` (the list they came from) and `what` they name.
PetscErrorCode CheckNames(MPI_Comm comm, const std::vector<std::string> &names, const char *option, const char *what);

// " (-body_widht was given: is it a misspelling of -body_width?)" when an option that
// nothing has read lies within typo distance of `option`, which is missing: a misspelt
// required option otherwise reads as a forgotten one. "" when there is none.
std::string MisspeltHint(const std::string &option);

// Reading: one OptionReader per PetscOptionsBegin block. Each call registers the
// name, checks that the text is well formed (so a malformed number is reported
// naming its option, not as PETSc's "Input string has no numeric value"), and then
// reads it through PETSc so that -help lists it. The first malformed value is kept
// and reported after the block (BAPD_CHECK_READ).
class OptionReader {
public:
  explicit OptionReader(PetscOptionItems *items) : items_(items) {}
  const std::string &problem() const { return problem_; }

  // `example`: a valid value shown in the message for a malformed one (default 0.01).
  PetscErrorCode Real(const char *name, const char *help, double *value, bool *set = nullptr, const char *example = "0.01");
  PetscErrorCode Int(const char *name, const char *help, PetscInt *value, bool *set = nullptr);
  PetscErrorCode String(const char *name, const char *help, std::string *value, bool *set = nullptr);
  PetscErrorCode Bool(const char *name, const char *help, bool *value);
  PetscErrorCode RealArray(const char *name, const char *help, std::vector<double> *values, bool *set = nullptr);
  PetscErrorCode StringArray(const char *name, const char *help, std::vector<std::string> *values, bool *set = nullptr);

private:
  std::string    Full(const char *name) const; // "-" + prefix + name without its '-'
  void           Fail(const std::string &message);
  // How a malformed scalar is described: "NAME needs a value: <needs>, e.g. NAME
  // <example>" or "NAME 'TEXT' is not a [finite] <kind>: <fix>, e.g. NAME <example>".
  struct Wording {
    const char *needs, *kind, *fix, *example;
  };
  // Reads one number; an empty or malformed text is recorded, worded by `wording`.
  template <class T>
  PetscErrorCode Number(const char *name, const char *help, T *value, bool *set, bool (*parses)(const std::string &),
                        const Wording &wording);
  PetscErrorCode Raw(const char *name, std::string *text, bool *present);
  // The text of a list option and its comma-separated items (none if absent).
  struct ListText {
    std::string              text;
    std::vector<std::string> items;
    bool                     present = false;
  };
  PetscErrorCode List(const char *name, ListText *list);

  PetscOptionItems *items_;
  std::string       problem_;
};

// A row's text kept as given in `Flags`, the record of what was given: a choice that the
// section's check parses and names in its message (-solver, -failure_softening).
template <class Flags> struct GivenText {
  std::string Flags::*text;
};

// One row of an option table: the option's name (after the set's prefix for a named
// set: "-region" of -load_NAME_region), its help, where its value goes in the section's
// record (or, GivenText, as given in the record of what was given) and, if it has one,
// the flag (in `Flags`) that says it was given; `example`: a valid value for the message
// on a malformed real. A section's block is one table whatever record a row fills.
// A block of options is read from tables of rows, the top-level sections' (kStepOptions,
// kOutputOptions, ... in scene_*.cpp) as the named sets' (kLoadSetOptions,
// kProbeOptions, kShapeOptions): ReadOptionRows reads one in order, so that -help lists
// it so, and the unused-option check and -help take the names from it (SetFamily,
// scene_input.hpp).
template <class Input, class Flags = Input> struct OptionRow {
  const char *name;
  const char *help;
  std::variant<std::string Input::*, double Input::*, PetscInt Input::*, std::vector<double> Input::*, bool Input::*,
               std::vector<std::string> Input::*, PetscBool Input::*, GivenText<Flags>>
              value;
  bool Flags::*given   = nullptr;
  const char *example = "0.01";
};
template <class Input, class Flags = Input> using OptionTable = std::vector<OptionRow<Input, Flags>>;

// Reads every option of `table` into *input through `r`; the given flags into *flags.
template <class Input, class Flags>
PetscErrorCode ReadOptionRows(OptionReader &r, const OptionTable<Input, Flags> &table, Input *input, Flags *flags)
{
  PetscFunctionBeginUser;
  for (const OptionRow<Input, Flags> &o : table) {
    bool given = false;
    if (auto text = std::get_if<std::string Input::*>(&o.value)) PetscCall(r.String(o.name, o.help, &(input->**text), &given));
    else if (auto real = std::get_if<double Input::*>(&o.value)) PetscCall(r.Real(o.name, o.help, &(input->**real), &given, o.example));
    else if (auto whole = std::get_if<PetscInt Input::*>(&o.value)) PetscCall(r.Int(o.name, o.help, &(input->**whole), &given));
    else if (auto reals = std::get_if<std::vector<double> Input::*>(&o.value)) PetscCall(r.RealArray(o.name, o.help, &(input->**reals), &given));
    else if (auto names = std::get_if<std::vector<std::string> Input::*>(&o.value))
      PetscCall(r.StringArray(o.name, o.help, &(input->**names), &given));
    else if (auto flag = std::get_if<bool Input::*>(&o.value)) PetscCall(r.Bool(o.name, o.help, &(input->**flag)));
    else if (auto kept = std::get_if<GivenText<Flags>>(&o.value)) PetscCall(r.String(o.name, o.help, &(flags->*(kept->text)), &given));
    else {
      PetscBool &petsc = input->*std::get<PetscBool Input::*>(o.value);
      bool       value = petsc;
      PetscCall(r.Bool(o.name, o.help, &value));
      petsc = value ? PETSC_TRUE : PETSC_FALSE;
    }
    if (o.given) flags->*o.given = given;
  }
  PetscFunctionReturn(0);
}
template <class Input> PetscErrorCode ReadOptionRows(OptionReader &r, const OptionTable<Input> &table, Input *input)
{
  return ReadOptionRows(r, table, input, input);
}

// The names of a set's options as suffixes of the set's name: "_region", ...
template <class Input> std::vector<std::string> OptionRowSuffixes(const OptionTable<Input> &table)
{
  std::vector<std::string> suffixes;
  for (const OptionRow<Input> &o : table) suffixes.push_back(std::string("_") + (o.name + 1));
  return suffixes;
}

// One PetscOptionsBegin block titled `title` (options prefixed by `prefix`, or
// none): `read` reads its options through the OptionReader (PETSc may run it more
// than once, e.g. for -help); the first malformed value is then reported.
PetscErrorCode ReadOptionBlock(MPI_Comm comm, const char *prefix, const char *title,
                               const std::function<PetscErrorCode(OptionReader &)> &read);

// A top-level block that is one table: its rows into *input, their given flags into *flags.
template <class Input, class Flags>
PetscErrorCode ReadOptionTable(MPI_Comm comm, const char *title, const OptionTable<Input, Flags> &table, Input *input, Flags *flags)
{
  return ReadOptionBlock(comm, nullptr, title, [&](OptionReader &r) { return ReadOptionRows(r, table, input, flags); });
}
template <class Input> PetscErrorCode ReadOptionTable(MPI_Comm comm, const char *title, const OptionTable<Input> &table, Input *input)
{
  return ReadOptionTable(comm, title, table, input, input);
}

} // namespace bapd

// PetscCheck with the message formatted by the C library: PETSc's printf writes
// 4550 as "4550.", which reads oddly in a message about an option value.
#define SceneCheck(cond, comm, ...) PetscCheck(cond, comm, PETSC_ERR_USER, "%s", ::bapd::Format(__VA_ARGS__).c_str())

#define BAPD_CHECK_READ(reader_problem, comm) \
  PetscCheck((reader_problem).empty(), comm, PETSC_ERR_USER, "%s", (reader_problem).c_str())
