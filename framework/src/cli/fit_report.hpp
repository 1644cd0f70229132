#pragma once
// Text forms of noise-term fits: one fit (table, csv, json) and the windowed time series.

#include <string>
#include <vector>

#include "command_support.hpp"
#include "stochnav/fit/fit_noise_terms.hpp"
#include "stochnav/io/record.hpp"
#include "stochnav/stats/davar.hpp"

namespace stochnav::cli {

/// JSON: the noise model of DESIGN.md with "<param>_sigma" after each parameter and
/// "diagnostics" (fit/fit_result_json.hpp). Table and CSV: one row per parameter in reporting
/// units with its 1-sigma uncertainty, then the IEEE 952 slope read-offs.
/// `record` describes the data (source, column, rate, unit); `samples` is its sample count (the
/// record's values may have been released: stats/phase.hpp's PhaseRecord).
std::string format_fit(const FitResult& fit, const Record& record, std::size_t samples,
                       OutputFormat format);

/// Coefficient time series of a windowed fit. JSON: {"units", "window", "step", "t": [...],
/// "terms": [{"type": T, "<param>": [...], "<param>_sigma": [...]}, ...], "failed": [bool, ...],
/// "failure": ["why", ...]}; CSV: one row per window, t then each parameter and its sigma, then
/// `failed` (0 or 1); table: the same rows, then a "# FIT FAILED at t = ..." line per failed
/// window.
std::string format_windowed_fit(const std::vector<double>& time_s,
                                const std::vector<FitResult>& fits, const Record& record,
                                const DavarOptions& davar, OutputFormat format);

}  // namespace stochnav::cli
