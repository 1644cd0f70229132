#pragma once
// The noise terms of every DAVAR window of one axis (Zhang et al. 2017, Eqs. 7 and 8): the
// dynamic Allan variance (stats/davar.hpp) at octave taus, then per window a weighted linear
// least-squares fit of the Allan-variance model, which is linear in the squared coefficients:
//   sigma^2(tau) = Q^2 3/tau^2 + N^2 /tau + B^2 (2 ln 2 / pi) + K^2 tau/3      (Eq. 7),
// natural units (signal rad/s or m/s^2: Q rad, N rad/sqrt(s), B rad/s, K rad/s/sqrt(s)).
//
// Why linear least squares (the paper's Eq. 8) rather than the Ceres fit of fit_noise_terms:
// the per-window fit runs a few hundred times per axis, and with the squared coefficients as
// unknowns it is a 4 x 4 solve, so a 30-min 100 Hz record fits in milliseconds.
// Weights: an Allan variance with EDF nu scatters as avar chi2(nu)/nu, variance 2 avar^2 / nu;
// each point gets weight nu_i / (2 model_i^2), nu_i the Greenhall EDF of a white-FM (angle
// random walk) window at that tau. A pilot fit weighs by the measured values, a second by the
// pilot model (weights from the data themselves would favour the points that scattered low).
// Coefficients stay >= 0: a term whose squared coefficient comes out negative is dropped and
// the rest refitted (an active-set non-negative least squares; at most 4 terms).

#include <cstddef>
#include <span>
#include <vector>

#include "stochnav/stats/davar.hpp"

namespace stochnav::davar_noise {

/// Terms of Eq. 7 a window fit may use (rate ramp is left out: a window too short to hold a
/// ramp is the point of the method).
enum class WindowTerm { kQuantization, kAngleRandomWalk, kBiasInstability, kRateRandomWalk };

struct WindowFitOptions {
  std::size_t window = 0;  ///< samples per window (>= 16)
  std::size_t step = 0;    ///< samples between window starts (>= 1)
  bool causal = false;     ///< analysis time at the window end (trailing) instead of its centre
  std::vector<WindowTerm> terms = {WindowTerm::kAngleRandomWalk, WindowTerm::kBiasInstability};
};

struct WindowFitSeries {
  std::vector<double> time_s;  ///< analysis time of each window (s), ascending
  /// Angle random walk N of each window (natural units, e.g. rad/sqrt(s)), >= 0.
  std::vector<double> angle_random_walk;
  /// Bias instability B of each window (natural units, e.g. rad/s), >= 0; zeros when the
  /// terms do not include it.
  std::vector<double> bias_instability;
};

/// Fits `terms` to every window of a uniformly sampled rate record (samples in natural units,
/// sample k at start_time_s + k / rate_hz): window_deviations, then fit_window_deviations.
WindowFitSeries fit_terms_per_window(std::span<const double> rate_samples, double rate_hz,
                                     double start_time_s, const WindowFitOptions& options);

/// The DAVAR of the record at the octave factors of one window (stats/davar.hpp). Throws
/// ConfigError when the options are invalid or the terms do not include kAngleRandomWalk, and
/// InputError when the record is shorter than one window or a window has fewer octave taus
/// than terms + 1.
DavarResult window_deviations(std::span<const double> rate_samples, double rate_hz,
                              double start_time_s, const WindowFitOptions& options);

/// Fits `options.terms` to every window (row) of `davar`, computed with options.window.
WindowFitSeries fit_window_deviations(const DavarResult& davar, const WindowFitOptions& options);

}  // namespace stochnav::davar_noise
