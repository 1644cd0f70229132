#pragma once
// JSON form of a scenario configuration (where JSON stops for scenarios). See
// configs/scenarios/*.json for complete, commented examples. Top level:
//
//   {"description": "...", "kind": "vibration_table" | "drilling", "seed": 1,
//    "imu": {"rate_hz": 100, "output": "increments" | "rates",
//            "truth_rate_hz": 100, "aid_rate_hz": 1},                 // rates divide rate_hz
//    "site": {"latitude_deg": 39.9778, "longitude_deg": 116.3448, "height_m": 50},
//    "sensors": {
//      "gyro":  {"noise": MODEL | [MODEL x, MODEL y, MODEL z],          // units deg/h etc.
//                "scheduled_noise": MODEL | [...],                       // scaled per phase
//                "bias_dph": [x, y, z] | v, "turn_on_bias_sigma_dph": s,
//                "scale_factor_ppm": [x, y, z] | v},
//      "accel": {"noise": ..., "scheduled_noise": ..., "bias_mg": ..., "turn_on_bias_sigma_mg": s,
//                "scale_factor_ppm": ...}},
//    "aids": {"depth_scale_error": 1e-3, "depth_noise_m": 0.05, "rop_noise_mph": 0.5,
//             "clock_offset_s": 0.004,    // optional, |x| < 1: aids.csv t = true time + x
//             "latency_s": 0.5,           // optional, >= 0: readings of true time t - latency
//             "dropouts": [{"start_s": 9000, "end_s": 9300}]},  // optional: no rows at true
//                                         // times in [start_s, end_s]; ascending, disjoint
//    "noise_variance_scale": {"gyro": 10, "accel": 1},          // optional, default 1:
//            factors on the VARIANCE of the scheduled noise (amplitude x sqrt(factor)) on top
//            of the phase scales, in every phase (a noise-level sweep)
//    "moving_noise_variance_scale": {"gyro": 100, "accel": 1},  // optional, default 1: the
//            same, only in phases where the tool moves (vibration-table vibration, drilling)
//    "vibration_table": {"attitude": {"inclination_deg", "toolface_deg", "azimuth_deg"},
//      "phases": [{"name": "static", "duration_s": 300, "motion": "static" | "sine" | "random",
//                  "sine": {"frequency_hz": 25, "amplitude_g": 5},
//                  "random": {"psd": [[f_hz, g2_per_hz], ...], "rms_g": 13.12,
//                             "components": 128},
//                  "gyro_noise_scale": 1, "accel_noise_scale": 1}, ...]},
//    "drilling": {"well": {"kickoff_md_m", "build_rate_deg_per_30m", "target_inclination_deg",
//                          "azimuth_deg", "turn_rate_deg_per_30m": 0}   // turn: in the build
//              | {"start": {"inclination_deg": 0, "azimuth_deg": 0},     // at MD 0, optional
//                 "sections": [{"length_m": L > 0, "build_rate_deg_per_30m": b,  // b, t: any
//                               "turn_rate_deg_per_30m": t}, ...]},   // sign, default 0; the
//            // path holds beyond the last section; inclination must stay in 0..180 deg
//      "start_md_m", "duration_s", "initial_static_s", "rop_mph", "rotation_rpm",
//      "initial_toolface_deg", "stand_length_m", "connection_s", "ramp_s",
//      "stand_pattern": [                                  // optional: every stand, in order
//        {"mode": "slide", "length_m": 9.5, "toolface_deg": 75, "rop_mph": 15},
//        {"mode": "rotate", "length_m": 19, "rpm": 100, "rop_mph": 40}],  // lengths sum to
//            // stand_length_m; rop_mph defaults to rop_mph, rpm to rotation_rpm; a slide
//            // holds toolface_deg (no rpm), after an orientation pause of orient_s
//      "orient_s": 30,       // with stand_pattern: depth still, toolface to the slide's the
//                            // shortest way with a raised-cosine profile (phase "orienting")
//      "vibration_episodes": [{"start_s", "end_s", "axial_g", "frequency_hz"}      // by time
//                           | {"start_md_m", "end_md_m", "axial_g", "frequency_hz"}],  // by
//            // drilled depth: only while drilling (never in connections or orientation),
//            // with the existing ramp at each edge of an active span
//      "noise_scales": {"static": {"gyro": 1, "accel": 1}, "drilling": {...},
//                       "vibration": {...}}},
//    "comments": {...}}                                               // free text, ignored
//
// MODEL is a noise model of model/noise_model_json.hpp. Unknown keys are rejected everywhere.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string_view>

#include "stochnav/scenario/scenario_config.hpp"

namespace stochnav {

/// Parses and validates a scenario. Throws ConfigError "<source>: <JSON pointer>: <problem>;
/// expected <form>" (source is typically the file name) on any unknown key, wrong type, missing
/// required value or value out of range.
ScenarioConfig scenario_config_from_json(const nlohmann::json& json, std::string_view source);

/// Reads and validates the scenario config file (`stochnav simulate scenario CONFIG`). Throws
/// InputError (unreadable, a folder, not JSON) or ConfigError "<file>: <JSON pointer>: ..." as
/// scenario_config_from_json.
ScenarioConfig read_scenario_config(const std::filesystem::path& file);

/// The complete configuration (defaults filled in) in the JSON form above.
nlohmann::json to_json(const ScenarioConfig& config);

}  // namespace stochnav
