#pragma once
// Records simulated from a noise model, for the diagnose tests.

#include <cstdint>

#include "stochnav/io/record.hpp"
#include "stochnav/model/reporting_units.hpp"
#include "stochnav/model/noise_model.hpp"
#include "stochnav/sim/noise_generator.hpp"

namespace stochnav::diagnose_testing {

/// A gyro term's coefficient given in its reporting unit (deg/sqrt(h), deg/h, ...) in SI.
inline double natural(ParameterDimension dimension, double reported) {
  return to_natural(Quantity::kAngularRate, dimension, reported);
}

/// `samples` samples of `truth` at rate_hz, written in the model's unit.
inline Record simulated_record(const NoiseModel& truth, std::size_t samples, double rate_hz,
                               std::uint64_t seed) {
  Record record;
  record.rate_hz = rate_hz;
  record.unit = truth.unit;
  record.kind = DataKind::kRate;
  record.source = "simulated";
  record.column = "value";
  record.values = simulate_noise(truth, static_cast<double>(samples) / rate_hz, rate_hz, seed);
  const double per_natural = 1.0 / si_per_unit(truth.unit);
  for (double& value : record.values) value *= per_natural;
  return record;
}

}  // namespace stochnav::diagnose_testing
