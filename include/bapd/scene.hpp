#pragma once
// A scene: everything a run needs, read from PETSc options (a YAML options file
// given with -options_file_yaml, every value overridable on the command line).
// SI units throughout. See docs/options.md for the full list.
#include <petscsys.h>
#include <string>
#include <vector>

#include "bapd/body.hpp"
#include "bapd/material.hpp"

namespace bapd {

// Piecewise-linear applied stretch lambda(t) through the knots (time[k], stretch[k]);
// ramps and holds are just knots. Before the first knot lambda = stretch[0], after the
// last one it stays at the last value.
struct Schedule {
  std::vector<double> time, stretch;
  double              stretch_at(double t) const;
  double              rate_at(double t) const; // d lambda / dt (right derivative)
  double              end_time() const { return time.empty() ? 0.0 : time.back(); }
};

enum class ComponentLoad { free, fixed, stretch };

// A named set of points held by a grip. Per component: free, fixed (u = 0) or
// following the stretch schedule, u = scale * (lambda(t) - 1) * reference_length.
struct LoadSet {
  enum class Region { top, bottom, left, right, box };
  std::string   name;
  Region        region = Region::top;
  double        box[4] = {0, 0, 0, 0}; // xmin, ymin, xmax, ymax (Region::box)
  int           layers = 1;            // point layers taken from the named edge
  ComponentLoad x = ComponentLoad::free, y = ComponentLoad::free;
  double        x_scale = 0.0, y_scale = 0.0;
};

struct Probe {
  std::string name;
  double      x = 0, y = 0; // the material point nearest to (x, y) is recorded
};

struct Scene {
  Body2D body;
  double horizon_factor = 3.015; // delta / dx

  ModelKind          model       = ModelKind::gent;
  Formulation        formulation = Formulation::plane_stress;
  MaterialParameters material;
  double             density = 1000.0; // kg/m^3

  bool   failure          = false; // no failure section: no bond-state work at all
  double critical_stretch = 0.0;

  std::vector<LoadSet> loads;
  Schedule             schedule;
  double               reference_length = 0.0; // default: body height

  std::vector<Probe> probes;

  std::string output_dir      = "output";
  PetscInt    output_interval = 100; // steps between history rows

  double   time_step        = 0.0;  // 0: use safety * stable step
  double   time_step_safety = 0.8;  // fraction of the computed stable step
  double   damping          = 0.0;  // mass-proportional damping coefficient [1/s]
  double   end_time         = 0.0;  // default: the schedule's last knot
  PetscInt progress_interval = 0;   // steps between progress lines (0: about 20 lines a run)

  double horizon() const { return horizon_factor * body.dx; }
};

// Reads and validates the scene. Every rejected value is reported once, naming the
// option and what would fix it, before any work is done.
PetscErrorCode SceneFromOptions(MPI_Comm comm, Scene *scene);
// Prints the scene in a few lines (rank 0).
PetscErrorCode SceneView(MPI_Comm comm, const Scene &scene);
// Rejects options that nothing read (a typo), suggesting the nearest known name.
// Call once every component has read its options.
PetscErrorCode CheckUnusedOptions(MPI_Comm comm);

} // namespace bapd
