// The "oracle" noise plugin on a scenario simulated here (20 s static, 10 s random vibration at
// a gyro noise scale of 5, 20 s static): the properties of every noise model, the white noise
// integral over each phase, the simulator's flicker bank as states, and clear errors.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "noise_plugin_support.hpp"
#include "scenario_builders.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/scenario/scenario_writer.hpp"
#include "stochnav/sim/flicker_bank.hpp"

namespace stochnav::plugin {
namespace {

using testing::Case;
using testing::case_name;
using testing::kDegPerHour;
using testing::kDegPerRootHour;
using testing::context_for;
using testing::make;
using testing::NoiseModelProperties;
using testing::registry;

constexpr double kGyroN = 0.01 * kDegPerRootHour;                    // scheduled ARW
constexpr double kGyroB = 0.5 * kDegPerHour;                         // constant flicker
constexpr double kAccelN = 0.029 / 60.0;                             // m/s/sqrt(s)
constexpr double kGyroScale = 5.0, kAccelScale = 3.0;

// The folder of the scenario, made once per test binary (before any test runs) and removed at
// the end: the property cases name it in their params.
const std::filesystem::path& scenario_dir() {
  static const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("stochnav_oracle_test_" + std::to_string(std::random_device()()));
  return path;
}

class ScenarioEnvironment : public ::testing::Environment {
 public:
  void SetUp() override {
    ScenarioConfig config = stochnav::testing::table_config(
        {90.0 * stochnav::testing::kDeg, 0.0, 0.0},
        {stochnav::testing::static_phase(20.0), stochnav::testing::random_phase(10.0, 5.0, 8),
         stochnav::testing::static_phase(20.0)});
    config.vibration_table->phases[1].gyro_noise_scale = kGyroScale;
    config.vibration_table->phases[1].accel_noise_scale = kAccelScale;
    for (std::size_t i = 0; i < 3; ++i) {
      config.gyro.noise[i].terms = {BiasInstabilityTerm{kGyroB}};
      config.gyro.scheduled_noise[i].terms = {
          AngleRandomWalkTerm{kGyroN * (1.0 + 0.5 * static_cast<double>(i))}};
      config.accel.scheduled_noise[i].terms = {AngleRandomWalkTerm{kAccelN}};
    }
    ScenarioOutputOptions options;
    options.out_dir = scenario_dir();
    options.seed = 3;
    write_scenario_outputs(config, options);
  }
  void TearDown() override { std::filesystem::remove_all(scenario_dir()); }
};

[[maybe_unused]] const auto* const kScenario =
    ::testing::AddGlobalTestEnvironment(new ScenarioEnvironment);

// The phases change at 20 s and 30 s: composed steps (0.37 s, then 1.9 s) cross both.
const PropertyCheckOptions kAcrossPhaseChanges{.times_s = {3.0, 19.5, 29.5}};

INSTANTIATE_TEST_SUITE_P(
    Oracle, NoiseModelProperties,
    ::testing::Values(Case{"oracle", {{"scenario", scenario_dir().string()}}, SensorGroup::kGyro,
                           kAcrossPhaseChanges},
                      Case{"oracle", {{"scenario", scenario_dir().string()}}, SensorGroup::kAccel,
                           kAcrossPhaseChanges}),
    case_name);

// The flicker bank's components faster than the 0.1 s folding time, as white PSD (rad^2/s).
double folded_flicker_psd() {
  const FlickerBank bank = design_flicker_bank(kGyroB, 0.01, 50.0);
  double psd = 0.0;
  for (std::size_t k = 0; k < bank.tau_c_s.size(); ++k) {
    if (bank.tau_c_s[k] < 0.1) psd += 2.0 * bank.sigma[k] * bank.sigma[k] * bank.tau_c_s[k];
  }
  return psd;
}

std::shared_ptr<NoiseModelPlugin> oracle(SensorGroup group) {
  return make("oracle", {{"scenario", scenario_dir().string()}}, group);
}

TEST(OracleNoise, WhiteNoiseOverEachPhaseIsTheScheduledPsdTimesItsDuration) {
  const auto gyro = oracle(SensorGroup::kGyro);
  const auto accel = oracle(SensorGroup::kAccel);
  EXPECT_TRUE(gyro->time_varying());
  EXPECT_TRUE(accel->time_varying());
  struct Phase {
    double start, end, gyro_scale, accel_scale;
  };
  const double folded = folded_flicker_psd();
  EXPECT_GT(folded, 0.0);
  Eigen::MatrixXd q(3, 3), sum(3, 3);
  for (const Phase& phase :
       {Phase{0, 20, 1, 1}, Phase{20, 30, kGyroScale, kAccelScale}, Phase{30, 50, 1, 1}}) {
    const double duration = phase.end - phase.start;
    gyro->white_noise_covariance(phase.start, duration, q);
    for (int i = 0; i < 3; ++i) {
      const double n = kGyroN * (1.0 + 0.5 * i);
      const double expected = (n * n * phase.gyro_scale * phase.gyro_scale + folded) * duration;
      EXPECT_NEAR(q(i, i), expected, 1e-12 * expected) << "gyro axis " << i << " " << phase.start;
    }
    EXPECT_EQ(q(0, 1), 0.0);
    accel->white_noise_covariance(phase.start, duration, q);
    const double expected = kAccelN * kAccelN * phase.accel_scale * phase.accel_scale * duration;
    EXPECT_NEAR(q(2, 2), expected, 1e-12 * expected) << "accel " << phase.start;
    // The filter's 10 ms epochs add up to the same integral.
    sum.setZero();
    for (int k = 0; k < static_cast<int>(std::lround(duration * 100.0)); ++k) {
      gyro->white_noise_covariance(phase.start + k * 0.01, 0.01, q);
      sum += q;
    }
    const double n = kGyroN;
    const double expected_x = (n * n * phase.gyro_scale * phase.gyro_scale + folded) * duration;
    EXPECT_NEAR(sum(0, 0), expected_x, 1e-9 * expected_x) << "epochs " << phase.start;
  }
  // An interval across a boundary integrates both sides: 5 s static + 5 s vibration.
  gyro->white_noise_covariance(15.0, 10.0, q);
  const double expected = kGyroN * kGyroN * (5.0 + 5.0 * kGyroScale * kGyroScale) + folded * 10.0;
  EXPECT_NEAR(q(0, 0), expected, 1e-12 * expected);
}

TEST(OracleNoise, FlickerStatesAreTheSimulatorsBankAboveTheFoldingTime) {
  const auto gyro = oracle(SensorGroup::kGyro);
  const FlickerBank bank = design_flicker_bank(kGyroB, 0.01, 50.0);
  double kept_variance = 0.0;
  int kept = 0;
  for (std::size_t k = 0; k < bank.tau_c_s.size(); ++k) {
    if (bank.tau_c_s[k] >= 0.1) {
      kept_variance += bank.sigma[k] * bank.sigma[k];
      ++kept;
    }
  }
  ASSERT_EQ(gyro->augmented_size(), 3 * kept);
  Eigen::MatrixXd p0(3 * kept, 3 * kept);
  gyro->augmented_initial_covariance(p0);
  EXPECT_NEAR(p0.trace(), 3.0 * kept_variance, 1e-12 * p0.trace());
  // The accelerometer of this scenario has no coloured noise.
  EXPECT_EQ(oracle(SensorGroup::kAccel)->augmented_size(), 0);
}

TEST(OracleNoise, NeedsASimulatedScenarioAndCannotBeFitted) {
  try {
    make("oracle", nlohmann::json::object(), SensorGroup::kGyro);
    ADD_FAILURE() << "no error without a scenario";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("/noise/gyro/params/scenario"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(make("oracle", {{"scenario", "/nonexistent/folder"}}), ConfigError);
  NoiseModelContext context = context_for(SensorGroup::kGyro);
  context.scenario_dir = scenario_dir();
  const auto from_run =
      registry().create_noise_model("oracle", nlohmann::json::object(), context, "/p");
  EXPECT_TRUE(from_run->equals(*oracle(SensorGroup::kGyro)));
  CalibrationRecord record;
  record.rate_hz = 100.0;
  for (auto& axis : record.axes) axis.assign(1000, 0.0);
  EXPECT_THROW(registry().fit_noise_model("oracle", record, {}, context, "/p"), ConfigError);
}

}  // namespace
}  // namespace stochnav::plugin
