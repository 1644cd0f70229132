#pragma once
// The static alignment of a host that feeds the IMU epoch by epoch (an embedder's own loop,
// examples/embed_runtime): the same span, checks and alignment as `stochnav run` with
// "initial_state/alignment" (experiment/initial_state.hpp), which uses this class too.
//
//   StreamingAligner aligner(config.initial_state->alignment.value(), record_start_s);
//   while (!aligner.feed(next_epoch())) {}             // the first static_s seconds
//   site.t_s = aligner.end_time_s();                   // the tie-on at the span's end
//   [build the plugins for the run from site]
//   const AlignedStart aligned = aligner.align(site, options, gyro, accel);
//   MwdNavigator navigator(aligned.state, gyro, accel, aids, aligned.options);
//
// Memory: the span's epochs (60,000 for 600 s at 100 Hz), released by nothing but the aligner's
// destruction: the fine alignment runs the filter over them once more.

#include <span>
#include <vector>

#include "stochnav/experiment/initial_state.hpp"
#include "stochnav/filter/filter_options.hpp"
#include "stochnav/ins/nav_state.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/plugin/run_config.hpp"

namespace stochnav {

class StreamingAligner final {
 public:
  /// `record_start_s`: the time of the record's start (s), the first epoch's t_s - dt_s; the
  /// span is the epochs up to record_start_s + config.static_s.
  StreamingAligner(const plugin::AlignmentConfig& config, double record_start_s);

  /// Takes the next epoch of the record (times increasing, the caller's to check). Returns true
  /// when the span is complete with this epoch: feed no more (a later epoch throws
  /// std::logic_error).
  bool feed(const ImuIncrement& increment);

  bool complete() const { return complete_; }
  /// Seconds of the record taken so far (s).
  double collected_s() const;
  /// The time of the last epoch taken (s): the aligned start's time once complete(); the
  /// record's start before any epoch.
  double end_time_s() const;
  std::span<const ImuIncrement> span() const { return span_; }

  /// Whether the span is the static one asked for: throws ConfigError naming
  /// /initial_state/alignment/static_s with the measured spreads and the fix when it is not, or
  /// when the record ended before static_s (check_static_span). Usable before complete(): a
  /// record that ends early is checked with what it had.
  void check() const;

  /// check(), then coarse and fine alignment over the span from `site` (the tie-on; its attitude
  /// is ignored, its t_s should be end_time_s()): align_at_rest.
  AlignedStart align(const NavState& site, const FilterOptions& options,
                     plugin::NoiseModelPlugin& gyro_noise,
                     plugin::NoiseModelPlugin& accel_noise) const;

 private:
  plugin::AlignmentConfig config_;
  double record_start_s_ = 0.0;
  std::vector<ImuIncrement> span_;
  bool complete_ = false;
};

}  // namespace stochnav
