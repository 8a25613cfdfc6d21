// A point table's header (text_table.hpp): both point cloud readers' messages, word for
// word as each reader wrote them when it checked its header itself.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bapd/core/geometry/text_table.hpp"

namespace bapd {
namespace {

const std::vector<std::string> kColumns3D = {"x", "y", "z", "volume", "block_id|block"};
const std::vector<std::string> kColumns2D = {"x", "y", "volume", "block_id|block"};

TEST(TextTableHeader, FindsColumnsInAnyCaseAndByAlias)
{
  std::vector<int> at;
  EXPECT_EQ(table_header("c.csv", 1, {"Volume", "X", "block", "Y"}, "Volume,X,block,Y", kColumns2D, 3, &at), "");
  EXPECT_EQ(at, (std::vector<int>{1, 3, 0, 2}));
  EXPECT_EQ(table_header("c.csv", 1, {"x", "y", "z", "volume"}, "", kColumns3D, 4, &at), "");
  EXPECT_EQ(at, (std::vector<int>{0, 1, 2, 3, -1})); // block_id is optional
  // The alias list is the table's notation, not a column name.
  EXPECT_EQ(table_header("c.csv", 1, {"x", "y", "volume", "block_id|block"}, "", kColumns2D, 3, &at), "");
  EXPECT_EQ(at, (std::vector<int>{0, 1, 2, -1}));
}

TEST(TextTableHeader, NumbersInTheFirstLine)
{
  std::vector<int> at;
  EXPECT_EQ(table_header("c.csv", 2, {"1", "2", "3", "1e-9"}, "", kColumns3D, 4, &at),
            "'c.csv', line 2: the first line must name the columns (x, y, z, volume and optionally block_id, "
            "e.g. 'x,y,z,volume'), not hold numbers");
  EXPECT_EQ(table_header("c.csv", 1, {"1", "2", "1e-9"}, "1,2,1e-9", kColumns2D, 3, &at),
            "'c.csv', line 1: the first line must name the columns (x, y, volume and optionally block_id, e.g. 'x,y,volume'), "
            "not hold numbers");
}

TEST(TextTableHeader, AColumnTwice)
{
  std::vector<int> at;
  EXPECT_EQ(table_header("c.csv", 1, {"x", "y", "z", "X", "volume"}, "", kColumns3D, 4, &at),
            "'c.csv', line 1: the header names column 'x' twice");
  EXPECT_EQ(table_header("c.csv", 3, {"x", "y", "block", "Block_ID", "volume"}, "x,y,block,Block_ID,volume", kColumns2D, 3, &at),
            "'c.csv', line 3: the header names column 'block_id' twice");
}

TEST(TextTableHeader, AMissingColumn)
{
  std::vector<int> at;
  EXPECT_EQ(table_header("c.csv", 1, {"x", "y", "volume"}, "", kColumns3D, 4, &at),
            "'c.csv', line 1: the header names no column 'z': the columns must include x, y, z and volume "
            "(block_id optional), e.g. 'x,y,z,volume'");
  EXPECT_EQ(table_header("no_volume.csv", 1, {"x", "y", "vol", "block_id"}, "x,y,vol,block_id", kColumns2D, 3, &at),
            "'no_volume.csv', line 1: the header 'x,y,vol,block_id' names no column 'volume': the columns must include x, y "
            "and volume (block_id optional), e.g. 'x,y,volume'");
}

} // namespace
} // namespace bapd
