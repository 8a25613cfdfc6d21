#pragma once
// The output section's records that the writers read: field files (-output_fields*,
// fields.hpp) and checkpoints (-checkpoint_*, -restart*, checkpoint.hpp). Read and
// checked with the scene (scene_output.cpp).
#include <petscsys.h>

#include <string>

namespace bapd {

// The positions the XDMF draws the points at.
enum class FieldGeometry { current, reference };

// -output_fields, -output_fields_interval, -output_fields_geometry.
struct FieldOptions {
  PetscBool     enabled  = PETSC_FALSE;
  PetscInt      interval = 0; // steps between files; 0: every end time / 20 of simulated time (cadence.hpp)
  FieldGeometry geometry = FieldGeometry::current;
};

// -checkpoint_interval, -checkpoint_on_error, -restart, -restart_discard_newer.
struct CheckpointOptions {
  std::string interval;            // -checkpoint_interval as given: steps or a wall-clock time (the two below)
  PetscInt    step_interval = 0;   // steps between checkpoints (0: none)
  double      wall_interval = 0;   // wall-clock seconds between checkpoints (0: none)
  PetscBool   on_error      = PETSC_TRUE;
  std::string restart;             // checkpoint to continue from ("" for a fresh run)
  PetscBool   discard_newer = PETSC_FALSE; // a restart may drop newer results in its output directory (output_directory.hpp)
  bool periodic() const { return step_interval > 0 || wall_interval > 0; }
};

} // namespace bapd
