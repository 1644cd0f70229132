// Stable32's sets of averaging factors (octave, decade, all) and stochnav's dense set.

#include <algorithm>
#include <array>
#include <cmath>

#include "stochnav/stats/deviation.hpp"

namespace stochnav {
namespace {

std::vector<std::size_t> octave_factors(std::size_t max_m) {
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; m <= max_m; m *= 2) factors.push_back(m);
  return factors;
}

std::vector<std::size_t> decade_factors(std::size_t max_m) {
  std::vector<std::size_t> factors;
  for (std::size_t decade = 1; decade <= max_m; decade *= 10) {
    for (const std::size_t multiple : std::array<std::size_t, 3>{1, 2, 4}) {
      if (multiple * decade <= max_m) factors.push_back(multiple * decade);
    }
  }
  return factors;
}

std::vector<std::size_t> dense_factors(std::size_t max_m) {
  std::vector<std::size_t> factors;
  for (int k = 0;; ++k) {
    const auto m = static_cast<std::size_t>(std::llround(std::pow(10.0, k / 10.0)));
    if (m > max_m) break;
    if (factors.empty() || m != factors.back()) factors.push_back(m);
  }
  return factors;
}

// Stable32 spreads its "all tau" points evenly over the decades of tau it plots: with D decades
// each step grows m by a factor of about 1 + 1/K, K = floor(213 / D) (about 490 / D points per
// decade once m > K; every m below).
std::vector<std::size_t> all_tau_factors(std::size_t max_m, double tau0_s) {
  if (!(tau0_s > 0.0) || !std::isfinite(tau0_s)) tau0_s = 1.0;
  const double first_decade = std::floor(std::log10(tau0_s));
  const double last_decade = std::ceil(std::log10(static_cast<double>(max_m) * tau0_s));
  const auto decades = static_cast<std::size_t>(std::max(1.0, last_decade - first_decade));
  const std::size_t k = std::max<std::size_t>(1, 213 / decades);
  std::vector<std::size_t> factors;
  for (std::size_t m = 1; m <= max_m; m += m / k + 1) factors.push_back(m);
  return factors;
}

/// Stable32's "fast" MTIE factors: windows of 2^k points, m = 2^k - 1.
std::vector<std::size_t> window_octave_factors(std::size_t max_m) {
  std::vector<std::size_t> factors;
  for (std::size_t window = 2; window - 1 <= max_m; window *= 2) factors.push_back(window - 1);
  return factors;
}

/// Theo1 needs even factors of at least 10: the others of a set are dropped, an odd one is
/// rounded up to the next even factor (duplicates removed).
std::vector<std::size_t> theo1_factors(const std::vector<std::size_t>& factors, std::size_t max_m) {
  std::vector<std::size_t> even;
  for (std::size_t m : factors) {
    const std::size_t rounded = m + m % 2;
    if (rounded < 10 || rounded > max_m) continue;
    if (even.empty() || rounded != even.back()) even.push_back(rounded);
  }
  return even;
}

std::vector<std::size_t> spaced_factors(TauSpacing spacing, std::size_t max_m, double tau0_s) {
  switch (spacing) {
    case TauSpacing::kOctave:
      return octave_factors(max_m);
    case TauSpacing::kDecade:
      return decade_factors(max_m);
    case TauSpacing::kDense:
      return dense_factors(max_m);
    case TauSpacing::kAll:
      return all_tau_factors(max_m, tau0_s);
  }
  return {};
}

}  // namespace

std::vector<std::size_t> averaging_factors(Deviation kind, TauSpacing spacing,
                                           std::size_t phase_count, double tau0_s) {
  const std::size_t max_m = max_averaging_factor(kind, phase_count);
  if (max_m == 0) return {};
  if (kind == Deviation::kMtie && spacing == TauSpacing::kOctave) {
    return window_octave_factors(max_m);
  }
  if (is_theo1(kind)) return theo1_factors(spaced_factors(spacing, max_m, tau0_s), max_m);
  return spaced_factors(spacing, max_m, tau0_s);
}

}  // namespace stochnav
