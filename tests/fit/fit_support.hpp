#pragma once
// Helpers of the fit tests: Allan-variance curves of simulated records and pull statistics.

#include <cmath>
#include <cstdint>
#include <vector>

#include "stochnav/fit/fit_data.hpp"
#include "stochnav/model/allan_variance.hpp"
#include "stochnav/sim/noise_generator.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav::fit_testing {

/// OADEV (octave taus, Stable32 EDF) of a simulated record of `truth` (natural units, rad/s).
inline FitData simulated_fit_data(const NoiseModel& truth, std::size_t samples, double rate_hz,
                                  std::uint64_t seed) {
  const double tau0 = 1.0 / rate_hz;
  const auto rate = simulate_noise(truth, static_cast<double>(samples) * tau0, rate_hz, seed);
  const auto phase = phase_from_rate(rate, tau0);
  const auto m = averaging_factors(Deviation::kOadev, TauSpacing::kOctave, phase.size(), tau0);
  const auto points = compute_deviation(Deviation::kOadev, phase, tau0, m);
  return fit_data_from_deviations(Deviation::kOadev, points, truth.unit, rate_hz);
}

/// The exact closed-form curve of `truth` at the taus of `like`, same edf: a noiseless input.
inline FitData closed_form_fit_data(const NoiseModel& truth, const FitData& like) {
  FitData data = like;
  for (std::size_t i = 0; i < data.tau_s.size(); ++i) {
    data.avar[i] = allan_variance(truth, data.tau_s[i]);
  }
  return data;
}

struct PullStatistics {
  std::vector<double> pulls;
  double mean() const {
    double sum = 0.0;
    for (double p : pulls) sum += p;
    return sum / static_cast<double>(pulls.size());
  }
  double standard_deviation() const {
    const double m = mean();
    double sum = 0.0;
    for (double p : pulls) sum += (p - m) * (p - m);
    return std::sqrt(sum / static_cast<double>(pulls.size() - 1));
  }
  /// Fraction of |pull| <= 1 (68.3 % for a standard normal).
  double within_one() const {
    double count = 0.0;
    for (double p : pulls) count += std::abs(p) <= 1.0;
    return count / static_cast<double>(pulls.size());
  }
};

}  // namespace stochnav::fit_testing
