#pragma once
// What the ISCWSA survey error models need to know about a well besides its listing: the
// geomagnetic field and gravity at the site, the azimuth reference of the listing and the
// near-vertical limit. The CLI reads them from a well JSON (survey_error/survey_inputs.hpp);
// here they are plain SI values.

#include <optional>

#include "stochnav/core/angles.hpp"

namespace stochnav::survey_error {

/// Which north the listing's azimuths, and the output's N and E axes, refer to.
enum class AzimuthReference {
  kTrue,  ///< true (geographic) north
  kGrid,  ///< grid north: true azimuth = grid azimuth + convergence
};

struct WellParameters {
  double latitude_rad = 0.0;      ///< geodetic latitude (rad); gyro models only
  double b_total_nT = 50000.0;    ///< total geomagnetic field intensity (nT), > 0
  double dip_rad = 0.0;           ///< magnetic dip, positive down (rad), |dip| < pi/2
  double declination_rad = 0.0;   ///< magnetic declination: true = magnetic + declination (rad)
  double convergence_rad = 0.0;   ///< grid convergence: true = grid + convergence (rad)
  double gravity_m_s2 = 9.80665;  ///< gravity field strength (m/s^2), > 0
  double earth_rate_rad_s = 7.292115e-5;      ///< Earth rotation rate (rad/s); gyro models only
  double vertical_section_azimuth_rad = 0.0;  ///< listing convention; not used by the MWD models
  /// Stations with inclination below this (rad) are near vertical: the weighting functions with
  /// a 1/sin(I) azimuth term take their near-vertical (singular) forms there.
  double vertical_inc_limit_rad = 1.0e-4 * kRadPerDeg;
  AzimuthReference azimuth_reference = AzimuthReference::kTrue;
  /// TVD of the listing's first station (the tie-on), m, for the depth-stretch term DSTG
  /// (MD x TVD). Needed when the listing does not start at the surface (MD 0, TVD 0).
  std::optional<double> tie_on_tvd_m;
};

}  // namespace stochnav::survey_error
