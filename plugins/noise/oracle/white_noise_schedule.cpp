#include "white_noise_schedule.hpp"

#include <algorithm>
#include <functional>
#include <limits>
#include <stdexcept>
#include <utility>

namespace stochnav::oracle {

WhiteNoiseSchedule::WhiteNoiseSchedule(std::vector<double> start_s, std::vector<AxisPsd> psd)
    : start_s_(std::move(start_s)), psd_(std::move(psd)) {
  if (start_s_.empty() || start_s_.size() != psd_.size() ||
      !std::is_sorted(start_s_.begin(), start_s_.end(), std::less_equal<>())) {
    throw std::invalid_argument("WhiteNoiseSchedule: starts must ascend, one PSD per start");
  }
}

std::size_t WhiteNoiseSchedule::piece_of(double t_s) const {
  while (cursor_ + 1 < start_s_.size() && start_s_[cursor_ + 1] <= t_s) ++cursor_;
  while (cursor_ > 0 && start_s_[cursor_] > t_s) --cursor_;
  return cursor_;
}

double WhiteNoiseSchedule::piece_end(std::size_t j) const {
  return j + 1 < start_s_.size() ? start_s_[j + 1] : std::numeric_limits<double>::infinity();
}

void WhiteNoiseSchedule::covariance(double t_s, double dt_s,
                                    Eigen::Ref<Eigen::MatrixXd> q_white) const {
  q_white.setZero();
  const double end = t_s + dt_s;
  std::size_t j = piece_of(t_s);
  if (end <= piece_end(j)) {  // the usual case: dt itself, not (t + dt) - t, for exact sums
    for (int i = 0; i < 3; ++i) q_white(i, i) = psd_[j][static_cast<std::size_t>(i)] * dt_s;
    return;
  }
  double from = t_s;
  // Boundaries inside [t, t + dt] split the integral there.
  while (true) {
    const double to = std::min(end, piece_end(j));
    for (int i = 0; i < 3; ++i) q_white(i, i) += psd_[j][static_cast<std::size_t>(i)] * (to - from);
    if (to >= end) break;
    from = to;
    ++j;
  }
}

}  // namespace stochnav::oracle
