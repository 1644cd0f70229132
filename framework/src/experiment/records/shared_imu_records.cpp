#include "records/shared_imu_records.hpp"

#include <algorithm>
#include <fstream>
#include <string>

namespace stochnav {
namespace {

// The parsed size of an IMU file, from the rows in its first 64 kB (0 when it cannot tell).
std::uint64_t estimated_parsed_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string chunk(std::size_t{1} << 16, '\0');
  in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
  const auto bytes = static_cast<std::uint64_t>(in.gcount());
  const auto rows = static_cast<std::uint64_t>(
      std::count(chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(bytes), '\n'));
  std::error_code error;
  const std::uint64_t file_bytes = std::filesystem::file_size(path, error);
  if (rows == 0 || error) return 0;
  return (file_bytes * rows / bytes + 1) * sizeof(ImuIncrement);
}

}  // namespace

SharedImuRecords::SharedImuRecords(std::size_t seeds, std::size_t runs_per_seed,
                                   std::uint64_t budget_bytes)
    : budget_bytes_(budget_bytes) {
  for (std::size_t s = 0; s < seeds; ++s) {
    slots_.push_back(std::make_unique<Slot>());
    slots_.back()->remaining_runs = runs_per_seed;
  }
}

SharedImuRecords::Lease SharedImuRecords::lease(std::size_t seed,
                                                const std::filesystem::path& imu) {
  Slot& slot = *slots_.at(seed);
  const std::lock_guard loading(slot.loading);
  {
    const std::lock_guard lock(mutex_);
    if (slot.record && slot.path == imu) return Lease(this, seed, slot.record);
    if (slot.streamed || slot.record || imu.extension() == ".gz") {
      return Lease(this, seed, nullptr);
    }
    const std::uint64_t bytes = estimated_parsed_bytes(imu);
    if (bytes == 0 || held_bytes_ + bytes > budget_bytes_) {
      slot.streamed = true;
      return Lease(this, seed, nullptr);
    }
    held_bytes_ += bytes;
    slot.bytes = bytes;
  }
  std::shared_ptr<const ImuRecord> record;
  try {
    record = read_imu_record(imu.string());
  } catch (...) {
    const std::lock_guard lock(mutex_);
    held_bytes_ -= slot.bytes;
    slot.bytes = 0;
    throw;
  }
  const std::lock_guard lock(mutex_);
  slot.path = imu;
  slot.record = record;
  return Lease(this, seed, record);
}

void SharedImuRecords::release(std::size_t seed) {
  const std::lock_guard lock(mutex_);
  Slot& slot = *slots_.at(seed);
  if (slot.remaining_runs > 0 && --slot.remaining_runs == 0) {
    slot.record.reset();
    held_bytes_ -= slot.bytes;
    slot.bytes = 0;
  }
}

}  // namespace stochnav
