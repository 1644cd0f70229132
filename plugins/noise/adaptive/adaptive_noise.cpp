// Noise plugin "adaptive": the white-noise level of a sensor group estimated on line from the
// filter's innovations (Sage-Husa with fading memory), the baseline that needs no noise model.
//
// Estimate (after each accepted measurement update at time t_k; noise_model_plugin.hpp
// UpdateFeedback): the process noise the innovation implies, minus the one the filter assumed,
//   dQ_k = K (z z^T - S) K^T  =  K z z^T K^T + P+ - P-         (n x n),
// restricted to the 3 x 3 block of the rows the group's white noise drives: attitude (gyro)
// or velocity (accel) of the core state (state_layout.hpp). That block's noise over the interval
// Delta_k = t_k - t_{k-1} since the previous update time was N^2 Delta_k I (navigation frame);
// the isotropic estimate (trace / 3 is invariant under the body-to-navigation rotation, so no
// axis mapping is needed, and the attitude block is too weakly observed for three separate
// levels) of the PSD is
//   s_k = N_{k-1}^2 + trace(dQ_k) / (3 Delta_k),
// blended with fading memory b ("forgetting"):
//   N_k^2 = clamp((1 - d_k) N_{k-1}^2 + d_k s_k, N_min^2, N_max^2),  d_k = (1 - b) / (1 - b^(k+1)),
// k = 1, 2, ... the update times so far (N_initial counts as the first sample; d_k -> 1 - b,
// a memory of about 1 / (1 - b) updates). Several aids at the same time add their dQ into one
// sample of that interval. Rejected updates (NIS gate) are ignored; the first update time only
// starts the clock (no interval yet).
// Discrete model over [t, t + dt]: Qw = N^2 dt I (N the current estimate), Qb = 0; no augmented
// states. Between updates N is constant, so steps compose exactly.
//
// params (reporting units: deg/sqrt(h) for gyros, m/s/sqrt(h) for accelerometers):
//   "N_initial"   starting level, > 0. Required.
//   "N_min"       lower clamp, >= 0. Default N_initial / 10.
//   "N_max"       upper clamp, >= N_initial. Default 100 N_initial.
//   "forgetting"  b in (0, 1). Default 0.98.
// params() writes this configuration, which restarts the estimator; equals() compares it (not
// the adapted level, which describe() reports).
// Fit params: the same keys except N_initial, which is the root-mean-square over the axes of N
// fitted (angle random walk with a bias-instability floor) to the calibration record's Allan
// variance; N_min, N_max default as above.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/calibration_fit.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/state_layout.hpp"
#include "stochnav/plugin/tabulated_noise_model.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"

namespace {

using stochnav::ParameterDimension;
using stochnav::plugin::Bound;
using stochnav::plugin::ParamUnit;
using stochnav::plugin::SensorGroup;

struct AdaptiveParams {
  double n_initial = 0.0;    ///< starting N, rad/sqrt(s) or m/s/sqrt(s)
  double n_min = 0.0;        ///< lower clamp of N, same units
  double n_max = 0.0;        ///< upper clamp of N, same units
  double forgetting = 0.98;  ///< fading-memory factor b, (0, 1)
};

const ParamUnit kLevelUnit = ParamUnit::of(ParameterDimension::kAnglePerRootTime);

const stochnav::plugin::ParamTable<AdaptiveParams> kAdaptiveTable{
    scalar(&AdaptiveParams::n_initial, "N_initial", kLevelUnit, Bound::kPositive,
           stochnav::plugin::kRequired, "starting level (fitters: fitted)"),
    scalar(&AdaptiveParams::n_min, "N_min", kLevelUnit, Bound::kNonNegative,
           stochnav::plugin::kDerived, "lower clamp, at most N_initial; default N_initial / 10"),
    scalar(&AdaptiveParams::n_max, "N_max", kLevelUnit, Bound::kPositive,
           stochnav::plugin::kDerived, "upper clamp, at least N_initial; default 100 N_initial"),
    scalar(&AdaptiveParams::forgetting, "forgetting", ParamUnit::fixed(""), Bound::kOpenUnit, 0.98,
           "fading-memory factor b"),
};

class AdaptiveNoise final : public stochnav::plugin::TabulatedNoiseModel<AdaptiveParams> {
 public:
  AdaptiveNoise(SensorGroup group, const AdaptiveParams& params)
      : TabulatedNoiseModel(group, kAdaptiveTable, params),
        psd_(params.n_initial * params.n_initial),
        interval_start_psd_(psd_) {}

  std::string_view type() const override { return "adaptive"; }
  bool time_varying() const override { return true; }

  void white_noise_covariance(double, double dt_s,
                              Eigen::Ref<Eigen::MatrixXd> q_white) const override {
    q_white.setZero();
    q_white.diagonal().setConstant(psd_ * dt_s);
  }

