#pragma once
// The experiment config of `stochnav compare`: one data source, filter variants that differ in
// their noise model (and optionally aids and filter options), a baseline. Validated completely
// before anything runs; unknown keys rejected; errors are ConfigError "<file>: <JSON pointer>:
// <problem>; expected <form>". Relative paths are relative to the experiment file's folder.
//
//   {
//     "description": "...",                                         // optional
//     "comments": {...},                                 // optional, any JSON, for readers only
//     "data": {"scenario_config": "../scenarios/paper_random_vibration.json",
//              "seeds": 5,              // or [11, 12, ...]: Monte-Carlo seeds of the scenario
//              "scenario_overrides": {"/drilling/duration_s": 14400}}   // optional: values set
//                       // at JSON pointers of the scenario config before simulating (a shorter
//                       // run of a long scenario); `compare --full-scenario` ignores them
//           | {"scenario": "runs/vib1"}                             // one simulated folder
//           | {"imu": "imu.csv", "truth": "truth.csv", "aids": "aids.csv"},   // recorded + truth
//     "baseline": "classic",                                        // a variant name
//     "aids": [{"plugin": "static_position", "params": {...}}],     // every variant's aids
//     "filter": {...},                                              // every variant's filter
//     "variants": [
//       {"name": "classic", "noise": {"gyro": {...}, "accel": {...}}},
//       {"name": "davar", "noise": {...}, "aids": [...], "filter": {...}},  // overrides
//       ...
//     ],
//     "threads": 0,                                 // worker threads; 0 (default): all cores
//     "pairs": [["davar", "white_tuned"], ...],     // optional paired comparisons [A, B]
//                                   // (default: every variant against the baseline)
//     "sweep": {"name": "vibration variance x",     // optional: the experiment at several levels
//               "set": ["/scenario/noise_variance_scale/gyro", "/variants/0/noise/gyro/params/N"],
//               "values": [1, 10, 100]}
//   }
// Sweep pointers have two roots: "/scenario/<pointer>" is a pointer into the scenario config
// (applied after data/scenario_overrides; simulated data only), "/variants/<i>/<pointer>" a
// pointer into variant i of this file as written (e.g. /variants/0/noise/gyro/params/N).
// Missing keys along a pointer are created (the scenario and run-config parsers still reject
// unknown keys). Level i sets values[i] at every pointer of "set".
// "noise", "aids" and "filter" have exactly the form of a run config (plugin/run_config.hpp).

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace stochnav {

struct ExperimentVariant {
  std::string name;           ///< unique, [A-Za-z0-9_.-]+ (used in file names)
  nlohmann::json run_config;  ///< a run config without "data": noise, aids, filter
  std::string gyro_plugin;    ///< the gyro noise plugin's type (results.json "noise_model")
};

/// "sweep" of an experiment (see above).
struct ExperimentSweep {
  std::string name;                 ///< the swept factor (axis label)
  std::vector<std::string> set;     ///< pointers, each starting /scenario/ or /variants/<i>/
  std::vector<nlohmann::json> values;  ///< one per level
};

struct ExperimentConfig {
  std::filesystem::path file;        ///< the experiment file (for messages)
  std::filesystem::path config_dir;  ///< its folder
  std::string description;
  /// Simulated data: the scenario config file and the seeds; else a fixed data section.
  std::optional<std::filesystem::path> scenario_config;
  std::vector<std::uint64_t> seeds;
  /// "scenario_overrides": JSON pointer -> value, applied to the scenario config (an object;
  /// empty when none). Each pointer must name an existing value of the scenario config.
  nlohmann::json scenario_overrides = nlohmann::json::object();
  /// A sweep level's /scenario/ values: pointer (into the scenario config) -> value, applied
  /// after scenario_overrides; missing keys are created (the scenario parser rejects unknown
  /// ones).
  nlohmann::json scenario_sweep_values = nlohmann::json::object();
  nlohmann::json fixed_data;  ///< "data" as a run config takes it (scenario folder or files)
  std::string baseline;
  std::vector<ExperimentVariant> variants;
  unsigned threads = 0;
  /// Paired comparisons [A, B] (variant names); default every variant against the baseline.
  std::vector<std::pair<std::string, std::string>> pairs;
  std::optional<ExperimentSweep> sweep;
  /// The experiment document as read (a sweep level rewrites it and parses it again).
  nlohmann::json document;
};

/// Reads and validates an experiment file. Each variant is also checked as the run config it
/// becomes (a placeholder data section stands in for the seeds' folders), so a bad noise or aid
/// section fails here, before any simulation, with the variant's JSON pointer.
ExperimentConfig read_experiment_config(const std::filesystem::path& file);

/// Parses and validates an experiment document (as read_experiment_config, without the file
/// read); `file` names it in messages and fixes the folder relative paths start from.
ExperimentConfig experiment_config_from_json(const nlohmann::json& document,
                                             const std::filesystem::path& file);

/// The experiment of sweep level `level` (0-based): the document with the level's value at every
/// sweep pointer, without the sweep. Throws ConfigError naming the sweep pointer at fault.
ExperimentConfig sweep_level(const ExperimentConfig& config, std::size_t level);

/// The run config document of one variant on one data section.
nlohmann::json variant_run_document(const ExperimentVariant& variant, const nlohmann::json& data);

}  // namespace stochnav
