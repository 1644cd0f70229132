#pragma once
// A navigation run's result as JSON that reads back bit for bit: how a shard of `stochnav
// compare` hands its runs to `stochnav compare merge` (experiment/shard_run.hpp), so that the
// merged results equal an unsharded run's.
//
// Only what compare reports is kept: has_truth, statistics (max_abs, sum_squares, count per
// metric), health, epochs, duration_s, wall_seconds, error_series (optional: compare plots the
// first seed's only), noise_models, fitted, fit_quality, consistency, aids, consistency_line,
// warnings, survey_stations. `start` and `filter_options` are not kept (default on reading).
//
// Exactness: finite doubles are written in the shortest form that reads back to the same bits
// (nlohmann::json's dump); NaN and infinities, which JSON has no number for, are written as
// {"non_finite": "nan" | "inf" | "-inf"}, also inside the run's JSON members (consistency, ...).

#include <nlohmann/json.hpp>

#include "stochnav/experiment/navigation_run.hpp"

namespace stochnav {

/// The JSON of `run` described above; error_series only when `with_error_series`.
nlohmann::json run_result_to_json(const NavigationRunResult& run, bool with_error_series);

/// The run back from run_result_to_json's JSON. Throws InputError naming `where` (a file) when
/// a member is missing or has the wrong type.
NavigationRunResult run_result_from_json(const nlohmann::json& json, const std::string& where);

/// `value` with every non-finite floating-point number replaced by its {"non_finite": ...}
/// marker, and back.
nlohmann::json with_non_finite_marked(const nlohmann::json& value);
nlohmann::json with_non_finite_restored(const nlohmann::json& value);

}  // namespace stochnav
