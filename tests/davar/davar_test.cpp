#include "stochnav/stats/davar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stochnav/core/errors.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav {
namespace {

// White noise plus a bias, a random walk and a variance step half-way: nothing special about
// any window.
Record test_record(std::size_t samples, double rate_hz, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Record record;
  record.rate_hz = rate_hz;
  record.source = "generated";
  double walk = 0.0;
  for (std::size_t i = 0; i < samples; ++i) {
    walk += 0.01 * normal(engine);
    const double scale = i < samples / 2 ? 1.0 : 3.0;
    record.values.push_back(400.0 + walk + scale * normal(engine));
  }
  return record;
}

// The naive reference: an overlapping Allan deviation of each window on its own.
double naive_window_adev(const Record& record, std::size_t start, std::size_t window,
                         std::size_t m) {
  const std::span<const double> samples(record.values.data() + start, window);
  const auto phase = phase_from_rate(samples, record.tau0());
  return deviation_value(Deviation::kOadev, phase, record.tau0(), m);
}

struct WindowCase {
  std::size_t samples, window, step;
};

class DavarMatchesNaive : public ::testing::TestWithParam<WindowCase> {};

TEST_P(DavarMatchesNaive, EveryWindowEqualsItsOwnOadev) {
  const auto [samples, window, step] = GetParam();
  const Record record = test_record(samples, 100.0, 7 + samples + window + step);
  const DavarResult davar = dynamic_allan_deviation(record, {.window = window, .step = step});
  const std::size_t expected_windows = (samples - window) / step + 1;
  ASSERT_EQ(davar.time_s.size(), expected_windows);
  ASSERT_EQ(davar.m, default_davar_m_values(window, DataKind::kRate));
  for (std::size_t k = 0; k < expected_windows; ++k) {
    EXPECT_NEAR(davar.time_s[k], (static_cast<double>(k * step) + 0.5 * static_cast<double>(window)) / 100.0, 1e-9);
    for (std::size_t j = 0; j < davar.m.size(); ++j) {
      const double naive = naive_window_adev(record, k * step, window, davar.m[j]);
      ASSERT_NEAR(davar.adev[k][j], naive, 1e-9 * naive) << "window " << k << " m " << davar.m[j];
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Shapes, DavarMatchesNaive,
                         ::testing::Values(WindowCase{2000, 500, 100}, WindowCase{2000, 500, 1},
                                           WindowCase{2000, 300, 700}, WindowCase{5000, 5000, 3},
                                           WindowCase{300000, 50000, 5000},
                                           WindowCase{1001, 37, 13}));

TEST(Davar, CausalTimesAreWindowEnds) {
  Record record = test_record(1000, 10.0, 3);
  record.start_time_s = 100.0;
  const DavarResult davar =
      dynamic_allan_deviation(record, {.window = 200, .step = 50, .causal = true});
  ASSERT_EQ(davar.time_s.size(), 17U);
  EXPECT_NEAR(davar.time_s.front(), 100.0 + 20.0, 1e-12);
  EXPECT_NEAR(davar.time_s.back(), 100.0 + 100.0, 1e-12);
}

TEST(Davar, PhaseInputMatchesRateInput) {
  const Record rate = test_record(3000, 1.0, 11);
  Record phase = rate;
  phase.kind = DataKind::kPhase;
  phase.values = phase_from_rate(rate.values, rate.tau0());
  const auto from_rate = dynamic_allan_deviation(rate, {.window = 1000, .step = 250});
  const auto from_phase = dynamic_allan_deviation(phase, {.window = 1001, .step = 250});
  ASSERT_EQ(from_rate.adev.size(), from_phase.adev.size());
  for (std::size_t k = 0; k < from_rate.adev.size(); ++k) {
    for (std::size_t j = 0; j < from_rate.m.size(); ++j) {
      EXPECT_NEAR(from_rate.adev[k][j], from_phase.adev[k][j], 1e-9 * from_rate.adev[k][j]);
    }
  }
}

TEST(Davar, StreamingMemoryDoesNotGrowWithRecordLength) {
  constexpr std::size_t kWindow = 4000;
  constexpr std::size_t kBlock = 4096;
  std::size_t rows = 0;
  DavarAccumulator davar({.window = kWindow, .step = 500}, DataKind::kRate, 100.0, 0.0,
                         [&rows](const DavarRow&) { ++rows; });
  std::mt19937_64 engine(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> block(kBlock);
  std::size_t most_buffered = 0;
  for (int b = 0; b < 500; ++b) {  // 2M samples
    for (double& y : block) y = normal(engine);
    davar.push(block);
    most_buffered = std::max(most_buffered, davar.buffered_points());
  }
  EXPECT_EQ(rows, (500 * kBlock - kWindow) / 500 + 1);
  EXPECT_LE(most_buffered, 2 * davar.m_values().back() + 2 * kBlock + 32768);
}

TEST(Davar, RejectsBadWindowAndStep) {
  const Record record = test_record(100, 1.0, 1);
  EXPECT_THROW(dynamic_allan_deviation(record, {.window = 50, .step = 0}), ConfigError);
  EXPECT_THROW(dynamic_allan_deviation(record, {.window = 101, .step = 1}), ConfigError);
  try {
    dynamic_allan_deviation(record, {.window = 500, .step = 1});
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("longer than the record"), std::string::npos);
  }
}

}  // namespace
}  // namespace stochnav
