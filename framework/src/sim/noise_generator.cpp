#include "stochnav/sim/noise_generator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/sim/normal_generator.hpp"
#include "term_samplers.hpp"

namespace stochnav {

class NoiseGenerator::Impl {
 public:
  Impl(const NoiseModel& model, double rate_hz, std::uint64_t seed, double flicker_band_max_s)
      : rate_hz_(rate_hz) {
    if (auto issue = find_model_issue(model)) {
      throw ConfigError(fmt::format("noise model {}: {}; expected {}", issue->pointer,
                                    issue->problem, issue->expected));
    }
    if (!std::isfinite(rate_hz) || !(rate_hz > 0.0)) {
      throw ConfigError(fmt::format("simulation rate {} Hz; expected a rate > 0", rate_hz));
    }
    if (!std::isfinite(flicker_band_max_s) || !(flicker_band_max_s > 0.0)) {
      throw ConfigError(fmt::format("flicker band end {} s; expected a time > 0",
                                    flicker_band_max_s));
    }
    const double tau0 = 1.0 / rate_hz;
    for (std::size_t i = 0; i < model.terms.size(); ++i) {
      const NoiseTerm& term = model.terms[i];
      if (const auto* nonstationary = std::get_if<NonstationaryTerm>(&term)) {
        segments_ = nonstationary->segments;
        continue;
      }
      samplers_.push_back(sim_detail::make_term_sampler(term, tau0, derive_stream_seed(seed, i),
                                                        flicker_band_max_s));
    }
  }

  void generate(std::span<double> out) {
    std::fill(out.begin(), out.end(), 0.0);
    for (auto& sampler : samplers_) sampler->add_to(out, next_index_);
    apply_segments(out);
    next_index_ += out.size();
  }

  std::uint64_t next_index() const { return next_index_; }
  double rate_hz() const { return rate_hz_; }

 private:
  // Sample k lies in a segment when its time t_k = k / rate is in [start, end).
  void apply_segments(std::span<double> out) const {
    const double first_time = static_cast<double>(next_index_) / rate_hz_;
    const double end_time = static_cast<double>(next_index_ + out.size()) / rate_hz_;
    for (const auto& segment : segments_) {
      if (segment.end_s <= first_time || segment.start_s >= end_time) continue;
      // First sample index with t_k >= start, first with t_k >= end (block-relative).
      const auto first_at_or_after = [&](double time) {
        const double k = std::ceil(time * rate_hz_ - static_cast<double>(next_index_));
        return static_cast<std::size_t>(std::clamp(k, 0.0, static_cast<double>(out.size())));
      };
      std::size_t begin = first_at_or_after(segment.start_s);
      std::size_t end = first_at_or_after(segment.end_s);
      // Guard the rounding of time * rate against the exact test t_k = k / rate.
      while (begin > 0 && sample_time(begin - 1) >= segment.start_s) --begin;
      while (begin < out.size() && sample_time(begin) < segment.start_s) ++begin;
      while (end > 0 && sample_time(end - 1) >= segment.end_s) --end;
      while (end < out.size() && sample_time(end) < segment.end_s) ++end;
      for (std::size_t i = begin; i < end; ++i) out[i] *= segment.scale;
    }
  }

  double sample_time(std::size_t block_index) const {
    return static_cast<double>(next_index_ + block_index) / rate_hz_;
  }

  double rate_hz_;
  std::vector<std::unique_ptr<sim_detail::TermSampler>> samplers_;
  std::vector<NonstationarySegment> segments_;
  std::uint64_t next_index_ = 0;
};

NoiseGenerator::NoiseGenerator(const NoiseModel& model, double rate_hz, std::uint64_t seed,
                               double flicker_band_max_s)
    : impl_(std::make_unique<Impl>(model, rate_hz, seed, flicker_band_max_s)) {}
NoiseGenerator::~NoiseGenerator() = default;
NoiseGenerator::NoiseGenerator(NoiseGenerator&&) noexcept = default;
NoiseGenerator& NoiseGenerator::operator=(NoiseGenerator&&) noexcept = default;

void NoiseGenerator::generate(std::span<double> out) { impl_->generate(out); }
std::uint64_t NoiseGenerator::next_index() const { return impl_->next_index(); }
double NoiseGenerator::rate_hz() const { return impl_->rate_hz(); }

std::vector<double> simulate_noise(const NoiseModel& model, double duration_s, double rate_hz,
                                   std::uint64_t seed) {
  if (!std::isfinite(duration_s) || !(duration_s > 0.0)) {
    throw ConfigError(fmt::format("simulation duration {} s; expected a duration > 0", duration_s));
  }
  if (!std::isfinite(rate_hz) || !(rate_hz > 0.0)) {
    throw ConfigError(fmt::format("simulation rate {} Hz; expected a rate > 0", rate_hz));
  }
  const double count = std::round(duration_s * rate_hz);
  if (count < 1.0) {
    throw ConfigError(fmt::format(
        "simulation of {} s at {} Hz has no samples; expected duration * rate >= 1", duration_s,
        rate_hz));
  }
  NoiseGenerator generator(model, rate_hz, seed, duration_s);
  std::vector<double> samples(static_cast<std::size_t>(count));
  generator.generate(samples);
  return samples;
}

}  // namespace stochnav
