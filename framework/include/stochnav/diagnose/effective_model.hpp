#pragma once
// The stationary equivalent of a noise model with a nonstationary term, for whole-record
// statistics (diagnose).
//
// A nonstationary term multiplies the rate samples of the other terms by scale(t). Over a record
// of duration T, at averaging times short against its segments, the overlapping Allan variance
// of the record then estimates w sigma^2(tau) with
//   w = (1/T) integral_0^T scale(t)^2 dt          (time-averaged variance factor),
// and the estimate is noisier than for a stationary record of the same length by the factor
//   kappa = [(1/T) integral scale^4 dt] / w^2 >= 1   (fewer effective samples: the loud
// stretches dominate the sum). Both are 1 without a nonstationary term.

#include "stochnav/model/noise_model.hpp"

namespace stochnav {

struct StationaryEquivalent {
  /// The model's stationary terms with every amplitude coefficient scaled by sqrt(w) (so each
  /// term's Allan variance is multiplied by w); no nonstationary term; same unit and rate.
  NoiseModel model;
  double variance_factor = 1.0;     ///< w
  double variance_inflation = 1.0;  ///< kappa, multiplies the variance of AVAR estimates
};

/// Mean of scale(t)^p over [0, duration_s) for the model's nonstationary term (1 outside every
/// segment; segments clipped to the record). 1 when there is no such term. duration_s > 0.
double mean_scale_power(const NoiseModel& model, double duration_s, int power);

/// Mean of scale(t)^2 over [t0_s, t1_s) (a DAVAR window), 1 without a nonstationary term.
double mean_scale_squared(const NoiseModel& model, double t0_s, double t1_s);

/// See the file comment. duration_s: record duration (s), > 0.
StationaryEquivalent stationary_equivalent(const NoiseModel& model, double duration_s);

/// Multiplies every amplitude coefficient of `term` (Q, N, B, K, R, Gauss-Markov sigma,
/// sinusoid amplitude) by `factor`; shape parameters (tau_c, frequency, phase) are kept.
NoiseTerm scale_amplitude(const NoiseTerm& term, double factor);

/// The model without its nonstationary term.
NoiseModel stationary_part(const NoiseModel& model);

/// The nonstationary term of the model, or nullptr.
const NonstationaryTerm* find_nonstationary(const NoiseModel& model);

}  // namespace stochnav
