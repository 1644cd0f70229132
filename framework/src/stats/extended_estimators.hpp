#pragma once
// Internal to the stats domain: deviation_values for the total, Theo1 and time-interval-error
// estimators (MTOTDEV, TTOTDEV, HTOTDEV, Theo1, MTIE, TIE rms), which estimators.cpp delegates.

#include <cstddef>
#include <span>
#include <vector>

#include "stochnav/stats/deviation.hpp"

namespace stochnav {

/// True for the kinds extended_deviation_values computes.
bool is_extended_estimator(Deviation kind);

/// The estimators of deviation.hpp for those kinds at each m (terms already checked):
/// kHtotdev as kHtotdevNobias (its bias correction needs the noise type: compute_deviation
/// applies it), kTheo1 with its ThêoBR factor. One factor after the other, each spread over
/// the stats threads (parallel.hpp).
std::vector<double> extended_deviation_values(Deviation kind, std::span<const double> phase,
                                              double tau0_s, std::span<const std::size_t> m_values);

}  // namespace stochnav
