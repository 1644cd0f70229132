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
// false), "method": "avar" (default) | "gmwm", "start"/"fix"/"bound" (plugin/fit_steering.hpp,
// e.g. "fix": {"gauss_markov.tau_c": 300})}: the Gauss-Markov term (and the others) fitted per
// axis to the record's Allan variance, or by GMWM to its wavelet variance.

#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "stochnav/core/errors.hpp"
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

struct GaussMarkovParams {
  Axes sigma{};  ///< stationary standard deviation per axis, rad/s or m/s^2
  Axes tau_c{};  ///< correlation time per axis, s
  Axes n{};      ///< angle random walk per axis, rad/sqrt(s) or m/s/sqrt(s)
  Axes k{};      ///< rate random walk per axis, rad/s/sqrt(s) or m/s^2/sqrt(s)
};

const stochnav::plugin::ParamTable<GaussMarkovParams> kGaussMarkovTable{
    per_axis(&GaussMarkovParams::sigma, "sigma", ParamUnit::of(ParameterDimension::kRate),
             Bound::kPositive, stochnav::plugin::kRequired, "stationary standard deviation"),
    per_axis(&GaussMarkovParams::tau_c, "tau_c", ParamUnit::of(ParameterDimension::kTime),
             Bound::kPositive, stochnav::plugin::kRequired, "correlation time"),
    per_axis(&GaussMarkovParams::n, "N", ParamUnit::of(ParameterDimension::kAnglePerRootTime),
             Bound::kNonNegative, 0.0, "angle random walk (white part)"),
    per_axis(&GaussMarkovParams::k, "K", ParamUnit::of(ParameterDimension::kRatePerRootTime),
             Bound::kNonNegative, 0.0, "rate random walk of the core bias"),
};

struct GaussMarkovFitOptions {
  bool white = true;              ///< fit N too
  bool rate_random_walk = false;  ///< fit K too
  stochnav::plugin::TermFitOptions fit;  ///< method, start, fix, bound
};

const stochnav::plugin::ParamTable<GaussMarkovFitOptions> kGaussMarkovFitTable =
    stochnav::plugin::ParamTable<GaussMarkovFitOptions>{
        stochnav::plugin::flag(&GaussMarkovFitOptions::white, "white", true,
                               "fit the angle random walk N too"),
        stochnav::plugin::flag(&GaussMarkovFitOptions::rate_random_walk, "rate_random_walk", false,
                               "fit the rate random walk K too"),
    }
        .plus(lift(&GaussMarkovFitOptions::fit, stochnav::plugin::term_fit_table()));

class GaussMarkovNoise final : public stochnav::plugin::TabulatedNoiseModel<GaussMarkovParams> {
 public:
  GaussMarkovNoise(SensorGroup group, const GaussMarkovParams& params)
      : TabulatedNoiseModel(group, kGaussMarkovTable, params) {}

  std::string_view type() const override { return "gauss_markov"; }
  int augmented_size() const override { return 3; }

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

  void augmented_transition(double, double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                            Eigen::Ref<Eigen::MatrixXd> q_d) const override {
    // The filter steps with a constant dt: the exponentials are computed once per distinct dt
    // (an instance is used from one thread at a time, noise_model_plugin.hpp).
    if (dt_s != cached_dt_) {
      const GaussMarkovParams& p = parameters();
      for (int i = 0; i < 3; ++i) {
        cached_decay_[i] = std::exp(-dt_s / p.tau_c[i]);
        // 1 - exp(-2 dt / tau) without cancellation for small steps.
        cached_q_[i] = p.sigma[i] * p.sigma[i] * -std::expm1(-2.0 * dt_s / p.tau_c[i]);
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
    for (int i = 0; i < 3; ++i) p0(i, i) = parameters().sigma[i] * parameters().sigma[i];
  }

  void augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const override { map.setIdentity(); }

 private:
  mutable double cached_dt_ = std::numeric_limits<double>::quiet_NaN();
  mutable Axes cached_decay_{};  ///< exp(-dt / tau_c) per axis
  mutable Axes cached_q_{};      ///< sigma^2 (1 - exp(-2 dt / tau_c)) per axis, natural units^2
};

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_gauss_markov(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  return std::make_unique<GaussMarkovNoise>(
      context.group, stochnav::plugin::parse_params(kGaussMarkovTable, json, context));
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_gauss_markov(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  using stochnav::TermType;
  const auto fit_options = kGaussMarkovFitTable.parse(json, context.params_pointer);
  stochnav::FitOptions options;
  options.terms = {TermType::kGaussMarkov};
  if (fit_options.white) options.terms.push_back(TermType::kAngleRandomWalk);
  if (fit_options.rate_random_walk) options.terms.push_back(TermType::kRateRandomWalk);
  options.controls = fit_options.fit.steering.controls(options.terms, record.group);
  const auto fits = stochnav::plugin::fit_calibration_axes(record, options, fit_options.fit.method);
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
STOCHNAV_PLUGIN_DOCUMENTATION_WITH_FIT(kGaussMarkovTable, kGaussMarkovFitTable)
