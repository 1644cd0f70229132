#pragma once
// Minimum curvature as a client recomputes a survey listing: the textbook closed form
// (experiment/survey.hpp states it), written here independently of the library's
// minimum_curvature_path, so that a test comparing the two checks the listing, not the code
// against itself.

#include <cmath>
#include <numbers>
#include <vector>

namespace stochnav::testing {

/// One listed station: MD (m), inclination and azimuth (deg).
struct ListedStation {
  double md_m;
  double inclination_deg;
  double azimuth_deg;
};

/// A position from the tie-on: north, east, TVD positive down (m).
struct ListedPosition {
  double north_m = 0.0;
  double east_m = 0.0;
  double tvd_m = 0.0;
};

/// Positions of `stations` from the tie-on `tie_on` (its MD and attitude) at (0, 0, 0):
///   beta = acos(cos(I2 - I1) - sin I1 sin I2 (1 - cos(A2 - A1))), RF = 2/beta tan(beta/2),
///   dN = dMD/2 (sin I1 cos A1 + sin I2 cos A2) RF, dE = ... sin A, dTVD = dMD/2 (cos I1 +
///   cos I2) RF.
inline std::vector<ListedPosition> client_minimum_curvature(
    const ListedStation& tie_on, const std::vector<ListedStation>& stations) {
  constexpr double kRad = std::numbers::pi / 180.0;
  std::vector<ListedPosition> positions;
  ListedPosition at;
  ListedStation previous = tie_on;
  for (const ListedStation& s : stations) {
    const double i1 = previous.inclination_deg * kRad, a1 = previous.azimuth_deg * kRad;
    const double i2 = s.inclination_deg * kRad, a2 = s.azimuth_deg * kRad;
    const double cos_beta =
        std::cos(i2 - i1) - std::sin(i1) * std::sin(i2) * (1 - std::cos(a2 - a1));
    const double beta = std::acos(std::fmin(1.0, std::fmax(-1.0, cos_beta)));
    const double ratio = beta < 1e-7 ? 1.0 + beta * beta / 12.0 : 2.0 / beta * std::tan(beta / 2);
    const double half_step_m = (s.md_m - previous.md_m) / 2.0 * ratio;
    at.north_m += half_step_m * (std::sin(i1) * std::cos(a1) + std::sin(i2) * std::cos(a2));
    at.east_m += half_step_m * (std::sin(i1) * std::sin(a1) + std::sin(i2) * std::sin(a2));
    at.tvd_m += half_step_m * (std::cos(i1) + std::cos(i2));
    positions.push_back(at);
    previous = s;
  }
  return positions;
}

}  // namespace stochnav::testing
