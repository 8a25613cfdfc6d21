// The cells of a test machine's export (export_table.hpp): separators, quoted cells,
// decimal commas, header names with their units, and the units' SI factors.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "export_table.hpp"

namespace bapd::fit {
namespace {

TEST(ExportTable, DetectsTheSeparatorAndSplitsQuotedCells)
{
  EXPECT_EQ(detect_separator("Time (s),Extension (mm),Load (N)"), ',');
  EXPECT_EQ(detect_separator("Time (s);Extension (mm);Load (N)"), ';');
  EXPECT_EQ(detect_separator("Time (s)\tExtension, long (mm)\tLoad (N)"), '\t');
  const std::vector<std::string> cells = split_cells("\"Load (N)\", \"1,5\" ,\"say \"\"hi\"\"\",", ',');
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_EQ(cells[0], "Load (N)");
  EXPECT_EQ(cells[1], "1,5");
  EXPECT_EQ(cells[2], "say \"hi\"");
  EXPECT_EQ(cells[3], "");
}

TEST(ExportTable, ReadsDecimalPointsAndCommasButNotThousandsSeparators)
{
  double v = 0.0;
  ASSERT_TRUE(parse_number("0,125", v));
  EXPECT_EQ(v, 0.125);
  ASSERT_TRUE(parse_number(" -1.5e-3 ", v));
  EXPECT_EQ(v, -1.5e-3);
  ASSERT_TRUE(parse_number("12", v));
  EXPECT_EQ(v, 12.0);
  for (const char *bad : {"", "ten", "1.234,5", "1,234,5", "inf", "nan", "0x10", "1.5 N"})
    EXPECT_FALSE(parse_number(bad, v)) << "'" << bad << "'";
}

TEST(ExportTable, SplitsHeaderCellsIntoQuantityAndUnit)
{
  struct Case {
    const char *cell, *name, *unit;
    Quantity    quantity;
  };
  for (const Case &c : {Case{"Extension (mm)", "extension", "mm", Quantity::extension},
                        Case{"Load (N)", "load", "N", Quantity::force},
                        Case{"Force [kN]", "force", "kN", Quantity::force},
                        Case{"Time (s)", "time", "s", Quantity::time},
                        Case{"nominal_stress_kPa", "nominal_stress", "kPa", Quantity::stress},
                        Case{"top_nominal_stress_Pa", "top_nominal_stress", "Pa", Quantity::stress},
                        Case{"stretch", "stretch", "", Quantity::stretch},
                        Case{"Tensile strain (%)", "tensile strain", "%", Quantity::strain},
                        Case{"Standardkraft [N]", "standardkraft", "N", Quantity::force},
                        Case{"Crosshead displacement", "crosshead displacement", "", Quantity::extension},
                        Case{"strain_energy_density", "strain_energy_density", "", Quantity::none},
                        Case{"max_load", "max_load", "", Quantity::force},
                        Case{"Specimen label", "specimen label", "", Quantity::none}}) {
    const ColumnName col = parse_column(c.cell);
    EXPECT_EQ(col.name, c.name) << c.cell;
    EXPECT_EQ(col.unit, c.unit) << c.cell;
    EXPECT_EQ(col.quantity, c.quantity) << c.cell;
  }
  EXPECT_EQ(unit_cell("(mm)"), "mm");
  EXPECT_EQ(unit_cell("[kN]"), "kN");
  EXPECT_EQ(unit_cell("%"), "%");
  EXPECT_EQ(unit_cell("gel 3"), "");
  EXPECT_EQ(unit_cell("1.5"), "");
}

TEST(ExportTable, GivesTheSIFactorOfEachUnitOfAQuantityAndNoneForAnother)
{
  EXPECT_EQ(si_factor(Quantity::extension, "mm"), 1e-3);
  EXPECT_EQ(si_factor(Quantity::extension, "\xc2\xb5m"), 1e-6); // UTF-8 micro sign
  EXPECT_EQ(si_factor(Quantity::extension, "in"), 0.0254);
  EXPECT_EQ(si_factor(Quantity::force, "kN"), 1e3);
  EXPECT_EQ(si_factor(Quantity::force, "mN"), 1e-3);
  EXPECT_EQ(si_factor(Quantity::stress, "MPa"), 1e6);
  EXPECT_EQ(si_factor(Quantity::stress, "N/mm^2"), 1e6);
  EXPECT_EQ(si_factor(Quantity::stress, "kpa"), 1e3);
  EXPECT_EQ(si_factor(Quantity::strain, "%"), 0.01);
  EXPECT_EQ(si_factor(Quantity::stretch, ""), 1.0);
  EXPECT_EQ(si_factor(Quantity::extension, "N"), 0.0); // a force unit on a length
  EXPECT_EQ(si_factor(Quantity::force, "mm"), 0.0);
  EXPECT_EQ(si_factor(Quantity::stress, ""), 0.0);      // a stress needs its unit
  EXPECT_EQ(si_factor(Quantity::strain, ""), 0.0);      // a strain too: % or fraction?
}

} // namespace
} // namespace bapd::fit
