#pragma once
// The IMU file of a run parsed on a reader thread, beside the navigation: the thread reads
// epochs with ImuFileReader (experiment/navigation_files.hpp: same columns, units, frames and
// checks) into blocks handed over through a bounded queue, so parsing is off the navigation's
// critical path and memory stays flat in the record's length (at most kBlocksInFlight blocks
// of kBlockEpochs epochs; blocks are recycled, no allocation once the queue is full).
//
// Errors keep their place: a bad row met by the thread is thrown by next() on the calling
// thread after the epochs before it have been returned, exactly as ImuFileReader would.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "stochnav/experiment/navigation_files.hpp"
#include "stochnav/ins/strapdown.hpp"

namespace stochnav {

class BackgroundImuReader final {
 public:
  static constexpr std::size_t kBlockEpochs = 4096;
  static constexpr std::size_t kBlocksInFlight = 4;

  /// Opens the file and reads its header and first rows on the calling thread (throws
  /// InputError as ImuFileReader does), then starts the reader thread.
  explicit BackgroundImuReader(const std::string& path);
  /// Stops the reader thread (also when the run stopped early) and waits for it.
  ~BackgroundImuReader();
  BackgroundImuReader(const BackgroundImuReader&) = delete;
  BackgroundImuReader& operator=(const BackgroundImuReader&) = delete;

  /// The next epoch's increments (rad, m/s; body frame). Returns false at the end. Throws the
  /// reader's InputError "file:line: ..." at the bad row's place in the record.
  bool next(ImuIncrement& increment) {
    if (position_ == current_.size() && !take_block()) return false;
    increment = current_[position_++];
    return true;
  }

  /// Nominal rate from the first interval (Hz) and the start of the first interval (s).
  double rate_hz() const { return rate_hz_; }
  double start_time_s() const { return start_time_s_; }

 private:
  struct Block {
    std::vector<ImuIncrement> epochs;
    bool last = false;         // nothing follows
    std::exception_ptr error;  // thrown after this block's epochs (last)
  };
  void read_blocks();  // the reader thread
  bool take_block();   // waits for the next block; false at the end (or throws its error)

  std::unique_ptr<ImuFileReader> reader_;  // used by the reader thread only, once started
  double rate_hz_ = 0.0;
  double start_time_s_ = 0.0;

  std::mutex mutex_;
  std::condition_variable filled_;   // a block was queued
  std::condition_variable emptied_;  // a block was returned (or stop asked)
  std::deque<Block> queue_;
  std::vector<std::vector<ImuIncrement>> spare_;  // consumed blocks for the thread to refill
  bool stop_ = false;

  std::vector<ImuIncrement> current_;  // the block being served
  std::size_t position_ = 0;
  bool finished_ = false;
  std::exception_ptr pending_error_;

  std::thread thread_;  // last: starts after everything above is constructed
};

}  // namespace stochnav
