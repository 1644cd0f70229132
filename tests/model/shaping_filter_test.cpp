// Shaping filters of single noise terms: the Allan variance of each state-space model, computed
// exactly from its Phi, Qd, P0 and M, matches the term's closed form; the bank is the
// simulator's; fast states fold into white noise; quantization's angle error does not grow.

#include "stochnav/model/shaping_filter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/model/closed_forms.hpp"
#include "stochnav/sim/flicker_bank.hpp"
#include "stochnav/sim/noise_generator.hpp"

namespace stochnav {
namespace {

constexpr double kStep = 0.01;  // s: sampling step of the exact discrete Allan variance

// Allan variance at tau = m h of the point samples y_k = M x_k (k = 0 .. 2m - 1) of the shaping
// states, started from P0, plus the white PSD's N^2 / tau. Exact for the sampled state-space
// model: the joint covariance of (x_k, z_k), z_k = sum_{j<k} c_j y_j with c = -1/m on the first
// window and +1/m on the second, is propagated step by step; AVAR = Var(z_2m) / 2.
double shaping_allan_variance(const ShapingFilter& filter, double tau_s) {
  const int n = filter.size();
  const int m = static_cast<int>(std::lround(tau_s / kStep));
  Eigen::MatrixXd phi(n, n), q_d(n, n), p0(n, n), map(1, n);
  filter.transition(kStep, phi, q_d);
  filter.initial_covariance(p0);
  filter.sensor_map(map);
  Eigen::MatrixXd joint = Eigen::MatrixXd::Zero(n + 1, n + 1);
  joint.topLeftCorner(n, n) = p0;
  Eigen::MatrixXd transition = Eigen::MatrixXd::Zero(n + 1, n + 1);
  transition.topLeftCorner(n, n) = phi;
  transition(n, n) = 1.0;
  Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(n + 1, n + 1);
  noise.topLeftCorner(n, n) = q_d;
  for (int k = 0; k < 2 * m; ++k) {
    transition.block(n, 0, 1, n) = (k < m ? -1.0 : 1.0) / m * map;
    joint = transition * joint * transition.transpose() + noise;
  }
  return 0.5 * joint(n, n) + filter.white_psd / tau_s;
}

const std::vector<double> kTaus = {0.3, 1.0, 3.0, 10.0, 30.0, 100.0};

TEST(ShapingFilter, GaussMarkovStateHasTheClosedFormAllanVariance) {
  const NoiseModel model{Unit::kRadPerSecond, 100.0, {GaussMarkovTerm{2.0, 5.0}}};
  const ShapingFilter filter = build_shaping_filter(model, {});
  ASSERT_EQ(filter.size(), 1);
  for (double tau : kTaus) {
    const double expected = closed_form::gauss_markov_avar(2.0, 5.0, tau);
    EXPECT_NEAR(shaping_allan_variance(filter, tau) / expected, 1.0, 0.01) << "tau " << tau;
  }
}

TEST(ShapingFilter, FlickerBankHasTheFlatFloorOverTheBand) {
  const NoiseModel model{Unit::kRadPerSecond, 100.0, {BiasInstabilityTerm{1.0}}};
  ShapingOptions options;
  options.tau0_s = 0.01;
  options.flicker_band_max_s = 1000.0;
  options.fold_below_s = 0.0;
  const ShapingFilter exact = build_shaping_filter(model, options);
  options.fold_below_s = 0.1;
  const ShapingFilter folded = build_shaping_filter(model, options);
  EXPECT_LT(folded.size(), exact.size());
  const double floor = closed_form::bias_instability_avar(1.0);
  for (double tau : kTaus) {
    const double ratio_exact = shaping_allan_variance(exact, tau) / floor;
    const double ratio_folded = shaping_allan_variance(folded, tau) / floor;
    std::printf("flicker bank AVAR / floor at tau %6.1f s: all states %.4f, folded %.4f\n", tau,
                ratio_exact, ratio_folded);
    // The 10 ms point samples of this computation over-weight the bank's sub-10 ms components
    // (a sample holds their full variance, not its interval mean's): compare from 3 s on.
    if (tau >= 3.0) {
      EXPECT_NEAR(ratio_exact, 1.0, 0.01) << "tau " << tau;
    }
    // Folding states faster than 0.1 s into white noise overstates the floor just above 0.1 s
    // (their correlation is lost) but leaves it within a few % from 10 x the folding time on.
    if (tau >= 1.0) {
      EXPECT_NEAR(ratio_folded, 1.0, 0.03) << "tau " << tau;
    }
  }
}

TEST(ShapingFilter, SmallerBankTradesStatesForRipple) {
  const NoiseModel model{Unit::kRadPerSecond, 100.0, {BiasInstabilityTerm{1.0}}};
  ShapingOptions options;
  options.tau0_s = 0.1;
  options.flicker_band_max_s = 600.0;
  options.flicker_components_per_decade = 1.0;
  const ShapingFilter filter = build_shaping_filter(model, options);
  EXPECT_LE(filter.size(), 6);
  const double floor = closed_form::bias_instability_avar(1.0);
  for (double tau : {1.0, 3.0, 10.0, 30.0, 100.0}) {
    const double ratio = shaping_allan_variance(filter, tau) / floor;
    std::printf("1-per-decade bank (%d states) AVAR / floor at tau %6.1f s: %.4f\n", filter.size(),
                tau, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.1) << "tau " << tau;
  }
}

TEST(ShapingFilter, DefaultBankIsTheSimulatorsBank) {
  const NoiseModel model{Unit::kRadPerSecond, 100.0, {BiasInstabilityTerm{3.0}}};
  ShapingOptions options;
  options.tau0_s = 0.01;
  options.flicker_band_max_s = 1800.0;
  options.fold_below_s = 0.0;
  const ShapingFilter filter = build_shaping_filter(model, options);
  const FlickerBank bank = design_flicker_bank(3.0, 0.01, 1800.0);
  ASSERT_EQ(filter.first_order.size(), bank.tau_c_s.size());
  for (std::size_t k = 0; k < bank.tau_c_s.size(); ++k) {
    EXPECT_EQ(filter.first_order[k].tau_c, bank.tau_c_s[k]);
    EXPECT_EQ(filter.first_order[k].sigma, bank.sigma[k]);
  }
  EXPECT_EQ(filter.white_psd, 0.0);
}

TEST(ShapingFilter, FastStatesFoldIntoTheirLowFrequencyWhiteNoise) {
  const NoiseModel model{
      Unit::kRadPerSecond, 100.0, {GaussMarkovTerm{2.0, 0.02}, GaussMarkovTerm{1.0, 0.5}}};
  ShapingOptions options;
  options.fold_below_s = 0.1;
  const ShapingFilter filter = build_shaping_filter(model, options);
  ASSERT_EQ(filter.size(), 1);
  EXPECT_EQ(filter.first_order[0].tau_c, 0.5);
  EXPECT_DOUBLE_EQ(filter.white_psd, 2.0 * 4.0 * 0.02);
  // Long-tau Allan variance of the folded state: the white form is its asymptote.
  for (double tau : {10.0, 30.0}) {
    const double expected = closed_form::gauss_markov_avar(2.0, 0.02, tau) +
                            closed_form::gauss_markov_avar(1.0, 0.5, tau);
    EXPECT_NEAR(shaping_allan_variance(filter, tau) / expected, 1.0, 0.03) << "tau " << tau;
  }
}

TEST(ShapingFilter, RampIsARandomConstantSlopeWithTheRampAllanVariance) {
  const NoiseModel model{Unit::kRadPerSecond, 100.0, {RateRampTerm{-0.2}}};
  const ShapingFilter filter = build_shaping_filter(model, {});
  ASSERT_EQ(filter.size(), 2);
  for (double tau : kTaus) {
    const double expected = closed_form::rate_ramp_avar(-0.2, tau);
    EXPECT_NEAR(shaping_allan_variance(filter, tau) / expected, 1.0, 1e-9) << "tau " << tau;
  }
  Eigen::MatrixXd a(2, 2), b(2, 2), c(2, 2), qa(2, 2), qb(2, 2), qc(2, 2);
  filter.transition(0.3, a, qa);
  filter.transition(1.7, b, qb);
  filter.transition(2.0, c, qc);
  EXPECT_LE((b * a - c).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_EQ(qc.cwiseAbs().maxCoeff(), 0.0);
}

TEST(ShapingFilter, OscillatorHasTheSinusoidAllanVariance) {
  const NoiseModel model{Unit::kRadPerSecond, 100.0, {SinusoidTerm{3.0, 0.05, std::nullopt}}};
  const ShapingFilter filter = build_shaping_filter(model, {});
  ASSERT_EQ(filter.size(), 2);
  for (double tau : {0.3, 1.0, 3.0, 10.0, 15.0}) {
    const double expected = closed_form::sinusoid_avar(3.0, 0.05, tau);
    EXPECT_NEAR(shaping_allan_variance(filter, tau) / expected, 1.0, 0.01) << "tau " << tau;
  }
}

TEST(ShapingFilter, RandomWalksGoToTheirPsdsAndQuantizationIsKeptAside) {
  const NoiseModel model{
      Unit::kRadPerSecond,
      100.0,
      {QuantizationTerm{1e-6}, AngleRandomWalkTerm{3e-4}, RateRandomWalkTerm{2e-5}}};
  const ShapingFilter filter = build_shaping_filter(model, {});
  EXPECT_EQ(filter.size(), 0);
  EXPECT_DOUBLE_EQ(filter.white_psd, 9e-8);
  EXPECT_DOUBLE_EQ(filter.bias_walk_psd, 4e-10);
  EXPECT_EQ(filter.quantization, 1e-6);
}

// What the omission of quantization rests on: its angle error (the integral of the rate noise)
// is bounded, variance 2 Q^2 over any horizon, unlike a rate error held over an interval.
TEST(ShapingFilter, QuantizationAngleErrorDoesNotAccumulate) {
  const double q = 1e-5;
  const NoiseModel model{Unit::kRadPerSecond, 100.0, {QuantizationTerm{q}}};
  const std::vector<double> record = simulate_noise(model, 2000.0, 100.0, 7);
  for (std::size_t horizon : {10u, 1000u, 10000u}) {
    double sum_squares = 0.0;
    std::size_t count = 0;
    for (std::size_t start = 0; start + horizon < record.size(); start += horizon) {
      double angle = 0.0;
      for (std::size_t k = start; k < start + horizon; ++k) angle += record[k] * 0.01;
      sum_squares += angle * angle;
      ++count;
    }
    // 20 independent windows at the longest horizon: chi-square(20)/20 lies in [0.4, 1.9].
    EXPECT_NEAR(sum_squares / static_cast<double>(count) / (2.0 * q * q), 1.0, 0.6)
        << "horizon " << horizon;
  }
}

TEST(ShapingFilter, RejectsNonstationaryTermsAndBadOptions) {
  const NoiseModel model{
      Unit::kRadPerSecond, 100.0, {AngleRandomWalkTerm{1.0}, NonstationaryTerm{{{0.0, 1.0, 2.0}}}}};
  EXPECT_THROW(build_shaping_filter(model, {}), ConfigError);
  ShapingOptions options;
  options.flicker_components_per_decade = 0.0;
  EXPECT_THROW(build_shaping_filter(NoiseModel{Unit::kRadPerSecond, 100.0, {}}, options),
               ConfigError);
}

}  // namespace
}  // namespace stochnav
