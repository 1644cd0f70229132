// End-to-end: `stochnav davar --format json` has the DESIGN.md shape and equals the library's
// DAVAR, and --causal moves the analysis times to the window ends.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <random>

#include "run_cli.hpp"
#include "stochnav/io/record.hpp"
#include "stochnav/stats/davar.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::run_cli;
using testing::TempDir;

std::string write_record(const TempDir& dir, std::size_t samples) {
  std::mt19937_64 engine(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::string text = "t,gyro\n";
  for (std::size_t i = 0; i < samples; ++i) {
    text += std::to_string(static_cast<double>(i) / 10.0) + "," +
            std::to_string(normal(engine) * (i > samples / 2 ? 4.0 : 1.0)) + "\n";
  }
  return dir.write("record.csv", text);
}

TEST(DavarCli, JsonShapeAndValuesMatchLibrary) {
  TempDir dir;
  const std::string input = write_record(dir, 5000);
  const auto result = run_cli("davar --input '" + input +
                                  "' --column gyro --window 1000 --step 250 --format json",
                              dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out);
  ASSERT_EQ(json.size(), 3U);
  ASSERT_TRUE(json.contains("t") && json.contains("tau") && json.contains("adev"));

  ReadOptions options;
  options.path = input;
  options.column = "gyro";
  const auto expected = dynamic_allan_deviation(read_record(options), {.window = 1000, .step = 250});
  ASSERT_EQ(json["t"].size(), expected.time_s.size());
  ASSERT_EQ(json["tau"].size(), expected.tau_s.size());
  ASSERT_EQ(json["adev"].size(), expected.adev.size());
  for (std::size_t k = 0; k < expected.adev.size(); ++k) {
    EXPECT_NEAR(json["t"][k].get<double>(), expected.time_s[k], 1e-9);
    ASSERT_EQ(json["adev"][k].size(), expected.tau_s.size());
    for (std::size_t j = 0; j < expected.tau_s.size(); ++j) {
      EXPECT_NEAR(json["adev"][k][j].get<double>(), expected.adev[k][j], 1e-9 * expected.adev[k][j]);
    }
  }
  // The variance step half-way shows: late windows are about 4x the early ones at tau0.
  EXPECT_GT(json["adev"].back()[0].get<double>() / json["adev"][0][0].get<double>(), 3.0);
}

TEST(DavarCli, CausalTimesAreWindowEnds) {
  TempDir dir;
  const std::string input = write_record(dir, 2000);
  const auto result = run_cli("davar --input '" + input +
                                  "' --window 500 --step 500 --causal --format json",
                              dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const auto json = nlohmann::json::parse(result.out);
  ASSERT_EQ(json["t"].size(), 4U);
  EXPECT_NEAR(json["t"][0].get<double>(), 50.0, 1e-9);
  EXPECT_NEAR(json["t"][3].get<double>(), 200.0, 1e-9);
}

}  // namespace
}  // namespace stochnav
