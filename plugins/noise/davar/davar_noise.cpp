// Noise plugin "davar": the paper's time-varying white noise (Zhang et al. 2017). The dynamic
// Allan variance of each gyro axis is fitted window by window (Eqs. 7, 8; windowed_term_fit.hpp)
// and the angle random walk of each window sets the filter's process noise at that time
// (Eq. 24: Q_k = N(t_k)^2, a PSD; over a step Qw = int N(s)^2 ds).
//
// Modes (the difference matters; see the report of the recovery test):
//   "offline"  centred windows, analysis time = window centre (the paper's Eq. 3), N^2 linear
//              between analysis times. Post-processing: the value at t uses data up to half a
//              window after t, so a rise of the noise is anticipated by half a window (it starts
//              to show window/2 before it happens and is complete window/2 after).
//   "causal"   trailing windows, analysis time = window end, N^2 held from one analysis time to
//              the next: the value at t uses only data before t, as a tool running the filter
//              in real time could. A rise shows with a lag: it starts to show when it happens and
//              is complete one window later (half-level at about window/2 after the change).
// Before the first analysis time both modes hold the first window's value (a real-time tool
// would hold a prior until its first window completes); after the last, the last value.
//
// params (what the factory rebuilds; reporting units of DESIGN.md):
//   "mode"  "offline" | "causal". Default "offline".
//   "t"     analysis times (s), strictly ascending, at least one. Required.
//   "N"     [[x...], [y...], [z...]]: angle random walk per axis at each analysis time, >= 0:
//           deg/sqrt(h) (gyro), m/s/sqrt(h) (accel). Required.
//   "K"     rate random walk of the core bias (constant), >= 0: deg/h/sqrt(h), m/s/h/sqrt(h);
//           a number or [x, y, z]. Default 0.
// Qw(t, dt) = diag(int_t^{t+dt} N_axis(s)^2 ds), Qb = diag(K^2) dt; no augmented states.
//
// Fit params (the fitter runs the windowed fit on the calibration record):
//   "window_s"  window length (s), > 0. Default 60.
//   "step_s"    step between windows (s), > 0. Default 5.
//   "mode"      as above. Default "offline".
//   "terms"     Eq. 7 terms fitted in each window, among "Q", "N", "B", "K"; must hold "N".
//               Default ["N", "B"]: a window of 60 s is short for K, while B absorbs the flat
//               floor that the bias instability of a FOG puts on every window (fitting N alone
//               would read that floor as white noise).
//   "N_floor_fraction"  in [0, 1], default 0.1: per axis, windowed N below this fraction of the
//               median of the axis' positive N values are raised to it. In quiet windows where
//               the bias-instability floor dominates, the non-negative fit may drop N entirely;
//               Q = 0 would make the filter trust the gyro blindly there.
//   "spin_axis" "none" (default), "x", "y" or "z": the body axis a tool spins about (an MWD
//               tool drilling at 60 rpm: "z"). The gyro axes across it see the steady rates
//               around them (Earth rate) as a sinusoid at the spin frequency; that motion is
//               fitted and removed window by window before their DAVAR (spin_motion.hpp).
//               Gyro only.
//   "floor_tau_s"  (s, >= 0) default 0: N(t) alone, the paper's Q. When > 0 (needs "B" in
//               terms), each window's white level is raised to meet its fitted bias-instability
//               floor at that tau: N_eff^2 = N^2 + (2 ln 2 / pi) B^2 floor_tau_s — the
//               floor-matched rule of the white plugin (calibration_fit.hpp) window by window.
//               For a sensor whose short-term noise is the floor (a FOG's flicker), N alone
//               leaves the filter's attitude sigma far below its error.
//   "rate_random_walk"  bool, default false: fit K once over the whole record (Ceres fit of
//               N and K, as the white plugin, plugin/calibration_fit.hpp) for
//               bias_walk_covariance. "rate_random_walk_end_s" (s, > 0) fits it over the
//               record before that time only (a static calibration span): over a record with
//               a noise episode the episode's energy at long taus reads as a rate random walk.
//               The bias instability B itself is not given to the
//               filter (it would need Gauss-Markov states; the classic filter omits it too).
//               "method" ("avar" | "gmwm") and "start"/"fix"/"bound" (plugin/fit_steering.hpp;
//               terms angle_random_walk, rate_random_walk) steer that N + K fit and need
//               "rate_random_walk": true; the windows' Eq. 7 fit is linear and takes neither.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "noise_level_series.hpp"
#include "spin_motion.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/model/reporting_units.hpp"
#include "stochnav/plugin/calibration_fit.hpp"
#include "stochnav/plugin/fit_steering.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"
#include "stochnav/plugin/tabulated_noise_model.hpp"
#include "windowed_term_fit.hpp"

