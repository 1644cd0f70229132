#pragma once
// The shaping filters of a sensor triad's three axes (model/shaping_filter.hpp) stacked into the
// augmented block of a noise-model plugin (plugin/noise_model_plugin.hpp): states of x, then y,
// then z, block-diagonal Phi, Qd and P0, and the 3 x n map M. Natural units (rad/s or m/s^2).

#include <Eigen/Core>
#include <array>
#include <limits>

#include "stochnav/model/shaping_filter.hpp"

namespace stochnav {

class SensorShaping final {
 public:
  explicit SensorShaping(const std::array<ShapingFilter, 3>& axes);

  const ShapingFilter& axis(int i) const { return axes_[static_cast<std::size_t>(i)]; }
  /// Total number of augmented states.
  int size() const { return size_; }

  /// Phi(dt), Qd(dt), size() x size() each, every entry written; recomputed only when dt
  /// changes (the filter steps with a constant interval). Not thread-safe: one caller at a time.
  void transition(double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                  Eigen::Ref<Eigen::MatrixXd> q_d) const;
  /// P0, size() x size().
  void initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const;
  /// M, 3 x size().
  void sensor_map(Eigen::Ref<Eigen::MatrixXd> map) const;
  /// diag(white_psd) dt and diag(bias_walk_psd) dt, 3 x 3 each.
  void white_noise_covariance(double dt_s, Eigen::Ref<Eigen::MatrixXd> q_white) const;
  void bias_walk_covariance(double dt_s, Eigen::Ref<Eigen::MatrixXd> q_bias) const;

 private:
  std::array<ShapingFilter, 3> axes_;
  std::array<int, 3> offset_{};
  int size_ = 0;
  mutable double cached_dt_ = std::numeric_limits<double>::quiet_NaN();
  mutable Eigen::MatrixXd cached_phi_, cached_q_d_;
};

}  // namespace stochnav
