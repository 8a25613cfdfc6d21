#pragma once
// A scene: everything a run needs, read from PETSc options (a YAML options file
// given with -options_file_yaml, every value overridable on the command line).
// SI units throughout. See docs/options.md for the full list.
//
// This header is the whole public interface: the grips, probes, schedule, output and
// time-stepping records and the option registry have their own headers, included here.
// The definitions: scene.cpp (reading and checking, SceneView) lists the files of each
// section.
#include <petscsys.h>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "bapd/core/geometry/body.hpp"
#include "bapd/core/geometry/shape3d.hpp"
#include "bapd/core/materials/material.hpp"
#include "bapd/solver/input/options.hpp"
#include "bapd/solver/input/scene_loading.hpp"
#include "bapd/solver/input/scene_output.hpp"
#include "bapd/solver/input/scene_probes.hpp"
#include "bapd/solver/input/scene_schedule.hpp"
#include "bapd/solver/input/scene_time_stepping.hpp"
#include "bapd/core/kernel/force_form.hpp"
#include "bapd/core/kernel/softening_law.hpp"
#include "bapd/core/kernel/volumetric_kind.hpp"
#include "bapd/core/kernel/stress_correction.hpp"

namespace bapd {

// -force_patch_correction (patch_correction.hpp): off; on = lambda, D numbers a point
// (the patch test); virial = (mu, S), 5 numbers a point in 2D, 9 in 3D (the patch test
// and the virial).
enum class PatchCorrection { off, lambda, virial };

// -solver: explicit dynamics (PETSc TS, the default) or static states by Newton (PETSc
// SNES on the energy-consistent force, load stepping along the schedule: static_solver.hpp).
enum class SolverKind { dynamic, static_newton };

// -partition_type: who splits the bond graph over the ranks (docs/options_run.md
// "Partition"): METIS on rank 0 (the whole body built there), or PT-Scotch in parallel
// (a lattice body built in slabs, one a rank: src/solver/parallel/distributed_body.hpp).
enum class PartitionType { metis, ptscotch };

// The static solver's load stepping (-static_*; docs/options_run.md "Static solver").
struct StaticOptions {
  double   stretch_step     = 0.25;  // first load step, in stretch [-]
  double   stretch_step_max = 1.0;   // largest load step, in stretch [-]
  double   stretch_step_min = 1e-4;  // a step cut below this ends the run with an error [-]
  double   growth           = 1.5;   // step x this after a step that converged in at most fast_iterations Newton iterations
  PetscInt fast_iterations  = 4;
  bool     secant_predictor = true;  // predict by the secant through the last two states (else a tangent solve)
  double   residual_tolerance = 1e-10; // Newton ends once |R| <= this x |grip reactions| (|R|: the free dofs' forces) [-]
  double   onset_tolerance  = 1e-3;  // the load step that breaks the first bonds is at most this x (lambda - 1) wide [-]
};

// What the scene learns of the 3D body by building its points once (scene_body3d.cpp),
// beyond the body itself: names for messages, the point count (the memory check) and
// the extent of the points' cells (the faces of the load sets).
struct SolidSummary {
  std::vector<std::string> solid_names; // -body_shapes name of each solid, for messages
  std::vector<std::string> notch_names; // -body_shapes name of each notch (Body<3>::notches)
  int64_t                  points = 0;  // material points of the body
  std::array<double, 3>    lo{}, hi{};  // the extent of the points' cells [m]: lattice point +- dx/2
};

// The body (-body_*, -horizon_factor; scene_body.cpp, scene_body3d.cpp): the plane
// sheet (dimension 2) or the solid (dimension 3; docs/options.md "3D bodies"), and the
// horizon. Only the body of the dimension is filled; each holds its own spacing.
struct BodySection {
  // -body_dimension (or 3 implied by a 3D solid): the driver's D (SimulationD<D>,
  // chosen once by main.cpp from the scene).
  int          dimension = 2;
  Body<2>      sheet;         // dimension 2
  Body<3>      solid;         // dimension 3
  SolidSummary solid_summary; // dimension 3
  double       horizon_factor = 3.015; // delta / dx (given points: delta_i / h_i, geometry.hpp)

