#include "stochnav/sim/noise_generator.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numeric>
#include <vector>

#include "sanitized_build.hpp"
#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

NoiseModel full_model() {
  return NoiseModel{Unit::kDegPerHour,
                    100.0,
                    {QuantizationTerm{1e-6}, AngleRandomWalkTerm{1e-5}, BiasInstabilityTerm{1e-6},
                     RateRandomWalkTerm{1e-7}, RateRampTerm{1e-9}, GaussMarkovTerm{1e-6, 10.0},
                     SinusoidTerm{1e-6, 3.0, std::nullopt}}};
}

TEST(NoiseGenerator, SameSeedSameRecordDifferentSeedDifferentRecord) {
  const auto a = simulate_noise(full_model(), 50.0, 100.0, 42);
  const auto b = simulate_noise(full_model(), 50.0, 100.0, 42);
  const auto c = simulate_noise(full_model(), 50.0, 100.0, 43);
  ASSERT_EQ(a.size(), 5000u);
  EXPECT_EQ(a, b);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differ += a[i] != c[i];
  EXPECT_EQ(differ, a.size());
}

TEST(NoiseGenerator, BlocksOfAnySizeGiveTheSameRecord) {
  const auto whole = simulate_noise(full_model(), 50.0, 100.0, 9);
  NoiseGenerator generator(full_model(), 100.0, 9, 50.0);
  std::vector<double> pieces;
  std::size_t block = 1;
  while (pieces.size() < whole.size()) {
    std::vector<double> out(std::min(block, whole.size() - pieces.size()));
    generator.generate(out);
    pieces.insert(pieces.end(), out.begin(), out.end());
    block = block * 3 + 1;
  }
  EXPECT_EQ(generator.next_index(), whole.size());
  ASSERT_EQ(pieces.size(), whole.size());
  for (std::size_t i = 0; i < whole.size(); ++i) EXPECT_EQ(pieces[i], whole[i]) << i;
}

TEST(NoiseGenerator, AddingATermLeavesTheOthersNoiseUnchanged) {
  NoiseModel white{Unit::kRadPerSecond, 10.0, {AngleRandomWalkTerm{1.0}}};
  NoiseModel with_ramp = white;
  with_ramp.terms.push_back(RateRampTerm{2.0});
  const auto a = simulate_noise(white, 10.0, 10.0, 5);
  const auto b = simulate_noise(with_ramp, 10.0, 10.0, 5);
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(b[k] - a[k], 2.0 * (static_cast<double>(k) + 0.5) * 0.1, 1e-12);
  }
}

TEST(NoiseGenerator, NonstationarySegmentsScaleTheOtherTerms) {
  NoiseModel base{Unit::kRadPerSecond, 10.0, {AngleRandomWalkTerm{1.0}, RateRampTerm{0.5}}};
  NoiseModel scaled = base;
  scaled.terms.push_back(NonstationaryTerm{{{2.0, 3.0, 8.0}, {5.05, 5.25, 0.0}}});
  const auto a = simulate_noise(base, 10.0, 10.0, 3);
  const auto b = simulate_noise(scaled, 10.0, 10.0, 3);
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double t = static_cast<double>(k) / 10.0;
    const double scale = (t >= 2.0 && t < 3.0) ? 8.0 : (t >= 5.05 && t < 5.25) ? 0.0 : 1.0;
    EXPECT_DOUBLE_EQ(b[k], scale * a[k]) << "t = " << t;
  }
}

TEST(NoiseGenerator, WhiteSampleVarianceIsNSquaredOverTau0) {
  NoiseModel model{Unit::kRadPerSecond, 200.0, {AngleRandomWalkTerm{0.3}}};
  const auto x = simulate_noise(model, 500.0, 200.0, 11);
  double sum2 = 0.0;
  for (double v : x) sum2 += v * v;
  const double variance = sum2 / static_cast<double>(x.size());
  EXPECT_NEAR(variance, 0.09 * 200.0, 0.02 * 0.09 * 200.0);
}

TEST(NoiseGenerator, GaussMarkovStartsStationary) {
  // Sample variance of a long-correlated GM across seeds at sample 0 equals sigma^2 (nearly:
  // the interval mean of a slowly varying state).
  NoiseModel model{Unit::kRadPerSecond, 100.0, {GaussMarkovTerm{2.0, 1000.0}}};
  double sum2 = 0.0;
  constexpr int kSeeds = 2000;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const auto x = simulate_noise(model, 0.01, 100.0, static_cast<std::uint64_t>(seed));
    sum2 += x[0] * x[0];
  }
  EXPECT_NEAR(sum2 / kSeeds, 4.0, 4.0 * 5.0 * std::sqrt(2.0 / kSeeds));
}

TEST(NoiseGenerator, RejectsInvalidArguments) {
  EXPECT_THROW(simulate_noise(full_model(), 0.0, 100.0, 1), ConfigError);
  EXPECT_THROW(simulate_noise(full_model(), 1.0, -1.0, 1), ConfigError);
  EXPECT_THROW(simulate_noise(full_model(), 0.001, 100.0, 1), ConfigError);
  NoiseModel bad{Unit::kRadPerSecond, 100.0, {GaussMarkovTerm{1.0, 0.0}}};
  try {
    simulate_noise(bad, 1.0, 100.0, 1);
    FAIL();
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("/terms/0/tau_c"), std::string::npos) << error.what();
  }
}

TEST(NoiseGenerator, ThroughputIsSeveralMillionSamplesPerSecond) {
  // Not a benchmark: a guard against a gross slowdown (Release builds reach far more; none
  // under a sanitizer).
  NoiseModel model{Unit::kDegPerHour,
                   100.0,
                   {QuantizationTerm{1e-6}, AngleRandomWalkTerm{1e-5}, RateRandomWalkTerm{1e-7},
                    GaussMarkovTerm{1e-6, 10.0}}};
  NoiseGenerator generator(model, 100.0, 1, 1e4);
  std::vector<double> block(1 << 16);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 32; ++i) generator.generate(block);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double rate = 32.0 * static_cast<double>(block.size()) / seconds;
  std::printf("[ throughput ] Q+N+K+GM: %.1f Msamples/s\n", rate / 1e6);
  NoiseGenerator flicker(NoiseModel{Unit::kDegPerHour, 100.0, {BiasInstabilityTerm{1e-6}}}, 100.0,
                         1, 7.2e5);
  const auto start2 = std::chrono::steady_clock::now();
  for (int i = 0; i < 8; ++i) flicker.generate(block);
  const double seconds2 =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start2).count();
  std::printf("[ throughput ] B (200 h band): %.1f Msamples/s\n",
              8.0 * static_cast<double>(block.size()) / seconds2 / 1e6);
  if (!testing::kSanitizedBuild) {
    EXPECT_GT(rate, 2e6);
  }
}

}  // namespace
}  // namespace stochnav
