#pragma once
// One navigation run (`stochnav run`, and each variant x seed of `stochnav compare`): the IMU
// file streamed through the MWD navigator with the config's noise models and aids, the errors
// against truth summarised as they go, and optionally the run's files written.
//
// Files in out_dir (all written to temporary files and renamed into place only when the whole
// run succeeded; an interrupted run leaves nothing):
//   nav.csv          t, lat, lon (deg), h (m), ve, vn, vu (m/s), inclination, toolface,
//                    azimuth (deg)                                       every `decimation` epochs
//   biases.csv       t, accel bias x y z (m/s^2), gyro bias x y z (deg/h)      same epochs
//   covariance.csv   t, 1-sigma of the 15 core states (m, m/s, deg, m/s^2, deg/h) (output.covariance)
//   innovations.csv  t, aid, type, accepted, nis, z_i and sigma_i (aid units), every update
//   errors.csv       t, the nine errors of experiment/navigation_errors.hpp, the filter's 1-sigma
//                    of each (<metric>_sigma; the MWD angles' by linearising them about the
//                    estimate), and the NEES of position, velocity and attitude (9 states;
//                    output.nees)                                   with truth, every `decimation`
//   metrics.json     {"metrics": {name: {"max_abs", "rms", "samples"}}, "filter_health": {...},
//                     "epochs", "duration_s", "noise_models": {"gyro", "accel"}, "aids": [...]}
//   errors.png       errors with their 3-sigma bounds over time (when gnuplot is installed)
//
// The initial state is the truth at the start of the IMU record: every variant starts equal,
// so comparisons measure the noise models, not the initialisation.

#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "stochnav/experiment/navigation_errors.hpp"
#include "stochnav/filter/error_state_filter.hpp"
#include "stochnav/plugin/run_config.hpp"

namespace stochnav {

struct NavigationRunOptions {
  std::filesystem::path out_dir;  ///< where the files go; empty: no files (compare's seeds)
  bool progress = false;          ///< progress bar on standard error (terminal only)
  bool plot = true;               ///< errors.png when out_dir is set and gnuplot exists
  std::size_t series_points = 2000;  ///< at most this many samples kept in error_series
};

/// One sample of the error time series (thinned) for plots.
struct ErrorSample {
  double t_s = 0.0;
  std::array<double, kErrorMetricCount> errors{};
  std::array<double, kErrorMetricCount> sigma{};  ///< the filter's 1-sigma of each error
};

struct NavigationRunResult {
  bool has_truth = false;
  ErrorStatistics statistics;
  FilterHealth health;
  std::uint64_t epochs = 0;
  double duration_s = 0.0;     ///< length of the record (s)
  double wall_seconds = 0.0;   ///< time the run took
  std::vector<ErrorSample> error_series;  ///< evenly thinned, first and last kept
  nlohmann::json noise_models;            ///< {"gyro": describe, "accel": describe}
  nlohmann::json metrics_json() const;
};

/// Runs the config. Throws ConfigError / InputError before the filter starts (bad config,
/// plugins, files) and InputError for a malformed IMU or truth row met while running.
NavigationRunResult run_navigation(const plugin::RunConfig& config,
                                   const NavigationRunOptions& options);

}  // namespace stochnav
