#include "stochnav/ins/mwd_attitude.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "stochnav/core/angles.hpp"

namespace stochnav {
namespace {

double angle_difference(double a, double b) {
  return std::abs(std::remainder(a - b, 2.0 * std::numbers::pi));
}

TEST(MwdAttitude, AxesFollowTheConventions) {
  // Inclined 30 deg towards azimuth 60 deg, toolface 0: z_b down the hole, x_b the high side.
  const MwdAttitude a{30.0 * kRadPerDeg, 0.0, 60.0 * kRadPerDeg};
  const Eigen::Matrix3d C = dcm_from_mwd(a);
  const double s = std::sin(30.0 * kRadPerDeg);
  const Eigen::Vector3d axis(s * std::sin(60.0 * kRadPerDeg), s * std::cos(60.0 * kRadPerDeg),
                             -std::cos(30.0 * kRadPerDeg));
  EXPECT_LT((C.col(2) - axis).norm(), 1e-15);
  EXPECT_GT(C(2, 0), 0.0);  // high side points up
  EXPECT_NEAR(C.col(0).dot(axis), 0.0, 1e-15);
  EXPECT_LT((C.transpose() * C - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_NEAR(C.determinant(), 1.0, 1e-15);
  // Toolface 90 deg: x_b turned clockwise (looking down the hole) from the high side, so it
  // is horizontal and to the right of the azimuth (East of North for azimuth 0).
  const Eigen::Matrix3d right = dcm_from_mwd({45.0 * kRadPerDeg, 90.0 * kRadPerDeg, 0.0});
  EXPECT_NEAR(right(0, 0), 1.0, 1e-15);
  // Vertical tool, toolface 0, azimuth 0: x_b North, y_b East, z_b Down.
  const Eigen::Matrix3d vertical = dcm_from_mwd({0.0, 0.0, 0.0});
  EXPECT_LT((vertical.col(0) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
  EXPECT_LT((vertical.col(1) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((vertical.col(2) - Eigen::Vector3d(0, 0, -1)).norm(), 1e-15);
}

TEST(MwdAttitude, RoundTripsOverTheWholeRange) {
  for (double inc = 0.5; inc < 180.0; inc += 7.3) {
    for (double tf = 0.0; tf < 360.0; tf += 23.7) {
      for (double az = 0.0; az < 360.0; az += 31.1) {
        const MwdAttitude a{inc * kRadPerDeg, tf * kRadPerDeg, az * kRadPerDeg};
        const MwdAttitude b = mwd_from_dcm(dcm_from_mwd(a));
        ASSERT_NEAR(b.inclination_rad, a.inclination_rad, 1e-12) << inc << " " << tf << " " << az;
        ASSERT_LT(angle_difference(b.toolface_rad, a.toolface_rad), 1e-12);
        ASSERT_LT(angle_difference(b.azimuth_rad, a.azimuth_rad), 1e-12);
        ASSERT_GE(b.toolface_rad, 0.0);
        ASSERT_LT(b.toolface_rad, 2.0 * std::numbers::pi);
        ASSERT_GE(b.azimuth_rad, 0.0);
        const MwdAttitude c = mwd_from_quaternion(quaternion_from_mwd(a));
        ASSERT_NEAR(c.inclination_rad, a.inclination_rad, 1e-12);
        ASSERT_LT(angle_difference(c.toolface_rad, a.toolface_rad), 1e-12);
        ASSERT_LT(angle_difference(c.azimuth_rad, a.azimuth_rad), 1e-12);
      }
    }
  }
}

TEST(MwdAttitude, NearVerticalReportsAzimuthZeroAndTheGyroToolface) {
  for (double inc : {0.0, 1e-9, 5e-8, 180.0 * kRadPerDeg}) {
    for (double tf = 0.0; tf < 360.0; tf += 45.0) {
      for (double az = 0.0; az < 360.0; az += 60.0) {
        const Eigen::Matrix3d C = dcm_from_mwd({inc, tf * kRadPerDeg, az * kRadPerDeg});
        const MwdAttitude b = mwd_from_dcm(C);
        EXPECT_EQ(b.azimuth_rad, 0.0);
        EXPECT_NEAR(b.inclination_rad, inc, 1e-12);
        // Only the sum is defined at vertical: at I = 0 it is the gyro toolface.
        if (inc < 1.0) {
          EXPECT_LT(angle_difference(b.toolface_rad, (tf + az) * kRadPerDeg), 1e-6);
        }
        // The convention reproduces the rotation to within 2 sin(I).
        EXPECT_LT((dcm_from_mwd(b) - C).norm(), 4.0 * std::sin(inc) + 1e-12);
      }
    }
  }
  // Just above the threshold the high-side toolface is kept.
  const MwdAttitude above{2e-6, 1.0, 2.0};
  const MwdAttitude back = mwd_from_dcm(dcm_from_mwd(above));
  EXPECT_NEAR(back.azimuth_rad, 2.0, 1e-6);
  EXPECT_NEAR(back.toolface_rad, 1.0, 1e-6);
}

TEST(MwdAttitude, AngularVelocityMatchesTheDerivativeOfTheRotation) {
  const MwdAttitude a{40.0 * kRadPerDeg, 120.0 * kRadPerDeg, 250.0 * kRadPerDeg};
  const double di = 0.3;
  const double dtf = -1.1;
  const double daz = 0.7;
  const double h = 1e-6;
  const auto at = [&](double t) {
    return dcm_from_mwd(
        {a.inclination_rad + di * t, a.toolface_rad + dtf * t, a.azimuth_rad + daz * t});
  };
  const Eigen::Matrix3d derivative = (at(h) - at(-h)) / (2 * h);
  const Eigen::Matrix3d skew = at(0).transpose() * derivative;
  const Eigen::Vector3d numeric(skew(2, 1), skew(0, 2), skew(1, 0));
  EXPECT_LT((mwd_angular_velocity_b(a, di, dtf, daz) - numeric).norm(), 1e-8);
}

}  // namespace
}  // namespace stochnav
