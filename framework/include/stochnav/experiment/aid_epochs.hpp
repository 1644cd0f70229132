#pragma once
// Aid rows on the IMU's epochs. A rig's surface channels (tally, ROP, slips) are stamped by
// their own clock, so an aids.csv row rarely falls on an IMU epoch; the filter applies
// measurements at IMU epochs only. The rule (docs/drilling-envelope.md, section 6):
//
//   a row at time r is applied at the FIRST IMU epoch t_k with t_k >= r - 1 us, i.e. at most
//   one IMU period after r; its time in the run's aid data becomes t_k.
//
// The offset t_k - r (0 <= offset < one period, 10 ms at 100 Hz) is the whole timing error:
// the interval aids (pipe tally, ROP) then compare a depth change or a mean rate over
// [r_k-1, r_k] with the INS over [t_k-1, t_k], whose ends differ by less than one period each;
// at 60 m/h that is under 0.2 mm of depth (against a tally's 5 cm) and an ROP ramp of 10 s
// changes the rate by under 0.1 % of itself over it. ZUPT flags move by the same at most one
// period, inside the stationary span's settle time.
//
// Rows must be at least 1.5 IMU periods apart (then at most one falls between two epochs,
// whose spacing the IMU reader holds within 1 % of the period); closer rows are refused (an
// InputError naming the file and rows). Rows before the first navigation epoch (during the
// alignment) and after the last are counted, not applied.

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "stochnav/plugin/aid_plugin.hpp"

namespace stochnav {

class AidEpochs final {
 public:
  /// `data` must outlive this object; its times are moved onto epochs as the run advances.
  /// `imu_period_s` > 0 is the IMU's nominal epoch spacing. Throws InputError when two rows
  /// are closer than 1.5 periods.
  AidEpochs(plugin::AidData& data, double imu_period_s);

  /// Call once per navigation epoch, in order, BEFORE the navigator steps over it: every row
  /// in (previous epoch, t_s] (with 1 us tolerance) is put on t_s.
  void advance_to(double t_s);

  /// Call after the last epoch: counts the rows the record never reached.
  void finish();

  std::size_t rows() const { return data_.rows(); }
  std::size_t applied() const { return on_grid_ + moved_; }
  /// {"rows", "on_grid", "moved", "max_offset_s", "before_start", "after_end"}
  nlohmann::json summary_json() const;

 private:
  plugin::AidData& data_;
  double period_s_;
  std::size_t next_ = 0;  // first row not yet placed
  bool started_ = false;
  std::size_t on_grid_ = 0;
  std::size_t moved_ = 0;
  std::size_t before_start_ = 0;
  std::size_t after_end_ = 0;
  double max_offset_s_ = 0.0;
};

}  // namespace stochnav
