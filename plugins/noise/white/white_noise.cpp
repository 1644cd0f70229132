// Noise plugin "white": constant white sensor noise per axis from datasheet values, with an
// optional rate random walk of the core bias block (the paper's classic filter).
//
// params (reporting units of DESIGN.md; a number applies to all axes, or [x, y, z]):
//   "N"  angle random walk, >= 0: deg/sqrt(h) (gyro), m/s/sqrt(h) (accel). Required.
//   "K"  rate random walk, >= 0: deg/h/sqrt(h) (gyro), m/s/h/sqrt(h) (accel). Default 0.
// Discrete model over [t, t + dt]: Qw = diag(N^2) dt, Qb = diag(K^2) dt (natural units); no
// augmented states.
// Fit params: {"rate_random_walk": bool (default false: fit N only)}; fits N (and K) per axis
// to the record's Allan variance; a failed N + K fit (a flicker floor: K on its bound or a
// chi-square far beyond its dof) uses the floor-matched rule of plugin/calibration_fit.hpp
// (fit_white_walk), reported in fit_quality().

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <memory>

#include "stochnav/model/reporting_units.hpp"
#include "stochnav/plugin/calibration_fit.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/params.hpp"

namespace {

using stochnav::ParameterDimension;
using stochnav::plugin::SensorGroup;
using Axes = std::array<double, 3>;

struct WhiteParams {
  Axes n{};  ///< angle random walk per axis, rad/sqrt(s) or m/s/sqrt(s)
  Axes k{};  ///< rate random walk per axis, rad/s/sqrt(s) or m/s^2/sqrt(s)
};

using stochnav::plugin::parameters_close;

class WhiteNoise final : public stochnav::plugin::NoiseModelPlugin {
 public:
  WhiteNoise(SensorGroup group, const WhiteParams& params)
      : NoiseModelPlugin(group), params_(params) {}

  std::string_view type() const override { return "white"; }

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

  nlohmann::json params() const override {
    nlohmann::json n = nlohmann::json::array(), k = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) {
      n.push_back(reported(ParameterDimension::kAnglePerRootTime, params_.n[i]));
      k.push_back(reported(ParameterDimension::kRatePerRootTime, params_.k[i]));
    }
    return {{"N", n}, {"K", k}};
  }

  std::string describe() const override {
    std::string text = fmt::format("white ({}):", stochnav::plugin::sensor_group_name(group()));
    const char* axis_names[] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
      text += fmt::format(" {}: N = {:.6g} {}, K = {:.6g} {};", axis_names[i],
                          reported(ParameterDimension::kAnglePerRootTime, params_.n[i]),
                          reported_unit(ParameterDimension::kAnglePerRootTime),
                          reported(ParameterDimension::kRatePerRootTime, params_.k[i]),
                          reported_unit(ParameterDimension::kRatePerRootTime));
    }
    text.pop_back();
    return text;
  }

  bool equals(const NoiseModelPlugin& other, double rel_tol) const override {
    const auto* that = dynamic_cast<const WhiteNoise*>(&other);
    if (that == nullptr || that->group() != group()) return false;
    for (int i = 0; i < 3; ++i) {
      if (!parameters_close(params_.n[i], that->params_.n[i], rel_tol)) return false;
      if (!parameters_close(params_.k[i], that->params_.k[i], rel_tol)) return false;
    }
    return true;
  }

 private:
  WhiteParams params_;
};

Axes to_natural(SensorGroup group, ParameterDimension dimension, Axes reported) {
  for (double& value : reported) {
    value = stochnav::to_natural(stochnav::plugin::sensor_quantity(group), dimension, value);
  }
  return reported;
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_white(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  using stochnav::plugin::Bound;
  const auto quantity = stochnav::plugin::sensor_quantity(context.group);
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  WhiteParams params;
  params.n = to_natural(
      context.group, ParameterDimension::kAnglePerRootTime,
      reader.axes("N", Bound::kNonNegative,
                  stochnav::reported_unit_name(quantity, ParameterDimension::kAnglePerRootTime)));
  params.k = to_natural(
      context.group, ParameterDimension::kRatePerRootTime,
      reader.axes_or("K", {0.0, 0.0, 0.0}, Bound::kNonNegative,
                     stochnav::reported_unit_name(quantity, ParameterDimension::kRatePerRootTime)));
  reader.finish();
  return std::make_unique<WhiteNoise>(context.group, params);
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_white(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  const bool with_walk = reader.boolean_or("rate_random_walk", false);
  reader.finish();
  const auto fit = stochnav::plugin::fit_white_walk(record, with_walk);
  WhiteParams params;
  params.n = fit.n;
  if (with_walk) params.k = fit.k;
  auto model = std::make_unique<WhiteNoise>(record.group, params);
  model->set_fit_quality(fit.quality);
  return model;
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("white",
                      "constant white sensor noise per axis (N), optional bias random walk (K)",
                      make_white, fit_white)
