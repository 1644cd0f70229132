#pragma once
// What the OWSG gyro tool model tests share with owsg_gyro_reference.py: its test well (30 m
// stations, vertical to 300 m, a build of 2 deg / 30 m turning from azimuth 30 to 78 deg up to
// 50 deg, a hold to 2400 m: 81 stations), its site (latitude 60 deg, 15.041 deg/h, 9.80665
// m/s^2), and the comparison of a model's covariance with the script's output.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
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

/// One row of owsg_gyro_reference.py's output: a source's NN, EE, VV, NE, NV, EV (m^2) at a
/// station.
struct ReferenceCovariance {
  const char* code;
  std::size_t station;
  std::array<double, 6> nev;
};

/// Checks `covariance` against the script's rows: every element within 1e-10 of the station's
/// largest variance (the reference's own rounding is 1e-17). Returns the largest error relative
/// to that variance.
inline double largest_error_against(const SurveyCovariance& covariance,
                                    std::span<const ReferenceCovariance> reference,
                                    const std::string& label) {
  double largest_relative = 0.0;
  for (const ReferenceCovariance& row : reference) {
    const Eigen::Matrix3d& c = source_named(covariance, row.code).nev_m2.at(row.station);
    const std::array<double, 6> found = {c(0, 0), c(1, 1), c(2, 2), c(0, 1), c(0, 2), c(1, 2)};
    const double scale = std::max({row.nev[0], row.nev[1], row.nev[2]});
    for (std::size_t i = 0; i < 6; ++i) {
      const double error = std::abs(found[i] - row.nev[i]);
      largest_relative = std::max(largest_relative, error / scale);
      EXPECT_LE(error, 1e-10 * scale)
          << label << " " << row.code << " station " << row.station << " element " << i;
    }
  }
  return largest_relative;
}

}  // namespace stochnav::survey_error::testing
