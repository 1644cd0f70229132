// The survey QC of a station from its connection's static data alone
// (experiment/station_qc.hpp): a static span synthesised from a known attitude and sensor
// errors gives the attitude back within the stated sigmas, across inclinations and azimuths;
// the sigmas follow the documented budget (a gyrocompass limited by bias / (W cos lat)); a
// continuous solution off by 5 combined sigma is flagged and one inside is not.

#include "stochnav/experiment/station_qc.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"

namespace stochnav {
namespace {

constexpr double kQcRadPerDegree = std::numbers::pi / 180.0;
constexpr double kQcLatitude = 46.58 * kQcRadPerDegree;

StationQcBudget qc_budget() {
  StationQcBudget b;
  b.latitude_rad = kQcLatitude;
  b.height_m = -300.0;
  b.gyro_bias_sigma_radps.setConstant(0.5 * kQcRadPerDegree / 3600.0);
  b.accel_bias_sigma_mps2.setConstant(1e-3);
  b.accel_scale_factor_sigma.setConstant(1e-4);
  b.gyro_white_psd.setConstant(std::pow(0.005 * kQcRadPerDegree / 60.0, 2));  // 0.005 deg/sqrt(h)
  b.accel_white_psd.setConstant(std::pow(0.06 / 60.0, 2));                    // 0.06 m/s/sqrt(h)
  return b;
}

// The span a static tool at the given angles records over `duration_s`, with sensor biases.
StaticSpan synthetic_static_span(double inclination_deg, double azimuth_deg, double toolface_deg,
                                 const Eigen::Vector3d& gyro_bias,
                                 const Eigen::Vector3d& accel_bias, double duration_s) {
  MwdAttitude attitude;
  attitude.inclination_rad = inclination_deg * kQcRadPerDegree;
  attitude.azimuth_rad = azimuth_deg * kQcRadPerDegree;
  attitude.toolface_rad = toolface_deg * kQcRadPerDegree;
  const Eigen::Matrix3d c_bn = quaternion_from_mwd(attitude).toRotationMatrix().transpose();
  const Eigen::Vector3d omega_b = c_bn * earth_rate_n(kQcLatitude) + gyro_bias;
  const Eigen::Vector3d f_b = -(c_bn * gravity_n(kQcLatitude, -300.0)) + accel_bias;
  StaticSpan span;
  span.add(omega_b * duration_s, f_b * duration_s, duration_s);
  return span;
}

TEST(StationQc, StaticSolutionIsTheAttitudeWithinItsSigmas) {
  std::mt19937_64 random(5);
  std::normal_distribution<double> normal;
  const StationQcBudget b = qc_budget();
  int inclination_inside = 0, azimuth_inside = 0, cases = 0;
  for (double inclination : {10.0, 45.0, 80.0, 90.0}) {
    for (double azimuth : {0.0, 60.0, 90.0, 200.0, 300.0}) {
      const Eigen::Vector3d gyro_bias(b.gyro_bias_sigma_radps.x() * normal(random),
                                      b.gyro_bias_sigma_radps.y() * normal(random),
                                      b.gyro_bias_sigma_radps.z() * normal(random));
      const Eigen::Vector3d accel_bias(1e-3 * normal(random), 1e-3 * normal(random),
                                       1e-3 * normal(random));
      const StaticSpan span =
          synthetic_static_span(inclination, azimuth, 30.0, gyro_bias, accel_bias, 300.0);
      const StationQc qc = station_qc(span, b, 0.0, inclination, 0.001, azimuth, 0.01);
      ASSERT_TRUE(qc.checked);
      ++cases;
      inclination_inside += std::abs(qc.static_inclination_deg - inclination) <=
                            3.0 * qc.static_inclination_sigma_deg;
      azimuth_inside += std::abs(std::remainder(qc.gyrocompass_azimuth_deg - azimuth, 360.0)) <=
                        3.0 * qc.gyrocompass_azimuth_sigma_deg;
      // The gravity total of a static tool is inside its tolerance, and so is the Earth rate.
      EXPECT_LT(std::abs(qc.gravity_total_m_s2 - qc.gravity_model_m_s2),
                3.0 * qc.gravity_sigma_m_s2 + 1e-9);
      EXPECT_LT(std::abs(qc.earth_rate_total_deg_h - 15.041), 3.0 * qc.earth_rate_sigma_deg_h);
    }
  }
  EXPECT_GE(inclination_inside, cases - 1);
  EXPECT_GE(azimuth_inside, cases - 1);
}

TEST(StationQc, GyrocompassSigmaIsTheBiasOverTheHorizontalEarthRate) {
  // A horizontal east-west tool: the along-hole (z) bias is east, across the horizontal Earth
  // rate W cos lat; the azimuth sigma is at least sigma_b / (W cos lat).
  const StationQcBudget b = qc_budget();
  const StaticSpan span = synthetic_static_span(90.0, 90.0, 0.0, Eigen::Vector3d::Zero(),
                                                Eigen::Vector3d::Zero(), 300.0);
  const StationQc qc = station_qc(span, b, 0.0, 90.0, 0.001, 90.0, 0.01);
  const double floor_deg = b.gyro_bias_sigma_radps.z() /
                           (wgs84::kEarthRate_radps * std::cos(kQcLatitude)) / kQcRadPerDegree;
  EXPECT_GT(qc.gyrocompass_azimuth_sigma_deg, floor_deg * 0.99);
  EXPECT_LT(qc.gyrocompass_azimuth_sigma_deg, floor_deg * 1.5);
  EXPECT_NEAR(qc.gyrocompass_azimuth_deg, 90.0, 1e-6);
  EXPECT_NEAR(qc.static_inclination_deg, 90.0, 1e-6);
}

TEST(StationQc, FlagsAContinuousSolutionOffByFiveSigmaAndNotOneInside) {
  const StationQcBudget b = qc_budget();
  const StaticSpan span = synthetic_static_span(30.0, 60.0, 10.0, Eigen::Vector3d::Zero(),
                                                Eigen::Vector3d::Zero(), 300.0);
  const StationQc reference = station_qc(span, b, 0.0, 30.0, 0.002, 60.0, 0.5);
  EXPECT_FALSE(reference.flagged);
  const double inclination_sigma = std::hypot(0.002, reference.static_inclination_sigma_deg);
  const StationQc off_inclination =
      station_qc(span, b, 0.0, 30.0 + 5.0 * inclination_sigma, 0.002, 60.0, 0.5);
  // The bias walk widens the static solution's sigma with the time since the start.
  StationQcBudget walking = b;
  walking.gyro_bias_walk_psd.setConstant(std::pow(1.0 * kQcRadPerDegree / 3600.0, 2) / 3600.0);
  EXPECT_GT(
      station_qc(span, walking, 36000.0, 30.0, 0.002, 60.0, 0.5).gyrocompass_azimuth_sigma_deg,
      2.0 * reference.gyrocompass_azimuth_sigma_deg);
  EXPECT_TRUE(off_inclination.flagged);
  EXPECT_NEAR(off_inclination.inclination_difference_sigmas, 5.0, 1e-6);
  const double azimuth_sigma = std::hypot(0.5, reference.gyrocompass_azimuth_sigma_deg);
  EXPECT_TRUE(station_qc(span, b, 0.0, 30.0, 0.002, 60.0 - 5.0 * azimuth_sigma, 0.5).flagged);
  EXPECT_FALSE(station_qc(span, b, 0.0, 30.0, 0.002, 60.0 - 2.0 * azimuth_sigma, 0.5).flagged);
  // Near vertical the azimuth is not checked; a span too short gives no QC.
  const StationQc vertical =
      station_qc(synthetic_static_span(1.0, 60.0, 10.0, Eigen::Vector3d::Zero(),
                                       Eigen::Vector3d::Zero(), 300.0),
                 b, 0.0, 1.0, 0.002, 100.0, 0.5);
  EXPECT_TRUE(std::isnan(vertical.azimuth_difference_sigmas));
  EXPECT_FALSE(vertical.flagged);
  StaticSpan short_span = span;
  short_span.delta_theta_b *= 5.0 / 300.0;
  short_span.delta_v_b *= 5.0 / 300.0;
  short_span.duration_s = 5.0;
  EXPECT_FALSE(station_qc(short_span, b, 0.0, 30.0, 0.002, 60.0, 0.5).checked);
}

}  // namespace
}  // namespace stochnav
