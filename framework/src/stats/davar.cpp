#include "stochnav/stats/davar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/parallel.hpp"
#include "vector_clones.hpp"

namespace stochnav {
namespace {

/// A double-double running sum: the prefix sums of squared second differences grow with the
/// record, and a window's sum is a small difference of two of them.
struct DoubleDoubleSum {
  double high = 0.0;
  double low = 0.0;
  void add(double value) {
    const double sum = high + value;
    const double virtual_value = sum - high;
    low += (high - (sum - virtual_value)) + (value - virtual_value);
    high = sum;
  }
  friend double operator-(const DoubleDoubleSum& a, const DoubleDoubleSum& b) {
    return (a.high - b.high) + (a.low - b.low);
  }
};

/// sum_{i < count} (x[i+2m] - 2 x[i+m] + x[i])^2 with 32 independent accumulators: four
/// vectors of eight, so four chains of additions keep the vector units busy.
STOCHNAV_WIDE_VECTOR_CLONES
double sum_squared_second_differences(const double* x, std::size_t m, std::size_t count) {
  constexpr std::size_t kLanes = 32;
  const double* x1 = x + m;
  const double* x2 = x1 + m;
  std::array<double, kLanes> acc{};
  std::size_t i = 0;
  for (; i + kLanes <= count; i += kLanes) {
    for (std::size_t lane = 0; lane < kLanes; ++lane) {
      const double d = x2[i + lane] - 2.0 * x1[i + lane] + x[i + lane];
      acc[lane] += d * d;
    }
  }
  for (; i < count; ++i) {
    const double d = x2[i] - 2.0 * x1[i] + x[i];
    acc[0] += d * d;
  }
  for (std::size_t width = kLanes / 2; width >= 1; width /= 2) {  // pairwise
    for (std::size_t lane = 0; lane < width; ++lane) acc[lane] += acc[lane + width];
  }
  return acc[0];
}

/// A window's sum at one averaging factor, waiting to go into its row.
struct WindowSum {
  std::size_t window = 0;
  double sum = 0.0;
};

std::size_t phase_points_per_window(std::size_t window, DataKind kind) {
  return kind == DataKind::kRate ? window + 1 : window;
}

/// Running state for one averaging factor m.
struct TauLane {
  std::size_t m = 0;
  std::size_t next_term = 0;  // global phase index i of the next term x[i+2m] - 2x[i+m] + x[i]
  DoubleDoubleSum prefix;      // sum of squared terms with index < next_term
  std::deque<DoubleDoubleSum> open_starts;  // prefixes at the starts of windows not yet ended
  std::size_t next_start_window = 0;       // window whose start prefix is recorded next
  std::size_t next_end_window = 0;         // window whose sum ends next
  std::vector<WindowSum> finished;         // sums completed by the current push
};

/// Lane groups of a push (tasks), and the terms of one piece of a group's sweep: with every
/// averaging factor of a 50,000-sample window the piece and its offsets (up to 2m) stay in the
/// L2 cache.
constexpr std::size_t kLaneGroups = 4;
constexpr std::size_t kPieceTerms = 4096;

}  // namespace

std::string DavarOptions::validate(std::size_t record_samples) const {
  if (step == 0) return "--step must be at least 1 sample (got 0)";
  if (window < 4) return "--window must be at least 4 samples (got " + std::to_string(window) + ")";
  // Its phase points (window + 1) and the windows' sums must stay countable: no record is
  // that long anyway (2^62 samples of 8 bytes are 32 EiB).
  constexpr std::size_t kLongestWindow = std::size_t{1} << 62;
  if (window > kLongestWindow) {
    return "--window " + std::to_string(window) + " is longer than any record can be (at most " +
           std::to_string(kLongestWindow) + " samples); use a window no longer than the record";
  }
  if (record_samples > 0 && window > record_samples) {
    return "--window " + std::to_string(window) + " is longer than the record (" +
           std::to_string(record_samples) + " samples); use a window of at most " +
           std::to_string(record_samples) + " samples";
  }
  return {};
}

std::vector<std::size_t> default_davar_m_values(std::size_t window, DataKind kind) {
  return averaging_factors(Deviation::kOadev, TauSpacing::kOctave,
                           phase_points_per_window(window, kind));
}

class DavarAccumulator::Impl {
 public:
  Impl(const DavarOptions& options, DataKind kind, double rate_hz, double start_time_s,
       RowSink sink)
      : options_(options),
        kind_(kind),
        tau0_(1.0 / rate_hz),
        start_time_s_(start_time_s),
        window_points_(phase_points_per_window(options.window, kind)),
        sink_(std::move(sink)) {
    if (options_.m_values.empty()) options_.m_values = default_davar_m_values(options.window, kind);
    if (options_.m_values.empty()) {
      // Too few points for a single Allan deviation: say how long a window must be.
      std::size_t shortest = 4;
      while (shortest < 64 && default_davar_m_values(shortest, kind).empty()) ++shortest;
      throw ConfigError("--window " + std::to_string(options.window) +
                        ": too short for an Allan deviation (no averaging factor fits in " +
                        std::to_string(window_points_) + " phase points); use --window " +
                        std::to_string(shortest) + " or more");
    }
    std::sort(options_.m_values.begin(), options_.m_values.end());
    if (options_.m_values.front() == 0 || 2 * options_.m_values.back() >= window_points_) {
      throw ConfigError("DAVAR averaging factors must satisfy 1 <= m and 2m < " +
                        std::to_string(window_points_) + " phase points per window");
    }
    for (std::size_t m : options_.m_values) lanes_.push_back(TauLane{.m = m});
  }

