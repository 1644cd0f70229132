#include "stochnav/experiment/streaming_aligner.hpp"

#include <stdexcept>

#include "stochnav/plugin/aid_schedule.hpp"

namespace stochnav {

StreamingAligner::StreamingAligner(const plugin::AlignmentConfig& config, double record_start_s)
    : config_(config), record_start_s_(record_start_s) {}

bool StreamingAligner::feed(const ImuIncrement& increment) {
  if (complete_) {
    throw std::logic_error("StreamingAligner::feed: the static span is complete; feed the "
                           "navigator from here");
  }
  span_.push_back(increment);
  // The span ends at the epoch within the epoch-matching tolerance of its nominal end, so that
  // 600 s at 100 Hz is 60,000 epochs whatever the rounding of the time stamps.
  const double end_s = record_start_s_ + config_.static_s;
  complete_ = increment.t_s >= end_s - plugin::kEpochMatchTolerance_s;
  return complete_;
}

double StreamingAligner::collected_s() const { return end_time_s() - record_start_s_; }

double StreamingAligner::end_time_s() const {
  return span_.empty() ? record_start_s_ : span_.back().t_s;
}

void StreamingAligner::check() const { check_static_span(span_, config_, record_start_s_); }

AlignedStart StreamingAligner::align(const NavState& site, const FilterOptions& options,
                                     plugin::NoiseModelPlugin& gyro_noise,
                                     plugin::NoiseModelPlugin& accel_noise) const {
  check();
  return align_at_rest(span_, site, config_, options, gyro_noise, accel_noise);
}

}  // namespace stochnav
