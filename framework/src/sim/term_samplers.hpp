#pragma once
// Per-term exact samplers behind NoiseGenerator (see sim/noise_generator.hpp for the methods).
// Internal to the sim domain.

#include <cstdint>
#include <memory>
#include <span>

#include "stochnav/model/noise_term.hpp"

namespace stochnav::sim_detail {

/// The interval-mean rate samples of one stationary (or deterministic) term.
class TermSampler {
 public:
  virtual ~TermSampler();
  TermSampler() = default;
  TermSampler(const TermSampler&) = delete;
  TermSampler& operator=(const TermSampler&) = delete;

  /// Adds samples first_index, first_index + 1, ... of this term to `out` (natural units).
  /// Calls must be consecutive: first_index continues where the previous call stopped.
  virtual void add_to(std::span<double> out, std::uint64_t first_index) = 0;
};

/// A sampler for `term` at sampling interval tau0_s, drawing from `stream_seed`. nullptr for a
/// nonstationary term (NoiseGenerator applies it). flicker_band_max_s: see FlickerBank.
std::unique_ptr<TermSampler> make_term_sampler(const NoiseTerm& term, double tau0_s,
                                               std::uint64_t stream_seed,
                                               double flicker_band_max_s);

}  // namespace stochnav::sim_detail
