// End-to-end: stochnav simulate scenario writes the four files, is deterministic by seed, and
// rejects bad configurations with exit code 2, the JSON pointer, and no output.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "run_cli.hpp"
#include "temp_dir.hpp"

namespace stochnav {
namespace {

using testing::run_cli;
using testing::TempDir;

nlohmann::json shipped(const std::string& name) {
  std::ifstream in(std::string(STOCHNAV_SOURCE_DIR) + "/configs/scenarios/" + name);
  return nlohmann::json::parse(in);
}

// A short version of a shipped configuration.
nlohmann::json short_table() {
  nlohmann::json config = shipped("paper_random_vibration.json");
  auto& phases = config["vibration_table"]["phases"];
  phases[0]["duration_s"] = 2;
  phases[1]["duration_s"] = 1;
  phases[2]["duration_s"] = 3;
  phases[3]["duration_s"] = 1;
  phases[4]["duration_s"] = 2;
  return config;
}

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(SimulateScenarioCli, WritesImuTruthAidsAndScenario) {
  TempDir dir;
  const std::string config = dir.write("table.json", short_table().dump());
  const auto result =
      run_cli("simulate scenario '" + config + "' --out '" + dir.file("out") + "'", dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_TRUE(result.err.empty()) << "no progress bar when stderr is not a terminal";
  const auto out = dir.path() / "out";
  const std::string imu = read(out / "imu.csv");
  EXPECT_EQ(imu.substr(0, imu.find('\n')), "t,dtheta_x,dtheta_y,dtheta_z,dv_x,dv_y,dv_z");
  EXPECT_EQ(lines(imu), 901u);  // 9 s at 100 Hz plus the header
  const std::string truth = read(out / "truth.csv");
  EXPECT_EQ(truth.substr(0, truth.find('\n')), "t,lat,lon,h,ve,vn,vu,inclination,toolface,azimuth");
  EXPECT_EQ(lines(truth), 92u);  // 10 Hz from t = 0
  const std::string aids = read(out / "aids.csv");
  EXPECT_EQ(aids.substr(0, aids.find('\n')),
            "t,measured_depth_m,rop_mph,zupt,measured_depth_true_m,rop_true_mph");
  EXPECT_EQ(lines(aids), 11u);
  const auto scenario = nlohmann::json::parse(read(out / "scenario.json"));
  EXPECT_EQ(scenario["seed"], 20170402);
  EXPECT_EQ(scenario["epochs"], 900);
  EXPECT_EQ(scenario["noise_schedule"]["phases"].size(), 5u);
  EXPECT_EQ(scenario["noise_schedule"]["phases"][2]["gyro_noise_scale"], 14.4);
  EXPECT_EQ(scenario["config"]["vibration_table"]["phases"].size(), 5u);
  EXPECT_EQ(scenario["motion"]["phases"][2]["vibration_components"].size(), 256u);
  EXPECT_EQ(scenario["files"]["imu.csv"]["units"][1], "rad");
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST(SimulateScenarioCli, SameSeedSameFilesOtherSeedOtherNoise) {
  TempDir dir;
  const std::string config = dir.write("table.json", short_table().dump());
  const auto run = [&](const std::string& out, const std::string& seed) {
    const auto result = run_cli(
        "simulate scenario '" + config + "' --out '" + dir.file(out) + "'" + seed, dir.path());
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return read(dir.path() / out / "imu.csv");
  };
  const std::string a = run("a", "");
  EXPECT_EQ(a, run("b", ""));
  EXPECT_EQ(a, run("c", " --seed 20170402"));
  EXPECT_NE(a, run("d", " --seed 1"));
  // The random-vibration realisation is drawn from the seed too.
  EXPECT_NE(read(dir.path() / "a" / "truth.csv"), read(dir.path() / "d" / "truth.csv"));
  EXPECT_EQ(read(dir.path() / "a" / "truth.csv"), read(dir.path() / "c" / "truth.csv"));
}

TEST(SimulateScenarioCli, DrillingScenarioRuns) {
  TempDir dir;
  nlohmann::json config = shipped("drilling_build_hold.json");
  config["drilling"]["duration_s"] = 30;
  config["drilling"]["initial_static_s"] = 10;
  config["imu"]["output"] = "rates";
  const std::string path = dir.write("drill.json", config.dump());
  const auto result =
      run_cli("simulate scenario '" + path + "' --out '" + dir.file("out") + "'", dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string aids = read(dir.path() / "out" / "aids.csv");
  EXPECT_EQ(lines(aids), 32u);
  EXPECT_NE(aids.find("\n5,"), std::string::npos);
  // Static at first (zupt 1), drilling later (zupt 0).
  EXPECT_NE(aids.find("\n5,450"), std::string::npos) << aids;
  const auto scenario = nlohmann::json::parse(read(dir.path() / "out" / "scenario.json"));
  EXPECT_EQ(scenario["files"]["imu.csv"]["units"][1], "rad/s");
  EXPECT_EQ(scenario["noise_schedule"]["phases"][1]["name"], "drilling");
}

struct BadConfigCase {
  std::string name;
  std::string pointer;
  nlohmann::json value;
  std::string expected;
};

void PrintTo(const BadConfigCase& c, std::ostream* os) { *os << c.name; }

class BadScenarioCli : public ::testing::TestWithParam<BadConfigCase> {};

TEST_P(BadScenarioCli, ExitCodeTwoOneLineWithPointerNoOutput) {
  const BadConfigCase& c = GetParam();
  TempDir dir;
  nlohmann::json config = short_table();
  config[nlohmann::json::json_pointer(c.pointer)] = c.value;
  const std::string path = dir.write("bad.json", config.dump());
  const auto result =
      run_cli("simulate scenario '" + path + "' --out '" + dir.file("out") + "'", dir.path());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  ASSERT_FALSE(result.err.empty());
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_NE(result.err.find("bad.json"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(c.expected), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "imu.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "scenario.json"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadScenarioCli,
    ::testing::Values(BadConfigCase{"unknown_key", "/imu/rate", 100,
                                    "/imu/rate: is an unknown key"},
                      BadConfigCase{"negative_duration", "/vibration_table/phases/0/duration_s",
                                    -300, "/vibration_table/phases/0/duration_s"},
                      BadConfigCase{"unknown_term_type", "/sensors/accel/noise/terms/0/type",
                                    "flicker", "/sensors/accel/noise/terms/0/type"}),
    [](const ::testing::TestParamInfo<BadConfigCase>& case_info) { return case_info.param.name; });

TEST(SimulateScenarioCli, MissingAndMalformedFiles) {
  TempDir dir;
  auto result =
      run_cli("simulate scenario '" + dir.file("absent.json") + "' --out '" + dir.file("out") + "'",
              dir.path());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("absent.json: cannot open"), std::string::npos) << result.err;
  const std::string broken = dir.write("broken.json", "{\"kind\": ");
  result =
      run_cli("simulate scenario '" + broken + "' --out '" + dir.file("out") + "'", dir.path());
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("not valid JSON"), std::string::npos) << result.err;
}

TEST(SimulateScenarioCli, SlideRotateScenarioRuns) {
  TempDir dir;
  nlohmann::json config = shipped("drilling_slide_rotate.json");
  config["drilling"]["duration_s"] = 90;
  config["drilling"]["initial_static_s"] = 10;
  config["drilling"]["orient_s"] = 20;
  config["aids"]["dropouts"] = {{{"start_s", 50}, {"end_s", 60}}};
  const std::string path = dir.write("slide.json", config.dump());
  const auto result =
      run_cli("simulate scenario '" + path + "' --out '" + dir.file("out") + "'", dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::string aids = read(dir.path() / "out" / "aids.csv");
  EXPECT_EQ(lines(aids), 92u - 11u);  // 0..90 s at 1 Hz without 50..60
  EXPECT_NE(aids.find("\n0.004,"), std::string::npos) << aids;
  EXPECT_NE(aids.find("\n49.004,"), std::string::npos) << aids;
  EXPECT_EQ(aids.find("\n50.004,"), std::string::npos) << aids;
  const auto scenario = nlohmann::json::parse(read(dir.path() / "out" / "scenario.json"));
  const auto& phases = scenario["noise_schedule"]["phases"];
  ASSERT_GE(phases.size(), 3u);
  EXPECT_EQ(phases[0]["name"], "static");
  EXPECT_EQ(phases[1]["name"], "orienting");
  EXPECT_EQ(phases[2]["name"], "drilling");
  EXPECT_EQ(scenario["config"]["drilling"]["stand_pattern"].size(), 2u);
  EXPECT_TRUE(scenario["files"]["aids.csv"].contains("timing"));
}

class BadDrillingScenarioCli : public ::testing::TestWithParam<BadConfigCase> {};

TEST_P(BadDrillingScenarioCli, ExitCodeTwoOneLineWithPointerNoOutput) {
  const BadConfigCase& c = GetParam();
  TempDir dir;
  nlohmann::json config = shipped("drilling_slide_rotate.json");
  config[nlohmann::json::json_pointer(c.pointer)] = c.value;
  const std::string path = dir.write("bad.json", config.dump());
  const auto result =
      run_cli("simulate scenario '" + path + "' --out '" + dir.file("out") + "'", dir.path());
  EXPECT_EQ(result.exit_code, 2) << result.err;
  ASSERT_FALSE(result.err.empty());
  EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << "one line: " << result.err;
  EXPECT_NE(result.err.find("bad.json"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find(c.expected), std::string::npos) << result.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out" / "imu.csv"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadDrillingScenarioCli,
    ::testing::Values(BadConfigCase{"pattern_not_summing", "/drilling/stand_pattern/0/length_m", 5,
                                    "/drilling/stand_pattern: has lengths summing to 24 m"},
                      BadConfigCase{"section_out_of_range",
                                    "/drilling/well/sections/1/build_rate_deg_per_30m", -3,
                                    "/drilling/well/sections/1: drives the inclination"},
                      BadConfigCase{"dropout_backwards", "/aids/dropouts/0/end_s", 100,
                                    "/aids/dropouts/0/end_s"}),
    [](const ::testing::TestParamInfo<BadConfigCase>& case_info) { return case_info.param.name; });

}  // namespace
}  // namespace stochnav
