#include "stochnav/experiment/navigation_errors.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "stochnav/core/angles.hpp"
#include "stochnav/ins/earth.hpp"

namespace stochnav {
namespace {

double wrapped_degrees(double angle_rad) {
  double degrees = std::remainder(angle_rad * kDegPerRad, 360.0);  // [-180, 180]
  if (degrees == -180.0) degrees = 180.0;
  return degrees;
}

}  // namespace

std::array<double, kErrorMetricCount> navigation_errors(const NavState& estimate,
                                                       const NavState& truth,
                                                       double vertical_inclination_deg) {
  const EarthRadii radii = earth_radii(truth.latitude_rad);
  const MwdAttitude est = mwd_from_quaternion(estimate.q_nb);
  const MwdAttitude tru = mwd_from_quaternion(truth.q_nb);
  const bool vertical = tru.inclination_rad * kDegPerRad < vertical_inclination_deg;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector3d dv = estimate.v_n - truth.v_n;
  return {
      (estimate.latitude_rad - truth.latitude_rad) * (radii.meridian_m + truth.height_m),
      std::remainder(estimate.longitude_rad - truth.longitude_rad, 2.0 * std::numbers::pi) *
          (radii.transverse_m + truth.height_m) * std::cos(truth.latitude_rad),
      estimate.height_m - truth.height_m,
      (est.inclination_rad - tru.inclination_rad) * kDegPerRad,
      vertical ? nan : wrapped_degrees(est.toolface_rad - tru.toolface_rad),
      vertical ? nan : wrapped_degrees(est.azimuth_rad - tru.azimuth_rad),
      dv.x(),
      dv.y(),
      dv.z()};
}

std::array<double, kErrorMetricCount> navigation_error_sigmas(
    const NavState& estimate, const Eigen::Matrix<double, 9, 9>& covariance,
    double vertical_inclination_deg) {
  const Eigen::Matrix<double, 9, 1> variance = covariance.diagonal();
  std::array<double, kErrorMetricCount> sigma{};
  // lat, lon, height errors are the north, east and up position errors.
  sigma[0] = std::sqrt(variance(1));
  sigma[1] = std::sqrt(variance(0));
  sigma[2] = std::sqrt(variance(2));
  // d(angles)/d(phi) by central differences: C_est = (I - [phi x]) C_true.
  constexpr double kStep = 1e-6;
  Eigen::Matrix3d jacobian;
  for (int k = 0; k < 3; ++k) {
    const MwdAttitude plus = mwd_from_quaternion(
        Eigen::Quaterniond(Eigen::AngleAxisd(-kStep, Eigen::Vector3d::Unit(k))) * estimate.q_nb);
    const MwdAttitude minus = mwd_from_quaternion(
        Eigen::Quaterniond(Eigen::AngleAxisd(kStep, Eigen::Vector3d::Unit(k))) * estimate.q_nb);
    jacobian(0, k) = (plus.inclination_rad - minus.inclination_rad) / (2 * kStep);
    jacobian(1, k) = std::remainder(plus.toolface_rad - minus.toolface_rad, 2 * std::numbers::pi) /
                     (2 * kStep);
    jacobian(2, k) = std::remainder(plus.azimuth_rad - minus.azimuth_rad, 2 * std::numbers::pi) /
                     (2 * kStep);
  }
  const Eigen::Matrix3d angles =
      jacobian * covariance.block<3, 3>(6, 6) * jacobian.transpose();
  const bool vertical =
      mwd_from_quaternion(estimate.q_nb).inclination_rad * kDegPerRad < vertical_inclination_deg;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  sigma[3] = std::sqrt(angles(0, 0)) * kDegPerRad;
  sigma[4] = vertical ? nan : std::sqrt(angles(1, 1)) * kDegPerRad;
  sigma[5] = vertical ? nan : std::sqrt(angles(2, 2)) * kDegPerRad;
  sigma[6] = std::sqrt(variance(3));
  sigma[7] = std::sqrt(variance(4));
  sigma[8] = std::sqrt(variance(5));
  return sigma;
}

void ErrorStatistics::add(const std::array<double, kErrorMetricCount>& errors) {
  for (std::size_t i = 0; i < kErrorMetricCount; ++i) {
    if (std::isnan(errors[i])) continue;
    max_abs_[i] = std::max(max_abs_[i], std::abs(errors[i]));
    sum_squares_[i] += errors[i] * errors[i];
    ++count_[i];
  }
}

ErrorStatistics ErrorStatistics::from_parts(
    const std::array<double, kErrorMetricCount>& max_abs,
    const std::array<double, kErrorMetricCount>& sum_squares,
    const std::array<std::size_t, kErrorMetricCount>& count) {
  ErrorStatistics statistics;
  statistics.max_abs_ = max_abs;
  statistics.sum_squares_ = sum_squares;
  statistics.count_ = count;
  return statistics;
}

double ErrorStatistics::rms(std::size_t metric) const {
  if (count_[metric] == 0) return std::numeric_limits<double>::quiet_NaN();
  return std::sqrt(sum_squares_[metric] / static_cast<double>(count_[metric]));
}

nlohmann::json ErrorStatistics::to_json() const {
  nlohmann::json out = nlohmann::json::object();
  for (std::size_t i = 0; i < kErrorMetricCount; ++i) {
    const std::string name(kErrorMetricNames[i]);
    if (count_[i] == 0) {
      out[name] = {{"max_abs", nullptr}, {"rms", nullptr}, {"samples", 0}};
    } else {
      out[name] = {{"max_abs", max_abs_[i]}, {"rms", rms(i)}, {"samples", count_[i]}};
    }
  }
  return out;
}

}  // namespace stochnav
