#include "stochnav/model/sensor_shaping.hpp"

namespace stochnav {

SensorShaping::SensorShaping(const std::array<ShapingFilter, 3>& axes) : axes_(axes) {
  for (std::size_t i = 0; i < 3; ++i) {
    offset_[i] = size_;
    size_ += axes_[i].size();
  }
  cached_phi_ = Eigen::MatrixXd::Zero(size_, size_);
  cached_q_d_ = Eigen::MatrixXd::Zero(size_, size_);
}

void SensorShaping::transition(double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                               Eigen::Ref<Eigen::MatrixXd> q_d) const {
  if (dt_s != cached_dt_) {
    for (std::size_t i = 0; i < 3; ++i) {
      const int n = axes_[i].size();
      axes_[i].transition(dt_s, cached_phi_.block(offset_[i], offset_[i], n, n),
                          cached_q_d_.block(offset_[i], offset_[i], n, n));
    }
    cached_dt_ = dt_s;
  }
  phi = cached_phi_;
  q_d = cached_q_d_;
}

void SensorShaping::initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const {
  p0.setZero();
  for (std::size_t i = 0; i < 3; ++i) {
    const int n = axes_[i].size();
    axes_[i].initial_covariance(p0.block(offset_[i], offset_[i], n, n));
  }
}

void SensorShaping::sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const {
  map.setZero();
  for (std::size_t i = 0; i < 3; ++i) {
    axes_[i].sensor_map(map.block(static_cast<Eigen::Index>(i), offset_[i], 1, axes_[i].size()));
  }
}

void SensorShaping::white_noise_covariance(double dt_s, Eigen::Ref<Eigen::MatrixXd> q_white) const {
  q_white.setZero();
  for (std::size_t i = 0; i < 3; ++i) {
    const auto d = static_cast<Eigen::Index>(i);
    q_white(d, d) = axes_[i].white_psd * dt_s;
  }
}

void SensorShaping::bias_walk_covariance(double dt_s, Eigen::Ref<Eigen::MatrixXd> q_bias) const {
  q_bias.setZero();
  for (std::size_t i = 0; i < 3; ++i) {
    const auto d = static_cast<Eigen::Index>(i);
    q_bias(d, d) = axes_[i].bias_walk_psd * dt_s;
  }
}

}  // namespace stochnav
