// Scene options (scene.hpp): a valid scene is read with the right values and
// defaults, a YAML file and flat options give the same scene, later options win,
// doubtful values and other laws' parameters draw warnings, and the grips are placed
// as asked. The rejections of invalid input and of unused options are in
// scene_rejections_test.cpp.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <unistd.h>

#include "bapd/solver/input/scene.hpp"
#include "bapd/solver/input/scene_input.hpp"
#include "plate_options.hpp"
#include "scene_reading.hpp"

namespace {

using bapd::ComponentLoad;
using bapd::LoadSet;
using bapd::Scene;
using bapd::test::PlateWithHole;

using Options = bapd::test::PlateOptions;


// The same scene as a YAML file, as a user writes it.
const char *const kPlateYAML = R"(body:
  width: 0.08
  height: 0.16
  thickness: 0.001
  dx: 0.001
  holes: [0.04, 0.08, 0.01]
material:
  bulk_ratio: 100
load:
  sets: [top, bottom]
  top:
    region: top
    x: fixed
    y: stretch
    y_scale: 0.5
  bottom:
    region: bottom
    x: fixed
    y: stretch
    y_scale: -0.5
  schedule: [0, 1, 1, 1.5, 2, 1.5]
probes: [left_mid]
probe:
  left_mid:
    at: [0, 0.08]
damping: 20
output:
  dir: out/plate
  interval: 200
)";

class SceneOptions : public bapd::test::SceneReading<Options> {
protected:
  // Writes text to a fresh file (on rank 0, which is where PETSc reads it) and
  // returns the name, the same on every rank.
  std::string TempFile(const std::string &text)
  {
    PetscMPIInt rank;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    char name[64] = "/tmp/bapd_scene_XXXXXX";
    if (rank == 0) {
      const int fd = mkstemp(name);
      EXPECT_GE(fd, 0);
      EXPECT_EQ(write(fd, text.data(), text.size()), (ssize_t)text.size());
      close(fd);
    }
    MPI_Bcast(name, sizeof(name), MPI_CHAR, 0, PETSC_COMM_WORLD);
    return name;
  }
  void RemoveFile(const std::string &name)
  {
    PetscMPIInt rank;
    MPI_Barrier(PETSC_COMM_WORLD);
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0) std::remove(name.c_str());
  }
};

