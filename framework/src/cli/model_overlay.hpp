#pragma once
// A fitted noise model drawn over a measured deviation: gnuplot datablocks and plot clauses.

#include <string>

#include "stochnav/io/record.hpp"

namespace stochnav::cli {

struct ModelOverlay {
  std::string datablocks;    ///< gnuplot datablocks with the curves
  std::string plot_clauses;  ///< ", $x using 1:2 with lines title '...'" per curve
};

/// Reads the noise model at `model_path` (noise-model JSON or `stochnav fit --format json`
/// output) and evaluates its Allan deviation, total and per term, from tau_min_s to tau_max_s,
/// in the unit of `record`.
ModelOverlay model_overlay(const std::string& model_path, const Record& record, double tau_min_s,
                           double tau_max_s);

}  // namespace stochnav::cli
