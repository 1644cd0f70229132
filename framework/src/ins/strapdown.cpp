#include "stochnav/ins/strapdown.hpp"

#include <cmath>

#include "stochnav/ins/cross_product_matrix.hpp"
#include "stochnav/ins/earth.hpp"

namespace stochnav {
namespace {

// Below this squared angle (rad^2; 0.1 rad) quaternion_from_rotation_vector sums its series.
constexpr double kSeriesAngleSquaredLimit = 0.01;

}  // namespace

Eigen::Quaterniond quaternion_from_rotation_vector(const Eigen::Vector3d& rotation_vector) {
  const double angle_squared = rotation_vector.squaredNorm();
  if (angle_squared < 1e-16) {
    // Taylor series: cos(a/2) = 1 - a^2/8, sin(a/2)/a = 1/2 - a^2/48 (error < 1e-33).
    const double half_sinc = 0.5 - angle_squared / 48.0;
    return Eigen::Quaterniond(1.0 - angle_squared / 8.0, half_sinc * rotation_vector.x(),
                              half_sinc * rotation_vector.y(), half_sinc * rotation_vector.z());
  }
  if (angle_squared < kSeriesAngleSquaredLimit) {
    // The series in s = a^2 to s^4 (an epoch's rotation: 7e-7 rad of Earth rate, 0.063 rad at
    // 60 rpm and 100 Hz), no sqrt, sin or cos: cos(a/2) = sum (-s/4)^n / (2n)!, sin(a/2)/a =
    // sum (-s/4)^n / (2 (2n + 1)!). Truncation below 3e-20 for s < 0.01; Horner's rounding
    // leaves 1-2 units in the last place, as std::sin and std::cos do.
    const double s = angle_squared;
    const double half_cos =
        1.0 - s * (1.0 / 8 - s * (1.0 / 384 - s * (1.0 / 46080 - s * (1.0 / 10321920))));
    const double half_sinc =
        0.5 - s * (1.0 / 48 - s * (1.0 / 3840 - s * (1.0 / 645120 - s * (1.0 / 185794560))));
    return Eigen::Quaterniond(half_cos, half_sinc * rotation_vector.x(),
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
  has_second_previous_ = false;
}

Eigen::Matrix3d epoch_mean_attitude(const Eigen::Matrix3d& c_nb_start,
                                    const Eigen::Vector3d& delta_theta_b) {
  const double angle_squared = delta_theta_b.squaredNorm();
  double first;   // (1 - cos a) / a^2
  double second;  // (a - sin a) / a^3
  if (angle_squared < 1e-2) {  // series to a^4: relative error under 1e-9
    first = 0.5 - angle_squared / 24.0 + angle_squared * angle_squared / 720.0;
    second = 1.0 / 6.0 - angle_squared / 120.0 + angle_squared * angle_squared / 5040.0;
  } else {
    const double angle = std::sqrt(angle_squared);
    first = (1.0 - std::cos(angle)) / angle_squared;
    second = (angle - std::sin(angle)) / (angle_squared * angle);
  }
  const Eigen::Matrix3d a = skew(delta_theta_b);
  return c_nb_start * (Eigen::Matrix3d::Identity() + first * a + second * (a * a));
}

void StrapdownIntegrator::correct_state(const NavState& state) {
  previous_state_.latitude_rad += state.latitude_rad - state_.latitude_rad;
  previous_state_.longitude_rad += state.longitude_rad - state_.longitude_rad;
  previous_state_.height_m += state.height_m - state_.height_m;
  state_ = state;
  state_.q_nb.normalize();
}

void StrapdownIntegrator::update(const ImuIncrement& increment) {
  const double dt = increment.dt_s;
  const Eigen::Vector3d& dtheta = increment.delta_theta_b;
  const Eigen::Vector3d& dv = increment.delta_v_b;
  if (!(dt > 0.0)) {
    state_.t_s = increment.t_s;
    specific_force_increment_n_.setZero();
    return;
  }
  const Eigen::Vector3d& dtheta_prev = has_previous_ ? previous_delta_theta_b_ : dtheta;
  const Eigen::Vector3d& dv_prev = has_previous_ ? previous_delta_v_b_ : dv;
  const NavState old = state_;

  // Mid-interval latitude and height extrapolated from k-1 and k-2 (they change smoothly).
  const double lat_mid = 1.5 * old.latitude_rad - 0.5 * previous_state_.latitude_rad;
  const double h_mid = 1.5 * old.height_m - 0.5 * previous_state_.height_m;
  // One sin, cos, tan and one pair of radii for the four terms at lat_mid.
  const LatitudeTerms mid(lat_mid);
  const LatitudeTrig& trig_mid = mid.trig;
  const Eigen::Vector3d omega_ie_mid = earth_rate_n(trig_mid);
  const Eigen::Vector3d g_mid = gravity_n(trig_mid, h_mid);

  // Velocity: specific force with rotation and sculling corrections, carried to the mid-interval
  // navigation frame.
  // Rotation compensation to second order (Savage: (1 - cos a)/a^2 a x dv + (1 - sin a/a)/a^2
  // a x (a x dv)); the second-order term removes a bias of (theta^2/6) |f_perp| that a
  // spinning tool (drill-string rotation) would otherwise see from the first-order form.
  const double angle_squared = dtheta.squaredNorm();
  const double first = 0.5 - angle_squared / 24.0;
  const double second = 1.0 / 6.0 - angle_squared / 120.0;
  const Eigen::Vector3d dtheta_x_dv = dtheta.cross(dv);
  // Two-sample sculling. (A three-sample form, exact for quadratic rate and force, is worse for
  // a spinning tool: the two-sample form and the (1 - cos a)/a^2 coefficient cancel each
  // other's third-order terms exactly for a constant spin, tests/ins/strapdown_test.cpp.)
  const Eigen::Vector3d sculling = (dtheta_prev.cross(dv) + dv_prev.cross(dtheta)) / 12.0;
  const Eigen::Vector3d dv_corrected =
      dv + first * dtheta_x_dv + second * dtheta.cross(dtheta_x_dv) + sculling;
  const Eigen::Vector3d dv_body_n = old.q_nb * dv_corrected;
  const Eigen::Vector3d omega_en_old = transport_rate_n(trig_mid, mid.radii, h_mid, old.v_n);
  const Eigen::Vector3d dv_sf_n =
      dv_body_n - 0.5 * ((omega_ie_mid + omega_en_old) * dt).cross(dv_body_n);
  specific_force_increment_n_ = dv_sf_n;
  // Coriolis and gravity with the trapezoid velocity of a predictor step: exact for a velocity
  // changing linearly, and never amplifying vibration aliased into the samples (an
  // extrapolation from k-1 and k-2 would double it at the Nyquist frequency).
  const Eigen::Vector3d v_predicted =
      old.v_n + dv_sf_n + (g_mid - (2.0 * omega_ie_mid + omega_en_old).cross(old.v_n)) * dt;
  const Eigen::Vector3d v_mid = 0.5 * (old.v_n + v_predicted);
  const Eigen::Vector3d omega_en_mid = transport_rate_n(trig_mid, mid.radii, h_mid, v_mid);
  state_.v_n = old.v_n + dv_sf_n + (g_mid - (2.0 * omega_ie_mid + omega_en_mid).cross(v_mid)) * dt;

  // Position: trapezoid of the velocity, radii at the mid-interval height and latitude.
  const Eigen::Vector3d v_average = 0.5 * (old.v_n + state_.v_n);
  state_.height_m = old.height_m + v_average.z() * dt;
  const double h_average = 0.5 * (old.height_m + state_.height_m);
  // The starting latitude's terms are usually known: the previous update's end (the memo).
  const double meridian_old_m = state_latitude_.at(old.latitude_rad).radii.meridian_m;
  state_.latitude_rad = old.latitude_rad + v_average.y() / (meridian_old_m + h_average) * dt;
  const double lat_average = 0.5 * (old.latitude_rad + state_.latitude_rad);
  const LatitudeTerms& average = mid_latitude_.at(lat_average);
  state_.latitude_rad =
      old.latitude_rad + v_average.y() / (average.radii.meridian_m + h_average) * dt;
  state_.longitude_rad =
      old.longitude_rad +
      v_average.x() / ((average.radii.transverse_m + h_average) * average.trig.cos) * dt;

  // Attitude with the Earth and transport rates at the (now known) mid-interval state.
  Eigen::Vector3d phi;
  if (has_second_previous_) {
    // Coning term exact for an angular rate varying quadratically over the last three intervals
    // (the integral of alpha x omega / 2 written with the three increments).
    const Eigen::Vector3d& dtheta_prev2 = second_previous_delta_theta_b_;
    phi = dtheta + (121.0 / 720.0) * dtheta_prev.cross(dtheta) -
          (31.0 / 720.0) * dtheta_prev2.cross(dtheta) +
          (1.0 / 720.0) * dtheta_prev2.cross(dtheta_prev);
  } else {
    phi = dtheta + dtheta_prev.cross(dtheta) / 12.0;  // two-sample form
  }
  // Almost always lat_average to the last bit (the memo then computes nothing).
  const LatitudeTerms& new_mid = mid_latitude_.at(0.5 * (old.latitude_rad + state_.latitude_rad));
  const Eigen::Vector3d zeta = (earth_rate_n(new_mid.trig) +
                                transport_rate_n(new_mid.trig, new_mid.radii, h_average, v_average)) *
                               dt;
  state_.q_nb =
      quaternion_from_rotation_vector(-zeta) * old.q_nb * quaternion_from_rotation_vector(phi);
  state_.q_nb.normalize();
  state_.t_s = increment.t_s;

  previous_state_ = old;
  has_second_previous_ = has_previous_;
  second_previous_delta_theta_b_ = previous_delta_theta_b_;
  previous_delta_theta_b_ = dtheta;
  previous_delta_v_b_ = dv;
  has_previous_ = true;
}

}  // namespace stochnav
