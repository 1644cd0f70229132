#pragma once
// Linearised dynamics of the 15 core INS error states (plugin/state_layout.hpp, core_state):
//   dr    ENU position error (m): dr_E = (R_N + h) cos(lat) dlon, dr_N = (R_M + h) dlat, dr_U = dh
//   dv_n  ENU velocity error (m/s)
//   phi   attitude error in n (rad), defined by C_nb_est = (I - [phi x]) C_nb_true
//   db_a  accelerometer bias error in b (m/s^2), db_g gyro bias error in b (rad/s)
// every error being estimate - truth. With the IMU compensated by the estimated biases, the
// sensor errors are d omega_ib_b = -db_g + w_g and d f_b = -db_a + w_a, and (Savage; Yan,
// "Principles of inertial navigation", ENU phi-angle form):
//   d phi/dt = -omega_in_n x phi + d omega_in_n + C_nb db_g - C_nb w_g
//   d dv/dt  = f_n x phi + v_n x (2 d omega_ie_n + d omega_en_n)
//              - (2 omega_ie_n + omega_en_n) x dv - C_nb db_a + d g_n + C_nb w_a
//   d dr/dt  = dv + (position terms of order v / R)
//   d db/dt  = bias random walk.
// d g_n keeps the vertical gravity gradient (+2 g / R dh on the up axis: the vertical channel's
// instability); horizontal gravity errors are neglected.
//
// The dynamics are split by how fast their inputs change. C_nb and f_n change at the IMU rate
// (vibration, toolface rotation): the filter accumulates their integrals over a covariance
// interval exactly, from the increments. Everything else changes with position and velocity,
// slowly, and is evaluated once per interval.

#include <Eigen/Core>

#include "stochnav/ins/latitude_terms.hpp"
#include "stochnav/ins/nav_state.hpp"

namespace stochnav {

using CoreMatrix = Eigen::Matrix<double, 15, 15>;

/// Integrals over one covariance interval [t, t + T] of the fast-changing inputs.
struct FastInputIntegrals {
  double interval_s = 0.0;                            ///< T (s)
  Eigen::Matrix3d c_nb_dt = Eigen::Matrix3d::Zero();  ///< integral of C_nb dt (s)
  Eigen::Vector3d f_n_dt = Eigen::Vector3d::Zero();   ///< integral of f_n dt (m/s)
  /// Integral of C_nb diag(omega_ib_b) dt (rad): the attitude error per unit gyro scale-factor
  /// error, d phi/dt = ... + C_nb diag(omega_ib_b) ds_g (the compensated rate errs by
  /// -ds_g omega per axis, like -db_g).
  Eigen::Matrix3d gyro_scale_dt = Eigen::Matrix3d::Zero();
  /// Integral of C_nb diag(f_ib_b) dt (m/s): d dv/dt = ... - C_nb diag(f_ib_b) ds_a.
  Eigen::Matrix3d accel_scale_dt = Eigen::Matrix3d::Zero();
  // The double integrals int_0^T int_0^t (.) ds dt of the velocity rows' inputs: the position
  // error's response to an attitude or accelerometer error held over the interval.
  Eigen::Vector3d f_n_dt2 = Eigen::Vector3d::Zero();          ///< of f_n (m)
  Eigen::Matrix3d c_nb_dt2 = Eigen::Matrix3d::Zero();         ///< of C_nb (s^2)
  Eigen::Matrix3d accel_scale_dt2 = Eigen::Matrix3d::Zero();  ///< of C_nb diag(f_ib_b) (m)

  /// Adds one epoch's increments (the integrals over the epoch of dt_s s) to both the single
  /// and the double integrals, the integrands taken linear within the epoch, and dt_s to T.
  void add_velocity_inputs(double dt_s, const Eigen::Matrix3d& c_nb_dt_epoch,
                           const Eigen::Vector3d& f_n_dt_epoch);
  /// The same for the accelerometer scale-factor input, when those states are estimated.
  void add_accel_scale_input(double dt_s, const Eigen::Matrix3d& accel_scale_dt_epoch);
};

/// The position rows' correction to the second-order transition I + F T + (F T)^2 / 2 when the
/// inputs change within the interval. (F T)^2 / 2 gives position's response to the velocity
/// rows' inputs as T / 2 times their single integrals, which holds for constant inputs only;
/// the exact response is their double integrals. A vibration whose period divides the interval
/// shows why it matters: its velocity change over each interval is nil, so the single integral
/// is blind to it, while the velocity error it causes, phi x the oscillation's velocity, is
/// sampled at the same phase at every interval's end and, taken as constant over the next
/// interval, integrates into a position error that grows without bound. The double integral
/// gives the oscillation's mean over the interval instead, and the position error stays bounded.
/// Each block is added to Phi's position rows (dimensionless; attitude in rad, the
/// accelerometer bias in m/s^2, its scale factor dimensionless).
struct PositionShapeCorrection {
  Eigen::Matrix3d attitude;     ///< to Phi(dr, phi) (m/rad)
  Eigen::Matrix3d accel_bias;   ///< to Phi(dr, db_a) (s^2)
  Eigen::Matrix3d accel_scale;  ///< to Phi(dr, ds_a) (m)
};
PositionShapeCorrection position_shape_correction(const FastInputIntegrals& fast);

/// The integral of the core error-dynamics matrix F over the interval, F_bar T (15 x 15,
/// dimensionless), with the slow terms evaluated at `state` (take the state at the interval's
/// end: position and velocity hardly change within it).
CoreMatrix integrated_core_dynamics(const NavState& state, const FastInputIntegrals& fast);

/// The same with the Earth-model terms of the state's latitude already known: `latitude` must
/// be LatitudeTerms(state.latitude_rad) (ins/latitude_terms.hpp; the strapdown keeps them).
CoreMatrix integrated_core_dynamics(const NavState& state, const LatitudeTerms& latitude,
                                    const FastInputIntegrals& fast);

}  // namespace stochnav
