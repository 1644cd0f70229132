#pragma once
// Streaming readers of a navigation run's inputs: the IMU file and the truth file written by
// `stochnav simulate scenario` (or recorded in the same form).
//
// imu.csv: a header row and one row per epoch, body axes, either
//   increments  t, dtheta_x, dtheta_y, dtheta_z (rad), dv_x, dv_y, dv_z (m/s) over [t - dt, t]
//   rates       t, gyro_x, gyro_y, gyro_z (rad/s), accel_x, accel_y, accel_z (m/s^2), each the
//               mean over [t - dt, t]
// with t in s, strictly increasing and uniformly sampled: a step more than 1 % away from the
// first one (a gap, a change of rate) is an InputError naming the line (the first row's interval
// is taken equal to the second's).
// truth.csv: t (s), lat, lon (deg), h (m), ve, vn, vu (m/s), inclination, toolface, azimuth (deg).

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "stochnav/ins/nav_state.hpp"
#include "stochnav/ins/strapdown.hpp"
#include "stochnav/io/csv_table_reader.hpp"

namespace stochnav {

/// The columns of a truth file, in the order of a truth row.
inline constexpr std::array<std::string_view, 10> kTruthColumns = {
    "t", "lat", "lon", "h", "ve", "vn", "vu", "inclination", "toolface", "azimuth"};

/// One truth row (kTruthColumns: t s, lat, lon deg, h m, ve, vn, vu m/s, inclination, toolface,
/// azimuth deg) as a NavState (radians, v_n east-north-up, q_nb from the MWD angles).
NavState nav_state_from_truth_row(std::span<const double, 10> row);

class ImuFileReader final {
 public:
  /// Opens the file and reads its header (and the first two rows, for the first interval).
  /// Throws InputError naming the file and line (no IMU columns, fewer than two rows, ...).
  explicit ImuFileReader(const std::string& path);

  /// The next epoch's increments. Returns false at the end. Throws InputError "file:line" for a
  /// bad row, a time that does not increase or a step that differs from the first.
  bool next(ImuIncrement& increment);

  /// Nominal rate from the first interval (Hz).
  double rate_hz() const { return 1.0 / first_interval_s_; }
  /// Time of the start of the first interval (s).
  double start_time_s() const { return start_time_s_; }
  bool increments() const { return increments_; }

 private:
  std::optional<CsvTableReader> table_;
  bool increments_ = true;
  double first_interval_s_ = 0.0;
  double start_time_s_ = 0.0;
  double last_t_s_ = 0.0;
  std::array<double, 7> row_{};
  std::array<std::array<double, 7>, 2> lookahead_{};
  int buffered_ = 0;
  int served_ = 0;
};

class TruthFileReader final {
 public:
  /// Throws InputError naming the file (missing columns, empty).
  explicit TruthFileReader(const std::string& path);

  /// The next truth row as a NavState. Returns false at the end. Throws InputError
  /// "FILE:LINE: time does not increase ..." when a row's t is not after the previous row's (rows
  /// swapped or duplicated), as ImuFileReader does: the run matches truth to the IMU epochs by
  /// time, and would silently skip epochs of an unsorted file.
  bool next(NavState& truth);

 private:
  CsvTableReader table_;
  double last_t_s_ = 0.0;
  bool started_ = false;
};

}  // namespace stochnav
