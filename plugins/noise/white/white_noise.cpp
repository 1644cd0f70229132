// Noise plugin "white": constant white sensor noise per axis from datasheet values, with an
// optional rate random walk of the core bias block (the paper's classic filter).
//
// params (reporting units of DESIGN.md; a number applies to all axes, or [x, y, z]):
//   "N"  angle random walk, >= 0: deg/sqrt(h) (gyro), m/s/sqrt(h) (accel). Required.
//   "K"  rate random walk, >= 0: deg/h/sqrt(h) (gyro), m/s/h/sqrt(h) (accel). Default 0.
// Discrete model over [t, t + dt]: Qw = diag(N^2) dt, Qb = diag(K^2) dt (natural units); no
// augmented states.
// Fit params: {"rate_random_walk": bool (default false: fit N only), "method": "avar" (default)
// | "gmwm", "start"/"fix"/"bound" (plugin/fit_steering.hpp, e.g. "bound": {"rate_random_walk.K":
// [0.001, 0.1]})}; fits N (and K) per axis to the record's Allan variance or by GMWM to its
// wavelet variance; a failed N + K fit (a flicker floor: K on its bound or a
// chi-square far beyond its dof) uses the floor-matched rule of plugin/calibration_fit.hpp
// (fit_white_walk), reported in fit_quality().

#include <array>
#include <memory>
#include <vector>

#include "stochnav/plugin/calibration_fit.hpp"
#include "stochnav/plugin/fit_steering.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"
#include "stochnav/plugin/tabulated_noise_model.hpp"

namespace {

using stochnav::ParameterDimension;
using stochnav::plugin::Bound;
using stochnav::plugin::ParamUnit;
using stochnav::plugin::SensorGroup;
using Axes = std::array<double, 3>;

struct WhiteParams {
  Axes n{};  ///< angle random walk per axis, rad/sqrt(s) or m/s/sqrt(s)
  Axes k{};  ///< rate random walk per axis, rad/s/sqrt(s) or m/s^2/sqrt(s)
};

const stochnav::plugin::ParamTable<WhiteParams> kWhiteTable{
    per_axis(&WhiteParams::n, "N", ParamUnit::of(ParameterDimension::kAnglePerRootTime),
             Bound::kNonNegative, stochnav::plugin::kRequired, "angle random walk"),
    per_axis(&WhiteParams::k, "K", ParamUnit::of(ParameterDimension::kRatePerRootTime),
             Bound::kNonNegative, 0.0, "rate random walk of the core bias"),
};

struct WhiteFitOptions {
  bool rate_random_walk = false;  ///< fit K as well as N
  stochnav::plugin::TermFitOptions fit;  ///< method, start, fix, bound
};

const stochnav::plugin::ParamTable<WhiteFitOptions> kWhiteFitTable =
    stochnav::plugin::ParamTable<WhiteFitOptions>{
        stochnav::plugin::flag(&WhiteFitOptions::rate_random_walk, "rate_random_walk", false,
                               "fit the rate random walk K as well as N"),
    }
        .plus(lift(&WhiteFitOptions::fit, stochnav::plugin::term_fit_table()));

class WhiteNoise final : public stochnav::plugin::TabulatedNoiseModel<WhiteParams> {
 public:
  WhiteNoise(SensorGroup group, const WhiteParams& params)
      : TabulatedNoiseModel(group, kWhiteTable, params) {}

  std::string_view type() const override { return "white"; }

  void white_noise_covariance(double, double dt_s,
                              Eigen::Ref<Eigen::MatrixXd> q_white) const override {
    q_white.setZero();
    for (int i = 0; i < 3; ++i) q_white(i, i) = parameters().n[i] * parameters().n[i] * dt_s;
  }

  void bias_walk_covariance(double, double dt_s,
                            Eigen::Ref<Eigen::MatrixXd> q_bias) const override {
    q_bias.setZero();
    for (int i = 0; i < 3; ++i) q_bias(i, i) = parameters().k[i] * parameters().k[i] * dt_s;
  }
};

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_white(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  return std::make_unique<WhiteNoise>(context.group,
                                      stochnav::plugin::parse_params(kWhiteTable, json, context));
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_white(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  const auto fit_options = kWhiteFitTable.parse(json, context.params_pointer);
  const bool with_walk = fit_options.rate_random_walk;
  std::vector<stochnav::TermType> terms = {stochnav::TermType::kAngleRandomWalk};
  if (with_walk) terms.push_back(stochnav::TermType::kRateRandomWalk);
  const auto fit =
      stochnav::plugin::fit_white_walk(record, with_walk, fit_options.fit.method,
                                       fit_options.fit.steering.controls(terms, record.group));
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
STOCHNAV_PLUGIN_DOCUMENTATION_WITH_FIT(kWhiteTable, kWhiteFitTable)
