// The tool's vibration separated from the INS velocity (filter/velocity_oscillation.hpp): an
// axial oscillation is counted to within a few percent once its RMS is past twice the
// threshold, the velocity's noise and a slow speed change are not counted at all, and the
// changes returned add up to the counted oscillation. Under vibration the counted part also holds
// the high-pass of the velocity's noise, whose interval means follow the closed form the interval
// aids add to their noise (high_passed_noise_variance).
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

// Under a vibration (share 1) the counted oscillation of the noisy velocity less that of the
// clean one is the high-pass of the noise alone (the filter is linear): its means over 1-s and
// 0.1-s intervals have the variance of the closed form, per unit of the noise's rate. 12,000 s
// on three axes: 36,000 1-s means, a relative sigma of about 1 %.
TEST(VelocityOscillation, HighPassedNoiseOfAnIntervalMeanHasTheClosedFormsVariance) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double rate = std::pow(0.06 / 60.0, 2);  // 0.06 m/s/sqrt(h): (m/s)^2 per s
  const double step_sigma = std::sqrt(rate * kStep_s);
  VelocityOscillation noisy(0.02, vibrating_velocity(0.0));
  VelocityOscillation clean(0.02, vibrating_velocity(0.0));
  Eigen::Vector3d noise = Eigen::Vector3d::Zero();
  struct Means {
    int samples_per_mean;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double squares = 0.0;
    int count = 0;
  };
  Means means[] = {{100}, {10}};
  for (int k = 1; k <= 1'200'000; ++k) {
    const double t = k * kStep_s;
    noise += step_sigma * Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    noisy.update(vibrating_velocity(t) + noise, kStep_s);
    clean.update(vibrating_velocity(t), kStep_s);
    if (t <= 10.0) continue;  // the share ramps up
    ASSERT_EQ(noisy.share(), 1.0);
    const Eigen::Vector3d high_passed = noisy.velocity_n() - clean.velocity_n();
    for (Means& m : means) {
      m.sum += high_passed;
      if (k % m.samples_per_mean != 0) continue;
      const Eigen::Vector3d mean = m.sum / m.samples_per_mean;
      m.squares += mean.squaredNorm() / 3.0;
      ++m.count;
      m.sum.setZero();
    }
  }
  for (const Means& m : means) {
    const double variance = m.squares / m.count;
    const double predicted =
        rate * VelocityOscillation::high_passed_noise_variance(m.samples_per_mean * kStep_s);
    // The discrete low-pass (gain dt / tau per step) leaves 3.5 % less than the continuous
    // form (0.966 and 0.970 exactly): the noise the aids add is slightly overstated, never less.
    EXPECT_GT(variance / predicted, 0.92) << m.samples_per_mean;
    EXPECT_LT(variance / predicted, 1.02) << m.samples_per_mean;
  }
  // The limits: tau / 2 per unit rate for a short interval, 0.57 of it over 1 s.
  const double tau = VelocityOscillation::kLowPassTime_s;
  EXPECT_NEAR(VelocityOscillation::high_passed_noise_variance(1e-6), tau / 2.0, 1e-6);
  EXPECT_NEAR(VelocityOscillation::high_passed_noise_variance(1.0) / (tau / 2.0), 0.5677, 1e-3);
  EXPECT_EQ(VelocityOscillation::high_passed_noise_variance(0.0), 0.0);
}

TEST(VelocityOscillation, AThresholdOfZeroCountsNothing) {
  VelocityOscillation oscillation(0.0, vibrating_velocity(0.0));
  for (int k = 1; k <= 500; ++k) {
    EXPECT_EQ(oscillation.update(vibrating_velocity(k * kStep_s), kStep_s), Eigen::Vector3d::Zero());
  }
}

}  // namespace
}  // namespace stochnav
