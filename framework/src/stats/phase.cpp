#include "stochnav/stats/phase.hpp"

#include <cmath>

namespace stochnav {
namespace {

/// Neumaier's variant of Kahan summation: also exact when an addend is larger than the sum,
/// which happens all the time in a zero-mean running sum.
class NeumaierSum {
 public:
  void add(double value) {
    const double sum = sum_ + value;
    // The branch-free form of "low-order bits lost from whichever operand is smaller".
    const bool sum_is_larger = std::abs(sum_) >= std::abs(value);
    const double large = sum_is_larger ? sum_ : value;
    const double small = sum_is_larger ? value : sum_;
    compensation_ += (large - sum) + small;
    sum_ = sum;
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0.0;
  double compensation_ = 0.0;
};

}  // namespace

std::vector<double> phase_from_rate(std::span<const double> rate, double tau0_s) {
  std::vector<double> phase(rate.size() + 1);
  phase[0] = 0.0;
  if (rate.empty()) return phase;

  NeumaierSum total;
  for (double y : rate) total.add(y);
  const double mean = total.value() / static_cast<double>(rate.size());

  NeumaierSum running;
  for (std::size_t i = 0; i < rate.size(); ++i) {
    running.add(rate[i] - mean);
    phase[i + 1] = running.value() * tau0_s;
  }
  return phase;
}

}  // namespace stochnav
