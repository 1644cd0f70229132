#include "stochnav/plugin/runtime.hpp"

#include <algorithm>
#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/record.hpp"

namespace stochnav::plugin {

namespace {

// "gyro_x" -> "dtheta_x", "accel_y" -> "dv_y"; "" for other names.
std::string increment_column_for(const std::string& rate_column) {
  for (const auto& [rate, increment] : {std::pair{"gyro_", "dtheta_"}, std::pair{"accel_", "dv_"}}) {
    const std::string prefix(rate);
    if (rate_column.size() == prefix.size() + 1 && rate_column.rfind(prefix, 0) == 0) {
      return increment + rate_column.substr(prefix.size());
    }
  }
  return {};
}

}  // namespace

CalibrationRecord read_calibration_record(const FitConfig& fit, SensorGroup group,
                                          std::string_view pointer) {
  CalibrationRecord calibration;
  calibration.group = group;
  calibration.source = fit.record.string() + " (" + fit.columns[0] + ", " + fit.columns[1] + ", " +
                       fit.columns[2] + ")";
  const Unit unit =
      group == SensorGroup::kGyro ? Unit::kRadPerSecond : Unit::kMeterPerSecondSquared;
  const std::vector<std::string> header = list_columns(fit.record.string());
  for (std::size_t axis = 0; axis < 3; ++axis) {
    ReadOptions options;
    options.path = fit.record.string();
    options.column = fit.columns[axis];
    options.unit = unit;
    // A scenario's imu.csv may hold increments (dtheta_x ..., dv_x ...) instead of the rate
    // columns: then the rates are the increments times the sampling rate.
    const std::string increment_column = increment_column_for(fit.columns[axis]);
    const bool from_increments =
        std::find(header.begin(), header.end(), fit.columns[axis]) == header.end() &&
        !increment_column.empty() &&
        std::find(header.begin(), header.end(), increment_column) != header.end();
    if (from_increments) options.column = increment_column;
    Record record = read_record(options);
    if (from_increments) {
      for (double& value : record.values) value *= record.rate_hz;
    }
    if (axis == 0) {
      calibration.rate_hz = record.rate_hz;
    } else if (std::abs(record.rate_hz - calibration.rate_hz) > 1e-9 * calibration.rate_hz) {
      throw InputError(calibration.source + ": columns have different rates; use one file");
    }
    const double first = std::ceil((fit.start_s - record.start_time_s) * record.rate_hz - 1e-9);
    const double last = fit.end_s
                            ? std::ceil((*fit.end_s - record.start_time_s) * record.rate_hz - 1e-9)
                            : static_cast<double>(record.values.size());
    const auto begin = static_cast<std::size_t>(std::max(0.0, first));
    const auto end = static_cast<std::size_t>(
        std::min(static_cast<double>(record.values.size()), std::max(0.0, last)));
    if (end <= begin + 1) {
      throw ConfigError(std::string(pointer) +
                        ": the window [start_s, end_s) holds no samples of " + fit.record.string() +
                        "; choose times within the record");
    }
    calibration.start_time_s = record.start_time_s + static_cast<double>(begin) / record.rate_hz;
    calibration.axes[axis].assign(record.values.begin() + static_cast<std::ptrdiff_t>(begin),
                                  record.values.begin() + static_cast<std::ptrdiff_t>(end));
  }
  return calibration;
}

std::shared_ptr<NoiseModelPlugin> build_noise_model(const NoiseConfig& config, SensorGroup group,
                                                    const PluginRegistry& registry,
                                                    NoiseModelContext context) {
  context.group = group;
  context.params_pointer = config.options_pointer();
  std::shared_ptr<NoiseModelPlugin> model;
  if (config.fit) {
    const std::string fit_pointer = config.pointer + "/fit";
    const auto& descriptor =
        registry.find(PluginKind::kNoiseModel, config.type, config.type_pointer());
    if (!descriptor.can_fit) {
      throw ConfigError(fit_pointer + ": noise plugin '" + config.type +
                        "' cannot fit its model from data; remove \"fit\" and give \"params\"");
    }
    const CalibrationRecord record = read_calibration_record(*config.fit, group, fit_pointer);
    model = registry.fit_noise_model(config.type, record, config.options(), context,
                                     config.type_pointer());
  } else {
    model = registry.create_noise_model(config.type, config.params, context, config.type_pointer());
  }
  if (model->group() != group || model->augmented_size() < 0) {
    throw ConfigError(config.type_pointer() + ": plugin '" + config.type +
                      "' built a model for the wrong sensor group or with a negative state "
                      "count; fix the plugin");
  }
  return model;
}

RunPlugins build_run_plugins(const RunConfig& config, const PluginRegistry& registry,
                             const AidData& aid_data, const NavState& initial_state,
                             double imu_rate_hz) {
  NoiseModelContext context;
  context.imu_rate_hz = imu_rate_hz;
  context.config_dir = config.config_dir;
  context.scenario_dir = config.data.scenario_dir;
  RunPlugins plugins;
  plugins.gyro = build_noise_model(config.noise.gyro, SensorGroup::kGyro, registry, context);
  plugins.accel = build_noise_model(config.noise.accel, SensorGroup::kAccel, registry, context);
  for (const auto& aid : config.aids) {
    AidContext aid_context{aid.params_pointer(), &aid_data, initial_state, config.config_dir};
    plugins.aids.push_back(
        registry.create_aid(aid.type, aid.params, aid_context, aid.type_pointer()));
  }
  // The layout the navigator will use: with the scale-factor blocks the filter options ask for.
  const FilterOptions& options = config.filter.options;
  plugins.layout = assign_state_layout(
      *plugins.gyro, *plugins.accel,
      {.gyro_scale_factor = options.estimates_gyro_scale_factor(),
       .accel_scale_factor = options.estimates_accel_scale_factor()});
  return plugins;
}

}  // namespace stochnav::plugin
