#include "stochnav/sim/block_pipeline.hpp"

#include <algorithm>
#include <array>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace stochnav {

struct BlockPipeline::Group {
  std::vector<std::size_t> streams;
  std::array<std::vector<double>, 2> buffers;  // streams.size() * block_size each, stream-major
  std::array<bool, 2> ready{false, false};
  int consumer_slot = 0;
  bool stop = false;
  std::mutex mutex;
  std::condition_variable changed;
  std::thread worker;
};

unsigned BlockPipeline::default_threads(std::size_t streams) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  if (cores == 1 || streams == 0) return 0;
  return static_cast<unsigned>(std::min<std::size_t>(std::max(cores - 1, 2u), streams));
}

BlockPipeline::BlockPipeline(std::vector<Stream> streams, std::size_t block_size,
                             unsigned threads)
    : streams_(std::move(streams)), block_size_(block_size), current_(streams_.size()) {
  const std::size_t group_count =
      std::max<std::size_t>(1, std::min<std::size_t>(threads, streams_.size()));
  for (std::size_t g = 0; g < group_count; ++g) groups_.push_back(std::make_unique<Group>());
  for (std::size_t s = 0; s < streams_.size(); ++s) groups_[s % group_count]->streams.push_back(s);
  for (auto& group : groups_) {
    for (auto& buffer : group->buffers) buffer.assign(group->streams.size() * block_size_, 0.0);
  }
  if (threads == 0) return;
  for (auto& group : groups_) {
    Group* g = group.get();
    g->worker = std::thread([this, g] { produce(*g); });
  }
}

BlockPipeline::~BlockPipeline() {
  for (auto& group : groups_) {
    if (!group->worker.joinable()) continue;
    {
      const std::lock_guard lock(group->mutex);
      group->stop = true;
    }
    group->changed.notify_all();
    group->worker.join();
  }
}

void BlockPipeline::fill(Group& group, int slot) {
  std::vector<double>& buffer = group.buffers[static_cast<std::size_t>(slot)];
  for (std::size_t i = 0; i < group.streams.size(); ++i) {
    streams_[group.streams[i]](std::span(buffer).subspan(i * block_size_, block_size_));
  }
}

void BlockPipeline::produce(Group& group) {
  for (int slot = 0;; slot ^= 1) {
    {
      std::unique_lock lock(group.mutex);
      group.changed.wait(lock, [&] { return group.stop || !group.ready[slot]; });
      if (group.stop) return;
    }
    fill(group, slot);
    {
      const std::lock_guard lock(group.mutex);
      group.ready[slot] = true;
    }
    group.changed.notify_all();
  }
}

void BlockPipeline::advance() {
  for (auto& group : groups_) {
    Group& g = *group;
    if (!g.worker.joinable()) {
      fill(g, 0);
    } else {
      std::unique_lock lock(g.mutex);
      if (started_) {
        g.ready[g.consumer_slot] = false;  // hand the used buffer back
        g.consumer_slot ^= 1;
        g.changed.notify_all();
      }
      g.changed.wait(lock, [&] { return g.ready[g.consumer_slot]; });
    }
    const std::vector<double>& buffer = g.buffers[static_cast<std::size_t>(g.consumer_slot)];
    for (std::size_t i = 0; i < g.streams.size(); ++i) {
      current_[g.streams[i]] = std::span(buffer).subspan(i * block_size_, block_size_);
    }
  }
  started_ = true;
}

}  // namespace stochnav
