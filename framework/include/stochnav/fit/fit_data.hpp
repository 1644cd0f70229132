#pragma once
// What fit_noise_terms consumes: a measured Allan-variance curve with its equivalent degrees of
// freedom, in natural units.

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "stochnav/core/units.hpp"
#include "stochnav/stats/deviation.hpp"

namespace stochnav {

struct FitData {
  std::vector<double> tau_s;  ///< averaging times (s), > 0
  /// Allan variance at each tau in natural units squared: (rad/s)^2 for gyros, (m/s^2)^2 for
  /// accelerometers, signal^2 for plain data; > 0.
  std::vector<double> avar;
  std::vector<double> edf;   ///< equivalent degrees of freedom of each avar, > 0
  Unit unit = Unit::kPlain;  ///< the signal's unit: fixes the reporting units of the result only
  double rate_hz = 0.0;      ///< sampling rate of the record (Hz), > 0: recorded in the model
};

/// Empty when `data` is usable; otherwise the reason, naming the field and index. Requires equal,
/// non-zero lengths, every value finite and > 0, and rate_hz > 0.
std::string validate(const FitData& data);

/// From an ADEV or OADEV table (stats/deviation.hpp) whose deviations are in `unit`:
/// avar = (si_per_unit(unit) * deviation)^2. Rows whose deviation is not > 0 or whose edf is not
/// finite and > 0 are left out. Other deviation kinds (MDEV, HDEV, ...) are not Allan variances
/// and must not be passed.
FitData fit_data_from_deviations(std::span<const DeviationPoint> points, Unit unit,
                                 double rate_hz);

/// From Allan deviations already in natural units: avar = adev^2. Spans must have equal lengths
/// (checked later by validate).
FitData fit_data_from_adev(std::span<const double> tau_s, std::span<const double> adev_natural,
                           std::span<const double> edf, Unit unit, double rate_hz);

}  // namespace stochnav
