// End-to-end: `stochnav wv` on the real ADIS16405 record (accelerometer Z, the channel with the
// largest bias) reproduces the R package wv's table
// (1e-8 relative), its JSON has exactly the DESIGN.md keys, phase input equals rate input, and
// bad input (too short, constant) exits 2 with one line.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "run_cli.hpp"
#include "temp_dir.hpp"
#include "wv_reference.hpp"

namespace stochnav {
namespace {

using testing::run_cli;
using testing::TempDir;

std::string noise_file(const TempDir& dir, std::size_t n, bool as_phase) {
  std::mt19937_64 engine(17);
  std::normal_distribution<double> normal(0.0, 0.1);
  std::string text = "# test record\n";
  double phase = 0.0;
  if (as_phase) text += "0\n";
  for (std::size_t i = 0; i < n; ++i) {
    const double y = 1.0 + normal(engine);
    phase += y * 0.5;  // tau0 = 0.5 s
    text += std::to_string(as_phase ? phase : y) + "\n";
  }
  return dir.write(as_phase ? "phase.txt" : "rate.txt", text);
}

nlohmann::json run_json(const std::string& arguments, const TempDir& dir) {
  const auto result = run_cli(arguments + " --format json", dir.path().string());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  return nlohmann::json::parse(result.out);
}

TEST(WvCli, AdisAccelerometerZMatchesTheWvPackageAndHasTheContractKeys) {
  STOCHNAV_REQUIRE_SHARED_DATA(table_path, "gmwm/adis_wv_ref.csv");
  STOCHNAV_REQUIRE_SHARED_DATA(record_path, "imu-static/adis16405_imu1_static_100hz.csv");
  TempDir dir;
  const auto json = run_json("wv --input '" + record_path + "' --column acc_z_g", dir);
  std::vector<std::string> keys;
  for (const auto& item : json.items()) keys.push_back(item.key());
  std::sort(keys.begin(), keys.end());
  EXPECT_EQ(keys, (std::vector<std::string>{"n", "scale_s", "wv", "wv_hi", "wv_lo"}));
  const auto rows = testing::read_wv_reference(table_path).at("Accel. Z");
  ASSERT_EQ(json["wv"].size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_NEAR(json["scale_s"][i].get<double>(), rows[i].scale_s, 1e-12 * rows[i].scale_s);
    EXPECT_NEAR(json["wv"][i].get<double>(), rows[i].wv, 1e-8 * rows[i].wv);
    EXPECT_NEAR(json["wv_lo"][i].get<double>(), rows[i].ci_low, 1e-8 * rows[i].ci_low);
    EXPECT_NEAR(json["wv_hi"][i].get<double>(), rows[i].ci_high, 1e-8 * rows[i].ci_high);
    EXPECT_EQ(json["n"][i].get<std::size_t>(), 1'000'000u - (std::size_t{1} << (i + 1)) + 1);
  }
}

TEST(WvCli, PhaseInputGivesTheSameWaveletVarianceAsRateInput) {
  TempDir dir;
  const std::string rate = noise_file(dir, 4096, false);
  const std::string phase = noise_file(dir, 4096, true);
  const auto from_rate = run_json("wv --input '" + rate + "' --rate 2", dir);
  const auto from_phase = run_json("wv --input '" + phase + "' --rate 2 --data phase", dir);
  ASSERT_EQ(from_rate["wv"].size(), 11u);
  ASSERT_EQ(from_phase["wv"].size(), from_rate["wv"].size());
  for (std::size_t i = 0; i < from_rate["wv"].size(); ++i) {
    // The text file holds 6 decimals: the phase differences carry that rounding.
    EXPECT_NEAR(from_phase["wv"][i].get<double>(), from_rate["wv"][i].get<double>(),
                1e-3 * from_rate["wv"][i].get<double>());
    EXPECT_EQ(from_rate["scale_s"][i].get<double>(),
              std::ldexp(1.0, static_cast<int>(i) + 1) / 2.0);
  }
}

TEST(WvCli, RobustAndCsvAndTableFormats) {
  TempDir dir;
  const std::string rate = noise_file(dir, 2048, false);
  const auto robust = run_json("wv --input '" + rate + "' --rate 2 --robust", dir);
  ASSERT_EQ(robust["wv"].size(), 10u);
  for (std::size_t i = 0; i < 10; ++i) {
    EXPECT_LT(robust["wv_lo"][i].get<double>(), robust["wv"][i].get<double>());
    EXPECT_GT(robust["wv_hi"][i].get<double>(), robust["wv"][i].get<double>());
  }
  const auto csv = run_cli("wv --input '" + rate + "' --rate 2 --format csv", dir.path().string());
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_EQ(csv.out.substr(0, csv.out.find('\n')), "level,scale,scale_s,n,wv_lo,wv,wv_hi");
  EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 11);
  const auto table = run_cli("wv --input '" + rate + "' --rate 2 --robust", dir.path().string());
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("robust, efficiency 0.6"), std::string::npos) << table.out;
}

TEST(WvCli, TooShortOrConstantRecordsExitTwoWithOneLine) {
  TempDir dir;
  const std::string short_record = noise_file(dir, 15, false);
  auto result = run_cli("wv --input '" + short_record + "' --rate 1", dir.path().string());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.err.find("at least 3"), std::string::npos) << result.err;

  std::string constant;
  for (int i = 0; i < 100; ++i) constant += "0.25\n";
  const std::string flat = dir.write("flat.txt", constant);
  for (const char* robust : {"", " --robust"}) {
    result = run_cli("wv --input '" + flat + "' --rate 1" + robust, dir.path().string());
    EXPECT_EQ(result.exit_code, 2) << robust;
    EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
    EXPECT_NE(result.err.find("constant"), std::string::npos) << result.err;
  }
}

}  // namespace
}  // namespace stochnav
