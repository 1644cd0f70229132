// An out-of-tree noise plugin: a second-order Gauss-Markov sensor error per axis (a critically
// damped pair of poles at -beta = -1 / tau_c), two augmented states per axis:
//   x1' = -beta x1 + x2,   x2' = -beta x2 + w,   w white with PSD q,   sensor error = x1.
// Its autocorrelation is smoother than the first-order model's (no cusp at lag 0), typical of
// band-limited vibration-induced errors.
//
// params: "sigma" stationary standard deviation of x1 (deg/h for gyros, m/s/h for accel), > 0;
//         "tau_c" correlation time 1 / beta (s), > 0. A number for all axes, or [x, y, z].
// Stationary covariance (Lyapunov F P + P F^T + G q G^T = 0):
//   var x1 = q / (4 beta^3) = sigma^2, cov(x1, x2) = q / (4 beta^2), var x2 = q / (2 beta).
// Exact discretisation over dt: Phi = e^(-beta dt) [[1, dt], [0, 1]],
//   Qd = q int_0^dt e^(-2 beta s) [[s^2, s], [s, 1]] ds.

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/params.hpp"

namespace {

using stochnav::plugin::SensorGroup;
using Axes = std::array<double, 3>;

/// Natural units (rad/s or m/s^2) per reporting unit (deg/h or m/s/h) of a rate.
double natural_per_reported_rate(SensorGroup group) {
  return group == SensorGroup::kGyro ? std::numbers::pi / 180.0 / 3600.0 : 1.0 / 3600.0;
}

class SecondOrderGaussMarkov final : public stochnav::plugin::NoiseModelPlugin {
 public:
  SecondOrderGaussMarkov(SensorGroup group, Axes sigma, Axes tau_c)
      : NoiseModelPlugin(group), sigma_(sigma), tau_c_(tau_c) {}

  std::string_view type() const override { return "second_order_gauss_markov"; }
  int augmented_size() const override { return 6; }

  void white_noise_covariance(double, double, Eigen::Ref<Eigen::MatrixXd> q_white) const override {
    q_white.setZero();
  }

  void augmented_transition(double, double dt, Eigen::Ref<Eigen::MatrixXd> phi,
                            Eigen::Ref<Eigen::MatrixXd> q_d) const override {
    phi.setZero();
    q_d.setZero();
    for (int i = 0; i < 3; ++i) {
      const double beta = 1.0 / tau_c_[i];
      const double q = 4.0 * beta * beta * beta * sigma_[i] * sigma_[i];
      const double decay = std::exp(-beta * dt);
      const int k = 2 * i;
      phi(k, k) = decay;
      phi(k, k + 1) = decay * dt;
      phi(k + 1, k + 1) = decay;
      const double b2 = 2.0 * beta * dt, e2 = std::exp(-b2);
      const double i0 = -std::expm1(-b2) / (2.0 * beta);
      const double i1 = (1.0 - e2 * (1.0 + b2)) / (4.0 * beta * beta);
      const double i2 = (2.0 - e2 * (2.0 + 2.0 * b2 + b2 * b2)) / (8.0 * beta * beta * beta);
      q_d(k, k) = q * i2;
      q_d(k, k + 1) = q_d(k + 1, k) = q * i1;
      q_d(k + 1, k + 1) = q * i0;
    }
  }

  void augmented_initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const override {
    p0.setZero();
    for (int i = 0; i < 3; ++i) {
      const double beta = 1.0 / tau_c_[i];
      const double q = 4.0 * beta * beta * beta * sigma_[i] * sigma_[i];
      const int k = 2 * i;
      p0(k, k) = sigma_[i] * sigma_[i];
      p0(k, k + 1) = p0(k + 1, k) = q / (4.0 * beta * beta);
      p0(k + 1, k + 1) = q / (2.0 * beta);
    }
  }

  void augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const override {
    map.setZero();
    for (int i = 0; i < 3; ++i) map(i, 2 * i) = 1.0;
  }

  nlohmann::json params() const override {
    nlohmann::json sigma = nlohmann::json::array(), tau = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) {
      sigma.push_back(sigma_[i] / natural_per_reported_rate(group()));
      tau.push_back(tau_c_[i]);
    }
    return {{"sigma", sigma}, {"tau_c", tau}};
  }

  std::string describe() const override {
    std::ostringstream text;
    text << "second_order_gauss_markov (" << stochnav::plugin::sensor_group_name(group()) << "):";
    for (int i = 0; i < 3; ++i) {
      text << " axis " << i << ": sigma = " << sigma_[i] / natural_per_reported_rate(group())
           << (group() == SensorGroup::kGyro ? " deg/h" : " m/s/h") << ", tau_c = " << tau_c_[i]
           << " s" << (i < 2 ? ";" : "");
    }
    return text.str();
  }

  bool equals(const NoiseModelPlugin& other, double rel_tol) const override {
    const auto* that = dynamic_cast<const SecondOrderGaussMarkov*>(&other);
    if (that == nullptr || that->group() != group()) return false;
    const auto close = [rel_tol](double a, double b) {
      return std::abs(a - b) <= rel_tol * std::max(std::abs(a), std::abs(b));
    };
    for (int i = 0; i < 3; ++i) {
      if (!close(sigma_[i], that->sigma_[i]) || !close(tau_c_[i], that->tau_c_[i])) return false;
    }
    return true;
  }

 private:
  Axes sigma_;  ///< stationary standard deviation of the sensor error per axis, rad/s or m/s^2
  Axes tau_c_;  ///< correlation time per axis, s
};

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  using stochnav::plugin::Bound;
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  Axes sigma = reader.axes("sigma", Bound::kPositive,
                           context.group == SensorGroup::kGyro ? "deg/h" : "m/s/h");
  for (double& value : sigma) value *= natural_per_reported_rate(context.group);
  const Axes tau_c = reader.axes("tau_c", Bound::kPositive, "s");
  reader.finish();
  return std::make_unique<SecondOrderGaussMarkov>(context.group, sigma, tau_c);
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("second_order_gauss_markov",
                      "second-order (critically damped) Gauss-Markov error, 2 states per axis",
                      make, ::stochnav::plugin::fit_not_supported)