void ExpectSameScene(const Scene &a, const Scene &b)
{
  EXPECT_EQ(a.body.sheet.width, b.body.sheet.width);
  EXPECT_EQ(a.body.sheet.height, b.body.sheet.height);
  EXPECT_EQ(a.body.sheet.thickness, b.body.sheet.thickness);
  EXPECT_EQ(a.body.sheet.dx, b.body.sheet.dx);
  ASSERT_EQ(a.body.sheet.holes.size(), b.body.sheet.holes.size());
  for (std::size_t h = 0; h < a.body.sheet.holes.size(); ++h) {
    EXPECT_EQ(a.body.sheet.holes[h].cx, b.body.sheet.holes[h].cx);
    EXPECT_EQ(a.body.sheet.holes[h].cy, b.body.sheet.holes[h].cy);
    EXPECT_EQ(a.body.sheet.holes[h].radius, b.body.sheet.holes[h].radius);
  }
  EXPECT_EQ(a.body.sheet.notches.size(), b.body.sheet.notches.size());
  EXPECT_EQ(a.body.horizon_factor, b.body.horizon_factor);
  EXPECT_EQ(a.material.model, b.material.model);
  EXPECT_EQ(a.material.formulation, b.material.formulation);
  EXPECT_EQ(a.material.parameters.mu, b.material.parameters.mu);
  EXPECT_EQ(a.material.parameters["-material_Jm"], b.material.parameters["-material_Jm"]);
  EXPECT_EQ(a.material.parameters.D, b.material.parameters.D);
  EXPECT_EQ(a.material.density, b.material.density);
  EXPECT_EQ(a.failure.enabled, b.failure.enabled);
  EXPECT_EQ(a.failure.critical_stretch, b.failure.critical_stretch);
  ASSERT_EQ(a.loading.sets.size(), b.loading.sets.size());
  for (std::size_t s = 0; s < a.loading.sets.size(); ++s) {
    EXPECT_EQ(a.loading.sets[s].name, b.loading.sets[s].name);
    EXPECT_EQ(a.loading.sets[s].region, b.loading.sets[s].region);
    EXPECT_EQ(a.loading.sets[s].layers, b.loading.sets[s].layers);
    EXPECT_EQ(a.loading.sets[s].x, b.loading.sets[s].x);
    EXPECT_EQ(a.loading.sets[s].y, b.loading.sets[s].y);
    EXPECT_EQ(a.loading.sets[s].x_scale, b.loading.sets[s].x_scale);
    EXPECT_EQ(a.loading.sets[s].y_scale, b.loading.sets[s].y_scale);
  }
  EXPECT_EQ(a.loading.schedule.time, b.loading.schedule.time);
  EXPECT_EQ(a.loading.schedule.stretch, b.loading.schedule.stretch);
  EXPECT_EQ(a.loading.reference_length, b.loading.reference_length);
  ASSERT_EQ(a.loading.probes.size(), b.loading.probes.size());
  for (std::size_t p = 0; p < a.loading.probes.size(); ++p) {
    EXPECT_EQ(a.loading.probes[p].name, b.loading.probes[p].name);
    EXPECT_EQ(a.loading.probes[p].x, b.loading.probes[p].x);
    EXPECT_EQ(a.loading.probes[p].y, b.loading.probes[p].y);
  }
  EXPECT_EQ(a.output.dir, b.output.dir);
  EXPECT_EQ(a.output.interval, b.output.interval);
  EXPECT_EQ(a.time_stepping.step, b.time_stepping.step);
  EXPECT_EQ(a.time_stepping.safety, b.time_stepping.safety);
  EXPECT_EQ(a.time_stepping.damping, b.time_stepping.damping);
  EXPECT_EQ(a.time_stepping.end_time, b.time_stepping.end_time);
  EXPECT_EQ(a.time_stepping.progress_interval, b.time_stepping.progress_interval);
}

// -help lists the options of every component even without a scene, and validates
// nothing. It must come first in the file (CaptureHelp, scene_reading.hpp).
TEST_F(SceneOptions, HelpListsEveryComponentWithoutAScene)
{
  std::string text;
  Scene       scene;
  const PetscErrorCode ierr = bapd::test::CaptureHelp([&] { return Read({{"-help", ""}, {"-load_sets", "grip"}}, &scene); }, &text);
  ASSERT_EQ(ierr, 0) << bapd::test::UserErrorText();
  EXPECT_TRUE(scene.help_only);
  for (const char *name : {"-body_width", "-body_holes", "-horizon_factor", "-material_mu", "-material_bulk_ratio", "-failure_critical_stretch",
                           "-load_schedule", "-load_grip_region", "-load_grip_y_scale", "-probes", "-output_dir", "-time_step_safety", "-end_time"})
    EXPECT_NE(text.find(name), std::string::npos) << name << " missing from -help";
}

// ----------------------------------------------------------------------------------
// Valid scenes