  // The spacing of the body (given points: their smallest): the time-step bound, the
  // travel scale, the faces' row depth.
  double dx() const { return dimension == 3 ? solid.dx : sheet.dx; }
  double horizon() const { return horizon_factor * dx(); } // (given points: the smallest delta_i)
};

// The material (-material_*, -force_*; scene_material.cpp): the law, its 2D reduction and
// parameters, and how the bond force is formed. The force (ForceOperator,
// TangentOperator) takes this section.
struct MaterialSection {
  ModelKind          model       = ModelKind::gent;
  Formulation        formulation = Formulation::plane_stress;
  ForceForm          force_form  = ForceForm::energy_consistent;
  // -material_volumetric (volumetric.hpp): U(J) per bond (the paper's) or once per point
  // from the mean dilatation (no volumetric locking in plane strain and 3D).
  Volumetric         volumetric  = Volumetric::bond;
  double             volumetric_stabilisation = 10.0; // kappa / mu (-material_volumetric_stabilisation)
  // -force_stress_correction (stress_correction.hpp): the bond-only force made to give
  // sum_j t_ij (x) xi_ij V_j = P; the identity for the energy-consistent form.
  StressCorrection   stress_correction = StressCorrection::none;
  // -force_patch_correction (patch_correction.hpp): the bond-only force made to pass the
  // affine patch test on given points (lambda per point, formed at setup), and with
  // virial to keep each point's virial as well ((mu, S) per point).
  PatchCorrection    patch_correction = PatchCorrection::off;
  MaterialParameters parameters;
  double             density = 1000.0; // kg/m^3
};

// Failure (-failure_*; scene_material.cpp): none unless the section is given.
struct FailureSection {
  bool     enabled           = false; // no failure section: no bond-state work at all
  double   critical_stretch  = 0.0;   // -failure_critical_stretch (eq 7), or 0
  double   fracture_energy   = 0.0;   // -failure_fracture_energy Gamma [J/m^2] (docs/method.md 5.2), or 0
  double   tip_concentration = 0.43;  // -failure_tip_concentration kappa: w_c = kappa Gamma / c (docs/method.md 5.2)
  Softening softening        = Softening::none; // -failure_softening: bonds fail gradually (softening.hpp; docs/method.md 5.4)
  double   fade_time         = 0.0;   // -failure_softening_time tau [s]: the time law's fading time (softening.hpp), or 0
  PetscInt passes            = 0;     // -failure_passes: breaking passes a step with Gamma (0: until none breaks; docs/method.md 5.2)
};

// The loading (-load_*, -probes, -probe_*; scene_loading.cpp, scene_probes.cpp): the
// load sets (grips), the stretch schedule and the probes that watch them.
struct LoadingSection {
  std::vector<LoadSet> sets;
  Schedule             schedule;
  double               reference_length = 0.0; // default: body height
  GripField            grip_field       = GripField::rigid;
  std::vector<Probe>   probes;

