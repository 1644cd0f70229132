#include "stochnav/stats/confidence.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace stochnav {
namespace {

TEST(ChiSquareInterval, TwoDegreesOfFreedomIsExponential) {
  // chi2 with 2 degrees of freedom: quantile(p) = -2 ln(1 - p).
  const double tail = 0.5 * (1.0 - 0.683);
  const DeviationInterval interval = chi_square_interval(3.0, 2.0, 0.683);
  EXPECT_NEAR(interval.lower, 3.0 * std::sqrt(2.0 / (-2.0 * std::log(tail))), 1e-12);
  EXPECT_NEAR(interval.upper, 3.0 * std::sqrt(2.0 / (-2.0 * std::log(1.0 - tail))), 1e-12);
}

TEST(ChiSquareInterval, ShrinksWithMoreFreedomAndBracketsTheEstimate) {
  double previous_width = INFINITY;
  for (double edf : {1.5, 10.0, 100.0, 1e4, 1e6}) {
    const DeviationInterval interval = chi_square_interval(1.0, edf);
    EXPECT_LT(interval.lower, 1.0);
    EXPECT_GT(interval.upper, 1.0);
    EXPECT_LT(interval.upper - interval.lower, previous_width);
    previous_width = interval.upper - interval.lower;
  }
  // Large edf: about +-1/sqrt(2 edf) around the estimate (one sigma of a deviation).
  const DeviationInterval wide = chi_square_interval(1.0, 1e6);
  EXPECT_NEAR(wide.upper - 1.0, 1.0 / std::sqrt(2e6), 1e-5);
  EXPECT_NEAR(1.0 - wide.lower, 1.0 / std::sqrt(2e6), 1e-5);
}

TEST(ChiSquareInterval, InvalidInputsGiveNaN) {
  EXPECT_TRUE(std::isnan(chi_square_interval(1.0, 0.0).lower));
  EXPECT_TRUE(std::isnan(chi_square_interval(1.0, NAN).upper));
  EXPECT_TRUE(std::isnan(chi_square_interval(1.0, 10.0, 1.0).lower));
  EXPECT_TRUE(std::isnan(chi_square_interval(1.0, 10.0, 0.0).lower));
}

}  // namespace
}  // namespace stochnav
