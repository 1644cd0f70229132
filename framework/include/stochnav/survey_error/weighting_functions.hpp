#pragma once
// The ISCWSA weighting functions: for one error source at one survey station, the change of the
// station's measured depth, inclination and azimuth per unit of the source (the derivatives
// dMD/de, dI/de, dA/de of the ISCWSA MWD Rev5 document, SPE 67616 appendix; the accelerometer
// and gyrocompass functions of the OWSG gyro tool models GYRO-NS-CT, GYRO-NS and GYRO-MWD, after
// SPE 90408).
//
// The azimuth derivative is returned multiplied by sin(I) (`lateral_rad`): the angle by which the
// error turns the hole direction horizontally, since dt/dA = sin(I) h for the unit hole
// direction t and the horizontal unit vector h = (-sin A, cos A, 0) in NEV. Several ISCWSA
// azimuth weights contain 1/sin(I) (ABXY-TI2, XYM3, XYM4, XYM3E, XYM4E, XCLA) and diverge
// near vertical, while sin(I) dA/de stays finite; at a station below the well's
// vertical_inc_limit those sources take their near-vertical ("singular") forms, which are the
// same expressions at I = 0: a pure sideways tilt of the hole, e.g. XYM3 tilts it north by its
// magnitude, XYM4 east, ABXY-TI2 by 1/G along h.
//
// Angles: inclination I from vertical down, [0, pi]; azimuths clockwise from north. AzT (true)
// orients the misalignment and tortuosity terms and the NEV frame; AzM = AzT - declination
// (magnetic) enters the sensor terms.

#include "stochnav/survey_error/error_model.hpp"
#include "stochnav/survey_error/well_parameters.hpp"

namespace stochnav::survey_error {

/// One station as the weighting functions see it (SI units).
struct StationGeometry {
  double md_m = 0.0;                  ///< measured depth (m)
  double tvd_m = 0.0;                 ///< true vertical depth (m), for DSTG
  double inclination_rad = 0.0;       ///< I
  double true_azimuth_rad = 0.0;      ///< AzT
  double magnetic_azimuth_rad = 0.0;  ///< AzM = AzT - declination
  /// The previous station (XYM3E/XYM4E scale with the interval, XCLA/XCLH with the change over
  /// it). At the first station, the same values as this one.
  double previous_md_m = 0.0;
  double previous_inclination_rad = 0.0;
  double previous_true_azimuth_rad = 0.0;
};

/// The change of a station's survey per unit of an error source.
struct ErrorWeights {
  double depth_m = 0.0;          ///< dMD/de (m per unit)
  double inclination_rad = 0.0;  ///< dI/de (rad per unit)
  double lateral_rad = 0.0;      ///< sin(I) dA/de (rad per unit): the horizontal turn of the hole
};

/// Which part of the well path an error at a station moves.
enum class LegReach {
  /// The station's survey is wrong: the halves of the legs before and after the station that
  /// the balanced-tangential form of minimum curvature assigns to its direction move, and an MD
  /// error lengthens the leg before and shortens the leg after (ISCWSA document, eq. for
  /// dr_k/dp_k and dr_(k+1)/dp_k).
  kHalfLegsAround,
  /// The path between the previous station and this one bends unseen (XCLA, XCLH): the whole
  /// leg before the station turns, the legs after it do not.
  kWholeLegBefore,
};

/// The reach of a weighting function: kWholeLegBefore for kXcla and kXclh, else kHalfLegsAround.
LegReach leg_reach(WeightingFunction function);

/// Whether the function's azimuth weight contains 1/sin(I), so that it has a near-vertical
/// form (used below WellParameters::vertical_inc_limit_rad): kAbxyTi2, kXym3, kXym4, kXym3e,
/// kXym4e, kXcla.
bool has_near_vertical_form(WeightingFunction function);

/// Whether `function` is a stationary gyrocompass term (kGxyB1, kGxyB2, kGxyG1, kGxyG4,
/// kGxyRn), whose azimuth error a continuous survey carries forward from its initialising
/// station (SurveyErrorModel::continuous_start_inclination_rad).
bool is_gyrocompass_weighting(WeightingFunction function);

/// dA/de of a gyrocompass term at `station` (rad of azimuth per rad/s of gyro error, i.e. s),
/// with Omega = well.earth_rate_rad_s and lat = well.latitude_rad:
///   kGxyB1  sin AzT / (Omega cos(lat) cos I)
///   kGxyB2  cos AzT / (Omega cos(lat))
///   kGxyG1  cos AzT sin I / (Omega cos(lat))
///   kGxyG4  sin AzT tan I / (Omega cos(lat))
///   kGxyRn  sqrt(1 - cos^2 AzT sin^2 I) / (Omega cos(lat) cos I), per unit of the rate noise
///           after the noise reduction factor (the OWSG weight divided by NRF; the caller
///           multiplies by NRF: SurveyErrorModel::noise_reduction_factor, continuous_gyro.hpp)
/// Requires is_gyrocompass_weighting(function) (else 0), I < pi/2, Omega > 0 and
/// |lat| < pi/2 (the caller checks; the values diverge there).
double gyrocompass_azimuth_weight_s(WeightingFunction function, const StationGeometry& station,
                                    const WellParameters& well);

/// The weights of `function` at `station`. `tortuosity_rad_per_m`: the model's default
/// tortuosity (XCLA, XCLH). The caller evaluates a near-vertical station with
/// has_near_vertical_form() at inclination 0 (error_propagation.cpp does).
ErrorWeights error_weights(WeightingFunction function, const StationGeometry& station,
                           const WellParameters& well, double tortuosity_rad_per_m);

}  // namespace stochnav::survey_error
