#include "stochnav/experiment/navigation_files.hpp"

#include <fmt/format.h>

#include <cmath>

#include "stochnav/core/angles.hpp"
#include "stochnav/core/errors.hpp"
#include "stochnav/ins/mwd_attitude.hpp"

namespace stochnav {
namespace {

constexpr std::array<std::string_view, 7> kIncrementColumns = {
    "t", "dtheta_x", "dtheta_y", "dtheta_z", "dv_x", "dv_y", "dv_z"};
constexpr std::array<std::string_view, 7> kRateColumns = {"t",       "gyro_x",  "gyro_y", "gyro_z",
                                                          "accel_x", "accel_y", "accel_z"};
// Relative deviation of an IMU time step from the first one that is still the same rate (the
// sample reader's tolerance: time stamps written with few digits jitter a little).
constexpr double kStepTolerance = 0.01;

bool has_all(const CsvTableReader& table, std::span<const std::string_view> names) {
  for (auto name : names) {
    if (!table.has_column(name)) return false;
  }
  return true;
}

}  // namespace

ImuFileReader::ImuFileReader(const std::string& path) {
  {
    CsvTableReader probe(path, {});
    increments_ = has_all(probe, kIncrementColumns);
    if (!increments_ && !has_all(probe, kRateColumns)) {
      throw InputError(path + ":1: not an IMU file; expected the columns t,dtheta_x,dtheta_y,"
                              "dtheta_z,dv_x,dv_y,dv_z (increments) or t,gyro_x,gyro_y,gyro_z,"
                              "accel_x,accel_y,accel_z (rates)");
    }
  }
  table_.emplace(path, increments_ ? std::span<const std::string_view>(kIncrementColumns)
                                   : std::span<const std::string_view>(kRateColumns));
  while (buffered_ < 2 && table_->next(lookahead_[static_cast<std::size_t>(buffered_)])) {
    ++buffered_;
  }
  if (buffered_ < 2) {
    throw InputError(path + ": fewer than two IMU epochs; a navigation run needs a record");
  }
  first_interval_s_ = lookahead_[1][0] - lookahead_[0][0];
  if (!(first_interval_s_ > 0.0)) {
    throw InputError(path + ": the first two epochs do not increase in t; sort the file");
  }
  start_time_s_ = lookahead_[0][0] - first_interval_s_;
  last_t_s_ = start_time_s_;
}

bool ImuFileReader::next(ImuIncrement& increment) {
  if (served_ < buffered_) {
    row_ = lookahead_[static_cast<std::size_t>(served_++)];
  } else if (!table_->next(row_)) {
    return false;
  }
  const double dt = row_[0] - last_t_s_;
  if (!(dt > 0.0)) {
    throw InputError(table_->path() + ":" + std::to_string(table_->line_number()) +
                     ": time does not increase (t = " + std::to_string(row_[0]) +
                     " s after " + std::to_string(last_t_s_) + " s); sort or cut the record");
  }
  // DESIGN.md: a gap or a change of rate is an error naming the line, never integrated over.
  if (std::abs(dt - first_interval_s_) > kStepTolerance * first_interval_s_) {
    throw InputError(fmt::format(
        "{}:{}: IMU time step {:.9g} s where the record started with {:.9g} s (t = {:.9g} s); "
        "a gap or a change of rate: fill the gap, resample, or split the record here",
        table_->path(), table_->line_number(), dt, first_interval_s_, row_[0]));
  }
  last_t_s_ = row_[0];
  increment.t_s = row_[0];
  increment.dt_s = dt;
  const double scale = increments_ ? 1.0 : dt;
  increment.delta_theta_b = Eigen::Vector3d(row_[1], row_[2], row_[3]) * scale;
  increment.delta_v_b = Eigen::Vector3d(row_[4], row_[5], row_[6]) * scale;
  return true;
}

TruthFileReader::TruthFileReader(const std::string& path) : table_(path, kTruthColumns) {}

bool TruthFileReader::next(NavState& truth) {
  std::array<double, 10> row{};
  if (!table_.next(row)) return false;
  if (started_ && !(row[0] > last_t_s_)) {
    throw InputError(fmt::format(
        "{}:{}: time does not increase (t = {:.9g} s after {:.9g} s): truth rows swapped or "
        "duplicated; sort the file by t and remove duplicate rows",
        table_.path(), table_.line_number(), row[0], last_t_s_));
  }
  started_ = true;
  last_t_s_ = row[0];
  truth = nav_state_from_truth_row(row);
  return true;
}

NavState nav_state_from_truth_row(std::span<const double, 10> row) {
  NavState truth;
  truth.t_s = row[0];
  truth.latitude_rad = row[1] * kRadPerDeg;
  truth.longitude_rad = row[2] * kRadPerDeg;
  truth.height_m = row[3];
  truth.v_n = Eigen::Vector3d(row[4], row[5], row[6]);
  truth.q_nb = quaternion_from_mwd({.inclination_rad = row[7] * kRadPerDeg,
                                    .toolface_rad = row[8] * kRadPerDeg,
                                    .azimuth_rad = row[9] * kRadPerDeg});
  return truth;
}

}  // namespace stochnav
