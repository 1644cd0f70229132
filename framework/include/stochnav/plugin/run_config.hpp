#pragma once
// The run config of `stochnav run` (and, per variant, the noise/aids/filter sections of
// `compare`): validated completely before anything runs, into plain structs. Unknown keys are
// rejected; every error is one ConfigError line "<JSON pointer>: <problem>; expected <form>".
// Relative paths are relative to the config file's folder.
//
//   {
//     "description": "...", "comments": {...},                 // optional, ignored
//     "data": {"scenario": "runs/vib1"}                        // a `simulate scenario` folder
//          |  {"imu": "imu.csv", "truth": "truth.csv", "aids": "aids.csv"},   // truth, aids
//          optional. Required unless `stochnav run --data DIR` replaces it (data_from_folder).
//     "noise": {
//       "gyro":  {"plugin": "gauss_markov", "params": {"sigma": 0.1, "tau_c": 100, "N": 0.05}},
//       "accel": {"plugin": "white", "params": {"N": 0.02},
//                 "fit": {"record": "static.csv", "start_s": 0, "end_s": 3600,     // all optional
//                         "columns": ["accel_x", "accel_y", "accel_z"]}}
//     },
//     "aids": [{"plugin": "zupt", "params": {...}}, ...],                         // default []
//     "filter": {                                       // every key optional; defaults below
//       "initial_sigma": {"position_m": 0.1, "velocity_m_s": 0.01,
//                         "attitude_deg": [0.0573, 0.0573, 0.573],
//                         "accel_bias_m_s2": 0.001, "gyro_bias_deg_h": 1.03},
//       "covariance_interval_s": 0.1,                   // >= 0 (0: every IMU epoch)
//       "max_consecutive_rejections": 3,                // integer >= 0 (0: strict gate)
//       "second_order_attitude_correlation_s": 900,     // >= 0 (0: first order only)
//       "heading_hypothesis_sigma_deg": 4,              // >= 0 (0: one filter, no bank)
//       "heading_hypothesis_consider": true,            // the bank's headings as consider states
//       "heading_hypothesis_robust_weights": true,      // the bank's weights bound outliers
//       "heading_hypothesis_hold_together": true,       // one consider rule for the bank
//       "heading_hypothesis_split_running": true,       // a running filter may become a bank
//       "heading_hypothesis_mirror_at_rotation": true,  // the mirror split waits for rotation
//       "heading_hypothesis_likelihood_power": 0.5,     // [0.05, 1]; the weights' tempering
//       "scale_factor_sigma_ppm": {"gyro": 0, "accel": 0},   // >= 0; > 0 adds the 3 states
//       "feedback": "closed_loop"},                     // the only mode implemented
//     "initial_state": {                                // optional with truth, required without
//       "tie_on": {"latitude_deg": 40, "longitude_deg": 116, "height_m": 50,
//                  "measured_depth_m": 0},              // MD optional (see InitialStateConfig)
//       "attitude": {"inclination_deg": 0, "azimuth_deg": 0, "toolface_deg": 0}   // either
//       | "alignment": {"static_s": 120, ...},          //   (AlignmentConfig: all keys)
//       "velocity_m_s": [0, 0, 0]},                     // ENU, default 0 (not with alignment)
//     "initial_error": {"position_m": [e, n, u], "velocity_m_s": [e, n, u],
//                       "attitude_deg": [about E, N, U], "gyro_bias_deg_h": [x, y, z],
//                       "accel_bias_m_s2": [x, y, z], "draw_seed": K},   // all optional
//     "output": {"decimation": 100, "covariance": true, "nees": true},
//     "survey": {"vertical_section_azimuth_deg": 45,   // [0, 360); default: see SurveyConfig
//                "ellipse_confidence": 0.95,           // (0, 1), the horizontal ellipse's
//                "datum_elevation_m": 30,              // depth datum above MSL (m), optional
//                "tie_on_tvd_m": 1200,                 // tie-on TVD below the datum, optional
//                "sensor_to_bit_m": 12.5,              // survey sensor behind the bit, [0, 200]
//                "tie_on_md_tolerance_m": 5,           // tie-on MD vs the tally, (0, 1000]
//                "grid_convergence_deg": 1.2,          // grid north from true, [-10, 10]
//                "well_reference": {"easting_m": 500000, "northing_m": 6200000,
//                                   "scale_factor": 0.9996},  // map coordinates, optional
//                "length_unit": "ft",                  // m | ft: ft adds survey_ft.csv
//                "error_model": "gyro_ns_ct",          // none | mwd_rev5 | mwd_rev4 | gyro_ns_ct
//                                                      // | gyro_ns | gyro_mwd
//                "well": "well.json",                  // `stochnav survey --well` file
//                "noise_model": "gyro_fit.json",       // gyro_ns_ct: fitted x-y gyro model
//                "gyrocompass_time_s": 60,             // gyro_ns_ct with a noise model, > 0
//                "running_speed_m_h": 2743.2}          // gyro_ns_ct, > 0
//   }
// Three-axis values accept a number (all axes) or [x, y, z]. With "fit", the noise model is
// fitted to the calibration record by the plugin's fitter (params then hold its fit options).
//
// The filter defaults are FilterOptions' member initialisers (filter/filter_options.hpp), the
// one place they are written; the numbers above are those defaults in the config's units.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stochnav/filter/filter_options.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/survey_error/gyro_noise_mapping.hpp"
#include "stochnav/survey_error/well_parameters.hpp"

