#include "stochnav/stats/phase.hpp"

#include <array>
#include <cmath>

#include "stochnav/core/huge_page_buffer.hpp"

namespace stochnav {
namespace {

/// Compensated running sum (Neumaier's method, with Knuth's branch-free TwoSum for the rounding
/// error of each addition): the error stays a few ulps of the result whatever the length, and
/// the only serial dependency is one addition per term.
class CompensatedSum {
 public:
  void add(double value) {
    const double sum = sum_ + value;
    const double value_part = sum - sum_;
    compensation_ += (sum_ - (sum - value_part)) + (value - value_part);
    sum_ = sum;
  }
  double value() const { return sum_ + compensation_; }
  double high() const { return sum_; }
  double low() const { return compensation_; }
  void merge(const CompensatedSum& other) {
    add(other.sum_);
    compensation_ += other.compensation_;
  }

 private:
  double sum_ = 0.0;
  double compensation_ = 0.0;
};

/// The mean as an unevaluated sum high + low: `high` alone, rounded to a double, would leave
/// an error of up to half an ulp that the running sum multiplies by the record length.
struct SplitMean {
  double high = 0.0;
  double low = 0.0;
};

SplitMean compensated_mean(std::span<const double> values) {
  // Four independent lanes, so the additions pipeline.
  std::array<CompensatedSum, 4> lanes;
  std::size_t i = 0;
  for (; i + 4 <= values.size(); i += 4) {
    for (std::size_t lane = 0; lane < 4; ++lane) lanes[lane].add(values[i + lane]);
  }
  for (; i < values.size(); ++i) lanes[0].add(values[i]);
  lanes[0].merge(lanes[1]);
  lanes[2].merge(lanes[3]);
  lanes[0].merge(lanes[2]);
  const double n = static_cast<double>(values.size());
  const double high = lanes[0].value() / n;
  // The remainder of the division, exact up to one rounding: sum - n * high.
  const double remainder = std::fma(-n, high, lanes[0].high()) + lanes[0].low();
  return {high, remainder / n};
}

}  // namespace

std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s) {
  std::vector<double> phase = huge_page_buffer(rate.size() + 1);
  phase.resize(rate.size() + 1);
  phase[0] = 0.0;
  if (rate.empty()) return phase;

  const SplitMean mean = compensated_mean(rate);
  CompensatedSum running;
  double* out = phase.data() + 1;
  for (std::size_t i = 0; i < rate.size(); ++i) {
    running.add(rate[i] - mean.high);
    out[i] = (running.value() - static_cast<double>(i + 1) * mean.low) * tau0_s;
  }
  return phase;
}

}  // namespace stochnav
