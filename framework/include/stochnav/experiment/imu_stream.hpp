#pragma once
// The IMU epochs of one navigation run, in order: from the file, parsed on a reader thread
// (experiment/background_imu_reader.hpp), or from a record already in memory that other runs
// share (experiment/imu_record.hpp). Either way the same increments (rad, m/s; body frame).

#include <cstddef>
#include <memory>
#include <string>

#include "stochnav/experiment/background_imu_reader.hpp"
#include "stochnav/experiment/imu_record.hpp"

namespace stochnav {

class ImuStream final {
 public:
  /// Streams the file (throws InputError for a file that cannot be an IMU record).
  explicit ImuStream(const std::string& path)
      : reader_(std::make_unique<BackgroundImuReader>(path)) {}
  /// Serves the shared record (not null).
  explicit ImuStream(std::shared_ptr<const ImuRecord> record) : record_(std::move(record)) {}

  /// The next epoch; false at the end. Throws InputError for a bad row of a streamed file.
  bool next(ImuIncrement& increment) {
    if (!record_) return reader_->next(increment);
    if (index_ == record_->epochs.size()) return false;
    increment = record_->epochs[index_++];
    return true;
  }

  double rate_hz() const { return record_ ? record_->rate_hz : reader_->rate_hz(); }
  double start_time_s() const { return record_ ? record_->start_time_s : reader_->start_time_s(); }

 private:
  std::unique_ptr<BackgroundImuReader> reader_;
  std::shared_ptr<const ImuRecord> record_;
  std::size_t index_ = 0;
};

}  // namespace stochnav