TEST_F(SceneOptions, ReadsThePlateWithAHoleWithItsDefaults)
{
  Scene scene;
  ASSERT_EQ(Read(PlateWithHole(), &scene), 0) << bapd::test::UserErrorText();
  EXPECT_FALSE(scene.help_only);
  EXPECT_EQ(scene.body.sheet.width, 0.08);
  EXPECT_EQ(scene.body.sheet.height, 0.16);
  EXPECT_EQ(scene.body.sheet.thickness, 0.001);
  EXPECT_EQ(scene.body.sheet.dx, 0.001);
  ASSERT_EQ(scene.body.sheet.holes.size(), 1u);
  EXPECT_EQ(scene.body.sheet.holes[0].cx, 0.04);
  EXPECT_EQ(scene.body.sheet.holes[0].cy, 0.08);
  EXPECT_EQ(scene.body.sheet.holes[0].radius, 0.01);
  EXPECT_TRUE(scene.body.sheet.notches.empty());

  // Defaults (docs/options.md).
  EXPECT_EQ(scene.body.horizon_factor, 3.015);
  EXPECT_EQ(scene.material.model, bapd::ModelKind::gent);
  EXPECT_EQ(scene.material.formulation, bapd::Formulation::plane_stress);
  EXPECT_EQ(scene.material.parameters.mu, 4.55e3);
  EXPECT_EQ(scene.material.parameters["-material_Jm"], 162.6);
  EXPECT_EQ(scene.material.parameters.D, 2.0 / (100.0 * 4.55e3)); // the scene's K = 2/D = 100 mu, same expression: exact
  EXPECT_EQ(scene.material.density, 1000.0);
  EXPECT_FALSE(scene.failure.enabled);
  EXPECT_EQ(scene.loading.reference_length, 0.16); // the body height
  EXPECT_EQ(scene.time_stepping.step, 0.0);
  EXPECT_EQ(scene.time_stepping.safety, 0.8);
  EXPECT_EQ(scene.time_stepping.end_time, 2.0); // the schedule's last knot
  EXPECT_EQ(scene.time_stepping.progress_interval, 0);

  ASSERT_EQ(scene.loading.sets.size(), 2u);
  const LoadSet &top = scene.loading.sets[0], &bottom = scene.loading.sets[1];
  EXPECT_EQ(top.name, "top");
  EXPECT_EQ(top.region, LoadSet::Region::top);
  // Grips outside the specimen, two horizons deep (2 x 3.015 dx: the 6 rows whose
  // centres lie within it), the affine field, the energy-consistent force (which
  // needs no stress correction: auto is none for it).
  EXPECT_EQ(top.placement, bapd::GripPlacement::outside);
  EXPECT_EQ(top.layers, 6);
  EXPECT_EQ(scene.body.sheet.grip_rows.top, 6);
  EXPECT_EQ(scene.body.sheet.grip_rows.bottom, 6);
  EXPECT_EQ(scene.body.sheet.grip_rows.left + scene.body.sheet.grip_rows.right, 0);
  EXPECT_EQ(scene.loading.grip_field, bapd::GripField::affine);
  EXPECT_EQ(scene.material.force_form, bapd::ForceForm::energy_consistent);
  EXPECT_EQ(scene.material.stress_correction, bapd::StressCorrection::none);
  EXPECT_EQ(top.x, ComponentLoad::fixed);
  EXPECT_EQ(top.y, ComponentLoad::stretch);
  EXPECT_EQ(top.y_scale, 0.5);
  EXPECT_EQ(bottom.name, "bottom");
  EXPECT_EQ(bottom.region, LoadSet::Region::bottom);
  EXPECT_EQ(bottom.y_scale, -0.5);
  EXPECT_EQ(scene.loading.schedule.time, (std::vector<double>{0, 1, 2}));
  EXPECT_EQ(scene.loading.schedule.stretch, (std::vector<double>{1, 1.5, 1.5}));

  ASSERT_EQ(scene.loading.probes.size(), 1u);
  EXPECT_EQ(scene.loading.probes[0].name, "left_mid");
  EXPECT_EQ(scene.loading.probes[0].x, 0.0);
  EXPECT_EQ(scene.loading.probes[0].y, 0.08);
  EXPECT_EQ(scene.time_stepping.damping, 20.0);
  EXPECT_EQ(scene.output.dir, "out/plate");
  EXPECT_EQ(scene.output.interval, 200);
  EXPECT_TRUE(bapd::SceneWarnings().empty());
  EXPECT_EQ(bapd::SceneView(PETSC_COMM_WORLD, scene), 0);
}

