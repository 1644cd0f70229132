#pragma once
// What diagnose measures on a record, once: overlapping Allan deviations with confidence
// intervals (octave taus for the gap, dense taus for the fits and plots) and the short-tau
// variances of its windows (the stationarity test).

#include <cstddef>
#include <vector>

#include "stochnav/diagnose/gap.hpp"
#include "stochnav/diagnose/stationarity.hpp"
#include "stochnav/fit/fit_data.hpp"
#include "stochnav/io/record.hpp"
#include "stochnav/stats/deviation.hpp"

namespace stochnav {

struct MeasuredStatistics {
  Unit unit = Unit::kPlain;  ///< the record's unit (deviations below are in it)
  double rate_hz = 0.0;
  std::size_t samples = 0;             ///< rate samples
  double duration_s = 0.0;             ///< samples / rate_hz
  std::vector<DeviationPoint> octave;  ///< OADEV, octave m, record unit, 68.3 % intervals
  std::vector<DeviationPoint> dense;   ///< OADEV, dense m, record unit
  AvarMeasurement octave_avar;         ///< the octave points in natural units (the gap's input)
  FitData dense_fit;                   ///< the dense points in natural units, Greenhall edf (fits)
  WindowVariances windows;             ///< stationarity windows
};

/// Measures a rate or phase record (phase records are differenced to rates for the windows).
/// Throws InputError when the record is too short for at least 4 octave taus (about 20 samples).
MeasuredStatistics measure_record(const Record& record, std::size_t windows);

/// The record's rate samples in natural units (differenced when it holds phase).
std::vector<double> natural_rate(const Record& record);

}  // namespace stochnav
