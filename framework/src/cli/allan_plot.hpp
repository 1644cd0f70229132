#pragma once
// The log-log deviation plot of `stochnav allan --plot`, with interval bars and, when a fitted
// noise model is given, the model's deviation and each of its terms.

#include <string>
#include <vector>

#include "stochnav/io/record.hpp"
#include "stochnav/stats/deviation.hpp"

namespace stochnav::cli {

/// Draws `points` to `plot_path` (.png or .svg). `fit_path`, when not empty, names a noise-model
/// JSON (as written by `stochnav fit --format json`) in the record's units.
void plot_allan_deviation(const std::vector<DeviationPoint>& points, const Record& record,
                          Deviation kind, const std::string& fit_path,
                          const std::string& plot_path);

}  // namespace stochnav::cli
