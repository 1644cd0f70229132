// The second-order attitude-error rate's covariance (filter/second_order_attitude.hpp) against a
// Monte Carlo of m = -1/2 phi x (phi x omega) and against the closed form for a heading error
// alone.
#include "stochnav/filter/second_order_attitude.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

namespace stochnav {
namespace {

constexpr double kEarthRate = 7.292115e-5;  // rad/s

Eigen::Vector3d earth_rate_enu(double latitude_rad) {
  return {0.0, kEarthRate * std::cos(latitude_rad), kEarthRate * std::sin(latitude_rad)};
}

TEST(SecondOrderAttitude, HeadingAloneIsHalfSigmaSquaredTimesHorizontalEarthRate) {
  // psi ~ N(0, s^2) about up: m = -1/2 (psi^2) (-omega_h) = 1/2 psi^2 omega_h, whose variance
  // along north is (1/2 Omega_N)^2 Var(psi^2) = (1/2 Omega_N)^2 2 s^4.
  const double s = 0.1;
  const Eigen::Vector3d omega = earth_rate_enu(60.0 * M_PI / 180.0);
  Eigen::Matrix3d p = Eigen::Matrix3d::Zero();
  p(2, 2) = s * s;
  const Eigen::Matrix3d c = second_order_attitude_rate_covariance(p, omega);
  const double expected = 0.25 * omega.y() * omega.y() * 2.0 * std::pow(s, 4);
  EXPECT_NEAR(c(1, 1), expected, 1e-12 * expected);
  EXPECT_NEAR(c(0, 0), 0.0, 1e-30);
  EXPECT_NEAR(c(2, 2), 0.0, 1e-30);
}

TEST(SecondOrderAttitude, MatchesMonteCarloForCorrelatedErrors) {
  Eigen::Matrix3d p;
  p << 4e-6, 1e-6, 3e-5,  //
      1e-6, 9e-6, -2e-5,  //
      3e-5, -2e-5, 1e-2;  // tilts of milliradians, heading 5.7 deg, correlated
  const Eigen::Vector3d omega = earth_rate_enu(70.0 * M_PI / 180.0);
  const Eigen::Matrix3d l = p.llt().matrixL();
  std::mt19937_64 random(42);
  std::normal_distribution<double> normal;
  const int samples = 400'000;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (int k = 0; k < samples; ++k) {
    const Eigen::Vector3d phi = l * Eigen::Vector3d(normal(random), normal(random), normal(random));
    const Eigen::Vector3d m = -0.5 * phi.cross(phi.cross(omega));
    mean += m;
    second += m * m.transpose();
  }
  mean /= samples;
  const Eigen::Matrix3d sampled = second / samples - mean * mean.transpose();
  const Eigen::Matrix3d c = second_order_attitude_rate_covariance(p, omega);
  // The mean's standard error is sqrt(c_ii / samples): 0.2 % of sigma; 1 % catches any slip.
  const Eigen::Vector3d expected_mean = second_order_attitude_rate_mean(p, omega);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(mean(i), expected_mean(i), 0.01 * std::sqrt(c(i, i)) + 1e-3 * std::abs(mean(i)))
        << "mean " << i;
  }
  EXPECT_GT(expected_mean(1), 0.0) << "a heading error of either sign tilts the frame north";
  // The sample covariance of these heavy-tailed products has a relative standard error of
  // about sqrt(kurtosis / samples), ~1 %: 5 % is far outside it yet catches a factor of 2.
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double scale = std::sqrt(c(i, i) * c(j, j));
      EXPECT_NEAR(sampled(i, j), c(i, j), 0.05 * scale) << "(" << i << ", " << j << ")";
    }
  }
}

TEST(SecondOrderAttitude, NoiseScalesWithIntervalAndCorrelationTimeAndVanishesAtZero) {
  Eigen::Matrix3d p = Eigen::Matrix3d::Identity() * 1e-6;
  p(2, 2) = 1e-2;
  const Eigen::Vector3d omega = earth_rate_enu(0.8);
  const Eigen::Matrix3d rate = second_order_attitude_rate_covariance(p, omega);
  EXPECT_TRUE(second_order_attitude_noise(p, omega, 0.1, 900.0).isApprox(rate * 180.0));
  EXPECT_TRUE(second_order_attitude_noise(p, omega, 0.1, 0.0).isZero());
  // As P^2: a heading known 10 times better adds 10^4 times less.
  Eigen::Matrix3d p_small = p / 100.0;
  EXPECT_NEAR(second_order_attitude_rate_covariance(p_small, omega).trace(), rate.trace() * 1e-4,
              1e-9 * rate.trace());
}

}  // namespace
}  // namespace stochnav