  void push(std::span<const double> samples) {
    if (samples.empty()) return;
    append_phase(samples);
    const std::size_t available_end = phase_base_ + phase_.size();  // one past last phase index
    // The lanes are independent: each runs on one thread, its window sums kept aside, then
    // filed into the rows in lane order (the same rows for every thread count). A task takes a
    // fixed group of lanes through the new terms a cache-sized piece at a time, all its lanes
    // per piece: the piece comes from memory once for the group, not once per lane. A lane's
    // sums do not depend on the grouping.
    const std::size_t groups = std::min(lanes_.size(), kLaneGroups);
    parallel_for(groups, [&](std::size_t group) {
      std::size_t first_term = available_end;
      std::size_t last_end = 0;
      for (std::size_t lane = group; lane < lanes_.size(); lane += groups) {
        first_term = std::min(first_term, lanes_[lane].next_term);
        if (available_end >= 2 * lanes_[lane].m + 1) {
          last_end = std::max(last_end, available_end - 2 * lanes_[lane].m);
        }
      }
      for (std::size_t limit = (first_term / kPieceTerms + 1) * kPieceTerms;;
           limit += kPieceTerms) {
        for (std::size_t lane = group; lane < lanes_.size(); lane += groups) {
          advance(lane, available_end, limit);
        }
        if (limit >= last_end) break;
      }
    });
    for (std::size_t lane = 0; lane < lanes_.size(); ++lane) {
      for (const WindowSum& done : lanes_[lane].finished) {
        record_window_sum(lane, done.window, done.sum);
      }
      lanes_[lane].finished.clear();
    }
    emit_completed_rows();
    drop_old_phase();
  }

  std::vector<std::size_t> term_counts() const {
    std::vector<std::size_t> counts;
    for (const auto& lane : lanes_) counts.push_back(window_points_ - 2 * lane.m);
    return counts;
  }
  const std::vector<std::size_t>& m_values() const { return options_.m_values; }
  std::size_t buffered_points() const { return phase_.size(); }

 private:
  void append_phase(std::span<const double> samples) {
    if (kind_ == DataKind::kPhase) {
      phase_.insert(phase_.end(), samples.begin(), samples.end());
      return;
    }
    if (!have_reference_) {
      // Integrating y - reference keeps the phase small; second differences do not change.
      const std::size_t count = std::min<std::size_t>(samples.size(), 1 << 16);
      double sum = 0.0;
      for (std::size_t i = 0; i < count; ++i) sum += samples[i];
      rate_reference_ = sum / static_cast<double>(count);
      have_reference_ = true;
      phase_.push_back(0.0);
    }
    // Written through a pointer into room made first (no push_back per sample), with the
    // running sum in locals: the loop is then bound by its chain of additions only.
    const std::size_t old_size = phase_.size();
    phase_.resize(old_size + samples.size());
    double* out = phase_.data() + old_size;
    DoubleDoubleSum sum = phase_sum_;
    const double reference = rate_reference_;
    const double tau0 = tau0_;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      sum.add((samples[i] - reference) * tau0);
      out[i] = sum.high + sum.low;
    }
    phase_sum_ = sum;
  }

  // Processes every term of lane `lane_index` before `limit` whose phase points have arrived.
  void advance(std::size_t lane_index, std::size_t available_end, std::size_t limit) {
    TauLane& lane = lanes_[lane_index];
    const std::size_t m = lane.m;
    if (available_end < 2 * m + 1) return;
    const std::size_t last_term_end = available_end - 2 * m;  // terms [next_term, last_term_end)
    const std::size_t span_end = window_points_ - 2 * m;      // terms per window
    while (lane.next_term <= last_term_end) {
      // Events at this position: the end of the oldest open window, then a new window start.
      const std::size_t end_position = lane.next_end_window * options_.step + span_end;
      const std::size_t start_position = lane.next_start_window * options_.step;
      if (lane.next_term == end_position && !lane.open_starts.empty()) {
        lane.finished.push_back({lane.next_end_window, lane.prefix - lane.open_starts.front()});
        lane.open_starts.pop_front();
        ++lane.next_end_window;
        continue;
      }
      if (lane.next_term == start_position) {
        lane.open_starts.push_back(lane.prefix);
        ++lane.next_start_window;
        continue;
      }
      std::size_t segment_end = std::min({last_term_end, start_position, limit});
      if (!lane.open_starts.empty()) segment_end = std::min(segment_end, end_position);
      if (segment_end <= lane.next_term) break;  // waiting for more data, or past `limit`
      lane.prefix.add(sum_of_squared_terms(m, lane.next_term, segment_end));
      lane.next_term = segment_end;
    }
  }

