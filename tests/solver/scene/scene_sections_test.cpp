// The scene's output and time-stepping sections (scene_output.cpp,
// scene_time_stepping.cpp): the options of field files, checkpoints, the damping route
// and the stable step's re-estimate are read, listed under -help, checked and known to
// the typo check with the rest of the scene, from the sections' option tables, and the
// components take them from the Scene.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cctype>
#include <map>
#include <string>

#include "bapd/solver/input/options.hpp"
#include "bapd/solver/input/scene.hpp"
#include "scene_reading.hpp"

namespace {

using bapd::Scene;
using Options = std::map<std::string, std::string>; // name -> value ("" for none)

// A small sheet pulled by two edge grips.
Options Sheet()
{
  return {
    {"-body_width", "0.02"},          {"-body_height", "0.04"},      {"-body_thickness", "0.001"}, {"-body_dx", "0.002"},
    {"-load_sets", "top,bottom"},     {"-load_top_region", "top"},   {"-load_top_y", "stretch"},   {"-load_top_y_scale", "0.5"},
    {"-load_bottom_region", "bottom"}, {"-load_bottom_y", "stretch"}, {"-load_bottom_y_scale", "-0.5"},
    {"-load_schedule", "0,1,1,1.5"},   {"-output_dir", "out/sections"},
  };
}

Options With(Options o, const Options &change)
{
  for (const auto &[name, value] : change) o[name] = value;
  return o;
}

class SceneSections : public bapd::test::SceneReading<Options> {};

// Whether `text` names option `name` itself (not only a longer one it begins).
bool Lists(const std::string &text, const std::string &name)
{
  for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
    const char next = at + name.size() < text.size() ? text[at + name.size()] : ' ';
    if (!(std::isalnum(static_cast<unsigned char>(next)) || next == '_')) return true;
  }
  return false;
}

// -help from the scene alone lists the sections' options. It must come first in the
// file (CaptureHelp, scene_reading.hpp).
TEST_F(SceneSections, HelpOfTheSceneListsTheOutputAndTimeSteppingSections)
{
  std::string text;
  Scene       scene;
  const PetscErrorCode ierr = bapd::test::CaptureHelp([&] { return Read({{"-help", ""}}, &scene); }, &text);
  ASSERT_EQ(ierr, 0) << bapd::test::UserErrorText();
  for (const char *name : {"-output_fields", "-output_fields_interval", "-output_fields_geometry", "-checkpoint_interval", "-checkpoint_on_error",
                           "-restart", "-restart_discard_newer", "-relaxation", "-time_step_reestimate", "-time_step_estimate",
                           "-time_step_crack_tip", "-solver", "-static_stretch_step"})
    EXPECT_TRUE(Lists(text, name)) << name << " missing from the scene's -help";
}

