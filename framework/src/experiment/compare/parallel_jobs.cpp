#include "stochnav/experiment/parallel_jobs.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace stochnav {

void run_parallel(std::size_t count, unsigned threads, ProgressBar& progress,
                  std::atomic<std::uint64_t>& done, const std::function<void(std::size_t)>& job) {
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> finished{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_failure;
  std::mutex failure_mutex;
  const auto worker = [&] {
    for (std::size_t i = next++; i < count && !failed; i = next++) {
      try {
        job(i);
      } catch (...) {
        const std::lock_guard lock(failure_mutex);
        if (!first_failure) first_failure = std::current_exception();
        failed = true;
      }
      ++done;
      ++finished;
    }
  };
  std::vector<std::thread> pool;
  const auto workers =
      static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads, count)));
  for (unsigned t = 1; t < workers; ++t) pool.emplace_back(worker);
  // A drawer thread keeps the progress up to date until the last job has finished (the last
  // jobs can run for a long time after the last one started).
  std::thread drawer([&] {
    while (finished < count && !failed) {
      progress.show(done);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  worker();
  for (auto& thread : pool) thread.join();
  drawer.join();
  if (first_failure) std::rethrow_exception(first_failure);
}

}  // namespace stochnav
