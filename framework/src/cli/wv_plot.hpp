#pragma once
// The log-log wavelet-variance plot of `stochnav wv --plot`, with the 95 % interval bars and,
// when a noise model is given, the model's implied wavelet variance and each of its terms.

#include <string>
#include <vector>

#include "stochnav/io/record.hpp"
#include "stochnav/stats/wavelet_variance.hpp"

namespace stochnav::cli {

/// Draws `points` to `plot_path` (.png or .svg). `record` gives the title and unit (its values
/// are not used). `fit_path`, when not empty, names a noise-model JSON in the record's units.
void plot_wavelet_variance(const std::vector<WaveletVariancePoint>& points, const Record& record,
                           bool robust, const std::string& fit_path, const std::string& plot_path);

}  // namespace stochnav::cli