  // Prescribed displacement of a stretch component with the given scale at time t,
  // u = scale * (lambda(t) - 1) * reference_length, and its rate du/dt.
  double grip_displacement(double scale, double t) const
  {
    return scale * (schedule.stretch_at(t) - 1.0) * reference_length;
  }
  double grip_velocity(double scale, double t) const { return scale * schedule.rate_at(t) * reference_length; }
};

// The output (-output_*, -checkpoint_*, -restart*; scene_output.cpp).
struct OutputSection {
  std::string       dir          = "output";
  PetscInt          interval     = 100;   // steps between history rows; the static test runs at these rows
  PetscInt          history_rows = 100;   // history rows by load: one at each end time / N of simulated time too (0: off)
  bool              final_state  = false; // final_state.csv and broken_bonds.csv at the end
  FieldOptions      fields;               // -output_fields* (fields.hpp)
  CheckpointOptions checkpoint;           // -checkpoint_*, -restart* (checkpoint.hpp)
};

// The run (-solver, -partition_type, -log_setup_memory, -static_*; scene_run.cpp).
struct RunSection {
  SolverKind    solver           = SolverKind::dynamic;
  PartitionType partition_type   = PartitionType::metis;
  bool          log_setup_memory = false; // every rank's peak memory after the set-up
  StaticOptions static_options;           // the static solver only
};

// Time stepping (-time_step*, -damping, -relaxation, -static_tolerance, -end_*,
// -progress_*; scene_time_stepping.cpp). The time-step control (TimeStepControl::
// EstimateStable) takes this section.
struct TimeSteppingSection {
  double   step    = 0.0;  // -time_step (0: use safety * stable step)
  double   safety  = 0.8;  // -time_step_safety: fraction of the computed stable step
  double   travel  = -1.0; // -time_step_travel: a step moves no bonded point more than this x dx (0: off; -1: the solver's choice, 0.1 with failure)
  double   damping = 0.0;  // mass-proportional damping coefficient [1/s]
  double   static_tolerance = 0.0; // hold ends once kinetic / internal energy < this (0: holds run out)
  double   end_time = 0.0; // default: the schedule's last knot
  PetscInt end_step = -1;  // stop after this step, before end_time, on purpose (split runs, tests; -1: run to end_time)
  PetscInt progress_interval = 0;         // steps between progress lines (0: about 20 lines a run)
  double   progress_wall_interval = 10.0; // also a progress line after this much wall time [s] since the last (0: off)
  RelaxationKind  relaxation = RelaxationKind::none; // -relaxation (relaxation.hpp)
  TimeStepOptions reestimate;                        // the stable step's re-estimate, -time_step_reestimate ... (time_step_control.hpp)
};

struct Scene {
  BodySection         body;
  MaterialSection     material;
  FailureSection      failure;
  LoadingSection      loading;
  OutputSection       output;
  RunSection          run;
  TimeSteppingSection time_stepping;

  // -help was given: every option was listed, nothing was validated and the scene
  // holds defaults only. The driver stops (with -help all, after PETSc's time stepper
  // has listed its options).
  bool help_only = false;
};

// Reads and validates the scene. Every rejected value is reported once, naming the
// option and what would fix it, before any work is done (error PETSC_ERR_USER; the
// message is what PetscErrorMessage returns). With -help it lists the options,
// validates nothing and returns with scene->help_only set.
PetscErrorCode SceneFromOptions(MPI_Comm comm, Scene *scene);
// Prints the scene in a few lines (rank 0): SceneText.
PetscErrorCode SceneView(MPI_Comm comm, const Scene &scene);
// The scene in a few lines: the body (2D: the sheet, lattice, holes, shapes, notches;
// 3D: the lattice or cloud, point count, the extent of the points' cells, each solid and
// notch by name), horizon, material, force, failure, load sets (3D: faces by axis, z
// components), schedule, probes, time stepping and output.
std::string SceneText(const Scene &scene);

// What the load regions read of the checked scene's body (scene_selection.cpp).
BodyExtent BodyExtentOf(const Scene &scene);

// Warnings issued by the last SceneFromOptions (also printed on rank 0, to stderr).
const std::vector<std::string> &SceneWarnings();

// How many material points the body holds, counted by the geometry stage's rule
// (geometry.hpp: body_point_count) without building them: on the lattice
// round(width/dx) x round(height/dx) cell centres, less those inside a hole
// (hole_containing, lattice.hpp); given points, those that are material.
// 64-bit: a fine -body_dx can ask for more than 2^31 points (refused, see below).
int64_t ScenePointEstimate(const Scene &scene);

// The memory check of the scene (before anything is built, with the lattice's pi x
// horizon_factor^2 bonds a point) again with the real point and bond counts (given
// points with their own horizons have more bonds a point: "either reaches", geometry.hpp).
// Collective; refuses with the option to change if the body does not fit.
PetscErrorCode CheckBodyMemory(MPI_Comm comm, const Scene &scene, int64_t points, int64_t bonds);

const char *to_string(PatchCorrection c); // the option's word: off, on, virial

} // namespace bapd
