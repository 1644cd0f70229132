// Time-interval errors of a phase record (ITU-T G.810; Stable32's MTIE and TIE rms).

#include "time_interval_errors.hpp"

#include <algorithm>
#include <array>
#include <vector>

#include "vector_clones.hpp"

namespace stochnav {
namespace {

/// Indices of a sliding window whose values are monotonic from front to back, so the front is
/// the window's extreme: each index enters and leaves once (amortised O(1) per point).
template <typename Before>
class MonotonicWindow {
 public:
  explicit MonotonicWindow(std::size_t capacity) { indices_.reserve(capacity); }

  /// Adds point i, dropping the points it makes irrelevant (those not `before` it).
  void push(const double* x, std::size_t i, Before before) {
    while (size() > 0 && !before(x[indices_.back()], x[i])) indices_.pop_back();
    indices_.push_back(i);
  }
  /// Forgets the front when it left the window (its index is below `first`).
  void expire(std::size_t first) {
    if (front_ < indices_.size() && indices_[front_] < first) ++front_;
    if (front_ > 4096 && 2 * front_ > indices_.size()) {  // reclaim the consumed prefix
      indices_.erase(indices_.begin(), indices_.begin() + static_cast<std::ptrdiff_t>(front_));
      front_ = 0;
    }
  }
  std::size_t front() const { return indices_[front_]; }

 private:
  std::size_t size() const { return indices_.size() - front_; }
  std::vector<std::size_t> indices_;
  std::size_t front_ = 0;
};

}  // namespace

double maximum_time_interval_error(std::span<const double> phase, std::size_t m) {
  const double* x = phase.data();
  const std::size_t n = phase.size();
  const auto strictly_greater = [](double kept, double added) { return kept > added; };
  const auto strictly_less = [](double kept, double added) { return kept < added; };
  MonotonicWindow<decltype(strictly_greater)> maxima(m + 2);
  MonotonicWindow<decltype(strictly_less)> minima(m + 2);
  double largest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    maxima.push(x, i, strictly_greater);
    minima.push(x, i, strictly_less);
    if (i < m) continue;
    const std::size_t first = i - m;  // window [first, i], m + 1 points
    maxima.expire(first);
    minima.expire(first);
    largest = std::max(largest, x[maxima.front()] - x[minima.front()]);
  }
  return largest;
}

STOCHNAV_WIDE_VECTOR_CLONES
double time_interval_error_sum(std::span<const double> phase, std::size_t m) {
  const double* x0 = phase.data();
  const double* x1 = x0 + m;
  const std::size_t count = phase.size() - m;
  std::array<double, 8> acc{};
  std::size_t i = 0;
  for (; i + 8 <= count; i += 8) {
    for (std::size_t lane = 0; lane < 8; ++lane) {
      const double diff = x1[i + lane] - x0[i + lane];
      acc[lane] += diff * diff;
    }
  }
  for (; i < count; ++i) {
    const double diff = x1[i] - x0[i];
    acc[0] += diff * diff;
  }
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

}  // namespace stochnav
