// Properties of the closed forms: slopes, limits, nulls, numerical accuracy across branches.

#include "stochnav/model/allan_variance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "stochnav/model/closed_forms.hpp"

namespace stochnav {
namespace {

double log_slope(const NoiseTerm& term, double tau) {
  const double ratio = 1.001;
  return 0.5 * std::log(allan_variance(term, tau * ratio) / allan_variance(term, tau)) /
         std::log(ratio);  // slope of the deviation
}

TEST(AllanVariance, PowerLawSlopesOfTheDeviation) {
  EXPECT_NEAR(log_slope(QuantizationTerm{1.0}, 3.0), -1.0, 1e-9);
  EXPECT_NEAR(log_slope(AngleRandomWalkTerm{1.0}, 3.0), -0.5, 1e-9);
  EXPECT_NEAR(log_slope(BiasInstabilityTerm{1.0}, 3.0), 0.0, 1e-9);
  EXPECT_NEAR(log_slope(RateRandomWalkTerm{1.0}, 3.0), 0.5, 1e-9);
  EXPECT_NEAR(log_slope(RateRampTerm{-1.0}, 3.0), 1.0, 1e-9);
}

TEST(AllanVariance, SlopeReadoffPointsOfIeee952) {
  // N at tau = 1 s, K at 3 s, Q at sqrt(3) s, R at sqrt(2) s: the deviation equals the coefficient.
  EXPECT_NEAR(std::sqrt(allan_variance(AngleRandomWalkTerm{0.7}, 1.0)), 0.7, 1e-15);
  EXPECT_NEAR(std::sqrt(allan_variance(RateRandomWalkTerm{0.7}, 3.0)), 0.7, 1e-15);
  EXPECT_NEAR(std::sqrt(allan_variance(QuantizationTerm{0.7}, std::sqrt(3.0))), 0.7, 1e-15);
  EXPECT_NEAR(std::sqrt(allan_variance(RateRampTerm{0.7}, std::sqrt(2.0))), 0.7, 1e-15);
  EXPECT_NEAR(std::sqrt(allan_variance(BiasInstabilityTerm{1.0}, 5.0)), 0.664282, 1e-6);
}

TEST(AllanVariance, GaussMarkovLimits) {
  const double s = 2.0, t = 10.0;
  const GaussMarkovTerm gm{s, t};
  // tau << T: a rate random walk with K^2 = 2 s^2 / T, AVAR = 2 s^2 tau / (3 T), to first
  // order: the next term of the expansion is -(3/4)(tau/T) relative.
  for (double tau : {1e-6, 1e-4, 1e-2}) {
    const double expected = 2 * s * s * tau / (3 * t) * (1.0 - 0.75 * tau / t);
    EXPECT_NEAR(allan_variance(gm, tau), expected, (tau / t) * (tau / t) * expected) << tau;
  }
  // tau >> T: white with N^2 = 2 s^2 T, AVAR = 2 s^2 T / tau.
  const double tau = 1e5;
  EXPECT_NEAR(allan_variance(gm, tau), 2 * s * s * t / tau, 2e-4 * 2 * s * s * t / tau);
  // Peak near tau = 1.89 T at 0.6179 s in deviation.
  double best = 0.0, best_tau = 0.0;
  for (double x = 1.0; x < 3.0; x += 1e-3) {
    const double v = allan_variance(gm, x * t);
    if (v > best) best = v, best_tau = x * t;
  }
  EXPECT_NEAR(best_tau / t, 1.89, 0.01);
  EXPECT_NEAR(std::sqrt(best) / s, 0.6179, 1e-3);
}

TEST(AllanVariance, OuIntegralShapeIsContinuousAcrossItsSeriesBranch) {
  using closed_form::ou_integral_shape;
  const double below = ou_integral_shape(std::nextafter(0.1, 0.0));
  const double above = ou_integral_shape(0.1);
  EXPECT_NEAR(below, above, 1e-13 * above);
  EXPECT_NEAR(ou_integral_shape(1e-5), 1e-15 / 3.0, 1e-20);
  // Integral definition by Simpson at h = 2.
  const double h = 2.0;
  double integral = 0.0;
  constexpr int kSteps = 2000;
  for (int i = 0; i <= kSteps; ++i) {
    const double s = h * i / kSteps;
    const double w = (i == 0 || i == kSteps) ? 1 : (i % 2 ? 4 : 2);
    integral += w * std::pow(1 - std::exp(-s), 2);
  }
  integral *= h / kSteps / 3;
  EXPECT_NEAR(ou_integral_shape(h), integral, 1e-12);
}

TEST(AllanVariance, SinusoidNullsAtMultiplesOfThePeriod) {
  const SinusoidTerm sine{3.0, 0.5, std::nullopt};
  EXPECT_NEAR(allan_variance(sine, 2.0), 0.0, 1e-25);
  EXPECT_NEAR(allan_variance(sine, 4.0), 0.0, 1e-25);
  EXPECT_GT(allan_variance(sine, 1.0), 0.0);
  // Peak value 0.7246 A in deviation at pi f tau = 1.1656.
  const double tau = 1.1656 / (std::numbers::pi * 0.5);
  EXPECT_NEAR(std::sqrt(allan_variance(sine, tau)), 0.7246 * 3.0, 1e-3);
}

TEST(AllanVariance, ModelSumsTermsAndIgnoresNonstationary) {
  const NoiseModel model{Unit::kRadPerSecond,
                         100.0,
                         {AngleRandomWalkTerm{1.0}, RateRandomWalkTerm{2.0},
                          NonstationaryTerm{{{0.0, 10.0, 5.0}}}}};
  EXPECT_DOUBLE_EQ(allan_variance(model, 3.0), 1.0 / 3.0 + 4.0);
  EXPECT_EQ(allan_variance(model.terms[2], 3.0), 0.0);
  EXPECT_TRUE(std::isnan(allan_variance(model, 0.0)));
  EXPECT_TRUE(std::isnan(allan_variance(model.terms[0], -1.0)));
}

}  // namespace
}  // namespace stochnav
