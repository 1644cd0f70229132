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

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "noise_level_series.hpp"
#include "spin_motion.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/model/reporting_units.hpp"
#include "stochnav/plugin/calibration_fit.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/param_table.hpp"
#include "stochnav/plugin/params.hpp"
#include "windowed_term_fit.hpp"

namespace {

using stochnav::ParameterDimension;
using stochnav::davar_noise::Interpolation;
using stochnav::davar_noise::NoiseLevelSeries;
using stochnav::davar_noise::WindowTerm;
using stochnav::plugin::SensorGroup;
using Axes = std::array<double, 3>;
using AxisSeries = std::array<std::vector<double>, 3>;

constexpr std::string_view kModes[] = {"offline", "causal"};
constexpr std::string_view kSpinAxes[] = {"none", "x", "y", "z"};
/// Allan variance of a bias-instability floor per B^2: 2 ln 2 / pi.
constexpr double kFloorAvarPerB2 = 2.0 * std::numbers::ln2 / std::numbers::pi;

struct DavarParams {
  bool causal = false;
  std::vector<double> time_s;  ///< analysis times (s), strictly ascending
  AxisSeries n;                ///< angle random walk per axis and time, natural units
  Axes k{};                    ///< rate random walk per axis, natural units
};

using stochnav::plugin::parameters_close;

// The constant parameters; the analysis times and N(t) are series, read below.
const stochnav::plugin::ParamTable<DavarParams> kConstantTable{
    per_axis(&DavarParams::k, "K",
             stochnav::plugin::ParamUnit::of(ParameterDimension::kRatePerRootTime),
             stochnav::plugin::Bound::kNonNegative, 0.0, "rate random walk of the core bias"),
};

NoiseLevelSeries level_series(const DavarParams& params) {
  AxisSeries psd;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    for (double n : params.n[axis]) psd[axis].push_back(n * n);
  }
  return NoiseLevelSeries(params.time_s, std::move(psd),
                          params.causal ? Interpolation::kHold : Interpolation::kLinear);
}

class DavarNoise final : public stochnav::plugin::NoiseModelPlugin {
 public:
  DavarNoise(SensorGroup group, DavarParams params)
      : NoiseModelPlugin(group), params_(std::move(params)), levels_(level_series(params_)) {}

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
    for (int i = 0; i < 3; ++i) q_bias(i, i) = params_.k[i] * params_.k[i] * dt_s;
  }

  nlohmann::json params() const override {
    nlohmann::json n = nlohmann::json::array();
    for (std::size_t axis = 0; axis < 3; ++axis) {
      nlohmann::json values = nlohmann::json::array();
      for (double value : params_.n[axis]) {
        values.push_back(reported(ParameterDimension::kAnglePerRootTime, value));
      }
      n.push_back(std::move(values));
    }
    nlohmann::json out =
        kConstantTable.to_json(params_, stochnav::plugin::sensor_quantity(group()));
    out["mode"] = params_.causal ? "causal" : "offline";
    out["t"] = params_.time_s;
    out["N"] = std::move(n);
    return out;
  }

  std::string describe() const override {
    std::string text = fmt::format("davar ({}): {}, {} analysis times over [{:.6g}, {:.6g}] s;",
                                   stochnav::plugin::sensor_group_name(group()),
                                   params_.causal ? "causal" : "offline", params_.time_s.size(),
                                   params_.time_s.front(), params_.time_s.back());
    const char* axis_names[] = {"x", "y", "z"};
    const std::string n_unit = reported_unit(ParameterDimension::kAnglePerRootTime);
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const auto [low, high] = std::minmax_element(params_.n[axis].begin(), params_.n[axis].end());
      text += fmt::format(" {}: N = {:.6g} .. {:.6g} {}, K = {:.6g} {};", axis_names[axis],
                          reported(ParameterDimension::kAnglePerRootTime, *low),
                          reported(ParameterDimension::kAnglePerRootTime, *high), n_unit,
                          reported(ParameterDimension::kRatePerRootTime, params_.k[axis]),
                          reported_unit(ParameterDimension::kRatePerRootTime));
    }
    text.pop_back();
    return text;
  }

  bool equals(const NoiseModelPlugin& other, double rel_tol) const override {
    const auto* that = dynamic_cast<const DavarNoise*>(&other);
    if (that == nullptr || that->group() != group()) return false;
    const DavarParams& a = params_;
    const DavarParams& b = that->params_;
    if (a.causal != b.causal || a.time_s.size() != b.time_s.size()) return false;
    for (std::size_t j = 0; j < a.time_s.size(); ++j) {
      if (!parameters_close(a.time_s[j], b.time_s[j], rel_tol)) return false;
      for (std::size_t axis = 0; axis < 3; ++axis) {
        if (!parameters_close(a.n[axis][j], b.n[axis][j], rel_tol)) return false;
      }
    }
    return kConstantTable.equal(a, b, rel_tol);
  }

 private:
  DavarParams params_;
  NoiseLevelSeries levels_;
};

