// End-to-end: every kind of bad input gives exit code 2, one line on stderr naming the file and
// line (or option) and a fix, and no output file.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_cli.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::run_cli;
using testing::TempDir;

struct BadInputCase {
  std::string name;
  std::string file_content;      // written to input.csv (or input.txt when rate_option set)
  std::string extra_arguments;   // after --input FILE
  std::string expected_fragment; // must appear in the one-line message
};

// Names the case in test listings instead of dumping its bytes.
void PrintTo(const BadInputCase& c, std::ostream* os) { *os << c.name; }

std::string good_csv(int rows) {
  std::string text = "t,x\n";
  for (int i = 0; i < rows; ++i) text += std::to_string(i) + "," + std::to_string((i * 7) % 5) + "\n";
  return text;
}

class BadInput : public ::testing::TestWithParam<BadInputCase> {};

TEST_P(BadInput, ExitCodeTwoOneLineNoOutput) {
  const BadInputCase& c = GetParam();
  TempDir dir;
  const std::string input = dir.write("input.csv", c.file_content);
  const std::string output = dir.file("out.json");
  const auto result = run_cli(c.extra_arguments.substr(0, c.extra_arguments.find(' ')) +
                                  " --input '" + input + "'" +
                                  c.extra_arguments.substr(c.extra_arguments.find(' ')) +
                                  " --output '" + output + "'",
                              dir.path().string());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  ASSERT_FALSE(result.err.empty());
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_NE(result.err.find(c.expected_fragment), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(output)) << "a failed run left " << output;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadInput,
    ::testing::Values(
        BadInputCase{"empty", "", "allan --format json", "no samples"},
        BadInputCase{"one_sample", "t,x\n0,1\n", "allan --format json", "only one sample"},
        BadInputCase{"non_numeric", "t,x\n0,1\n1,x2\n2,3\n", "allan --format json", "input.csv:3"},
        BadInputCase{"nan", "t,x\n0,1\n1,NaN\n2,3\n", "allan --format json", "input.csv:3"},
        BadInputCase{"missing_column", good_csv(10), "allan --column gyro_z --format json",
                     "no column 'gyro_z'"},
        BadInputCase{"gap", "t,x\n0,1\n1,2\n2,3\n5,4\n6,5\n", "allan --format json",
                     "input.csv:5"},
        BadInputCase{"decreasing", "t,x\n0,1\n1,2\n0.5,3\n", "allan --format json",
                     "input.csv:4"},
        BadInputCase{"window_too_long", good_csv(100), "davar --window 500 --step 10 --format json",
                     "longer than the record"},
        BadInputCase{"step_zero", good_csv(100), "davar --window 50 --step 0 --format json",
                     "--step"},
        // Reported by the fuzzing pass of issue #17: these crashed (an empty set of averaging
        // factors) or wrapped a negative count into a huge one.
        BadInputCase{"window_too_short_for_any_tau", good_csv(4),
                     "davar --window 4 --step 1 --format json", "--window 4"},
        BadInputCase{"phase_window_too_short", good_csv(5),
                     "davar --window 5 --step 1 --data phase --format json", "--window 5"},
        BadInputCase{"negative_window", good_csv(100), "davar --window -1 --step 1 --format json",
                     "--window"},
        BadInputCase{"negative_step", good_csv(100), "davar --window 50 --step -5 --format json",
                     "--step"},
        BadInputCase{"fit_window_too_short", good_csv(100), "fit --window 4 --step 1 --format json",
                     "--window 4"},
        BadInputCase{"unknown_unit", good_csv(100), "allan --unit furlong/fortnight --format json",
                     "unknown unit"},
        BadInputCase{"unknown_format", good_csv(100), "allan --format xml", "--format"},
        BadInputCase{"unknown_option", good_csv(100), "allan --frobnicate 3", "frobnicate"},
        BadInputCase{"bad_plot_extension", good_csv(100), "allan --plot out.jpg", ".png"}),
    [](const ::testing::TestParamInfo<BadInputCase>& case_info) { return case_info.param.name; });

TEST(CliErrors, MissingInputFile) {
  TempDir dir;
  const auto result = run_cli("allan --input '" + dir.file("absent.csv") + "'", dir.path().string());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("absent.csv: cannot open"), std::string::npos) << result.err;
}

TEST(CliErrors, NoRateWithoutTimeColumn) {
  TempDir dir;
  const auto input = dir.write("plain.txt", "1\n2\n3\n4\n");
  const auto result = run_cli("allan --input '" + input + "'", dir.path().string());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("--rate"), std::string::npos) << result.err;
}

}  // namespace
}  // namespace stochnav
