#include "stochnav/experiment/station_qc.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/filter/alignment.hpp"
#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/mwd_attitude.hpp"

namespace stochnav {
namespace {

// Names of their own: the sanitizer preset's unity build puts this file beside others.
constexpr double kUndefinedQc = std::numeric_limits<double>::quiet_NaN();
constexpr double kQcDegPerHourPerRadPerSecond = kDegPerRad * 3600.0;

// (inclination, azimuth) in rad of the static solution of the means; NaN when the means cannot
// be aligned (no specific force or no horizontal Earth rate).
std::array<double, 2> static_solution_angles(const Eigen::Vector3d& omega_b,
                                             const Eigen::Vector3d& f_b, double latitude_rad) {
  StaticMeans means;
  means.omega_ib_b = omega_b;
  means.f_ib_b = f_b;
  means.duration_s = 1.0;
  try {
    const MwdAttitude attitude = mwd_from_quaternion(coarse_alignment(means, latitude_rad));
    return {attitude.inclination_rad, attitude.azimuth_rad};
  } catch (const ConfigError&) {
    return {kUndefinedQc, kUndefinedQc};
  }
}

double wrapped_angle(double angle_rad) { return std::remainder(angle_rad, 2.0 * std::numbers::pi); }

}  // namespace

StationQc station_qc(const StaticSpan& span, const StationQcBudget& budget, double t_s,
                     double continuous_inclination_deg, double continuous_inclination_sigma_deg,
                     double continuous_azimuth_deg, double continuous_azimuth_sigma_deg) {
  StationQc qc;
  qc.static_duration_s = span.duration_s;
  const double t = span.duration_s;
  if (!(t >= kMinimumStaticSpan_s)) {
    qc.static_inclination_deg = qc.static_inclination_sigma_deg = kUndefinedQc;
    qc.gyrocompass_azimuth_deg = qc.gyrocompass_azimuth_sigma_deg = kUndefinedQc;
    qc.gravity_total_m_s2 = qc.gravity_model_m_s2 = qc.gravity_sigma_m_s2 = kUndefinedQc;
    qc.earth_rate_total_deg_h = qc.earth_rate_sigma_deg_h = kUndefinedQc;
    qc.inclination_difference_sigmas = qc.azimuth_difference_sigmas = kUndefinedQc;
    return qc;
  }
  qc.checked = true;
  const Eigen::Vector3d omega = span.delta_theta_b / t;
  const Eigen::Vector3d f = span.delta_v_b / t;
  const double g = normal_gravity(budget.latitude_rad, budget.height_m);
  const double elapsed_s = std::max(0.0, t_s - budget.start_t_s);
  const Eigen::Array3d gyro_var = budget.gyro_bias_sigma_radps.array().square() +
                                  budget.gyro_bias_walk_psd.array() * elapsed_s +
                                  budget.gyro_white_psd.array() / t;
  const Eigen::Array3d accel_var = budget.accel_bias_sigma_mps2.array().square() +
                                   budget.accel_bias_walk_psd.array() * elapsed_s +
                                   (budget.accel_scale_factor_sigma.array() * g).square() +
                                   budget.accel_white_psd.array() / t;

  const auto angles = static_solution_angles(omega, f, budget.latitude_rad);
  // First-order propagation by central differences, per input axis.
  Eigen::Array2d variance = Eigen::Array2d::Zero();
  const double step_omega = 1e-3 * wgs84::kEarthRate_radps;
  const double step_f = 1e-5 * g;
  for (int axis = 0; axis < 3; ++axis) {
    for (const bool gyro : {true, false}) {
      const double step = gyro ? step_omega : step_f;
      Eigen::Vector3d delta = Eigen::Vector3d::Zero();
      delta(axis) = step;
      const auto plus = gyro ? static_solution_angles(omega + delta, f, budget.latitude_rad)
                             : static_solution_angles(omega, f + delta, budget.latitude_rad);
      const auto minus = gyro ? static_solution_angles(omega - delta, f, budget.latitude_rad)
                              : static_solution_angles(omega, f - delta, budget.latitude_rad);
      const double input_var = gyro ? gyro_var(axis) : accel_var(axis);
      for (int k = 0; k < 2; ++k) {
        const double slope =
            (k == 0 ? plus[k] - minus[k] : wrapped_angle(plus[k] - minus[k])) / (2 * step);
        variance(k) += slope * slope * input_var;
      }
    }
  }
  qc.static_inclination_deg = angles[0] * kDegPerRad;
  qc.static_inclination_sigma_deg = std::sqrt(variance(0)) * kDegPerRad;
  const bool azimuth_defined = qc.static_inclination_deg > kMinimumInclination_deg &&
                               continuous_inclination_deg > kMinimumInclination_deg;
  qc.gyrocompass_azimuth_deg = azimuth_defined ? angles[1] * kDegPerRad : kUndefinedQc;
  qc.gyrocompass_azimuth_sigma_deg =
      azimuth_defined ? std::sqrt(variance(1)) * kDegPerRad : kUndefinedQc;

  qc.gravity_total_m_s2 = f.norm();
  qc.gravity_model_m_s2 = g;
  const Eigen::Vector3d up_b = f.normalized();  // the total's sensitivity to each axis
  qc.gravity_sigma_m_s2 = std::sqrt((up_b.array().square() * accel_var).sum());
  qc.earth_rate_total_deg_h = omega.norm() * kQcDegPerHourPerRadPerSecond;
  const Eigen::Vector3d spin_b = omega.normalized();
  qc.earth_rate_sigma_deg_h =
      std::sqrt((spin_b.array().square() * gyro_var).sum()) * kQcDegPerHourPerRadPerSecond;

  const double inclination_sigma =
      std::hypot(continuous_inclination_sigma_deg, qc.static_inclination_sigma_deg);
  qc.inclination_difference_sigmas =
      std::abs(continuous_inclination_deg - qc.static_inclination_deg) / inclination_sigma;
  qc.azimuth_difference_sigmas = kUndefinedQc;
  if (azimuth_defined && std::isfinite(continuous_azimuth_sigma_deg)) {
    const double difference =
        wrapped_angle((continuous_azimuth_deg - qc.gyrocompass_azimuth_deg) / kDegPerRad) *
        kDegPerRad;
    qc.azimuth_difference_sigmas =
        std::abs(difference) /
        std::hypot(continuous_azimuth_sigma_deg, qc.gyrocompass_azimuth_sigma_deg);
  }
  qc.flagged = qc.inclination_difference_sigmas > 3.0 ||
               (std::isfinite(qc.azimuth_difference_sigmas) && qc.azimuth_difference_sigmas > 3.0);
  return qc;
}

}  // namespace stochnav