[[noreturn]] void reject(const std::string& pointer, const nlohmann::json& found,
                         std::string_view expected) {
  throw stochnav::ConfigError(
      fmt::format("{}: found {}; expected {}", pointer, found.dump(), expected));
}

/// "t": finite, strictly ascending, at least one.
std::vector<double> read_times(stochnav::plugin::ParamReader& reader) {
  const nlohmann::json& json = reader.raw("t");
  const std::string pointer = reader.pointer("t");
  if (json.is_null()) reject(pointer, json, "an array of analysis times (s)");
  if (!json.is_array() || json.empty()) reject(pointer, json, "a non-empty array of times (s)");
  std::vector<double> times;
  for (std::size_t j = 0; j < json.size(); ++j) {
    const auto& value = json[j];
    if (!value.is_number() || !std::isfinite(value.get<double>()) ||
        (j > 0 && !(value.get<double>() > times.back()))) {
      reject(pointer + "/" + std::to_string(j), value,
             "a finite time (s) greater than the one before");
    }
    times.push_back(value.get<double>());
  }
  return times;
}

/// "N": three arrays of `count` values >= 0 in reporting units, returned in natural units.
AxisSeries read_levels(stochnav::plugin::ParamReader& reader, SensorGroup group,
                       std::size_t count) {
  const auto quantity = stochnav::plugin::sensor_quantity(group);
  const std::string unit =
      stochnav::reported_unit_name(quantity, ParameterDimension::kAnglePerRootTime);
  const nlohmann::json& json = reader.raw("N");
  const std::string pointer = reader.pointer("N");
  if (!json.is_array() || json.size() != 3) {
    reject(pointer, json,
           fmt::format("[[x...], [y...], [z...]], {} values of N ({}) per axis", count, unit));
  }
  AxisSeries levels;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const auto& values = json[axis];
    const std::string axis_pointer = pointer + "/" + std::to_string(axis);
    if (!values.is_array() || values.size() != count) {
      reject(axis_pointer, values,
             fmt::format("an array of {} values (one per analysis time in /t)", count));
    }
    for (std::size_t j = 0; j < count; ++j) {
      const auto& value = values[j];
      if (!value.is_number() || !std::isfinite(value.get<double>()) || value.get<double>() < 0.0) {
        reject(axis_pointer + "/" + std::to_string(j), value,
               fmt::format("a number >= 0 ({})", unit));
      }
      levels[axis].push_back(stochnav::to_natural(quantity, ParameterDimension::kAnglePerRootTime,
                                                  value.get<double>()));
    }
  }
  return levels;
}

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_davar(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  DavarParams params;
  params.causal = reader.choice_or("mode", "offline", kModes) == "causal";
  params.time_s = read_times(reader);
  params.n = read_levels(reader, context.group, params.time_s.size());
  kConstantTable.read(reader, stochnav::plugin::sensor_quantity(context.group), params);
  reader.finish();
  return std::make_unique<DavarNoise>(context.group, std::move(params));
}

std::vector<stochnav::davar_noise::WindowTerm> read_terms(stochnav::plugin::ParamReader& reader) {
  const nlohmann::json& json = reader.raw("terms");
  if (json.is_null()) return {WindowTerm::kAngleRandomWalk, WindowTerm::kBiasInstability};
  const std::string pointer = reader.pointer("terms");
  constexpr std::string_view kExpected =
      "an array of distinct terms among \"Q\", \"N\", \"B\", "
      "\"K\" that holds \"N\"";
  if (!json.is_array()) reject(pointer, json, kExpected);
  std::vector<WindowTerm> terms;
  for (std::size_t j = 0; j < json.size(); ++j) {
    const std::string name = json[j].is_string() ? json[j].get<std::string>() : "";
    WindowTerm term = WindowTerm::kAngleRandomWalk;
    if (name == "Q") {
      term = WindowTerm::kQuantization;
    } else if (name == "N") {
      term = WindowTerm::kAngleRandomWalk;
    } else if (name == "B") {
      term = WindowTerm::kBiasInstability;
    } else if (name == "K") {
      term = WindowTerm::kRateRandomWalk;
    } else {
      reject(pointer + "/" + std::to_string(j), json[j], kExpected);
    }
    if (std::find(terms.begin(), terms.end(), term) != terms.end()) {
      reject(pointer + "/" + std::to_string(j), json[j], kExpected);
    }
    terms.push_back(term);
  }
  if (std::find(terms.begin(), terms.end(), WindowTerm::kAngleRandomWalk) == terms.end()) {
    reject(pointer, json, kExpected);
  }
  return terms;
}

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

