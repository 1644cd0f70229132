#pragma once
// A white-noise level that varies in time: the PSD N(t)^2 of each of three axes, known at
// analysis times t_0 < t_1 < ... < t_{n-1}, and its exact integral over any [t, t + dt].
//
// Between analysis times N^2 is either
//   kLinear  linear from N_j^2 to N_{j+1}^2 (offline DAVAR: centred windows), or
//   kHold    held at N_j^2 until t_{j+1} (causal DAVAR: the value at t comes from the last window
//            that ended at or before t, so it uses only data before t);
// before t_0 it is N_0^2 and after t_{n-1} it is N_{n-1}^2.
// The integral is the sum of exact per-segment integrals, so consecutive steps compose to
// rounding: I(t, dt1) + I(t + dt1, dt2) = I(t, dt1 + dt2).
//
// Calls are cheap and do not allocate: a cursor remembers the segment of the last call (the
// filter asks in increasing t), with a binary search when t jumps. Not thread-safe (the cursor
// is mutable), like every noise model instance (noise_model_plugin.hpp).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

namespace stochnav::davar_noise {

enum class Interpolation { kLinear, kHold };

class NoiseLevelSeries {
 public:
  /// `time_s` strictly ascending, non-empty; `psd[axis]` the PSD N^2 (natural units, e.g.
  /// rad^2/s) of the same length, >= 0. The caller validates.
  NoiseLevelSeries(std::vector<double> time_s, std::array<std::vector<double>, 3> psd,
                   Interpolation interpolation)
      : time_s_(std::move(time_s)), psd_(std::move(psd)), interpolation_(interpolation) {}

  /// int_{t}^{t + dt} N(s)^2 ds per axis (natural units, e.g. rad^2), dt >= 0.
  Eigen::Vector3d integral(double t_s, double dt_s) const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    if (!(dt_s > 0.0)) return sum;
    const double end = t_s + dt_s;
    double from = t_s;
    std::ptrdiff_t segment = locate(t_s);
    const auto last = static_cast<std::ptrdiff_t>(time_s_.size()) - 1;
    while (true) {
      const double segment_end = segment < last ? time_s_[static_cast<std::size_t>(segment + 1)]
                                                : std::numeric_limits<double>::infinity();
      const double to = std::min(end, segment_end);
      if (to > from) add_segment(segment, from, to, sum);
      if (to >= end) break;
      from = to;
      ++segment;
    }
    cursor_ = segment;
    return sum;
  }

  /// N^2(t) per axis (natural units).
  Eigen::Vector3d level(double t_s) const {
    const std::ptrdiff_t segment = locate(t_s);
    Eigen::Vector3d value;
    for (int axis = 0; axis < 3; ++axis) value(axis) = level_in(segment, axis, t_s);
    return value;
  }

  const std::vector<double>& time_s() const { return time_s_; }
  const std::array<std::vector<double>, 3>& psd() const { return psd_; }
  Interpolation interpolation() const { return interpolation_; }

 private:
  /// Index j of the segment [t_j, t_{j+1}) holding t: -1 before t_0, n - 1 from t_{n-1} on.
  std::ptrdiff_t locate(double t_s) const {
    const auto n = static_cast<std::ptrdiff_t>(time_s_.size());
    const auto contains = [&](std::ptrdiff_t j) {
      const bool after_start = j < 0 || time_s_[static_cast<std::size_t>(j)] <= t_s;
      const bool before_end = j + 1 >= n || t_s < time_s_[static_cast<std::size_t>(j + 1)];
      return after_start && before_end;
    };
    if (contains(cursor_)) return cursor_;
    if (cursor_ + 1 < n && contains(cursor_ + 1)) return cursor_ + 1;
    const auto after = std::upper_bound(time_s_.begin(), time_s_.end(), t_s);
    return static_cast<std::ptrdiff_t>(after - time_s_.begin()) - 1;
  }

  double level_in(std::ptrdiff_t segment, int axis, double t_s) const {
    const auto& psd = psd_[static_cast<std::size_t>(axis)];
    if (segment < 0) return psd.front();
    const auto j = static_cast<std::size_t>(segment);
    if (j + 1 >= psd.size() || interpolation_ == Interpolation::kHold) return psd[j];
    const double fraction = (t_s - time_s_[j]) / (time_s_[j + 1] - time_s_[j]);
    return psd[j] + (psd[j + 1] - psd[j]) * fraction;
  }

  /// Adds int_from^to N^2 of one segment: exact for a constant or linear level (trapezoid).
  void add_segment(std::ptrdiff_t segment, double from, double to, Eigen::Vector3d& sum) const {
    const double length = to - from;
    for (int axis = 0; axis < 3; ++axis) {
      sum(axis) += 0.5 * length * (level_in(segment, axis, from) + level_in(segment, axis, to));
    }
  }

  std::vector<double> time_s_;
  std::array<std::vector<double>, 3> psd_;
  Interpolation interpolation_;
  mutable std::ptrdiff_t cursor_ = -1;
};

}  // namespace stochnav::davar_noise
