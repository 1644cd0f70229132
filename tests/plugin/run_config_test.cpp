// Run-config validation, and building a run's plugins (including a fitted noise model) from it.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
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

  // No truth: the run starts from "initial_state".
  nlohmann::json minimal() const {
    return {{"data", {{"imu", "imu.csv"}}},
            {"noise",
             {{"gyro", {{"plugin", "white"}, {"params", {{"N", 0.05}}}}},
              {"accel", {{"plugin", "gauss_markov"}, {"params", {{"sigma", 1}, {"tau_c", 10}}}}}}},
            {"initial_state",
             {{"tie_on", {{"latitude_deg", 40}, {"longitude_deg", 116}, {"height_m", 50}}},
              {"attitude", {{"inclination_deg", 60}, {"azimuth_deg", 100}, {"toolface_deg", 30}}}}}};
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
  EXPECT_EQ(config.output.decimation, 100u);
  ASSERT_TRUE(config.initial_state);
  EXPECT_EQ(config.initial_state->tie_on.latitude_deg, 40.0);
  EXPECT_FALSE(config.initial_state->tie_on.measured_depth_m);
  ASSERT_TRUE(config.initial_state->attitude);
  EXPECT_EQ(config.initial_state->attitude->toolface_deg, 30.0);
  EXPECT_FALSE(config.initial_state->alignment);
  EXPECT_FALSE(config.initial_error);
}

// One set of defaults: a config without "filter", and one with every key at its documented
// default value, both give FilterOptions{} exactly (up to the deg / ppm round trip).
void expect_same_options(const FilterOptions& a, const FilterOptions& b, double tolerance) {
  EXPECT_EQ(a.covariance_interval_s, b.covariance_interval_s);
  EXPECT_EQ(a.max_consecutive_rejections, b.max_consecutive_rejections);
  EXPECT_EQ(a.second_order_attitude_correlation_s, b.second_order_attitude_correlation_s);
  EXPECT_EQ(a.heading_hypotheses_likelihood_power, b.heading_hypotheses_likelihood_power);
  EXPECT_EQ(a.heading_hypotheses_hold_together, b.heading_hypotheses_hold_together);
  EXPECT_EQ(a.heading_hypotheses_split_running, b.heading_hypotheses_split_running);
  EXPECT_EQ(a.heading_hypotheses_mirror_at_rotation, b.heading_hypotheses_mirror_at_rotation);
  EXPECT_TRUE(a.position_sigma_m.isApprox(b.position_sigma_m, tolerance));
  EXPECT_TRUE(a.velocity_sigma_mps.isApprox(b.velocity_sigma_mps, tolerance));
  EXPECT_TRUE(a.attitude_sigma_rad.isApprox(b.attitude_sigma_rad, tolerance));
  EXPECT_TRUE(a.accel_bias_sigma_mps2.isApprox(b.accel_bias_sigma_mps2, tolerance));
  EXPECT_TRUE(a.gyro_bias_sigma_radps.isApprox(b.gyro_bias_sigma_radps, tolerance));
  EXPECT_TRUE((a.gyro_scale_factor_sigma - b.gyro_scale_factor_sigma).norm() <= tolerance);
  EXPECT_TRUE((a.accel_scale_factor_sigma - b.accel_scale_factor_sigma).norm() <= tolerance);
  EXPECT_TRUE(a.initial_gyro_bias_radps.isZero());
  EXPECT_TRUE(a.initial_accel_bias_mps2.isZero());
}

TEST_F(RunConfigTest, FilterDefaultsAreFilterOptionsDefaults) {
  const FilterOptions defaults;
  expect_same_options(parse_run_config(minimal(), dir_.path()).filter.options, defaults, 0.0);
  expect_same_options(parse_filter_section(nlohmann::json::object(), "/filter").options, defaults,
                      0.0);
  // The numbers the run_config.hpp comment states, in the config's units.
  const nlohmann::json stated = nlohmann::json::parse(R"({
      "initial_sigma": {"position_m": 0.1, "velocity_m_s": 0.01,
                        "attitude_deg": [0.0572958, 0.0572958, 0.572958],
                        "accel_bias_m_s2": 0.001, "gyro_bias_deg_h": 1.031324},
      "covariance_interval_s": 0.1, "max_consecutive_rejections": 3,
      "second_order_attitude_correlation_s": 900, "heading_hypothesis_likelihood_power": 0.5,
      "heading_hypothesis_hold_together": true, "heading_hypothesis_split_running": true,
      "heading_hypothesis_mirror_at_rotation": true,
      "scale_factor_sigma_ppm": {"gyro": 0, "accel": 0}, "feedback": "closed_loop"})");
  expect_same_options(parse_filter_section(stated, "/filter").options, defaults, 1e-6);
}

