#pragma once
// The oscillation of the tool's velocity that the IMU measures and the aids' reference
// trajectory does not state: axial vibration of the drill string (a tool oscillating along its
// axis by A / (2 pi f): 0.55 m/s at 2.8 g and 8 Hz, while the rig states a rate of penetration
// of millimetres per second).
//
// The INS velocity error inherits the attitude error times the true velocity change,
// d dv = -phi x (dv_true) (filter/error_dynamics.hpp). The navigator linearises that coupling
// about the reference trajectory the aids state (MwdNavigator, docs/drilling-envelope.md fix 1)
// so that the INS's own velocity error is not read as attitude information. Under vibration the
// true velocity is the reference plus the oscillation; without it in the coupling, the filter's
// velocity error at an epoch lacks phi x (the oscillation's velocity there), which at 1-Hz aid
// epochs on whole-hertz vibration is the same phase every time: a steady lateral velocity error
// of phi times 0.55 m/s that the ROP's lateral constraint then read as heading information (on
// a sliding east-west well at 74 N an episode of 9 min moved the bank over the heading by 15 to
// 35 deg and halved its sigma, the truth ending beyond the 91st percentile on 6 of 8 seeds).
//
// The oscillation is the INS velocity less its low-pass (a first-order filter of time constant
// kLowPassTime_s: above about 1 Hz it passes the vibration to within a few percent), counted
// while its RMS (smoothed over kPowerTime_s) exceeds the threshold: in proportion from one to
// two thresholds, in full above (a vibration's ramp enters smoothly). The threshold
// keeps the INS's own velocity noise out (about 0.5 mm/s RMS at this band for 0.06 m/s/sqrt(h)),
// which, in the coupling, correlates the attitude gain with the noise that drives the velocity
// error (fix 1's finding); a vibration's increments are hundreds of times that noise.
//
// The aids that measure a mean over an interval (the ROP: the rig's rate against the INS's mean
// velocity since the last epoch) take the INS velocity less the counted oscillation: over
// intervals holding part of a vibration cycle (8.37 Hz at 1-Hz epochs) the oscillation's mean is
// up to (A / w) / (pi f T), 10 mm/s at 2.8 g, 37 times the ROP's sigma, which no aid states.

#include <Eigen/Core>

namespace stochnav {

class VelocityOscillation {
 public:
  static constexpr double kLowPassTime_s = 0.5;
  static constexpr double kPowerTime_s = 1.0;

  /// threshold_mps: RMS (m/s) above which the oscillation counts (in full above twice it); 0:
  /// never (always zero).
  /// initial_v_n: the velocity at the start (m/s, ENU).
  VelocityOscillation(double threshold_mps, const Eigen::Vector3d& initial_v_n);

  /// Takes the INS velocity at the end of an epoch of dt_s (m/s, ENU) and returns the change of
  /// the counted oscillation over the epoch (m/s, ENU): what the coupling's velocity change adds.
  Eigen::Vector3d update(const Eigen::Vector3d& v_n, double dt_s);

  /// The filter corrected the INS velocity by `correction_n` (m/s, ENU): a correction is not an
  /// oscillation, so the low-pass moves with it (otherwise the step would pass the high-pass and
  /// the aids would see a corrected velocity return over kLowPassTime_s).
  void shift(const Eigen::Vector3d& correction_n) { low_pass_n_ += correction_n; }

  /// The counted oscillation at the last epoch (m/s, ENU): zero below the threshold.
  const Eigen::Vector3d& velocity_n() const { return counted_n_; }

  /// The share of the high-passed INS velocity counted at the last epoch, in [0, 1]. The
  /// high-pass takes the INS's own velocity noise with the vibration: an aid comparing the
  /// velocity less the counted oscillation misses that share of its high-passed noise
  /// (high_passed_noise_variance).
  double share() const { return share_; }

  /// The variance of the mean over an interval of duration_s of a random walk's high-passed
  /// part, per unit of its rate (m^2/s^3 -> m^2/s^2): the high-pass of a random walk of rate q
  /// is an Ornstein-Uhlenbeck process of time constant tau = kLowPassTime_s and variance
  /// q tau / 2, whose mean over T has (q tau / 2) (2 tau / T) (1 - (tau / T) (1 - exp(-T / tau))).
  static double high_passed_noise_variance(double duration_s);

 private:
  double threshold_squared_;
  Eigen::Vector3d low_pass_n_;
  double mean_square_ = 0.0;
  Eigen::Vector3d counted_n_ = Eigen::Vector3d::Zero();
  double share_ = 0.0;
};

}  // namespace stochnav
