// The Haar wavelet variance against the R package `wv` on the real ADIS16405 record (every
// channel and scale to 1e-8 relative, ../shared/data/gmwm/SOURCES.md), and its properties: the
// identity with the overlapping Allan variance, block-size independence, the streaming memory
// bound, white noise inside its interval.

#include "stochnav/stats/wavelet_variance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "stochnav/io/record.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"
#include "temp_dir.hpp"
#include "wv_reference.hpp"

namespace stochnav {
namespace {

double wv_relative_difference(double value, double reference) {
  return std::abs(value / reference - 1.0);
}

std::vector<double> wv_white_noise(std::size_t n, double sigma, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> y(n);
  for (double& v : y) v = normal(engine);
  return y;
}

TEST(WaveletVariance, LevelsAreFloorLog2MinusOne) {
  EXPECT_EQ(wavelet_variance_levels(3), 0);
  EXPECT_EQ(wavelet_variance_levels(4), 1);
  EXPECT_EQ(wavelet_variance_levels(15), 2);
  EXPECT_EQ(wavelet_variance_levels(16), 3);
  EXPECT_EQ(wavelet_variance_levels(1'000'000), 18);
}

TEST(WaveletVariance, MatchesTheWvPackageOnEveryAdisChannelAndScale) {
  STOCHNAV_REQUIRE_SHARED_DATA(table_path, "gmwm/adis_wv_ref.csv");
  STOCHNAV_REQUIRE_SHARED_DATA(record_path, "imu-static/adis16405_imu1_static_100hz.csv");
  const auto reference = testing::read_wv_reference(table_path);
  ASSERT_EQ(reference.size(), 6u);
  double worst = 0.0;
  for (const auto& [channel, rows] : reference) {
    SCOPED_TRACE(channel);
    const Record record = read_record(
        {.path = record_path, .column = testing::adis_wv_channel_columns().at(channel)});
    ASSERT_EQ(record.values.size(), 1'000'000u);
    const auto points = haar_wavelet_variance(record.values, record.rate_hz);
    ASSERT_EQ(points.size(), rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
      EXPECT_EQ(points[i].scale_samples, std::size_t{1} << (i + 1));
      EXPECT_EQ(points[i].coefficients, 1'000'000u - (std::size_t{1} << (i + 1)) + 1);
      EXPECT_LT(wv_relative_difference(points[i].scale_s, rows[i].scale_s), 1e-12);
      EXPECT_LT(wv_relative_difference(points[i].variance, rows[i].wv), 1e-8) << "level " << i + 1;
      EXPECT_LT(wv_relative_difference(points[i].lower, rows[i].ci_low), 1e-8) << "level " << i + 1;
      EXPECT_LT(wv_relative_difference(points[i].upper, rows[i].ci_high), 1e-8)
          << "level " << i + 1;
      worst = std::max({worst, wv_relative_difference(points[i].variance, rows[i].wv),
                        wv_relative_difference(points[i].lower, rows[i].ci_low),
                        wv_relative_difference(points[i].upper, rows[i].ci_high)});
    }
  }
  std::printf("[ wv ref   ] largest relative difference from wv over 6 x 18 rows: %.2e\n", worst);
}

TEST(WaveletVariance, IsHalfTheOverlappingAllanVarianceAtHalfTheScale) {
  const auto y = wv_white_noise(5000, 0.3, 7);
  const auto points = haar_wavelet_variance(y, 10.0);
  const auto phase = phase_from_rate(y, 0.1);
  for (const auto& p : points) {
    const double adev = deviation_value(Deviation::kOadev, phase, 0.1, p.scale_samples / 2);
    EXPECT_NEAR(p.variance, adev * adev / 2.0, 1e-12 * p.variance) << p.level;
    EXPECT_EQ(p.coefficients, term_count(Deviation::kOadev, p.scale_samples / 2, phase.size()));
  }
}

TEST(WaveletVariance, DoesNotDependOnTheBlockSizes) {
  const auto y = wv_white_noise(10'000, 1.0, 3);
  const auto whole = haar_wavelet_variance(y, 1.0);
  for (std::size_t block : {1u, 3u, 64u, 1000u, 4096u}) {
    HaarWaveletVarianceAccumulator accumulator(wavelet_variance_levels(y.size()));
    for (std::size_t first = 0; first < y.size(); first += block) {
      accumulator.push(
          std::span<const double>(y).subspan(first, std::min(block, y.size() - first)));
    }
    const auto blocks = accumulator.result(1.0);
    ASSERT_EQ(blocks.size(), whole.size());
    for (std::size_t i = 0; i < whole.size(); ++i) {
      EXPECT_EQ(blocks[i].variance, whole[i].variance) << "block " << block << " level " << i + 1;
    }
  }
}

TEST(WaveletVariance, StreamingHoldsOnlyTheDelayLines) {
  // max_level 10: 2^10 - 1 values at most, however long the record.
  HaarWaveletVarianceAccumulator accumulator(10);
  const auto y = wv_white_noise(1 << 16, 1.0, 5);
  for (int repeat = 0; repeat < 8; ++repeat) {
    accumulator.push(y);
    EXPECT_LE(accumulator.buffered_values(), (1u << 10) - 1);
  }
  EXPECT_EQ(accumulator.result(1.0).size(), 10u);
}

TEST(WaveletVariance, WhiteNoiseLiesInsideItsIntervals) {
  // nu^2_j = sigma^2 / 2^j for white noise; with 95 % intervals, at most a few of 14 levels miss.
  const double sigma = 2.0;
  const auto points = haar_wavelet_variance(wv_white_noise(1 << 16, sigma, 11), 100.0);
  int outside = 0;
  for (const auto& p : points) {
    const double truth = sigma * sigma / static_cast<double>(p.scale_samples);
    EXPECT_LT(p.lower, p.variance);
    EXPECT_GT(p.upper, p.variance);
    if (truth < p.lower || truth > p.upper) ++outside;
  }
  EXPECT_EQ(points.size(), 15u);
  EXPECT_LE(outside, 2);
}

}  // namespace
}  // namespace stochnav
