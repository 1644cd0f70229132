// The navigator gives the same state and covariance whether its covariance products exploit
// the structure of the transition or are dense (the code path of earlier versions,
// FilterOptions::structured_covariance = false): with ~100 augmented states (the `augmented`
// plugin: a flicker bank, a Gauss-Markov state, a ramp and an oscillator per axis: by blocks),
// and with the layouts of the fixed-size kernels (filter/core_covariance.hpp): scale-factor
// states, first-order Gauss-Markov states, both. And a navigator split from another
// (MwdNavigator::split) continues as it.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "static_truth.hpp"
#include "stochnav/filter/core_correction.hpp"
#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/plugin/plugin_registry.hpp"

namespace stochnav {
namespace {

using testing::kDeg;
using testing::NoisyStaticAid;
using testing::StaticImu;
using testing::StaticImuErrors;
using testing::TimeSeededStaticAid;

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

// MwdNavigator::split: a copy on plugins of its own, with no correction and the same P, is the
// navigator: stepped on, both give the same state, P and aid intervals to the last bit. Split in
// the middle of a covariance interval (the accumulated fast inputs and noise carried over) and
// of an interval aid's interval, with dense and structured augmented states and scale factors.
// A correction moves the copy by it; a copy onto other models is refused.
TEST(MwdNavigator, ASplitCopyContinuesAsTheNavigatorToTheLastBit) {
  const plugin::PluginRegistry registry({plugin::bundled_plugin_dir()});
  const NavState truth = testing::static_truth_state();
  const StaticImuErrors errors{.gyro_arw = 0.05 * kDeg / 60.0,
                               .accel_vrw = 5e-4,
                               .gyro_bias = Eigen::Vector3d(1e-6, -2e-6, 3e-6),
                               .accel_bias = Eigen::Vector3d(3e-4, 1e-4, -2e-4)};
  for (const bool structured : {false, true}) {
    SCOPED_TRACE(structured ? "structured" : "dense");
    FilterOptions options;
    options.structured_covariance = structured;
    options.gyro_scale_factor_sigma.setConstant(100e-6);
    options.accel_scale_factor_sigma.setConstant(100e-6);
    const NoiseModels models = flicker_banks(registry);
    TimeSeededStaticAid fix(truth);
    testing::IntervalRecorder recorder(7, 3);
    MwdNavigator navigator(truth, *models.gyro, *models.accel, {&fix, &recorder}, options);
    StaticImu imu(truth, errors, kImuRateHz, 21);
    for (int k = 0; k < 1234; ++k) navigator.step(imu.next());  // 0.04 s into an interval

    // A copy of a copy, the first gone with its plugins before the second steps (nothing may
    // point into it: the sanitizer stage).
    const int n = static_cast<int>(navigator.covariance().rows());
    const NoiseModels own = flicker_banks(registry);
    TimeSeededStaticAid own_fix(truth);
    testing::IntervalRecorder own_recorder(7, 3);
    std::unique_ptr<MwdNavigator> copy;
    {
      const NoiseModels first = flicker_banks(registry);
      TimeSeededStaticAid first_fix(truth);
      testing::IntervalRecorder first_recorder(7, 3);
      const std::unique_ptr<MwdNavigator> first_copy =
          navigator.split(*first.gyro, *first.accel, {&first_fix, &first_recorder},
                          Eigen::VectorXd::Zero(n), navigator.covariance(), false);
      copy = first_copy->split(*own.gyro, *own.accel, {&own_fix, &own_recorder},
                               Eigen::VectorXd::Zero(n), first_copy->covariance(), false);
    }
    const std::size_t recorded = recorder.intervals.size();
    for (int k = 0; k < 1000; ++k) {
      const ImuIncrement increment = imu.next();
      navigator.step(increment);
      copy->step(increment);
    }
    EXPECT_EQ(copy->state().q_nb.coeffs(), navigator.state().q_nb.coeffs());
    EXPECT_EQ(copy->state().v_n, navigator.state().v_n);
    EXPECT_EQ(copy->state().latitude_rad, navigator.state().latitude_rad);
    EXPECT_EQ(copy->state().height_m, navigator.state().height_m);
    EXPECT_EQ(copy->gyro_bias_b(), navigator.gyro_bias_b());
    EXPECT_EQ(copy->accel_scale_factor(), navigator.accel_scale_factor());
    EXPECT_EQ(copy->block_estimate("gyro.augmented"), navigator.block_estimate("gyro.augmented"));
    EXPECT_EQ(copy->covariance(), navigator.covariance());
    ASSERT_EQ(own_recorder.intervals.size(), recorder.intervals.size() - recorded);
    ASSERT_GT(own_recorder.intervals.size(), 100u);
    // The first interval after the split began before it.
    EXPECT_EQ(own_recorder.intervals.front().duration_s, recorder.intervals[recorded].duration_s);
    for (std::size_t i = 0; i < own_recorder.intervals.size(); ++i) {
      EXPECT_EQ(own_recorder.intervals[i].mean_v_n, recorder.intervals[recorded + i].mean_v_n);
      EXPECT_EQ(own_recorder.intervals[i].mean_velocity_error_map,
                recorder.intervals[recorded + i].mean_velocity_error_map);
    }

    // A correction of 0.1 rad in heading turns the copy by it.
    Eigen::VectorXd correction = Eigen::VectorXd::Zero(n);
    correction(plugin::core_state::kAttitude + 2) = 0.1;
    const NoiseModels turned_models = flicker_banks(registry);
    TimeSeededStaticAid turned_fix(truth);
    testing::IntervalRecorder turned_recorder(7, 3);
    const std::unique_ptr<MwdNavigator> turned =
        navigator.split(*turned_models.gyro, *turned_models.accel,
                        {&turned_fix, &turned_recorder}, correction, navigator.covariance(),
                        false);
    const CoreEstimate from{navigator.state(), navigator.accel_bias_b(), navigator.gyro_bias_b()};
    const CoreEstimate to{turned->state(), turned->accel_bias_b(), turned->gyro_bias_b()};
    EXPECT_NEAR(std::abs(core_difference(to, from)(plugin::core_state::kAttitude + 2)), 0.1,
                1e-12);

    // Other models lay out another error state.
    const NoiseModels white = white_with_bias_walk(registry);
    EXPECT_THROW((void)navigator.split(*white.gyro, *white.accel, {&own_fix, &own_recorder},
                                       Eigen::VectorXd::Zero(n), navigator.covariance(), false),
                 std::invalid_argument);
  }
}

}  // namespace
}  // namespace stochnav
