#include "stochnav/filter/alignment.hpp"

#include <cmath>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/filter/mwd_navigator.hpp"
#include "stochnav/ins/earth.hpp"

namespace stochnav {
namespace {

// Orthonormal triad from a primary and a secondary direction.
Eigen::Matrix3d triad(const Eigen::Vector3d& primary, const Eigen::Vector3d& secondary) {
  const Eigen::Vector3d first = primary.normalized();
  const Eigen::Vector3d second = primary.cross(secondary).normalized();
  Eigen::Matrix3d frame;
  frame << first, second, first.cross(second);
  return frame;
}

}  // namespace

StaticMeans static_means(std::span<const ImuIncrement> increments) {
  StaticMeans means;
  for (const ImuIncrement& increment : increments) {
    means.omega_ib_b += increment.delta_theta_b;
    means.f_ib_b += increment.delta_v_b;
    means.duration_s += increment.dt_s;
  }
  if (!(means.duration_s > 0.0)) {
    throw ConfigError("alignment: the static period is empty; give it a positive duration");
  }
  means.omega_ib_b /= means.duration_s;
  means.f_ib_b /= means.duration_s;
  return means;
}

StaticSpread static_spread(std::span<const ImuIncrement> increments, double block_s) {
  std::vector<double> gyro, accel;
  Eigen::Vector3d theta = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
  double duration = 0.0;
  for (const ImuIncrement& increment : increments) {
    theta += increment.delta_theta_b;
    v += increment.delta_v_b;
    duration += increment.dt_s;
    if (duration >= block_s * (1.0 - 1e-9)) {
      gyro.push_back(theta.norm() / duration);
      accel.push_back(v.norm() / duration);
      theta.setZero();
      v.setZero();
      duration = 0.0;
    }
  }
  const auto deviation = [](const std::vector<double>& x) {
    if (x.size() < 2) return 0.0;
    double mean = 0.0;
    for (double value : x) mean += value;
    mean /= static_cast<double>(x.size());
    double sum = 0.0;
    for (double value : x) sum += (value - mean) * (value - mean);
    return std::sqrt(sum / static_cast<double>(x.size() - 1));
  };
  return {deviation(gyro), deviation(accel), static_cast<int>(gyro.size())};
}

Eigen::Quaterniond coarse_alignment(const StaticMeans& means, double latitude_rad) {
  const Eigen::Vector3d f_n(0.0, 0.0, 1.0);  // direction of the specific force at rest: up
  const Eigen::Vector3d omega_n = earth_rate_n(latitude_rad);
  if (means.f_ib_b.norm() < 1.0 || means.omega_ib_b.cross(means.f_ib_b).norm() == 0.0 ||
      std::cos(latitude_rad) < 1e-6) {
    throw ConfigError(
        "alignment: the specific force or the horizontal Earth rate vanishes; align on a static "
        "period away from the poles");
  }
  const Eigen::Matrix3d c_nb =
      triad(f_n, omega_n) * triad(means.f_ib_b, means.omega_ib_b).transpose();
  return Eigen::Quaterniond(c_nb).normalized();
}

FineAlignmentResult fine_alignment(const NavState& initial,
                                   std::span<const ImuIncrement> increments,
                                   plugin::NoiseModelPlugin& gyro_noise,
                                   plugin::NoiseModelPlugin& accel_noise,
                                   std::vector<plugin::AidPlugin*> aids,
                                   const FilterOptions& options) {
  MwdNavigator navigator(initial, gyro_noise, accel_noise, std::move(aids), options);
  for (const ImuIncrement& increment : increments) navigator.step(increment);
  FineAlignmentResult result;
  result.state = navigator.state();
  // The biases whole (bias state plus augmented share, 70 % of a FOG's turn-on bias in a
  // 0.5 deg/h flicker model's states): the form a start whose augmented states begin at their
  // prior needs (the bank over the heading). And the whole end, from which a one-filter run
  // continues this filter.
  result.gyro_bias_b = navigator.gyro_total_bias_b();
  result.accel_bias_b = navigator.accel_total_bias_b();
  result.core_covariance = navigator.core_covariance_with_total_biases();
  result.whole = navigator.whole_start();
  const Eigen::VectorXd sigma = result.core_covariance.diagonal().cwiseSqrt();
  result.position_sigma_m = sigma.segment<3>(0);
  result.velocity_sigma_mps = sigma.segment<3>(3);
  result.attitude_sigma_rad = sigma.segment<3>(6);
  result.accel_bias_sigma_mps2 = sigma.segment<3>(9);
  result.gyro_bias_sigma_radps = sigma.segment<3>(12);
  return result;
}

}  // namespace stochnav
