#pragma once
// A stationary noise model of one sensor axis turned into what an error-state Kalman filter
// needs (plugin/noise_model_plugin.hpp): a white rate PSD, a bias random-walk PSD and augmented
// shaping states with their exact discrete transition Phi(dt), noise Qd(dt), initial covariance
// P0 and map M (sensor error = M x). Natural units throughout: signal = rad/s (gyro) or m/s^2
// (accelerometer); time in s.
//
// Term by term (model/noise_term.hpp):
//   angle_random_walk N  white PSD N^2 (signal^2 s).
//   rate_random_walk K   bias random-walk PSD K^2 (signal^2/s): the filter's core bias block.
//   gauss_markov s, T    one first-order state: Phi = e^(-dt/T), Qd = s^2 (1 - e^(-2dt/T)),
//                        P0 = s^2, M = 1 (exact discretisation of the Ornstein-Uhlenbeck process).
//   bias_instability B   the sum-of-Gauss-Markov bank of sim/flicker_bank.hpp, one first-order
//                        state per component. With components_per_decade = 2 and the simulator's
//                        tau0 and band this is the very bank the simulator draws from; fewer
//                        components per decade give a smaller bank whose floor ripples more
//                        (FlickerBank::max_relative_ripple; at 1 per decade over 0.1-600 s: 5
//                        states, within 3.3 % of the floor at 1-100 s).
//   rate_ramp R          two states (g, s): g' = s, s' = 0, so Phi = [1 dt; 0 1], Qd = 0,
//                        P0 = diag(0, R^2), M = [1 0]: a random constant slope of standard
//                        deviation |R| from zero at t = 0, whose Allan variance is R^2 tau^2 / 2.
//                        Not stationary: P grows as the ramp does.
//   sinusoid A, f        two states (c, s) of an undamped oscillator: Phi = rotation by 2 pi f dt,
//                        Qd = 0, P0 = (A^2 / 2) I, M = [1 0] (a sinusoid of random phase).
//   quantization Q       not represented, kept in `quantization` for the record. Its angle error
//                        is the current quantization residual: bounded (variance ~2 Q^2 between
//                        any two instants, however far apart), not accumulating; the filter only
//                        takes augmented states as a rate error held over its covariance interval,
//                        which would turn it into an accumulating angle error. Over a 0.1 s
//                        interval a typical FOG's ARW adds N^2 0.1 s, which exceeds Q^2 for
//                        Q < 0.32 N sqrt(s) (e.g. N = 0.002 deg/sqrt(h) = 0.12 arcsec/sqrt(s):
//                        Q < 0.04 arcsec); beyond that Q is an angle-measurement noise the filter
//                        ignores.
//   nonstationary        rejected: a schedule is not a stationary shaping filter (the oracle
//                        plugin integrates its white part separately).
//
// Fast first-order states: the filter holds augmented states constant over its covariance
// interval (0.1 s by default) and integrates them into the attitude as M x dt. A state whose
// correlation time is much shorter than that interval would be integrated as if it were constant,
// overstating its effect. First-order states (Gauss-Markov and bank components) with
// tau_c < fold_below_s are therefore folded into the white PSD with their low-frequency
// equivalent 2 s^2 tau_c (the variance of the integral of an OU process over t >> tau_c is
// 2 s^2 tau_c t): exact in the long run, they only lose their correlation below ~tau_c. For the
// flicker bank with fold_below_s = 0.1 the Allan variance is then 28 % above the floor at
// tau = 0.3 s, 2.7 % at 1 s and < 0.3 % from 3 s on (tests/model/shaping_filter_test.cpp).
// The same holds for sinusoids: only lines well below 1 / (2 x interval) = 5 Hz are represented
// faithfully by the held oscillator states.
//
// State order within an axis: first-order states (model order, bank components ascending),
// then ramp (g, s), then oscillators (c, s) per sinusoid.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "stochnav/model/noise_model.hpp"

namespace stochnav {

struct ShapingOptions {
  /// Sampling interval of the sensor (s), > 0: the lower end of the flicker bank's flat band.
  double tau0_s = 0.01;
  /// Upper end of the flicker bank's flat band (s), >= tau0_s (the simulator uses the record
  /// duration).
  double flicker_band_max_s = 3600.0;
  /// Density of the bank's correlation times, > 0 (the simulator's bank: 2).
  double flicker_components_per_decade = 2.0;
  /// First-order states with tau_c below this (s) are folded into the white PSD; 0 keeps all.
  double fold_below_s = 0.1;

  /// Empty when valid; otherwise the reason, naming the option.
  std::string validate() const;
};

struct FirstOrderState {
  double sigma = 0.0;  ///< stationary standard deviation, signal
  double tau_c = 0.0;  ///< correlation time (s), > 0
};

struct OscillatorState {
  double amplitude = 0.0;     ///< A, signal
  double frequency_hz = 0.0;  ///< f (Hz), > 0
};

/// One axis. A plain value; the member functions write caller-sized outputs and never allocate.
struct ShapingFilter {
  double white_psd = 0.0;      ///< N^2 plus folded first-order states, signal^2 s
  double bias_walk_psd = 0.0;  ///< K^2, signal^2 / s
  double quantization = 0.0;   ///< Q (signal s), not represented (see above)
  std::vector<FirstOrderState> first_order;
  std::vector<double> ramp_sigma;  ///< |R| per ramp term, signal / s (two states each)
  std::vector<OscillatorState> oscillators;

  /// Number of augmented states.
  int size() const;
  /// Phi(dt) and Qd(dt), size() x size() each, every entry written; dt = 0 gives I and 0.
  void transition(double dt_s, Eigen::Ref<Eigen::MatrixXd> phi,
                  Eigen::Ref<Eigen::MatrixXd> q_d) const;
  /// P0, size() x size(): the stationary covariance (the ramp: diag(0, R^2)).
  void initial_covariance(Eigen::Ref<Eigen::MatrixXd> p0) const;
  /// M as a row, 1 x size().
  void sensor_map(Eigen::Ref<Eigen::MatrixXd> map_row) const;
};

/// Builds the shaping filter of one axis' model (natural units). Throws ConfigError for invalid
/// options or a nonstationary term.
ShapingFilter build_shaping_filter(const NoiseModel& model, const ShapingOptions& options);

}  // namespace stochnav
