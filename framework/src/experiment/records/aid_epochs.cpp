#include "stochnav/experiment/aid_epochs.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "stochnav/core/errors.hpp"
#include "stochnav/plugin/aid_schedule.hpp"

namespace stochnav {
namespace {
constexpr double kTolerance_s = plugin::kEpochMatchTolerance_s;
constexpr double kMinimumSpacing_periods = 1.5;
}  // namespace

AidEpochs::AidEpochs(plugin::AidData& data, double imu_period_s)
    : data_(data), period_s_(imu_period_s) {
  const auto t = data_.time_s();
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (t[i] - t[i - 1] < kMinimumSpacing_periods * period_s_ - kTolerance_s) {
      throw InputError(fmt::format(
          "{}: rows {} and {} are {:.6g} s apart (t = {:.9g} and {:.9g} s), less than 1.5 IMU "
          "periods ({:.6g} s): an aid row is applied at the IMU epoch at or after it, one per "
          "epoch; thin the aid data or merge the rows",
          data_.source(), i + 1, i + 2, t[i] - t[i - 1], t[i - 1], t[i],
          kMinimumSpacing_periods * period_s_));
    }
  }
}

void AidEpochs::advance_to(double t_s) {
  const auto t = data_.time_s();
  if (!started_) {
    started_ = true;
    // Rows before the first epoch's own period belong to the span before navigation started.
    while (next_ < t.size() && t[next_] <= t_s - period_s_ + kTolerance_s) {
      ++before_start_;
      ++next_;
    }
  }
  if (next_ < t.size() && t[next_] <= t_s + kTolerance_s) {
    const double offset = t_s - t[next_];
    if (std::abs(offset) <= kTolerance_s) {
      ++on_grid_;
    } else {
      ++moved_;
      max_offset_s_ = std::max(max_offset_s_, offset);
      data_.move_row_time(next_, t_s);
    }
    ++next_;
  }
}

void AidEpochs::finish() {
  after_end_ += data_.rows() - next_;
  next_ = data_.rows();
}

nlohmann::json AidEpochs::summary_json() const {
  return {
      {"rows", data_.rows()},          {"on_grid", on_grid_},           {"moved", moved_},
      {"max_offset_s", max_offset_s_}, {"before_start", before_start_}, {"after_end", after_end_}};
}

}  // namespace stochnav
