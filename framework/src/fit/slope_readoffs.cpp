#include "stochnav/fit/slope_readoffs.hpp"

#include <cmath>
#include <limits>

#include "stochnav/model/closed_forms.hpp"

namespace stochnav {
namespace {

// Lowest line of log-log slope `slope` through the points, as min_i adev_i * tau_i^-slope times
// `factor`.
SlopeReadoff lowest_line(const FitData& data, double slope, double factor) {
  SlopeReadoff readoff{std::numeric_limits<double>::infinity(), 0.0};
  for (std::size_t i = 0; i < data.tau_s.size(); ++i) {
    const double value = factor * std::sqrt(data.avar[i]) * std::pow(data.tau_s[i], -slope);
    if (value < readoff.value) readoff = {value, data.tau_s[i]};
  }
  return readoff;
}

}  // namespace

SlopeReadoffs slope_readoffs(const FitData& data) {
  SlopeReadoffs readoffs;
  readoffs.quantization = lowest_line(data, -1.0, 1.0 / std::sqrt(3.0));
  readoffs.angle_random_walk = lowest_line(data, -0.5, 1.0);
  readoffs.bias_instability =
      lowest_line(data, 0.0, 1.0 / std::sqrt(closed_form::kFlickerFloorPerB2));
  readoffs.rate_random_walk = lowest_line(data, 0.5, std::sqrt(3.0));
  readoffs.rate_ramp = lowest_line(data, 1.0, std::sqrt(2.0));
  return readoffs;
}

}  // namespace stochnav
