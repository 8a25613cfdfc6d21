#pragma once
// The scene's sections (internal to src/solver/scene*.cpp): what the options said
// before the checks, and the read and check pass of each section. SceneFromOptions
// (scene.cpp) runs every Read* (so that -help lists every block), then every Check*,
// which turns the raw input into the Scene's values, first problem reported.
#include <petscsys.h>
#include <string>
#include <vector>

#include "bapd/solver/input/scene.hpp"

namespace bapd {

// What the options said, beyond the values that go straight into the Scene: which
// were given, and the raw text of lists and choices, for the checks.
struct LoadInput {
  std::string         name, region, x = "free", y = "free", z = "free", placement = "auto"; // auto: -load_grip_placement's
  std::string         group, file; // region group: the physical group and its Gmsh file
  bool                region_set = false, box_set = false, layers_set = false, depth_set = false, x_scale_set = false,
                      y_scale_set = false, z_scale_set = false, points_set = false, block_set = false;
  std::vector<double> box, points; // points: region polygon or curve
  PetscInt            block = 0;   // region block: the block id of the given points
  PetscInt            layers  = 1;
  double              depth   = 0.0;
  double              x_scale = 1.0, y_scale = 1.0, z_scale = 1.0;
};

struct ShapeInput {
  std::string         name, type, op = "subtract", file, discretisation = "lattice";
  bool                type_set = false;
  std::vector<double> box, centre, radii, points, axis; // axis: a 3D cylinder's end points
  double              radius = 0, angle = 0; // angle in degrees, as given
  bool                radius_set = false, op_set = false;
};

struct ProbeInput {
  std::string         name;
  std::vector<double> at;
  bool                at_set = false;
  std::string         group, file; // -probe_NAME_group (a Gmsh physical point) and its file
  PetscInt            block     = 0; // -probe_NAME_block: a block id of the cloud with one point
  bool                block_set = false;
};

struct SceneInput {
  bool                     width_set = false, height_set = false, thickness_set = false, dx_set = false;
  double                   dx = 0; // -body_dx: the lattice spacing of the sheet or the solid
  std::vector<double>      holes, notches;
  std::vector<std::string> shape_names;
  std::vector<ShapeInput>  shapes;
  std::string              cloud; // -body_cloud: a point cloud file instead of the lattice
  PetscInt                 dimension = 2; // -body_dimension (2 or 3; 3D solids imply 3)
  bool                     dimension_set = false, grip_placement_set = false, grip_field_set = false;
  std::string              model = "gent", formulation = "plane_stress", force_form = "energy_consistent",
                           stress_correction = "auto", patch_correction = "auto", volumetric = "bond", grip_field = "auto", grip_placement = "outside";
  bool                     formulation_set = false; // -material_formulation given (refused in 3D)
  bool                     D_set = false, bulk_ratio_set = false;
  double                   bulk_ratio = 1000.0;
  std::vector<std::string> law_options_given; // the laws' own options that were given (-material_Jm, ...), for CheckMaterial
  bool                     critical_stretch_set = false, fracture_energy_set = false, fade_time_set = false;
  std::string              softening = "none"; // -failure_softening
  std::vector<std::string> load_names;
  std::vector<LoadInput>   loads;
  std::vector<double>      schedule;
  bool                     schedule_set = false, reference_length_set = false;
  std::vector<std::string> probe_names;
  std::vector<ProbeInput>  probes;
  bool                     end_time_set = false;
  std::string              solver = "dynamic", partition_type = "metis"; // -solver, -partition_type as given
  std::string              relaxation = "none";       // -relaxation as given
  std::string              field_geometry = "current"; // -output_fields_geometry as given
  bool                     restart_set = false;        // -restart given (it needs a file)
};

// The options of the named sets, each family from its set's option table: -load_NAME_...
// (scene_loading.cpp), -probe_NAME_... (scene_probes.cpp), -body_NAME_... (the shapes,
// scene_body.cpp). The unused-option check names the list an undeclared set is missing
// from ("'grip' is not one of -load_sets"), and -help lists each family's options.
struct SetFamily {
  std::string              head;        // "-load_": the options' names start with it, then the set's name
  std::string              list_option; // "-load_sets": the option that lists the names
  std::vector<std::string> suffixes;    // "_region", ...: after the set's name, in -help's order
};
SetFamily LoadSetFamily();
SetFamily ProbeFamily();
SetFamily ShapeFamily();
// Every family, in the order of the sections (the body's shapes, load sets, probes).
std::vector<SetFamily> SetFamilies();

// Body (scene_body.cpp): -body_* and -horizon_factor.
PetscErrorCode ReadBody(MPI_Comm comm, BodySection *body, SceneInput *in);
PetscErrorCode CheckBody(MPI_Comm comm, const SceneInput &in, Scene *scene);
// The parts of the body's check shared with the 3D body (scene_body3d.cpp).
PetscErrorCode CheckHorizonFactor(MPI_Comm comm, const Scene &scene);
bool           IsShape3D(const std::string &type); // box, cylinder, sphere, notch
// One shape of -body_shapes of the 2D sheet, checked and appended to *shapes
// (scene_shape.cpp); `read_mesh`: its Gmsh mesh if already read (else null).
PetscErrorCode CheckShape(MPI_Comm comm, const ShapeInput &in, const Body<2> &b, TriangleSet *read_mesh, std::vector<Shape> *shapes);
PetscErrorCode CheckBody3D(MPI_Comm comm, const SceneInput &in, Scene *scene);
// Refuses a lattice that cannot fit in memory, counting the rows of the grips outside
// the sheet (Body<2>::grip_rows, OutsideGripRows: SceneFromOptions sets them first).
PetscErrorCode CheckBodyFits(MPI_Comm comm, const Scene &scene);
// Material and failure (scene_material.cpp): -material_*, -force_form, -failure_*.
PetscErrorCode ReadMaterial(MPI_Comm comm, MaterialSection *material, FailureSection *failure, SceneInput *in);
PetscErrorCode CheckMaterial(MPI_Comm comm, const SceneInput &in, Scene *scene);
// Each section's lines of SceneText: the material, force and failure; the load sets and
// the schedule (scene_loading.cpp); the probes (scene_probes.cpp); the time step, the
// run's end and holds (scene_time_stepping.cpp); the output (scene_output.cpp).
std::string MaterialText(const Scene &scene);
std::string LoadingText(const Scene &scene);
std::string ProbesText(const Scene &scene);
std::string TimeSteppingText(const Scene &scene);
std::string OutputText(const OutputSection &output);
// Loading (scene_loading.cpp): -load_sets, -load_schedule, -load_NAME_*.
PetscErrorCode ReadLoading(MPI_Comm comm, LoadingSection *loading, SceneInput *in);
PetscErrorCode CheckLoading(MPI_Comm comm, const SceneInput &in, Scene *scene);
// The rows the edge grips placed outside the sheet add beyond each edge (Body<2>::
// grip_rows): the deepest grip's on each edge; none in 3D (a face holds the body's own
// points). A function of the checked load sets only.
EdgeRows OutsideGripRows(const LoadingSection &loading);
// The Gmsh files the body reads (its mesh shapes): where a physical group's file
// defaults to (load sets and probes by group).
std::vector<std::string> BodyGmshFiles(const Body<2> &body);
std::vector<std::string> BodyGmshFiles(const Body<3> &body); // (its mesh solids)
// The file of physical group `group` of -PREFIX_NAME_group (owner: "load set", "probe"):
// `given` (-PREFIX_NAME_file), else the body's one Gmsh file (`files`, its `kinds`:
// "mesh shapes", "mesh solids"); several files and none given is refused.
PetscErrorCode GroupGmshFile(MPI_Comm comm, const std::string &given, const std::vector<std::string> &files, const char *prefix,
                             const char *owner, const std::string &name, const char *kinds, const std::string &group, std::string *file);
// Probes (scene_probes.cpp): -probes, -probe_NAME_at or -probe_NAME_group.
PetscErrorCode ReadProbes(MPI_Comm comm, SceneInput *in);
PetscErrorCode CheckProbes(MPI_Comm comm, const SceneInput &in, Scene *scene);
// Output (scene_output.cpp): -output_*, -checkpoint_*, -restart*.
PetscErrorCode ReadOutput(MPI_Comm comm, OutputSection *output, SceneInput *in);
PetscErrorCode CheckOutput(MPI_Comm comm, const SceneInput &in, Scene *scene);
// The run (scene_run.cpp): -solver, -partition_type, -log_setup_memory, -static_*.
PetscErrorCode ReadRun(MPI_Comm comm, RunSection *run, SceneInput *in);
PetscErrorCode CheckRun(MPI_Comm comm, const SceneInput &in, Scene *scene);
// Time stepping (scene_time_stepping.cpp): -time_step*, -damping, -relaxation,
// -static_tolerance, -end_time, -end_step, -progress_*. Checked after the loading (the
// end time defaults to the schedule's).
PetscErrorCode ReadTimeStepping(MPI_Comm comm, TimeSteppingSection *time_stepping, SceneInput *in);
PetscErrorCode CheckTimeStepping(MPI_Comm comm, const SceneInput &in, Scene *scene);

} // namespace bapd
