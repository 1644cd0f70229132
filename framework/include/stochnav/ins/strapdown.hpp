#pragma once
// Strapdown inertial navigation in the ENU frame of ins/nav_state.hpp, driven by IMU increments.
//
// One update(k) advances the state from t_k - dt to t_k with the increments of that interval and
// those of earlier intervals, in the order velocity, position, attitude:
//   velocity   dv_sf = (I - [zeta x] / 2) C_nb(k-1) (dv + a1 dtheta x dv
//                      + a2 dtheta x (dtheta x dv)                          (rotation)
//                      + (dtheta_prev x dv + dv_prev x dtheta) / 12)        (two-sample sculling)
//              with a1 = (1 - cos a)/a^2 ~ 1/2 - a^2/24, a2 = (1 - sin a / a)/a^2 ~ 1/6 - a^2/120,
//              v_k = v_k-1 + dv_sf + (g_n - (2 omega_ie_n + omega_en_n) x v_mid) dt, with latitude
//              and height at mid-interval extrapolated from k-1 and k-2 and v_mid the trapezoid
//              velocity of a predictor step;
//   position   h, then lat, then lon by the trapezoid of v_n with the radii at mid-interval;
//   attitude   phi = dtheta + (121 dtheta_prev x dtheta - 31 dtheta_prev2 x dtheta
//                    + dtheta_prev2 x dtheta_prev) / 720
//              (coning term exact for an angular rate varying quadratically over three intervals),
//              zeta = (omega_ie_n + omega_en_n) dt at mid-interval,
//              q_nb(k) = q(-zeta) q_nb(k-1) q(phi), normalised.
// After construction or set_state() the first update has no previous interval (coning and sculling
// zero) and the second uses the two-sample coning form dtheta_prev x dtheta / 12; correct_state()
// (a filter's feedback) keeps the previous intervals.
//
// Accuracy allowed by this integration order, for exact increments at 100 Hz (the noise-free
// scenarios of tests/ins/strapdown_test.cpp, one hour each; measured values in brackets):
//   static tool                   attitude < 1e-10 rad (1.5e-11), velocity < 1e-5 m/s (2.7e-7);
//   vibration table, 5 g 25 Hz sine and 13 g random (20-2000 Hz) vibration
//                                 attitude < 1e-8 rad (2e-9), velocity < 1e-3 m/s (2.1e-4);
//   drilling, 60 rpm rotation through a 10 deg/30 m build
//                                 attitude < 3e-7 rad (1.1e-7), velocity < 2e-3 m/s (7.2e-4);
//   drilling at 160 rpm, 280 s at 85 deg: velocity 9.0e-3 m/s (the spin's theta^4 residual,
//                                 3e-5 m/s^2, a 3-ppm cross-axis accelerometer scale factor).
// What limits them: (a) under drill-string rotation theta = omega dt per interval (0.063 rad at
// 60 rpm, 100 Hz), the coning residual is of order |omega_ie| theta^4 per interval and the
// velocity terms are exact to third order in theta; (b) vibration above the Nyquist frequency
// makes the Coriolis and transport terms, which use sampled velocities, wrong by up to
// 2 |omega_ie| |v_vib| dt per interval (zero mean); (c) the free-inertial vertical channel
// amplifies every error by about cosh(t / 570 s), and the horizontal channels turn attitude
// error into Schuler oscillations (84 min). dt == 0 leaves the state unchanged apart from t_s.
//
// Cost: no allocation, a handful of sin/cos/sqrt per update (the terms of a latitude computed
// once: ins/latitude_terms.hpp) (> 1M updates/s on one core; see
// bench/scenario_bench.cpp).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "stochnav/ins/latitude_terms.hpp"
#include "stochnav/ins/nav_state.hpp"

namespace stochnav {

/// IMU increments over [t_s - dt_s, t_s], in the body frame.
struct ImuIncrement {
  double t_s = 0.0;                                         ///< end of the interval (s)
  double dt_s = 0.0;                                        ///< interval length (s), >= 0
  Eigen::Vector3d delta_theta_b = Eigen::Vector3d::Zero();  ///< integral of omega_ib_b (rad)
  Eigen::Vector3d delta_v_b = Eigen::Vector3d::Zero();      ///< integral of f_b (m/s)
};

class StrapdownIntegrator final {
 public:
  explicit StrapdownIntegrator(const NavState& initial);

  /// Advances the state over the increment's interval; state().t_s becomes increment.t_s.
  void update(const ImuIncrement& increment);

  const NavState& state() const { return state_; }

  /// The last update's specific-force velocity increment in the navigation frame (m/s): the
  /// rotation- and sculling-compensated increment, without gravity and Coriolis.
  const Eigen::Vector3d& specific_force_increment_n() const { return specific_force_increment_n_; }

  /// The Earth-model terms of state().latitude_rad (ins/latitude_terms.hpp), bit for bit
  /// LatitudeTerms(state().latitude_rad), kept for the next update, which starts there.
  const LatitudeTerms& latitude_terms() const { return state_latitude_.at(state_.latitude_rad); }

  /// Replaces the state (a new start) and forgets the previous increments and the extrapolation
  /// history.
  void set_state(const NavState& state);

  /// Replaces the state by a corrected estimate of it at the same time (a filter's feedback) and
  /// keeps the previous increments, whose sculling and coning terms the next update still needs:
  /// forgetting them at every aid epoch dropped, once per epoch of aiding, a velocity term of
  /// (theta^2 / 12) |f_perp| dt under drill-string rotation (theta = the spin per IMU epoch,
  /// f_perp the specific force across the spin axis): 2.3e-4 m/s a second at 160 rpm and 100 Hz,
  /// an acceleration error of 23 micro-g. The k-2 state of the mid-interval extrapolation moves
  /// with the correction.
  void correct_state(const NavState& state);

 private:
  NavState state_;
  NavState previous_state_;  // state at k-2 for the mid-interval extrapolation
  Eigen::Vector3d specific_force_increment_n_ = Eigen::Vector3d::Zero();  // m/s
  Eigen::Vector3d previous_delta_theta_b_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d previous_delta_v_b_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d second_previous_delta_theta_b_ = Eigen::Vector3d::Zero();
  bool has_previous_ = false;
  bool has_second_previous_ = false;
  // The terms of the state's latitude, and of the mid-interval latitude of position and attitude.
  mutable LatitudeTermsMemo state_latitude_;
  LatitudeTermsMemo mid_latitude_;
};

/// Unit quaternion of a rotation vector (rad), accurate for small angles.
Eigen::Quaterniond quaternion_from_rotation_vector(const Eigen::Vector3d& rotation_vector);

/// The mean of C_nb over an IMU epoch whose body frame turns at a constant rate by
/// delta_theta_b (rad) from c_nb_start: c_nb_start (I + a1 [a x] + a2 [a x]^2), a = delta_theta_b,
/// a1 = (1 - cos|a|) / |a|^2, a2 = (|a| - sin|a|) / |a|^3 (the navigation frame's own turn, under
/// 1e-6 rad an epoch, left out). The chord (C_nb(start) + C_nb(end)) / 2 is short by |a|^2 / 8
/// across the rotation axis: 0.35 % at 160 rpm and 100 Hz.
Eigen::Matrix3d epoch_mean_attitude(const Eigen::Matrix3d& c_nb_start,
                                    const Eigen::Vector3d& delta_theta_b);

}  // namespace stochnav
