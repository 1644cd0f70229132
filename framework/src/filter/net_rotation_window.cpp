#include "stochnav/filter/net_rotation_window.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace stochnav {

NetRotationWindow::NetRotationWindow(int window_s)
    : per_second_(static_cast<std::size_t>(std::max(window_s, 1)), 0.0) {}

void NetRotationWindow::add(double t_s, double rotation_rad) {
  const auto second = static_cast<std::int64_t>(std::floor(t_s));
  const auto size = static_cast<std::int64_t>(per_second_.size());
  const auto slot = [size](std::int64_t s) {
    return static_cast<std::size_t>(((s % size) + size) % size);
  };
  if (!started_) {
    started_ = true;
    second_ = second;
  } else if (second > second_) {
    // The seconds that left the window make way for the new ones; the sum afresh, so that
    // rounding does not accumulate over a long record.
    const std::int64_t steps = std::min(second - second_, size);
    for (std::int64_t i = 1; i <= steps; ++i) per_second_[slot(second_ + i)] = 0.0;
    second_ = second;
    net_rad_ = std::accumulate(per_second_.begin(), per_second_.end(), 0.0);
  }
  per_second_[slot(second_)] += rotation_rad;
  net_rad_ += rotation_rad;
}

bool NetRotationWindow::rotating() const {
  return std::abs(net_rad_) > 2.0 * std::numbers::pi;
}

}  // namespace stochnav
