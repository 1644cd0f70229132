// The noise plugins "ar" and "arma" through the runtime: the noise-model properties on the grid
// of their block interval, params round trips, errors naming the JSON pointer, and fits that
// recover the block-averaged process of a simulated calibration record.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <string>

#include "noise_plugin_support.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/sim/noise_generator.hpp"

namespace stochnav::plugin {
namespace {

using testing::Case;
using testing::case_name;
using testing::context_for;
using testing::make;
using testing::NoiseModelProperties;
using testing::on_grid;
using testing::registry;

const nlohmann::json kArParams = {{"axes",
                                   {{{"ar", {0.9}}, {"sigma", 1.0}},
                                    {{"ar", {0.75, -0.5}}, {"sigma", 2.0}},
                                    {{"ar", {0.5, 0.2, 0.1}}, {"sigma", 0.5}}}},
                                  {"K", 0.01}};

const nlohmann::json kArmaParams = {
    {"interval_s", 0.2},
    {"axes",
     {{{"ar", {0.8}}, {"ma", {0.4}}, {"sigma", 1.0}},
      {{"ar", nlohmann::json::array()}, {"ma", {0.3, -0.2}}, {"sigma", 0.3}},
      {{"ar", {1.2, -0.5}}, {"sigma", 2.0}}}},
    {"K", {0.0, 0.02, 0.01}}};

// The plugins' transitions are defined on the grid of their interval (0.1 s, 0.2 s); every
// case also has a rate random walk so that steps shorter than half an interval (which move no
// block) still add noise, as the fixture's positivity check asks.
INSTANTIATE_TEST_SUITE_P(
    ArArma, NoiseModelProperties,
    ::testing::Values(Case{"ar", kArParams, SensorGroup::kGyro, on_grid(0.3, 1.9, 0.1)},
                      Case{"arma", kArmaParams, SensorGroup::kAccel, on_grid(0.4, 1.8, 0.2)},
                      Case{"arma", kArmaParams, SensorGroup::kGyro, on_grid(0.2, 0.2, 0.2)}),
    case_name);

TEST(ArNoise, StatesFollowTheBlockModel) {
  const auto model = make("ar", kArParams);
  ASSERT_EQ(model->augmented_size(), 1 + 2 + 3);
  EXPECT_FALSE(model->time_varying());
  Eigen::MatrixXd map(3, 6), p0(6, 6), phi(6, 6), q(6, 6);
  model->augmented_sensor_map(map);
  EXPECT_EQ(map(0, 0), 1.0);
  EXPECT_EQ(map(1, 1), 1.0);
  EXPECT_EQ(map(2, 3), 1.0);
  EXPECT_EQ(map.sum(), 3.0);
  // x axis AR(1): stationary variance sigma^2 / (1 - phi^2), sigma in deg/h.
  const double deg_h = std::numbers::pi / 180.0 / 3600.0;
  model->augmented_initial_covariance(p0);
  EXPECT_NEAR(p0(0, 0), deg_h * deg_h / (1.0 - 0.81), 1e-12 * p0(0, 0));
  // 0.3 s = 3 blocks: phi^3; a step that is not a multiple rounds to whole blocks.
  model->augmented_transition(0.0, 0.3, phi, q);
  EXPECT_NEAR(phi(0, 0), 0.729, 1e-15);
  EXPECT_NEAR(q(0, 0), deg_h * deg_h * (1.0 + 0.81 + 0.6561), 1e-12 * q(0, 0));
  Eigen::MatrixXd phi_rounded(6, 6), q_rounded(6, 6);
  model->augmented_transition(0.0, 0.29, phi_rounded, q_rounded);
  EXPECT_EQ(phi_rounded, phi);
  Eigen::Matrix3d q_white;
  model->white_noise_covariance(0.0, 0.01, q_white);
  EXPECT_EQ(q_white.cwiseAbs().maxCoeff(), 0.0);
}

TEST(ArNoise, ParamsRoundTripAndDescribeNamesTheOrders) {
  const auto model = make("arma", kArmaParams, SensorGroup::kAccel);
  const auto params = model->params();
  EXPECT_EQ(params["interval_s"], 0.2);
  EXPECT_EQ(params["axes"][1]["ma"], (nlohmann::json{0.3, -0.2}));
  EXPECT_TRUE(model->equals(*make("arma", params, SensorGroup::kAccel), 1e-12));
  EXPECT_FALSE(model->equals(*make("arma", params, SensorGroup::kGyro), 1e-6));
  auto changed = params;
  changed["axes"][0]["ma"] = {0.41};
  EXPECT_FALSE(model->equals(*make("arma", changed, SensorGroup::kAccel), 1e-6));
  EXPECT_NE(model->describe().find("ARMA(0, 2)"), std::string::npos) << model->describe();
  // Same coefficients under the other type are a different model.
  const auto ar = make("ar", kArParams);
  auto as_arma = ar->params();
  for (auto& axis : as_arma["axes"]) axis["ma"] = nlohmann::json::array();
  EXPECT_FALSE(ar->equals(*make("arma", as_arma), 1e-6));
}

std::string message(const std::string& type, const nlohmann::json& params) {
  try {
    make(type, params);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(accepted)";
}

TEST(ArNoise, BadParamsNameTheJsonPointer) {
  auto nonstationary = kArParams;
  nonstationary["axes"][1]["ar"] = {0.5, 0.6};
  EXPECT_EQ(
      message("ar", nonstationary)
          .rfind("/noise/gyro/params/axes/1/ar: found [0.5,0.6]; expected a stationary AR part", 0),
      0u)
      << message("ar", nonstationary);
  auto odd_interval = kArParams;
  odd_interval["interval_s"] = 0.105;
  EXPECT_EQ(message("ar", odd_interval)
                .rfind("/noise/gyro/params/interval_s: found 0.105; expected a whole multiple", 0),
            0u)
      << message("ar", odd_interval);
  auto with_ma = kArParams;
  with_ma["axes"][2]["ma"] = {0.1};
  EXPECT_EQ(message("ar", with_ma).rfind("/noise/gyro/params/axes/2/ma: unknown key", 0), 0u)
      << message("ar", with_ma);
  auto empty_ar = kArParams;
  empty_ar["axes"][0]["ar"] = nlohmann::json::array();
  EXPECT_EQ(message("ar", empty_ar).rfind("/noise/gyro/params/axes/0/ar: found []", 0), 0u);
  auto bad_sigma = kArmaParams;
  bad_sigma["axes"][0]["sigma"] = -1;
  EXPECT_NE(message("arma", bad_sigma).find("/noise/gyro/params/axes/0/sigma: found -1"),
            std::string::npos);
  EXPECT_EQ(message("arma", {{"axes", {1, 2}}}).rfind("/noise/gyro/params/axes: found [1,2]", 0),
            0u);
  EXPECT_EQ(message("arma", nlohmann::json::object()).rfind("/noise/gyro/params/axes: missing", 0),
            0u);
  auto bad_coefficient = kArmaParams;
  bad_coefficient["axes"][0]["ma"] = {"x"};
  EXPECT_EQ(
      message("arma", bad_coefficient).rfind("/noise/gyro/params/axes/0/ma/0: found \"x\"", 0), 0u);
}

// Gauss-Markov (sigma, tau) + angle random walk N, 100 Hz, three axes with their own seeds.
struct SimulatedGyro {
  double sigma = 10.0 * std::numbers::pi / 180.0 / 3600.0;  // rad/s (10 deg/h)
  double tau = 2.0;                                         // s
  double n = 0.05 * std::numbers::pi / 180.0 / 60.0;        // rad/sqrt(s) (0.05 deg/sqrt(h))
  double rate_hz = 100.0;

  CalibrationRecord record(double duration_s, std::uint64_t seed) const {
    const NoiseModel model{
        Unit::kRadPerSecond, rate_hz, {AngleRandomWalkTerm{n}, GaussMarkovTerm{sigma, tau}}};
    CalibrationRecord record;
    record.group = SensorGroup::kGyro;
    record.rate_hz = rate_hz;
    record.source = "simulated";
    for (std::size_t axis = 0; axis < 3; ++axis) {
      record.axes[axis] = simulate_noise(model, duration_s, rate_hz, seed + axis);
    }
    return record;
  }
  // Closed forms of the mean over blocks of T: Gauss-Markov part
  // 2 s^2 (tau/T)^2 (T/tau - 1 + a) at lag 0 and s^2 (tau/T)^2 (1 - a)^2 at lag 1 with
  // a = exp(-T/tau); white part N^2 / T at lag 0 only.
  double block_variance(double interval) const {
    const double ratio = tau / interval, a = std::exp(-interval / tau);
    return 2.0 * sigma * sigma * ratio * ratio * (1.0 / ratio - 1.0 + a) + n * n / interval;
  }
  double block_lag1_covariance(double interval) const {
    const double ratio = tau / interval, a = std::exp(-interval / tau);
    return sigma * sigma * ratio * ratio * (1.0 - a) * (1.0 - a);
  }
};

// Lag-0 and lag-1 autocovariance of the block-mean sensor error as the filter sees the model:
// M P0 M^T and M Phi(T) P0 M^T.
std::pair<Eigen::Vector3d, Eigen::Vector3d> model_block_covariances(const NoiseModelPlugin& model,
                                                                    double interval) {
  const int n = model.augmented_size();
  Eigen::MatrixXd map(3, n), p0(n, n), phi(n, n), q(n, n);
  model.augmented_sensor_map(map);
  model.augmented_initial_covariance(p0);
  model.augmented_transition(0.0, interval, phi, q);
  return {(map * p0 * map.transpose()).diagonal(), (map * phi * p0 * map.transpose()).diagonal()};
}

class BlockProcessFit : public ::testing::TestWithParam<std::string> {};

TEST_P(BlockProcessFit, RecoversTheVarianceAndLagOneCorrelationOfTheBlockMean) {
  const SimulatedGyro truth;
  const double interval = 0.1;
  const auto record = truth.record(3000.0, 41);
  const auto model = registry().fit_noise_model(GetParam(), record, {{"K", 0.001}},
                                                context_for(SensorGroup::kGyro), "/noise/gyro");
  const double variance = truth.block_variance(interval);
  const double correlation = truth.block_lag1_covariance(interval) / variance;
  const auto [lag0, lag1] = model_block_covariances(*model, interval);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(lag0(axis), variance, 0.15 * variance) << model->describe();
    EXPECT_NEAR(lag1(axis) / lag0(axis), correlation, 0.05) << model->describe();
  }
  if (GetParam() == "arma") {
    // The block mean of a Gauss-Markov process plus white noise is an ARMA(1, 1) whose AR root
    // is exp(-T / tau): BIC should find it.
    const nlohmann::json params = model->params();
    for (const auto& axis : params["axes"]) {
      ASSERT_EQ(axis["ar"].size(), 1u) << model->describe();
      EXPECT_NEAR(axis["ar"][0].get<double>(), std::exp(-interval / truth.tau), 0.01);
    }
  }
  // A fitted model is like any other: it rebuilds from its params.
  EXPECT_TRUE(model->equals(*make(GetParam(), model->params()), 1e-12));
  EXPECT_NEAR(model->params()["K"][0].get<double>(), 0.001, 1e-15);
}

INSTANTIATE_TEST_SUITE_P(ArAndArma, BlockProcessFit, ::testing::Values("ar", "arma"));

TEST(ArFit, ChoosesAnOrderAndRejectsBadOptions) {
  const SimulatedGyro truth;
  const auto record = truth.record(300.0, 7);
  const auto fit = [&](const std::string& type, const nlohmann::json& params) {
    try {
      registry().fit_noise_model(type, record, params, context_for(SensorGroup::kGyro), "/p");
    } catch (const ConfigError& error) {
      return std::string(error.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(fit("ar", {{"method", "yule_walker"}, {"criterion", "aic"}}), "(accepted)");
  EXPECT_EQ(fit("ar", {{"max_order", 0}}).rfind("/noise/gyro/params/max_order: found 0", 0), 0u)
      << fit("ar", {{"max_order", 0}});
  EXPECT_EQ(fit("ar", {{"max_order", 2.5}}).rfind("/noise/gyro/params/max_order: found 2.5", 0),
            0u);
  EXPECT_EQ(fit("ar", {{"method", "ls"}}).rfind("/noise/gyro/params/method: found \"ls\"", 0), 0u);
  EXPECT_EQ(fit("ar", {{"interval_s", 0.015}})
                .rfind("/noise/gyro/params/interval_s: found 0.015; expected a whole multiple", 0),
            0u);
  EXPECT_EQ(fit("arma", {{"max_p", 0}, {"max_q", 0}}).rfind("/noise/gyro/params/max_p", 0), 0u);
  EXPECT_EQ(fit("arma", {{"max_q", 3}}).rfind("/noise/gyro/params/max_q: found 3", 0), 0u);
  // Too short a record is an input error naming the record.
  EXPECT_THROW(registry().fit_noise_model("ar", record, {{"interval_s", 10.0}, {"max_order", 8}},
                                          context_for(SensorGroup::kGyro), "/p"),
               InputError);
}

}  // namespace
}  // namespace stochnav::plugin