namespace {

using stochnav::ParameterDimension;
using stochnav::davar_noise::Interpolation;
using stochnav::davar_noise::NoiseLevelSeries;
using stochnav::plugin::SensorGroup;
using Axes = std::array<double, 3>;
using AxisSeries = std::array<std::vector<double>, 3>;

struct DavarParams {
  bool causal = false;
  std::vector<double> time_s;  ///< analysis times (s), strictly ascending
  AxisSeries n;                ///< angle random walk per axis and time, natural units
  Axes k{};                    ///< rate random walk per axis, natural units
};

using stochnav::plugin::Bound;
using stochnav::plugin::ParamUnit;

const auto kModeEntry = [](auto member) {
  return stochnav::plugin::choice(member, "mode", {{"offline", false}, {"causal", true}}, false,
                                  "centred windows (offline) or trailing windows (causal)");
};

const stochnav::plugin::ParamTable<DavarParams> kDavarTable{
    kModeEntry(&DavarParams::causal),
    series(&DavarParams::time_s, "t", ParamUnit::fixed("s"), {.ascending = true}, "analysis times"),
    axis_series(&DavarParams::n, "N", ParamUnit::of(ParameterDimension::kAnglePerRootTime),
                Bound::kNonNegative, &DavarParams::time_s, "t",
                "angle random walk at each analysis time"),
    per_axis(&DavarParams::k, "K", ParamUnit::of(ParameterDimension::kRatePerRootTime),
             Bound::kNonNegative, 0.0, "rate random walk of the core bias"),
};

NoiseLevelSeries level_series(const DavarParams& params) {
  AxisSeries psd;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    for (double n : params.n[axis]) psd[axis].push_back(n * n);
  }
  return NoiseLevelSeries(params.time_s, std::move(psd),
                          params.causal ? Interpolation::kHold : Interpolation::kLinear);
}

class DavarNoise final : public stochnav::plugin::TabulatedNoiseModel<DavarParams> {
 public:
  DavarNoise(SensorGroup group, const DavarParams& params)
      : TabulatedNoiseModel(group, kDavarTable, params), levels_(level_series(params)) {}

  std::string_view type() const override { return "davar"; }
  bool time_varying() const override { return true; }

  void white_noise_covariance(double t_s, double dt_s,
                              Eigen::Ref<Eigen::MatrixXd> q_white) const override {
    q_white.setZero();
    q_white.diagonal() = levels_.integral(t_s, dt_s);
  }

  void bias_walk_covariance(double, double dt_s,
                            Eigen::Ref<Eigen::MatrixXd> q_bias) const override {
    q_bias.setZero();
    for (int i = 0; i < 3; ++i) q_bias(i, i) = parameters().k[i] * parameters().k[i] * dt_s;
  }

 private:
  NoiseLevelSeries levels_;
};

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_davar(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  return std::make_unique<DavarNoise>(context.group,
                                      stochnav::plugin::parse_params(kDavarTable, json, context));
}

using stochnav::davar_noise::WindowTerm;

struct DavarFitOptions {
  double window_s = 60.0;
  double step_s = 5.0;
  bool causal = false;
  std::vector<WindowTerm> terms;
  bool rate_random_walk = false;
  double rate_random_walk_end_s = 0.0;  ///< 0: the whole record
  double n_floor_fraction = 0.1;
  int spin_axis = -1;        ///< body axis the tool spins about (0 x, 1 y, 2 z), -1: none
  double floor_tau_s = 0.0;  ///< 0: N(t) alone; > 0: N raised to the window's floor there
  /// method, start, fix, bound of the whole-record N + K fit (rate_random_walk)
  stochnav::plugin::TermFitOptions walk_fit;
};

/// Allan variance of a bias-instability floor per B^2: 2 ln 2 / pi.
constexpr double kFloorAvarPerB2 = 2.0 * std::numbers::ln2 / std::numbers::pi;

