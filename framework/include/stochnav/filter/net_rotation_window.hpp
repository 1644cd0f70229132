#pragma once
// The tool's net rotation about its own axis (body z) over a sliding window of the record's
// time: whether it is rotating as a drill string does, for the east-west mirror
// (heading_hypotheses.cpp), which is a rotating tool's.
//
// The rule is one full turn, net, within the window (default 600 s): any steady rotation faster
// than one turn per window counts (0.1 rpm for 10 min; drilling rotates at 20-180 rpm and is
// counted within 3 s), while a slide's orientation to its toolface (at most half a turn, once
// per slide) and rocking (back and forth, net zero) do not. A tool that stops rotating still
// counts for up to one window.
//
// The rotation is summed per whole second of the record's time (t_s), the window holding one
// sum per second: constant memory, one pass over the window per second of record. Times that
// go backwards are counted in the current second.

#include <cstdint>
#include <vector>

namespace stochnav {

class NetRotationWindow {
 public:
  explicit NetRotationWindow(int window_s = 600);

  /// The rotation about the tool axis over the epoch ending at `t_s` (rad, signed).
  void add(double t_s, double rotation_rad);
  /// The net rotation within the window (rad, signed).
  double net_rad() const { return net_rad_; }
  /// Whether the net rotation within the window exceeds one full turn.
  bool rotating() const;

 private:
  std::vector<double> per_second_;  // rad, one slot per second of the window, as a ring
  std::int64_t second_ = 0;         // the second the latest epoch fell in
  bool started_ = false;
  double net_rad_ = 0.0;
};

}  // namespace stochnav
