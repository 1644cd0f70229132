// Noise plugin "gauss_markov": a first-order Gauss-Markov (Ornstein-Uhlenbeck) sensor error per
// axis, as three augmented states, plus optional white noise and bias random walk.
//
// params (reporting units of DESIGN.md; a number applies to all axes, or [x, y, z]):
//   "sigma"  stationary standard deviation, > 0: deg/h (gyro), m/s/h (accel). Required.
//   "tau_c"  correlation time, > 0: s. Required.
//   "N"      angle random walk (white part), >= 0: deg/sqrt(h), m/s/sqrt(h). Default 0.
//   "K"      rate random walk of the core bias, >= 0: deg/h/sqrt(h), m/s/h/sqrt(h). Default 0.
// Augmented states x (3, natural rate units), sensor error += x (M = I):
//   Phi = diag(exp(-dt / tau_c)), Qd = diag(sigma^2 (1 - exp(-2 dt / tau_c))), P0 = diag(sigma^2)
// (exact discretisation: the stationary variance sigma^2 is preserved step after step);
// Qw = diag(N^2) dt, Qb = diag(K^2) dt.
// Fit params: {"white": bool (default true: fit N too), "rate_random_walk": bool (default
// false)}: the Gauss-Markov term (and the others) fitted per axis to the record's Allan variance.

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "stochnav/core/errors.hpp"
#include "stochnav/model/reporting_units.hpp"
#include "stochnav/plugin/calibration_fit.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/params.hpp"

namespace {

using stochnav::ParameterDimension;
using stochnav::plugin::SensorGroup;
using Axes = std::array<double, 3>;

struct GaussMarkovParams {
  Axes sigma{};  ///< stationary standard deviation per axis, rad/s or m/s^2
  Axes tau_c{};  ///< correlation time per axis, s
  Axes n{};      ///< angle random walk per axis, rad/sqrt(s) or m/s/sqrt(s)
  Axes k{};      ///< rate random walk per axis, rad/s/sqrt(s) or m/s^2/sqrt(s)
};

using stochnav::plugin::parameters_close;

class GaussMarkovNoise final : public stochnav::plugin::NoiseModelPlugin {
 public:
  GaussMarkovNoise(SensorGroup group, const GaussMarkovParams& params)
      : NoiseModelPlugin(group), params_(params) {}

  std::string_view type() const override { return "gauss_markov"; }
  int augmented_size() const override { return 3; }

  void white_noise_covariance(double, double dt_s,
                              Eigen::Ref<Eigen::MatrixXd> q_white) const override {
    q_white.setZero();
    for (int i = 0; i < 3; ++i) q_white(i, i) = params_.n[i] * params_.n[i] * dt_s;
  }

  void bias_walk_covariance(double, double dt_s,
                            Eigen::Ref<Eigen::MatrixXd> q_bias) const override {
    q_bias.setZero();
    for (int i = 0; i < 3; ++i) q_bias(i, i) = params_.k[i] * params_.k[i] * dt_s;
  }

  void augmented_transition(double, double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                            Eigen::Ref<Eigen::MatrixXd> q_d) const override {
    // The filter steps with a constant dt: the exponentials are computed once per distinct dt
    // (an instance is used from one thread at a time, noise_model_plugin.hpp).
    if (dt_s != cached_dt_) {
      for (int i = 0; i < 3; ++i) {
        cached_decay_[i] = std::exp(-dt_s / params_.tau_c[i]);
        // 1 - exp(-2 dt / tau) without cancellation for small steps.
        cached_q_[i] =
            params_.sigma[i] * params_.sigma[i] * -std::expm1(-2.0 * dt_s / params_.tau_c[i]);
      }
      cached_dt_ = dt_s;
    }
    phi.setZero();
    q_d.setZero();
    for (int i = 0; i < 3; ++i) {
      phi(i, i) = cached_decay_[i];
      q_d(i, i) = cached_q_[i];
    }
  }

  void augmented_initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const override {
    p0.setZero();
    for (int i = 0; i < 3; ++i) p0(i, i) = params_.sigma[i] * params_.sigma[i];
  }

  void augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const override { map.setIdentity(); }

  nlohmann::json params() const override {
    nlohmann::json sigma = nlohmann::json::array(), tau = nlohmann::json::array(),
                   n = nlohmann::json::array(), k = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) {
      sigma.push_back(reported(ParameterDimension::kRate, params_.sigma[i]));
      tau.push_back(params_.tau_c[i]);
      n.push_back(reported(ParameterDimension::kAnglePerRootTime, params_.n[i]));
      k.push_back(reported(ParameterDimension::kRatePerRootTime, params_.k[i]));
    }
    return {{"sigma", sigma}, {"tau_c", tau}, {"N", n}, {"K", k}};
  }

