// The thread pool of `stochnav compare` (experiment/parallel_jobs.hpp): every job once, on the
// threads asked for, the first failure rethrown after the running jobs finished, no job started
// after a failure, and the degenerate counts.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "stochnav/core/errors.hpp"
#include "stochnav/experiment/parallel_jobs.hpp"

namespace stochnav {
namespace {

struct Pool {
  ProgressBar progress{"test", 0, false};
  std::atomic<std::uint64_t> done{0};
};

TEST(ParallelJobs, RunsEveryJobExactlyOnce) {
  for (unsigned threads : {1u, 2u, 3u, 8u, 64u}) {
    Pool pool;
    constexpr std::size_t kJobs = 1000;
    std::vector<std::atomic<int>> runs(kJobs);
    run_parallel(kJobs, threads, pool.progress, pool.done, [&](std::size_t i) { ++runs[i]; });
    for (std::size_t i = 0; i < kJobs; ++i) EXPECT_EQ(runs[i], 1) << "job " << i;
    EXPECT_EQ(pool.done, kJobs) << threads << " threads";
  }
}

TEST(ParallelJobs, UsesSeveralThreadsButNoMoreThanAsked) {
  Pool pool;
  std::mutex mutex;
  std::set<std::thread::id> seen;
  std::atomic<int> running{0};
  std::atomic<int> most{0};
  run_parallel(24, 3, pool.progress, pool.done, [&](std::size_t) {
    const int now = ++running;
    int previous = most.load();
    while (now > previous && !most.compare_exchange_weak(previous, now)) {
    }
    {
      const std::lock_guard lock(mutex);
      seen.insert(std::this_thread::get_id());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    --running;
  });
  EXPECT_LE(most, 3);
  EXPECT_LE(seen.size(), 3u);
  EXPECT_GE(seen.size(), 2u) << "24 jobs of 5 ms on 3 workers ran on one thread";
}

TEST(ParallelJobs, ZeroJobsAndMoreThreadsThanJobs) {
  Pool pool;
  int calls = 0;
  run_parallel(0, 8, pool.progress, pool.done, [&](std::size_t) { ++calls; });
  EXPECT_EQ(calls, 0);
  std::atomic<int> one{0};
  run_parallel(1, 0, pool.progress, pool.done, [&](std::size_t) { ++one; });  // 0 threads: 1
  EXPECT_EQ(one, 1);
}

TEST(ParallelJobs, RethrowsTheFirstFailureWithItsType) {
  Pool pool;
  try {
    run_parallel(50, 4, pool.progress, pool.done, [&](std::size_t i) {
      if (i == 7) throw ConfigError("job 7 failed");
    });
    FAIL() << "no exception";
  } catch (const ConfigError& error) {
    EXPECT_STREQ(error.what(), "job 7 failed");
  }
}

TEST(ParallelJobs, StartsNoJobAfterAFailure) {
  Pool pool;
  std::atomic<std::size_t> started{0};
  EXPECT_THROW(run_parallel(10000, 2, pool.progress, pool.done,
                            [&](std::size_t i) {
                              ++started;
                              if (i == 3) throw InputError("bad seed");
                              std::this_thread::sleep_for(std::chrono::milliseconds(2));
                            }),
               InputError);
  // Job 3 failed; each of the two workers may have taken one more index before seeing it.
  EXPECT_LE(started, 6u);
  EXPECT_EQ(pool.done, started.load()) << "every started job is counted as done";
}

TEST(ParallelJobs, WaitsForRunningJobsBeforeRethrowing) {
  Pool pool;
  std::atomic<bool> slow_finished{false};
  EXPECT_THROW(run_parallel(2, 2, pool.progress, pool.done,
                            [&](std::size_t i) {
                              if (i == 0) {
                                std::this_thread::sleep_for(std::chrono::milliseconds(100));
                                slow_finished = true;
                              } else {
                                throw std::runtime_error("fast failure");
                              }
                            }),
               std::runtime_error);
  EXPECT_TRUE(slow_finished) << "returned while a job still ran (its captures would dangle)";
}

}  // namespace
}  // namespace stochnav
