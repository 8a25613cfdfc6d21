// The words of an enum's values (enum_words.hpp): to_string and parse read one table,
// so every value's word parses back to it, and a word not in the table is refused
// without touching the value.
#include <gtest/gtest.h>

#include <string>

#include "bapd/core/enum_words.hpp"
#include "bapd/core/kernel/force_form.hpp"
#include "bapd/core/kernel/softening_law.hpp"
#include "bapd/core/kernel/stress_correction.hpp"

namespace bapd {
namespace {

TEST(EnumWords, EveryWordParsesBackToItsValue)
{
  for (Softening s : {Softening::none, Softening::linear, Softening::exponential, Softening::time}) {
    Softening back = s == Softening::none ? Softening::linear : Softening::none;
    ASSERT_TRUE(softening_words.parse(to_string(s), back)) << to_string(s);
    EXPECT_EQ(back, s);
  }
  for (StressCorrection c : {StressCorrection::none, StressCorrection::tensor, StressCorrection::scalar}) {
    StressCorrection back = c == StressCorrection::none ? StressCorrection::tensor : StressCorrection::none;
    ASSERT_TRUE(parse(to_string(c), back)) << to_string(c);
    EXPECT_EQ(back, c);
  }
  EXPECT_STREQ(to_string(ForceForm::energy_consistent), "energy_consistent");
}

TEST(EnumWords, AWordNotInTheTableIsRefusedAndLeavesTheValue)
{
  ForceForm form = ForceForm::bond_only;
  EXPECT_FALSE(force_form_words.parse("bond-only", form)); // the table's words only: callers normalise
  EXPECT_FALSE(force_form_words.parse("", form));
  EXPECT_EQ(form, ForceForm::bond_only);
  constexpr EnumWords<Softening::exponential> words{"none", "linear", "exponential"};
  static_assert(words.size == 3);
  EXPECT_STREQ(words(static_cast<Softening>(7)), "?"); // a value outside the enum has no word
}

} // namespace
} // namespace bapd
