// The fast inputs' integrals over a covariance interval (filter/error_dynamics.hpp): the
// position rows' correction to the second-order transition is nil for constant inputs and is
// the closed-form double integral for a vibration whose period divides the interval.

#include "stochnav/filter/error_dynamics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "stochnav/ins/cross_product_matrix.hpp"

namespace stochnav {
namespace {

constexpr double kDt = 0.01;  // s, a 100-Hz IMU
constexpr int kEpochs = 100;  // a 1-s interval

TEST(PositionShapeCorrection, IsNilForInputsConstantOverTheInterval) {
  const Eigen::Matrix3d c_nb =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d f_n(0.4, -0.2, 9.8);
  FastInputIntegrals fast;
  for (int k = 0; k < kEpochs; ++k) {
    fast.add_velocity_inputs(kDt, c_nb * kDt, f_n * kDt);
    fast.add_accel_scale_input(kDt, 2.0 * c_nb * kDt);
  }
  EXPECT_NEAR(fast.interval_s, 1.0, 1e-12);
  EXPECT_TRUE(fast.f_n_dt.isApprox(f_n, 1e-12));
  const PositionShapeCorrection correction = position_shape_correction(fast);
  EXPECT_LT(correction.attitude.norm(), 1e-12);
  EXPECT_LT(correction.accel_bias.norm(), 1e-12);
  EXPECT_LT(correction.accel_scale.norm(), 1e-12);
}

// f_n = a sin(w t) e over whole periods: the single integral is nil, the exact double integral
// int_0^T int_0^t a sin(w s) ds dt = a T / w; (F T)^2 / 2 alone would give 0.
TEST(PositionShapeCorrection, GivesAPhaseLockedVibrationItsDoubleIntegral) {
  const double a = 2.0 * 9.8;  // m/s^2
  const double w = 2.0 * std::numbers::pi * 10.0;
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  FastInputIntegrals fast;
  for (int k = 0; k < kEpochs; ++k) {
    const double t0 = k * kDt;
    const double increment = a / w * (std::cos(w * t0) - std::cos(w * (t0 + kDt)));  // m/s
    fast.add_velocity_inputs(kDt, Eigen::Matrix3d::Identity() * kDt, increment * axis);
  }
  EXPECT_LT(fast.f_n_dt.norm(), 1e-12);
  const Eigen::Matrix3d expected = skew(Eigen::Vector3d(a * 1.0 / w * axis));
  const PositionShapeCorrection correction = position_shape_correction(fast);
  // The single integral is taken linear within an epoch: trapezoid errors, which cancel over
  // whole periods.
  EXPECT_TRUE(correction.attitude.isApprox(expected, 1e-3)) << correction.attitude << "\nexpected\n"
                                                            << expected;
  EXPECT_LT(correction.accel_bias.norm(), 1e-12);
}

}  // namespace
}  // namespace stochnav