TEST_F(RunConfigTest, FilterSectionIsReadInSiUnits) {
  const nlohmann::json filter = nlohmann::json::parse(R"({
      "initial_sigma": {"attitude_deg": [1, 2, 3], "gyro_bias_deg_h": 3600},
      "covariance_interval_s": 0, "max_consecutive_rejections": 0,
      "second_order_attitude_correlation_s": 0, "heading_hypothesis_likelihood_power": 1,
      "heading_hypothesis_hold_together": false, "heading_hypothesis_split_running": false,
      "heading_hypothesis_mirror_at_rotation": false,
      "scale_factor_sigma_ppm": {"gyro": [10, 20, 30], "accel": 50}})");
  const FilterOptions options = parse_filter_section(filter, "/filter").options;
  EXPECT_NEAR(options.attitude_sigma_rad.y(), 2.0 * std::numbers::pi / 180.0, 1e-15);
  EXPECT_NEAR(options.gyro_bias_sigma_radps.x(), std::numbers::pi / 180.0, 1e-15);
  EXPECT_EQ(options.covariance_interval_s, 0.0);
  EXPECT_EQ(options.max_consecutive_rejections, 0);
  EXPECT_EQ(options.second_order_attitude_correlation_s, 0.0);
  EXPECT_EQ(options.heading_hypotheses_likelihood_power, 1.0);
  EXPECT_FALSE(options.heading_hypotheses_hold_together);
  EXPECT_FALSE(options.heading_hypotheses_split_running);
  EXPECT_FALSE(options.heading_hypotheses_mirror_at_rotation);
  EXPECT_NEAR(options.gyro_scale_factor_sigma.z(), 30e-6, 1e-18);
  EXPECT_NEAR(options.accel_scale_factor_sigma.x(), 50e-6, 1e-18);
  EXPECT_EQ(options.position_sigma_m, FilterOptions{}.position_sigma_m);
}

TEST_F(RunConfigTest, InitialStateAndErrorSections) {
  nlohmann::json document = minimal();
  document["initial_state"].erase("attitude");
  document["initial_state"]["alignment"] = {{"static_s", 30}, {"attitude_sigma_deg", 2}};
  document["initial_state"]["tie_on"]["measured_depth_m"] = 450;
  document["initial_error"] = {
      {"position_m", {1, -2, 3}}, {"attitude_deg", 0.5}, {"gyro_bias_deg_h", -1}, {"draw_seed", 7}};
  const RunConfig config = parse_run_config(document, dir_.path());
  ASSERT_TRUE(config.initial_state->alignment);
  EXPECT_EQ(config.initial_state->alignment->static_s, 30.0);
  EXPECT_EQ(config.initial_state->alignment->max_accel_spread_m_s2,
            AlignmentConfig{}.max_accel_spread_m_s2);
  EXPECT_EQ((*config.initial_state->alignment->attitude_sigma_deg)[2], 2.0);
  EXPECT_EQ(*config.initial_state->tie_on.measured_depth_m, 450.0);
  ASSERT_TRUE(config.initial_error);
  EXPECT_EQ(config.initial_error->position_m[1], -2.0);
  EXPECT_EQ(config.initial_error->attitude_deg[2], 0.5);
  EXPECT_EQ(config.initial_error->gyro_bias_deg_h[0], -1.0);
  EXPECT_EQ(config.initial_error->velocity_m_s[0], 0.0);
  EXPECT_EQ(*config.initial_error->draw_seed, 7u);
}

