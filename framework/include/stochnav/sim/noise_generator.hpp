#pragma once
// Noise records from a noise model (part 1 of `stochnav simulate`).
//
// Sample k (k = 0, 1, ...) is the mean of the model's continuous-time rate over
// [k tau0, (k + 1) tau0), tau0 = 1 / rate_hz, in natural units (rad/s for gyro models, m/s^2 for
// accelerometer models, the signal itself for plain ones; divide by si_per_unit(model.unit) to
// write it in the model's unit). So the integrated record (phase) samples the continuous angle
// exactly, and at every tau = m tau0 the expected Allan variance of a record equals the closed
// form of model/closed_forms.hpp, term by term:
//   quantization       (e[k+1] - e[k]) / tau0 with e white angle noise of variance Q^2;
//   angle_random_walk  white, variance N^2 / tau0;
//   bias_instability   a bank of Gauss-Markov processes (sim/flicker_bank.hpp), flat floor
//                      0.664 B over [tau0, flicker_band_max_s], exact bank AVAR elsewhere;
//   rate_random_walk   Brownian rate w(t), its interval mean drawn jointly with the increment
//                      (random walk starts at 0);
//   rate_ramp          R (k + 1/2) tau0;
//   gauss_markov       exact discretisation of the Ornstein-Uhlenbeck state and its interval
//                      integral, started from the stationary distribution;
//   sinusoid           A [cos(phi + w t_k) - cos(phi + w t_k+1)] / (w tau0), w = 2 pi f, with
//                      phi = phase_rad or, when absent, uniform in [0, 2 pi) from the seed;
//   nonstationary      sample k of the sum of the other terms times the scale of the segment
//                      containing t_k = k tau0 (1 outside every segment).
//
// Randomness: term i draws from its own NormalGenerator (sim/normal_generator.hpp) seeded with
// derive_stream_seed(seed, i) (flicker components: sub-streams of that), so the same seed gives
// the same record whatever the block sizes, and adding a term leaves the others' noise intact.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "stochnav/model/noise_model.hpp"

namespace stochnav {

/// Streaming generator: memory independent of the record length (a few kB per term, plus
/// about 100 bytes per flicker component). Not thread-safe; use one per thread.
class NoiseGenerator final {
 public:
  /// Throws ConfigError if the model breaks a rule of find_model_issue, rate_hz is not > 0, or
  /// flicker_band_max_s is not > 0 (it sets the upper end of the bias-instability band, s:
  /// normally the record duration).
  NoiseGenerator(const NoiseModel& model, double rate_hz, std::uint64_t seed,
                 double flicker_band_max_s);
  ~NoiseGenerator();
  NoiseGenerator(NoiseGenerator&&) noexcept;
  NoiseGenerator& operator=(NoiseGenerator&&) noexcept;
  NoiseGenerator(const NoiseGenerator&) = delete;
  NoiseGenerator& operator=(const NoiseGenerator&) = delete;

  /// Writes the next out.size() samples (natural units) into `out`.
  void generate(std::span<double> out);

  /// Index of the next sample to be generated (samples generated so far).
  std::uint64_t next_index() const;
  double rate_hz() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

/// A whole record: round(duration_s * rate_hz) samples (at least 1), natural units, with the
/// flicker band up to duration_s. Throws ConfigError for an invalid model, duration_s or
/// rate_hz not > 0, or fewer than one sample.
std::vector<double> simulate_noise(const NoiseModel& model, double duration_s, double rate_hz,
                                   std::uint64_t seed);

}  // namespace stochnav
