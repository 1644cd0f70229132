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
// to u, and B_sg alike. For a tool spinning at 60 rpm about a horizontal axis, the cross-axis
// accelerometer scale factors rectify gravity into a steady specific-force error across the
// hole, (ds_x + ds_y) / 2 g sin(inclination), whose mean over a 1-s interval is half its effect
// at the epoch: about 5e-4 m/s for 100 ppm, half the ROP's lateral sigma. Without this column
// the 36-h drilling run took it for position information (east and TVD 6-9 m off against
// sigmas of 0.7-1.2 m). The gyro terms are the attitude's drift inside the interval seen
// through the specific force (a 100-ppm gyro scale factor on the spin axis: about
// g T^2 / 6 * 2 pi 1e-4 = 1e-3 m/s). Time-weighted integrals are taken at each
// IMU epoch's midpoint, the epoch's C_nb as its mean over the epoch.
//
// The white noise inside the interval makes the rest of the mean's error, with covariance
//   (1/T^2) [ int (u - t_prev)^2 dQ_v(u) + int [W_f(u) x] dQ_phi(u) [W_f(u) x]^T ],
// W_f(u) the integral up to u: the accelerometer noise integrated into the velocity, and the
// gyro noise turning the attitude inside the interval (g T / 2 times it: small for a FOG's
// white noise, not for a model that reads the drill string's rotation as noise). Its
// correlation with the process noise of the same interval is left out (stochastic cloning of
// the interval's start position would be exact; tried, it made the 36-h inclination less
// consistent, 76 % inside 3 sigma against 93 %, for reasons not yet found).
//
// Under vibration the velocities given are the INS's less the counted oscillation
// (VelocityOscillation): its high-pass, which holds the vibration and the fast part of the
// velocity noise alike. The share of the noise's high-pass taken out is not in the error state's
// model of the mean, so the mean's noise covariance adds it as independent noise (its
// correlation with the rest left out: conservative): share^2 times the accelerometer noise's
// rate times VelocityOscillation::high_passed_noise_variance(T). Without it the filter's
// vertical velocity was 94 % inside 3 sigma in a 12-Hz episode (docs/drilling-envelope.md).
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
  /// One IMU epoch as the interval needs it.
  struct Epoch {
    Eigen::Vector3d v_start_n;  ///< INS velocity at the epoch's start, ENU (m/s)
    Eigen::Vector3d v_end_n;    ///< and at its end
    Eigen::Matrix3d c_nb_mean;  ///< mean attitude over the epoch (ins/strapdown.hpp)
    Eigen::Vector3d delta_v_n;  ///< specific-force velocity increment, ENU (m/s)
    /// The increment of the specific force the scale factors multiply, free of this epoch's
    /// noise (MwdNavigator: a smoothed specific force): the measured increment would correlate
    /// the map with the noise of the measurement it weighs.
    Eigen::Vector3d scale_factor_delta_v_b;
    Eigen::Vector3d delta_theta_b;   ///< compensated angle increment, body (rad)
    Eigen::Matrix3d velocity_noise;  ///< accelerometer white noise of the epoch, ENU (m^2/s^2)
    Eigen::Matrix3d attitude_noise;  ///< gyro white noise of the epoch, ENU (rad^2)
    double dt_s = 0.0;
    /// The share of the INS velocity's high-pass taken out of v_start_n and v_end_n as the
    /// tool's vibration (VelocityOscillation::share): that share of the velocity noise's
    /// high-passed part is then missing from the mean, which the error state still holds.
    double oscillation_share = 0.0;
  };

  void add_epoch(const Epoch& epoch);

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
  Eigen::Vector3d v_n_dt_ = Eigen::Vector3d::Zero();                   // int v_n du (m)
  Eigen::Vector3d weighted_f_n_dt_ = Eigen::Vector3d::Zero();          // W_f (m)
  Eigen::Matrix3d weighted_c_nb_dt_ = Eigen::Matrix3d::Zero();         // W_c (s^2)
  Eigen::Matrix3d weighted_accel_scale_ = Eigen::Matrix3d::Zero();     // W_sa (m)
  Eigen::Matrix3d c_nb_dt_ = Eigen::Matrix3d::Zero();                  // A_c (s)
  Eigen::Matrix3d gyro_scale_dt_ = Eigen::Matrix3d::Zero();            // A_sg (rad)
  Eigen::Matrix3d weighted_f_x_c_nb_ = Eigen::Matrix3d::Zero();        // B_c (m s)
  Eigen::Matrix3d weighted_f_x_gyro_scale_ = Eigen::Matrix3d::Zero();  // B_sg (m)
  Eigen::Matrix3d weighted_noise_ = Eigen::Matrix3d::Zero();        // int (u - t_prev)^2 dQ_v (m^2)
  Eigen::Matrix3d attitude_noise_image_ = Eigen::Matrix3d::Zero();  // int [W_f x] dQ_phi [.]^T
  Eigen::Matrix3d removed_noise_ = Eigen::Matrix3d::Zero();  // int share^2 dQ_v (m^2/s^2)
};

}  // namespace stochnav
