#pragma once
// Helpers for the aid-plugin tests: a true state perturbed into an estimate by a core error
// state dx = estimate - truth (plugin/aid_plugin.hpp), and the numerical derivative of an aid's
// residual with respect to dx.

#include <Eigen/Core>
#include <cmath>
#include <functional>

#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/nav_state.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav::plugin::aid_test {

using ErrorState = Eigen::Matrix<double, core_state::kSize, 1>;

/// The estimate whose error against `truth` is dx: position moved by dr (ENU, m, scaled at the
/// true latitude and height), v_n + dv, and C_nb_est = (I - [phi x]) C_nb_true, i.e.
/// q_est = q(-phi) q_true (the inverse of MwdNavigator::feed_back, q_true = q(phi) q_est).
inline NavState perturbed(const NavState& truth, const ErrorState& dx) {
  namespace cs = core_state;
  const EarthRadii radii = earth_radii(truth.latitude_rad);
  NavState estimate = truth;
  estimate.longitude_rad +=
      dx(cs::kPosition) / ((radii.transverse_m + truth.height_m) * std::cos(truth.latitude_rad));
  estimate.latitude_rad += dx(cs::kPosition + 1) / (radii.meridian_m + truth.height_m);
  estimate.height_m += dx(cs::kPosition + 2);
  estimate.v_n += dx.segment<3>(cs::kVelocity);
  estimate.q_nb =
      (quaternion_from_rotation_vector(-dx.segment<3>(cs::kAttitude)) * truth.q_nb).normalized();
  return estimate;
}

/// d residual / d dx at dx = 0 by central differences: steps of 1e-3 m for the position (its
/// residual passes through latitude and longitude) and 1e-6 for the other states.
inline Eigen::MatrixXd numerical_jacobian(
    const std::function<Eigen::VectorXd(const ErrorState&)>& residual, int rows) {
  Eigen::MatrixXd jacobian(rows, core_state::kSize);
  for (int j = 0; j < core_state::kSize; ++j) {
    const double step = j < core_state::kVelocity ? 1e-3 : 1e-6;
    ErrorState dx = ErrorState::Zero();
    dx(j) = step;
    jacobian.col(j) = (residual(dx) - residual(-dx)) / (2.0 * step);
  }
  return jacobian;
}

}  // namespace stochnav::plugin::aid_test
