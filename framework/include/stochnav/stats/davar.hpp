#pragma once
// Dynamic Allan variance (DAVAR): the overlapping Allan deviation of every window of a record.
//
// Window k covers input samples [k * step, k * step + window). For rate data those samples are
// integrated to window + 1 phase points; for phase data the window holds `window` phase points.
// Each window's deviation at averaging factor m equals the overlapping Allan deviation of that
// window alone (Zhang et al. 2017, Eq. 3-5):
//   sigma^2(k, m) = sum_i (x[i+2m] - 2 x[i+m] + x[i])^2 / (2 tau^2 (P - 2m)),
// with i running over the window's P phase points. The window's analysis time is its centre
// (offline DAVAR, the paper's Eq. 3) or its end (causal: computable as soon as the last sample
// arrives).
//
// Cost: every squared second difference is computed once per m and accumulated into a running
// (compensated) prefix sum; a window's sum is the difference of two prefixes, so the cost is
// O(record length x number of taus) whatever the window and step. The averaging factors of each
// pushed block are spread over the stats threads (parallel.hpp), one factor per task: the
// result is bitwise the same for every thread count (it depends on the push block sizes).
// Memory: the phase of the last 2 * max(m) + block samples plus the windows still open,
// O(window), independent of the record length.

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "stochnav/io/record.hpp"

namespace stochnav {

struct DavarOptions {
  std::size_t window = 0;  ///< input samples per window (>= 3 for rate, >= 4 for phase data)
  std::size_t step = 0;    ///< input samples between window starts (>= 1)
  bool causal = false;     ///< analysis time at the window end instead of its centre
  /// Averaging factors m. Empty: Stable32 octave set for the window length.
  std::vector<std::size_t> m_values;

  /// Empty when valid; otherwise the reason, naming the option.
  std::string validate(std::size_t record_samples) const;
};

/// One analysis time of a DAVAR.
struct DavarRow {
  std::size_t window_index = 0;
  double time_s = 0.0;             ///< window centre (or end when causal), record time (s)
  std::vector<double> deviation;   ///< overlapping Allan deviation per m, in the record's unit
};

/// Streaming DAVAR: push samples block by block, completed windows come out in order.
class DavarAccumulator final {
 public:
  using RowSink = std::function<void(const DavarRow&)>;

  /// `m_values` must be non-empty, ascending and have 2 * m < phase points per window.
  DavarAccumulator(const DavarOptions& options, DataKind kind, double rate_hz, double start_time_s,
                   RowSink sink);
  ~DavarAccumulator();
  DavarAccumulator(const DavarAccumulator&) = delete;
  DavarAccumulator& operator=(const DavarAccumulator&) = delete;

  /// Appends samples (rate or phase, as given at construction). Emits every window that
  /// completes within them.
  void push(std::span<const double> samples);

  const std::vector<std::size_t>& m_values() const;
  /// Terms of the overlapping estimator per window at each m: phase points - 2m.
  std::vector<std::size_t> term_counts() const;
  /// Phase points held in memory now: bounded by 2 * max(m) + 2 * block + 32768, whatever the
  /// record length (the streaming guarantee, checked by the tests).
  std::size_t buffered_points() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

struct DavarResult {
  std::vector<double> time_s;             ///< analysis time per window (s)
  std::vector<double> tau_s;              ///< m * tau0 (s)
  std::vector<std::size_t> m;             ///< averaging factors
  std::vector<std::size_t> terms;         ///< terms per window at each m
  std::vector<std::vector<double>> adev;  ///< adev[window][tau], in the record's unit
};

/// DAVAR of a whole record in memory. Throws ConfigError if the options are invalid for it.
DavarResult dynamic_allan_deviation(const Record& record, const DavarOptions& options);

/// The same for samples held elsewhere (a numpy array): `values` as Record::values, the first
/// at start_time_s (s); `source` names the data in messages.
DavarResult dynamic_allan_deviation(std::span<const double> values, DataKind kind, double rate_hz,
                                    double start_time_s, const DavarOptions& options,
                                    const std::string& source);

/// Averaging factors DAVAR uses by default: octave m with 2m <= (phase points - 1) / 2 as for
/// Stable32's OADEV octave set on a record of one window.
std::vector<std::size_t> default_davar_m_values(std::size_t window, DataKind kind);

}  // namespace stochnav
