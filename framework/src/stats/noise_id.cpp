#include "stochnav/stats/noise_id.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace stochnav {
namespace {

constexpr int kMaxDifferences = 3;
using PerDifference = std::array<double, kMaxDifferences + 1>;

/// Means of the d-th differences of z[k] = x[k m], k < points, d = 0 .. MaxD: one pass for z,
/// the sums of its differences telescope.
template <int MaxD>
PerDifference decimated_difference_means(std::span<const double> phase, std::size_t m,
                                         std::size_t points) {
  const auto z = [&](std::size_t k) { return phase[k * m]; };
  PerDifference mean{};
  for (std::size_t k = 0; k < points; ++k) mean[0] += z(k);
  mean[0] /= static_cast<double>(points);
  const std::size_t last = points - 1;
  if constexpr (MaxD >= 1) mean[1] = (z(last) - z(0)) / static_cast<double>(points - 1);
  if constexpr (MaxD >= 2) {
    mean[2] = ((z(last) - z(last - 1)) - (z(1) - z(0))) / static_cast<double>(points - 2);
  }
  if constexpr (MaxD >= 3) {
    mean[3] = ((z(last) - 2.0 * z(last - 1) + z(last - 2)) - (z(2) - 2.0 * z(1) + z(0))) /
              static_cast<double>(points - 3);
  }
  return mean;
}

/// Lag-1 autocorrelations r1[d], d = 0 .. MaxD, of the d-th differences of the decimated phase
/// z[k] = x[k m], k < points (> MaxD + 1), read on the fly (no copy of a long record): one pass
/// for the mean of z, one pass for all the sums. No trend is removed: Stable32's
/// identifications match the raw decimated phase (removing a quadratic first changes them on the
/// Cs 5071A record).
template <int MaxD>
PerDifference lag1_of_decimated_differences(std::span<const double> phase, std::size_t m,
                                            std::size_t points) {
  const auto z = [&](std::size_t k) { return phase[k * m]; };
  const PerDifference mean = decimated_difference_means<MaxD>(phase, m, points);
  PerDifference lagged{};
  PerDifference squares{};
  PerDifference previous{};
  // recent = z(k), z(k-1), z(k-2), z(k-3); the d-th difference that ends at k starts at k - d.
  std::array<double, 4> recent{};
  const auto step_to = [&](std::size_t k) {
    recent = {z(k), recent[0], recent[1], recent[2]};
    const auto& [z0, z1, z2, z3] = recent;
    return PerDifference{z0, z0 - z1, z0 - 2.0 * z1 + z2, z0 - 3.0 * z1 + 3.0 * z2 - z3};
  };
  // The first MaxD + 1 points, where the higher differences are still incomplete.
  for (std::size_t k = 0; k <= MaxD; ++k) {
    const PerDifference value = step_to(k);
    for (std::size_t d = 0; d <= k; ++d) {
      const double centred = value[d] - mean[d];
      if (k > d) lagged[d] += previous[d] * centred;
      squares[d] += centred * centred;
      previous[d] = centred;
    }
  }
  for (std::size_t k = MaxD + 1; k < points; ++k) {
    const PerDifference value = step_to(k);
    for (std::size_t d = 0; d <= MaxD; ++d) {  // unrolled: MaxD is a constant
      const double centred = value[d] - mean[d];
      lagged[d] += previous[d] * centred;
      squares[d] += centred * centred;
      previous[d] = centred;
    }
  }
  PerDifference r1{};
  for (std::size_t d = 0; d <= MaxD; ++d) r1[d] = squares[d] > 0.0 ? lagged[d] / squares[d] : 0.0;
  return r1;
}

NoiseId lag1_noise_id(std::span<const double> phase, std::size_t m, int max_differences) {
  const std::size_t points = (phase.size() - 1) / m + 1;
  const PerDifference r1 = max_differences >= 3
                               ? lag1_of_decimated_differences<3>(phase, m, points)
                               : lag1_of_decimated_differences<2>(phase, m, points);
  for (int d = 0;; ++d) {
    const double r = r1[static_cast<std::size_t>(d)];
    const double delta = r / (1.0 + r);
    if (delta < 0.25 || d >= max_differences) {
      const double alpha = 2.0 - 2.0 * d - 2.0 * delta;
      const auto rounded = static_cast<int>(2 - 2 * d - std::lround(2.0 * delta));
      return {std::clamp(rounded, -2, 2), NoiseIdMethod::kLag1Autocorrelation, alpha};
    }
  }
}

/// Allan-variance tau exponent mu -> noise alpha; mu = -2 is white or flicker PM (alpha 2, 1).
int alpha_from_mu(int mu) { return std::clamp(-1 - mu, -2, 2); }

/// Sample variance of the non-overlapping frequency averages over their Allan variance.
double b1_ratio(std::span<const double> phase, std::size_t m) {
  const std::size_t n = (phase.size() - 1) / m;
  const auto average = [&](std::size_t k) { return phase[(k + 1) * m] - phase[k * m]; };
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += average(k);
  mean /= static_cast<double>(n);
  double variance = 0.0;
  double allan = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double deviation = average(k) - mean;
    variance += deviation * deviation;
    if (k + 1 < n) {
      const double step = average(k + 1) - average(k);
      allan += step * step;
    }
  }
  variance /= static_cast<double>(n - 1);
  allan /= 2.0 * static_cast<double>(n - 1);
  return allan > 0.0 ? variance / allan : 1.0;
}

