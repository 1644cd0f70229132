#pragma once
// Static alignment of a strapdown IMU: coarse analytic alignment (levelling from the
// accelerometers, gyrocompassing from the gyros) and fine alignment (the navigation filter run
// over the static period with zero-velocity and known-position updates, which estimates the
// residual tilt, heading and the sensor biases).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "stochnav/filter/filter_options.hpp"
#include "stochnav/ins/nav_state.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/plugin/aid_plugin.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"

namespace stochnav {

/// Mean body rates of a static period.
struct StaticMeans {
  Eigen::Vector3d omega_ib_b = Eigen::Vector3d::Zero();  ///< mean angular rate (rad/s)
  Eigen::Vector3d f_ib_b = Eigen::Vector3d::Zero();      ///< mean specific force (m/s^2)
  double duration_s = 0.0;                               ///< length of the period (s)
};

/// Means of the increments (sum of increments / sum of intervals). Throws ConfigError when the
/// span is empty or its intervals sum to zero.
StaticMeans static_means(std::span<const ImuIncrement> increments);

/// How still a span is: the standard deviation, over consecutive blocks of `block_s` seconds,
/// of each block's mean |omega_ib_b| and mean |f_ib_b|. A static tool shows only sensor noise
/// averaged over a block; a tool that turns or moves shows far more. Blocks shorter than
/// block_s at the end are dropped; fewer than two whole blocks give zero spreads.
struct StaticSpread {
  double gyro_radps = 0.0;   ///< std of the block means of |omega| (rad/s)
  double accel_mps2 = 0.0;   ///< std of the block means of |f| (m/s^2)
  int blocks = 0;            ///< number of blocks used
};
StaticSpread static_spread(std::span<const ImuIncrement> increments, double block_s);

/// Coarse alignment: the C_nb (as q_nb) that maps the measured mean specific force to
/// (0, 0, g) and the measured mean rate to the Earth rate (0, W cos lat, W sin lat) in ENU,
/// by TRIAD (gravity trusted first, the Earth rate fixing heading). Heading error is about
/// gyro bias / (W cos lat) rad: 0.06 deg per 0.01 deg/h of bias at 40 deg latitude.
/// Throws ConfigError when the specific force or the horizontal Earth rate vanishes (not
/// static, or at a pole).
Eigen::Quaterniond coarse_alignment(const StaticMeans& means, double latitude_rad);

/// Fine alignment: runs the navigation filter over the static period from `initial` (position
/// known, velocity zero, attitude from coarse_alignment), with the given noise models and aids
/// (typically a zero-velocity / static-position aid). Returns the navigator's final state and
/// estimates, the biases whole: the bias states plus the noise models' augmented share
/// (MwdNavigator::gyro_total_bias_b), so that a run whose augmented states start from their
/// prior starts from all the bias the attitude was aligned with.
struct FineAlignmentResult {
  NavState state;
  Eigen::Vector3d gyro_bias_b = Eigen::Vector3d::Zero();         ///< whole bias, rad/s
  Eigen::Vector3d accel_bias_b = Eigen::Vector3d::Zero();        ///< whole bias, m/s^2
  Eigen::Vector3d attitude_sigma_rad = Eigen::Vector3d::Zero();  ///< 1-sigma of phi, E N U
  // The other core 1-sigmas at the end (the diagonal of core_covariance).
  Eigen::Vector3d position_sigma_m = Eigen::Vector3d::Zero();       ///< ENU (m)
  Eigen::Vector3d velocity_sigma_mps = Eigen::Vector3d::Zero();     ///< ENU (m/s)
  Eigen::Vector3d accel_bias_sigma_mps2 = Eigen::Vector3d::Zero();  ///< body (m/s^2)
  Eigen::Vector3d gyro_bias_sigma_radps = Eigen::Vector3d::Zero();  ///< body (rad/s)
  /// The core block of P at the end (core_state order), correlations included, with the bias
  /// states' rows those of the whole biases (MwdNavigator::core_covariance_with_total_biases).
  Eigen::Matrix<double, 15, 15> core_covariance = Eigen::Matrix<double, 15, 15>::Zero();
  /// The navigator's whole end (bias and augmented states apart, the whole P): a run with the
  /// same noise models continues from it (FilterOptions::whole_start).
  FilterOptions::WholeStart whole;
};
FineAlignmentResult fine_alignment(const NavState& initial,
                                   std::span<const ImuIncrement> increments,
                                   plugin::NoiseModelPlugin& gyro_noise,
                                   plugin::NoiseModelPlugin& accel_noise,
                                   std::vector<plugin::AidPlugin*> aids,
                                   const FilterOptions& options);

}  // namespace stochnav
