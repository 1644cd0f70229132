#pragma once
// JSON form of noise models (DESIGN.md): where JSON stops. Parsing validates strictly and yields
// plain NoiseModel values in natural units; writing converts back to reporting units.
//
//   {"units": "deg/h", "rate_hz": 100,
//    "terms": [{"type": "quantization", "Q": 0.2},                      // arcsec
//              {"type": "angle_random_walk", "N": 0.05},                // deg/sqrt(h)
//              {"type": "bias_instability", "B": 0.05},                 // deg/h
//              {"type": "rate_random_walk", "K": 0.3},                  // deg/h/sqrt(h)
//              {"type": "rate_ramp", "R": 0.01},                        // deg/h^2
//              {"type": "gauss_markov", "sigma": 0.1, "tau_c": 100},    // deg/h, s
//              {"type": "sinusoid", "amplitude": 1, "frequency_hz": 2,  // deg/h, Hz
//               "phase_rad": 0.5},                                      // optional, rad
//              {"type": "nonstationary",
//               "segments": [{"start": 2400, "end": 3600, "scale": 8}]}]}   // s, s, factor
//
// The reporting units follow the signal's quantity (model/reporting_units.hpp). A fit result
// (fit/fit_result_json.hpp) is accepted too: each parameter may be followed by "<name>_sigma"
// (a number >= 0 or null) and the top level may hold a "diagnostics" object; both are checked
// for form and otherwise ignored.

#include <nlohmann/json.hpp>
#include <string_view>

#include "stochnav/model/noise_model.hpp"

namespace stochnav {

/// Parses and validates a noise model. `pointer_prefix` is the JSON pointer of `json` within its
/// document (e.g. "/sensors/0/noise"), prepended to every message. Throws ConfigError with the
/// one-line message "<JSON pointer>: <problem>; expected <form>" on: a non-object, unknown or
/// missing keys, wrong JSON types, an unknown unit or term type, non-finite or out-of-range
/// values (see find_model_issue), misordered segments, or a second nonstationary term.
NoiseModel noise_model_from_json(const nlohmann::json& json, std::string_view pointer_prefix = "");

/// Parses one term object for a signal in `unit`; `pointer` locates it in its document.
/// Checks the JSON form and the ranges of this term alone.
NoiseTerm noise_term_from_json(const nlohmann::json& json, Unit unit, std::string_view pointer);

/// The model as JSON in reporting units (values rounded to 15 significant digits).
nlohmann::json to_json(const NoiseModel& model);

/// One term as JSON, in the reporting units for a signal in `unit`.
nlohmann::json to_json(const NoiseTerm& term, Unit unit);

}  // namespace stochnav
