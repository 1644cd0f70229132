#pragma once
// Simulated phase records of the five power-law noises, for property tests.

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace stochnav::stats_test {

inline std::vector<double> white_noise(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> values(n);
  for (double& value : values) value = normal(engine);
  return values;
}

/// Running sum with a leading zero: n values -> n + 1 points.
inline std::vector<double> integrated(const std::vector<double>& values) {
  std::vector<double> sums(values.size() + 1, 0.0);
  for (std::size_t i = 0; i < values.size(); ++i) sums[i + 1] = sums[i] + values[i];
  return sums;
}

/// Flicker (1/f) noise: white noise through the fractional-integration filter of N. J. Kasdin
/// (Proc. IEEE 83(5), 1995), h_0 = 1, h_k = h_{k-1} (k - 1/2) / k. O(n^2): keep n small.
inline std::vector<double> flicker_noise(std::size_t n, std::uint64_t seed) {
  const std::vector<double> white = white_noise(n, seed);
  std::vector<double> filter(n);
  filter[0] = 1.0;
  for (std::size_t k = 1; k < n; ++k) {
    filter[k] = filter[k - 1] * (static_cast<double>(k) - 0.5) / static_cast<double>(k);
  }
  std::vector<double> values(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t k = 0; k <= i; ++k) values[i] += filter[k] * white[i - k];
  }
  return values;
}

/// About n phase points of the power-law noise S_y(f) ~ f^alpha, alpha = 2 .. -2.
inline std::vector<double> power_law_phase(int alpha, std::size_t n, std::uint64_t seed) {
  switch (alpha) {
    case 2:
      return white_noise(n, seed);
    case 1:
      return flicker_noise(n, seed);
    case 0:
      return integrated(white_noise(n, seed));
    case -1:
      return integrated(flicker_noise(n, seed));
    default:
      return integrated(integrated(white_noise(n, seed)));
  }
}

}  // namespace stochnav::stats_test
