#pragma once
// A fitted noise model drawn over a measured deviation: gnuplot datablocks and plot clauses.

#include <string>

#include "stochnav/io/record.hpp"

namespace stochnav::cli {

struct ModelOverlay {
  std::string datablocks;    ///< gnuplot datablocks with the curves
  std::string plot_clauses;  ///< ", $x using 1:2 with lines title '...'" per curve
};

/// What a model's curve shows.
enum class ModelCurve {
  kAllanDeviation,       ///< sqrt(AVAR(tau)) (unit of the record)
  kHaarWaveletVariance,  ///< Haar wavelet variance at scale tau: AVAR(tau / 2) / 2 (unit^2)
};

/// Reads the noise model at `model_path` (noise-model JSON or `stochnav fit --format json`
/// output) and evaluates its Allan deviation (or wavelet variance), total and per term, from
/// tau_min_s to tau_max_s, in the unit of `record`.
ModelOverlay model_overlay(const std::string& model_path, const Record& record, double tau_min_s,
                           double tau_max_s, ModelCurve curve = ModelCurve::kAllanDeviation);

}  // namespace stochnav::cli
