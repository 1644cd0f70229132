#include "stochnav/stats/robust_wavelet_variance.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "brent_minimum.hpp"
#include "stochnav/stats/parallel.hpp"

namespace stochnav {
namespace {

/// Truncated moments E[Z^(2k) 1(|Z| <= c)], k = 0 .. 10, of a standard normal Z, by the
/// recursion mu_2k = (2k - 1) mu_2k-2 - 2 c^(2k-1) phi(c) (integration by parts).
std::array<double, 11> truncated_normal_moments(double c) {
  const double cdf = 0.5 * std::erfc(-c / std::numbers::sqrt2);
  const double density = std::exp(-0.5 * c * c) / std::sqrt(2.0 * std::numbers::pi);
  std::array<double, 11> mu{};
  mu[0] = 2.0 * cdf - 1.0;
  double c_power = c;  // c^(2k - 1)
  for (int k = 1; k <= 10; ++k) {
    mu[k] = (2.0 * k - 1.0) * mu[k - 1] - 2.0 * c_power * density;
    c_power *= c * c;
  }
  return mu;
}

/// E[Z^2 (1 - Z^2/c^2)^4 1(|Z| <= c)] shifted by `power` (Z^(2 + 2 power) instead of Z^2):
/// sum over i of binomial(4, i) (-1)^i mu_(2 + 2 power + 2i) / c^(2i).
double biweight_moment(const std::array<double, 11>& mu, double c, int power) {
  constexpr std::array<double, 5> kBinomial = {1.0, -4.0, 6.0, -4.0, 1.0};
  const double inverse_c2 = 1.0 / (c * c);
  double total = 0.0;
  double scale = 1.0;
  for (int i = 0; i <= 4; ++i) {
    total += kBinomial[i] * mu[1 + power + i] * scale;
    scale *= inverse_c2;
  }
  return total;
}

/// 0.5 M^2 / Q as `wv` computes it (see the header: one coefficient of Q as `wv` has it).
double wv_biweight_efficiency(double c) {
  const auto mu = truncated_normal_moments(c);
  const double a = biweight_moment(mu, c, 0);
  const double m = biweight_moment(mu, c, 1) - a;
  // E[Z^4 (1 - Z^2/c^2)^8] by the binomial expansion, except the Z^18 term's sign (wv's).
  constexpr std::array<double, 9> kCoefficients = {1.0,   -8.0, 28.0, -56.0, 70.0,
                                                   -56.0, 28.0, 8.0,  1.0};
  const double inverse_c2 = 1.0 / (c * c);
  double fourth = 0.0;
  double scale = 1.0;
  for (int i = 0; i <= 8; ++i) {
    fourth += kCoefficients[i] * mu[2 + i] * scale;
    scale *= inverse_c2;
  }
  const double q = fourth - a * a;
  return 0.5 * m * m / q;
}

/// sum over the coefficients of psi_c(w k)^2, in fixed chunks over the stats threads (the same
/// sum for every thread count).
double biweight_sum(std::span<const double> w, double k, double c) {
  constexpr std::size_t kBiweightChunk = std::size_t{1} << 15;
  const std::size_t chunks = (w.size() + kBiweightChunk - 1) / kBiweightChunk;
  std::vector<double> partial(chunks);
  const double c2 = c * c;
  parallel_for(chunks, [&](std::size_t chunk) {
    const std::size_t first = chunk * kBiweightChunk;
    const std::size_t last = std::min(w.size(), first + kBiweightChunk);
    double sum = 0.0;
    for (std::size_t i = first; i < last; ++i) {
      const double r = w[i] * k;
      const double r2 = r * r;
      if (r2 <= c2) {
        const double t = 1.0 - r2 / c2;
        const double t2 = t * t;
        sum += r2 * t2 * t2;
      }
    }
    partial[chunk] = sum;
  });
  double total = 0.0;
  for (double p : partial) total += p;
  return total;
}

}  // namespace

double biweight_tuning_constant(double efficiency) {
  if (!(efficiency > 0.0 && efficiency <= 0.99)) {
    throw std::invalid_argument("biweight_tuning_constant: efficiency must be in (0, 0.99]");
  }
  return brent_minimum(
      [efficiency](double c) {
        const double gap = wv_biweight_efficiency(c) - efficiency;
        return gap * gap;
      },
      0.0, 100.0, r_optimize_tolerance());
}

double biweight_consistency_constant(double c) {
  return biweight_moment(truncated_normal_moments(c), c, 0);
}

double biweight_wavelet_scale(std::span<const double> coefficients, double c) {
  const auto n = static_cast<double>(coefficients.size());
  double mean = 0.0;
  for (double w : coefficients) mean += w;
  mean /= n;
  double squares = 0.0;
  for (double w : coefficients) squares += (w - mean) * (w - mean);
  const double variance = squares / (n - 1.0);
  if (!(variance > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  const double sd = std::sqrt(variance);
  const double a = biweight_consistency_constant(c);
  const double s = brent_minimum(
      [&](double scale) {
        const double gap = biweight_sum(coefficients, 1.0 / (sd * std::sqrt(scale)), c) / n - a;
        return gap * gap;
      },
      0.0, 2.0, r_optimize_tolerance());
  return s * variance;
}

std::vector<WaveletVariancePoint> robust_haar_wavelet_variance(std::span<const double> rate,
                                                               double rate_hz, double efficiency) {
  const double c = biweight_tuning_constant(efficiency);
  const double widen = std::sqrt(1.0 / efficiency);
  const int levels = wavelet_variance_levels(rate.size());
  const std::size_t n = rate.size();
  std::vector<double> scaling(rate.begin(), rate.end());  // V_{j-1}
  std::vector<double> w;
  std::vector<WaveletVariancePoint> points;
  double lowest_lower = std::numeric_limits<double>::infinity();
  for (int j = 1; j <= levels; ++j) {
    const std::size_t lag = std::size_t{1} << (j - 1);
    const std::size_t first = (std::size_t{1} << j) - 1;  // first t without boundary
    w.resize(n - first);
    for (std::size_t t = first; t < n; ++t) w[t - first] = 0.5 * (scaling[t] - scaling[t - lag]);
    for (std::size_t t = n; t-- > first;) scaling[t] = 0.5 * (scaling[t] + scaling[t - lag]);

    WaveletVariancePoint classical;
    classical.level = j;
    classical.scale_samples = std::size_t{1} << j;
    classical.scale_s = static_cast<double>(classical.scale_samples) / rate_hz;
    classical.coefficients = w.size();
    double squares = 0.0;
    for (double value : w) squares += value * value;
    classical.variance = squares / static_cast<double>(w.size());
    set_wavelet_variance_interval(classical);

    WaveletVariancePoint robust = classical;
    robust.variance = biweight_wavelet_scale(w, c);
    const double lower_width = (classical.variance - classical.lower) / classical.variance;
    const double upper_width = (classical.upper - classical.variance) / classical.variance;
    robust.lower = robust.variance - lower_width * widen * robust.variance;
    if (!(robust.lower > 0.0)) robust.lower = std::min(robust.variance / 2.0, lowest_lower);
    robust.upper = robust.variance + upper_width * widen * robust.variance;
    lowest_lower = std::min(lowest_lower, robust.lower);
    points.push_back(robust);
  }
  return points;
}

}  // namespace stochnav
