#include "stochnav/filter/velocity_oscillation.hpp"

#include <algorithm>
#include <cmath>

namespace stochnav {

VelocityOscillation::VelocityOscillation(double threshold_mps, const Eigen::Vector3d& initial_v_n)
    : threshold_squared_(threshold_mps * threshold_mps), low_pass_n_(initial_v_n) {}

Eigen::Vector3d VelocityOscillation::update(const Eigen::Vector3d& v_n, double dt_s) {
  if (!(threshold_squared_ > 0.0) || !(dt_s > 0.0)) return Eigen::Vector3d::Zero();
  low_pass_n_ += std::min(1.0, dt_s / kLowPassTime_s) * (v_n - low_pass_n_);
  const Eigen::Vector3d oscillation = v_n - low_pass_n_;
  mean_square_ += std::min(1.0, dt_s / kPowerTime_s) * (oscillation.squaredNorm() - mean_square_);
  // Counted in full from twice the threshold, not at all below it, in proportion between: a
  // vibration's ramp then enters smoothly, not as a step at the threshold. The root is taken
  // only in between: sqrt is monotonic and exact at 1 and 4, so outside (1, 4) the clamp's
  // result is known (NaN falls through to the root as before).
  const double relative_power = mean_square_ / threshold_squared_;
  const double share = relative_power <= 1.0   ? 0.0
                       : relative_power >= 4.0 ? 1.0
                                               : std::clamp(std::sqrt(relative_power) - 1.0, 0.0, 1.0);
  const Eigen::Vector3d counted = share * oscillation;
  const Eigen::Vector3d change = counted - counted_n_;
  counted_n_ = counted;
  return change;
}

}  // namespace stochnav
