#pragma once
// What an aid's plugin::InsInterval needs, accumulated over the IMU epochs since the aid's
// previous measurement epoch t_prev, and the first-order map from the whole error state at the
// epoch t to the error of the interval's mean ENU velocity.
//
// With the error dynamics of error_dynamics.hpp (d dv/dt = [f_n x] phi - C_nb (db_a + M_a x_a +
// diag(f_b) ds_a) + ..., d phi/dt = C_nb (db_g + M_g x_g + diag(omega_b) ds_g) + ...) and T =
// t - t_prev, the mean's error is, to first order in the interval,
//   dv_mean = dv - (1/T) int (u - t_prev) d(dv)/du du
//           = dv - [W_f x] phi / T + W_c (db_a + M_a x_a) / T + W_sa ds_a / T
//             + ([W_f x] A_c - B_c) (db_g + M_g x_g) / T + ([W_f x] A_sg - B_sg) ds_g / T
// with W_f = int (u - t_prev) f_n du, W_c = int (u - t_prev) C_nb du,
// W_sa = int (u - t_prev) C_nb diag(f_b) du, A_c = int C_nb du, A_sg = int C_nb diag(omega_b) du
// (over the interval), B_c = int (u - t_prev) [f_n(u) x] A_c(u) du with A_c(u) the integral up
// to u, and B_sg alike. The gyro terms are the attitude's drift inside the interval seen through
// the specific force: for a tool spinning at 60 rpm about a horizontal axis a gyro scale-factor
// error of 100 ppm moves the mean of a 1-s interval by about g T^2 / 6 * 2 pi 1e-4 = 1e-3 m/s,
// as much as a lateral velocity constraint measures. Time-weighted integrals are taken at each
// IMU epoch's midpoint.
//
// Units: seconds, metres, radians; ENU navigation frame n, body frame b.

#include <Eigen/Core>

#include "stochnav/plugin/aid_plugin.hpp"

namespace stochnav {

/// Where the sensor-error states beyond the 15 core states sit in the error state.
struct IntervalMapLayout {
  int width = 15;                  ///< columns of the map: the highest state used + 1
  int gyro_scale_offset = -1;      ///< -1: not estimated
  int accel_scale_offset = -1;     ///< -1: not estimated
  int gyro_augmented_offset = -1;  ///< -1: none
  int accel_augmented_offset = -1;
  const Eigen::MatrixXd* gyro_sensor_map = nullptr;   ///< M_g, 3 x gyro augmented size
  const Eigen::MatrixXd* accel_sensor_map = nullptr;  ///< M_a, 3 x accel augmented size
};

class InsIntervalAccumulator {
 public:
  /// Adds one IMU epoch of dt_s: the INS velocity at its start and end, the attitude at its
  /// midpoint, the compensated increments (body), and the accelerometer white noise integrated
  /// into the velocity over the epoch (ENU, m^2/s^2).
  void add_epoch(const Eigen::Vector3d& v_start_n, const Eigen::Vector3d& v_end_n,
                 const Eigen::Matrix3d& c_nb_mid, const Eigen::Vector3d& delta_v_b,
                 const Eigen::Vector3d& delta_theta_b, const Eigen::Matrix3d& velocity_noise,
                 double dt_s);

  double duration_s() const { return duration_s_; }

  /// The interval for an aid (its map over the 15 core states).
  plugin::InsInterval interval() const;

  /// The map of dv_mean over the error state's first layout.width columns (3 x width).
  void mean_error_map(const IntervalMapLayout& layout, Eigen::Ref<Eigen::MatrixXd> map) const;

  /// A correction dx fed back to the INS changes the velocity history of the open interval by
  /// its image through the mean's map: pass mean_error_map * dx (ENU, m/s).
  void shift_mean_velocity(const Eigen::Vector3d& mean_velocity_correction) {
    v_n_dt_ -= duration_s_ * mean_velocity_correction;
  }

 private:
  void core_map(Eigen::Ref<Eigen::Matrix<double, 3, 15>> map) const;
  Eigen::Matrix3d gyro_map(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) const;

  double duration_s_ = 0.0;
  Eigen::Vector3d v_n_dt_ = Eigen::Vector3d::Zero();            // int v_n du (m)
  Eigen::Vector3d weighted_f_n_dt_ = Eigen::Vector3d::Zero();   // W_f (m)
  Eigen::Matrix3d weighted_c_nb_dt_ = Eigen::Matrix3d::Zero();  // W_c (s^2)
  Eigen::Matrix3d weighted_accel_scale_ = Eigen::Matrix3d::Zero();  // W_sa (m)
  Eigen::Matrix3d c_nb_dt_ = Eigen::Matrix3d::Zero();              // A_c (s)
  Eigen::Matrix3d gyro_scale_dt_ = Eigen::Matrix3d::Zero();        // A_sg (rad)
  Eigen::Matrix3d weighted_f_x_c_nb_ = Eigen::Matrix3d::Zero();    // B_c (m s)
  Eigen::Matrix3d weighted_f_x_gyro_scale_ = Eigen::Matrix3d::Zero();  // B_sg (m)
  Eigen::Matrix3d weighted_noise_ = Eigen::Matrix3d::Zero();  // int (u - t_prev)^2 dQ_v (m^2)
};

}  // namespace stochnav
