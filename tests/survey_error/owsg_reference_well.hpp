#pragma once
// The test well and site of owsg_gyro_reference.py, shared by the OWSG gyro tool model tests:
// 30 m stations, vertical to 300 m, a build of 2 deg / 30 m turning from azimuth 30 to 78 deg
// up to 50 deg, a hold to 2400 m (81 stations); latitude 60 deg, 15.041 deg/h, 9.80665 m/s^2.

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "stochnav/core/angles.hpp"
#include "stochnav/survey_error/tool_models.hpp"

namespace stochnav::survey_error::testing {

inline std::vector<ListingStation> reference_well() {
  std::vector<ListingStation> stations;
  for (int k = 0; k <= 80; ++k) {
    const int build = std::clamp(k - 10, 0, 25);
    stations.push_back({30.0 * k, 2.0 * build * kRadPerDeg, (30.0 + 2.0 * build) * kRadPerDeg});
  }
  return stations;
}

inline WellParameters reference_site() {
  WellParameters well;
  well.latitude_rad = 60.0 * kRadPerDeg;
  well.earth_rate_rad_s = 15.041 * kRadPerDeg / 3600.0;
  well.gravity_m_s2 = 9.80665;
  return well;
}

/// The source `code` of a model's covariance; throws std::out_of_range when it has none.
inline const SourceCovariance& source_named(const SurveyCovariance& covariance,
                                            const std::string& code) {
  const auto found =
      std::find_if(covariance.sources.begin(), covariance.sources.end(),
                   [&](const SourceCovariance& source) { return source.code == code; });
  if (found == covariance.sources.end()) throw std::out_of_range("no source " + code);
  return *found;
}

}  // namespace stochnav::survey_error::testing
