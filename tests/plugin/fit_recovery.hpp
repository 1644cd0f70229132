#pragma once
// Fit-recovery tests: simulated calibration records, and the summary of a parameter recovered
// from many of them.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <vector>

#include "stochnav/model/noise_model.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"
#include "stochnav/sim/noise_generator.hpp"

namespace stochnav::plugin::testing {

/// A gyro calibration record of three axes simulated from `model`, axis i with seed
/// first_seed + i.
inline CalibrationRecord simulated_record(const NoiseModel& model, double duration_s,
                                          std::uint64_t first_seed) {
  CalibrationRecord record;
  record.group = SensorGroup::kGyro;
  record.rate_hz = model.rate_hz;
  record.source = "simulated";
  for (std::size_t axis = 0; axis < 3; ++axis) {
    record.axes[axis] = simulate_noise(model, duration_s, model.rate_hz, first_seed + axis);
  }
  return record;
}

struct Recovery {
  double mean = 0.0;
  double std = 0.0;     ///< sample standard deviation of the estimates
  double within = 0.0;  ///< fraction of the estimates within the tolerance of the truth
};

inline Recovery recovery(const std::vector<double>& estimates, double truth, double tolerance) {
  const auto count = static_cast<double>(estimates.size());
  Recovery r;
  for (double x : estimates) r.mean += x / count;
  for (double x : estimates) {
    r.std += (x - r.mean) * (x - r.mean) / (count - 1.0);
    r.within += std::abs(x - truth) <= tolerance ? 1.0 / count : 0.0;
  }
  r.std = std::sqrt(r.std);
  return r;
}

/// The recovery checks: the mean within three standard errors of the truth or 1 % of it (no
/// bias that matters), and at least 90 % of the estimates within `tolerance`. Prints the summary.
inline void expect_recovered(const char* name, const std::vector<double>& estimates, double truth,
                             double tolerance) {
  const Recovery r = recovery(estimates, truth, tolerance);
  std::printf("%s: true %g, mean %g, std %g, within %g: %.0f %%\n", name, truth, r.mean, r.std,
              tolerance, 100.0 * r.within);
  const double standard_error = r.std / std::sqrt(static_cast<double>(estimates.size()));
  EXPECT_NEAR(r.mean, truth, std::max(3.0 * standard_error, 0.01 * std::abs(truth))) << name;
  EXPECT_GE(r.within, 0.9) << name;
}

}  // namespace stochnav::plugin::testing
