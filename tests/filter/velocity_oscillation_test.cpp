// The tool's vibration separated from the INS velocity (filter/velocity_oscillation.hpp): an
// axial oscillation is counted to within a few percent once its RMS is past twice the
// threshold, the velocity's noise and a slow speed change are not counted at all, and the
// changes returned add up to the counted oscillation.
#include "stochnav/filter/velocity_oscillation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace stochnav {
namespace {

constexpr double kStep_s = 0.01;  // 100 Hz
const Eigen::Vector3d kAxis = Eigen::Vector3d(1.0, 0.2, -0.1).normalized();

// 0.55 m/s at 8 Hz along kAxis (2.8 g axial vibration) on a drilling speed of 33 m/h.
Eigen::Vector3d vibrating_velocity(double t_s) {
  return kAxis * (33.0 / 3600.0 + 0.55 * std::cos(2.0 * std::numbers::pi * 8.0 * t_s));
}

TEST(VelocityOscillation, CountsAnAxialVibrationAndSumsItsChanges) {
  VelocityOscillation oscillation(0.02, vibrating_velocity(0.0));
  Eigen::Vector3d summed = Eigen::Vector3d::Zero();
  double worst = 0.0;
  for (int k = 1; k <= 1000; ++k) {
    const double t = k * kStep_s;
    summed += oscillation.update(vibrating_velocity(t), kStep_s);
    const Eigen::Vector3d truth = vibrating_velocity(t) - kAxis * (33.0 / 3600.0);
    if (t > 5.0) worst = std::max(worst, (oscillation.velocity_n() - truth).norm());
  }
  EXPECT_LT(worst, 0.05 * 0.55);  // the first-order low-pass's residue at 8 Hz
  EXPECT_LT((summed - oscillation.velocity_n()).norm(), 1e-12);
}

TEST(VelocityOscillation, LeavesNoiseAndSlowChangesOut) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  // An INS velocity walking with 0.06 m/s/sqrt(h) accelerometer noise while the speed ramps from
  // rest to 60 m/h over 10 s (a stand's start): nothing is counted.
  const double step_sigma = 0.06 / 60.0 * std::sqrt(kStep_s);
  VelocityOscillation oscillation(0.02, Eigen::Vector3d::Zero());
  Eigen::Vector3d noise = Eigen::Vector3d::Zero();
  for (int k = 1; k <= 3000; ++k) {
    const double t = k * kStep_s;
    noise += step_sigma * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    const Eigen::Vector3d v = kAxis * (60.0 / 3600.0) * std::min(1.0, t / 10.0) + noise;
    EXPECT_EQ(oscillation.update(v, kStep_s), Eigen::Vector3d::Zero()) << t;
  }
  EXPECT_EQ(oscillation.velocity_n(), Eigen::Vector3d::Zero());
}

// A correction of the INS velocity (the filter's feedback) is not an oscillation: shifted with
// it, the counted oscillation is that of the uncorrected velocity (unshifted, the 5-mm/s step
// would pass the high-pass).
TEST(VelocityOscillation, AFedBackCorrectionIsNotCounted) {
  VelocityOscillation corrected(0.02, vibrating_velocity(0.0));
  VelocityOscillation reference(0.02, vibrating_velocity(0.0));
  const Eigen::Vector3d correction(0.005, -0.003, 0.001);
  double worst = 0.0;
  for (int k = 1; k <= 1000; ++k) {
    const double t = k * kStep_s;
    if (k == 600) corrected.shift(correction);
    const Eigen::Vector3d offset = k >= 600 ? correction : Eigen::Vector3d::Zero();
    corrected.update(vibrating_velocity(t) + offset, kStep_s);
    reference.update(vibrating_velocity(t), kStep_s);
    worst = std::max(worst, (corrected.velocity_n() - reference.velocity_n()).norm());
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(VelocityOscillation, AThresholdOfZeroCountsNothing) {
  VelocityOscillation oscillation(0.0, vibrating_velocity(0.0));
  for (int k = 1; k <= 500; ++k) {
    EXPECT_EQ(oscillation.update(vibrating_velocity(k * kStep_s), kStep_s), Eigen::Vector3d::Zero());
  }
}

}  // namespace
}  // namespace stochnav
