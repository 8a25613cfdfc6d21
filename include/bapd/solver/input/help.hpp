#pragma once
// -help that helps: `bapd -help` (also -h, --help) lists bapd's own options alone,
// grouped as the scene reads them, each with its unit, its current value (the scene's,
// or the default) and "required" where there is no default; `bapd -help all` adds
// PETSc's options (time stepper, logging, viewers) in PETSc's own format.
//
// PETSc prints the help of an options block while the block is read, when -help is
// in the options database: bapd keeps -help out of the database during
// PetscInitialize (which would otherwise print PETSc's 58 generic lines), puts it in
// afterwards, and tidies each line through PetscHelpPrintf, PETSc's hook for help
// output.
#include <petscsys.h>

namespace bapd {

enum class HelpMode { none, bapd, all };

// Before PetscInitialize: finds -help [all], -h or --help in argv, records the mode,
// and rewrites argv so that PETSc sees -help only for `all` (the bapd mode is
// switched on after initialisation by BeginHelp).
HelpMode TakeHelpArguments(int *argc, char ***argv);

// After PetscInitialize (collective): for the bapd mode, prints the usage lines,
// installs the tidying PetscHelpPrintf and sets -help in the database.
PetscErrorCode BeginHelp(MPI_Comm comm);

// The mode TakeHelpArguments found (HelpMode::none in tests and tools that call
// SceneFromOptions without main: they see -help through the database as usual).
HelpMode CurrentHelpMode();

// PETSc's help line for one option, as bapd prints it: "  -body_width <required>  Sheet
// width along x [m]" instead of "  -body_width <0. : 0.>: Sheet width along x [m]
// (required) (docs/options.md)". Lines that are not an option's are returned as they are.
// Exposed for the unit test.
std::string TidyHelpLine(const std::string &line);

} // namespace bapd
