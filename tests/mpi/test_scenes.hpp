#pragma once
// Small scenes shared by the solver tests, set as PETSc options.
#include <petscsys.h>
#include <string>

namespace bapd_test {

// Clears the options database and inserts the given options.
inline PetscErrorCode SetOptions(const std::string &options)
{
  PetscFunctionBegin;
  PetscCall(PetscOptionsClear(nullptr));
  PetscCall(PetscOptionsInsertString(nullptr, options.c_str()));
  PetscFunctionReturn(0);
}

// `dir` with the rank count: ctest may run a test's rank counts side by side, and a
// run owns its output directory (a second run into it is refused: output_directory.hpp).
inline std::string OutputDirPerRankCount(const std::string &dir)
{
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return dir + "_np" + std::to_string(size);
}

// A free 20 x 20 mm Gent sheet, 1 mm grid, a hole and a notch so that the families
// near the cuts are irregular. No loads: tests set the state themselves.
inline std::string FreeSheetScene(const std::string &output_dir)
{
  return "-body_width 0.02 -body_height 0.02 -body_thickness 0.001 -body_dx 0.001 "
         "-body_holes 0.006,0.013,0.0025 -body_notches 0.012,0.0065,0.02,0.0065 "
         "-horizon_factor 3.015 -material_model gent -material_mu 4.55e3 -material_Jm 162.6 "
         "-material_bulk_ratio 100 -material_density 1000 -end_time 1 -output_dir " +
         OutputDirPerRankCount(output_dir) + " -output_interval 1000000 -progress_interval 1000000";
}

} // namespace bapd_test
