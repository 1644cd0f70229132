// The public helpers an embedder uses instead of rewriting the CLI's: a truth row as a NavState,
// a run config's filter start, and reading a scenario config file.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/initial_state.hpp"
#include "stochnav/experiment/navigation_files.hpp"
#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

TEST(TruthRow, BecomesANavStateInRadiansWithTheMwdAttitude) {
  const std::array<double, 10> row = {12.5, 30.0, -100.0, 50.0, 1.0, 2.0, 3.0, 45.0, 10.0, 60.0};
  const NavState state = nav_state_from_truth_row(row);
  EXPECT_EQ(state.t_s, 12.5);
  EXPECT_DOUBLE_EQ(state.latitude_rad, 30.0 * kRadPerDeg);
  EXPECT_DOUBLE_EQ(state.longitude_rad, -100.0 * kRadPerDeg);
  EXPECT_EQ(state.height_m, 50.0);
  EXPECT_EQ(state.v_n, Eigen::Vector3d(1.0, 2.0, 3.0));
  const Eigen::Quaterniond expected = quaternion_from_mwd({.inclination_rad = 45.0 * kRadPerDeg,
                                                           .toolface_rad = 10.0 * kRadPerDeg,
                                                           .azimuth_rad = 60.0 * kRadPerDeg});
  EXPECT_LT((state.q_nb.coeffs() - expected.coeffs()).norm(), 1e-15);
  EXPECT_EQ(kTruthColumns.front(), "t");
  EXPECT_EQ(kTruthColumns.back(), "azimuth");
}

TEST(FilterStart, AppliesTheConfiguredInitialErrorOnly) {
  plugin::RunConfig config;
  NavState start;
  start.latitude_rad = 0.5;
  const FilterOptions options;
  const FilterStart plain = filter_start(config, start, options);
  EXPECT_EQ(plain.estimate.latitude_rad, start.latitude_rad);
  EXPECT_EQ(plain.options.initial_gyro_bias_radps, options.initial_gyro_bias_radps);

  config.initial_error = plugin::InitialErrorConfig{};
  config.initial_error->position_m = {0.0, 100.0, 0.0};  // 100 m north
  config.initial_error->gyro_bias_deg_h = {1.0, 0.0, 0.0};
  const FilterStart offset = filter_start(config, start, options);
  EXPECT_NEAR((offset.estimate.latitude_rad - start.latitude_rad) * 6.36e6, 100.0, 0.5);
  EXPECT_NEAR(offset.options.initial_gyro_bias_radps.x(), kRadPerDeg / 3600.0, 1e-18);
}

TEST(ScenarioConfigFile, ReadsShippedConfigsAndNamesFileAndTypo) {
  const ScenarioConfig shipped = read_scenario_config(std::string(STOCHNAV_SOURCE_DIR) +
                                                      "/configs/scenarios/drilling_short.json");
  EXPECT_EQ(shipped.seed, 11u);

  const testing::TempDir dir;
  const auto error_of = [](const std::filesystem::path& file) -> std::string {
    try {
      read_scenario_config(file);
    } catch (const std::runtime_error& error) {  // InputError or ConfigError
      return error.what();
    }
    return "(accepted)";
  };
  EXPECT_EQ(error_of(dir.path()), dir.path().string() +
                                      ": is a folder, not a JSON file; give the scenario "
                                      "config as a file");
  const auto with_key_renamed = [&](const std::string& from, const std::string& to) {
    std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) + "/configs/scenarios/drilling_short.json");
    nlohmann::json document = nlohmann::json::parse(in);
    document[to] = document[from];
    document.erase(from);
    const auto file = dir.path() / (to + ".json");
    std::ofstream(file) << document.dump();
    return error_of(file);
  };
  // An optional key and a required one, misspelt: each named as the typo it is.
  EXPECT_NE(
      with_key_renamed("seed", "sede").find("/sede: unknown key 'sede'; did you mean 'seed'?"),
      std::string::npos);
  EXPECT_NE(with_key_renamed("imu", "imus").find("/imus: unknown key 'imus'; did you mean 'imu'?"),
            std::string::npos);
}

}  // namespace
}  // namespace stochnav