TEST_F(SceneSections, ReadsFieldsCheckpointsRelaxationAndTheReestimateIntoTheScene)
{
  Scene scene;
  ASSERT_EQ(Read(Sheet(), &scene), 0) << bapd::test::UserErrorText();
  EXPECT_FALSE(scene.output.fields.enabled); // the defaults
  EXPECT_EQ(scene.output.fields.geometry, bapd::FieldGeometry::current);
  EXPECT_FALSE(scene.output.checkpoint.periodic());
  EXPECT_TRUE(scene.output.checkpoint.on_error);
  EXPECT_EQ(scene.time_stepping.relaxation, bapd::RelaxationKind::none);
  EXPECT_EQ(scene.time_stepping.reestimate.interval, 50);
  EXPECT_TRUE(scene.time_stepping.reestimate.startup_krylov);

  const Options given = With(Sheet(), {{"-output_fields", ""},
                                       {"-output_fields_interval", "25"},
                                       {"-output_fields_geometry", "Reference"},
                                       {"-checkpoint_interval", "10min"},
                                       {"-checkpoint_on_error", "false"},
                                       {"-restart_discard_newer", ""},
                                       {"-relaxation", "adaptive"},
                                       {"-time_step_reestimate", "7"},
                                       {"-time_step_estimate", "power"},
                                       {"-time_step_crack_tip", "0"}});
  ASSERT_EQ(Read(given, &scene), 0) << bapd::test::UserErrorText();
  EXPECT_TRUE(scene.output.fields.enabled);
  EXPECT_EQ(scene.output.fields.interval, 25);
  EXPECT_EQ(scene.output.fields.geometry, bapd::FieldGeometry::reference);
  EXPECT_EQ(scene.output.checkpoint.step_interval, 0);
  EXPECT_EQ(scene.output.checkpoint.wall_interval, 600.0);
  EXPECT_FALSE(scene.output.checkpoint.on_error);
  EXPECT_TRUE(scene.output.checkpoint.discard_newer);
  EXPECT_EQ(scene.output.checkpoint.restart, "");
  EXPECT_EQ(scene.time_stepping.relaxation, bapd::RelaxationKind::adaptive);
  EXPECT_EQ(scene.time_stepping.reestimate.interval, 7);
  EXPECT_FALSE(scene.time_stepping.reestimate.startup_krylov);
  EXPECT_EQ(scene.time_stepping.reestimate.tip, 0);
  EXPECT_EQ(bapd::CheckUnusedOptions(PETSC_COMM_WORLD), 0) << bapd::test::UserErrorText();
}

// Each option lands in its section, which is what the component that reads it takes
// (ForceOperator and TangentOperator: the material; TimeStepControl: the time stepping).
TEST_F(SceneSections, EachOptionLandsInItsSection)
{
  Scene scene;
  ASSERT_EQ(Read(With(Sheet(), {{"-material_volumetric_stabilisation", "4"}, {"-time_step_travel", "0.2"}, {"-time_step_band", "0.1"}}), &scene),
            0)
    << bapd::test::UserErrorText();
  const bapd::MaterialSection &material = scene.material;
  EXPECT_EQ(material.volumetric_stabilisation, 4.0);
  EXPECT_EQ(material.force_form, bapd::ForceForm::energy_consistent);
  const bapd::TimeSteppingSection &stepping = scene.time_stepping;
  EXPECT_EQ(stepping.travel, 0.2);
  EXPECT_EQ(stepping.reestimate.band, 0.1);
  EXPECT_EQ(scene.body.sheet.dx, 0.002);
}

TEST_F(SceneSections, RejectsEachBadSectionValueNamingItsOption)
{
  const std::map<std::string, Options> cases = {
    {"-relaxation", {{"-relaxation", "fast"}}},
    {"-output_fields_geometry", {{"-output_fields_geometry", "deformed"}}},
    {"-output_fields_interval", {{"-output_fields_interval", "-1"}}},
    {"-checkpoint_interval", {{"-checkpoint_interval", "10parsecs"}}},
    {"-time_step_estimate", {{"-time_step_estimate", "lanczos"}}},
    {"-time_step_reestimate", {{"-time_step_reestimate", "-1"}}},
    {"-time_step_band", {{"-time_step_band", "0.5"}}},
    {"-time_step_crack_tip", {{"-time_step_crack_tip", "16"}}},
  };
  for (const auto &[option, change] : cases) {
    const std::string message = Rejection(With(Sheet(), change));
    EXPECT_EQ(message.find(option), 0u) << option << ": " << message;
  }
}

TEST_F(SceneSections, AMisspeltSectionOptionIsAnsweredWithItsName)
{
  Scene scene;
  ASSERT_EQ(Read(With(Sheet(), {{"-relaxaton", "adaptive"}}), &scene), 0) << bapd::test::UserErrorText();
  EXPECT_EQ(bapd::CheckUnusedOptions(PETSC_COMM_WORLD), PETSC_ERR_USER);
  EXPECT_EQ(bapd::test::UserErrorText(), "-relaxaton is not a bapd option. Did you mean -relaxation? (run with -help to list every option)");
}

} // namespace
