#pragma once
// Progress of long runs on standard error. On a terminal: a bar redrawn in place at most ten
// times a second. Otherwise (a log file, a batch job): a plain line "label: 42.0 %, 95 s
// elapsed, ETA 131 s" at most every 30 s, and a last one at finish when any was printed before
// (a run shorter than 30 s prints nothing). Either way update() costs a counter increment
// between checks of the clock, so it costs nothing in the hot loop.

#include <chrono>
#include <cstdint>
#include <string>

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

}  // namespace stochnav
