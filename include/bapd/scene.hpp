#pragma once
// A scene: everything a run needs, read from PETSc options (a YAML options file
// given with -options_file_yaml, every value overridable on the command line).
// SI units throughout. See docs/options.md for the full list.
#include <petscsys.h>
#include <cstdint>
#include <string>
#include <vector>

#include "bapd/body.hpp"
#include "bapd/material.hpp"

namespace bapd {

// Piecewise-linear applied stretch lambda(t) through the knots (time[k], stretch[k]);
// ramps and holds are just knots. Before the first knot lambda = stretch[0], after the
// last one it stays at the last value. No knots: lambda = 1 throughout.
struct Schedule {
  std::vector<double> time, stretch;
  double              stretch_at(double t) const;
  double              rate_at(double t) const; // d lambda / dt (right derivative)
  double              end_time() const { return time.empty() ? 0.0 : time.back(); }
};

enum class ComponentLoad { free, fixed, stretch };

// Which bond force the kernel computes (-force_form): the paper's bond-only form
// (eq 23, ba_force.hpp), or the energy-consistent one, minus the gradient of the
// strain energy (ba_force_energy.hpp, METHOD.md section 3), whose undamped motion
// conserves energy where the bond-only form's grows near free surfaces (flutter).
enum class ForceForm { bond_only, energy_consistent };

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
  ForceForm          force_form  = ForceForm::bond_only;
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
  double   time_step_travel = 0.0;  // a step moves no bonded point more than this x dx (0: off)
  double   damping          = 0.0;  // mass-proportional damping coefficient [1/s]
  double   static_tolerance = 0.0;  // hold ends once kinetic / internal energy < this (0: holds run out)
  double   end_time         = 0.0;  // default: the schedule's last knot
  PetscInt progress_interval = 0;   // steps between progress lines (0: about 20 lines a run)

  // -help was given: every option was listed, nothing was validated and the scene
  // holds defaults only. The driver should list the other components' options and stop.
  bool help_only = false;

  double horizon() const { return horizon_factor * body.dx; }
  // Prescribed displacement of a stretch component with the given scale at time t,
  // u = scale * (lambda(t) - 1) * reference_length, and its rate du/dt.
  double grip_displacement(double scale, double t) const
  {
    return scale * (schedule.stretch_at(t) - 1.0) * reference_length;
  }
  double grip_velocity(double scale, double t) const { return scale * schedule.rate_at(t) * reference_length; }
};

// Reads and validates the scene. Every rejected value is reported once, naming the
// option and what would fix it, before any work is done (error PETSC_ERR_USER; the
// message is what PetscErrorMessage returns). With -help it lists the options,
// validates nothing and returns with scene->help_only set.
PetscErrorCode SceneFromOptions(MPI_Comm comm, Scene *scene);
// Prints the scene in a few lines (rank 0).
PetscErrorCode SceneView(MPI_Comm comm, const Scene &scene);
// Rejects options that nothing read (a typo), suggesting the nearest known name.
// Call once every component has read its options.
PetscErrorCode CheckUnusedOptions(MPI_Comm comm);

// Warnings issued by the last SceneFromOptions (also printed on rank 0, to stderr).
const std::vector<std::string> &SceneWarnings();
// Adds an option name ("-integrator_foo") to the names CheckUnusedOptions suggests
// from. Every option SceneFromOptions reads is registered already.
void RegisterOptionName(const std::string &name);

// How many material points the body holds, counted by make_lattice's rule
// (lattice.hpp) without building them: round(width/dx) x round(height/dx) cell
// centres, less those closer than a radius to a hole's centre.
PetscInt ScenePointEstimate(const Scene &scene);

// The local points (reference positions x, 2 per point, n points) that a load set
// holds: within `layers` layers of its edge (top: y > height - layers*dx, bottom:
// y < layers*dx, left: x < layers*dx, right: x > width - layers*dx) or inside its
// box (edges included). Indices into x, increasing. Pass owned points only; whether
// a set holds any point at all is for the caller to check over the communicator.
PetscErrorCode LoadSetSelect(const Scene &scene, const LoadSet &set, const double *x, PetscInt n,
                             std::vector<PetscInt> *selected);

// Where a probe reads: the point nearest to (probe.x, probe.y), ties broken by the
// lowest natural id, so the choice is the same on any number of ranks.
struct ProbeLocation {
  PetscMPIInt owner       = -1; // rank that owns the point
  int64_t     natural_id  = -1;
  PetscInt    local_index = -1; // index into the owner's x; -1 on the other ranks
  double      distance    = 0;  // from (probe.x, probe.y) to the point [m]
};
// Collective. x: owned reference positions (2 per point), natural_id: their ids.
PetscErrorCode ProbeLocate(MPI_Comm comm, const Probe &probe, const double *x, const int64_t *natural_id, PetscInt n,
                           ProbeLocation *location);

const char *to_string(LoadSet::Region region);
const char *to_string(ComponentLoad load);
const char *to_string(ForceForm form);

} // namespace bapd
