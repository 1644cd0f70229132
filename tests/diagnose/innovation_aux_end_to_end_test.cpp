// diagnose --run --aux end to end: a static scenario whose gyro bias follows a simulated tool
// temperature (aux_sensitivity in the scenario's gyro noise; aids.csv carries temperature_c),
// a filter run with a white gyro model that does not know it, then diagnose --run --aux
// temperature_c. Over seeds: the drift is found with the right column when the sensitivity is
// there and (almost) never when it is not.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "run_cli.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::run_cli;
using testing::TempDir;

constexpr int kSeeds = 5;

// A horizontal tool on a static table for `duration_s`; gyro white noise plus a bias of
// `coefficient_dph_per_degc` deg/h per degC (0: the tool logs its temperature, the gyro ignores
// it) of a temperature rising 5 degC/h with a 3-degC, 600-s sinusoid, on gyro x and y.
nlohmann::json static_scenario(double duration_s, double coefficient_dph_per_degc) {
  using nlohmann::json;
  const json gyro_terms = json::array({{{"type", "angle_random_walk"}, {"N", 0.005}},
                                       {{"type", "aux_sensitivity"},
                                        {"coefficient", coefficient_dph_per_degc},
                                        {"column", "temperature_c"},
                                        {"profile_start", 25.0},
                                        {"profile_rise_per_h", 5.0},
                                        {"profile_amplitude", 3.0},
                                        {"profile_period_s", 600.0}}});
  const json gyro_model = {{"units", "deg/h"}, {"rate_hz", 100}, {"terms", gyro_terms}};
  const json gyro_plain = {{"units", "deg/h"},
                           {"rate_hz", 100},
                           {"terms", json::array({{{"type", "angle_random_walk"}, {"N", 0.005}}})}};
  return {
      {"kind", "vibration_table"},
      {"imu",
       {{"rate_hz", 100}, {"output", "increments"}, {"truth_rate_hz", 10}, {"aid_rate_hz", 1}}},
      {"site", {{"latitude_deg", 39.9778}, {"longitude_deg", 116.3448}, {"height_m", 50.0}}},
      {"sensors",
       {{"gyro", {{"noise", json::array({gyro_model, gyro_model, gyro_plain})}}},
        {"accel",
         {{"noise",
           {{"units", "m/s^2"},
            {"rate_hz", 100},
            {"terms", json::array({{{"type", "angle_random_walk"}, {"N", 0.029}}})}}}}}}},
      {"vibration_table",
       {{"attitude", {{"inclination_deg", 90.0}, {"toolface_deg", 0.0}, {"azimuth_deg", 0.0}}},
        {"phases",
         json::array({{{"name", "static"}, {"duration_s", duration_s}, {"motion", "static"}}})}}}};
}

struct AuxOutcome {
  bool found = false;                ///< some aux_drift finding on temperature_c
  std::set<std::string> components;  ///< "aid_type component" of the findings
  std::string report;                ///< report.json, for failure messages
};

