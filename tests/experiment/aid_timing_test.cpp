// Aid data from a real recording: rows stamped by the rig's own clock, off the IMU grid
// (experiment/aid_epochs.hpp). Before, aid times had to match an IMU epoch within 1 us: a
// recording whose aids were 4 ms off made no update and no station, said "filter health: ok"
// and ended 3,690 km above the Earth.
//   - rows 4 ms off the grid are applied at the next epoch: the run is as good as on the grid;
//   - a run with aids of which none is ever accepted fails (exit 2, nothing written);
//   - rows closer than 1.5 IMU periods are refused.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "csv_columns.hpp"
#include "json_file.hpp"
#include "run_cli.hpp"
#include "temp_dir.hpp"

namespace {

using stochnav::testing::read_csv_columns;
using stochnav::testing::read_json;

// The short drilling scenario cut to 40 min (alignment, a stand, a connection), simulated
// with the given aids.csv clock offset into scratch/<tag>.
std::string simulate_short_drilling(const stochnav::testing::TempDir& scratch,
                                    const std::string& tag, double clock_offset_s) {
  std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) + "/configs/scenarios/drilling_short.json");
  nlohmann::json scenario = nlohmann::json::parse(in);
  scenario["drilling"]["duration_s"] = 2400;
  scenario["drilling"]["vibration_episodes"] = nlohmann::json::array();
  if (clock_offset_s != 0.0) scenario["aids"]["clock_offset_s"] = clock_offset_s;
  std::ofstream(scratch.file(tag + ".json")) << scenario.dump();
  const auto simulated = stochnav::testing::run_cli(
      "simulate scenario '" + scratch.file(tag + ".json") + "' --out '" + scratch.file(tag) + "'",
      scratch.path().string());
  EXPECT_EQ(simulated.exit_code, 0) << simulated.err;
  return scratch.file(tag);
}

stochnav::testing::CliResult run_shipped_drilling_config(const stochnav::testing::TempDir& scratch,
                                                         const std::string& data,
                                                         const std::string& out) {
  return stochnav::testing::run_cli("run '" + std::string(STOCHNAV_SOURCE_DIR) +
                                        "/configs/runs/drilling_build_hold.json' --out '" + out +
                                        "' --data '" + data + "' --no-plot",
                                    scratch.path().string());
}

TEST(AidTiming, RowsOffTheImuGridAreAppliedAtTheNextEpoch) {
  const stochnav::testing::TempDir scratch;
  const std::string on_grid = simulate_short_drilling(scratch, "on_grid", 0.0);
  const std::string off_grid = simulate_short_drilling(scratch, "off_grid", 0.004);
  const auto a = run_shipped_drilling_config(scratch, on_grid, scratch.file("run_on"));
  const auto b = run_shipped_drilling_config(scratch, off_grid, scratch.file("run_off"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;

  const nlohmann::json rows_on = read_json(scratch.file("run_on/metrics.json"))["aid_rows"];
  const nlohmann::json rows_off = read_json(scratch.file("run_off/metrics.json"))["aid_rows"];
  EXPECT_GT(rows_on["on_grid"].get<int>(), 2000);
  EXPECT_EQ(rows_on["moved"].get<int>(), 0);
  EXPECT_EQ(rows_off["on_grid"].get<int>(), 0);
  // The last row, 4 ms after the record's last epoch, is counted, not applied.
  EXPECT_EQ(rows_off["after_end"].get<int>(), rows_on["after_end"].get<int>() + 1);
  EXPECT_NEAR(rows_off["moved"].get<int>(), rows_on["on_grid"].get<int>(), 1);
  EXPECT_NEAR(rows_off["max_offset_s"].get<double>(), 0.006, 1e-6);  // next 10-ms epoch

  // The same updates and stations, and the same accuracy to well inside the errors' sigma.
  const auto metrics_on = read_json(scratch.file("run_on/metrics.json"));
  const auto metrics_off = read_json(scratch.file("run_off/metrics.json"));
  EXPECT_EQ(metrics_off["survey_stations"], metrics_on["survey_stations"]);
  EXPECT_GT(metrics_off["survey_stations"].get<int>(), 0);
  for (std::size_t i = 0; i < metrics_on["aids"].size(); ++i) {
    const int on = metrics_on["aids"][i]["attempts"].get<int>();
    const int off = metrics_off["aids"][i]["attempts"].get<int>();
    EXPECT_GE(off, on - 1) << i;
    EXPECT_LE(off, on) << i;
  }
  const auto errors_on = read_csv_columns(scratch.file("run_on/errors.csv"));
  const auto errors_off = read_csv_columns(scratch.file("run_off/errors.csv"));
  for (const std::string metric : {"lat_err_m", "lon_err_m", "height_err_m"}) {
    const double last_on = errors_on.at(metric).back();
    const double last_off = errors_off.at(metric).back();
    EXPECT_LT(std::abs(last_off - last_on), errors_on.at(metric + "_sigma").back()) << metric;
    EXPECT_LT(std::abs(last_off), 3.0 * errors_off.at(metric + "_sigma").back()) << metric;
  }
}

// Rewrites aids.csv with every time shifted by `shift_s`.
void shift_aid_times(const std::string& folder, double shift_s) {
  std::ifstream in(folder + "/aids.csv");
  std::string header;
  std::getline(in, header);
  std::ostringstream out;
  out << header << '\n';
  std::string line;
  while (std::getline(in, line)) {
    const auto comma = line.find(',');
    out.precision(12);
    out << std::stod(line.substr(0, comma)) + shift_s << line.substr(comma) << '\n';
  }
  in.close();
  std::ofstream(folder + "/aids.csv") << out.str();
}

TEST(AidTiming, ARunWhoseAidsNeverUpdateFailsAndWritesNothing) {
  const stochnav::testing::TempDir scratch;
  const std::string data = simulate_short_drilling(scratch, "late", 0.0);
  shift_aid_times(data, 1e5);  // every row after the end of the IMU record
  const auto result = run_shipped_drilling_config(scratch, data, scratch.file("run"));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("no aid update was accepted"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("after the end"), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(scratch.file("run/nav.csv")));
  EXPECT_FALSE(std::filesystem::exists(scratch.file("run/metrics.json")));
}

TEST(AidTiming, RowsCloserThanOneAndAHalfImuPeriodsAreRefused) {
  const stochnav::testing::TempDir scratch;
  const std::string data = simulate_short_drilling(scratch, "dense", 0.0);
  std::ifstream in(data + "/aids.csv");
  std::string header, first, second;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  in.close();
  // A copy of the first row 5 ms later.
  const auto comma = first.find(',');
  std::ostringstream close_row;
  close_row.precision(12);
  close_row << std::stod(first.substr(0, comma)) + 0.005 << first.substr(comma);
  std::ofstream(data + "/aids.csv") << header << '\n'
                                    << first << '\n'
                                    << close_row.str() << '\n'
                                    << second << '\n';
  const auto result = run_shipped_drilling_config(scratch, data, scratch.file("run"));
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("less than 1.5 IMU periods"), std::string::npos) << result.err;
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
}

}  // namespace
