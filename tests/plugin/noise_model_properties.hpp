#pragma once
// The properties every noise-model plugin must have (noise_model_plugin.hpp), as a
// value-parameterised GoogleTest fixture. The TEST_Ps live in noise_plugin_test.cpp; each plugin's
// test file instantiates them for its own cases:
//   INSTANTIATE_TEST_SUITE_P(Ar, NoiseModelProperties, ::testing::Values(Case{...}), case_name);

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/plugin_registry.hpp"

namespace stochnav::plugin::testing {

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

/// One model under test. Models whose transition is defined on a grid of propagation intervals
/// (e.g. ar, arma) set dt1, dt2 and step_s to multiples of that interval.
struct Case {
  std::string type;
  nlohmann::json params;
  SensorGroup group;
  double dt1 = 0.37;     ///< first of two consecutive steps (s) in the composition test
  double dt2 = 1.9;      ///< second step (s)
  double step_s = 0.01;  ///< step (s) of the 1e5-step stationarity test
};

inline void PrintTo(const Case& c, std::ostream* os) {
  *os << c.type << " " << sensor_group_name(c.group) << " " << c.params.dump();
}

inline std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  return info.param.type + "_" + std::string(sensor_group_name(info.param.group)) + "_" +
         std::to_string(info.index);
}

class NoiseModelProperties : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    model_ = make(GetParam().type, GetParam().params, GetParam().group);
    n_ = model_->augmented_size();
  }

  struct Step {
    Eigen::MatrixXd q_white = Eigen::MatrixXd(3, 3);
    Eigen::MatrixXd q_bias = Eigen::MatrixXd(3, 3);
    Eigen::MatrixXd phi, q_d;
  };

  Step step(double t, double dt) const {
    Step s;
    s.phi.resize(n_, n_);
    s.q_d.resize(n_, n_);
    model_->white_noise_covariance(t, dt, s.q_white);
    model_->bias_walk_covariance(t, dt, s.q_bias);
    model_->augmented_transition(t, dt, s.phi, s.q_d);
    return s;
  }

  std::shared_ptr<NoiseModelPlugin> model_;
  int n_ = 0;
};

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