namespace stochnav::plugin {

/// Files of a `simulate scenario` folder.
inline constexpr std::string_view kScenarioImuFile = "imu.csv";
inline constexpr std::string_view kScenarioTruthFile = "truth.csv";
inline constexpr std::string_view kScenarioAidsFile = "aids.csv";

/// IMU CSV columns (t in s; gyro rad/s, accel m/s^2, body axes): the defaults of FitConfig.
inline constexpr std::array<std::string_view, 3> kGyroColumns = {"gyro_x", "gyro_y", "gyro_z"};
inline constexpr std::array<std::string_view, 3> kAccelColumns = {"accel_x", "accel_y", "accel_z"};

struct DataConfig {
  std::filesystem::path scenario_dir;          ///< "scenario": folder; empty when files are given
  std::filesystem::path imu;                   ///< "imu", or <scenario>/imu.csv; must exist
  std::optional<std::filesystem::path> truth;  ///< "truth", or <scenario>/truth.csv if present
  std::optional<std::filesystem::path> aids;   ///< "aids", or <scenario>/aids.csv if present
};

/// "fit": build the noise model from a calibration record.
struct FitConfig {
  std::filesystem::path record;        ///< "record" (default: data imu); must exist
  double start_s = 0.0;                ///< "start_s": first record time used (s), >= 0
  std::optional<double> end_s;         ///< "end_s": end of the window (s), > start_s; default: end
  std::array<std::string, 3> columns;  ///< "columns": x, y, z; default kGyroColumns/kAccelColumns
};

/// One plugin entry: {"plugin": TYPE, "params": {...}}.
struct PluginConfig {
  std::string type;                                  ///< "plugin", required
  nlohmann::json params = nlohmann::json::object();  ///< "params", default {} (plugin-checked)
  std::string pointer;  ///< JSON pointer of the entry, e.g. "/noise/gyro", "/aids/0"
  std::string type_pointer() const { return pointer + "/plugin"; }
  std::string params_pointer() const { return pointer + "/params"; }
};

struct NoiseConfig : PluginConfig {
  std::optional<FitConfig> fit;  ///< "fit", default absent: the model comes from params
  /// "fit_options", with "fit" only: the fitter's own options (method, terms, start, fix,
  /// bound, ...), which it then reads instead of "params" (which must then be absent or {}).
  std::optional<nlohmann::json> fit_options;
  /// Where the model's or the fitter's keys are read: .../fit_options or .../params.
  std::string options_pointer() const {
    return fit_options ? pointer + "/fit_options" : params_pointer();
  }
  const nlohmann::json& options() const { return fit_options ? *fit_options : params; }
};

struct NoiseSection {
  NoiseConfig gyro;   ///< "gyro", required
  NoiseConfig accel;  ///< "accel", required
  const NoiseConfig& of(SensorGroup group) const {
    return group == SensorGroup::kGyro ? gyro : accel;
  }
};

/// "filter": the navigator's options, parsed into FilterOptions (whose member initialisers are
/// the defaults) from the config's units: initial_sigma attitude in deg, gyro bias in deg/h,
/// scale factors in ppm. "feedback" has one value, "closed_loop" (the navigator feeds every
/// update back into the INS); any other value is rejected here, at validation.
struct FilterConfig {
  FilterOptions options;
};

/// "initial_state/tie_on": the known position where the run starts (and the survey's tie-on).
struct TieOnConfig {
  double latitude_deg = 0.0;                ///< "latitude_deg", required, [-90, 90]
  double longitude_deg = 0.0;               ///< "longitude_deg", required
  double height_m = 0.0;                    ///< "height_m", ellipsoidal, required
  std::optional<double> measured_depth_m;   ///< "measured_depth_m" (m), optional: absent, the
                                            ///< tally at the start (the aid data's leading
                                            ///< measured_depth_m at rest) minus
                                            ///< "survey/sensor_to_bit_m", else 0
};

/// "initial_state/attitude": a known attitude (deg; ins/mwd_attitude.hpp conventions).
struct AttitudeConfig {
  double inclination_deg = 0.0;  ///< "inclination_deg", required, [0, 180]
  double azimuth_deg = 0.0;      ///< "azimuth_deg", required, from true north
  double toolface_deg = 0.0;     ///< "toolface_deg", required
};

/// "initial_state/alignment": static alignment over the first static_s seconds of the IMU
/// record (coarse levelling + gyrocompassing, then fine alignment: the filter with
/// zero-velocity and known-position updates at 1 Hz). Navigation starts at the end of the span.
/// The span must be static: the standard deviation, over the span's 1-s blocks, of the blocks'
/// mean |omega| and mean |f| must not exceed the two spreads below. The defaults let a rocking
/// but parked carrier align (the PSINS vehicle record spreads 101 deg/h and 0.002 m/s^2 over
/// its first 300 s; a still FOG tool well under 1 deg/h) and refuse a tool that turns (a
/// rotary table at 60 rpm spreads about 6e5 deg/h) or is carried.
struct AlignmentConfig {
  double static_s = 0.0;                       ///< "static_s" (s), required, > 0
  double max_gyro_spread_deg_h = 360.0;        ///< "max_gyro_spread_deg_h" (0.1 deg/s), > 0
  double max_accel_spread_m_s2 = 0.05;         ///< "max_accel_spread_m_s2", > 0
  double zero_velocity_sigma_m_s = 0.01;       ///< "zero_velocity_sigma_m_s": ZUPT noise, > 0
  double position_sigma_m = 0.1;               ///< "position_sigma_m": known-position noise, > 0
  /// "attitude_sigma_deg": 1-sigma of the coarse attitude about E, N, U (deg), > 0. Default:
  /// tilt from the accel bias sigma over g, heading from the gyro bias sigma over the
  /// horizontal Earth rate (the coarse-alignment error budget), floored at 0.1 / 1 deg, the
  /// heading capped at 30 deg.
  std::optional<std::array<double, 3>> attitude_sigma_deg;
};

struct InitialStateConfig {
  TieOnConfig tie_on;                        ///< "tie_on", required
  std::optional<AttitudeConfig> attitude;    ///< "attitude" XOR "alignment"
  std::optional<AlignmentConfig> alignment;
  std::array<double, 3> velocity_m_s{};      ///< "velocity_m_s", ENU, default 0
};

/// "initial_error": an error put into the initial estimate on purpose, so that convergence and
/// consistency are tested from a start away from truth. Applied to whichever initial state the
/// run uses (truth's first row, initial_state, or the alignment's result).
///   position, velocity: estimate - truth, ENU; attitude: the rotation phi (about E, N, U) with
///   C_nb_estimate = (I - [phi x]) C_nb_true, the filter's own attitude-error convention.
///   Biases: the filter's initial bias ESTIMATE is offset by this much from where it would
///   otherwise start (zero, or the alignment's estimate). The true bias is unknown to the filter,
///   so this is an error relative to the filter's default start, not to the true bias.
/// With "draw_seed", an error drawn from N(0, sigma^2) with the filter's initial sigmas (after
/// alignment, its sigmas) is added to the given ones, per component (xoshiro256**, seeded).
struct InitialErrorConfig {
  std::array<double, 3> position_m{};       ///< "position_m" (m), ENU
  std::array<double, 3> velocity_m_s{};     ///< "velocity_m_s" (m/s), ENU
  std::array<double, 3> attitude_deg{};     ///< "attitude_deg" (deg), about E, N, U
  std::array<double, 3> gyro_bias_deg_h{};  ///< "gyro_bias_deg_h" (deg/h), body axes
  std::array<double, 3> accel_bias_m_s2{};  ///< "accel_bias_m_s2" (m/s^2), body axes
  std::optional<std::uint64_t> draw_seed;   ///< "draw_seed", integer >= 0
};

struct OutputConfig {
  std::size_t decimation = 100;  ///< "decimation": write every n-th epoch, >= 1
  bool covariance = true;        ///< "covariance": write the 1-sigma of the core states
  bool nees = true;              ///< "nees": write NEES against truth (when there is truth)
};

/// "survey": the references of the survey listing (survey.csv's columns after the QC's;
/// experiment/survey_listing.hpp). Every key optional.
struct SurveyConfig {
  /// "vertical_section_azimuth_deg" (deg from true north), [0, 360). Absent: the tie-on's
  /// azimuth ("initial_state/attitude", the aligned one after "alignment", or truth's at a start
  /// from truth) when more than 1 deg from vertical, else the closure azimuth of the last
  /// station.
  std::optional<double> vertical_section_azimuth_deg;
  /// "ellipse_confidence": the probability inside the horizontal error ellipse, (0, 1).
  double ellipse_confidence = 0.95;
  /// "datum_elevation_m" (m): elevation of the depth datum (e.g. the rotary kelly bushing)
  /// above mean sea level, finite, |E| <= 10000. Absent: no datum columns (NaN).
  std::optional<double> datum_elevation_m;
  /// "tie_on_tvd_m" (m): the tie-on's TVD below the depth datum, finite, |T| <= 20000; only
  /// with datum_elevation_m. Absent: datum_elevation_m - the tie-on's height_m (the ellipsoidal
  /// height taken as the elevation above MSL: the geoid undulation, tens of metres, ignored).
  std::optional<double> tie_on_tvd_m;
  /// "sensor_to_bit_m" (m): how far the survey sensor sits behind the bit, finite, [0, 200].
  /// The depth data's "measured_depth_m" (a pipe tally) is the BIT's depth: a station's MD is
  /// the tally minus this (experiment/tally_smoother.hpp), and so is the tie-on's MD when it is
  /// not configured.
  double sensor_to_bit_m = 0.0;
  /// "tie_on_md_tolerance_m" (m), (0, 1000]: a configured tie-on MD
  /// ("initial_state/tie_on/measured_depth_m") farther than this from the tally at the start
  /// (the mean of the depth data's leading readings flagged "zupt", else its first) minus
  /// sensor_to_bit_m is rejected (exit 2) before the run: one of them is wrong.
  double tie_on_md_tolerance_m = 5.0;
  /// "grid_convergence_deg" (deg), [-10, 10]: grid north's angle from true north, clockwise
  /// positive; survey.csv's grid_azimuth_deg = azimuth_deg - this. Absent: grid_azimuth_deg NaN.
  std::optional<double> grid_convergence_deg;
  /// "well_reference": the map (projected CRS) coordinates of the tie-on, the origin of the
  /// listing's north/east: "easting_m" and "northing_m" (m, finite, |x| <= 1e8, required) and
  /// "scale_factor" (the grid scale factor at the well, [0.99, 1.01], default 1). Only with
  /// grid_convergence_deg (the offsets are turned into grid north). Absent: survey.csv's
  /// map_easting_m / map_northing_m NaN.
  struct WellReference {
    double easting_m = 0.0;
    double northing_m = 0.0;
    double scale_factor = 1.0;
  };
  std::optional<WellReference> well_reference;
  /// "length_unit": "m" (default: survey.csv only) or "ft" (survey_ft.csv too: the listing in
  /// international feet, 0.3048 m, DLS per 100 ft). survey.csv stays in metres either way.
  std::string length_unit = "m";
  /// "error_model": the survey tool model (survey_error/tool_models.hpp) whose covariance the
  /// run writes beside the filter's for its survey stations (iscwsa_covariance.csv,
  /// survey_uncertainty.png; experiment/survey.hpp). "none" (default): neither file.
  std::string error_model = "none";
  /// "well": a `stochnav survey --well` file (survey_error/survey_inputs.hpp), read here.
  /// Required for mwd_rev5/mwd_rev4 (the magnetic field); for the gyro models (gyro_ns_ct,
  /// gyro_ns, gyro_mwd) absent means the tie-on's latitude, 15.041 deg/h, 9.80665 m/s^2, true
  /// north.
  std::optional<survey_error::WellParameters> well;
  /// "noise_model" (gyro_ns_ct): a fitted gyro noise model file (`stochnav fit` JSON) mapped to
  /// GXY-RN/GD/GRW (survey_error/gyro_noise_mapping.hpp). Absent: the run's own gyro model when
  /// it is white (plugin "white", fitted or not), else the OWSG magnitudes.
  std::optional<NoiseModel> gyro_noise_model;
  /// "gyrocompass_time_s" (s), > 0: T of the mapping.
  double gyrocompass_time_s = survey_error::kDefaultGyrocompassTime_s;
  /// "running_speed_m_h" (m/h), > 0: the continuous survey's speed; absent: OWSG's 2743.2.
  std::optional<double> running_speed_m_h;
};

struct RunConfig {
  std::filesystem::path config_dir;  ///< folder of the config file (relative paths, plugins)
  DataConfig data;                   ///< "data", required (or --data)
  NoiseSection noise;                ///< "noise", required
  std::vector<PluginConfig> aids;    ///< "aids", default []
  FilterConfig filter;               ///< "filter", default {}
  std::optional<InitialStateConfig> initial_state;  ///< "initial_state"
  std::optional<InitialErrorConfig> initial_error;  ///< "initial_error"
  OutputConfig output;               ///< "output", default {}
  SurveyConfig survey;               ///< "survey", default {}
};

/// Validates a whole run config. `config_dir` resolves relative paths. Checks that the data
/// files exist (ConfigError naming the pointer otherwise); plugin types and params are checked
/// when the plugins are built (runtime.hpp), still before anything runs. With `data`, the
/// document's "data" section is ignored (may be absent) and `data` is used instead.
RunConfig parse_run_config(const nlohmann::json& document, const std::filesystem::path& config_dir,
                           const std::optional<DataConfig>& data = std::nullopt);

/// Reads and validates a run config file. Throws InputError when it cannot be read or is not
/// JSON (naming file, line and column), ConfigError when invalid.
RunConfig read_run_config(const std::filesystem::path& file,
                          const std::optional<DataConfig>& data = std::nullopt);

/// The run config of a host that feeds the IMU itself (an embedder driving MwdNavigator from
/// its own loop, as examples/embed_runtime and the Python Navigator do): the "data" section may
/// be absent and is ignored (the result's `data` is empty); everything else is validated as
/// read_run_config does.
RunConfig read_embedded_run_config(const std::filesystem::path& file);

/// Throws ConfigError naming "/initial_state" when the config has neither truth (a truth file)
/// nor "initial_state": a navigation run must start somewhere. run_navigation calls it first;
/// a config that is only inspected (`stochnav plugins show`) needs no start.
void check_run_start(const RunConfig& config);

/// The data of a recording folder (`stochnav run --data DIR`): DIR/imu.csv required,
/// DIR/aids.csv and DIR/truth.csv used when present; scenario_dir = DIR when it holds a
/// scenario.json (a `simulate scenario` folder). Throws ConfigError
/// "--data DIR: no imu.csv; ..." when DIR or its imu.csv is missing.
DataConfig data_from_folder(const std::filesystem::path& dir);

/// The "filter" section at `pointer` into FilterOptions (FilterConfig above).
FilterConfig parse_filter_section(const nlohmann::json& json, const std::string& pointer);

/// The "noise" section at `pointer` (e.g. "/noise", "/variants/2/noise" for compare).
/// `default_record` is the record a "fit" without "record" uses.
NoiseSection parse_noise_section(const nlohmann::json& json, const std::string& pointer,
                                 const std::filesystem::path& config_dir,
                                 const std::filesystem::path& default_record);

/// The "aids" array at `pointer`.
std::vector<PluginConfig> parse_aids_section(const nlohmann::json& json,
                                             const std::string& pointer);

}  // namespace stochnav::plugin
