#pragma once
// The thread pool of `stochnav compare`: independent jobs (a seed's simulation, one variant on
// one seed) spread over worker threads.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>

#include "stochnav/core/progress_bar.hpp"

namespace stochnav {

/// Runs job(0) .. job(count - 1), each exactly once, on min(threads, count) workers (at least
/// one; the calling thread is one of them), handing out indices in increasing order. `done` is
/// incremented once per finished job (successful or not) and drawn on `progress` by a helper
/// thread until the last job finishes. When a job throws, no further job is started; the jobs
/// already running finish, and then the first exception (in time) is rethrown on the calling
/// thread. Returns when every started job has finished.
void run_parallel(std::size_t count, unsigned threads, ProgressBar& progress,
                  std::atomic<std::uint64_t>& done, const std::function<void(std::size_t)>& job);

}  // namespace stochnav
