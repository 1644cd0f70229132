// The navigator gives the same state and covariance whether its covariance products exploit
// the structure of the transition or are dense (the code path of earlier versions,
// FilterOptions::structured_covariance = false): with ~100 augmented states (the `augmented`
// plugin: a flicker bank, a Gauss-Markov state, a ramp and an oscillator per axis: by blocks),
// and with the layouts of the fixed-size kernels (filter/core_covariance.hpp): scale-factor
// states, first-order Gauss-Markov states, both.

#include <gtest/gtest.h>

#include "static_truth.hpp"
#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/plugin/plugin_registry.hpp"

namespace stochnav {
namespace {

using testing::kDeg;
using testing::NoisyStaticAid;
using testing::StaticImu;
using testing::StaticImuErrors;

constexpr double kImuRateHz = 100.0;

std::shared_ptr<plugin::NoiseModelPlugin> augmented(const plugin::PluginRegistry& registry,
                                                    plugin::SensorGroup group,
                                                    const nlohmann::json& model) {
  const plugin::NoiseModelContext context{
      .group = group, .imu_rate_hz = kImuRateHz, .params_pointer = "/noise"};
  return registry.create_noise_model(
      "augmented", {{"model", model}, {"flicker_band_max_s", 36.0 * 3600.0}}, context, "/noise");
}

struct NavigatorRun {
  NavState state;
  Eigen::Vector3d gyro_bias_b, accel_bias_b;
  Eigen::Vector3d gyro_scale_factor, accel_scale_factor;
  Eigen::MatrixXd covariance;
  int augmented_size = 0;
  bool scale_factor_states = false;
};

struct NoiseModels {
  std::shared_ptr<plugin::NoiseModelPlugin> gyro, accel;
};

// Gyro: 0.5 deg/h flicker floor with the simulator's bank (2 per decade up to 36 h), a
// Gauss-Markov state and a ramp (2 x 2 block) per axis. Accelerometer: a flicker bank and an
// oscillator (rotation, 2 x 2 block) per axis.
NoiseModels flicker_banks(const plugin::PluginRegistry& registry) {
  return {augmented(registry, plugin::SensorGroup::kGyro,
                    {{"units", "deg/h"},
                     {"rate_hz", kImuRateHz},
                     {"terms",
                      {{{"type", "angle_random_walk"}, {"N", 0.05}},
                       {{"type", "bias_instability"}, {"B", 0.5}},
                       {{"type", "gauss_markov"}, {"sigma", 0.5}, {"tau_c", 30}},
                       {{"type", "rate_ramp"}, {"R", 0.1}}}}}),
          augmented(registry, plugin::SensorGroup::kAccel,
                    {{"units", "m/s^2"},
                     {"rate_hz", kImuRateHz},
                     {"terms",
                      {{{"type", "angle_random_walk"}, {"N", 5e-4}},
                       {{"type", "bias_instability"}, {"B", 2e-4}},
                       {{"type", "sinusoid"}, {"amplitude", 1e-4}, {"frequency_hz", 0.02}}}}})};
}

plugin::NoiseModelContext noise_context(plugin::SensorGroup group) {
  return {.group = group, .imu_rate_hz = kImuRateHz, .params_pointer = "/noise"};
}

// White noise and a bias random walk: the 15 core states (21 with the scale factors).
NoiseModels white_with_bias_walk(const plugin::PluginRegistry& registry) {
  return {registry.create_noise_model("white", {{"N", 0.05}, {"K", 0.05}},
                                      noise_context(plugin::SensorGroup::kGyro), "/noise"),
          registry.create_noise_model("white", {{"N", 0.03}, {"K", 0.5}},
                                      noise_context(plugin::SensorGroup::kAccel), "/noise")};
}

// A first-order Gauss-Markov error per axis (3 augmented states, diagonal Phi) on each sensor.
NoiseModels gauss_markov(const plugin::PluginRegistry& registry) {
  return {registry.create_noise_model("gauss_markov",
                                      {{"sigma", 0.5}, {"tau_c", 300.0}, {"N", 0.05}},
                                      noise_context(plugin::SensorGroup::kGyro), "/noise"),
          registry.create_noise_model("gauss_markov",
                                      {{"sigma", 0.7}, {"tau_c", 100.0}, {"N", 0.03}},
                                      noise_context(plugin::SensorGroup::kAccel), "/noise")};
}

// A static tool for `seconds` at 100 Hz with 1 Hz position and zero-velocity updates (so the
// run goes through the updates and the feedback of every state); scale-factor states when
// `scale_factor_sigma` > 0.
NavigatorRun run(const NoiseModels& models, bool structured, double scale_factor_sigma,
                 int seconds) {
  FilterOptions options;
  options.structured_covariance = structured;
  options.gyro_scale_factor_sigma.setConstant(scale_factor_sigma);
  options.accel_scale_factor_sigma.setConstant(scale_factor_sigma);
  const NavState truth = testing::static_truth_state();
  StaticImuErrors errors{.gyro_arw = 0.05 * kDeg / 60.0,
                         .accel_vrw = 5e-4,
                         .gyro_bias = Eigen::Vector3d(1e-6, -2e-6, 3e-6),
                         .accel_bias = Eigen::Vector3d(3e-4, 1e-4, -2e-4)};
  StaticImu imu(truth, errors, kImuRateHz, 21);
  NoisyStaticAid aid(truth, 0.05, 0.002, 22);
  MwdNavigator navigator(truth, *models.gyro, *models.accel, {&aid}, options);
  for (int k = 0; k < seconds * static_cast<int>(kImuRateHz); ++k) navigator.step(imu.next());
  EXPECT_TRUE(navigator.health().ok());
  return {navigator.state(),
          navigator.gyro_bias_b(),
          navigator.accel_bias_b(),
          navigator.gyro_scale_factor(),
          navigator.accel_scale_factor(),
          navigator.covariance(),
          models.gyro->augmented_size() + models.accel->augmented_size(),
          scale_factor_sigma > 0.0};
}

// The structured run's P and state against the dense run's, both in units of the dense run's
// standard deviations (a relative P difference would be meaningless for the near-zero
// correlations): P below `tolerance`, the state below `state_tolerance`.
void expect_same_filter(const NavigatorRun& structured, const NavigatorRun& dense,
                        double tolerance, double state_tolerance) {
  ASSERT_EQ(structured.covariance.rows(), dense.covariance.rows());
  const Eigen::VectorXd sigma_s = structured.covariance.diagonal().cwiseSqrt();
  const Eigen::VectorXd sigma_d = dense.covariance.diagonal().cwiseSqrt();
  const Eigen::MatrixXd correlation_difference = sigma_s.cwiseInverse().asDiagonal() *
                                                 (structured.covariance - dense.covariance) *
                                                 sigma_s.cwiseInverse().asDiagonal();
  EXPECT_LT(correlation_difference.cwiseAbs().maxCoeff(), tolerance)
      << "difference of P, in units of the standard deviations";
  EXPECT_LT((sigma_s - sigma_d).cwiseQuotient(sigma_d).cwiseAbs().maxCoeff(), tolerance);

  // State differences against what the filter knows about it (its standard deviations).
  const EarthRadii radii = earth_radii(dense.state.latitude_rad);
  const double north_m = (structured.state.latitude_rad - dense.state.latitude_rad) *
                         (radii.meridian_m + dense.state.height_m);
  EXPECT_LT(std::abs(north_m), state_tolerance * sigma_d(1));
  EXPECT_LT(std::abs(structured.state.height_m - dense.state.height_m),
            state_tolerance * sigma_d(2));
  EXPECT_LT((structured.state.v_n - dense.state.v_n).norm(), state_tolerance * sigma_d(4));
  EXPECT_LT(structured.state.q_nb.angularDistance(dense.state.q_nb),
            state_tolerance * sigma_d(6));
  EXPECT_LT((structured.accel_bias_b - dense.accel_bias_b).norm(), state_tolerance * sigma_d(9));
  EXPECT_LT((structured.gyro_bias_b - dense.gyro_bias_b).norm(), state_tolerance * sigma_d(12));
  if (dense.scale_factor_states) {  // after the core: gyro, then accelerometer
    EXPECT_LT((structured.gyro_scale_factor - dense.gyro_scale_factor).norm(),
              state_tolerance * sigma_d(15));
    EXPECT_LT((structured.accel_scale_factor - dense.accel_scale_factor).norm(),
              state_tolerance * sigma_d(18));
  }
}

// Rounding only: both paths do the same arithmetic in another order (and the update in the
// expanded Joseph form), each step contributing ~1e-16 relative, and the filter forgets old
// errors rather than amplifying them: after 1200 propagations and 120 updates the paths
// differ by 2.5e-12 (measured), far below 1e-10.
constexpr double kRoundingTolerance = 1e-10;
// The state over the 10-minute runs below: the attitude, known to 1e-4 rad, is held in a
// quaternion whose components round at 1e-16, and 600 corrections leave the paths' attitudes
// 1.3e-14 to 1.9e-14 rad apart (measured), 1.2e-10 to 1.7e-10 of a sigma: 1e-9 of a sigma.
constexpr double kStateRoundingTolerance = 1e-9;

TEST(StructuredNavigator, MatchesTheDensePathWithAugmentedStates) {
  constexpr int kSeconds = 120;
  const plugin::PluginRegistry registry({plugin::bundled_plugin_dir()});
  const NoiseModels models = flicker_banks(registry);
  const NavigatorRun structured = run(models, true, 0.0, kSeconds);
  const NavigatorRun dense = run(models, false, 0.0, kSeconds);
  ASSERT_GE(structured.augmented_size, 90) << "the case is about ~100 augmented states";
  ASSERT_EQ(structured.covariance.rows(), 15 + structured.augmented_size);
  expect_same_filter(structured, dense, kRoundingTolerance, kRoundingTolerance);
}

// The fixed-size kernels (filter/core_covariance.hpp) of the layouts KF-GINS-like filters use:
// the 21 states of the core and both scale-factor blocks; the core and 6 first-order
// Gauss-Markov states; both (27). The same tolerance as above over 10 minutes (6000
// propagations, 600 updates).
TEST(StructuredNavigator, MatchesTheDensePathWithScaleFactorStates) {
  constexpr int kSeconds = 600;
  const plugin::PluginRegistry registry({plugin::bundled_plugin_dir()});
  const NoiseModels models = white_with_bias_walk(registry);
  const NavigatorRun structured = run(models, true, 100e-6, kSeconds);
  const NavigatorRun dense = run(models, false, 100e-6, kSeconds);
  ASSERT_EQ(structured.covariance.rows(), 21);
  expect_same_filter(structured, dense, kRoundingTolerance, kStateRoundingTolerance);
}

TEST(StructuredNavigator, MatchesTheDensePathWithGaussMarkovStates) {
  constexpr int kSeconds = 600;
  const plugin::PluginRegistry registry({plugin::bundled_plugin_dir()});
  const NoiseModels models = gauss_markov(registry);
  const NavigatorRun structured = run(models, true, 0.0, kSeconds);
  const NavigatorRun dense = run(models, false, 0.0, kSeconds);
  ASSERT_EQ(structured.covariance.rows(), 21);
  expect_same_filter(structured, dense, kRoundingTolerance, kStateRoundingTolerance);
}

TEST(StructuredNavigator, MatchesTheDensePathWithScaleFactorAndGaussMarkovStates) {
  constexpr int kSeconds = 600;
  const plugin::PluginRegistry registry({plugin::bundled_plugin_dir()});
  const NoiseModels models = gauss_markov(registry);
  const NavigatorRun structured = run(models, true, 100e-6, kSeconds);
  const NavigatorRun dense = run(models, false, 100e-6, kSeconds);
  ASSERT_EQ(structured.covariance.rows(), 27);
  expect_same_filter(structured, dense, kRoundingTolerance, kStateRoundingTolerance);
}

}  // namespace
}  // namespace stochnav