TEST_F(RunConfigTest, DataFolderReplacesTheDataSection) {
  nlohmann::json document = minimal();
  document.erase("data");
  EXPECT_EQ(error_of(document), "/data: missing; expected an object");
  const RunConfig config = parse_run_config(document, dir_.path(), data_from_folder(dir_.path()));
  EXPECT_EQ(config.data.imu, dir_.path() / "imu.csv");
  EXPECT_EQ(config.data.aids, dir_.path() / "aids.csv");
  EXPECT_FALSE(config.data.truth);
  try {
    data_from_folder(dir_.path() / "nowhere");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("--data " + (dir_.path() / "nowhere").string(), 0),
              0u)
        << error.what();
  }
}

TEST_F(RunConfigTest, AnEmbeddersConfigNeedsNoDataSection) {
  nlohmann::json document = minimal();
  document.erase("data");
  const std::filesystem::path file = dir_.path() / "embedded.json";
  std::ofstream(file) << document.dump();
  EXPECT_THROW(read_run_config(file), ConfigError) << "a run needs its data";
  const RunConfig config = read_embedded_run_config(file);
  EXPECT_TRUE(config.data.imu.empty());
  EXPECT_EQ(config.noise.gyro.type, "white");
  ASSERT_TRUE(config.initial_state);
  // Everything else is still checked.
  document["filter"] = {{"covariance_interval_s", -1}};
  std::ofstream(file) << document.dump();
  EXPECT_THROW(read_embedded_run_config(file), ConfigError);
}

TEST_F(RunConfigTest, FullConfigIsRead) {
  nlohmann::json document = minimal();
  document["data"]["aids"] = "aids.csv";
  document["noise"]["gyro"]["fit"] = {{"start_s", 10}, {"end_s", 50}};
  document["aids"] = {{{"plugin", "zupt"}, {"params", {{"sigma_m_s", 0.01}}}}};
  document["filter"] = {{"initial_sigma", {{"position_m", {1, 2, 3}}}},
                        {"feedback", "closed_loop"}};
  document["output"] = {{"decimation", 10}, {"nees", false}};
  const RunConfig config = parse_run_config(document, dir_.path());
  ASSERT_TRUE(config.noise.gyro.fit);
  EXPECT_EQ(config.noise.gyro.fit->record, dir_.path() / "imu.csv");
  EXPECT_EQ(config.noise.gyro.fit->columns[2], "gyro_z");
  EXPECT_EQ(*config.noise.gyro.fit->end_s, 50.0);
  ASSERT_EQ(config.aids.size(), 1u);
  EXPECT_EQ(config.aids[0].type, "zupt");
  EXPECT_EQ(config.aids[0].params_pointer(), "/aids/0/params");
  EXPECT_EQ(config.filter.options.position_sigma_m.y(), 2.0);
  EXPECT_EQ(config.output.decimation, 10u);
  EXPECT_FALSE(config.output.nees);
}