const stochnav::plugin::ParamTable<DavarFitOptions> kDavarFitTable =
    stochnav::plugin::ParamTable<DavarFitOptions>{
        scalar(&DavarFitOptions::window_s, "window_s", ParamUnit::fixed("s"), Bound::kPositive,
               60.0, "DAVAR window length"),
        scalar(&DavarFitOptions::step_s, "step_s", ParamUnit::fixed("s"), Bound::kPositive, 5.0,
               "step between windows"),
        kModeEntry(&DavarFitOptions::causal),
        stochnav::plugin::choices(&DavarFitOptions::terms, "terms",
                                  {{"Q", WindowTerm::kQuantization},
                                   {"N", WindowTerm::kAngleRandomWalk},
                                   {"B", WindowTerm::kBiasInstability},
                                   {"K", WindowTerm::kRateRandomWalk}},
                                  {WindowTerm::kAngleRandomWalk, WindowTerm::kBiasInstability},
                                  "Eq. 7 terms fitted in each window; must hold \"N\""),
        stochnav::plugin::flag(&DavarFitOptions::rate_random_walk, "rate_random_walk", false,
                               "fit K once over the record"),
        scalar(&DavarFitOptions::rate_random_walk_end_s, "rate_random_walk_end_s",
               ParamUnit::fixed("s"), Bound::kNonNegative, 0.0,
               "fit K over the record before this time only (0: all of it)"),
        scalar(&DavarFitOptions::n_floor_fraction, "N_floor_fraction", ParamUnit::fixed(""),
               Bound::kNonNegative, 0.1,
               "at most 1: windowed N raised to this fraction of the axis' median"),
        stochnav::plugin::choice(
            &DavarFitOptions::spin_axis, "spin_axis", {{"none", -1}, {"x", 0}, {"y", 1}, {"z", 2}},
            -1, "body axis the tool spins about: its motion is removed first (gyro)"),
        scalar(&DavarFitOptions::floor_tau_s, "floor_tau_s", ParamUnit::fixed("s"),
               Bound::kNonNegative, 0.0,
               "each window's N raised to meet its fitted floor B at this tau (0: off)"),
    }
        .plus(lift(&DavarFitOptions::walk_fit, stochnav::plugin::term_fit_table()));

// The samples of `record` before end_s (s, record time), all of it when end_s is past its end.
stochnav::plugin::CalibrationRecord leading_part(const stochnav::plugin::CalibrationRecord& record,
                                                 double end_s) {
  stochnav::plugin::CalibrationRecord part = record;
  const double samples = std::floor((end_s - record.start_time_s) * record.rate_hz);
  for (auto& axis : part.axes) {
    if (samples >= 0.0 && samples < static_cast<double>(axis.size())) {
      axis.resize(static_cast<std::size_t>(samples));
    }
  }
  part.source += fmt::format(" (before {} s)", end_s);
  return part;
}

// Raises values below floor_fraction x (median of the positive values) to that floor.
void raise_to_floor(std::vector<double>& values, double floor_fraction) {
  std::vector<double> positive;
  for (double v : values) {
    if (v > 0.0) positive.push_back(v);
  }
  if (positive.empty()) return;
  const auto middle = positive.begin() + static_cast<std::ptrdiff_t>(positive.size() / 2);
  std::nth_element(positive.begin(), middle, positive.end());
  const double floor = floor_fraction * *middle;
  for (double& v : values) v = std::max(v, floor);
}

std::size_t samples_for(double seconds, double rate_hz) {
  return static_cast<std::size_t>(std::llround(seconds * rate_hz));
}

