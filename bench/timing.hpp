#pragma once
// Wall-clock timing for the benchmark programs: best of several runs.

#include <algorithm>
#include <chrono>
#include <functional>
#include <limits>

namespace stochnav::bench {

/// Runs `work` `repeats` times and returns the shortest wall time in seconds.
inline double best_seconds(const std::function<void()>& work, int repeats = 3) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    work();
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    best = std::min(best, elapsed.count());
  }
  return best;
}

}  // namespace stochnav::bench
