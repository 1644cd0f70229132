// Noise plugin "oracle": the true noise of a simulated scenario, as the simulator drew it (read
// from the scenario's scenario.json): the bound no fitted model can beat.
//
// params:
//   "scenario"      folder of the simulated scenario (relative to the config file); default the
//                   run's own scenario (NoiseModelContext::scenario_dir).
//   "fold_below_s"  first-order states faster than this (s) become white noise, >= 0, default 0.1
//                   (the filter's covariance interval; model/shaping_filter.hpp says why).
// Per axis:
//   white noise  the angle random walk of the sensor's constant and scheduled models, the latter
//                times the phase scale squared: Qw(t, dt) is the exact integral of that piecewise
//                constant PSD over [t, t + dt] (time_varying() when a schedule exists);
//   states       the constant model's other terms as shaping states with the simulator's exact
//                parameters: its flicker bank (tau0 = 1 / IMU rate, band up to the duration,
//                2 components per decade), Gauss-Markov, ramp, sinusoid; rate random walk as the
//                core bias walk.
// A scheduled model (one with a nonstationary term) may hold white terms only (angle random walk,
// quantization, and Gauss-Markov or flicker components that fold into white noise): a scaled
// coloured state would need a time-varying map. Such a model is rejected with a ConfigError.
// No fitter: the oracle is not estimated from data.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "scenario_noise.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/model/sensor_shaping.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/tabulated_noise_model.hpp"
#include "stochnav/plugin/plugin_documentation.hpp"
#include "white_noise_schedule.hpp"

namespace {

using stochnav::NoiseModel;
using stochnav::NonstationarySegment;
using stochnav::ShapingFilter;
using stochnav::oracle::ScenarioNoise;
using stochnav::oracle::WhiteNoiseSchedule;
using stochnav::plugin::SensorGroup;

// A white PSD switched on by a schedule: psd * scale(t)^2, scale 1 outside the segments.
struct ScheduledWhite {
  double psd = 0.0;
  std::vector<NonstationarySegment> segments;

