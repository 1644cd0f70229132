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
//   states.csv       t, every sensor-error state (biases, scale factors, the noise models'
//                    augmented states and the sensor error they make) and its 1-sigma, units
//                    in the names (experiment/run/states_file.hpp)             same epochs
//   innovations.csv  t, aid, type, accepted, nis, z_i and sigma_i (aid units), every update
//   errors.csv       (only with truth) t, the nine errors of experiment/navigation_errors.hpp, the filter's 1-sigma
//                    of each (<metric>_sigma; the MWD angles' by linearising them about the
//                    estimate), and the NEES of position, velocity and attitude (9 states;
//                    output.nees)                                   with truth, every `decimation`
//   metrics.json     {"metrics": {name: {"max_abs", "rms", "samples"}} | null without truth,
//                     "consistency": {"inside_3sigma": {name: share}, "nees_mean", "nees_dof"}
//                     | null without truth, "aids": [{"type", "dof", "attempts",
//                     "rejected_share", "nis_mean"}] (experiment/run_consistency.hpp),
//                     "aid_rows": {"rows", "on_grid", "moved", "max_offset_s",
//                     "before_start", "after_end"} (experiment/aid_epochs.hpp: rows off the
//                     IMU grid are applied at the next epoch),
//                     "heading_hypotheses": {"initial", "final", "largest_weight", "splits"}
//                     (the bank of filters over an uncertain heading, at the start or split
//                     from the running filter, filter/heading_hypotheses.hpp),
//                     "self_check": {"source", "optimistic", "reason", "survey_qc":
//                     {"stations", "checked", "flagged", "worst_inclination_sigmas",
//                     "worst_azimuth_sigmas"}} (a station whose continuous solution leaves its
//                     connection's static solution, experiment/station_qc.hpp, makes the run
//                     optimistic),
//                     "filter_health": {...}, "epochs", "duration_s", "noise_models":
//                     {"gyro", "accel"}, "survey_stations", "initial": {"t_s", position
//                     and MWD angles of the start (after any alignment, before the deliberate
//                     initial error), the initial bias estimates and 1-sigmas the navigator
//                     started with}}
//   errors.png       errors with their 3-sigma bounds over time (with truth, gnuplot installed)
//   survey.csv, trajectory.xml (WITSML), survey_errors.csv (with truth), well_path.csv,
//   survey.png
//                    survey stations at the connections (experiment/survey.hpp), each with
//                    its static QC in the qc_* columns after DESIGN.md's
//
// The start (plugin/run_config.hpp): with "initial_state", the tie-on with the given attitude
// at the start of the IMU record, or the static alignment over its first static_s seconds
// (navigation, and every output file, then starts at the end of that span); without it, the
// truth's first row (every compare variant starts equal, so comparisons measure the noise
// models, not the initialisation). Truth, when present, only scores. "initial_error" then
// offsets the estimate from that start. The survey's tie-on is the start position (before the
// deliberate error) with the configured MD, else the tally at the start ("measured_depth_m" at
// rest) minus "survey/sensor_to_bit_m", else 0; a configured MD farther than
// "survey/tie_on_md_tolerance_m" from that tally is a ConfigError before the run
// (run/survey_start.hpp).

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "stochnav/experiment/imu_record.hpp"
#include "stochnav/experiment/navigation_errors.hpp"
#include "stochnav/filter/error_state_filter.hpp"
#include "stochnav/filter/filter_options.hpp"
#include "stochnav/ins/nav_state.hpp"
#include "stochnav/plugin/run_config.hpp"

namespace stochnav {

struct NavigationRunOptions {
  std::filesystem::path out_dir;  ///< where the files go; empty: no files (compare's seeds)
  bool progress = false;          ///< progress on standard error (core/progress_bar.hpp)
  bool plot = true;               ///< errors.png when out_dir is set and gnuplot exists
  std::size_t series_points = 2000;  ///< at most this many samples kept in error_series
  /// The config's IMU file already parsed (compare's variants of one seed share it,
  /// experiment/imu_record.hpp); null: the file is parsed on a reader thread as the run goes.
  std::shared_ptr<const ImuRecord> imu_record;
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
  nlohmann::json fitted;                  ///< {"gyro": params(), "accel": params()}
  nlohmann::json fit_quality;             ///< {"gyro": fit_quality(), "accel": ...} (null: none)
  nlohmann::json consistency;             ///< RunConsistency::consistency_json()
  nlohmann::json aids;                    ///< RunConsistency::aids_json()
  nlohmann::json self_check;              ///< RunConsistency::self_check_json()
  std::string consistency_line;           ///< "consistency: ok" / "... OPTIMISTIC ..." / ""
  std::vector<std::string> warnings;      ///< aids rejected too often
  std::size_t survey_stations = 0;        ///< stations in survey.csv
  nlohmann::json aid_rows;                ///< AidEpochs::summary_json(): where the rows went
  /// {"initial", "final", "largest_weight", "splits"}: the bank over the heading
  /// (HeadingHypotheses; 1, 1 and 0 for a filter that never split).
  nlohmann::json heading_hypotheses;
  NavState start;                         ///< the start (after alignment, before the error)
  FilterOptions filter_options;           ///< the options the navigator ran with
  nlohmann::json metrics_json() const;
};

/// Runs the config. Throws ConfigError / InputError before the filter starts (bad config,
/// plugins, files), InputError for a malformed IMU or truth row met while running, and
/// InputError when the run has aids but accepted none of their updates (nothing written).
NavigationRunResult run_navigation(const plugin::RunConfig& config,
                                   const NavigationRunOptions& options);

}  // namespace stochnav
