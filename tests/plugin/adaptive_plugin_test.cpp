// Noise plugin "adaptive" (Sage-Husa): the noise-model properties, and the estimator closing the
// loop with a Kalman filter on a simulated random walk of known PSD: it converges to that PSD
// from above and from below and never leaves its clamps.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "noise_plugin_support.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav::plugin {
namespace {

using testing::Case;
using testing::case_name;
using testing::kDegPerRootHour;
using testing::make;
using testing::NoiseModelProperties;

INSTANTIATE_TEST_SUITE_P(
    Adaptive, NoiseModelProperties,
    ::testing::Values(
        Case{"adaptive", {{"N_initial", 0.05}}, SensorGroup::kGyro},
        Case{"adaptive",
             {{"N_initial", 0.03}, {"N_min", 0.01}, {"N_max", 0.3}, {"forgetting", 0.9}},
             SensorGroup::kAccel}),
    case_name);

TEST(AdaptiveNoise, BadParamsNameTheJsonPointer) {
  const auto message = [](const nlohmann::json& params) {
    try {
      make("adaptive", params);
    } catch (const ConfigError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({{"N_initial", 0.05}, {"forgetting", 1.0}})
                .find("/noise/gyro/params/forgetting: found 1"),
            std::string::npos);
  EXPECT_NE(message({{"N_initial", 0.05}, {"N_max", 0.01}})
                .find("/noise/gyro/params/N_max: found 0.01; expected at least N_initial"),
            std::string::npos);
  EXPECT_NE(message({{"N", 0.05}}).find("/noise/gyro/params/N_initial"), std::string::npos);
}

/// A Kalman filter on the 15-state layout whose attitude block (gyro) or velocity block (accel)
/// is a 3-axis random walk of PSD q_true, measured directly each second with noise R = r I; the
/// filter takes its process noise from the model and reports every update to it. Returns the
/// model's N^2 (rad^2/s or (m/s)^2/s) after each update.
std::vector<double> run_closed_loop(NoiseModelPlugin& model, double q_true, double r, int updates,
                                    std::uint64_t seed) {
  const int rows =
      model.group() == SensorGroup::kGyro ? core_state::kAttitude : core_state::kVelocity;
  const int n = core_state::kSize;
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal;
  Eigen::Vector3d truth = Eigen::Vector3d::Zero(), estimate = Eigen::Vector3d::Zero();
  Eigen::MatrixXd p = Eigen::MatrixXd::Identity(n, n) * 1e-6;
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(3, n);
  h.middleCols(rows, 3).setIdentity();
  const Eigen::Matrix3d r_matrix = Eigen::Matrix3d::Identity() * r;
  Eigen::MatrixXd q_white(3, 3);
  std::vector<double> levels;
  const double dt = 0.01;  // 100 Hz propagation, 1 Hz updates
  double t = 0.0;
  for (int k = 0; k < updates; ++k) {
    for (int epoch = 0; epoch < 100; ++epoch) {
      model.white_noise_covariance(t, dt, q_white);
      p.block(rows, rows, 3, 3) += q_white;
      for (int axis = 0; axis < 3; ++axis) truth(axis) += std::sqrt(q_true * dt) * normal(random);
      t += dt;
    }
    Eigen::Vector3d z_measured;
    for (int axis = 0; axis < 3; ++axis)
      z_measured(axis) = truth(axis) + std::sqrt(r) * normal(random);
    const Eigen::VectorXd innovation = z_measured - estimate;
    const Eigen::MatrixXd s = h * p * h.transpose() + r_matrix;
    const Eigen::MatrixXd gain = p * h.transpose() * s.inverse();
    const Eigen::MatrixXd prior = p;
    estimate += (gain * innovation).segment(rows, 3);
    p = (Eigen::MatrixXd::Identity(n, n) - gain * h) * p;
    const UpdateFeedback feedback{
        t, "test", true, innovation.dot(s.ldlt().solve(innovation)), innovation, s, gain, prior, p};
    model.on_update(feedback);
    Eigen::MatrixXd probe(3, 3);
    model.white_noise_covariance(t, 1.0, probe);
    levels.push_back(probe(0, 0));
  }
  return levels;
}

double mean_of_last_half(const std::vector<double>& values) {
  double sum = 0.0;
  for (std::size_t i = values.size() / 2; i < values.size(); ++i) sum += values[i];
  return sum / static_cast<double>(values.size() - values.size() / 2);
}

TEST(AdaptiveNoise, ConvergesToTheTrueNoiseFromBelowAndAbove) {
  const double n_true = 0.5;  // deg/sqrt(h)
  const double q_true = std::pow(n_true * kDegPerRootHour, 2);
  const double r = q_true * 1.0;  // measurement noise comparable to one second of walk
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    for (const double start : {0.1, 2.5}) {  // N_initial in units of n_true
      const auto model =
          make("adaptive", {{"N_initial", start * n_true}, {"N_min", 0.01}, {"N_max", 10.0}});
      const auto levels = run_closed_loop(*model, q_true, r, 1500, seed);
      const double estimate = std::sqrt(mean_of_last_half(levels) / q_true) * n_true;
      std::printf("seed %d, start %.2f deg/sqrt(h): N estimate %.4f (truth %.2f)\n",
                  static_cast<int>(seed), start * n_true, estimate, n_true);
      EXPECT_NEAR(estimate, n_true, 0.1 * n_true) << "seed " << seed << " start " << start;
      // The first updates move it the right way.
      const double first = std::sqrt(levels[20] / q_true);
      if (start < 1.0) {
        EXPECT_GT(first, start);
      } else {
        EXPECT_LT(first, start);
      }
    }
  }
}

TEST(AdaptiveNoise, AccelerometerLevelAdaptsOnTheVelocityBlock) {
  const double n_true = 0.02;  // m/s/sqrt(h)
  const double q_true = std::pow(n_true / 60.0, 2);
  const auto model =
      make("adaptive", {{"N_initial", 0.2}, {"N_min", 1e-4}, {"N_max", 1.0}}, SensorGroup::kAccel);
  const auto levels = run_closed_loop(*model, q_true, q_true, 1500, 7);
  EXPECT_NEAR(std::sqrt(mean_of_last_half(levels) / q_true), 1.0, 0.1);
}

TEST(AdaptiveNoise, NeverLeavesItsClamps) {
  const double n_true = 0.5;
  const double q_true = std::pow(n_true * kDegPerRootHour, 2);
  for (const auto& [n_min, n_max] : {std::pair{0.01, 0.2}, std::pair{1.0, 3.0}}) {
    const double start = n_max == 0.2 ? 0.1 : 2.0;
    const auto model = make("adaptive", {{"N_initial", start}, {"N_min", n_min}, {"N_max", n_max}});
    const auto levels = run_closed_loop(*model, q_true, q_true, 300, 3);
    const double low = std::pow(n_min * kDegPerRootHour, 2);
    const double high = std::pow(n_max * kDegPerRootHour, 2);
    for (double level : levels) {
      EXPECT_GE(level, low * (1 - 1e-12));
      EXPECT_LE(level, high * (1 + 1e-12));
    }
    // The truth is outside [N_min, N_max]: the estimate stays by the clamp nearest to it (a
    // single update may still move it off the clamp, the other way).
    const double settled = mean_of_last_half(levels);
    if (n_max == 0.2) {
      EXPECT_GT(settled, 0.95 * high);
    } else {
      EXPECT_LT(settled, 1.05 * low);
    }
  }
}

TEST(AdaptiveNoise, RejectedUpdatesLeaveTheLevelUnchanged) {
  const auto model = make("adaptive", {{"N_initial", 0.05}});
  const Eigen::VectorXd z = Eigen::VectorXd::Constant(3, 1.0);
  const Eigen::MatrixXd s = Eigen::MatrixXd::Identity(3, 3);
  const Eigen::MatrixXd gain = Eigen::MatrixXd::Constant(15, 3, 0.5);
  const Eigen::MatrixXd p = Eigen::MatrixXd::Identity(15, 15);
  Eigen::MatrixXd before(3, 3), after(3, 3);
  model->white_noise_covariance(0.0, 1.0, before);
  for (double t : {1.0, 2.0, 3.0}) model->on_update({t, "test", false, 3.0, z, s, gain, p, p});
  model->white_noise_covariance(0.0, 1.0, after);
  EXPECT_EQ(before, after);
}

}  // namespace
}  // namespace stochnav::plugin
