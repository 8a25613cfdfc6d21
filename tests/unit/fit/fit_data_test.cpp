// Reading test curves (fit_data.hpp): units, the mode line and tag, test machine
// exports (tests/data/fit: a comma CSV with units, a ';' CSV with decimal commas, a
// tab-separated one with a preamble and a units row) against the values computed by
// hand, the rows before loading starts dropped, and one message naming the file (and
// the column or the missing option) for each kind of bad data.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

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

std::string error_of(const std::string &path, const std::string &tag = "", const Specimen &specimen = {})
{
  try {
    read_curve(path, tag, specimen);
  } catch (const FitError &e) {
    return e.what();
  }
  return "";
}

// A notched pure-shear curve (toughness.hpp) reads as pure shear marked notched, with
// its gauge length (H0); past its largest stress the cut sheet's load cell may read
// below zero, before it not.
TEST(FitData, ReadsANotchedCurveWithItsHeightAndTheCutSheetsOffset)
{
  const std::string text = "Extension (mm),Load (N)\n0,0\n5,1.5\n10,2.0\n15,0.3\n20,-0.002\n";
  for (const std::string &tag : {std::string("notched_pure_shear"), std::string("Notched pure-shear")}) {
    const Curve c = read_curve(write("notched.csv", text), tag, Specimen{0.01, 2.1e-4});
    EXPECT_TRUE(c.notched) << tag;
    EXPECT_EQ(c.mode, LoadMode::pure_shear);
    EXPECT_EQ(c.gauge_length_m, 0.01);
    ASSERT_EQ(c.stretch.size(), 4u);
    EXPECT_DOUBLE_EQ(c.stretch[1], 2.0);
    EXPECT_LT(c.stress_Pa[3], 0.0);
  }
  const std::string line = write("notched_line.csv", "# mode: notched_pure_shear\n" + text);
  EXPECT_TRUE(read_curve(line, "", Specimen{0.01, 2.1e-4}).notched);
  // the tag wins: as un-notched pure shear the negative row is refused
  EXPECT_NE(error_of(line, "pure_shear", Specimen{0.01, 2.1e-4}).find("negative nominal stress"), std::string::npos);
  const std::string early = write("notched_early.csv", "# mode: notched_pure_shear\nstretch,stress_Pa\n1.5,10\n2,-1\n3,30\n4,0\n");
  EXPECT_NE(error_of(early).find("negative nominal stress"), std::string::npos) << error_of(early);
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
                        Case{head + "1.1,10\n1.2,20\n0.9,-5\n", "stretches > 1 once loading starts"},
                        Case{head + "1.1,10\n1.2,-20\n", "negative nominal stress"},
                        Case{head + "1.1,10\n", "at least 2"},
                        Case{head + "1.1,ten\n1.2,20\n", "'ten' is not a number"},
                        Case{"# mode: uniaxial\nstretch,stress\n1.1,1\n1.2,2\n", "column 'stress' (stress) needs its unit"},
                        Case{"# mode: uniaxial\nstretch,force\n1.1,1\n1.2,2\n", "column 'force' (force) needs its unit"},
                        Case{"# mode: uniaxial\nstretch,weight_g\n1.1,1\n1.2,2\n", "no header line names"},
                        Case{"# mode: uniaxial\n1.1,1\n1.2,2\n", "data before any header"},
                        Case{"# mode: uniaxial\nstretch,stress_Pa\n1.0,0\n1.2,20\n", "1 data point(s) once the 1 row(s)"},
                        Case{"stretch,stress_Pa\n1.1,1\n1.2,2\n", "which test is it?"},
                        Case{"# mode: torsion\nstretch,stress_Pa\n1.1,1\n1.2,2\n", "'torsion' is not a test"}}) {
    const std::string path = write("bad.csv", c.text), what = error_of(path);
    EXPECT_NE(what.find(c.expect), std::string::npos) << what;
    EXPECT_EQ(what.find(path), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
  EXPECT_NE(error_of("/nonexistent/x.csv").find("cannot open"), std::string::npos);
}


// The sample exports of tests/data/fit, with the values worked out by hand next to
// each test. The code rounds three times (the value read, its unit's factor, the
// division by the gauge length or the section) and the hand value once: 1e-15
// relative is a few ulps.
const std::string data_dir = BAPD_FIT_DATA_DIR;

void expect_curve(const Curve &c, const std::vector<double> &stretch, const std::vector<double> &stress_Pa)
{
  ASSERT_EQ(c.stretch.size(), stretch.size()) << c.file;
  for (std::size_t i = 0; i < stretch.size(); ++i) {
    EXPECT_NEAR(c.stretch[i], stretch[i], 1e-15 * stretch[i]) << c.file << " row " << i;
    EXPECT_NEAR(c.stress_Pa[i], stress_Pa[i], 1e-15 * stress_Pa[i]) << c.file << " row " << i;
  }
}

bool has_note(const Curve &c, const std::string &text)
{
  for (const std::string &n : c.notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

TEST(FitData, ReadsACommaExportOfExtensionAndForceWithUnits)
{
  // Time (s),Extension (mm),Load (N); gauge length 20 mm, section 10 mm^2:
  // lambda = 1 + e / 20 mm, P = F / 1e-5 m^2. Rows 1-2 (extension 0) are at rest.
  const Curve c = read_curve(data_dir + "/uniaxial_comma_units.csv", "uniaxial", Specimen{0.02, 1e-5});
  expect_curve(c, {1.1, 1.25, 1.5, 2.0, 3.0}, {5000.0, 10000.0, 16000.0, 25000.0, 40000.0});
  EXPECT_TRUE(has_note(c, "dropped 2 row(s) before loading starts (lines 2-3")) << c.notes.size();
  EXPECT_TRUE(has_note(c, "'Extension (mm)' / gauge length 0.02 m"));
  EXPECT_TRUE(has_note(c, "'Load (N)' / cross-section 1e-05 m^2"));
}

TEST(FitData, ReadsASemicolonExportWithDecimalCommas)
{
  // Time (s);Displacement [mm];Force [kN], decimal commas; gauge length 10 mm, section
  // 50 mm x 2 mm = 1e-4 m^2: 1,250 mm -> 1.125, 0,00040 kN = 0.4 N -> 4000 Pa.
  const Curve c = read_curve(data_dir + "/pure_shear_semicolon_decimal_comma.csv", "pure_shear", Specimen{0.01, 0.05 * 0.002});
  EXPECT_EQ(c.mode, LoadMode::pure_shear);
  expect_curve(c, {1.125, 1.25, 1.5, 2.0}, {4000.0, 7000.0, 12000.0, 20000.0});
  EXPECT_TRUE(has_note(c, "';'-separated, decimal commas"));
  EXPECT_TRUE(has_note(c, "dropped 1 row(s) before loading starts (line 2:"));
}

TEST(FitData, ReadsATabExportWithAPreambleAUnitsRowAndStrainInPercent)
{
  // Two preamble lines, then Time / Tensile strain / Tensile stress over (s) (%) (MPa):
  // lambda = 1 + strain / 100, P = stress 1e6; the rest row and a slack row (strain
  // -0.2 %, stress -0.0001 MPa) come before loading starts.
  const Curve c = read_curve(data_dir + "/uniaxial_tab_preamble.txt", "uniaxial");
  expect_curve(c, {1.1, 1.5, 2.0}, {5000.0, 18000.0, 30000.0});
  EXPECT_TRUE(has_note(c, "skipped 2 line(s) before the header (line 4)"));
  EXPECT_TRUE(has_note(c, "1 + 'Tensile strain (%)'"));
  EXPECT_TRUE(has_note(c, "dropped 2 row(s) before loading starts (lines 6-7"));
}

TEST(FitData, DropsTheRestPointOfBapdFitsOwnFormatWithANote)
{
  const Curve c = read_curve(write("rest.csv", "# mode: uniaxial\nstretch,nominal_stress_Pa\n1.0,0\n1.1,10\n1.2,20\n"), "");
  expect_curve(c, {1.1, 1.2}, {10.0, 20.0});
  EXPECT_TRUE(has_note(c, "dropped 1 row(s) before loading starts (line 3:"));
}

TEST(FitData, AnExportWithoutItsSpecimenOrUnitsGetsAMessageNamingTheColumnAndTheOption)
{
  const std::string comma = data_dir + "/uniaxial_comma_units.csv";
  struct Case {
    std::string path;
    Specimen    specimen;
    std::string expect;
  };
  const std::string head = "# mode: uniaxial\n";
  for (const Case &c : {Case{comma, {0.0, 1e-5}, "column 'Extension (mm)' is the extension: give the specimen's gauge length"},
                        Case{comma, {0.0, 1e-5}, "-fit_gauge_length L in m"},
                        Case{comma, {0.02, 0.0}, "column 'Load (N)' is the force: give the specimen's cross-section"},
                        Case{comma, {0.02, 0.0}, "-fit_cross_section A in m^2 (e.g. 1e-5 for 10 mm^2) or -fit_width W -fit_thickness T"},
                        Case{write("furlong.csv", head + "Extension (furlong),Load (N)\n1,1\n2,2\n"), {0.02, 1e-5},
                             "column 'Extension (furlong)': 'furlong' is not a unit of extension bapd-fit reads (m, mm, cm, um, in)"},
                        Case{write("nounit.csv", head + "Extension,Load (N)\n1,1\n2,2\n"), {0.02, 1e-5},
                             "column 'Extension' (extension) needs its unit in the header, e.g. 'Extension (mm)'"},
                        Case{write("true.csv", head + "Strain (%),True stress (MPa)\n1,1\n2,2\n"), {},
                             "column 'True stress (MPa)': bapd-fit fits the nominal (engineering) stress"},
                        Case{write("text.csv", head + "Time (s);Extension (mm);Load (N)\n0;1,5;0,1\n1;2,5;n/a\n"), {0.02, 1e-5},
                             ":4: column 'Load (N)': 'n/a' is not a number"},
                        Case{write("thousands.csv", head + "Time (s);Extension (mm);Load (N)\n0;1.500,5;0,1\n"), {0.02, 1e-5},
                             "'1.500,5' is not a number (thousands separators are not read"},
                        Case{write("utf16.csv", std::string("\xff\xfeT\0i\0m\0e\0\n\0", 12)), {0.02, 1e-5},
                             "the file is UTF-16 text"}}) {
    const std::string what = error_of(c.path, "", c.specimen);
    EXPECT_NE(what.find(c.expect), std::string::npos) << what;
    EXPECT_EQ(what.find(c.path), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
}

} // namespace
} // namespace bapd::fit
