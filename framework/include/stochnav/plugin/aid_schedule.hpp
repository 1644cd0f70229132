#pragma once
// When an aid measures: at a fixed rate from a start time, or at the rows of its aid data.
// Shared by the aiding plugins so that every aid matches IMU epochs the same way.

#include <cstddef>
#include <optional>
#include <span>

namespace stochnav::plugin {

/// Two times closer than this (s) are the same epoch: IMU time stamps on a grid of 1e-3 s or
/// coarser, written with at least microsecond resolution, match their aid rows.
inline constexpr double kEpochMatchTolerance_s = 1e-6;

class AidSchedule final {
 public:
  /// Measurements at start_s + k / rate_hz, k = 1, 2, ... (rate_hz > 0).
  static AidSchedule periodic(double start_s, double rate_hz);
  /// Measurements at the given times (s, ascending; the span must outlive the schedule).
  static AidSchedule at_rows(std::span<const double> row_times_s);

  /// Whether t (s) is a measurement time.
  bool due(double t_s) const { return row_at(t_s).has_value(); }
  /// For row schedules, the row at t; for periodic ones, k. nullopt when not due. Any order
  /// of t; ascending times (a run's epochs) cost O(1) each, other orders a binary search.
  std::optional<std::size_t> row_at(double t_s) const;

 private:
  double start_s_ = 0.0;
  double period_s_ = 0.0;
  std::span<const double> rows_;
  // The first row at or after the previous query's time less the tolerance: where the next
  // query of a run, one epoch later, starts its search. Not shared between threads: each
  // plugin instance holds its own schedule.
  mutable std::size_t next_row_ = 0;
};

}  // namespace stochnav::plugin
