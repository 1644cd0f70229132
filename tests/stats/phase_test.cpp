#include "stochnav/stats/phase.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "power_law_noise.hpp"

namespace stochnav {
namespace {

TEST(PhaseFromRate, IntegratesTheMeanRemovedRate) {
  const std::vector<double> rate = {1.0, 3.0, 2.0, 6.0};  // mean 3
  const std::vector<double> phase = phase_from_rate(rate, 0.5);
  EXPECT_EQ(phase, (std::vector<double>{0.0, -1.0, -1.0, -1.5, 0.0}));
  EXPECT_EQ(phase_from_rate({}, 1.0), (std::vector<double>{0.0}));
}

TEST(PhaseFromRate, StaysAccurateOverLongRecords) {
  // A large bias with small noise, y = 1e4 + k 2^-30 with integer |k| <= 2^16: exact in double,
  // so the exact phase is known, (S_i - i K / n) 2^-30 with S_i = k_0 + ... + k_(i-1), K = S_n
  // (S_i n < 2^63: exact in 64-bit integers).
  // Naive running sums would be off by about n eps |bias| = 4e-6 at the end.
  const std::size_t n = 2'000'000;
  std::mt19937_64 engine(4);
  std::uniform_int_distribution<std::int64_t> uniform(-(1 << 16), 1 << 16);
  std::vector<std::int64_t> k(n);
  std::vector<double> rate(n);
  std::int64_t total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    k[i] = uniform(engine);
    rate[i] = 1.0e4 + std::ldexp(static_cast<double>(k[i]), -30);
    total += k[i];
  }
  const std::vector<double> phase = phase_from_rate(rate, 1.0);
  std::int64_t partial = 0;
  double worst = 0.0;
  for (std::size_t i = 1; i <= n; ++i) {
    partial += k[i - 1];
    const std::int64_t numerator =
        partial * static_cast<std::int64_t>(n) - static_cast<std::int64_t>(i) * total;
    const long double exact =
        std::ldexp(static_cast<long double>(numerator) / static_cast<long double>(n), -30);
    worst = std::max(worst, std::abs(static_cast<double>(exact) - phase[i]));
  }
  EXPECT_LT(worst, 1e-12);
}

}  // namespace
}  // namespace stochnav