/// Replaces the DAVAR of the two axes across `spin_axis` by that of their spin-free residuals
/// and the spin axis' own where its rate was not steady (spin_motion.hpp), on the windows and
/// factors of the spin axis' own DAVAR.
void remove_spin_motion(const stochnav::plugin::CalibrationRecord& record, std::size_t spin_axis,
                        const stochnav::davar_noise::WindowFitOptions& options,
                        std::array<stochnav::DavarResult, 3>& deviations) {
  const auto across = stochnav::davar_noise::cross_axes(spin_axis);
  auto windows = stochnav::davar_noise::spin_free_window_deviations(
      record.axes[across[0]], record.axes[across[1]], record.axes[spin_axis], record.rate_hz,
      options.window, options.step, deviations[spin_axis].m);
  stochnav::davar_noise::replace_unsteady_spin_rows(deviations[spin_axis].adev, windows);
  for (std::size_t j = 0; j < 2; ++j) {
    deviations[across[j]] = deviations[spin_axis];
    deviations[across[j]].adev = std::move(windows.cross[j]);
  }
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> fit_davar(
    const stochnav::plugin::CalibrationRecord& record, const nlohmann::json& json,
    const stochnav::plugin::NoiseModelContext& context) {
  const auto fit = kDavarFitTable.parse(json, context.params_pointer);
  const std::string pointer = context.params_pointer;
  if (std::find(fit.terms.begin(), fit.terms.end(), WindowTerm::kAngleRandomWalk) ==
      fit.terms.end()) {
    throw stochnav::ConfigError(fmt::format(
        "{}/terms: found {}; expected an array of distinct terms among \"Q\", \"N\", \"B\", "
        "\"K\" that holds \"N\"",
        pointer, kDavarFitTable.to_json(fit)["terms"].dump()));
  }
  if (!fit.rate_random_walk && (json.contains("method") || !fit.walk_fit.steering.empty())) {
    // The windows' Eq. 7 fit is linear least squares: only the N + K fit is steered.
    throw stochnav::ConfigError(
        fmt::format("{}/{}: steers the whole-record N + K fit; add \"rate_random_walk\": true, or "
                    "remove it (the windows' Eq. 7 fit takes neither)",
                    pointer, json.contains("method") ? "method" : "start, fix, bound"));
  }
  if (fit.n_floor_fraction > 1.0) {
    throw stochnav::ConfigError(
        fmt::format("{}/N_floor_fraction: found {}; expected a number in "
                    "[0, 1]",
                    pointer, fit.n_floor_fraction));
  }
  if (fit.spin_axis >= 0 && record.group != SensorGroup::kGyro) {
    throw stochnav::ConfigError(fmt::format(
        "{}/spin_axis: found \"{}\"; the spin angle comes from the gyro, so spin_axis applies to "
        "the gyro model only: remove it from the accelerometer's fit params",
        pointer, kDavarFitTable.to_json(fit)["spin_axis"].get<std::string>()));
  }
  if (fit.floor_tau_s > 0.0 && std::find(fit.terms.begin(), fit.terms.end(),
                                         WindowTerm::kBiasInstability) == fit.terms.end()) {
    throw stochnav::ConfigError(
        fmt::format("{}/floor_tau_s: found {}; the floor comes from the windows' fitted B: add "
                    "\"B\" to \"terms\" or set floor_tau_s to 0",
                    pointer, fit.floor_tau_s));
  }
  stochnav::davar_noise::WindowFitOptions options;
  options.terms = fit.terms;
  options.window = samples_for(fit.window_s, record.rate_hz);
  options.step = std::max<std::size_t>(1, samples_for(fit.step_s, record.rate_hz));
  options.causal = fit.causal;
  if (options.window < 16) {
    throw stochnav::ConfigError(fmt::format(
        "{}/window_s: found {}; expected a window of at least 16 samples ({:.6g} s at {:.6g} Hz)",
        pointer, fit.window_s, 16.0 / record.rate_hz, record.rate_hz));
  }

  const bool spinning = fit.spin_axis >= 0;
  const auto spin_axis = static_cast<std::size_t>(std::max(fit.spin_axis, 0));
  std::array<stochnav::DavarResult, 3> deviations;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (spinning && axis != spin_axis) continue;
    try {
      deviations[axis] = stochnav::davar_noise::window_deviations(
          record.axes[axis], record.rate_hz, record.start_time_s, options);
    } catch (const stochnav::InputError& error) {
      throw stochnav::InputError(record.source + ": " + error.what());
    }
  }
  if (spinning) remove_spin_motion(record, spin_axis, options, deviations);

  DavarParams params;
  params.causal = fit.causal;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    auto series = stochnav::davar_noise::fit_window_deviations(deviations[axis], options);
    if (axis == 0) params.time_s = series.time_s;
    params.n[axis] = std::move(series.angle_random_walk);
    if (fit.floor_tau_s > 0.0) {
      // The white level whose Allan variance at floor_tau_s equals the window's N and B.
      for (std::size_t j = 0; j < params.n[axis].size(); ++j) {
        const double b = series.bias_instability[j];
        params.n[axis][j] = std::sqrt(params.n[axis][j] * params.n[axis][j] +
                                      kFloorAvarPerB2 * b * b * fit.floor_tau_s);
      }
    }
    raise_to_floor(params.n[axis], fit.n_floor_fraction);
  }
  nlohmann::json quality;  // the windows' DAVAR fits are not summarised: null without K
  if (fit.rate_random_walk) {
    // N and K only, as the white plugin fits them (with its floor-matched rule when the fit
    // fails): B is not given to the filter, so K must absorb the bias wander that B would
    // otherwise take.
    const auto walk = stochnav::plugin::fit_white_walk(
        fit.rate_random_walk_end_s > 0.0 ? leading_part(record, fit.rate_random_walk_end_s)
                                         : record,
        true, fit.walk_fit.method,
        fit.walk_fit.steering.controls(
            std::vector{stochnav::TermType::kAngleRandomWalk, stochnav::TermType::kRateRandomWalk},
            record.group));
    params.k = walk.k;
    quality = {{"rate_random_walk_fit", walk.quality}};
  }
  auto model = std::make_unique<DavarNoise>(record.group, params);
  model->set_fit_quality(std::move(quality));
  return model;
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("davar",
                      "time-varying white noise N(t) from windowed Allan-variance fits (DAVAR, "
                      "offline or causal)",
                      make_davar, fit_davar)
STOCHNAV_PLUGIN_DOCUMENTATION_WITH_FIT(kDavarTable, kDavarFitTable)
