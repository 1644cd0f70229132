// Run-config validation, and building a run's plugins (including a fitted noise model) from it.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/runtime.hpp"
#include "temp_dir.hpp"

namespace stochnav::plugin {
namespace {

class RunConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // A static IMU record: white noise on every channel, 100 Hz, 60 s.
    std::ofstream csv(dir_.file("imu.csv"));
    csv << "t,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
    std::mt19937_64 random(5);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int k = 0; k < 6000; ++k) {
      csv << k * 0.01;
      for (int c = 0; c < 3; ++c) csv << ',' << 1e-4 * normal(random);
      for (int c = 0; c < 3; ++c) csv << ',' << 1e-3 * normal(random);
      csv << '\n';
    }
    dir_.write("aids.csv", "t,zupt\n0,1\n1,0\n");
  }

  nlohmann::json minimal() const {
    return {{"data", {{"imu", "imu.csv"}}},
            {"noise",
             {{"gyro", {{"plugin", "white"}, {"params", {{"N", 0.05}}}}},
              {"accel", {{"plugin", "gauss_markov"}, {"params", {{"sigma", 1}, {"tau_c", 10}}}}}}}};
  }

  std::string error_of(const nlohmann::json& document) const {
    try {
      parse_run_config(document, dir_.path());
    } catch (const ConfigError& error) {
      return error.what();
    }
    return "(valid)";
  }

  testing::TempDir dir_;
};

TEST_F(RunConfigTest, MinimalConfigGetsTheDocumentedDefaults) {
  const RunConfig config = parse_run_config(minimal(), dir_.path());
  EXPECT_EQ(config.data.imu, dir_.path() / "imu.csv");
  EXPECT_FALSE(config.data.truth);
  EXPECT_EQ(config.noise.gyro.type, "white");
  EXPECT_EQ(config.noise.gyro.params_pointer(), "/noise/gyro/params");
  EXPECT_EQ(config.noise.accel.type_pointer(), "/noise/accel/plugin");
  EXPECT_TRUE(config.aids.empty());
  EXPECT_EQ(config.filter.feedback, FeedbackMode::kClosedLoop);
  EXPECT_EQ(config.filter.initial_sigma.attitude_deg[2], 0.5);
  EXPECT_EQ(config.output.decimation, 100u);
}

TEST_F(RunConfigTest, FullConfigIsRead) {
  nlohmann::json document = minimal();
  document["data"]["aids"] = "aids.csv";
  document["noise"]["gyro"]["fit"] = {{"start_s", 10}, {"end_s", 50}};
  document["aids"] = {{{"plugin", "zupt"}, {"params", {{"sigma_m_s", 0.01}}}}};
  document["filter"] = {{"initial_sigma", {{"position_m", {1, 2, 3}}}}, {"feedback", "open_loop"}};
  document["output"] = {{"decimation", 10}, {"nees", false}};
  const RunConfig config = parse_run_config(document, dir_.path());
  ASSERT_TRUE(config.noise.gyro.fit);
  EXPECT_EQ(config.noise.gyro.fit->record, dir_.path() / "imu.csv");
  EXPECT_EQ(config.noise.gyro.fit->columns[2], "gyro_z");
  EXPECT_EQ(*config.noise.gyro.fit->end_s, 50.0);
  ASSERT_EQ(config.aids.size(), 1u);
  EXPECT_EQ(config.aids[0].type, "zupt");
  EXPECT_EQ(config.aids[0].params_pointer(), "/aids/0/params");
  EXPECT_EQ(config.filter.initial_sigma.position_m[1], 2.0);
  EXPECT_EQ(config.filter.feedback, FeedbackMode::kOpenLoop);
  EXPECT_EQ(config.output.decimation, 10u);
  EXPECT_FALSE(config.output.nees);
}

TEST_F(RunConfigTest, EveryErrorNamesItsPointer) {
  auto with = [this](const std::string& pointer, const nlohmann::json& value) {
    nlohmann::json document = minimal();
    document[nlohmann::json::json_pointer(pointer)] = value;
    return error_of(document);
  };
  EXPECT_EQ(with("/extra", 1),
            "/extra: unknown key; expected only aids, data, filter, noise, output");
  EXPECT_EQ(with("/noise/gyro/plugn", "x").substr(0, 30), "/noise/gyro/plugn: unknown key");
  EXPECT_EQ(with("/noise/gyro/params", 3),
            "/noise/gyro/params: not an object; expected the plugin's parameters as an object");
  EXPECT_EQ(with("/data/imu", "nope.csv").substr(0, 31),
            "/data/imu: file not found: " + dir_.path().string().substr(0, 4));
  EXPECT_NE(
      with("/filter/feedback", "loop").find("/filter/feedback: found \"loop\"; expected one of"),
      std::string::npos);
  EXPECT_EQ(with("/output/decimation", 0), "/output/decimation: found 0; expected an integer >= 1");
  EXPECT_NE(
      with("/filter/initial_sigma/attitude_deg", -1).find("/filter/initial_sigma/attitude_deg"),
      std::string::npos);
  EXPECT_EQ(with("/aids", {{{"params", {}}}}),
            "/aids/0/plugin: missing; expected a non-empty string");
  EXPECT_EQ(with("/noise/gyro/fit", {{"start_s", 5}, {"end_s", 1}}).substr(0, 24),
            "/noise/gyro/fit/end_s: 1");
  nlohmann::json no_accel = minimal();
  no_accel["noise"].erase("accel");
  EXPECT_EQ(error_of(no_accel), "/noise/accel: missing; expected an object");
  nlohmann::json both = minimal();
  both["data"]["scenario"] = ".";
  EXPECT_NE(error_of(both).find("/data: both \"scenario\" and \"imu\" given"), std::string::npos);
}

TEST_F(RunConfigTest, BuildsThePluginsAndFitsFromTheCalibrationRecord) {
  nlohmann::json document = minimal();
  document["noise"]["gyro"]["params"] = nlohmann::json::object();
  document["noise"]["gyro"]["fit"] = {{"start_s", 0}, {"end_s", 40}};
  const RunConfig config = parse_run_config(document, dir_.path());
  const PluginRegistry registry(default_search_path(config.config_dir));
  const RunPlugins plugins = build_run_plugins(config, registry, AidData(), NavState(), 100.0);
  // White noise of 1e-4 rad/s per sample at 100 Hz: N = 1e-4 / sqrt(100) = 1e-5 rad/sqrt(s).
  Eigen::Matrix3d q;
  plugins.gyro->white_noise_covariance(0.0, 1.0, q);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::sqrt(q(i, i)), 1e-5, 1.5e-6);
  EXPECT_EQ(plugins.layout.size(), 18);
  EXPECT_EQ(plugins.accel->placement().augmented_offset, 15);

  document["noise"]["gyro"]["fit"]["columns"] = {"gyro_x", "gyro_y", "gyro_w"};
  const RunConfig bad_column = parse_run_config(document, dir_.path());
  EXPECT_THROW(build_run_plugins(bad_column, registry, AidData(), NavState(), 100.0), InputError);
  document["noise"]["gyro"]["fit"].erase("columns");
  document["noise"]["gyro"]["fit"]["start_s"] = 100;
  document["noise"]["gyro"]["fit"]["end_s"] = 200;
  try {
    build_run_plugins(parse_run_config(document, dir_.path()), registry, AidData(), NavState(),
                      100.0);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("/noise/gyro/fit: the window"), std::string::npos);
  }
}

}  // namespace
}  // namespace stochnav::plugin
