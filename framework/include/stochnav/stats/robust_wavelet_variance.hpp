#pragma once
// The robust Haar wavelet variance of the R package `wv` (`wvar(x, robust = TRUE, eff = 0.6)`;
// Guerrier, Molinari, Victoria-Feser, "Robust inference for time series models: a wavelet-based
// framework", 2014): at each level, an M-estimate of the scale of the wavelet coefficients with
// Tukey's biweight, tuned for a chosen efficiency at the Gaussian relative to the classical
// estimate. Coefficients, levels and units as in wavelet_variance.hpp (variances in U^2).
//
// Definitions (as `wv` computes them):
//   psi_c(r)   = r (1 - r^2 / c^2)^2 for |r| <= c, 0 beyond (the biweight).
//   a(c)       = E[psi_c(Z)^2], Z standard normal (the consistency constant).
//   c(eff)     = the tuning constant: `wv` minimises (0.5 M(c)^2 / Q(c) - eff)^2 over [0, 100],
//                M = E[Z^2 psi_c(Z)^2] - a, Q = E[psi_c(Z)^4] - a^2 but with the coefficient of
//                E[Z^18 1(|Z| <= c)] / c^14 taken as +8 instead of the binomial -8. Kept as `wv`
//                has it, so the numbers agree: c(0.6) = 4.97336 (the binomial coefficient gives
//                4.40028). docs/wavelet-variance.md says more.
//   scale      for the n coefficients W of one level, x = W / sd(W) (sd with n - 1), then
//                s = the minimiser over [0, 2] of (mean(psi_c(x / sqrt(s))^2) - a(c))^2,
//                and the robust wavelet variance is s var(W).
//   interval   the classical interval's relative half-widths, scaled by sqrt(1 / eff), around
//                the robust value: lower = nu_r (1 - sqrt(1/eff) (nu - lower_c) / nu) (when that
//                is <= 0: the smaller of nu_r / 2 and the lower bounds of the levels before),
//                upper = nu_r (1 + sqrt(1/eff) (upper_c - nu) / nu).
// Both minimisations use Brent's method with R's `optimize` tolerance (brent_minimum.hpp), as
// `wv` does; the estimate therefore carries that tolerance, about 1e-4 relative.

#include <span>
#include <vector>

#include "stochnav/stats/wavelet_variance.hpp"

namespace stochnav {

/// The efficiency `wv` uses by default.
inline constexpr double kWvRobustEfficiency = 0.6;

/// c(eff) as defined above; eff in (0, 0.99] (`wv` refuses more: use the classical estimate).
double biweight_tuning_constant(double efficiency);

/// a(c) = E[psi_c(Z)^2], c > 0.
double biweight_consistency_constant(double c);

/// The robust scale s var(W) of one level's coefficients (n >= 2, not all equal), for the
/// tuning constant c.
double biweight_wavelet_scale(std::span<const double> coefficients, double c);

/// The robust wavelet variance of a record in memory, levels 1 .. J (J >= 1 needs N >= 4), with
/// the interval above. Memory: one level's coefficients and scaling coefficients, two arrays
/// of N values, beside the record. Cost: about 30 passes over each level's coefficients.
std::vector<WaveletVariancePoint> robust_haar_wavelet_variance(
    std::span<const double> rate, double rate_hz, double efficiency = kWvRobustEfficiency);

}  // namespace stochnav