/// "spin_axis": "none" (default) or the body axis the tool spins about; gyro only (the spin
/// angle comes from the gyro's own axis).
std::optional<std::size_t> read_spin_axis(stochnav::plugin::ParamReader& reader,
                                          SensorGroup group) {
  const std::string name = reader.choice_or("spin_axis", "none", kSpinAxes);
  if (name == "none") return std::nullopt;
  if (group != SensorGroup::kGyro) {
    throw stochnav::ConfigError(fmt::format(
        "{}: found \"{}\"; the spin angle comes from the gyro, so spin_axis applies to the gyro "
        "model only: remove it from the accelerometer's fit params",
        reader.pointer("spin_axis"), name));
  }
  return static_cast<std::size_t>(name[0] - 'x');
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
  using stochnav::plugin::Bound;
  stochnav::plugin::ParamReader reader(json, context.params_pointer);
  const double window_s = reader.number_or("window_s", 60.0, Bound::kPositive, "s");
  const double step_s = reader.number_or("step_s", 5.0, Bound::kPositive, "s");
  const bool causal = reader.choice_or("mode", "offline", kModes) == "causal";
  stochnav::davar_noise::WindowFitOptions options;
  options.terms = read_terms(reader);
  const bool with_walk = reader.boolean_or("rate_random_walk", false);
  const double walk_end_s =
      reader.number_or("rate_random_walk_end_s", 0.0, Bound::kNonNegative, "s");
  const double floor_fraction = reader.number_or("N_floor_fraction", 0.1, Bound::kNonNegative, "");
  if (floor_fraction > 1.0) {
    throw stochnav::ConfigError(fmt::format("{}: found {}; expected a number in [0, 1]",
                                            reader.pointer("N_floor_fraction"), floor_fraction));
  }
  const auto spin_axis = read_spin_axis(reader, record.group);
  const double floor_tau_s = reader.number_or("floor_tau_s", 0.0, Bound::kNonNegative, "s");
  if (floor_tau_s > 0.0 && std::ranges::find(options.terms, WindowTerm::kBiasInstability) ==
                               options.terms.end()) {
    throw stochnav::ConfigError(
        fmt::format("{}: found {}; the floor comes from the windows' fitted B: add \"B\" to "
                    "\"terms\" or set floor_tau_s to 0",
                    reader.pointer("floor_tau_s"), floor_tau_s));
  }
  reader.finish();
  options.window = samples_for(window_s, record.rate_hz);
  options.step = std::max<std::size_t>(1, samples_for(step_s, record.rate_hz));
  options.causal = causal;
  if (options.window < 16) {
    throw stochnav::ConfigError(fmt::format(
        "{}: found {}; expected a window of at least 16 samples ({:.6g} s at {:.6g} Hz)",
        reader.pointer("window_s"), window_s, 16.0 / record.rate_hz, record.rate_hz));
  }

  DavarParams params;
  params.causal = causal;
  std::array<stochnav::DavarResult, 3> deviations;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (spin_axis && axis != *spin_axis) continue;
    try {
      deviations[axis] = stochnav::davar_noise::window_deviations(
          record.axes[axis], record.rate_hz, record.start_time_s, options);
    } catch (const stochnav::InputError& error) {
      throw stochnav::InputError(record.source + ": " + error.what());
    }
  }
  if (spin_axis) remove_spin_motion(record, *spin_axis, options, deviations);
  for (std::size_t axis = 0; axis < 3; ++axis) {
    auto series = stochnav::davar_noise::fit_window_deviations(deviations[axis], options);
    if (axis == 0) params.time_s = series.time_s;
    params.n[axis] = std::move(series.angle_random_walk);
    if (floor_tau_s > 0.0) {
      // The white level whose Allan variance at floor_tau_s equals the window's N and B.
      for (std::size_t j = 0; j < params.n[axis].size(); ++j) {
        const double b = series.bias_instability[j];
        params.n[axis][j] = std::sqrt(params.n[axis][j] * params.n[axis][j] +
                                      kFloorAvarPerB2 * b * b * floor_tau_s);
      }
    }
    raise_to_floor(params.n[axis], floor_fraction);
  }
  nlohmann::json quality;  // the windows' DAVAR fits are not summarised: null without K
  if (with_walk) {
    // N and K only, as the white plugin fits them (with its floor-matched rule when the fit
    // fails): B is not given to the filter, so K must absorb the bias wander that B would
    // otherwise take.
    const auto fit = stochnav::plugin::fit_white_walk(
        walk_end_s > 0.0 ? leading_part(record, walk_end_s) : record, true);
    params.k = fit.k;
    quality = {{"rate_random_walk_fit", fit.quality}};
  }
  auto model = std::make_unique<DavarNoise>(record.group, std::move(params));
  model->set_fit_quality(std::move(quality));
  return model;
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("davar",
                      "time-varying white noise N(t) from windowed Allan-variance fits (DAVAR, "
                      "offline or causal)",
                      make_davar, fit_davar)
