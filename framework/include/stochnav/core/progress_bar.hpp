#pragma once
// Progress of long runs on standard error. On a terminal: a bar redrawn in place at most ten
// times a second. Otherwise (a log file, a batch job): a plain line "label: 42.0 %, 95 s
// elapsed, ETA 131 s" at most every 30 s, and a last one at finish when any was printed before
// (a run shorter than 30 s prints nothing). Either way update() costs a counter increment
// between checks of the clock, so it costs nothing in the hot loop.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace stochnav {

class ProgressBar final {
 public:
  /// `total`: units of work (0 when unknown: a count is shown instead, no ETA). Prints nothing
  /// when `enabled` is false.
  ProgressBar(std::string label, std::uint64_t total, bool enabled = true);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Reports `done` units; cheap unless a redraw is due.
  void update(std::uint64_t done) {
    if (active_ && (++calls_ & 0x3FF) == 0) draw(done, false);
  }
  /// Draws now if the last draw is old enough (0.1 s on a terminal, 30 s otherwise; for a
  /// thread that only draws).
  void show(std::uint64_t done) {
    if (active_) draw(done, false);
  }
  /// Draws the final state and ends the line.
  void finish(std::uint64_t done);

 private:
  void draw(std::uint64_t done, bool last);

  std::string label_;
  std::uint64_t total_;
  bool active_;
  bool terminal_;
  bool finished_ = false;
  bool printed_ = false;  // a plain line was printed (not a terminal)
  std::uint64_t calls_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

/// True when standard error is a terminal. The commands that print their result on standard
/// output (allan, davar, fit, diagnose) show progress only then: never into a pipe, a file or a
/// test's capture, where a plain progress line would mix with what a script reads.
bool standard_error_is_terminal();

/// A ProgressBar drawn by a thread of its own from a counter the work adds to: for work inside
/// library calls and parallel tasks, which add to counter() once per block, window or stage (a
/// relaxed atomic addition) and know nothing else of the display. The thread wakes every 0.1 s;
/// the bar redraws at its own pace. Disabled: no thread, nothing drawn, counter() is nullptr.
class ProgressTicker final {
 public:
  ProgressTicker(std::string label, std::uint64_t total, bool enabled);
  /// Stops the thread (the bar ends its line if finish() was not called: an error follows).
  ~ProgressTicker();
  ProgressTicker(const ProgressTicker&) = delete;
  ProgressTicker& operator=(const ProgressTicker&) = delete;

  /// The counter of units done; nullptr when disabled (the work then counts nothing).
  std::atomic<std::uint64_t>* counter() { return enabled_ ? &done_ : nullptr; }
  /// Stops the thread and draws the final state (`total` units done when total > 0).
  void finish();

 private:
  void stop();

  ProgressBar bar_;
  std::uint64_t total_;
  bool enabled_;
  std::atomic<std::uint64_t> done_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace stochnav
