#include "stochnav/experiment/background_imu_reader.hpp"

#include <utility>

namespace stochnav {

BackgroundImuReader::BackgroundImuReader(const std::string& path)
    : reader_(std::make_unique<ImuFileReader>(path)),
      rate_hz_(reader_->rate_hz()),
      start_time_s_(reader_->start_time_s()) {
  thread_ = std::thread([this] { read_blocks(); });
}

BackgroundImuReader::~BackgroundImuReader() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  emptied_.notify_all();
  thread_.join();
}

void BackgroundImuReader::read_blocks() {
  while (true) {
    Block block;
    {
      std::unique_lock lock(mutex_);
      emptied_.wait(lock, [this] { return stop_ || queue_.size() < kBlocksInFlight; });
      if (stop_) return;
      if (!spare_.empty()) {
        block.epochs = std::move(spare_.back());
        spare_.pop_back();
      }
    }
    block.epochs.resize(kBlockEpochs);
    std::size_t count = 0;
    try {
      while (count < kBlockEpochs && reader_->next(block.epochs[count])) ++count;
      block.last = count < kBlockEpochs;
    } catch (...) {
      block.error = std::current_exception();
      block.last = true;
    }
    block.epochs.resize(count);
    const bool last = block.last;
    {
      const std::lock_guard lock(mutex_);
      queue_.push_back(std::move(block));
    }
    filled_.notify_one();
    if (last) return;
  }
}

bool BackgroundImuReader::take_block() {
  while (true) {
    if (pending_error_) std::rethrow_exception(std::exchange(pending_error_, nullptr));
    if (finished_) return false;
    Block block;
    {
      std::unique_lock lock(mutex_);
      filled_.wait(lock, [this] { return !queue_.empty(); });
      block = std::move(queue_.front());
      queue_.pop_front();
      if (current_.capacity() > 0) spare_.push_back(std::move(current_));
    }
    emptied_.notify_one();
    current_ = std::move(block.epochs);
    position_ = 0;
    finished_ = block.last;
    pending_error_ = block.error;
    if (!current_.empty()) return true;
  }
}

}  // namespace stochnav
