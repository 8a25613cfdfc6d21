// PETSc's -help lines as bapd prints them (help.hpp).
#include <gtest/gtest.h>

#include "bapd/solver/input/help.hpp"

namespace {

TEST(Help, RequiredOptionShowsRequiredNotPetscsZero)
{
  EXPECT_EQ(bapd::TidyHelpLine("  -body_width <0. : 0.>: Sheet width along x [m] (required) (docs/options.md)\n"),
            "  -body_width <required>                Sheet width along x [m]\n");
  // Given by the scene: its value.
  EXPECT_EQ(bapd::TidyHelpLine("  -body_width <0.07 : 0.>: Sheet width along x [m] (required) (docs/options.md)\n"),
            "  -body_width <0.07>                    Sheet width along x [m]\n");
}

TEST(Help, ValuesWithoutPetscsDotsAndDefaultsWhereTheSceneDiffers)
{
  EXPECT_EQ(bapd::TidyHelpLine("  -material_mu <4550. : 4550.>: Shear modulus mu [Pa] (docs/options.md)\n"),
            "  -material_mu <4550>                   Shear modulus mu [Pa]\n");
  EXPECT_EQ(bapd::TidyHelpLine("  -load_top_y <now stretch : formerly free>: y component (docs/options.md)\n"),
            "  -load_top_y <stretch, default free>   y component\n");
  EXPECT_EQ(bapd::TidyHelpLine("  -output_fields: <FALSE : FALSE> Write the point fields (docs/options.md)\n"),
            "  -output_fields <false>                Write the point fields\n");
  EXPECT_EQ(bapd::TidyHelpLine("  -restart <now  : formerly >: Continue from this checkpoint file (docs/options.md)\n"),
            "  -restart <none>                       Continue from this checkpoint file\n");
}

TEST(Help, Lists)
{
  EXPECT_EQ(bapd::TidyHelpLine("  -body_holes <0.>: Circular holes [m] (docs/options.md)\n"),
            "  -body_holes <none>                    Circular holes [m]\n");
  EXPECT_EQ(bapd::TidyHelpLine("  -load_schedule <0.,1.,1.,5.125>: Stretch schedule (docs/options.md)\n"),
            "  -load_schedule <0,1,1,5.125>          Stretch schedule\n");
  EXPECT_EQ(bapd::TidyHelpLine("  -probes <string1,string2,...>: Names of the probes (docs/options.md)\n"),
            "  -probes <names>                       Names of the probes\n");
}

TEST(Help, OtherLines)
{
  EXPECT_EQ(bapd::TidyHelpLine("----------------------------------------\n"), "\n");
  EXPECT_EQ(bapd::TidyHelpLine("Body: a plane sheet:\n"), "Body: a plane sheet:\n");
  EXPECT_EQ(bapd::TidyHelpLine("  -log_view ascii[:[filename]]: Prints object (PetscOptionsGetViewer)\n"), "");
}

} // namespace