  std::string describe() const override {
    std::string text =
        fmt::format("gauss_markov ({}):", stochnav::plugin::sensor_group_name(group()));
    const char* axis_names[] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
      text += fmt::format(" {}: sigma = {:.6g} {}, tau_c = {:.6g} s, N = {:.6g} {}, K = {:.6g} {};",
                          axis_names[i], reported(ParameterDimension::kRate, params_.sigma[i]),
                          reported_unit(ParameterDimension::kRate), params_.tau_c[i],
                          reported(ParameterDimension::kAnglePerRootTime, params_.n[i]),
                          reported_unit(ParameterDimension::kAnglePerRootTime),
                          reported(ParameterDimension::kRatePerRootTime, params_.k[i]),
                          reported_unit(ParameterDimension::kRatePerRootTime));
    }
    text.pop_back();
    return text;
  }

  bool equals(const NoiseModelPlugin& other, double rel_tol) const override {
    const auto* that = dynamic_cast<const GaussMarkovNoise*>(&other);
    if (that == nullptr || that->group() != group()) return false;
    for (int i = 0; i < 3; ++i) {
      if (!parameters_close(params_.sigma[i], that->params_.sigma[i], rel_tol) ||
          !parameters_close(params_.tau_c[i], that->params_.tau_c[i], rel_tol) ||
          !parameters_close(params_.n[i], that->params_.n[i], rel_tol) ||
          !parameters_close(params_.k[i], that->params_.k[i], rel_tol)) {
        return false;
      }
    }
    return true;
  }

 private:
  GaussMarkovParams params_;
  mutable double cached_dt_ = std::numeric_limits<double>::quiet_NaN();
  mutable Axes cached_decay_{};  ///< exp(-dt / tau_c) per axis
  mutable Axes cached_q_{};      ///< sigma^2 (1 - exp(-2 dt / tau_c)) per axis, natural units^2
};

Axes read_natural(stochnav::plugin::ParamReader& reader, SensorGroup group, std::string_view key,
                  ParameterDimension dimension, stochnav::plugin::Bound bound,
                  const Axes* fallback) {
  const auto quantity = stochnav::plugin::sensor_quantity(group);
  const std::string unit = stochnav::reported_unit_name(quantity, dimension);
  Axes values = fallback != nullptr ? reader.axes_or(key, *fallback, bound, unit)
                                    : reader.axes(key, bound, unit);
  for (double& value : values) value = stochnav::to_natural(quantity, dimension, value);
  return values;
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_gauss_markov(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  using stochnav::plugin::Bound;
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  const Axes zero{0.0, 0.0, 0.0};
  GaussMarkovParams params;
  params.sigma = read_natural(reader, context.group, "sigma", ParameterDimension::kRate,
                              Bound::kPositive, nullptr);
  params.tau_c = reader.axes("tau_c", Bound::kPositive, "s");
  params.n = read_natural(reader, context.group, "N", ParameterDimension::kAnglePerRootTime,
                          Bound::kNonNegative, &zero);
  params.k = read_natural(reader, context.group, "K", ParameterDimension::kRatePerRootTime,
                          Bound::kNonNegative, &zero);
  reader.finish();
  return std::make_unique<GaussMarkovNoise>(context.group, params);
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_gauss_markov(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  using stochnav::TermType;
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  const bool with_white = reader.boolean_or("white", true);
  const bool with_walk = reader.boolean_or("rate_random_walk", false);
  reader.finish();
  stochnav::FitOptions options;
  options.terms = {TermType::kGaussMarkov};
  if (with_white) options.terms.push_back(TermType::kAngleRandomWalk);
  if (with_walk) options.terms.push_back(TermType::kRateRandomWalk);
  const auto fits = stochnav::plugin::fit_calibration_axes(record, options);
  GaussMarkovParams params;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const auto& model = fits[axis].model;
    const auto* gm = stochnav::plugin::find_term(model, TermType::kGaussMarkov);
    if (gm == nullptr) {
      throw stochnav::InputError(record.source + ": no Gauss-Markov term fitted on axis " +
                                 std::to_string(axis) + "; use a longer record or another model");
    }
    params.sigma[axis] = std::get<stochnav::GaussMarkovTerm>(*gm).sigma;
    params.tau_c[axis] = std::get<stochnav::GaussMarkovTerm>(*gm).tau_c;
    if (const auto* arw = stochnav::plugin::find_term(model, TermType::kAngleRandomWalk)) {
      params.n[axis] = std::get<stochnav::AngleRandomWalkTerm>(*arw).n;
    }
    if (const auto* rrw = stochnav::plugin::find_term(model, TermType::kRateRandomWalk)) {
      params.k[axis] = std::get<stochnav::RateRandomWalkTerm>(*rrw).k;
    }
    if (!(params.sigma[axis] > 0.0 && params.tau_c[axis] > 0.0)) {
      throw stochnav::InputError(record.source + ": the fitted Gauss-Markov term of axis " +
                                 std::to_string(axis) + " is degenerate; use a longer record");
    }
  }
  auto model = std::make_unique<GaussMarkovNoise>(record.group, params);
  model->set_fit_quality(stochnav::plugin::calibration_fit_quality(fits));
  return model;
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("gauss_markov",
                      "first-order Gauss-Markov sensor error per axis as 3 augmented states",
                      make_gauss_markov, fit_gauss_markov)
