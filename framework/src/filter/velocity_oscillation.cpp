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
  share_ = relative_power <= 1.0   ? 0.0
           : relative_power >= 4.0 ? 1.0
                                   : std::clamp(std::sqrt(relative_power) - 1.0, 0.0, 1.0);
  const Eigen::Vector3d counted = share_ * oscillation;
  const Eigen::Vector3d change = counted - counted_n_;
  counted_n_ = counted;
  return change;
}

double VelocityOscillation::high_passed_noise_variance(double duration_s) {
  if (!(duration_s > 0.0)) return 0.0;
  const double tau = kLowPassTime_s;
  // (2 tau / T) (1 - (tau / T) (1 - exp(-T / tau))) = 2 (x - 1 + exp(-x)) / x^2, x = T / tau;
  // its series 1 - x / 3 + x^2 / 12 below 1e-3 (the closed form cancels there).
  const double x = duration_s / tau;
  const double share_of_variance =
      x < 1e-3 ? 1.0 - x / 3.0 + x * x / 12.0 : 2.0 * (x + std::expm1(-x)) / (x * x);
  return 0.5 * tau * share_of_variance;
}

}  // namespace stochnav
