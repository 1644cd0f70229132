// A persistent pool: workers sleep on a condition variable between jobs, so a parallel_for costs
// a wake-up (microseconds), not a thread creation, and the engine can split even short passes.

#include "stochnav/stats/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace stochnav {
namespace {

std::size_t default_thread_count() {
  if (const char* text = std::getenv("STOCHNAV_THREADS")) {
    char* end = nullptr;
    const unsigned long value = std::strtoul(text, &end, 10);
    if (end != text && *end == '\0' && value > 0) return value;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

std::atomic<std::size_t> thread_override{0};
thread_local bool inside_task = false;

class Pool {
 public:
  ~Pool() { resize(0); }

  /// Runs the job on `threads` threads (this one included); false if the pool is busy.
  bool run(std::size_t count, const std::function<void(std::size_t)>& task, std::size_t threads) {
    std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
    if (!busy.owns_lock()) return false;
    if (workers_.size() != threads - 1) resize(threads - 1);  // only when the count changes
    {
      std::lock_guard<std::mutex> lock(mutex_);
      task_ = &task;
      count_ = count;
      next_.store(0);
      failed_task_ = std::numeric_limits<std::size_t>::max();
      error_ = nullptr;
      running_ = workers_.size();
      ++generation_;
    }
    wake_.notify_all();
    work();
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return running_ == 0; });
    task_ = nullptr;
    if (error_) std::rethrow_exception(error_);
    return true;
  }

 private:
  void work() {
    inside_task = true;
    for (std::size_t i = next_.fetch_add(1); i < count_; i = next_.fetch_add(1)) {
      try {
        (*task_)(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (i < failed_task_) {
          failed_task_ = i;
          error_ = std::current_exception();
        }
      }
    }
    inside_task = false;
  }

  void resize(std::size_t workers) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (auto& thread : workers_) thread.join();
    workers_.clear();
    stop_ = false;
    // Each new worker starts from the current generation: it waits for the next job.
    for (std::size_t i = 0; i < workers; ++i) {
      workers_.emplace_back([this, seen = generation_] { worker_loop(seen); });
    }
  }

  void worker_loop(std::uint64_t seen) {
    for (;;) {
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
        if (stop_) return;
        seen = generation_;
      }
      work();
      std::lock_guard<std::mutex> lock(mutex_);
      if (--running_ == 0) done_.notify_one();
    }
  }

  std::mutex busy_;  // one job at a time
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable done_;
  std::vector<std::thread> workers_;
  const std::function<void(std::size_t)>* task_ = nullptr;
  std::size_t count_ = 0;
  std::atomic<std::size_t> next_{0};
  std::size_t running_ = 0;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
  std::size_t failed_task_ = 0;
  std::exception_ptr error_;
};

Pool& pool() {
  static Pool instance;
  return instance;
}

}  // namespace

std::size_t stats_thread_count() {
  const std::size_t chosen = thread_override.load();
  if (chosen > 0) return chosen;
  static const std::size_t fallback = default_thread_count();
  return fallback;
}

void set_stats_thread_count(std::size_t threads) { thread_override.store(threads); }

void parallel_for(std::size_t count, const std::function<void(std::size_t)>& task) {
  const std::size_t threads = stats_thread_count();
  if (threads > 1 && count > 1 && !inside_task && pool().run(count, task, threads)) return;
  // Serial: in order; the first failing task's exception propagates after the rest ran, as in
  // the pool.
  std::exception_ptr error;
  for (std::size_t i = 0; i < count; ++i) {
    try {
      task(i);
    } catch (...) {
      if (!error) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace stochnav
