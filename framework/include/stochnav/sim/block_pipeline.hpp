#pragma once
// Blocks of samples from several independent streams (e.g. the noise of six IMU axes), produced
// ahead of use by background threads so a consumer (the true-motion integration) and the
// producers run at the same time.
//
// Each stream is a callable that writes its next samples into a span; streams are split into
// groups, one producer thread per group, and each group fills two buffers in turn (double
// buffering). A stream is only ever called by one thread, in order, so the samples are the
// same whatever the number of threads (0 threads: streams are called on the consumer's thread
// when a block is requested).

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace stochnav {

class BlockPipeline final {
 public:
  using Stream = std::function<void(std::span<double>)>;

  /// Whatever the streams refer to must outlive the pipeline (producers may call them until
  /// the destructor has joined them).
  /// `threads`: producer threads (0 = synchronous; more than streams.size() is capped).
  BlockPipeline(std::vector<Stream> streams, std::size_t block_size, unsigned threads);
  ~BlockPipeline();
  BlockPipeline(const BlockPipeline&) = delete;
  BlockPipeline& operator=(const BlockPipeline&) = delete;

  /// Makes the next block current: the previous block's buffers are handed back to their
  /// producers, and the call waits until every stream's next block_size samples are ready.
  void advance();

  /// Samples of `stream` in the current block (block_size of them; valid until advance()).
  std::span<const double> current(std::size_t stream) const { return current_[stream]; }

  std::size_t block_size() const { return block_size_; }

  /// A producer count for a consumer that also works: all cores but the consumer's, yet at
  /// least two (so a consumer with little to do leaves no core idle), at most `streams`;
  /// 0 on a single-core machine.
  static unsigned default_threads(std::size_t streams);

 private:
  struct Group;
  void fill(Group& group, int slot);
  void produce(Group& group);

  std::vector<Stream> streams_;
  std::size_t block_size_;
  std::vector<std::unique_ptr<Group>> groups_;
  std::vector<std::span<const double>> current_;
  bool started_ = false;
};

}  // namespace stochnav
