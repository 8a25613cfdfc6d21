// Scene options (scene.hpp) refused: every invalid input is rejected by a message
// naming its option, and an option that nothing read is answered with the nearest
// real name or with the set list it is missing from.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <map>
#include <string>
#include <vector>

#include "bapd/solver/input/scene.hpp"
#include "bapd/solver/input/scene_input.hpp"
#include "plate_options.hpp"
#include "scene_reading.hpp"

namespace {

using bapd::Scene;
using bapd::test::PlateWithHole;

using Options = bapd::test::PlateOptions;

class SceneOptions : public bapd::test::SceneReading<Options> {};

// ----------------------------------------------------------------------------------
// Invalid scenes: each is rejected, and the message names the option to change.

struct Case {
  const char *what;
  Options     change;          // options set on top of the plate ("<erase>" removes one)
  const char *option;          // must appear in the message
  const char *detail = nullptr; // and so must this, if given
};

Options Apply(Options base, const Options &change)
{
  for (const auto &[name, value] : change) {
    if (value == "<erase>") base.erase(name);
    else base[name] = value;
  }
  return base;
}

// The body: its size, spacing, holes, notches and horizon.
const std::vector<Case> kBodyCases = {
  {"width missing", {{"-body_width", "<erase>"}}, "-body_width", "required"},
  {"height zero", {{"-body_height", "0"}}, "-body_height", "> 0"},
  {"thickness negative", {{"-body_thickness", "-0.001"}}, "-body_thickness"},
  {"dx zero", {{"-body_dx", "0"}}, "-body_dx"},
  {"dx larger than the body", {{"-body_dx", "0.1"}}, "-body_dx", "larger than the body"},
  {"width not a number", {{"-body_width", "8cm"}}, "-body_width", "not a number"},
  {"width without value", {{"-body_width", ""}}, "-body_width", "needs a value"},
  {"holes not triples", {{"-body_holes", "0.04,0.08"}}, "-body_holes", "multiple of 3"},
  {"hole list malformed", {{"-body_holes", "0.04,x,0.01"}}, "-body_holes", "not a number"},
  {"hole radius zero", {{"-body_holes", "0.04,0.08,0"}}, "-body_holes", "radius"},
  {"hole out of reach", {{"-body_holes", "0.2,0.08,0.01"}}, "-body_holes", "does not reach the body"},
  {"hole covers the body", {{"-body_holes", "0.04,0.08,1"}}, "-body_holes", "no material"},
  {"notches not quadruples", {{"-body_notches", "0.01,0.02,0.03"}}, "-body_notches", "multiple of 4"},
  {"notch end outside", {{"-body_notches", "0.05,0.02,0.09,0.02"}}, "-body_notches", "outside the body"},
  {"notch of zero length", {{"-body_notches", "0.05,0.02,0.05,0.02"}}, "-body_notches", "zero length"},
  {"notch across the width", {{"-body_notches", "0,0.02,0.08,0.02"}}, "-body_notches", "top and a bottom piece"},
  {"notch across the height", {{"-body_notches", "0.02,0,0.02,0.16"}}, "-body_notches", "left and a right piece"},
  {"two notches across", {{"-body_notches", "0,0.02,0.05,0.02,0.049,0.02,0.08,0.03"}}, "-body_notches", "together join"},
  {"notches through the hole", {{"-body_notches", "0,0.08,0.031,0.08,0.049,0.08,0.08,0.08"}}, "-body_notches", "hole 1"},
  {"holes across the width", {{"-body_holes", "0.02,0.08,0.02,0.06,0.08,0.02"}}, "-body_holes", "hole 1, hole 2 together join the left and right edges"},
  {"notch cutting a corner", {{"-body_notches", "0,0.15,0.01,0.16"}}, "-body_notches", "top-left corner"},
  {"horizon below one spacing", {{"-horizon_factor", "0.5"}}, "-horizon_factor"},
};

// The grips' placement and depth, and the material.
const std::vector<Case> kGripAndMaterialCases = {
  {"unknown placement", {{"-load_grip_placement", "beside"}}, "-load_grip_placement", "outside or inside"},
  {"unknown set placement", {{"-load_top_placement", "over"}}, "-load_top_placement", "outside, inside or auto"},
  {"depth and layers", {{"-load_top_depth", "0.003"}, {"-load_top_layers", "3"}}, "-load_top_depth", "keep one"},
  {"depth zero", {{"-load_top_depth", "0"}}, "-load_top_depth", "> 0"},
  // material
  {"unknown model", {{"-material_model", "mooney"}}, "-material_model", "choose gent, neo_hookean, "},
  {"unknown formulation", {{"-material_formulation", "3d"}}, "-material_formulation", "plane_stress, plane_strain or plane_stress_incompressible"},
  {"mu zero", {{"-material_mu", "0"}}, "-material_mu"},
  {"mu negative", {{"-material_mu", "-4550"}}, "-material_mu"},
  {"Jm zero", {{"-material_Jm", "0"}}, "-material_Jm"},
  {"D negative", {{"-material_bulk_ratio", "<erase>"}, {"-material_D", "-1e-6"}}, "-material_D"},
  {"D and bulk ratio", {{"-material_D", "1e-6"}}, "-material_bulk_ratio", "only one"},
  {"bulk ratio zero", {{"-material_bulk_ratio", "0"}}, "-material_bulk_ratio"},
  {"density zero", {{"-material_density", "0"}}, "-material_density"},
  {"critical stretch below one", {{"-failure_critical_stretch", "0.9"}}, "-failure_critical_stretch", "> 1"},
  {"unknown stress correction", {{"-force_stress_correction", "matrix"}}, "-force_stress_correction", "none (the paper's force), tensor, scalar or auto"},
};

// The load sets, their regions and components, and the schedule.
const std::vector<Case> kLoadingCases = {
  {"set name with a dash", {{"-load_sets", "top-grip"}}, "-load_sets", "letters"},
  {"set listed twice", {{"-load_sets", "top,bottom,top"}}, "-load_sets", "twice"},
  {"region missing", {{"-load_top_region", "<erase>"}}, "-load_top_region", "required"},
  {"unknown region", {{"-load_top_region", "middle"}}, "-load_top_region", "top, bottom, left, right, box, "},
  {"polygon without points", {{"-load_top_region", "polygon"}}, "-load_top_points", "required"},
  {"polygon of two vertices", {{"-load_top_region", "polygon"}, {"-load_top_points", "0,0,0.01,0"}}, "-load_top_points", "at least 3 vertices"},
  {"polygon crossing itself", {{"-load_top_region", "polygon"}, {"-load_top_points", "0,0,0.01,0.01,0.01,0,0,0.01"}}, "-load_top_points", "cross"},
  {"polygon off the body", {{"-load_top_region", "polygon"}, {"-load_top_points", "0.1,0.1,0.2,0.1,0.2,0.2"}}, "-load_top_points", "outside the body"},
  {"polygon with a depth", {{"-load_top_region", "polygon"}, {"-load_top_points", "0,0,0.01,0,0,0.01"}, {"-load_top_depth", "0.001"}}, "-load_top_depth", "edge regions, curve and group"},
  {"polygon placed outside", {{"-load_top_region", "polygon"}, {"-load_top_points", "0,0,0.01,0,0,0.01"}, {"-load_top_placement", "outside"}}, "-load_top_placement", "holds the body's own points"},
  {"curve of one vertex", {{"-load_top_region", "curve"}, {"-load_top_points", "0,0.16"}}, "-load_top_points", "at least 2 vertices"},
  {"curve points odd", {{"-load_top_region", "curve"}, {"-load_top_points", "0,0.16,0.08"}}, "-load_top_points", "x,y pairs"},
  {"box placed outside", {{"-load_top_region", "box"}, {"-load_top_box", "0,0.15,0.08,0.16"}, {"-load_top_placement", "outside"}}, "-load_top_placement", "only the edge regions"},
  {"points on an edge region", {{"-load_top_points", "0,0.16,0.08,0.16"}}, "-load_top_points", "regions polygon and curve"},
  {"group without a name", {{"-load_top_region", "group"}}, "-load_top_group", "required"},
  {"group without a Gmsh body", {{"-load_top_region", "group"}, {"-load_top_group", "grip"}}, "-load_top_file", "reads 0 Gmsh files"},
  {"group file missing", {{"-load_top_region", "group"}, {"-load_top_group", "grip"}, {"-load_top_file", "no_such.geo"}}, "-load_top_group", "cannot open 'no_such.geo'"},
  {"group on an edge region", {{"-load_top_group", "grip"}}, "-load_top_group", "region group"},
  {"box missing", {{"-load_top_region", "box"}}, "-load_top_box", "required"},
  {"box of three numbers", {{"-load_top_region", "box"}, {"-load_top_box", "0,0,1"}}, "-load_top_box", "four"},
  {"box empty", {{"-load_top_region", "box"}, {"-load_top_box", "0,0.15,0,0.16"}}, "-load_top_box", "empty"},
  {"box outside", {{"-load_top_region", "box"}, {"-load_top_box", "0.1,0.1,0.2,0.2"}}, "-load_top_box", "outside the body"},
  {"box on an edge region", {{"-load_top_box", "0,0.15,0.08,0.16"}}, "-load_top_box", "region box"},
  {"layers zero", {{"-load_top_layers", "0"}}, "-load_top_layers"},
  {"layers not whole", {{"-load_top_layers", "1.5"}}, "-load_top_layers", "whole number"},
  {"layers through the body", {{"-load_top_placement", "inside"}, {"-load_top_layers", "160"}}, "-load_top_layers", "fewer rows"},
  {"unknown component load", {{"-load_top_x", "pull"}}, "-load_top_x", "free, fixed or stretch"},
  {"scale on a fixed component", {{"-load_top_x_scale", "0.5"}}, "-load_top_x_scale", "stretch"},
  {"stretch without schedule", {{"-load_schedule", "<erase>"}, {"-end_time", "1"}}, "-load_top_y", "-load_schedule"},
  {"schedule odd count", {{"-load_schedule", "0,1,1"}}, "-load_schedule", "pairs"},
  {"schedule times not increasing", {{"-load_schedule", "0,1,1,1.5,1,2"}}, "-load_schedule", "increase"},
  {"schedule negative time", {{"-load_schedule", "-1,1,1,1.5"}}, "-load_schedule", "t >= 0"},
  {"schedule stretch zero", {{"-load_schedule", "0,1,1,0"}}, "-load_schedule", "> 0"},
  {"reference length zero", {{"-load_reference_length", "0"}}, "-load_reference_length"},
  {"unknown grip field", {{"-load_grip_field", "mirror"}}, "-load_grip_field", "rigid, affine or auto"},
  {"grips pulled together by a negative scale", {{"-load_bottom_y", "fixed"}, {"-load_bottom_y_scale", "<erase>"}, {"-load_top_y_scale", "-1"}},
   "-load_top_y_scale -1", "toward each other"},
  {"grips pushed together by the lower scale", {{"-load_bottom_y_scale", "0.75"}}, "-load_bottom_y_scale 0.75", "(-0.25) (lambda - 1) L"},
  {"affine grips without a bottom grip", {{"-load_grip_field", "affine"}, {"-load_bottom_y", "free"}, {"-load_bottom_y_scale", "<erase>"}}, "-load_grip_field", "1 top and 0 bottom"},
};

// Probes, output and time stepping.
const std::vector<Case> kProbeOutputAndTimeCases = {
  {"probe outside", {{"-probe_left_mid_at", "0.1,0.08"}}, "-probe_left_mid_at", "outside the body"},
  {"probe in the hole", {{"-probe_left_mid_at", "0.04,0.08"}}, "-probe_left_mid_at", "inside hole 1"},
  {"probe position missing", {{"-probe_left_mid_at", "<erase>"}}, "-probe_left_mid_at", "required"},
  {"probe position of three numbers", {{"-probe_left_mid_at", "0,0.08,0"}}, "-probe_left_mid_at", "exactly two"},
  {"probe listed twice", {{"-probes", "left_mid,left_mid"}}, "-probes", "twice"},
  // output and time
  {"output interval zero", {{"-output_interval", "0"}}, "-output_interval"},
  {"time step negative", {{"-time_step", "-1e-5"}}, "-time_step"},
  {"safety zero", {{"-time_step_safety", "0"}}, "-time_step_safety"},
  {"damping negative", {{"-damping", "-1"}}, "-damping"},
  {"end time negative", {{"-end_time", "-1"}}, "-end_time"},
  {"progress interval negative", {{"-progress_interval", "-2"}}, "-progress_interval"},
  {"no end time and no schedule",
   {{"-load_schedule", "<erase>"}, {"-load_top_y", "fixed"}, {"-load_top_y_scale", "<erase>"}, {"-load_bottom_y", "fixed"}, {"-load_bottom_y_scale", "<erase>"}},
   "-end_time",
   "required"},
};

TEST_F(SceneOptions, RejectsEachInvalidInputNamingItsOption)
{
  for (const std::vector<Case> *cases : {&kBodyCases, &kGripAndMaterialCases, &kLoadingCases, &kProbeOutputAndTimeCases})
    for (const Case &c : *cases) {
      const std::string message = Rejection(Apply(PlateWithHole(), c.change));
      EXPECT_NE(message.find(c.option), std::string::npos) << c.what << ": message does not name " << c.option << ":\n  " << message;
      if (c.detail) {
        EXPECT_NE(message.find(c.detail), std::string::npos) << c.what << ": message lacks '" << c.detail << "':\n  " << message;
      }
    }
}

// ----------------------------------------------------------------------------------
// Options that nothing read

TEST_F(SceneOptions, UnusedOptionIsAnsweredWithTheNearestName)
{
  Options o          = PlateWithHole();
  o["-material_muu"] = "5000";
  Scene scene;
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  const PetscErrorCode ierr = bapd::CheckUnusedOptions(PETSC_COMM_WORLD);
  EXPECT_EQ(ierr, PETSC_ERR_USER);
  EXPECT_EQ(bapd::test::UserErrorText(), "-material_muu is not a bapd option. Did you mean -material_mu? (run with -help to list every option)");
}

TEST_F(SceneOptions, UnusedOptionsOfAnUndeclaredSetNameTheSetList)
{
  Options o               = PlateWithHole();
  o["-load_grip_region"]  = "left";
  o["-probe_tipp_at"]     = "0,0";
  o["-load_top_regoin"]   = "top";
  Scene scene;
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  const PetscErrorCode ierr = bapd::CheckUnusedOptions(PETSC_COMM_WORLD);
  EXPECT_EQ(ierr, PETSC_ERR_USER);
  const std::string message = bapd::test::UserErrorText();
  EXPECT_NE(message.find("-load_grip_region is not a bapd option. 'grip' is not one of -load_sets"), std::string::npos) << message;
  EXPECT_NE(message.find("-probe_tipp_at is not a bapd option. 'tipp' is not one of -probes"), std::string::npos) << message;
  EXPECT_NE(message.find("-load_top_regoin is not a bapd option. Did you mean -load_top_region?"), std::string::npos) << message;
}

// The options of a named set come from its option table (SetFamily): every option in it
// is read for a declared set, and answered with the set list for an undeclared one.
TEST_F(SceneOptions, EveryOptionOfASetTableIsReadAndNamesItsSetList)
{
  const std::map<std::string, std::string> declared = {{"-body_", "cut"}, {"-load_", "top"}, {"-probe_", "left_mid"}};
  const std::vector<bapd::SetFamily>       families = bapd::SetFamilies();
  ASSERT_EQ(families.size(), declared.size());
  Options given = PlateWithHole();
  given["-body_shapes"] = "cut";
  for (const bapd::SetFamily &f : families)
    for (const std::string &suffix : f.suffixes)
      given[f.head + declared.at(f.head) + suffix] = "1"; // (a value every kind parses; the checks may refuse it)
  Scene scene;
  Read(given, &scene);
  EXPECT_EQ(bapd::CheckUnusedOptions(PETSC_COMM_WORLD), 0) << bapd::test::UserErrorText();

  for (const bapd::SetFamily &f : families)
    for (const std::string &suffix : f.suffixes) { // one at a time: PETSc keeps a message of about 1000 characters
      Options           stray = PlateWithHole();
      const std::string name  = f.head + "zz" + suffix;
      stray[name]             = "1";
      ASSERT_EQ(Read(stray, &scene), 0) << bapd::test::UserErrorText();
      EXPECT_EQ(bapd::CheckUnusedOptions(PETSC_COMM_WORLD), PETSC_ERR_USER) << name;
      const std::string message = bapd::test::UserErrorText();
      EXPECT_EQ(message.find(name + " is not a bapd option. 'zz' is not one of " + f.list_option + ": add it there"), 0u) << message;
    }
}

TEST_F(SceneOptions, PetscRuntimeOptionsAreNotTypos)
{
  Options o = PlateWithHole();
  for (const char *name : {"-ts_type", "-ts_monitor", "-log_view", "-malloc_debug", "-options_left", "-info", "-on_error_abort",
                           "-viewer_binary_skip_info", "-vec_type", "-snes_monitor", "-ksp_type", "-pc_type", "-mat_type"})
    o[name] = "";
  Scene scene;
  ASSERT_EQ(Read(o, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(bapd::CheckUnusedOptions(PETSC_COMM_WORLD), 0) << bapd::test::UserErrorText();
}

} // namespace