/// R(n) = MVAR / AVAR at m: about 1/m for white PM, much larger for flicker PM.
int white_or_flicker_pm(std::span<const double> phase, std::size_t m) {
  const double md = static_cast<double>(m);
  const double modified = deviation_value(Deviation::kMdev, phase, 1.0, m);
  const double allan = deviation_value(Deviation::kOadev, phase, 1.0, m);
  if (!(allan > 0.0)) return 1;
  const double ratio = (modified * modified) / (allan * allan);
  const double white_pm = 1.0 / md;
  const double flicker_pm =
      3.0 * std::log(256.0 / 27.0) / (2.0 * (1.038 + 3.0 * std::log(std::numbers::pi * md)));
  return ratio < std::sqrt(white_pm * flicker_pm) ? 2 : 1;
}

NoiseId b1_noise_id(Deviation kind, std::span<const double> phase, std::size_t m) {
  // Stable32 evaluates the expected ratios at the estimator's term count (its `#` column), not
  // at the number of averages: that is what reproduces its tables (Cs 5071A, all taus). Fewer
  // than 2 makes every expectation 1 (no information) rather than undefined.
  const double n = static_cast<double>(std::max<std::size_t>(term_count(kind, m, phase.size()), 2));
  const double ratio = b1_ratio(phase, m);
  int mu = -2;
  while (mu < 2 && ratio >= std::sqrt(b1_expected(n, mu) * b1_expected(n, mu + 1))) ++mu;
  if (mu != -2) return {alpha_from_mu(mu), NoiseIdMethod::kB1Ratio, ratio};
  // R(n) needs one MDEV term: N >= 3m.
  if (term_count(Deviation::kMdev, m, phase.size()) == 0) {
    return {1, NoiseIdMethod::kB1Ratio, ratio};
  }
  return {white_or_flicker_pm(phase, m), NoiseIdMethod::kB1AndRn, ratio};
}

}  // namespace

double lag1_autocorrelation(std::span<const double> series) {
  if (series.size() < 2) return 0.0;
  return lag1_of_decimated_differences<0>(series, 1, series.size())[0];
}

double b1_expected(double n, int mu) {
  if (mu == 0) return n * std::log(n) / (2.0 * (n - 1.0) * std::numbers::ln2);
  const double p = static_cast<double>(mu);
  return n * (1.0 - std::pow(n, p)) / (2.0 * (n - 1.0) * (1.0 - std::pow(2.0, p)));
}

bool keeps_previous_noise_type(Deviation kind, std::size_t m, std::size_t phase_count) {
  if (m == 0 || phase_count < 2) return false;
  const std::size_t averages = (phase_count - 1) / m;
  if (averages + 1 >= kMinLag1Points) return false;
  return averages < (is_overlapping(kind) ? 8u : 10u);
}

NoiseId identify_noise(Deviation kind, std::span<const double> phase, std::size_t m) {
  if (m == 0 || phase.size() < 2 * m + 2) {
    throw std::invalid_argument("identify_noise: m = " + std::to_string(m) + " needs more than " +
                                std::to_string(2 * m + 1) + " phase points, got " +
                                std::to_string(phase.size()));
  }
  const std::size_t decimated_points = (phase.size() - 1) / m + 1;
  if (decimated_points >= kMinLag1Points) {
    return lag1_noise_id(phase, m, difference_order(kind));
  }
  return b1_noise_id(kind, phase, m);
}

}  // namespace stochnav
