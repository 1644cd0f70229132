// aids.csv timing: rig-clock offset, latency and dropouts (scenario_config.hpp AidConfig).

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "scenario_builders.hpp"
#include "stochnav/scenario/scenario_writer.hpp"
#include "stochnav/scenario/true_motion.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

// Rows of a numeric CSV file (header skipped).
std::vector<std::vector<double>> read_rows(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

std::vector<std::vector<double>> run_aids(const ScenarioConfig& config, const testing::TempDir& dir,
                                          const std::string& name) {
  ScenarioOutputOptions options;
  options.out_dir = dir.path() / name;
  options.seed = 3;
  write_scenario_outputs(config, options);
  return read_rows(options.out_dir / "aids.csv");
}

ScenarioConfig aid_config() {
  ScenarioConfig config = testing::drilling_config(200.0);
  config.drilling->initial_static_s = 20.0;
  config.imu.truth_rate_hz = 10.0;
  config.imu.aid_rate_hz = 10.0;
  config.aids.depth_noise_m = 0.05;
  config.aids.rop_noise_mps = 1e-4;
  return config;
}

TEST(ScenarioAids, ClockOffsetShiftsTheWrittenTimesOnly) {
  testing::TempDir dir;
  ScenarioConfig config = aid_config();
  const auto plain = run_aids(config, dir, "plain");
  config.aids.clock_offset_s = 0.004;
  const auto offset = run_aids(config, dir, "offset");
  ASSERT_EQ(plain.size(), 2001u);
  ASSERT_EQ(offset.size(), plain.size());
  for (std::size_t k = 0; k < plain.size(); ++k) {
    EXPECT_EQ(plain[k][0], static_cast<double>(k) / 10.0);
    EXPECT_NEAR(offset[k][0], static_cast<double>(k) / 10.0 + 0.004, 1e-12);
    // Not on the IMU grid (100 Hz).
    EXPECT_GT(std::abs(offset[k][0] * 100.0 - std::round(offset[k][0] * 100.0)), 0.3);
    for (std::size_t c = 1; c < plain[k].size(); ++c) EXPECT_EQ(offset[k][c], plain[k][c]);
  }
}

TEST(ScenarioAids, LatencyWritesTheReadingsOfAnEarlierTime) {
  testing::TempDir dir;
  ScenarioConfig config = aid_config();
  config.aids.depth_noise_m = 0.0;
  config.aids.rop_noise_mps = 0.0;
  config.aids.latency_s = 0.35;
  const auto rows = run_aids(config, dir, "late");
  auto motion = make_true_motion(config, 3);
  int moving = 0;
  for (const auto& row : rows) {
    const double t = row[0];
    const TruthSample earlier = motion->truth(std::max(0.0, t - 0.35));
    const TruthSample now = motion->truth(t);
    EXPECT_EQ(row[1], earlier.measured_depth_m) << t;
    EXPECT_NEAR(row[2], earlier.rop_mps * 3600.0, 1e-12) << t;
    EXPECT_EQ(row[3], earlier.stationary ? 1.0 : 0.0) << t;
    EXPECT_EQ(row[4], now.measured_depth_m) << t;  // the true columns stay at the row's time
    moving += now.rop_mps > 0.0 && row[1] != row[4];
  }
  EXPECT_GT(moving, 100);
}

TEST(ScenarioAids, DropoutsRemoveRowsAndLeaveTheOthersUnchanged) {
  testing::TempDir dir;
  ScenarioConfig config = aid_config();
  const auto plain = run_aids(config, dir, "plain");
  config.aids.dropouts = {{30.0, 35.05}, {150.0, 199.0}};
  const auto gappy = run_aids(config, dir, "gappy");
  std::vector<std::vector<double>> kept;
  for (const auto& row : plain) {
    const double t = row[0];
    if ((t >= 30.0 && t <= 35.05) || (t >= 150.0 && t <= 199.0)) continue;
    kept.push_back(row);
  }
  EXPECT_EQ(gappy, kept);
  EXPECT_EQ(gappy.size(), plain.size() - 51 - 491);
}

}  // namespace
}  // namespace stochnav