  double sum_of_squared_terms(std::size_t m, std::size_t begin, std::size_t end) const {
    return sum_squared_second_differences(phase_.data() + (begin - phase_base_), m, end - begin);
  }

  void record_window_sum(std::size_t lane_index, std::size_t window, double sum) {
    if (pending_.empty() || pending_.back().window_index < window) {
      while (pending_.empty() || pending_.back().window_index < window) {
        DavarRow row;
        row.window_index = pending_.empty() ? window : pending_.back().window_index + 1;
        row.deviation.assign(lanes_.size(), 0.0);
        pending_.push_back(std::move(row));
      }
    }
    DavarRow& row = pending_[window - pending_.front().window_index];
    const double tau = static_cast<double>(lanes_[lane_index].m) * tau0_;
    const double terms = static_cast<double>(window_points_ - 2 * lanes_[lane_index].m);
    row.deviation[lane_index] = std::sqrt(std::max(sum, 0.0) / (2.0 * tau * tau * terms));
  }

  // A window is complete when its smallest m (the last lane to reach its end) has been recorded.
  void emit_completed_rows() {
    const std::size_t complete_before = lanes_.front().next_end_window;
    while (!pending_.empty() && pending_.front().window_index < complete_before) {
      DavarRow& row = pending_.front();
      const double start = static_cast<double>(row.window_index * options_.step);
      const double offset = options_.causal ? static_cast<double>(options_.window)
                                            : 0.5 * static_cast<double>(options_.window);
      row.time_s = start_time_s_ + (start + offset) * tau0_;
      sink_(row);
      pending_.pop_front();
    }
  }

  // Keeps only the phase points a future term can use, and re-bases them near zero.
  void drop_old_phase() {
    std::size_t oldest_needed = phase_base_ + phase_.size();
    for (const auto& lane : lanes_) oldest_needed = std::min(oldest_needed, lane.next_term);
    const std::size_t drop = oldest_needed - phase_base_;
    if (drop < (1 << 15) && drop < phase_.size() / 2) return;
    phase_.erase(phase_.begin(), phase_.begin() + static_cast<std::ptrdiff_t>(drop));
    phase_base_ = oldest_needed;
    if (kind_ == DataKind::kRate && !phase_.empty()) {
      const double base = phase_.front();
      for (double& x : phase_) x -= base;
      phase_sum_.high -= base;
    }
  }

  DavarOptions options_;
  DataKind kind_;
  double tau0_;
  double start_time_s_;
  std::size_t window_points_;
  RowSink sink_;
  std::vector<TauLane> lanes_;
  std::vector<double> phase_;   // phase points [phase_base_, phase_base_ + size)
  std::size_t phase_base_ = 0;  // global phase index of phase_[0]
  DoubleDoubleSum phase_sum_;
  double rate_reference_ = 0.0;
  bool have_reference_ = false;
  std::deque<DavarRow> pending_;
};

DavarAccumulator::DavarAccumulator(const DavarOptions& options, DataKind kind, double rate_hz,
                                   double start_time_s, RowSink sink)
    : impl_(std::make_unique<Impl>(options, kind, rate_hz, start_time_s, std::move(sink))) {}
DavarAccumulator::~DavarAccumulator() = default;
void DavarAccumulator::push(std::span<const double> samples) { impl_->push(samples); }
const std::vector<std::size_t>& DavarAccumulator::m_values() const { return impl_->m_values(); }
std::vector<std::size_t> DavarAccumulator::term_counts() const { return impl_->term_counts(); }
std::size_t DavarAccumulator::buffered_points() const { return impl_->buffered_points(); }

DavarResult dynamic_allan_deviation(const Record& record, const DavarOptions& options) {
  return dynamic_allan_deviation(record.values, record.kind, record.rate_hz, record.start_time_s,
                                 options, record.source);
}

DavarResult dynamic_allan_deviation(std::span<const double> values, DataKind kind, double rate_hz,
                                    double start_time_s, const DavarOptions& options,
                                    const std::string& source) {
  if (const std::string problem = options.validate(values.size()); !problem.empty()) {
    throw ConfigError(source + ": " + problem);
  }
  DavarResult result;
  DavarAccumulator accumulator(options, kind, rate_hz, start_time_s,
                               [&result](const DavarRow& row) {
                                 result.time_s.push_back(row.time_s);
                                 result.adev.push_back(row.deviation);
                               });
  constexpr std::size_t kBlock = 1 << 18;
  for (std::size_t begin = 0; begin < values.size(); begin += kBlock) {
    accumulator.push(values.subspan(begin, std::min(kBlock, values.size() - begin)));
  }
  result.m = accumulator.m_values();
  result.terms = accumulator.term_counts();
  const double tau0_s = 1.0 / rate_hz;  // as Record::tau0()
  for (std::size_t m : result.m) result.tau_s.push_back(static_cast<double>(m) * tau0_s);
  return result;
}

}  // namespace stochnav
