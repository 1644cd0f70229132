#include "stochnav/plugin/aid_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace stochnav::plugin {

AidSchedule AidSchedule::periodic(double start_s, double rate_hz) {
  AidSchedule schedule;
  schedule.start_s_ = start_s;
  schedule.period_s_ = 1.0 / rate_hz;
  return schedule;
}

AidSchedule AidSchedule::at_rows(std::span<const double> row_times_s) {
  AidSchedule schedule;
  schedule.rows_ = row_times_s;
  return schedule;
}

std::optional<std::size_t> AidSchedule::row_at(double t_s) const {
  if (period_s_ > 0.0) {
    const double k = std::round((t_s - start_s_) / period_s_);
    if (k < 1.0 || std::abs(t_s - (start_s_ + k * period_s_)) > kEpochMatchTolerance_s) {
      return std::nullopt;
    }
    return static_cast<std::size_t>(k);
  }
  // The first row not before t - tolerance: from the previous query's when t has not gone
  // back, by a binary search otherwise; the same row either way.
  const double earliest = t_s - kEpochMatchTolerance_s;
  std::size_t row = std::min(next_row_, rows_.size());
  if (row > 0 && !(rows_[row - 1] < earliest)) {
    row = static_cast<std::size_t>(std::lower_bound(rows_.begin(), rows_.end(), earliest) -
                                   rows_.begin());
  } else {
    while (row < rows_.size() && rows_[row] < earliest) ++row;
  }
  next_row_ = row;
  if (row == rows_.size() || rows_[row] > t_s + kEpochMatchTolerance_s) return std::nullopt;
  return row;
}

}  // namespace stochnav::plugin
