#include "stochnav/ins/strapdown.hpp"

#include <cmath>

#include "stochnav/ins/earth.hpp"

namespace stochnav {

Eigen::Quaterniond quaternion_from_rotation_vector(const Eigen::Vector3d& rotation_vector) {
  const double angle_squared = rotation_vector.squaredNorm();
  if (angle_squared < 1e-16) {
    // Taylor series: cos(a/2) = 1 - a^2/8, sin(a/2)/a = 1/2 - a^2/48 (error < 1e-33).
    const double half_sinc = 0.5 - angle_squared / 48.0;
    return Eigen::Quaterniond(1.0 - angle_squared / 8.0, half_sinc * rotation_vector.x(),
                              half_sinc * rotation_vector.y(), half_sinc * rotation_vector.z());
  }
  const double angle = std::sqrt(angle_squared);
  const double half_sinc = std::sin(0.5 * angle) / angle;
  return Eigen::Quaterniond(std::cos(0.5 * angle), half_sinc * rotation_vector.x(),
                            half_sinc * rotation_vector.y(), half_sinc * rotation_vector.z());
}

StrapdownIntegrator::StrapdownIntegrator(const NavState& initial) { set_state(initial); }

void StrapdownIntegrator::set_state(const NavState& state) {
  state_ = state;
  state_.q_nb.normalize();
  previous_state_ = state_;
  has_previous_ = false;
}

void StrapdownIntegrator::update(const ImuIncrement& increment) {
  const double dt = increment.dt_s;
  const Eigen::Vector3d& dtheta = increment.delta_theta_b;
  const Eigen::Vector3d& dv = increment.delta_v_b;
  if (!(dt > 0.0)) {
    state_.t_s = increment.t_s;
    return;
  }
  const Eigen::Vector3d& dtheta_prev = has_previous_ ? previous_delta_theta_b_ : dtheta;
  const Eigen::Vector3d& dv_prev = has_previous_ ? previous_delta_v_b_ : dv;
  const NavState old = state_;

  // Mid-interval extrapolation from k-1 and k-2 for the Earth terms of the velocity update.
  const double lat_mid = 1.5 * old.latitude_rad - 0.5 * previous_state_.latitude_rad;
  const double h_mid = 1.5 * old.height_m - 0.5 * previous_state_.height_m;
  const Eigen::Vector3d v_mid = 1.5 * old.v_n - 0.5 * previous_state_.v_n;
  const Eigen::Vector3d omega_ie_mid = earth_rate_n(lat_mid);
  const Eigen::Vector3d omega_en_mid = transport_rate_n(lat_mid, h_mid, v_mid);
  const Eigen::Vector3d zeta_mid = (omega_ie_mid + omega_en_mid) * dt;

  // Velocity.
  const Eigen::Vector3d dv_corrected = dv + 0.5 * dtheta.cross(dv) +
                                       (dtheta_prev.cross(dv) + dv_prev.cross(dtheta)) / 12.0;
  const Eigen::Vector3d dv_body_n = old.q_nb * dv_corrected;
  const Eigen::Vector3d dv_sf_n = dv_body_n - 0.5 * zeta_mid.cross(dv_body_n);
  const Eigen::Vector3d dv_gravity_coriolis_n =
      (gravity_n(lat_mid, h_mid) - (2.0 * omega_ie_mid + omega_en_mid).cross(v_mid)) * dt;
  state_.v_n = old.v_n + dv_sf_n + dv_gravity_coriolis_n;

  // Position: trapezoid of the velocity, radii at the mid-interval height and latitude.
  const Eigen::Vector3d v_average = 0.5 * (old.v_n + state_.v_n);
  state_.height_m = old.height_m + v_average.z() * dt;
  const double h_average = 0.5 * (old.height_m + state_.height_m);
  const EarthRadii radii_old = earth_radii(old.latitude_rad);
  state_.latitude_rad =
      old.latitude_rad + v_average.y() / (radii_old.meridian_m + h_average) * dt;
  const double lat_average = 0.5 * (old.latitude_rad + state_.latitude_rad);
  const EarthRadii radii = earth_radii(lat_average);
  state_.latitude_rad = old.latitude_rad + v_average.y() / (radii.meridian_m + h_average) * dt;
  state_.longitude_rad = old.longitude_rad + v_average.x() /
                                                 ((radii.transverse_m + h_average) *
                                                  std::cos(lat_average)) *
                                                 dt;

  // Attitude with the Earth and transport rates at the (now known) mid-interval state.
  const Eigen::Vector3d phi = dtheta + dtheta_prev.cross(dtheta) / 12.0;
  const double lat_new_mid = 0.5 * (old.latitude_rad + state_.latitude_rad);
  const Eigen::Vector3d zeta = (earth_rate_n(lat_new_mid) +
                                transport_rate_n(lat_new_mid, h_average, v_average)) *
                               dt;
  state_.q_nb = quaternion_from_rotation_vector(-zeta) * old.q_nb *
                quaternion_from_rotation_vector(phi);
  state_.q_nb.normalize();
  state_.t_s = increment.t_s;

  previous_state_ = old;
  previous_delta_theta_b_ = dtheta;
  previous_delta_v_b_ = dv;
  has_previous_ = true;
}

}  // namespace stochnav
