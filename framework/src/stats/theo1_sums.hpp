#pragma once
// Internal to the stats domain: the double sum of Theo1 and Stable32's ThêoBR bias factor
// (deviation.hpp, kTheo1 and kTheo1Nobias), which estimators.cpp normalises.

#include <cstddef>
#include <span>

namespace stochnav {

/// sum_{i=0}^{N-m-1} sum_{j=1}^{m/2} (x[i] - x[i+j] + x[i+m] - x[i+m-j])^2 / j for even
/// m >= 2, m <= N - 1. Cost O(N m): for each j one vectorised pass over i; the j are spread
/// over the stats threads in tasks fixed by m (bitwise the same for every thread count).
double theo1_sum(std::span<const double> phase, std::size_t m);

/// THEO1 variance at even m (the sum over its normalisation 0.75 (N - m) (m tau0)^2).
double theo1_variance(std::span<const double> phase, double tau0_s, std::size_t m);

/// Stable32's ThêoBR factor k = mean over i = 0 .. floor(N/6) - 3 of
/// OAVAR(9 + 3i) / THEO1(12 + 4i) (the Allan variance at the same tau as Theo1). 1 when
/// N < 24 (no ratio). Dimensionless and independent of tau0. Cost O(N^3) in all (about 0.015
/// N^3 term evaluations): a few ms for 1000 points, seconds for 10^4.
double theo1_bias_factor(std::span<const double> phase);

/// The nominal noise type of a ThêoBR factor: the nearest (geometrically) of the nominal
/// Avar / Theo1 ratios 0.4 (alpha 2), 0.6 (1), 1.0 (0), 1.71 (-1), 2.24 (-2).
int theo1_bias_noise_type(double bias_factor);

}  // namespace stochnav
