#pragma once
// What the GMWM fit (gmwm_fit.hpp) consumes: a Haar wavelet variance with its 95 % interval,
// from a record (stats/wavelet_variance.hpp, robust_wavelet_variance.hpp) or from a table
// computed elsewhere (the R package `wv`'s tables: read_wavelet_variance_table), in natural
// units.

#include <span>
#include <string>
#include <vector>

#include "stochnav/core/units.hpp"
#include "stochnav/stats/wavelet_variance.hpp"

namespace stochnav {

struct GmwmData {
  std::vector<double> scale_s;  ///< tau_j = 2^j tau0 (s), ascending, > 0
  std::vector<double> wv;       ///< nu^2_j in natural units squared ((rad/s)^2 for gyros), > 0
  std::vector<double> wv_lo;    ///< lower bound of the 95 % interval, same unit, <= wv
  std::vector<double> wv_hi;    ///< upper bound, same unit, > wv
  Unit unit = Unit::kPlain;     ///< the signal's unit: fixes the reporting units only
  double rate_hz = 0.0;         ///< sampling rate of the record (Hz), > 0
  std::string source;           ///< where the numbers come from, for messages
};

/// Empty when usable; otherwise one line naming the problem and how to fix it: fewer than 3
/// scales, unequal lengths, a wavelet variance that is zero everywhere (a constant record), a
/// value not finite or not > 0, an interval not around its value, scales not ascending.
std::string validate(const GmwmData& data);

/// From wavelet-variance levels whose variances are in `unit` squared (as stats/ returns them
/// for a record written in `unit`): multiplied by si_per_unit(unit)^2.
GmwmData gmwm_data_from_levels(std::span<const WaveletVariancePoint> levels, Unit unit,
                               double rate_hz, std::string source);

/// The classical (or, `robust`, the robust) Haar wavelet variance of rate samples in `unit` at
/// rate_hz, as GmwmData. Throws InputError (one line starting with `source`) for fewer than 16
/// samples (under 3 scales) or a constant record.
GmwmData gmwm_data_from_rate(std::span<const double> rate, double rate_hz, Unit unit, bool robust,
                             const std::string& source);

/// Reads a wavelet-variance table: CSV with a header naming `scale_s`, `wv` and the interval as
/// `ci_low`, `ci_high` (the `wv` package's tables) or `wv_lo`, `wv_hi` (`stochnav wv --format
/// csv`); text cells may be quoted. With a `channel` column, `channel` selects the rows (it must
/// be given when the table holds more than one); with a `freq` column, the rate comes from it
/// unless rate_hz > 0 is given, otherwise rate_hz (> 0) is required. Values are in `unit`
/// squared. Throws InputError (one line: file, line or column, how to fix) for a missing file
/// or column, an unknown channel, a bad cell.
GmwmData read_wavelet_variance_table(const std::string& path, const std::string& channel, Unit unit,
                                     double rate_hz);

}  // namespace stochnav
