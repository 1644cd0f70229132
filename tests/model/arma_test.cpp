// ARMA estimation and state-space form (model/arma.hpp) against closed forms and simulations
// with known truth over many seeds.

#include "stochnav/model/arma.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "stochnav/model/noise_model.hpp"
#include "stochnav/sim/noise_generator.hpp"

namespace stochnav {
namespace {

// y_k = sum phi_i y_{k-i} + e_k + sum theta_j e_{k-j}, started after a burn-in of 1000 samples.
std::vector<double> simulate_arma(const std::vector<double>& phi, const std::vector<double>& theta,
                                  double sigma, int n, std::uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  const int burn_in = 1000, total = n + burn_in;
  std::vector<double> y(total, 0.0), e(total, 0.0);
  for (int k = 0; k < total; ++k) {
    e[k] = normal(engine);
    double value = e[k];
    for (std::size_t i = 0; i < phi.size() && k > static_cast<int>(i); ++i) {
      value += phi[i] * y[k - 1 - i];
    }
    for (std::size_t j = 0; j < theta.size() && k > static_cast<int>(j); ++j) {
      value += theta[j] * e[k - 1 - j];
    }
    y[k] = value;
  }
  return {y.begin() + burn_in, y.end()};
}

// AR(2) with phi = (0.75, -0.5): asymptotic variance of either estimate (1 - phi_2^2) / n
// (Brockwell & Davis, example 5.1.1 / 5.2), independent of the code's ar_standard_errors.
class Ar2Recovery : public ::testing::TestWithParam<ArMethod> {};

TEST_P(Ar2Recovery, MeanErrorIsSmallAndStandardErrorsCoverAsPromised) {
  const std::vector<double> phi{0.75, -0.5};
  const int n = 2000, seeds = 20;
  const double se = std::sqrt((1.0 - phi[1] * phi[1]) / n);
  double sum_error[2] = {0.0, 0.0};
  int within_one = 0, within_two = 0;
  for (int seed = 0; seed < seeds; ++seed) {
    const auto y = simulate_arma(phi, {}, 2.0, n, 100 + seed);
    const ArmaModel fit = fit_ar_all_orders(y, 2, GetParam())[2];
    ASSERT_EQ(fit.ar.size(), 2u);
    const auto code_se = ar_standard_errors(fit, n);
    for (int i = 0; i < 2; ++i) {
      const double error = fit.ar[i] - phi[i];
      sum_error[i] += error;
      within_one += std::abs(error) < se;
      within_two += std::abs(error) < 2.0 * se;
      EXPECT_NEAR(code_se[i], se, 0.1 * se);
    }
    EXPECT_NEAR(fit.sigma, 2.0, 0.1);
  }
  for (int i = 0; i < 2; ++i)
    EXPECT_LT(std::abs(sum_error[i] / seeds), 3.0 * se / std::sqrt(seeds));
  // 40 estimates: 68 % and 95 % nominal, binomial sd 7 % and 3.4 %.
  EXPECT_GE(within_one, 20);
  EXPECT_LE(within_one, 34);
  EXPECT_GE(within_two, 34);
}

TEST_P(Ar2Recovery, BicPicksTheTrueOrderInMostSeeds) {
  int right = 0;
  for (int seed = 0; seed < 20; ++seed) {
    const auto y = simulate_arma({0.75, -0.5}, {}, 1.0, 2000, 200 + seed);
    right += select_ar(y, 8, GetParam(), InformationCriterion::kBic).model.ar.size() == 2;
  }
  EXPECT_GE(right, 17);
}

INSTANTIATE_TEST_SUITE_P(Methods, Ar2Recovery,
                         ::testing::Values(ArMethod::kBurg, ArMethod::kYuleWalker));

TEST(ArmaCss, RecoversPhiAndThetaOfAnArma11) {
  const double phi = 0.7, theta = 0.4;
  const int n = 3000, seeds = 5;
  // Asymptotic standard errors of ARMA(1, 1) (Brockwell & Davis, example 5.2.5):
  // var(phi) = (1 + phi theta)^2 (1 - phi^2) / ((phi + theta)^2 n), same with theta's
  // (1 - theta^2).
  const double scale = (1.0 + phi * theta) / ((phi + theta) * std::sqrt(n));
  const double se_phi = scale * std::sqrt(1.0 - phi * phi);
  const double se_theta = scale * std::sqrt(1.0 - theta * theta);
  for (int seed = 0; seed < seeds; ++seed) {
    const auto y = simulate_arma({phi}, {theta}, 0.5, n, 300 + seed);
    const ArmaFit fit = fit_arma_css(y, 1, 1, 1, InformationCriterion::kBic);
    EXPECT_NEAR(fit.model.ar[0], phi, 4.0 * se_phi) << seed;
    EXPECT_NEAR(fit.model.ma[0], theta, 4.0 * se_theta) << seed;
    EXPECT_NEAR(fit.model.sigma, 0.5, 0.03) << seed;
    const ArmaFit chosen = select_arma(y, 3, 2, InformationCriterion::kBic);
    EXPECT_EQ(chosen.model.ar.size(), 1u) << seed;
    EXPECT_EQ(chosen.model.ma.size(), 1u) << seed;
  }
}

TEST(ArmaCss, ResultIsStationaryAndInvertibleEvenForAnOverfittedModel) {
  const auto y = simulate_arma({0.5}, {}, 1.0, 1000, 7);
  const ArmaFit fit = fit_arma_css(y, 3, 2, 3, InformationCriterion::kAic);
  EXPECT_TRUE(is_stationary(fit.model.ar));
  EXPECT_TRUE(is_invertible(fit.model.ma));
}

// A first-order Gauss-Markov process sampled every T is AR(1) with phi = exp(-T / tau) and
// innovation variance sigma^2 (1 - phi^2). The simulator gives interval means; at 1 kHz they are
// point samples to 1e-4.
TEST(GaussMarkov, SampledAtTheIntervalIsAnAr1WithTheClosedFormCoefficient) {
  const double sigma = 3.0, tau = 2.0, interval = 0.1, rate = 1000.0;
  const double phi = std::exp(-interval / tau);
  const int n = 10000;
  const double se = std::sqrt((1.0 - phi * phi) / n);
  int order_one = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const NoiseModel model{Unit::kRadPerSecond, rate, {GaussMarkovTerm{sigma, tau}}};
    const auto record = simulate_noise(model, n * interval, rate, seed);
    std::vector<double> samples;
    for (std::size_t i = 0; i < record.size(); i += 100) samples.push_back(record[i]);
    const auto y = demeaned(samples);
    const ArmaModel ar1 = fit_ar_all_orders(y, 1, ArMethod::kBurg)[1];
    EXPECT_NEAR(ar1.ar[0], phi, 4.0 * se) << seed;
    EXPECT_NEAR(ar1.sigma, sigma * std::sqrt(1.0 - phi * phi), 0.05 * sigma) << seed;
    order_one += select_ar(y, 8, ArMethod::kBurg, InformationCriterion::kBic).model.ar.size() == 1;
  }
  EXPECT_GE(order_one, 4);
}

// Block means over T of a Gauss-Markov process: lag h >= 1 autocovariances decay as
// exp(-T / tau)^h, so the ARMA fit's AR root is exp(-T / tau), and its autocovariances match
// gamma(0) = 2 s^2 (tau/T)^2 (T/tau - 1 + a), gamma(1) = s^2 (tau/T)^2 (1 - a)^2, a = exp(-T/tau).
TEST(GaussMarkov, BlockMeansAreAnArma11WithTheClosedFormAutocovariance) {
  const double sigma = 1.0, tau = 0.5, interval = 0.1, rate = 100.0;
  const double a = std::exp(-interval / tau), ratio = tau / interval;
  const double gamma0 = 2.0 * sigma * sigma * ratio * ratio * (1.0 / ratio - 1.0 + a);
  const double gamma1 = sigma * sigma * ratio * ratio * (1.0 - a) * (1.0 - a);
  const NoiseModel model{Unit::kRadPerSecond, rate, {GaussMarkovTerm{sigma, tau}}};
  const auto y = demeaned(block_means(simulate_noise(model, 2000.0, rate, 5), 10));
  const ArmaFit fit = fit_arma_css(y, 1, 1, 1, InformationCriterion::kBic);
  EXPECT_NEAR(fit.model.ar[0], a, 0.02);
  const auto gamma = autocovariance(fit.model, 2);
  EXPECT_NEAR(gamma[0], gamma0, 0.05 * gamma0);
  EXPECT_NEAR(gamma[1], gamma1, 0.05 * gamma0);
  EXPECT_NEAR(gamma[2], gamma1 * a, 0.05 * gamma0);
}

TEST(StateSpace, StationaryCovarianceMatchesClosedForms) {
  const ArmaModel ar1{{0.9}, {}, 2.0};
  EXPECT_NEAR(stationary_covariance(state_space(ar1))(0, 0), 4.0 / (1.0 - 0.81), 1e-12);
  // ARMA(1, 1): gamma(0) = s^2 (1 + 2 phi theta + theta^2) / (1 - phi^2),
  // gamma(1) = s^2 (1 + phi theta)(phi + theta) / (1 - phi^2).
  const double phi = -0.6, theta = 0.3, s = 0.7;
  const auto gamma = autocovariance(ArmaModel{{phi}, {theta}, s}, 1);
  EXPECT_NEAR(gamma[0], s * s * (1 + 2 * phi * theta + theta * theta) / (1 - phi * phi), 1e-12);
  EXPECT_NEAR(gamma[1], s * s * (1 + phi * theta) * (phi + theta) / (1 - phi * phi), 1e-12);
  // AR(2): gamma(1) / gamma(0) = phi_1 / (1 - phi_2).
  const auto ar2 = autocovariance(ArmaModel{{0.75, -0.5}, {}, 1.0}, 1);
  EXPECT_NEAR(ar2[1] / ar2[0], 0.75 / 1.5, 1e-12);
}

TEST(StateSpace, KStepsEqualKSingleSteps) {
  const ArmaStateSpace space = state_space(ArmaModel{{0.5, 0.2, -0.1}, {0.4, 0.1}, 1.5});
  const int r = space.size();
  ASSERT_EQ(r, 3);
  Eigen::MatrixXd phi1(r, r), q1(r, r), phi_k(r, r), q_k(r, r);
  k_step_transition(space, 1, phi1, q1);
  EXPECT_LE((phi1 - space.a).cwiseAbs().maxCoeff(), 0.0);
  Eigen::MatrixXd phi = Eigen::MatrixXd::Identity(r, r), q = Eigen::MatrixXd::Zero(r, r);
  for (int k = 1; k <= 17; ++k) {
    phi = phi1 * phi;
    q = phi1 * q * phi1.transpose() + q1;
  }
  k_step_transition(space, 17, phi_k, q_k);
  EXPECT_LE((phi_k - phi).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LE((q_k - q).cwiseAbs().maxCoeff(), 1e-12 * q.cwiseAbs().maxCoeff());
  // Stationary identity: Q_k = P - A^k P A^kT.
  const Eigen::MatrixXd p = stationary_covariance(space);
  EXPECT_LE((q_k - (p - phi_k * p * phi_k.transpose())).cwiseAbs().maxCoeff(),
            1e-12 * p.cwiseAbs().maxCoeff());
  k_step_transition(space, 0, phi_k, q_k);
  EXPECT_TRUE(phi_k.isIdentity(0.0));
  EXPECT_EQ(q_k.cwiseAbs().maxCoeff(), 0.0);
}

TEST(Polynomials, StationarityAndInvertibilityFollowTheRoots) {
  EXPECT_TRUE(is_stationary(std::vector<double>{1.2, -0.5}));  // inside the AR(2) triangle
  EXPECT_FALSE(is_stationary(std::vector<double>{0.5, 0.6}));  // phi_1 + phi_2 > 1
  EXPECT_FALSE(is_stationary(std::vector<double>{1.0}));       // unit root
  EXPECT_TRUE(is_stationary(std::vector<double>{}));
  EXPECT_TRUE(is_invertible(std::vector<double>{0.5}));
  EXPECT_FALSE(is_invertible(std::vector<double>{-1.5}));
  EXPECT_THROW(stationary_covariance(state_space(ArmaModel{{1.1}, {}, 1.0})),
               std::invalid_argument);
}

TEST(InformationCriterion, IsLikelihoodTermPlusPenalty) {
  EXPECT_DOUBLE_EQ(information_criterion(InformationCriterion::kAic, 2.0, 100, 3),
                   100 * std::log(2.0) + 6.0);
  EXPECT_DOUBLE_EQ(information_criterion(InformationCriterion::kBic, 2.0, 100, 3),
                   100 * std::log(2.0) + 3.0 * std::log(100.0));
}

TEST(BlockMeans, AverageWholeBlocksAndDropThePartialOne) {
  const std::vector<double> x{1, 2, 3, 4, 5, 6, 7};
  EXPECT_EQ(block_means(x, 3), (std::vector<double>{2, 5}));
  EXPECT_EQ(demeaned(std::vector<double>{1, 3}), (std::vector<double>{-1, 1}));
}

}  // namespace
}  // namespace stochnav
