#pragma once
// Wall-clock timing for the benchmark programs: best of several runs.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <functional>
#include <limits>
#include <string>

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

/// Seconds of the whole process `'cli' arguments` (best of `repeats`), output discarded; a
/// non-zero exit is reported on standard output.
inline double cli_seconds(const std::string& cli, const std::string& arguments, int repeats = 3) {
  const std::string command = "'" + cli + "' " + arguments + " > /dev/null";
  return best_seconds(
      [&] {
        if (std::system(command.c_str()) != 0) fmt::print("failed: {}\n", command);
      },
      repeats);
}

}  // namespace stochnav::bench
