#include "stochnav/experiment/tally_smoother.hpp"

#include <cmath>
#include <limits>

namespace stochnav {

void StationaryDepthMean::add(double md_m) {
  if (!std::isfinite(md_m)) return;
  if (count_ == 0) first_m_ = md_m;
  // About the first reading: a sum of km-sized depths would lose the millimetres.
  sum_of_offsets_m_ += md_m - first_m_;
  ++count_;
}

void StationaryDepthMean::reset() { *this = StationaryDepthMean{}; }

double StationaryDepthMean::mean_m() const {
  if (count_ == 0) return std::numeric_limits<double>::quiet_NaN();
  return first_m_ + sum_of_offsets_m_ / static_cast<double>(count_);
}

double StationaryDepthMean::sigma_m(const DepthReadingSigma& sigma, double tie_on_md_m) const {
  if (count_ == 0) return std::numeric_limits<double>::quiet_NaN();
  const double random_part_m2 = sigma.random_m * sigma.random_m / static_cast<double>(count_);
  const double scale_part_m = sigma.scale * (mean_m() - tie_on_md_m);
  return std::sqrt(random_part_m2 + scale_part_m * scale_part_m);
}

}  // namespace stochnav
