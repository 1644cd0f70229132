#pragma once
// The worker threads of the statistics engine (Allan-family sums, noise identification, DAVAR,
// record parsing): a small persistent pool that runs independent tasks.
//
// Determinism contract: callers split their work into tasks whose boundaries depend only on the
// data (record length, averaging factors), never on the thread count, and combine the per-task
// results in task order. Results are therefore bitwise identical with 1, 2 or 64 threads.

#include <cstddef>
#include <functional>

namespace stochnav {

/// Threads the engine uses (>= 1): set_stats_thread_count, else the environment variable
/// STOCHNAV_THREADS (a positive integer), else std::thread::hardware_concurrency().
std::size_t stats_thread_count();

/// Overrides the thread count for later calls; 0 restores the default above. Not to be called
/// while a parallel_for runs.
void set_stats_thread_count(std::size_t threads);

/// Runs task(i) for every i in [0, count), spread over stats_thread_count() threads (the caller
/// is one of them), and returns when all have finished. Tasks must be independent. If tasks
/// throw, the exception of the lowest-numbered failing task is rethrown once all have finished
/// (later tasks still run). Called from inside a task, or while another thread uses the pool, the
/// tasks run on the calling thread in order (no deadlock, same results).
void parallel_for(std::size_t count, const std::function<void(std::size_t)>& task);

}  // namespace stochnav
