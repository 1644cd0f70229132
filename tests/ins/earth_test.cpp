#include "stochnav/ins/earth.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "stochnav/core/angles.hpp"

namespace stochnav {
namespace {

TEST(Earth, NormalGravityMatchesSomiglianaAtEquatorAndPoles) {
  EXPECT_NEAR(normal_gravity(0.0, 0.0), 9.7803253359, 1e-10);
  EXPECT_NEAR(normal_gravity(90.0 * kRadPerDeg, 0.0), 9.8321849378, 1e-9);
  EXPECT_NEAR(normal_gravity(-90.0 * kRadPerDeg, 0.0), 9.8321849378, 1e-9);
  // Free-air gradient about -3.086e-6 /s^2 per metre at mid latitudes.
  const double gradient =
      (normal_gravity(45.0 * kRadPerDeg, 100.0) - normal_gravity(45.0 * kRadPerDeg, 0.0)) / 100.0;
  EXPECT_NEAR(gradient, -3.086e-6, 0.01e-6);
  for (double h : {-3000.0, 0.0, 5000.0}) {
    const double numeric = (normal_gravity(0.7, h + 1.0) - normal_gravity(0.7, h - 1.0)) / 2.0;
    EXPECT_NEAR(normal_gravity_height_gradient(0.7, h), numeric, 1e-12);
  }
  const Eigen::Vector3d g = gravity_n(30.0 * kRadPerDeg, 10.0);
  EXPECT_EQ(g.x(), 0.0);
  EXPECT_EQ(g.y(), 0.0);
  EXPECT_DOUBLE_EQ(g.z(), -normal_gravity(30.0 * kRadPerDeg, 10.0));
}

TEST(Earth, RadiiAtEquatorAndPoleAndTheirDerivatives) {
  const double a = wgs84::kSemiMajorAxis_m;
  const double e2 = wgs84::kEccentricitySquared;
  const EarthRadii equator = earth_radii(0.0);
  EXPECT_NEAR(equator.transverse_m, a, 1e-6);
  EXPECT_NEAR(equator.meridian_m, a * (1.0 - e2), 1e-6);
  const EarthRadii pole = earth_radii(90.0 * kRadPerDeg);
  EXPECT_NEAR(pole.meridian_m, pole.transverse_m, 1e-6);
  EXPECT_NEAR(pole.transverse_m, a / std::sqrt(1.0 - e2), 1e-6);
  for (double lat : {-70.0, -10.0, 0.0, 25.0, 39.9778, 80.0}) {
    const double h = 1e-6;
    const EarthRadii plus = earth_radii(lat * kRadPerDeg + h);
    const EarthRadii minus = earth_radii(lat * kRadPerDeg - h);
    const EarthRadii derivative = earth_radii_derivative(lat * kRadPerDeg);
    EXPECT_NEAR(derivative.meridian_m, (plus.meridian_m - minus.meridian_m) / (2 * h), 1e-2);
    EXPECT_NEAR(derivative.transverse_m, (plus.transverse_m - minus.transverse_m) / (2 * h), 1e-2);
  }
}

TEST(Earth, EarthRateAndTransportRate) {
  const double lat = 39.9778 * kRadPerDeg;
  const Eigen::Vector3d omega = earth_rate_n(lat);
  EXPECT_NEAR(omega.norm(), 7.292115e-5, 1e-18);
  EXPECT_EQ(omega.x(), 0.0);
  EXPECT_NEAR(std::atan2(omega.z(), omega.y()), lat, 1e-15);
  // Moving East at the speed of the Earth's surface rotation doubles the rate about the
  // polar axis; moving North rotates n about -East.
  const EarthRadii r = earth_radii(lat);
  const Eigen::Vector3d east = transport_rate_n(lat, 0.0, Eigen::Vector3d(10.0, 0.0, 0.0));
  EXPECT_NEAR(east.y(), 10.0 / r.transverse_m, 1e-18);
  EXPECT_NEAR(east.z(), 10.0 * std::tan(lat) / r.transverse_m, 1e-18);
  const Eigen::Vector3d north = transport_rate_n(lat, 100.0, Eigen::Vector3d(0.0, 5.0, 0.0));
  EXPECT_NEAR(north.x(), -5.0 / (r.meridian_m + 100.0), 1e-18);
  EXPECT_EQ(north.y(), 0.0);
}

}  // namespace
}  // namespace stochnav
