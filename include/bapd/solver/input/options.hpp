#pragma once
// The names of every option bapd reads, so that an option nobody read (a typo) is
// refused with the nearest real name. Included by scene.hpp.
#include <petscsys.h>
#include <string>

namespace bapd {

// Rejects options that nothing read (a typo), suggesting the nearest known name.
// Call once every component has read its options.
PetscErrorCode CheckUnusedOptions(MPI_Comm comm);

// Adds an option name ("-integrator_foo") to the names CheckUnusedOptions suggests
// from. Every option SceneFromOptions reads is registered already.
void RegisterOptionName(const std::string &name);

} // namespace bapd
