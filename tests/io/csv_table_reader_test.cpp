// CsvTableReader: plain rows (the one-pass path) and everything else (the general path) give
// the same values, and bad rows the same errors.

#include "stochnav/io/csv_table_reader.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "stochnav/core/errors.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::TempDir;

constexpr std::array<std::string_view, 3> kWanted = {"c", "a", "c"};  // reordered, repeated

std::string error_of(const std::string& path, std::span<const std::string_view> columns) {
  CsvTableReader table(path, columns);
  std::array<double, 3> values{};
  try {
    while (table.next(std::span<double>(values.data(), columns.size()))) {
    }
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(CsvTableReader, PlainAndPaddedCellsGiveTheSameValues) {
  const TempDir dir;
  const std::string path = dir.write("t.csv",
                                     "a,b,c\n"
                                     "1.5,2,-3e-7\n"
                                     " 1.5 ,+2,\t-3e-7\n"
                                     "# a comment\n"
                                     "\n"
                                     "1.5,x,-3e-7\n");  // b is not asked for: any text
  constexpr std::array<std::string_view, 2> wanted = {"c", "a"};
  CsvTableReader table(path, wanted);
  std::array<double, 2> values{};
  for (int row = 0; row < 3; ++row) {
    ASSERT_TRUE(table.next(values)) << row;
    EXPECT_EQ(values[0], -3e-7) << row;
    EXPECT_EQ(values[1], 1.5) << row;
  }
  EXPECT_FALSE(table.next(values));
}

TEST(CsvTableReader, AColumnAskedForTwiceFillsBoth) {
  const TempDir dir;
  const std::string path = dir.write("t.csv", "a,b,c\n1,2,3\n4,5,6\n");
  CsvTableReader table(path, kWanted);
  std::array<double, 3> values{};
  ASSERT_TRUE(table.next(values));
  EXPECT_EQ(values, (std::array<double, 3>{3, 1, 3}));
  ASSERT_TRUE(table.next(values));
  EXPECT_EQ(values, (std::array<double, 3>{6, 4, 6}));
}

TEST(CsvTableReader, BadRowsAreNamed) {
  const TempDir dir;
  constexpr std::array<std::string_view, 2> wanted = {"a", "c"};
  const auto error = [&](const std::string& row) {
    return error_of(dir.write("t.csv", "a,b,c\n1,2,3\n" + row + "\n"), wanted);
  };
  EXPECT_NE(error("1,2").find("t.csv:3: 2 cells for 3 columns"), std::string::npos);
  EXPECT_NE(error("1,2,3,4").find("t.csv:3: 4 cells for 3 columns"), std::string::npos);
  EXPECT_NE(error("1,2,3x").find("column c is not a number ('3x')"), std::string::npos);
  EXPECT_NE(error("nan,2,3").find("column a is NaN or infinite"), std::string::npos);
  EXPECT_NE(error("1,2,inf").find("column c is NaN or infinite"), std::string::npos);
  EXPECT_NE(error("1,2,").find("column c is not a number"), std::string::npos);
  EXPECT_EQ(error("1,anything,3"), "");
}

}  // namespace
}  // namespace stochnav
