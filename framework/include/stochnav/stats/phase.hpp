#pragma once
// From a rate record (gyro rate, fractional frequency) to the phase record (angle, clock phase)
// that every Allan-family estimator works on.

#include <span>
#include <vector>

namespace stochnav {

/// Integrates N rate samples y (any unit U) taken every tau0_s seconds into N + 1 phase points
/// (unit U*s):
///   x[0] = 0,  x[i + 1] = x[i] + (y[i] - mean(y)) * tau0_s.
/// The mean rate is removed first. That subtracts a straight line from the phase, which every
/// deviation of deviation.hpp annihilates (they are built from second or third differences of
/// x), so no deviation changes; but it keeps |x| small, so the differences do not lose digits to
/// cancellation against a large ramp. The mean and the running sum use compensated (Neumaier)
/// summation: the error of x[i] stays a few ulps whatever N is.
/// An empty `rate` gives {0}. tau0_s must be > 0 (not checked).
std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s);

}  // namespace stochnav
