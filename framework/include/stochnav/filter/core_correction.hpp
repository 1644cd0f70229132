#pragma once
// The 15 core error states (plugin/state_layout.hpp, core_state) as a difference between two
// navigation estimates, and the feedback of such a difference into an estimate. One convention
// for both, the filter's: x = estimate - truth for position (ENU, m), velocity (ENU, m/s) and
// the biases (body axes), and C_nb_est = (I - [phi x]) C_nb_true for the attitude error phi
// (n frame, rad). Feeding a correction x back into an estimate gives the truth to first order.

#include <Eigen/Core>

#include "stochnav/ins/nav_state.hpp"

namespace stochnav {

/// A navigation estimate with the biases the core error state describes.
struct CoreEstimate {
  NavState state;
  Eigen::Vector3d accel_bias_b = Eigen::Vector3d::Zero();  ///< m/s^2
  Eigen::Vector3d gyro_bias_b = Eigen::Vector3d::Zero();   ///< rad/s
};

/// Applies the core part of an error-state correction (the first 15 entries of `correction`,
/// x = estimate - truth): position, velocity and biases minus x, attitude rotated by phi.
void apply_core_correction(const Eigen::Ref<const Eigen::VectorXd>& correction,
                           CoreEstimate& estimate);

/// x such that apply_core_correction(x, estimate) gives `reference` (to first order in the
/// attitude; exactly for the rotation vector phi = log(C_ref C_est^T)).
Eigen::Matrix<double, 15, 1> core_difference(const CoreEstimate& estimate,
                                             const CoreEstimate& reference);

}  // namespace stochnav
