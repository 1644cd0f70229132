#include "stochnav/experiment/imu_record.hpp"

#include "stochnav/experiment/background_imu_reader.hpp"

namespace stochnav {

std::shared_ptr<const ImuRecord> read_imu_record(const std::string& path) {
  auto record = std::make_shared<ImuRecord>();
  record->path = path;
  BackgroundImuReader reader(path);
  record->rate_hz = reader.rate_hz();
  record->start_time_s = reader.start_time_s();
  ImuIncrement increment;
  while (reader.next(increment)) record->epochs.push_back(increment);
  record->epochs.shrink_to_fit();
  return record;
}

}  // namespace stochnav
