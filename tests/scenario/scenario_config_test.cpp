#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
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

// The shipped config `base` with the case's change gives one ConfigError line naming the
// source, the fragment expected and the expected form.
void expect_config_error(const BadCase& c, const std::string& base) {
  nlohmann::json document = load(base);
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
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST_P(BadScenario, ThrowsConfigErrorNamingSourceAndPointer) {
  expect_config_error(GetParam(), "paper_fixed_frequency.json");
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

TEST(ScenarioConfig, SlideRotateConfigurationParsesAndEchoesStably) {
  const ScenarioConfig config =
      scenario_config_from_json(load("drilling_slide_rotate.json"), "slide_rotate");
  const nlohmann::json echo = to_json(config);
  const ScenarioConfig again = scenario_config_from_json(echo, "echo");
  EXPECT_EQ(to_json(again), echo);
  const DrillingConfig& d = *config.drilling;
  ASSERT_EQ(d.well.sections.size(), 3u);
  EXPECT_NEAR(d.well.start_azimuth_rad, 80.0 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_NEAR(d.well.sections[2].turn_rate_rad_per_m, 6.0 * std::numbers::pi / 180.0 / 30.0, 1e-15);
  ASSERT_EQ(d.stand_pattern.size(), 2u);
  EXPECT_EQ(d.stand_pattern[0].mode, DrillMode::kSlide);
  EXPECT_EQ(d.stand_pattern[0].rotation_radps, 0.0);
  EXPECT_NEAR(d.stand_pattern[1].rotation_radps, 100.0 * 2.0 * std::numbers::pi / 60.0, 1e-12);
  EXPECT_EQ(d.orient_s, 30.0);
  ASSERT_EQ(d.vibration_episodes.size(), 1u);
  ASSERT_EQ(d.md_vibration_episodes.size(), 1u);
  EXPECT_EQ(d.md_vibration_episodes[0].end_md_m, 680.0);
  EXPECT_EQ(config.aids.clock_offset_s, 0.004);
  EXPECT_EQ(config.aids.latency_s, 0.5);
  ASSERT_EQ(config.aids.dropouts.size(), 1u);
}

TEST(ScenarioConfig, PatternDefaultsComeFromRopAndRotation) {
  nlohmann::json document = load("drilling_slide_rotate.json");
  document["drilling"]["stand_pattern"][1].erase("rpm");
  document["drilling"]["stand_pattern"][1].erase("rop_mph");
  document["drilling"]["well"] = {{"kickoff_md_m", 300},
                                  {"build_rate_deg_per_30m", 3},
                                  {"target_inclination_deg", 30},
                                  {"azimuth_deg", 80},
                                  {"turn_rate_deg_per_30m", -2}};
  const ScenarioConfig config = scenario_config_from_json(document, "defaults");
  const DrillingConfig& d = *config.drilling;
  EXPECT_EQ(d.stand_pattern[1].rotation_radps, d.rotation_radps);
  EXPECT_EQ(d.stand_pattern[1].rop_mps, d.rop_mps);
  EXPECT_NEAR(d.well.turn_rate_rad_per_m, -2.0 * std::numbers::pi / 180.0 / 30.0, 1e-15);
  const nlohmann::json echo = to_json(config);
  EXPECT_EQ(to_json(scenario_config_from_json(echo, "echo")), echo);
  // Without a turn the plane well echoes as before (no turn key).
  document["drilling"]["well"].erase("turn_rate_deg_per_30m");
  EXPECT_FALSE(to_json(scenario_config_from_json(document, "plane"))["drilling"]["well"].contains(
      "turn_rate_deg_per_30m"));
}

class BadDrillingScenario : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadDrillingScenario, ThrowsConfigErrorNamingSourceAndPointer) {
  expect_config_error(GetParam(), "drilling_slide_rotate.json");
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadDrillingScenario,
    ::testing::Values(
        BadCase{"pattern_not_summing", "/drilling/stand_pattern/1/length_m", 18,
                "/drilling/stand_pattern: has lengths summing to 27.5 m, not stand_length_m 28.5"},
        BadCase{"pattern_empty", "/drilling/stand_pattern", nlohmann::json::array(),
                "/drilling/stand_pattern: is empty"},
        BadCase{"unknown_mode", "/drilling/stand_pattern/0/mode", "wobble",
                "/drilling/stand_pattern/0/mode: is \"wobble\"; expected \"rotate\" or \"slide\""},
        BadCase{"slide_without_toolface", "/drilling/stand_pattern/0/toolface_deg", nullptr,
                "/drilling/stand_pattern/0/toolface_deg: is missing"},
        BadCase{"rpm_in_slide", "/drilling/stand_pattern/0/rpm", 50,
                "/drilling/stand_pattern/0/rpm: is given for a slide segment"},
        BadCase{"toolface_in_rotate", "/drilling/stand_pattern/1/toolface_deg", 10,
                "/drilling/stand_pattern/1/toolface_deg: is given for a rotate segment"},
        BadCase{"segment_shorter_than_ramps", "/drilling/ramp_s", 3000,
                "/drilling/stand_pattern/0/length_m: is 9.5 m: the ramps alone drill more"},
        BadCase{"unknown_segment_key", "/drilling/stand_pattern/1/torque", 3,
                "/drilling/stand_pattern/1/torque: is an unknown key"},
        BadCase{"orient_zero", "/drilling/orient_s", 0, "/drilling/orient_s: is 0, not > 0"},
        BadCase{"orient_without_pattern", "/drilling/stand_pattern", nullptr,
                "/drilling/orient_s: is given without \"stand_pattern\""},
        BadCase{"section_drops_below_vertical", "/drilling/well/sections/1/build_rate_deg_per_30m",
                -3, "/drilling/well/sections/1: drives the inclination to -30 deg"},
        BadCase{"section_beyond_180", "/drilling/well/sections/2/build_rate_deg_per_30m", 40,
                "/drilling/well/sections/2: drives the inclination to 230 deg"},
        BadCase{"section_zero_length", "/drilling/well/sections/0/length_m", 0,
                "/drilling/well/sections/0/length_m: is 0, not > 0"},
        BadCase{"sections_with_kickoff", "/drilling/well/kickoff_md_m", 500,
                "/drilling/well/kickoff_md_m: cannot be combined with \"sections\""},
        BadCase{"sections_empty", "/drilling/well/sections", nlohmann::json::array(),
                "/drilling/well/sections: is empty"},
        BadCase{"start_inclination", "/drilling/well/start/inclination_deg", 190,
                "/drilling/well/start/inclination_deg: is 190"},
        BadCase{"unknown_section_key", "/drilling/well/sections/0/dogleg", 3,
                "/drilling/well/sections/0/dogleg: is an unknown key"},
        BadCase{"md_episode_backwards", "/drilling/vibration_episodes/1/end_md_m", 630,
                "/drilling/vibration_episodes/1/end_md_m: is 630, not beyond start_md_m"},
        BadCase{"md_episode_empty", "/drilling/vibration_episodes/1/end_md_m", 640,
                "/drilling/vibration_episodes/1/end_md_m: is 640, not beyond start_md_m"},
        BadCase{"md_episodes_overlap", "/drilling/vibration_episodes/2",
                nlohmann::json::parse(
                    R"({"start_md_m": 670, "end_md_m": 700, "axial_g": 1, "frequency_hz": 9})"),
                "/drilling/vibration_episodes/2/start_md_m: overlaps the previous depth episode"},
        BadCase{"time_episodes_overlap", "/drilling/vibration_episodes/2",
                nlohmann::json::parse(
                    R"({"start_s": 1700, "end_s": 1900, "axial_g": 1, "frequency_hz": 9})"),
                "/drilling/vibration_episodes/2/start_s: overlaps the previous episode"},
        BadCase{"time_in_md_episode", "/drilling/vibration_episodes/1/start_s", 5,
                "/drilling/vibration_episodes/1/start_s: is a time in a depth episode"},
        BadCase{"dropout_backwards", "/aids/dropouts/0/end_s", 9000,
                "/aids/dropouts/0/end_s: is 9000, not after start_s 9000"},
        BadCase{"dropouts_overlap", "/aids/dropouts/1",
                nlohmann::json::parse(R"({"start_s": 9200, "end_s": 9400})"),
                "/aids/dropouts/1/start_s: overlaps or touches the previous dropout"},
        BadCase{"dropouts_not_array", "/aids/dropouts", 3, "/aids/dropouts: is a number"},
        BadCase{"clock_offset_too_large", "/aids/clock_offset_s", 1.5,
                "/aids/clock_offset_s: is 1.5"},
        BadCase{"negative_latency", "/aids/latency_s", -0.1, "/aids/latency_s: is -0.1, negative"}),
    [](const ::testing::TestParamInfo<BadCase>& case_info) { return case_info.param.name; });

}  // namespace
}  // namespace stochnav
