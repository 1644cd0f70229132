#include "stochnav/filter/ins_interval_accumulator.hpp"

#include "stochnav/filter/velocity_oscillation.hpp"
#include "stochnav/ins/cross_product_matrix.hpp"
#include "stochnav/plugin/state_layout.hpp"

namespace stochnav {
namespace {

namespace cs = plugin::core_state;

}  // namespace

void InsIntervalAccumulator::add_epoch(const Epoch& epoch) {
  const double dt_s = epoch.dt_s;
  const Eigen::Matrix3d& c_nb_mean = epoch.c_nb_mean;
  const double weight = duration_s_ + 0.5 * dt_s;  // u - t_prev at the epoch's midpoint
  const Eigen::Vector3d& f_n_dt = epoch.delta_v_n;
  const Eigen::Matrix3d c_dt = c_nb_mean * dt_s;
  const Eigen::Matrix3d gyro_scale_step = c_nb_mean * epoch.delta_theta_b.asDiagonal();
  const Eigen::Matrix3d f_x = skew(f_n_dt);
  // The running integrals A at the epoch's midpoint.
  weighted_f_x_c_nb_.noalias() += weight * f_x * (c_nb_dt_ + 0.5 * c_dt);
  weighted_f_x_gyro_scale_.noalias() += weight * f_x * (gyro_scale_dt_ + 0.5 * gyro_scale_step);
  c_nb_dt_ += c_dt;
  gyro_scale_dt_ += gyro_scale_step;
  weighted_accel_scale_.noalias() += weight * c_nb_mean * epoch.scale_factor_delta_v_b.asDiagonal();
  duration_s_ += dt_s;
  v_n_dt_ += 0.5 * dt_s * (epoch.v_start_n + epoch.v_end_n);
  const Eigen::Matrix3d f_image = skew(weighted_f_n_dt_ + (0.5 * weight) * f_n_dt);
  attitude_noise_image_.noalias() += f_image * epoch.attitude_noise * f_image.transpose();
  weighted_f_n_dt_ += weight * f_n_dt;
  weighted_c_nb_dt_ += weight * c_dt;
  weighted_noise_ += (weight * weight) * epoch.velocity_noise;
  // Zero but in a vibration episode: no matrix product on the epochs of every other interval.
  if (epoch.oscillation_share > 0.0) {
    removed_noise_ += (epoch.oscillation_share * epoch.oscillation_share) * epoch.velocity_noise;
  }
}

Eigen::Matrix3d InsIntervalAccumulator::gyro_map(const Eigen::Matrix3d& a,
                                                 const Eigen::Matrix3d& b) const {
  return (skew(weighted_f_n_dt_) * a - b) / duration_s_;
}

void InsIntervalAccumulator::core_map(Eigen::Ref<Eigen::Matrix<double, 3, 15>> map) const {
  const double t = duration_s_;
  map.setZero();
  map.block<3, 3>(0, cs::kVelocity).setIdentity();
  map.block<3, 3>(0, cs::kAttitude) = -skew(weighted_f_n_dt_ / t);
  map.block<3, 3>(0, cs::kAccelBias) = weighted_c_nb_dt_ / t;
  map.block<3, 3>(0, cs::kGyroBias) = gyro_map(c_nb_dt_, weighted_f_x_c_nb_);
}

plugin::InsInterval InsIntervalAccumulator::interval() const {
  plugin::InsInterval interval;
  if (!(duration_s_ > 0.0)) return interval;
  const double t = duration_s_;
  interval.duration_s = t;
  interval.mean_v_n = v_n_dt_ / t;
  core_map(interval.mean_velocity_error_map);
  interval.mean_velocity_noise_covariance =
      (weighted_noise_ + attitude_noise_image_) / (t * t) +
      (removed_noise_ / t) * VelocityOscillation::high_passed_noise_variance(t);
  return interval;
}

void InsIntervalAccumulator::mean_error_map(const IntervalMapLayout& layout,
                                            Eigen::Ref<Eigen::MatrixXd> map) const {
  map.setZero();
  if (!(duration_s_ > 0.0)) return;
  core_map(map.leftCols<15>());
  const double t = duration_s_;
  if (layout.accel_scale_offset >= 0) {
    map.middleCols<3>(layout.accel_scale_offset) = weighted_accel_scale_ / t;
  }
  if (layout.gyro_scale_offset >= 0) {
    map.middleCols<3>(layout.gyro_scale_offset) =
        gyro_map(gyro_scale_dt_, weighted_f_x_gyro_scale_);
  }
  if (layout.accel_augmented_offset >= 0) {
    map.middleCols(layout.accel_augmented_offset, layout.accel_sensor_map->cols()).noalias() =
        map.middleCols<3>(cs::kAccelBias) * *layout.accel_sensor_map;
  }
  if (layout.gyro_augmented_offset >= 0) {
    map.middleCols(layout.gyro_augmented_offset, layout.gyro_sensor_map->cols()).noalias() =
        map.middleCols<3>(cs::kGyroBias) * *layout.gyro_sensor_map;
  }
}

}  // namespace stochnav
