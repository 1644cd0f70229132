// MwdNavigator's accessors for an embedding host: every state block's estimate and covariance by
// name, and the covariance at the current epoch on request.

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

using testing::kRateHz;

std::shared_ptr<plugin::NoiseModelPlugin> gauss_markov(const plugin::PluginRegistry& registry,
                                                       plugin::SensorGroup group, double sigma) {
  const plugin::NoiseModelContext context{
      .group = group, .imu_rate_hz = kRateHz, .params_pointer = "/noise"};
  return registry.create_noise_model(
      "gauss_markov", {{"sigma", sigma}, {"tau_c", 60.0}}, context, "/noise");
}

struct Fixture {
  plugin::PluginRegistry registry{{plugin::bundled_plugin_dir()}};
  std::shared_ptr<plugin::NoiseModelPlugin> gyro =
      gauss_markov(registry, plugin::SensorGroup::kGyro, 0.5);
  std::shared_ptr<plugin::NoiseModelPlugin> accel =
      gauss_markov(registry, plugin::SensorGroup::kAccel, 1.0);
  NavState truth = testing::static_truth_state();
  StaticImu imu{truth,
                StaticImuErrors{.gyro_arw = 0.05 * kDeg / 60.0,
                                .accel_vrw = 5e-4,
                                .gyro_bias = Eigen::Vector3d(1e-6, -2e-6, 3e-6),
                                .accel_bias = Eigen::Vector3d(3e-4, 1e-4, -2e-4)},
                kRateHz, 31};
  NoisyStaticAid aid{truth, 0.05, 0.002, 32};

  FilterOptions options(double covariance_interval_s) const {
    FilterOptions result;
    result.covariance_interval_s = covariance_interval_s;
    result.gyro_scale_factor_sigma.setConstant(100e-6);
    result.accel_scale_factor_sigma.setConstant(100e-6);
    return result;
  }
};

TEST(NavigatorStateBlocks, EveryBlockByNameMatchesTheLayoutAndTheCovariance) {
  Fixture f;
  MwdNavigator navigator(f.truth, *f.gyro, *f.accel, {&f.aid}, f.options(0.1));
  for (int k = 0; k < 30 * static_cast<int>(kRateHz); ++k) navigator.step(f.imu.next());
  ASSERT_TRUE(navigator.health().ok());
  const Eigen::MatrixXd& p = navigator.covariance();
  int sensor_states = 0;
  for (const plugin::StateBlock& block : navigator.layout().blocks()) {
    SCOPED_TRACE(block.name);
    EXPECT_EQ(navigator.block_covariance(block.name),
              p.block(block.offset, block.offset, block.size, block.size));
    if (block.name == "position" || block.name == "velocity" || block.name == "attitude") {
      EXPECT_THROW((void)navigator.block_estimate(block.name), std::invalid_argument);
      continue;
    }
    EXPECT_EQ(navigator.block_estimate(block.name).size(), block.size);
    sensor_states += block.size;
  }
  EXPECT_EQ(sensor_states, 6 + 6 + 6) << "biases, scale factors and two Gauss-Markov blocks";
  EXPECT_EQ(navigator.block_estimate("gyro_bias"), Eigen::VectorXd(navigator.gyro_bias_b()));
  EXPECT_EQ(navigator.block_estimate("accel_scale_factor"),
            Eigen::VectorXd(navigator.accel_scale_factor()));
  // The Gauss-Markov states have learnt something from the aid (not the zero they started at).
  EXPECT_GT(navigator.block_estimate("gyro.gauss_markov").norm(), 0.0);
  try {
    (void)navigator.block_covariance("gyro.white");
    FAIL() << "an unknown block must throw";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("gyro.gauss_markov"), std::string::npos)
        << "the message lists the blocks there are: " << error.what();
  }
}

// covariance_now() propagates the open interval at once: after 0.37 s of a 1-s interval it is
// exactly the covariance of a twin whose interval is 0.37 s (the same epochs, one propagation),
// and it has grown from the stale covariance().
TEST(NavigatorStateBlocks, CovarianceNowPropagatesTheOpenInterval) {
  Fixture a, b;
  MwdNavigator asked(a.truth, *a.gyro, *a.accel, {}, a.options(1.0));
  MwdNavigator twin(b.truth, *b.gyro, *b.accel, {}, b.options(0.37));
  for (int k = 0; k < 37; ++k) {
    asked.step(a.imu.next());
    twin.step(b.imu.next());
  }
  const Eigen::MatrixXd stale = asked.covariance();
  const Eigen::MatrixXd now = asked.covariance_now();
  EXPECT_GT(now(plugin::core_state::kAttitude + 2, plugin::core_state::kAttitude + 2),
            stale(plugin::core_state::kAttitude + 2, plugin::core_state::kAttitude + 2));
  EXPECT_LE((now - twin.covariance()).cwiseAbs().maxCoeff(),
            1e-12 * twin.covariance().cwiseAbs().maxCoeff());
  // Asked again at the same epoch: nothing left to propagate.
  EXPECT_EQ(asked.covariance_now(), now);
}

}  // namespace
}  // namespace stochnav
