// Typo suggestions for option names (option_suggest.hpp).
#include <gtest/gtest.h>

#include "bapd/solver/input/option_suggest.hpp"

using bapd::EditDistance;
using bapd::SuggestOption;

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps)
{
  EXPECT_EQ(EditDistance("", ""), 0u);
  EXPECT_EQ(EditDistance("", "abc"), 3u);
  EXPECT_EQ(EditDistance("material_muu", "material_mu"), 1u); // one insertion
  EXPECT_EQ(EditDistance("body_dy", "body_dx"), 1u);           // one substitution
  EXPECT_EQ(EditDistance("body_widht", "body_width"), 1u);     // one adjacent swap
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(EditDistance("Material_JM", "material_jm"), 0u);   // case is ignored, as PETSc does
}

TEST(EditDistance, IsSymmetric)
{
  for (const char *a : {"load_top_y", "probe_tip_at", "x"})
    for (const char *b : {"load_tpo_y", "probes", ""}) EXPECT_EQ(EditDistance(a, b), EditDistance(b, a)) << a << " vs " << b;
}

TEST(SuggestOption, FindsTheNearestKnownName)
{
  const std::vector<std::string> known = {"-material_mu", "-material_Jm", "-material_D", "-body_width", "-body_dx", "-load_top_y_scale"};
  EXPECT_EQ(SuggestOption("-material_muu", known), "-material_mu");
  EXPECT_EQ(SuggestOption("-body_widht", known), "-body_width");
  EXPECT_EQ(SuggestOption("-load_top_yscale", known), "-load_top_y_scale");
  EXPECT_EQ(SuggestOption("-MATERIAL_JM", known), "-material_Jm"); // answered in the documented spelling
}

TEST(SuggestOption, FindsANameGivenWithoutItsPrefix)
{
  const std::vector<std::string> known = {"-material_mu", "-body_dx", "-body_width"};
  EXPECT_EQ(SuggestOption("-dx", known), "-body_dx");
  EXPECT_EQ(SuggestOption("-mu", known), "-material_mu");
}

TEST(SuggestOption, StaysSilentForUnrelatedNames)
{
  const std::vector<std::string> known = {"-material_mu", "-body_dx"};
  EXPECT_EQ(SuggestOption("-completely_unrelated", known), "");
  EXPECT_EQ(SuggestOption("-material_mu", {}), "");
}

TEST(SuggestOption, BreaksTiesAlphabetically)
{
  // Both are one substitution away: the answer must not depend on the list order.
  EXPECT_EQ(SuggestOption("-aa", {"-ac", "-ab"}), "-ab");
  EXPECT_EQ(SuggestOption("-aa", {"-ab", "-ac"}), "-ab");
}
