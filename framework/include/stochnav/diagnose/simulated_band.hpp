#pragma once
// The spread of a model's Allan deviation over records simulated from it: several seeds, the
// measured record's length and rate (sim/noise_generator.hpp), OADEV at the same taus. The
// band that plots and report.md show, and a check on the closed forms that works for
// nonstationary models too.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "stochnav/model/noise_model.hpp"

namespace stochnav {

struct SimulatedBand {
  std::vector<double> tau_s;
  std::vector<double> low;     ///< smallest simulated deviation per tau (natural units)
  std::vector<double> median;  ///< median simulated deviation
  std::vector<double> high;    ///< largest simulated deviation
  int seeds = 0;
};

/// Simulates `seeds` records of `samples` samples at rate_hz (seeds seed, seed + 1, ...) and
/// computes their OADEV at the averaging factors `m` (each with 2m < samples + 1). With k seeds
/// the [low, high] envelope holds a new record's value with probability (k - 1)/(k + 1) per tau.
SimulatedBand simulate_band(const NoiseModel& model, std::size_t samples, double rate_hz,
                            std::span<const std::size_t> m, int seeds, std::uint64_t seed);

}  // namespace stochnav