// Without -material_D or -material_bulk_ratio the gel is nearly incompressible,
// K = 2/D = 1000 mu (docs/options.md explains the choice).
TEST_F(SceneOptions, DefaultsToABulkModulusOfAThousandShearModuli)
{
  Options o = PlateWithHole();
  o.erase("-material_bulk_ratio");
  Scene scene;
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.material.parameters.D, 2.0 / (1000.0 * 4.55e3)); // same expression as the default: exact
}

TEST_F(SceneOptions, ReadsEveryOtherChoice)
{
  Options o = PlateWithHole();
  o.erase("-material_bulk_ratio");
  o["-material_model"]           = "neo-hookean";
  o["-material_formulation"]     = "plane_strain";
  o["-material_mu"]              = "1e4";
  o["-material_D"]               = "2e-6";
  o["-material_density"]         = "1100";
  o["-failure_critical_stretch"] = "7.2";
  o["-horizon_factor"]           = "2.515";
  o["-body_notches"]             = "0.05,0.02,0.08,0.02";
  o["-load_bottom_layers"]       = "3";
  o["-load_sets"]                = "top,bottom,side";
  o["-load_side_region"]         = "box";
  o["-load_side_box"]            = "0,0.06,0.005,0.1";
  o["-load_side_x"]              = "fixed";
  o["-load_reference_length"]    = "0.1";
  o["-time_step"]                = "1e-5";
  o["-time_step_safety"]         = "0.5";
  o["-end_time"]                 = "3";
  o["-progress_interval"]        = "50";
  o["-force_stress_correction"]  = "tensor";
  o["-load_grip_field"]          = "affine";
  Scene scene;
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.material.stress_correction, bapd::StressCorrection::tensor);
  EXPECT_EQ(scene.loading.grip_field, bapd::GripField::affine);
  EXPECT_EQ(scene.material.model, bapd::ModelKind::neo_hookean);
  EXPECT_EQ(scene.material.formulation, bapd::Formulation::plane_strain);
  EXPECT_EQ(scene.material.parameters.mu, 1e4);
  EXPECT_EQ(scene.material.parameters.D, 2e-6);
  EXPECT_EQ(scene.material.density, 1100.0);
  EXPECT_TRUE(scene.failure.enabled);
  EXPECT_EQ(scene.failure.critical_stretch, 7.2);
  EXPECT_EQ(scene.body.horizon_factor, 2.515);
  ASSERT_EQ(scene.body.sheet.notches.size(), 1u);
  EXPECT_EQ(scene.body.sheet.notches[0].x1, 0.08);
  EXPECT_EQ(scene.loading.sets[1].layers, 3);
  ASSERT_EQ(scene.loading.sets.size(), 3u);
  EXPECT_EQ(scene.loading.sets[2].region, LoadSet::Region::box);
  EXPECT_EQ(scene.loading.sets[2].box[1], 0.06);
  EXPECT_EQ(scene.loading.sets[2].box[2], 0.005);
  EXPECT_EQ(scene.loading.sets[2].y, ComponentLoad::free);
  EXPECT_EQ(scene.loading.reference_length, 0.1);
  EXPECT_EQ(scene.time_stepping.step, 1e-5);
  EXPECT_EQ(scene.time_stepping.safety, 0.5);
  EXPECT_EQ(scene.time_stepping.end_time, 3.0);
  EXPECT_EQ(scene.time_stepping.progress_interval, 50);
  // A stretch grip without a scale moves by (lambda - 1) L.
  o.erase("-load_top_y_scale");
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.loading.sets[0].y_scale, 1.0);
  // The underscore spelling of the model name is accepted too.
  o["-material_model"] = "neo_hookean";
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.material.model, bapd::ModelKind::neo_hookean);
}

