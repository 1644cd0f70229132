#pragma once
// What the tests of the in-tree noise plugins share: the bundled plugins' registry, a context,
// building a model, matrix expectations, and the installed property-test fixture
// (stochnav/testing/noise_model_case.hpp; its TEST_Ps are compiled in noise_plugin_test.cpp):
//   INSTANTIATE_TEST_SUITE_P(Ar, NoiseModelProperties, ::testing::Values(Case{...}), case_name);

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "stochnav/core/angles.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/testing/noise_model_case.hpp"

namespace stochnav::plugin::testing {

using Case = stochnav::testing::NoiseModelCase;
using stochnav::testing::NoiseModelProperties;
inline constexpr auto case_name = &stochnav::testing::noise_model_case_name;

// Reporting units of the noise terms in SI, for parameters written as a datasheet gives them.
inline constexpr double kDegPerHour = kRadPerDeg / 3600.0;    ///< rad/s
inline constexpr double kDegPerRootHour = kRadPerDeg / 60.0;  ///< rad/sqrt(s)

/// Property checks for models defined on a grid of propagation intervals (ar, arma): the two
/// composed steps and the stationarity step on that grid.
inline PropertyCheckOptions on_grid(double dt1_s, double dt2_s, double step_s) {
  PropertyCheckOptions options;
  options.dt1_s = dt1_s;
  options.dt2_s = dt2_s;
  options.stationary_step_s = step_s;
  return options;
}

/// The bundled plugins, loaded once per test binary.
inline const PluginRegistry& registry() {
  static const PluginRegistry instance({bundled_plugin_dir()});
  return instance;
}

/// 100 Hz IMU, params under "/noise/<group>/params".
inline NoiseModelContext context_for(SensorGroup group) {
  NoiseModelContext context;
  context.group = group;
  context.imu_rate_hz = 100.0;
  context.params_pointer = "/noise/" + std::string(sensor_group_name(group)) + "/params";
  return context;
}

inline std::shared_ptr<NoiseModelPlugin> make(const std::string& type, const nlohmann::json& params,
                                              SensorGroup group = SensorGroup::kGyro) {
  return registry().create_noise_model(type, params, context_for(group), "/noise/x/plugin");
}

inline void expect_symmetric_psd(const Eigen::MatrixXd& q, const char* what) {
  if (q.size() == 0) return;
  const double scale = std::max(q.cwiseAbs().maxCoeff(), 1e-300);
  EXPECT_LE((q - q.transpose()).cwiseAbs().maxCoeff(), 1e-14 * scale) << what;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(q);
  EXPECT_GE(solver.eigenvalues().minCoeff(), -1e-14 * scale) << what;
}

inline void expect_close(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double rel,
                         const char* what) {
  const double scale = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), 1e-300});
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), rel * scale) << what << "\n" << a << "\n" << b;
}

}  // namespace stochnav::plugin::testing