TEST_F(RunConfigTest, EveryErrorNamesItsPointer) {
  auto with = [this](const std::string& pointer, const nlohmann::json& value) {
    nlohmann::json document = minimal();
    document[nlohmann::json::json_pointer(pointer)] = value;
    return error_of(document);
  };
  EXPECT_EQ(with("/extra", 1).substr(0, 35), "/extra: unknown key; expected only ");
  EXPECT_NE(with("/extra", 1).find("initial_state"), std::string::npos);
  EXPECT_EQ(with("/noise/gyro/plugn", "x").substr(0, 30), "/noise/gyro/plugn: unknown key");
  EXPECT_EQ(with("/noise/gyro/params", 3),
            "/noise/gyro/params: not an object; expected the plugin's parameters as an object");
  EXPECT_EQ(with("/data/imu", "nope.csv").substr(0, 31),
            "/data/imu: file not found: " + dir_.path().string().substr(0, 4));
  const std::string one_mode =
      "; the navigator has one mode, \"closed_loop\" (every update fed back into the INS): give "
      "it or leave the key out";
  EXPECT_EQ(with("/filter/feedback", "loop"), "/filter/feedback: found \"loop\"" + one_mode);
  EXPECT_EQ(with("/filter/feedback", "open_loop"),
            "/filter/feedback: found \"open_loop\"" + one_mode);
  EXPECT_EQ(with("/filter/covariance_interval_s", -0.1).rfind("/filter/covariance_interval_s:", 0),
            0u);
  EXPECT_EQ(with("/filter/max_consecutive_rejections", 2.5),
            "/filter/max_consecutive_rejections: found 2.5; expected an integer >= 0");
  EXPECT_EQ(with("/filter/max_consecutive_rejections", -1),
            "/filter/max_consecutive_rejections: found -1; expected an integer >= 0");
  EXPECT_EQ(with("/filter/heading_hypothesis_likelihood_power", 0),
            "/filter/heading_hypothesis_likelihood_power: 0.000000 is out of range; expected a "
            "value in [0.050000, 1.000000]");
  EXPECT_EQ(with("/filter/lockout", 3).substr(0, 31), "/filter/lockout: unknown key; e");
  EXPECT_EQ(with("/filter/scale_factor_sigma_ppm/gyro", -1)
                .rfind("/filter/scale_factor_sigma_ppm/gyro", 0),
            0u);
  EXPECT_EQ(with("/initial_state/tie_on/latitude_deg", 91)
                .rfind("/initial_state/tie_on/latitude_deg: 91", 0),
            0u);
  EXPECT_EQ(with("/initial_state/alignment", {{"static_s", 10}})
                .rfind("/initial_state: both \"attitude\" and \"alignment\" given", 0),
            0u);
  EXPECT_EQ(with("/initial_state/tie_on", {{"latitude_deg", 1}})
                .rfind("/initial_state/tie_on/longitude_deg: missing", 0),
            0u);
  EXPECT_EQ(with("/initial_error/draw_seed", -3),
            "/initial_error/draw_seed: found -3; expected an integer >= 0");
  EXPECT_EQ(with("/initial_error/attitude", 1).substr(0, 38),
            "/initial_error/attitude: unknown key; ");
  nlohmann::json no_start = minimal();
  no_start.erase("initial_state");
  const RunConfig without_start = parse_run_config(no_start, dir_.path());
  try {
    check_run_start(without_start);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("/initial_state: missing, and the data has no truth",
                                              0),
              0u);
  }
  EXPECT_NO_THROW(check_run_start(parse_run_config(minimal(), dir_.path())));
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

// The fitter's options under their own key (issue #30 item 3): "fit_options" reaches the
// fitter in place of "params", and errors name it; "params" beside it, or "fit_options"
// without "fit", is refused.
TEST_F(RunConfigTest, FitOptionsAreTheFittersOwnKey) {
  nlohmann::json document = minimal();
  document["noise"]["gyro"].erase("params");
  document["noise"]["gyro"]["fit"] = {{"start_s", 0}, {"end_s", 40}};
  document["noise"]["gyro"]["fit_options"] = {{"method", "avar"}};
  const RunConfig config = parse_run_config(document, dir_.path());
  ASSERT_TRUE(config.noise.gyro.fit_options);
  EXPECT_EQ(config.noise.gyro.options_pointer(), "/noise/gyro/fit_options");
  const PluginRegistry registry(default_search_path(config.config_dir));
  const RunPlugins plugins = build_run_plugins(config, registry, AidData(), NavState(), 100.0);
  Eigen::Matrix3d q;
  plugins.gyro->white_noise_covariance(0.0, 1.0, q);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::sqrt(q(i, i)), 1e-5, 1.5e-6);

  document["noise"]["gyro"]["fit_options"] = {{"method", "fourier"}};
  try {
    build_run_plugins(parse_run_config(document, dir_.path()), registry, AidData(), NavState(),
                      100.0);
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("/noise/gyro/fit_options/method"),
              std::string::npos)
        << error.what();
  }
  document["noise"]["gyro"]["fit_options"] = {{"method", "avar"}};
  document["noise"]["gyro"]["params"] = {{"method", "gmwm"}};
  EXPECT_NE(error_of(document).find("/noise/gyro/params: given beside \"fit_options\""),
            std::string::npos)
      << error_of(document);
  document["noise"]["gyro"].erase("params");
  document["noise"]["gyro"].erase("fit");
  EXPECT_NE(error_of(document).find("/noise/gyro/fit_options: given without \"fit\""),
            std::string::npos)
      << error_of(document);
  document["noise"]["gyro"]["fit"] = {{"start_s", 0}, {"end_s", 40}};
  document["noise"]["gyro"]["fit_options"] = "gmwm";
  EXPECT_NE(error_of(document).find("/noise/gyro/fit_options: found \"gmwm\""),
            std::string::npos)
      << error_of(document);
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
