// The robust wavelet variance (the `wv` package's biweight M-estimate): its constants, agreement
// with the classical estimate on Gaussian noise, resistance to outliers, and its intervals.
// There is no published robust table to check against (../shared/data/gmwm holds classical ones).

#include "stochnav/stats/robust_wavelet_variance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "stochnav/stats/wavelet_variance.hpp"

namespace stochnav {
namespace {

std::vector<double> gaussian_noise(std::size_t n, double sigma, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> y(n);
  for (double& v : y) v = normal(engine);
  return y;
}

/// E[f(Z)] over |Z| <= c by Simpson's rule, for checking the closed forms.
template <typename F>
double gaussian_expectation(F f, double c) {
  const int steps = 20000;
  const double h = 2.0 * c / steps;
  double sum = 0.0;
  for (int i = 0; i <= steps; ++i) {
    const double z = -c + i * h;
    const double weight = (i == 0 || i == steps) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    sum += weight * f(z) * std::exp(-0.5 * z * z);
  }
  return sum * h / 3.0 / std::sqrt(2.0 * std::numbers::pi);
}

TEST(RobustWaveletVariance, ConsistencyConstantIsTheGaussianMeanOfPsiSquared) {
  for (double c : {2.0, 4.97336, 8.0}) {
    const double expected = gaussian_expectation(
        [c](double z) {
          const double t = 1.0 - z * z / (c * c);
          return z * z * t * t * t * t;
        },
        c);
    EXPECT_NEAR(biweight_consistency_constant(c), expected, 1e-10) << c;
  }
}

TEST(RobustWaveletVariance, TuningConstantIsTheWvPackagesForEfficiency06) {
  // Brent's minimiser with R's tolerance, as wv runs it: 4.9733606... (see the header for why it
  // differs from the textbook biweight constant).
  EXPECT_NEAR(biweight_tuning_constant(0.6), 4.97336, 1e-4);
  EXPECT_LT(biweight_tuning_constant(0.5), biweight_tuning_constant(0.6));
  EXPECT_LT(biweight_tuning_constant(0.6), biweight_tuning_constant(0.9));
  EXPECT_THROW(biweight_tuning_constant(0.995), std::invalid_argument);
}

TEST(RobustWaveletVariance, AgreesWithTheClassicalEstimateOnGaussianNoise) {
  const auto y = gaussian_noise(1 << 16, 1.5, 21);
  const auto classical = haar_wavelet_variance(y, 1.0);
  const auto robust = robust_haar_wavelet_variance(y, 1.0);
  ASSERT_EQ(robust.size(), classical.size());
  for (std::size_t i = 0; i < robust.size(); ++i) {
    EXPECT_EQ(robust[i].coefficients, classical[i].coefficients);
    EXPECT_EQ(robust[i].scale_s, classical[i].scale_s);
    // Within the robust interval, which is sqrt(1 / 0.6) times wider than the classical one.
    EXPECT_GT(classical[i].variance, robust[i].lower) << i;
    EXPECT_LT(classical[i].variance, robust[i].upper) << i;
    EXPECT_GT(robust[i].lower, 0.0);
    EXPECT_LT(robust[i].lower, robust[i].variance);
  }
  EXPECT_NEAR(robust[0].variance / classical[0].variance, 1.0, 0.03);
}

TEST(RobustWaveletVariance, ResistsOutliersThatInflateTheClassicalEstimate) {
  auto y = gaussian_noise(1 << 16, 1.0, 33);
  const auto clean = robust_haar_wavelet_variance(y, 1.0);
  std::mt19937_64 engine(99);
  std::uniform_int_distribution<std::size_t> where(0, y.size() - 1);
  for (int k = 0; k < 300; ++k) y[where(engine)] += (k % 2 == 0 ? 50.0 : -50.0);  // 0.5 %
  const auto classical = haar_wavelet_variance(y, 1.0);
  const auto robust = robust_haar_wavelet_variance(y, 1.0);
  // Level 1: white noise gives 0.5; the spikes add about 0.005 * 2500 / 2 = 6 to the classical.
  EXPECT_GT(classical[0].variance, 5.0);
  EXPECT_NEAR(robust[0].variance, 0.5, 0.05);
  EXPECT_NEAR(robust[0].variance / clean[0].variance, 1.0, 0.1);
}

}  // namespace
}  // namespace stochnav
