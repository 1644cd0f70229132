// A day and a half of drilling, as a user runs it: the SHIPPED 36-h scenario
// (configs/scenarios/drilling_build_hold.json: 13 M IMU epochs at 100 Hz, a build from vertical
// to horizontal at 60 rpm, 34 connections with ZUPT, four axial-vibration episodes, a FOG with a
// 0.5 deg/h flicker floor and scale-factor errors) is simulated with its own seed and navigated
// by the SHIPPED run config (configs/runs/drilling_build_hold.json, the white gyro model) and by
// the davar_causal and augmented gyro models of the shipped experiment
// (configs/experiments/drilling_build_hold.json). Every run is judged against its own 3-sigma
// bounds over the whole record and at every survey station: a filter drifting far while it
// reports itself healthy fails here, and so does one whose error is small but whose sigma is
// smaller still.
//
// What this test found: the white model with its bias random walk matched to the flicker floor
// at 9 min (K = 1.5 deg/h/sqrt(h)) kept the toolface inside its 3 sigma only 94 % of the 36 h
// and the station azimuth error RMS (0.105 deg) above its sigma RMS (0.084); K matched at 2 min
// (3.15) is inside 98.9 % and 0.114 / 0.126. The shorter records of the other tests do not show
// it. About 70 s of CPU and 1.8 GB of scratch disk (imu.csv); not run under the sanitizers, where
// the 2-h drilling test covers the same code.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "csv_columns.hpp"
#include "json_file.hpp"
#include "run_cli.hpp"
#include "sanitized_build.hpp"
#include "temp_dir.hpp"

namespace {

using stochnav::testing::read_json;

const std::string kSource = STOCHNAV_SOURCE_DIR;

// The shipped run config with its gyro model replaced by the shipped experiment's variant `name`.
nlohmann::json run_config_with_experiment_gyro(const std::string& name) {
  nlohmann::json run = read_json(kSource + "/configs/runs/drilling_build_hold.json");
  const nlohmann::json experiment =
      read_json(kSource + "/configs/experiments/drilling_build_hold.json");
  for (const auto& variant : experiment.at("variants")) {
    if (variant.at("name") == name) run["noise"] = variant.at("noise");
  }
  return run;
}

void expect_consistent_over_the_record(const nlohmann::json& metrics) {
  EXPECT_TRUE(metrics.at("filter_health").at("ok").get<bool>());
  EXPECT_FALSE(metrics.at("self_check").at("optimistic").get<bool>())
      << metrics.at("self_check").at("reason");
  const auto& consistency = metrics.at("consistency");
  const auto& inside = consistency.at("inside_3sigma");
  // Measured (seed 7): position 100 %, inclination 99.6-99.9 %, azimuth 99.99-100 %, velocity
  // 99.1-99.9 %, toolface 98.9-99.7 %; a Gaussian error would be inside 99.7 %.
  for (const char* metric :
       {"lat_err_m", "lon_err_m", "height_err_m", "inclination_err_deg", "azimuth_err_deg"}) {
    EXPECT_GE(inside.at(metric).get<double>(), 0.99) << metric;
  }
  for (const char* metric : {"ve_err_mps", "vn_err_mps", "vu_err_mps", "toolface_err_deg"}) {
    EXPECT_GE(inside.at(metric).get<double>(), 0.98) << metric;
  }
  // Mean NEES over 9 states (measured 5.2-5.6): below 9 is not optimistic on average; above 3,
  // the bounds are not so loose that the checks above are empty.
  const double nees = consistency.at("nees_mean").get<double>();
  EXPECT_LT(nees, 9.0);
  EXPECT_GT(nees, 3.0);
}

void expect_every_station_inside_three_sigma(const std::string& survey_errors_csv) {
  const auto stations = stochnav::testing::read_csv_columns(survey_errors_csv);
  const std::size_t count = stations.at("t_s").size();
  ASSERT_EQ(count, 34u);  // one per connection
  for (std::size_t i = 0; i < count; ++i) {
    for (const char* axis : {"north", "east", "tvd"}) {
      const double error = stations.at(std::string(axis) + "_m")[i];
      const double sigma = stations.at(std::string(axis) + "_sigma_m")[i];
      EXPECT_LE(std::abs(error), 3.0 * sigma) << axis << " at station " << i;
    }
    const double azimuth = stations.at("azimuth_deg")[i];
    const double azimuth_sigma = stations.at("azimuth_sigma_deg")[i];
    if (std::isfinite(azimuth) && std::isfinite(azimuth_sigma)) {  // NaN while vertical
      EXPECT_LE(std::abs(azimuth), 3.0 * azimuth_sigma) << "azimuth at station " << i;
    }
  }
  // The last station, 1420 m MD after 36 h: within a metre (measured 0.05-0.45 m; sigmas about 0.5 m).
  const double north = stations.at("north_m")[count - 1];
  const double east = stations.at("east_m")[count - 1];
  EXPECT_LT(std::hypot(north, east), 1.0);
}

TEST(DrillingDay, ShippedScenarioAndModelsStayInsideTheirOwnThreeSigmaFor36Hours) {
  if (stochnav::testing::kSanitizedBuild) {
    GTEST_SKIP() << "36 h of statistics; under the sanitizers the 2-h drilling test runs the "
                    "same code";
  }
  const stochnav::testing::TempDir scratch;
  const std::string data = scratch.file("scenario");
  const auto simulated = stochnav::testing::run_cli(
      "simulate scenario '" + kSource + "/configs/scenarios/drilling_build_hold.json' --out '" +
          data + "'",
      scratch.path().string());
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;

  for (const std::string model : {"white", "davar_causal", "augmented"}) {
    SCOPED_TRACE(model);
    std::string config = kSource + "/configs/runs/drilling_build_hold.json";
    if (model != "white") {  // the shipped run config's own model is the white one
      config = scratch.file(model + ".json");
      std::ofstream(config) << run_config_with_experiment_gyro(model).dump();
    }
    const std::string out = scratch.file("run_" + model);
    const auto result = stochnav::testing::run_cli(
        "run '" + config + "' --out '" + out + "' --data '" + data + "' --no-plot",
        scratch.path().string());
    ASSERT_EQ(result.exit_code, 0) << result.err;
    std::printf("%s: %s", model.c_str(), result.out.c_str());
    expect_consistent_over_the_record(read_json(out + "/metrics.json"));
    expect_every_station_inside_three_sigma(out + "/survey_errors.csv");
  }
}

}  // namespace