  double at(double t_s) const {
    for (const NonstationarySegment& segment : segments) {
      if (segment.start_s <= t_s && t_s < segment.end_s) return psd * segment.scale * segment.scale;
    }
    return psd;
  }
};

struct AxisNoise {
  ShapingFilter stationary;               ///< states, constant white PSD, bias walk
  std::vector<ScheduledWhite> scheduled;  ///< white parts that follow a schedule
};

void append(ShapingFilter& into, const ShapingFilter& from) {
  into.white_psd += from.white_psd;
  into.bias_walk_psd += from.bias_walk_psd;
  into.quantization = std::hypot(into.quantization, from.quantization);
  into.first_order.insert(into.first_order.end(), from.first_order.begin(), from.first_order.end());
  into.ramp_sigma.insert(into.ramp_sigma.end(), from.ramp_sigma.begin(), from.ramp_sigma.end());
  into.oscillators.insert(into.oscillators.end(), from.oscillators.begin(), from.oscillators.end());
}

void add_model(AxisNoise& axis, const NoiseModel& model, const stochnav::ShapingOptions& options,
               const std::string& where) {
  NoiseModel stationary = model;
  std::vector<NonstationarySegment> segments;
  std::erase_if(stationary.terms, [&segments](const stochnav::NoiseTerm& term) {
    const auto* schedule = std::get_if<stochnav::NonstationaryTerm>(&term);
    if (schedule != nullptr) segments = schedule->segments;
    return schedule != nullptr;
  });
  const ShapingFilter filter = stochnav::build_shaping_filter(stationary, options);
  if (segments.empty()) {
    append(axis.stationary, filter);
    return;
  }
  if (filter.size() > 0 || filter.bias_walk_psd > 0.0) {
    throw stochnav::ConfigError(
        where +
        ": a scheduled model with coloured terms (states or rate random walk); expected "
        "white terms only under a nonstationary schedule");
  }
  axis.scheduled.push_back({filter.white_psd, segments});
}

WhiteNoiseSchedule white_schedule(const std::array<AxisNoise, 3>& axes) {
  std::set<double> starts = {0.0};
  for (const AxisNoise& axis : axes) {
    for (const ScheduledWhite& part : axis.scheduled) {
      for (const NonstationarySegment& segment : part.segments) {
        starts.insert(segment.start_s);
        starts.insert(segment.end_s);
      }
    }
  }
  std::vector<double> start_s(starts.begin(), starts.end());
  std::vector<WhiteNoiseSchedule::AxisPsd> psd;
  for (double t : start_s) {
    WhiteNoiseSchedule::AxisPsd piece{};
    for (std::size_t i = 0; i < 3; ++i) {
      piece[i] = axes[i].stationary.white_psd;
      for (const ScheduledWhite& part : axes[i].scheduled) piece[i] += part.at(t);
    }
    psd.push_back(piece);
  }
  // Merge equal neighbours: a schedule that never changes the PSD is no schedule.
  std::vector<double> merged_start = {start_s[0]};
  std::vector<WhiteNoiseSchedule::AxisPsd> merged_psd = {psd[0]};
  for (std::size_t j = 1; j < start_s.size(); ++j) {
    if (psd[j] != merged_psd.back()) {
      merged_start.push_back(start_s[j]);
      merged_psd.push_back(psd[j]);
    }
  }
  return WhiteNoiseSchedule(merged_start, merged_psd);
}

struct OracleParams {
  std::string scenario;       ///< the scenario folder, absolute once built ("": the run's own)
  double fold_below_s = 0.1;  ///< s
};

const stochnav::plugin::ParamTable<OracleParams> kOracleTable{
    stochnav::plugin::text(&OracleParams::scenario, "scenario", "",
                           "folder of the simulated scenario, relative to the config file; "
                           "default (\"\"): the run's own scenario"),
    scalar(&OracleParams::fold_below_s, "fold_below_s", stochnav::plugin::ParamUnit::fixed("s"),
           stochnav::plugin::Bound::kNonNegative, 0.1,
           "first-order states faster than this become white noise"),
};

struct OracleModel {
  std::array<AxisNoise, 3> axes;
  ScenarioNoise truth;
};

OracleModel build_oracle(const OracleParams& params, SensorGroup group) {
  OracleModel model;
  model.truth = stochnav::oracle::read_scenario_noise(params.scenario, group);
  stochnav::ShapingOptions options;
  options.tau0_s = 1.0 / model.truth.rate_hz;
  options.flicker_band_max_s = std::max(model.truth.duration_s, options.tau0_s);
  options.fold_below_s = params.fold_below_s;
  const std::string file = (std::filesystem::path(params.scenario) / "scenario.json").string();
  const std::string name(stochnav::plugin::sensor_group_name(group));
  for (std::size_t i = 0; i < 3; ++i) {
    add_model(model.axes[i], model.truth.constant[i], options,
              file + ": /config/sensors/" + name + "/noise");
    add_model(model.axes[i], model.truth.scheduled[i], options,
              file + ": /scheduled_noise_models/" + name + "/" + std::to_string(i));
  }
  return model;
}

std::array<ShapingFilter, 3> stationary_parts(const OracleModel& model) {
  return {model.axes[0].stationary, model.axes[1].stationary, model.axes[2].stationary};
}

class OracleNoise final : public stochnav::plugin::TabulatedNoiseModel<OracleParams> {
 public:
  OracleNoise(SensorGroup group, const OracleParams& params, OracleModel model)
      : TabulatedNoiseModel(group, kOracleTable, params),
        model_(std::move(model)),
        shaping_(stationary_parts(model_)),
        white_(white_schedule(model_.axes)) {}

  std::string_view type() const override { return "oracle"; }
  int augmented_size() const override { return shaping_.size(); }
  bool time_varying() const override { return white_.varies(); }