TEST_F(SceneOptions, YAMLFileGivesTheSameSceneAsFlatOptions)
{
  Scene flat, yaml;
  ASSERT_EQ(Read(PlateWithHole(), &flat), 0) << bapd::test::UserErrorText();
  PetscOptionsClear(nullptr);
  const std::string file = TempFile(kPlateYAML);
  ASSERT_EQ(PetscOptionsInsertFileYAML(PETSC_COMM_WORLD, nullptr, file.c_str(), PETSC_TRUE), 0);
  RemoveFile(file);
  ASSERT_EQ(bapd::SceneFromOptions(PETSC_COMM_WORLD, &yaml), 0) << bapd::test::UserErrorText();
  ExpectSameScene(flat, yaml);
  EXPECT_EQ(bapd::CheckUnusedOptions(PETSC_COMM_WORLD), 0) << bapd::test::UserErrorText();
}

TEST_F(SceneOptions, OptionsAfterTheFileOverrideIt)
{
  // What "bapd -options_file_yaml plate.yaml -material_mu 5000 ..." does: the file
  // is inserted first, the later options replace its values.
  PetscOptionsClear(nullptr);
  const std::string file = TempFile(kPlateYAML);
  ASSERT_EQ(PetscOptionsInsertFileYAML(PETSC_COMM_WORLD, nullptr, file.c_str(), PETSC_TRUE), 0);
  RemoveFile(file);
  ASSERT_EQ(PetscOptionsInsertString(nullptr, "-material_mu 5000 -load_top_y_scale 0.25 -load_schedule 0,1,4,2 -body_holes 0.04,0.08,0.02"), 0);
  Scene scene;
  ASSERT_EQ(bapd::SceneFromOptions(PETSC_COMM_WORLD, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.material.parameters.mu, 5000.0);
  EXPECT_EQ(scene.material.parameters.D, 2.0 / (100.0 * 5000.0)); // the file's bulk ratio, the new mu
  EXPECT_EQ(scene.loading.sets[0].y_scale, 0.25);
  EXPECT_EQ(scene.loading.sets[1].y_scale, -0.5); // untouched
  EXPECT_EQ(scene.loading.schedule.time, (std::vector<double>{0, 4}));
  EXPECT_EQ(scene.time_stepping.end_time, 4.0);
  EXPECT_EQ(scene.body.sheet.holes[0].radius, 0.02);
  EXPECT_EQ(scene.body.sheet.width, 0.08); // from the file
}

TEST_F(SceneOptions, WarnsAboutDoubtfulButUsableValues)
{
  Options o = PlateWithHole();
  o["-load_top_x"] = "free";
  o["-load_top_y"] = "free";
  o.erase("-load_top_y_scale");
  o["-time_step_safety"] = "1.5";
  o["-horizon_factor"]   = "6";
  Scene scene;
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  const std::vector<std::string> &w = bapd::SceneWarnings();
  auto any = [&](const char *text) {
    for (const std::string &m : w)
      if (m.find(text) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(any("load set 'top' holds neither component")) << ::testing::PrintToString(w);
  EXPECT_TRUE(any("-time_step_safety 1.5")) << ::testing::PrintToString(w);
  EXPECT_TRUE(any("-horizon_factor 6")) << ::testing::PrintToString(w);
}

// A scene may carry the parameters of laws it does not use (one file for a study that
// switches -material_model); they are ignored, and one warning names each with its law
// and the law in use. The law's own parameters draw none.
TEST_F(SceneOptions, WarnsOnceAboutParametersOfLawsNotInUse)
{
  Options o = PlateWithHole();
  o["-material_Jm"] = "100"; // Gent's own: no warning
  Scene own;
  ASSERT_EQ(Read(o, &own), 0) << bapd::test::UserErrorText();
  EXPECT_TRUE(bapd::SceneWarnings().empty()) << ::testing::PrintToString(bapd::SceneWarnings());

  o["-material_lambda_m"]  = "-1"; // invalid for Arruda-Boyce, but unused here
  o["-material_ogden_mu1"] = "3000";
  Scene scene;
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  const std::vector<std::string> &w = bapd::SceneWarnings();
  ASSERT_EQ(w.size(), 1u) << ::testing::PrintToString(w);
  EXPECT_NE(w[0].find("-material_lambda_m (arruda_boyce), -material_ogden_mu1 (ogden)"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("the law is gent (-material_model)"), std::string::npos) << w[0];
  EXPECT_EQ(w[0].find("-material_Jm"), std::string::npos) << w[0];

  o["-material_model"] = "arruda_boyce"; // now -material_lambda_m is the law's own, and checked
  EXPECT_NE(Rejection(o).find("-material_lambda_m"), std::string::npos);
}

// The paper's method (docs/options.md, "The paper's method"): one row of the
// specimen's own edge per grip, rigid, the bond-only force uncorrected.
TEST_F(SceneOptions, PaperGripsAreOneRigidRowInsideTheSpecimen)
{
  Options o = PlateWithHole();
  o["-force_form"] = "bond_only";
  Scene corrected; // auto: the bond-only form is tensor-corrected unless told otherwise
  ASSERT_EQ(Read(o, &corrected), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(corrected.material.stress_correction, bapd::StressCorrection::tensor);
  o["-load_grip_placement"] = "inside";
  o["-force_stress_correction"] = "none";
  Scene scene;
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.material.force_form, bapd::ForceForm::bond_only);
  for (const LoadSet &l : scene.loading.sets) {
    EXPECT_EQ(l.placement, bapd::GripPlacement::inside);
    EXPECT_EQ(l.layers, 1);
  }
  EXPECT_FALSE(scene.body.sheet.grip_rows.any());
  EXPECT_EQ(scene.loading.grip_field, bapd::GripField::rigid);
  EXPECT_EQ(scene.material.stress_correction, bapd::StressCorrection::none);
  EXPECT_EQ(scene.loading.reference_length, 0.16); // the whole height, as the paper measures it
}

TEST_F(SceneOptions, GripDepthInRowsOrMetresAndPerSetPlacement)
{
  Options o = PlateWithHole();
  o["-load_top_depth"] = "0.004";      // rows at 0.5 .. 3.5 mm: 4
  o["-load_bottom_placement"] = "inside";
  o["-load_bottom_layers"] = "2";
  o["-horizon_factor"] = "2.515";
  Scene scene;
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(scene.loading.sets[0].placement, bapd::GripPlacement::outside);
  EXPECT_EQ(scene.loading.sets[0].layers, 4);
  EXPECT_EQ(scene.loading.sets[1].placement, bapd::GripPlacement::inside);
  EXPECT_EQ(scene.loading.sets[1].layers, 2);
  EXPECT_EQ(scene.body.sheet.grip_rows.top, 4);
  EXPECT_EQ(scene.body.sheet.grip_rows.bottom, 0);
  EXPECT_EQ(scene.loading.grip_field, bapd::GripField::rigid); // affine by default only with both grips outside
  // The default depth is two horizons: 2 x 2.515 dx holds 5 row centres, 2 x 3.515 dx 7.
  for (const auto &[factor, rows] : {std::pair{"2.515", 5}, {"3.015", 6}, {"3.515", 7}}) {
    Options d = PlateWithHole();
    d["-horizon_factor"] = factor;
    ASSERT_EQ(Read(d, &scene), 0) << bapd::test::UserErrorText();
    EXPECT_EQ(scene.loading.sets[0].layers, rows) << factor;
    EXPECT_EQ(scene.body.sheet.grip_rows.bottom, rows) << factor;
  }
  EXPECT_EQ(bapd::GripRows(6 * 0.0005, 0.0005), 6); // whole rows given in metres keep their count
  EXPECT_EQ(bapd::GripRows(0.1e-3, 1e-3), 1);       // at least one row
}

} // namespace
