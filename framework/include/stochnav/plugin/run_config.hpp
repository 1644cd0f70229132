#pragma once
// The run config of `stochnav run` (and, per variant, the noise/aids sections of `compare`):
// validated completely before anything runs, into plain structs. Every default lives in this
// header, as the member initialisers below. Unknown keys are rejected; every error is one
// ConfigError line "<JSON pointer>: <problem>; expected <form>". Relative paths are relative to
// the config file's folder.
//
//   {
//     "data": {"scenario": "runs/vib1"}                        // a `simulate scenario` folder
//          |  {"imu": "imu.csv", "truth": "truth.csv", "aids": "aids.csv"},   // truth, aids
//          optional
//     "noise": {
//       "gyro":  {"plugin": "gauss_markov", "params": {"sigma": 0.1, "tau_c": 100, "N": 0.05}},
//       "accel": {"plugin": "white", "params": {"N": 0.02},
//                 "fit": {"record": "static.csv", "start_s": 0, "end_s": 3600,     // all optional
//                         "columns": ["accel_x", "accel_y", "accel_z"]}}
//     },
//     "aids": [{"plugin": "zupt", "params": {...}}, ...],                         // default []
//     "filter": {"initial_sigma": {"position_m": 0.1, "velocity_m_s": 0.01,
//                                  "attitude_deg": [0.05, 0.05, 0.5],
//                                  "accel_bias_m_s2": 0.001, "gyro_bias_deg_h": 0.05},
//                "feedback": "closed_loop"},
//     "output": {"decimation": 100, "covariance": true, "nees": true}
//   }
// Three-axis values accept a number (all axes) or [x, y, z]. With "fit", the noise model is
// fitted to the calibration record by the plugin's fitter (params then hold its fit options).

#include <array>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stochnav/plugin/noise_model_plugin.hpp"

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
};

struct NoiseSection {
  NoiseConfig gyro;   ///< "gyro", required
  NoiseConfig accel;  ///< "accel", required
  const NoiseConfig& of(SensorGroup group) const {
    return group == SensorGroup::kGyro ? gyro : accel;
  }
};

enum class FeedbackMode {
  kClosedLoop,  ///< "closed_loop": estimated errors are fed back into the INS after each update
  kOpenLoop,    ///< "open_loop": the INS runs free; the filter only estimates its errors
};

/// Initial 1-sigma uncertainties of the core error states (per axis).
struct InitialSigma {
  std::array<double, 3> position_m = {0.1, 0.1, 0.1};          ///< "position_m", ENU, >= 0
  std::array<double, 3> velocity_m_s = {0.01, 0.01, 0.01};     ///< "velocity_m_s", ENU, >= 0
  std::array<double, 3> attitude_deg = {0.05, 0.05, 0.5};      ///< "attitude_deg", n, >= 0
  std::array<double, 3> accel_bias_m_s2 = {1e-3, 1e-3, 1e-3};  ///< "accel_bias_m_s2", b, >= 0
  std::array<double, 3> gyro_bias_deg_h = {0.05, 0.05, 0.05};  ///< "gyro_bias_deg_h", b, >= 0
};

struct FilterConfig {
  InitialSigma initial_sigma;                         ///< "initial_sigma"
  FeedbackMode feedback = FeedbackMode::kClosedLoop;  ///< "feedback"
};

struct OutputConfig {
  std::size_t decimation = 100;  ///< "decimation": write every n-th epoch, >= 1
  bool covariance = true;        ///< "covariance": write the 1-sigma of the core states
  bool nees = true;              ///< "nees": write NEES against truth (when there is truth)
};

struct RunConfig {
  std::filesystem::path config_dir;  ///< folder of the config file (relative paths, plugins)
  DataConfig data;                   ///< "data", required
  NoiseSection noise;                ///< "noise", required
  std::vector<PluginConfig> aids;    ///< "aids", default []
  FilterConfig filter;               ///< "filter", default {}
  OutputConfig output;               ///< "output", default {}
};

/// Validates a whole run config. `config_dir` resolves relative paths. Checks that the data
/// files exist (ConfigError naming the pointer otherwise); plugin types and params are checked
/// when the plugins are built (runtime.hpp), still before anything runs.
RunConfig parse_run_config(const nlohmann::json& document, const std::filesystem::path& config_dir);

/// Reads and validates a run config file. Throws InputError when it cannot be read or is not
/// JSON (naming file, line and column), ConfigError when invalid.
RunConfig read_run_config(const std::filesystem::path& file);

/// The "noise" section at `pointer` (e.g. "/noise", "/variants/2/noise" for compare).
/// `default_record` is the record a "fit" without "record" uses.
NoiseSection parse_noise_section(const nlohmann::json& json, const std::string& pointer,
                                 const std::filesystem::path& config_dir,
                                 const std::filesystem::path& default_record);

/// The "aids" array at `pointer`.
std::vector<PluginConfig> parse_aids_section(const nlohmann::json& json,
                                             const std::string& pointer);

}  // namespace stochnav::plugin
