#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/scenario/scenario_config_json.hpp"

namespace stochnav {
namespace {

nlohmann::json load(const std::string& name) {
  std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) + "/configs/scenarios/" + name);
  return nlohmann::json::parse(in);
}

TEST(ScenarioConfig, ShippedConfigurationsParseAndEchoStably) {
  for (const char* name :
       {"paper_fixed_frequency.json", "paper_random_vibration.json", "drilling_build_hold.json"}) {
    SCOPED_TRACE(name);
    const ScenarioConfig config = scenario_config_from_json(load(name), name);
    const nlohmann::json echo = to_json(config);
    // The echo is itself a valid configuration that echoes to the same JSON.
    const ScenarioConfig again = scenario_config_from_json(echo, "echo");
    EXPECT_EQ(to_json(again), echo);
  }
  const ScenarioConfig fixed =
      scenario_config_from_json(load("paper_fixed_frequency.json"), "fixed");
  EXPECT_NEAR(scenario_duration_s(fixed), 300 + 5400 + 600 + 900, 1e-9);
  const ScenarioConfig random =
      scenario_config_from_json(load("paper_random_vibration.json"), "random");
  EXPECT_NEAR(scenario_duration_s(random), 1800.0, 1e-9);
  EXPECT_NEAR(random.vibration_table->phases[2].random.rms_mps2, 13.12 * 9.80665, 1e-9);
}

struct BadCase {
  std::string name;
  std::string pointer;   // JSON pointer of the change
  nlohmann::json value;  // new value (null: remove)
  std::string expected;  // fragment of the message
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class BadScenario : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScenario, ThrowsConfigErrorNamingSourceAndPointer) {
  const BadCase& c = GetParam();
  nlohmann::json document = load("paper_fixed_frequency.json");
  const nlohmann::json::json_pointer pointer(c.pointer);
  if (c.value.is_null()) {
    document[pointer.parent_pointer()].erase(pointer.back());
  } else {
    document[pointer] = c.value;
  }
  try {
    scenario_config_from_json(document, "bad.json");
    FAIL() << "no error";
  } catch (const ConfigError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind("bad.json: ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_NE(message.find("expected"), std::string::npos) << message;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadScenario,
    ::testing::Values(BadCase{"unknown_top_key", "/colour", "red", "/colour: is an unknown key"},
                      BadCase{"unknown_phase_key", "/vibration_table/phases/1/amplitude", 3,
                              "/vibration_table/phases/1/amplitude: is an unknown key"},
                      BadCase{"negative_duration", "/vibration_table/phases/2/duration_s", -5,
                              "/vibration_table/phases/2/duration_s: is -5, not > 0"},
                      BadCase{"unknown_term", "/sensors/gyro/noise/terms/0/type", "pink_noise",
                              "/sensors/gyro/noise/terms/0/type: unknown term type \"pink_noise\""},
                      BadCase{"missing_rate", "/imu/rate_hz", nullptr, "/imu/rate_hz: is missing"},
                      BadCase{"rate_too_low", "/imu/rate_hz", 50, "/imu/rate_hz: is 50"},
                      BadCase{"aid_rate_not_divisor", "/imu/aid_rate_hz", 3, "/imu/aid_rate_hz"},
                      BadCase{"unknown_kind", "/kind", "centrifuge", "/kind: is \"centrifuge\""},
                      BadCase{"unknown_motion", "/vibration_table/phases/0/motion", "shake",
                              "/vibration_table/phases/0/motion"},
                      BadCase{"accel_units_for_gyro", "/sensors/gyro/noise/units", "m/s^2",
                              "/sensors/gyro/noise/units"},
                      BadCase{"nonstationary_in_schedule", "/sensors/gyro/scheduled_noise/terms/0",
                              nlohmann::json::parse(R"({"type": "nonstationary",
                                          "segments": [{"start": 0, "end": 1, "scale": 2}]})"),
                              "/sensors/gyro/scheduled_noise/terms/0"},
                      BadCase{"string_for_number", "/site/latitude_deg", "north",
                              "/site/latitude_deg: is a string, not a number"}),
    [](const ::testing::TestParamInfo<BadCase>& case_info) { return case_info.param.name; });

TEST(ScenarioConfig, DrillingRangesAreChecked) {
  nlohmann::json document = load("drilling_build_hold.json");
  document["drilling"]["vibration_episodes"][1]["start_s"] = 2500;
  EXPECT_THROW(scenario_config_from_json(document, "d.json"), ConfigError);
  document = load("drilling_build_hold.json");
  document["drilling"]["well"]["target_inclination_deg"] = 120;
  try {
    scenario_config_from_json(document, "d.json");
    FAIL();
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("/drilling/well/target_inclination_deg"),
              std::string::npos);
  }
  document = load("drilling_build_hold.json");
  document["drilling"]["ramp_s"] = 5000;
  EXPECT_THROW(scenario_config_from_json(document, "d.json"), ConfigError);
}

}  // namespace
}  // namespace stochnav
