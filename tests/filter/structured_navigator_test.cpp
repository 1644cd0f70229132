// The navigator with ~100 augmented states (the `augmented` plugin: a flicker bank, a
// Gauss-Markov state, a ramp and an oscillator per axis) gives the same state and covariance
// whether its covariance products exploit the block structure or are dense (the code path of
// earlier versions, FilterOptions::structured_covariance = false).

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
  Eigen::MatrixXd covariance;
  int augmented_size = 0;
};

NavigatorRun run(bool structured, int seconds) {
  const plugin::PluginRegistry registry({plugin::bundled_plugin_dir()});
  // Gyro: 0.5 deg/h flicker floor with the simulator's bank (2 per decade up to 36 h), a
  // Gauss-Markov state and a ramp (2 x 2 block) per axis.
  const auto gyro = augmented(registry, plugin::SensorGroup::kGyro,
                              {{"units", "deg/h"},
                               {"rate_hz", kImuRateHz},
                               {"terms",
                                {{{"type", "angle_random_walk"}, {"N", 0.05}},
                                 {{"type", "bias_instability"}, {"B", 0.5}},
                                 {{"type", "gauss_markov"}, {"sigma", 0.5}, {"tau_c", 30}},
                                 {{"type", "rate_ramp"}, {"R", 0.1}}}}});
  // Accelerometer: a flicker bank and an oscillator (rotation, 2 x 2 block) per axis.
  const auto accel =
      augmented(registry, plugin::SensorGroup::kAccel,
                {{"units", "m/s^2"},
                 {"rate_hz", kImuRateHz},
                 {"terms",
                  {{{"type", "angle_random_walk"}, {"N", 5e-4}},
                   {{"type", "bias_instability"}, {"B", 2e-4}},
                   {{"type", "sinusoid"}, {"amplitude", 1e-4}, {"frequency_hz", 0.02}}}}});
  FilterOptions options;
  options.structured_covariance = structured;
  const NavState truth = testing::static_truth_state();
  StaticImuErrors errors{.gyro_arw = 0.05 * kDeg / 60.0,
                         .accel_vrw = 5e-4,
                         .gyro_bias = Eigen::Vector3d(1e-6, -2e-6, 3e-6),
                         .accel_bias = Eigen::Vector3d(3e-4, 1e-4, -2e-4)};
  StaticImu imu(truth, errors, kImuRateHz, 21);
  NoisyStaticAid aid(truth, 0.05, 0.002, 22);
  MwdNavigator navigator(truth, *gyro, *accel, {&aid}, options);
  for (int k = 0; k < seconds * static_cast<int>(kImuRateHz); ++k) navigator.step(imu.next());
  EXPECT_TRUE(navigator.health().ok());
  return {navigator.state(), navigator.gyro_bias_b(), navigator.accel_bias_b(),
          navigator.covariance(), gyro->augmented_size() + accel->augmented_size()};
}

TEST(StructuredNavigator, MatchesTheDensePathWithAugmentedStates) {
  constexpr int kSeconds = 120;
  const NavigatorRun structured = run(true, kSeconds);
  const NavigatorRun dense = run(false, kSeconds);
  ASSERT_GE(structured.augmented_size, 90) << "the case is about ~100 augmented states";
  ASSERT_EQ(structured.covariance.rows(), 15 + structured.augmented_size);

  // Rounding only: both paths do the same arithmetic in another order (and the update in the
  // expanded Joseph form), each step contributing ~1e-16 relative, and the filter forgets old
  // errors rather than amplifying them: after 1200 propagations and 120 updates the paths
  // differ by 2.5e-12 (measured), far below 1e-10.
  const Eigen::VectorXd sigma_s = structured.covariance.diagonal().cwiseSqrt();
  const Eigen::VectorXd sigma_d = dense.covariance.diagonal().cwiseSqrt();
  const Eigen::MatrixXd correlation_difference = sigma_s.cwiseInverse().asDiagonal() *
                                                 (structured.covariance - dense.covariance) *
                                                 sigma_s.cwiseInverse().asDiagonal();
  EXPECT_LT(correlation_difference.cwiseAbs().maxCoeff(), 1e-10)
      << "difference of P, in units of the standard deviations";
  EXPECT_LT((sigma_s - sigma_d).cwiseQuotient(sigma_d).cwiseAbs().maxCoeff(), 1e-10);

  // State differences against what the filter knows about it (its standard deviations).
  const EarthRadii radii = earth_radii(dense.state.latitude_rad);
  const double north_m = (structured.state.latitude_rad - dense.state.latitude_rad) *
                         (radii.meridian_m + dense.state.height_m);
  EXPECT_LT(std::abs(north_m), 1e-10 * sigma_d(1));
  EXPECT_LT(std::abs(structured.state.height_m - dense.state.height_m), 1e-10 * sigma_d(2));
  EXPECT_LT((structured.state.v_n - dense.state.v_n).norm(), 1e-10 * sigma_d(4));
  EXPECT_LT(structured.state.q_nb.angularDistance(dense.state.q_nb), 1e-10 * sigma_d(6));
  EXPECT_LT((structured.accel_bias_b - dense.accel_bias_b).norm(), 1e-10 * sigma_d(9));
  EXPECT_LT((structured.gyro_bias_b - dense.gyro_bias_b).norm(), 1e-10 * sigma_d(12));
}

}  // namespace
}  // namespace stochnav
