// Reading test curves (fit_data.hpp): units, the mode line and tag, and one message
// naming the file for each kind of bad data.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "fit_data.hpp"
#include "fit_error.hpp"

namespace bapd::fit {
namespace {

std::string write(const std::string &name, const std::string &text)
{
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const std::string &path, const std::string &tag = "")
{
  try {
    read_curve(path, tag);
  } catch (const FitError &e) {
    return e.what();
  }
  return "";
}

TEST(FitData, ReadsUnitsModeLineAndTag)
{
  const std::string path = write("kpa.csv", "# mode: pure_shear\n# a comment\nstretch,nominal_stress_kPa\n1.5,2.5\n2.0,4.0\n");
  const Curve       c    = read_curve(path, "");
  EXPECT_EQ(c.mode, LoadMode::pure_shear);
  ASSERT_EQ(c.stress_Pa.size(), 2u);
  EXPECT_EQ(c.stress_Pa[0], 2500.0);
  EXPECT_EQ(read_curve(path, "uniaxial").mode, LoadMode::uniaxial); // the tag wins
  const Curve pa = read_curve(write("pa.csv", "time_s,stretch,stress_Pa\n0,1.1,10\n1,1.2,20\n"), "equibiaxial");
  EXPECT_EQ(pa.stretch[1], 1.2);
  EXPECT_EQ(pa.stress_Pa[1], 20.0);
}

TEST(FitData, EachKindOfBadDataGetsAMessageNamingTheFile)
{
  const std::string head = "# mode: uniaxial\nstretch,nominal_stress_Pa\n";
  struct Case {
    std::string text, expect;
  };
  for (const Case &c : {Case{head + "1.2,10\n1.1,20\n", "must increase strictly"},
                        Case{head + "1.2,10\n1.2,20\n", "must increase strictly"},
                        Case{head + "1.0,0\n1.2,20\n", "stretches > 1"},
                        Case{head + "1.1,10\n1.2,-20\n", "negative nominal stress"},
                        Case{head + "1.1,10\n", "at least 2"},
                        Case{head + "1.1,ten\n1.2,20\n", "'ten' is not a number"},
                        Case{"# mode: uniaxial\nstretch,force_N\n1.1,1\n1.2,2\n", "stress column named with its unit"},
                        Case{"stretch,stress_Pa\n1.1,1\n1.2,2\n", "which test is it?"},
                        Case{"# mode: torsion\nstretch,stress_Pa\n1.1,1\n1.2,2\n", "'torsion' is not a test"}}) {
    const std::string path = write("bad.csv", c.text), what = error_of(path);
    EXPECT_NE(what.find(c.expect), std::string::npos) << what;
    EXPECT_EQ(what.find(path), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
  EXPECT_NE(error_of("/nonexistent/x.csv").find("cannot open"), std::string::npos);
}

} // namespace
} // namespace bapd::fit
