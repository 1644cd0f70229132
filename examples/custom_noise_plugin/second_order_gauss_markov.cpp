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
//   Qd = q int_0^dt e^(-2 beta s) [[s^2, s], [s, 1]] ds
//      = q [[2 r2 / (8 beta^3), r1 / (4 beta^2)], [., r0 / (2 beta)]],
//   r_n = 1 - e^(-2 beta dt) sum_{k <= n} (2 beta dt)^k / k!   (exp_remainder).

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <memory>

#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"
#include "stochnav/plugin/tabulated_noise_model.hpp"

namespace {

using stochnav::ParameterDimension;
using stochnav::plugin::Bound;
using stochnav::plugin::ParamUnit;
using stochnav::plugin::SensorGroup;
using Axes = std::array<double, 3>;

struct SecondOrderParams {
  Axes sigma{};  ///< stationary standard deviation of the sensor error per axis, rad/s or m/s^2
  Axes tau_c{};  ///< correlation time per axis, s
};

// Each parameter declared once: parsing (with deg/h -> rad/s), params(), describe(), equals().
const stochnav::plugin::ParamTable<SecondOrderParams> kTable{
    per_axis(&SecondOrderParams::sigma, "sigma", ParamUnit::of(ParameterDimension::kRate),
             Bound::kPositive, stochnav::plugin::kRequired, "stationary standard deviation of x1"),
    per_axis(&SecondOrderParams::tau_c, "tau_c", ParamUnit::of(ParameterDimension::kTime),
             Bound::kPositive, stochnav::plugin::kRequired, "correlation time 1 / beta"),
};

/// 1 - e^-x (1 + x + ... + x^n / n!) for x >= 0. For x < 1 summed as its series
/// e^-x (x^(n+1) / (n+1)! + ...): the difference cancels to nothing at small steps (the
/// property suite caught Qd losing positive semi-definiteness at dt = 1e-4 s).
double exp_remainder(int n, double x) {
  double term = 1.0, partial = 1.0;  // x^k / k! and the sum up to k = n
  for (int k = 1; k <= n; ++k) {
    term *= x / k;
    partial += term;
  }
  if (x >= 1.0) return 1.0 - std::exp(-x) * partial;
  double tail = 0.0;
  for (int k = n + 1; k <= n + 40; ++k) {
    term *= x / k;
    tail += term;
    if (term <= 1e-17 * tail) break;
  }
  return std::exp(-x) * tail;
}

class SecondOrderGaussMarkov final
    : public stochnav::plugin::TabulatedNoiseModel<SecondOrderParams> {
 public:
  SecondOrderGaussMarkov(SensorGroup group, const SecondOrderParams& params)
      : TabulatedNoiseModel(group, kTable, params) {}

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
      const double beta = 1.0 / parameters().tau_c[i];
      const double q = driving_psd(i);
      const double decay = std::exp(-beta * dt);
      const int k = 2 * i;
      phi(k, k) = decay;
      phi(k, k + 1) = decay * dt;
      phi(k + 1, k + 1) = decay;
      const double b2 = 2.0 * beta * dt;
      const double i0 = exp_remainder(0, b2) / (2.0 * beta);
      const double i1 = exp_remainder(1, b2) / (4.0 * beta * beta);
      const double i2 = 2.0 * exp_remainder(2, b2) / (8.0 * beta * beta * beta);
      q_d(k, k) = q * i2;
      q_d(k, k + 1) = q_d(k + 1, k) = q * i1;
      q_d(k + 1, k + 1) = q * i0;
    }
  }

  void augmented_initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const override {
    p0.setZero();
    for (int i = 0; i < 3; ++i) {
      const double beta = 1.0 / parameters().tau_c[i];
      const double q = driving_psd(i);
      const int k = 2 * i;
      p0(k, k) = parameters().sigma[i] * parameters().sigma[i];
      p0(k, k + 1) = p0(k + 1, k) = q / (4.0 * beta * beta);
      p0(k + 1, k + 1) = q / (2.0 * beta);
    }
  }

  void augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const override {
    map.setZero();
    for (int i = 0; i < 3; ++i) map(i, 2 * i) = 1.0;
  }

  // The table's describe() plus a derived quantity (fmt comes with stochnav::framework).
  std::string describe() const override {
    return TabulatedNoiseModel::describe() +
           fmt::format("; driving PSD q = {:.3g} (natural units^2/s^3, x axis)", driving_psd(0));
  }

 private:
  /// q = 4 beta^3 sigma^2, natural units.
  double driving_psd(int axis) const {
    const double beta = 1.0 / parameters().tau_c[axis];
    return 4.0 * beta * beta * beta * parameters().sigma[axis] * parameters().sigma[axis];
  }
};

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  return std::make_unique<SecondOrderGaussMarkov>(
      context.group, stochnav::plugin::parse_params(kTable, json, context));
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("second_order_gauss_markov",
                      "second-order (critically damped) Gauss-Markov error, 2 states per axis",
                      make, ::stochnav::plugin::fit_not_supported)
// Optional: the params reference `stochnav plugins doc` prints, from the same table.
STOCHNAV_PLUGIN_DOCUMENTATION(kTable)
