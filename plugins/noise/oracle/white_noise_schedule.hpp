#pragma once
// A white rate noise whose PSD is piecewise constant in time, per axis: what a simulated
// scenario's angle random walk becomes under its phase scales (sim/noise_generator.hpp: sample k
// is scaled by the segment containing t_k, so on the sample grid the PSD steps exactly at the
// segment boundaries).
//
// covariance(t, dt) = diag over axes of integral_t^(t + dt) psd(u) du, exact (the pieces are
// integrated separately), so consecutive intervals compose to rounding. A cursor remembers the
// piece of the last call: consecutive calls cost O(1) without allocation.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

namespace stochnav::oracle {

class WhiteNoiseSchedule final {
 public:
  using AxisPsd = std::array<double, 3>;  ///< signal^2 s per axis (rad^2/s for gyros)

  /// psd[j] holds from start_s[j] to start_s[j + 1] (the last one from start_s.back() on; before
  /// start_s[0] the first one). start_s ascending, strictly; equal non-empty lengths.
  WhiteNoiseSchedule(std::vector<double> start_s, std::vector<AxisPsd> psd);

  /// 3 x 3 diagonal, signal^2 s^2 (rad^2 for gyros); dt = 0 gives 0. Not thread-safe (cursor).
  void covariance(double t_s, double dt_s, Eigen::Ref<Eigen::MatrixXd> q_white) const;

  /// Whether the PSD changes at all over time.
  bool varies() const { return start_s_.size() > 1; }
  const std::vector<double>& start_s() const { return start_s_; }
  const std::vector<AxisPsd>& psd() const { return psd_; }

 private:
  std::size_t piece_of(double t_s) const;
  double piece_end(std::size_t j) const;

  std::vector<double> start_s_;
  std::vector<AxisPsd> psd_;
  mutable std::size_t cursor_ = 0;
};

}  // namespace stochnav::oracle
