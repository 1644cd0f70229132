#pragma once
// A progress bar on standard error for long runs, drawn only when standard error is a terminal
// and at most ten times a second, so that it costs nothing in the hot loop.

#include <chrono>
#include <cstdint>
#include <string>

namespace stochnav {

class ProgressBar final {
 public:
  /// `total`: units of work (0 when unknown: the bar shows a count instead). Draws nothing
  /// when `enabled` is false or standard error is not a terminal.
  ProgressBar(std::string label, std::uint64_t total, bool enabled = true);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Reports `done` units; cheap unless a redraw is due.
  void update(std::uint64_t done) {
    if (active_ && (++calls_ & 0x3FF) == 0) draw(done, false);
  }
  /// Redraws now if the last draw is older than 0.1 s (for a thread that only draws).
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
  bool finished_ = false;
  std::uint64_t calls_ = 0;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace stochnav
