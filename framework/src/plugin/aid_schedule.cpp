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
  const auto it = std::lower_bound(rows_.begin(), rows_.end(), t_s - kEpochMatchTolerance_s);
  if (it == rows_.end() || *it > t_s + kEpochMatchTolerance_s) return std::nullopt;
  return static_cast<std::size_t>(it - rows_.begin());
}

}  // namespace stochnav::plugin