  void on_update(const stochnav::plugin::UpdateFeedback& feedback) override {
    if (!feedback.accepted) return;
    if (!(feedback.t_s == update_time_s_)) {  // a new update time (also the very first)
      interval_s_ = std::isfinite(update_time_s_) ? feedback.t_s - update_time_s_ : 0.0;
      update_time_s_ = feedback.t_s;
      interval_start_psd_ = psd_;
      interval_dq_trace_ = 0.0;
      if (interval_s_ > 0.0) ++updates_;
    }
    if (!(interval_s_ > 0.0)) return;
    const int rows = group() == SensorGroup::kGyro ? stochnav::plugin::core_state::kAttitude
                                                   : stochnav::plugin::core_state::kVelocity;
    const auto gain = feedback.gain.middleRows(rows, 3);
    // trace(K z z^T K^T) - trace(K S K^T), without forming the 3 x 3 products.
    const double explained = (gain * feedback.innovation).squaredNorm();
    const double predicted = (gain * feedback.innovation_covariance).cwiseProduct(gain).sum();
    interval_dq_trace_ += explained - predicted;

    const double sample = interval_start_psd_ + interval_dq_trace_ / (3.0 * interval_s_);
    const double b = parameters().forgetting;
    const double weight = (1.0 - b) / (1.0 - std::pow(b, static_cast<double>(updates_ + 1)));
    psd_ = std::clamp((1.0 - weight) * interval_start_psd_ + weight * sample,
                      parameters().n_min * parameters().n_min,
                      parameters().n_max * parameters().n_max);
  }

  std::string describe() const override {
    const std::string unit = stochnav::reported_unit_name(
        stochnav::plugin::sensor_quantity(group()), ParameterDimension::kAnglePerRootTime);
    return fmt::format(
        "adaptive ({}): Sage-Husa, forgetting {:.6g}; N = {:.6g} {} now (initial {:.6g}, "
        "clamps [{:.6g}, {:.6g}]) after {} update times",
        stochnav::plugin::sensor_group_name(group()), parameters().forgetting,
        reported(std::sqrt(psd_)), unit, reported(parameters().n_initial),
        reported(parameters().n_min), reported(parameters().n_max), updates_);
  }

 private:
  double reported(double natural) const {
    return stochnav::to_reported(stochnav::plugin::sensor_quantity(group()),
                                 ParameterDimension::kAnglePerRootTime, natural);
  }

  double psd_;                      ///< current N^2, rad^2/s or (m/s)^2/s
  double interval_start_psd_;       ///< N^2 before the updates of the current update time
  double interval_dq_trace_ = 0.0;  ///< sum of trace(dQ) over the current update time's aids
  double interval_s_ = 0.0;         ///< time since the previous update time (s)
  double update_time_s_ = -std::numeric_limits<double>::infinity();
  long updates_ = 0;  ///< update times with a known interval so far
};

/// Fills the clamps left to their defaults around N_initial (in reporting units, as given) and
/// checks N_min <= N_initial <= N_max; `pointer` is the params' JSON pointer.
AdaptiveParams complete(AdaptiveParams params, SensorGroup group, const std::string& pointer) {
  const auto quantity = stochnav::plugin::sensor_quantity(group);
  const double initial_reported = kLevelUnit.to_reported(quantity, params.n_initial);
  if (std::isnan(params.n_min)) {
    params.n_min = kLevelUnit.to_natural(quantity, initial_reported / 10.0);
  }
  if (std::isnan(params.n_max)) {
    params.n_max = kLevelUnit.to_natural(quantity, initial_reported * 100.0);
  }
  const std::string unit = kLevelUnit.name(quantity);
  if (params.n_min > params.n_initial) {
    throw stochnav::ConfigError(
        fmt::format("{}: found {:.6g}; expected at most N_initial = {} {}", pointer + "/N_min",
                    kLevelUnit.to_reported(quantity, params.n_min), initial_reported, unit));
  }
  if (params.n_max < params.n_initial) {
    throw stochnav::ConfigError(
        fmt::format("{}: found {:.6g}; expected at least N_initial = {} {}", pointer + "/N_max",
                    kLevelUnit.to_reported(quantity, params.n_max), initial_reported, unit));
  }
  return params;
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_adaptive(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  return std::make_unique<AdaptiveNoise>(
      context.group, complete(stochnav::plugin::parse_params(kAdaptiveTable, json, context),
                              context.group, context.params_pointer));
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_adaptive(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  stochnav::FitOptions options;
  options.terms = {stochnav::TermType::kAngleRandomWalk, stochnav::TermType::kBiasInstability};
  const auto fits = stochnav::plugin::fit_calibration_axes(record, options);
  double sum_of_squares = 0.0;
  for (const auto& fit : fits) {
    if (const auto* arw =
            stochnav::plugin::find_term(fit.model, stochnav::TermType::kAngleRandomWalk)) {
      const double n = std::get<stochnav::AngleRandomWalkTerm>(*arw).n;
      sum_of_squares += n * n;
    }
  }
  const double n_initial = std::sqrt(sum_of_squares / 3.0);
  if (!(n_initial > 0.0)) {
    throw stochnav::InputError(record.source +
                               ": no angle random walk could be fitted to start the adaptive "
                               "estimator; give N_initial with the factory instead");
  }
  // The factory's keys but N_initial, which the fit gives.
  static const auto kFitTable = kAdaptiveTable.without("N_initial");
  AdaptiveParams params = stochnav::plugin::parse_params(kFitTable, json, context);
  params.n_initial = n_initial;
  params = complete(params, record.group, context.params_pointer);
  auto model = std::make_unique<AdaptiveNoise>(record.group, params);
  model->set_fit_quality(stochnav::plugin::calibration_fit_quality(fits));
  return model;
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("adaptive",
                      "white noise level estimated on line from the innovations (Sage-Husa, "
                      "fading memory)",
                      make_adaptive, fit_adaptive)
STOCHNAV_PLUGIN_DOCUMENTATION_WITH_FIT(kAdaptiveTable, kAdaptiveTable.without("N_initial"))
