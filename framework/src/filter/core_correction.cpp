#include "stochnav/filter/core_correction.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "stochnav/ins/earth.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav {
namespace core = plugin::core_state;

void apply_core_correction(const Eigen::Ref<const Eigen::VectorXd>& correction,
                           CoreEstimate& estimate) {
  NavState& state = estimate.state;
  const Eigen::Vector3d dr = correction.segment<3>(core::kPosition);
  // A correction without a horizontal part (the navigator's second-order attitude drift, fed
  // back at every covariance interval) leaves latitude and longitude as they are: skip the
  // radii's sin and sqrt and the cos (subtracting 0 / (R + h) changes no finite latitude).
  if (dr.x() != 0.0 || dr.y() != 0.0) {
    const EarthRadii radii = earth_radii(state.latitude_rad);
    state.latitude_rad -= dr.y() / (radii.meridian_m + state.height_m);
    state.longitude_rad -=
        dr.x() / ((radii.transverse_m + state.height_m) * std::cos(state.latitude_rad));
  }
  state.height_m -= dr.z();
  state.v_n -= correction.segment<3>(core::kVelocity);
  // C_est = (I - [phi x]) C_true, so C_true = Rot(phi) C_est to first order.
  const Eigen::Vector3d phi = correction.segment<3>(core::kAttitude);
  state.q_nb = (quaternion_from_rotation_vector(phi) * state.q_nb).normalized();
  estimate.accel_bias_b -= correction.segment<3>(core::kAccelBias);
  estimate.gyro_bias_b -= correction.segment<3>(core::kGyroBias);
}

Eigen::Matrix<double, 15, 1> core_difference(const CoreEstimate& estimate,
                                             const CoreEstimate& reference) {
  const NavState& a = estimate.state;
  const NavState& b = reference.state;
  Eigen::Matrix<double, 15, 1> x;
  const EarthRadii radii = earth_radii(b.latitude_rad);
  x(core::kPosition) = std::remainder(a.longitude_rad - b.longitude_rad, 2 * std::numbers::pi) *
                       (radii.transverse_m + b.height_m) * std::cos(b.latitude_rad);
  x(core::kPosition + 1) = (a.latitude_rad - b.latitude_rad) * (radii.meridian_m + b.height_m);
  x(core::kPosition + 2) = a.height_m - b.height_m;
  x.segment<3>(core::kVelocity) = a.v_n - b.v_n;
  const Eigen::AngleAxisd rotation(b.q_nb * a.q_nb.conjugate());  // Rot(phi) = C_ref C_est^T
  x.segment<3>(core::kAttitude) = rotation.angle() * rotation.axis();
  x.segment<3>(core::kAccelBias) = estimate.accel_bias_b - reference.accel_bias_b;
  x.segment<3>(core::kGyroBias) = estimate.gyro_bias_b - reference.gyro_bias_b;
  return x;
}

}  // namespace stochnav
