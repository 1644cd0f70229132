#pragma once
// Options of the MWD navigation filter (filter/mwd_navigator.hpp), with units. The run config's
// "filter" section fills this struct; the defaults here are the documented defaults.

#include <Eigen/Core>

namespace stochnav {

struct FilterOptions {
  /// P is propagated once per interval of this length (s), with the transition and noise of
  /// the whole interval accumulated from every IMU epoch in it (the fast inputs, C_nb and f_n,
  /// integrated exactly; see filter/error_dynamics.hpp). 0 propagates at every IMU epoch. The
  /// INS itself always runs at the IMU rate. At 0.1 s the covariance differs from the
  /// every-epoch propagation by far less than its own uncertainty (tests/filter).
  double covariance_interval_s = 0.1;

  /// After this many consecutive NIS-gate rejections of one aid, its next measurement is
  /// applied ungated. A gate must not lock the filter out of its aiding for good once the state
  /// has drifted past the gate (the classic gate lockout: rejected updates let the error grow,
  /// which makes the next NIS larger still). 0 keeps the gate strict.
  int max_consecutive_rejections = 10;

  // Initial 1-sigma uncertainties of the core error states.
  Eigen::Vector3d position_sigma_m{0.1, 0.1, 0.1};          ///< ENU (m)
  Eigen::Vector3d velocity_sigma_mps{0.01, 0.01, 0.01};     ///< ENU (m/s)
  Eigen::Vector3d attitude_sigma_rad{1e-3, 1e-3, 1e-2};     ///< phi about E, N, U (rad)
  Eigen::Vector3d accel_bias_sigma_mps2{1e-3, 1e-3, 1e-3};  ///< body axes (m/s^2)
  Eigen::Vector3d gyro_bias_sigma_radps{5e-6, 5e-6, 5e-6};  ///< body axes (rad/s) (~1 deg/h)

  // Scale-factor error states (plugin/state_layout.hpp: blocks "gyro_scale_factor" and
  // "accel_scale_factor", 3 states each, after the 15 core states): the sensor reads
  // (1 + s) times the true rate or specific force per body axis, s a random constant
  // (dimensionless; 1e-6 = 1 ppm). A group's 3 states exist when any of its sigmas is > 0; they
  // start at zero with these 1-sigma uncertainties. A tool rotating at 60 rpm turns a 10 ppm
  // z scale factor into a 13 deg/h apparent z bias while drilling that vanishes at every
  // connection: without these states the filter attributes it to the bias.
  Eigen::Vector3d gyro_scale_factor_sigma{0.0, 0.0, 0.0};   ///< body axes (dimensionless)
  Eigen::Vector3d accel_scale_factor_sigma{0.0, 0.0, 0.0};  ///< body axes (dimensionless)

  /// Covariance products by blocks (filter/error_state_filter.hpp, BlockTransition and
  /// JosephForm::kExpanded): augmented states cost O(n^2) per propagation and update instead of
  /// O(n^3), with the same results to rounding. false: the dense products, kept as the
  /// reference for tests and benchmarks.
  bool structured_covariance = true;
};

}  // namespace stochnav