  void white_noise_covariance(double t_s, double dt_s,
                              Eigen::Ref<Eigen::MatrixXd> q_white) const override {
    white_.covariance(t_s, dt_s, q_white);
  }
  void bias_walk_covariance(double, double dt_s,
                            Eigen::Ref<Eigen::MatrixXd> q_bias) const override {
    shaping_.bias_walk_covariance(dt_s, q_bias);
  }
  void augmented_transition(double, double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                            Eigen::Ref<Eigen::MatrixXd> q_d) const override {
    shaping_.transition(dt_s, phi, q_d);
  }
  void augmented_initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const override {
    shaping_.initial_covariance(p0);
  }
  void augmented_sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const override {
    shaping_.sensor_map(map);
  }

  // The table's parameters and the truth read from the scenario (derived).
  std::string describe() const override {
    std::string text = TabulatedNoiseModel::describe() +
                       fmt::format("; {} shaping states, white noise in {} pieces", shaping_.size(),
                                   white_.start_s().size());
    const char* axis_names[] = {"x", "y", "z"};
    for (std::size_t i = 0; i < 3; ++i) {
      text += fmt::format("\n{}: constant {}\n{}: scheduled {}", axis_names[i],
                          stochnav::describe(model_.truth.constant[i]), axis_names[i],
                          stochnav::describe(model_.truth.scheduled[i]));
    }
    return text;
  }

  // The table's parameters and the truth read from the scenario.
  bool equals(const NoiseModelPlugin& other, double rel_tol) const override {
    if (!TabulatedNoiseModel::equals(other, rel_tol)) return false;
    const auto& that = static_cast<const OracleNoise&>(other);
    const auto close = [rel_tol](double a, double b) {
      return stochnav::plugin::parameters_close(a, b, rel_tol);
    };
    for (std::size_t i = 0; i < 3; ++i) {
      if (!stochnav::equals(model_.truth.constant[i], that.model_.truth.constant[i], rel_tol) ||
          !stochnav::equals(model_.truth.scheduled[i], that.model_.truth.scheduled[i], rel_tol)) {
        return false;
      }
    }
    return close(model_.truth.rate_hz, that.model_.truth.rate_hz) &&
           close(model_.truth.duration_s, that.model_.truth.duration_s);
  }

 private:
  OracleModel model_;
  stochnav::SensorShaping shaping_;
  WhiteNoiseSchedule white_;
};

std::unique_ptr<stochnav::plugin::NoiseModelPlugin> make_oracle(
    const nlohmann::json& json, const stochnav::plugin::NoiseModelContext& context) {
  auto params = stochnav::plugin::parse_params(kOracleTable, json, context);
  const std::string pointer = context.params_pointer + "/scenario";
  std::filesystem::path folder;
  if (!params.scenario.empty()) {
    folder = context.config_dir / params.scenario;
  } else if (!context.scenario_dir.empty()) {
    folder = context.scenario_dir;
  } else {
    throw stochnav::ConfigError(
        pointer +
        ": missing, and the run has no simulated scenario; expected the folder of a scenario "
        "made by `stochnav simulate scenario` (the oracle knows only simulated noise)");
  }
  if (!std::filesystem::exists(folder / "scenario.json")) {
    throw stochnav::MissingDataError(pointer + ": found \"" + folder.string() +
                                     "\" without scenario.json; expected the folder of a scenario "
                                     "made by `stochnav simulate scenario`");
  }
  params.scenario = std::filesystem::absolute(folder).lexically_normal().string();
  return std::make_unique<OracleNoise>(context.group, params, build_oracle(params, context.group));
}

}  // namespace

STOCHNAV_NOISE_PLUGIN("oracle",
                      "the true noise of a simulated scenario (scenario.json): time-varying white "
                      "noise as scheduled, coloured terms as the simulator's shaping states",
                      make_oracle, stochnav::plugin::fit_not_supported)
STOCHNAV_PLUGIN_DOCUMENTATION(kOracleTable)
