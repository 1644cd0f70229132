#include "stochnav/stats/noise_id.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "power_law_noise.hpp"

namespace stochnav {
namespace {

struct NoiseCase {
  int alpha;
  std::vector<std::size_t> m_values;  // where the lag-1 method is reliable for this noise
};

class NoiseIdentification : public ::testing::TestWithParam<NoiseCase> {};

// 40 seeds of 4096 points: every identification must be right.
TEST_P(NoiseIdentification, FindsTheSimulatedNoise) {
  const NoiseCase& c = GetParam();
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    const std::vector<double> phase = stats_test::power_law_phase(c.alpha, 4096, 1000 + seed);
    for (std::size_t m : c.m_values) {
      for (Deviation kind : {Deviation::kOadev, Deviation::kMdev, Deviation::kHdev}) {
        const NoiseId id = identify_noise(kind, phase, m);
        EXPECT_EQ(id.method, NoiseIdMethod::kLag1Autocorrelation);
        EXPECT_EQ(id.alpha, c.alpha)
            << "seed " << seed << " m " << m << " estimate " << id.statistic;
      }
    }
  }
}

// Flicker noises are identified reliably at m = 1 only: decimating a flicker record without
// averaging aliases it towards white (a known limit of the lag-1 method on decimated phase).
std::string alpha_name(const ::testing::TestParamInfo<NoiseCase>& info) {
  return "Alpha" + std::string(info.param.alpha < 0 ? "Minus" : "") +
         std::to_string(std::abs(info.param.alpha));
}

INSTANTIATE_TEST_SUITE_P(PowerLawNoises, NoiseIdentification,
                         ::testing::Values(NoiseCase{2, {1, 4, 16}}, NoiseCase{1, {1}},
                                           NoiseCase{0, {1, 4, 16}}, NoiseCase{-1, {1}},
                                           NoiseCase{-2, {1, 4, 16, 64}}),
                         alpha_name);

TEST(NoiseIdentification, LongWhiteFmRecordAtManyFactors) {
  const std::vector<double> phase = stats_test::power_law_phase(0, 1 << 17, 7);
  for (std::size_t m = 1; m <= 1024; m *= 2) {
    EXPECT_EQ(identify_noise(Deviation::kOadev, phase, m).alpha, 0) << "m " << m;
  }
}

// B1 (with R(n) for the PM noises) from 28 non-overlapping averages (m = 100 on 2801 points):
// a coarse fallback, so only a majority of seeds is asserted. ADEV takes the expectations at
// its 27 terms; the overlapping estimators take them at N - 2m terms, as Stable32 does.
TEST(NoiseIdentification, FewPointsUseTheB1Ratio) {
  for (int alpha : {2, 0, -2}) {
    std::size_t right = 0;
    for (std::uint64_t seed = 1; seed <= 30; ++seed) {
      const std::vector<double> phase = stats_test::power_law_phase(alpha, 2800, seed);
      const NoiseId id = identify_noise(Deviation::kAdev, phase, 100);
      EXPECT_NE(id.method, NoiseIdMethod::kLag1Autocorrelation);
      if (id.alpha == alpha) ++right;
    }
    EXPECT_GE(right, 21u) << "alpha " << alpha;
  }
}

TEST(NoiseIdentification, B1ExpectationsFollowBarnes) {
  // mu = -1 (white FM): the sample variance equals the Allan variance.
  EXPECT_DOUBLE_EQ(b1_expected(10.0, -1), 1.0);
  // mu = 1 (random-walk FM): N / 2; mu = 2: N (N + 1) / 6; mu = -2: (N^2 - 1) / (1.5 N (N - 1)).
  EXPECT_NEAR(b1_expected(10.0, 1), 5.0, 1e-12);
  EXPECT_NEAR(b1_expected(10.0, 2), 110.0 / 6.0, 1e-12);
  EXPECT_NEAR(b1_expected(10.0, -2), 99.0 / 135.0, 1e-12);
  // mu = 0 (flicker FM) is the limit N ln N / (2 (N - 1) ln 2).
  EXPECT_NEAR(b1_expected(10.0, 0), 10.0 * std::log(10.0) / (18.0 * std::log(2.0)), 1e-12);
}

TEST(NoiseIdentification, KeepsThePreviousTypeOnlyWithVeryFewAverages) {
  // 1001 points: m = 128 leaves 7 averages, m = 100 leaves 10, m = 125 leaves 8.
  EXPECT_TRUE(keeps_previous_noise_type(Deviation::kOadev, 128, 1001));
  EXPECT_FALSE(keeps_previous_noise_type(Deviation::kOadev, 125, 1001));
  EXPECT_TRUE(keeps_previous_noise_type(Deviation::kAdev, 125, 1001));
  EXPECT_FALSE(keeps_previous_noise_type(Deviation::kAdev, 100, 1001));
  EXPECT_FALSE(keeps_previous_noise_type(Deviation::kAdev, 1, 1001));
}

TEST(NoiseIdentification, Lag1AutocorrelationOfSimpleSeries) {
  EXPECT_DOUBLE_EQ(lag1_autocorrelation(std::vector<double>{1.0, -1.0, 1.0, -1.0}), -0.75);
  EXPECT_DOUBLE_EQ(lag1_autocorrelation(std::vector<double>{2.0, 2.0, 2.0}), 0.0);
  EXPECT_DOUBLE_EQ(lag1_autocorrelation(std::vector<double>{5.0}), 0.0);
}

// The plausible types (the EDF rule's input, deviation.hpp EdfRule): one type where the lag-1
// estimate rests on thousands of points, several at Riley's minimum of 30 decimated points
// (sd of the estimate about 0.37 for white noise), all of them with fewer than 4 differences.
// Always the identified type among them, whichever method identified it.
TEST(NoiseIdentification, PlausibleTypesWidenAsTheDecimatedPointsFall) {
  std::size_t wide_at_30_points = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<double> phase = stats_test::power_law_phase(0, 4096, 2000 + seed);
    const AlphaRange many = plausible_alphas(Deviation::kOadev, phase, 1);
    EXPECT_EQ(many.low, 0) << "seed " << seed;
    EXPECT_EQ(many.high, 0) << "seed " << seed;
    const std::size_t m = 4095 / 29;  // 30 decimated points
    const AlphaRange few = plausible_alphas(Deviation::kOadev, phase, m);
    EXPECT_LE(few.low, 0) << "seed " << seed;
    EXPECT_GE(few.high, 0) << "seed " << seed;
    if (few.high > few.low) ++wide_at_30_points;
    const AlphaRange none = plausible_alphas(Deviation::kOadev, phase, 4095 / 4);  // 5 points
    EXPECT_EQ(none.low, -2);
    EXPECT_EQ(none.high, 2);
    for (std::size_t factor : {std::size_t{1}, m, std::size_t{4095 / 20}}) {
      const NoiseId id = identify_noise(Deviation::kOadev, phase, factor);
      EXPECT_LE(id.plausible.low, id.alpha) << "seed " << seed << " m " << factor;
      EXPECT_GE(id.plausible.high, id.alpha) << "seed " << seed << " m " << factor;
    }
  }
  EXPECT_GE(wide_at_30_points, 15u);
  EXPECT_THROW(plausible_alphas(Deviation::kOadev, std::vector<double>(10, 0.0), 0),
               std::invalid_argument);
}

TEST(NoiseIdentification, RejectsTooShortRecords) {
  const std::vector<double> phase(10, 0.0);
  EXPECT_THROW(identify_noise(Deviation::kOadev, phase, 0), std::invalid_argument);
  EXPECT_THROW(identify_noise(Deviation::kOadev, phase, 5), std::invalid_argument);
  EXPECT_NO_THROW(identify_noise(Deviation::kOadev, phase, 4));
}

}  // namespace
}  // namespace stochnav
