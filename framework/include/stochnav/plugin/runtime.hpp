#pragma once
// From a validated run config to ready plugin objects: the noise model of each sensor group
// (built from params, or fitted to a calibration record), the aids, and the state layout.
// Everything here runs before the filter starts and throws ConfigError / InputError.

#include <memory>
#include <string_view>
#include <vector>

#include "stochnav/ins/nav_state.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/plugin_registry.hpp"
#include "stochnav/plugin/run_config.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav::plugin {

/// The window [fit.start_s, fit.end_s) of the three columns fit.columns of fit.record, in SI
/// units (the IMU CSV convention: rad/s, m/s^2), at the rate of its time column. Throws
/// InputError (file, column) or ConfigError naming `pointer` (an empty window).
CalibrationRecord read_calibration_record(const FitConfig& fit, SensorGroup group,
                                          std::string_view pointer);

/// One group's noise model: fitted when config.fit is set, else built from config.params.
/// `context` supplies imu_rate_hz, config_dir and scenario_dir; group and params_pointer are set
/// here. Also checks that the plugin returned a model of the right group.
std::shared_ptr<NoiseModelPlugin> build_noise_model(const NoiseConfig& config, SensorGroup group,
                                                    const PluginRegistry& registry,
                                                    NoiseModelContext context);

struct RunPlugins {
  std::shared_ptr<NoiseModelPlugin> gyro;
  std::shared_ptr<NoiseModelPlugin> accel;
  std::vector<std::shared_ptr<AidPlugin>> aids;  ///< in config order
  /// core 15, the scale-factor blocks the run's filter options ask for, gyro block, accel
  /// block: the navigator's layout; models already placed
  StateLayout layout;
};

/// Builds every plugin of a run. `aid_data` is the run's aid data (empty AidData when none).
RunPlugins build_run_plugins(const RunConfig& config, const PluginRegistry& registry,
                             const AidData& aid_data, const NavState& initial_state,
                             double imu_rate_hz);

}  // namespace stochnav::plugin