// Simulates the scenario with `seed`, runs the white-model filter on it and diagnoses the run
// against temperature_c read from the scenario's aids.csv.
AuxOutcome simulate_run_and_diagnose(const TempDir& dir, const std::string& name,
                                     double coefficient, std::uint64_t seed) {
  AuxOutcome outcome;
  const std::string scenario = dir.file(name + "_scenario");
  const std::string scenario_config =
      dir.write(name + "_scenario.json", static_scenario(1800.0, coefficient).dump());
  auto result = run_cli("simulate scenario '" + scenario_config + "' --seed " +
                            std::to_string(seed) + " --out '" + scenario + "'",
                        dir.path().string());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  if (result.exit_code != 0) return outcome;
  const nlohmann::json config = {
      {"data", {{"scenario", scenario}}},
      {"noise",
       {{"gyro", {{"plugin", "white"}, {"params", {{"N", 0.005}}}}},
        {"accel", {{"plugin", "white"}, {"params", {{"N", 0.029}}}}}}},
      {"aids",
       {{{"plugin", "static_position"},
         {"params",
          {{"sigma_position_m", 0.01}, {"sigma_velocity_mps", 0.3}, {"nis_gate", false}}}}}}};
  const std::string run_config = dir.write(name + "_run.json", config.dump());
  const std::string run = dir.file(name + "_run");
  result = run_cli("run '" + run_config + "' --out '" + run + "'", dir.path().string());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  if (result.exit_code != 0) return outcome;
  const std::string diag = dir.file(name + "_diag");
  result = run_cli("diagnose --run '" + run + "' --aux temperature_c --aux-file '" + scenario +
                       "/aids.csv' --out '" + diag + "' --plots none",
                   dir.path().string());
  EXPECT_EQ(result.exit_code, 0) << result.err;
  if (result.exit_code != 0) return outcome;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(diag + "/report.json"));
  outcome.report = report.dump(2);
  for (const auto& finding : report.value("aux_drift", nlohmann::json::array())) {
    if (finding["column"] != "temperature_c") continue;
    outcome.found = true;
    // A horizontal gyro bias tilts the tool: the drift is in the horizontal components.
    EXPECT_EQ(finding["component"].get<std::string>().find(" U "), std::string::npos)
        << finding.dump();
    outcome.components.insert(finding["aid_type"].get<std::string>() + " " +
                              finding["component"].get<std::string>());
  }
  return outcome;
}

TEST(DiagnoseRunAuxEndToEnd, ScenarioWritesTheTemperatureColumn) {
  const TempDir dir;
  const std::string config = dir.write("s.json", static_scenario(20.0, 0.5).dump());
  const auto result = run_cli("simulate scenario '" + config + "' --out '" + dir.file("s") + "'",
                              dir.path().string());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::ifstream aids(dir.file("s/aids.csv"));
  std::string header, first;
  std::getline(aids, header);
  std::getline(aids, first);
  EXPECT_EQ(header,
            "t,measured_depth_m,rop_mph,zupt,measured_depth_true_m,rop_true_mph,temperature_c");
  EXPECT_EQ(first.substr(first.rfind(',') + 1), "25");  // profile_start at t = 0
  const nlohmann::json scenario = nlohmann::json::parse(std::ifstream(dir.file("s/scenario.json")));
  EXPECT_EQ(scenario["files"]["aids.csv"]["columns"].back(), "temperature_c");

  // In scheduled_noise the phase scales would multiply it: refused.
  nlohmann::json bad = static_scenario(20.0, 0.5);
  bad["sensors"]["gyro"]["scheduled_noise"] = bad["sensors"]["gyro"]["noise"][0];
  const std::string bad_config = dir.write("bad.json", bad.dump());
  const auto refused =
      run_cli("simulate scenario '" + bad_config + "' --out '" + dir.file("bad") + "'",
              dir.path().string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_NE(refused.err.find("aux_sensitivity term in scheduled_noise"), std::string::npos)
      << refused.err;
}

TEST(DiagnoseRunAuxEndToEnd, FindsTheTemperatureDriftOfTheGyroBias) {
  const TempDir dir;
  int detected = 0;
  int false_alarms = 0;
  std::string reports;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const AuxOutcome with = simulate_run_and_diagnose(dir, "with" + std::to_string(seed), 0.5,
                                                      static_cast<std::uint64_t>(seed));
    const AuxOutcome without = simulate_run_and_diagnose(dir, "without" + std::to_string(seed), 0.0,
                                                         static_cast<std::uint64_t>(seed));
    detected += with.found ? 1 : 0;
    false_alarms += without.found ? 1 : 0;
    std::string components;
    for (const auto& c : with.components) components += " [" + c + "]";
    std::printf("seed %d: with sensitivity %s%s; without %s\n", seed,
                with.found ? "found" : "missed", components.c_str(),
                without.found ? "FOUND" : "nothing");
    if (!with.found) reports += with.report;
    if (without.found) reports += without.report;
  }
  EXPECT_GE(detected, kSeeds - 1) << reports;
  EXPECT_LE(false_alarms, 1) << reports;
}

}  // namespace
}  // namespace stochnav
