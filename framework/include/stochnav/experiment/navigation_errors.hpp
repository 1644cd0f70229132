#pragma once
// Navigation errors against truth, and their summary statistics: the metrics of `stochnav run`
// (DIR/metrics.json) and `stochnav compare` (results.json), named as DESIGN.md and the paper's
// Table 3 (maximum absolute error).

#include <array>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string_view>

#include "stochnav/ins/mwd_attitude.hpp"
#include "stochnav/ins/nav_state.hpp"

namespace stochnav {

/// The error metrics, in this order everywhere (metrics.json, errors.csv, results.json).
inline constexpr std::array<std::string_view, 9> kErrorMetricNames = {
    "lat_err_m",           "lon_err_m",        "height_err_m",
    "inclination_err_deg", "toolface_err_deg", "azimuth_err_deg",
    "ve_err_mps",          "vn_err_mps",       "vu_err_mps"};
inline constexpr std::size_t kErrorMetricCount = kErrorMetricNames.size();

/// Estimate - truth for each metric: north and east position errors in metres (on the
/// ellipsoid's radii at the true position), height (m), MWD angles in degrees wrapped to
/// (-180, 180], ENU velocities (m/s). Where the hole is near vertical (true inclination below
/// `vertical_inclination_deg`) toolface and azimuth errors are individually undefined: both
/// are reported as NaN and left out of the statistics.
std::array<double, kErrorMetricCount> navigation_errors(const NavState& estimate,
                                                       const NavState& truth,
                                                       double vertical_inclination_deg = 1.0);

/// The filter's 1-sigma of each metric, from the covariance of the first nine core error
/// states (dr ENU m, dv ENU m/s, phi rad; plugin/state_layout.hpp), in the metrics' units. The
/// MWD angles' sigmas come from linearising the angles about `estimate` (numerically); NaN for
/// toolface and azimuth near vertical, as in navigation_errors.
std::array<double, kErrorMetricCount> navigation_error_sigmas(
    const NavState& estimate, const Eigen::Matrix<double, 9, 9>& covariance,
    double vertical_inclination_deg = 1.0);

/// Running maximum absolute value and RMS of each metric, NaNs skipped.
class ErrorStatistics final {
 public:
  void add(const std::array<double, kErrorMetricCount>& errors);

  double max_abs(std::size_t metric) const { return max_abs_[metric]; }
  double rms(std::size_t metric) const;
  std::size_t count(std::size_t metric) const { return count_[metric]; }
  double sum_squares(std::size_t metric) const { return sum_squares_[metric]; }

  /// Statistics with exactly these parts (as max_abs, sum_squares and count return them): a
  /// run's statistics read back from a file (experiment/run_result_json.hpp).
  static ErrorStatistics from_parts(const std::array<double, kErrorMetricCount>& max_abs,
                                    const std::array<double, kErrorMetricCount>& sum_squares,
                                    const std::array<std::size_t, kErrorMetricCount>& count);

  /// {"lat_err_m": {"max_abs": x, "rms": y, "samples": n}, ...}; metrics with no sample have
  /// null values.
  nlohmann::json to_json() const;

 private:
  std::array<double, kErrorMetricCount> max_abs_{};
  std::array<double, kErrorMetricCount> sum_squares_{};
  std::array<std::size_t, kErrorMetricCount> count_{};
};

}  // namespace stochnav
