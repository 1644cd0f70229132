#pragma once
// The parsed IMU records of `stochnav compare`'s seeds: every variant of a seed navigates on the
// same imu.csv, so the first of them to run parses it (experiment/imu_record.hpp) and the others
// share that copy; it is dropped when the seed's last variant has run. Records are shared while
// the parsed copies held at once stay within a memory budget; past it a run streams the file
// itself, as `stochnav run` does (memory stays bounded for long records and many seeds).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <vector>

#include "stochnav/experiment/imu_record.hpp"

namespace stochnav {

class SharedImuRecords final {
 public:
  /// Held while a run uses the record; releases the run's claim on destruction.
  class Lease final {
   public:
    Lease(SharedImuRecords* owner, std::size_t seed, std::shared_ptr<const ImuRecord> record)
        : owner_(owner), seed_(seed), record_(std::move(record)) {}
    ~Lease() {
      if (owner_ != nullptr) owner_->release(seed_);
    }
    Lease(const Lease&) = delete;
    Lease& operator=(const Lease&) = delete;
    /// The shared record; null when the run should stream the file itself.
    const std::shared_ptr<const ImuRecord>& record() const { return record_; }

   private:
    SharedImuRecords* owner_;
    std::size_t seed_;
    std::shared_ptr<const ImuRecord> record_;
  };

  static constexpr std::uint64_t kDefaultBudgetBytes = std::uint64_t{1} << 30;  // 1 GiB

  /// `runs_per_seed` runs (the variants) will lease each of the `seeds` records.
  SharedImuRecords(std::size_t seeds, std::size_t runs_per_seed,
                   std::uint64_t budget_bytes = kDefaultBudgetBytes);

  /// The record of seed `seed` read from `imu` (by this call when no run of the seed has read it
  /// yet; the seed's other runs wait for it rather than read it too). Throws InputError for a
  /// bad IMU file. A record over the budget, or a run of the seed naming another file, gets a
  /// lease without a record.
  Lease lease(std::size_t seed, const std::filesystem::path& imu);

 private:
  struct Slot {
    std::mutex loading;  // held while the record is read
    std::filesystem::path path;
    std::shared_ptr<const ImuRecord> record;
    std::uint64_t bytes = 0;  // counted against the budget while held
    std::size_t remaining_runs = 0;
    bool streamed = false;  // over the budget: every run of the seed streams the file
  };
  void release(std::size_t seed);

  std::mutex mutex_;  // guards held_bytes_ and the slots' fields but `loading`
  std::vector<std::unique_ptr<Slot>> slots_;
  std::uint64_t budget_bytes_;
  std::uint64_t held_bytes_ = 0;
};

}  // namespace stochnav
