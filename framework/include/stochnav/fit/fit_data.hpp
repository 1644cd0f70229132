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
  /// Phase points of the record (rate samples + 1) when the avar are overlapping estimates
  /// (OADEV) with tau_s = m / rate_hz, m integer. Then the fit weighs and correlates the points
  /// with the covariance of the estimates under the fitted model (fit/oadev_covariance.hpp).
  /// 0: unknown; the fit uses `edf` and treats the points as independent.
  std::size_t phase_count = 0;
};

/// Empty when `data` is usable; otherwise the reason, naming the field and index. Requires equal,
/// non-zero lengths, every value finite and > 0, and rate_hz > 0.
std::string validate(const FitData& data);

/// From a deviation table (stats/deviation.hpp) of `kind` kOadev or kAdev whose deviations are
/// in `unit`: avar = (si_per_unit(unit) * deviation)^2. Rows whose deviation is not > 0 or whose
/// edf is not finite and > 0 are left out. For kOadev, phase_count = terms + 2 m. Throws
/// ConfigError for other kinds (MDEV, HDEV, ... are not Allan variances).
FitData fit_data_from_deviations(Deviation kind, std::span<const DeviationPoint> points,
                                 Unit unit, double rate_hz);

/// From Allan deviations already in natural units: avar = adev^2. Spans must have equal lengths
/// (checked later by validate). phase_count: see FitData.
FitData fit_data_from_adev(std::span<const double> tau_s, std::span<const double> adev_natural,
                           std::span<const double> edf, Unit unit, double rate_hz,
                           std::size_t phase_count = 0);

}  // namespace stochnav
