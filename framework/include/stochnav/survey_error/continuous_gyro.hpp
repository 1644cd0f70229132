#pragma once
// The gyro terms of the OWSG hybrid gyro tool model GYRO-NS-CT ("XYZ Accel with XY Static and
// Continuous Gyro", after Torkildsen et al., SPE 90408) whose correlation between stations is
// neither random nor systematic, and which welleng propagates as zero:
//
//   GXY-RN   XY gyro random noise (1-sigma rate noise of a stationary gyrocompass)
//   GXY-GD   continuous-survey gyro drift (a constant rate error while running in hole)
//   GXY-GRW  continuous-survey gyro random walk (the angle random walk of the gyro)
//
// The survey: below the continuous start inclination (15 deg in GYRO-NS-CT) every station is
// a stationary gyrocompass; the first station at or above it initialises the continuous
// survey with its gyrocompass azimuth, and every later station is continuous (the tool running
// at `running_speed`). Azimuth errors (rad), with Omega the Earth rate, phi the latitude,
// dt_j = dMD_j / running speed the time over leg j and I_j' the mean inclination of leg j:
//
//   gyrocompass station k (the initialising station included):
//       n_k sigma_RN NRF sqrt(1 - cos^2 AzT sin^2 I) / (Omega cos phi cos I),  n_k independent;
//   continuous station k after the initialising station k0: the initialising error carried
//       forward (n_k0 ...), plus
//       GD:  g sigma_GD sum over k0 < j <= k of dt_j / sin I_j'        (one g for the survey)
//       GRW: sigma_GRW sum over k0 < j <= k of w_j sqrt(dt_j) / sin I_j'   (w_j independent)
//
// with g, w_j, n_k independent standard normal. These are the OWSG weighting functions (GXY-RN;
// the recursions XY_Gyro_Drift + dMD / (speed sin I') and sqrt(XY_Gyro_Random_Walk^2 + dMD /
// (speed sin^2 I')) of GXY-GD and GXY-GRW). The OWSG table propagates GD and GRW as systematic
// and RN as random; here each term's correlation between stations is propagated exactly: GD is
// systematic (one g), GRW a random walk (station K and a later station share the increments up
// to K, not their whole error), RN independent between gyrocompass stations but the same
// initialising error at every continuous station. The position error of a station is then
// linear in the independent variables and its covariance exact to first order
// (leg_effects.hpp, propagate_loadings). The magnitudes from a fitted gyro noise model:
// gyro_noise_mapping.hpp; `stochnav survey --model gyro_ns_ct`: tool_models.hpp.

#include <span>
#include <vector>

#include "stochnav/core/angles.hpp"
#include "stochnav/survey_error/error_propagation.hpp"
#include "stochnav/survey_error/well_parameters.hpp"

namespace stochnav::survey_error {

/// The terms' magnitudes and the tool parameters they need (SI).
struct ContinuousGyroTerms {
  double noise_rad_s = 0.0;             ///< GXY-RN 1 sigma (rad/s); OWSG 0.4 deg/h
  double noise_reduction_factor = 1.0;  ///< GXY-RN's NoiseReductionFactor; OWSG 0.4082
  double drift_rad_s = 0.0;             ///< GXY-GD 1 sigma (rad/s); OWSG 0.5 deg/h
  double random_walk_rad_per_sqrt_s =
      0.0;                         ///< GXY-GRW 1 sigma (rad/sqrt(s)); OWSG 0.25 deg/sqrt(h)
  double running_speed_m_s = 0.0;  ///< continuous survey speed along hole (m/s), > 0
  double continuous_start_inclination_rad = 15.0 * kRadPerDeg;  ///< in (0, pi/2)
};

/// The values of the OWSG GYRO-NS-CT tool model (rev 5, 2020): 0.4 deg/h, 0.4082, 0.5 deg/h,
/// 0.25 deg/sqrt(h), 2743.2 m/h, 15 deg.
ContinuousGyroTerms owsg_gyro_ns_ct_terms();

/// The NEV covariance (m^2) of GXY-RN, GXY-GD and GXY-GRW (in this order) at every station,
/// with the frames of error_propagation.hpp (well.earth_rate_rad_s and well.latitude_rad are
/// used). Requires what propagate_survey_errors requires, |latitude| < 90 deg, an Earth rate
/// and a running speed > 0, and every gyrocompass station below 90 deg inclination; throws
/// std::invalid_argument "survey_error::continuous_gyro_covariance: reason" otherwise.
std::vector<SourceCovariance> continuous_gyro_covariance(const ContinuousGyroTerms& terms,
                                                         std::span<const ListingStation> stations,
                                                         const WellParameters& well);

/// The index of the station that initialises the continuous survey (the first at or above the
/// start inclination), or the number of stations when every station is a gyrocompass.
std::size_t continuous_initialisation_station(std::span<const ListingStation> stations,
                                              const ContinuousGyroTerms& terms);

/// The same for a continuous start inclination `start_inclination_rad`.
std::size_t continuous_initialisation_station(std::span<const ListingStation> stations,
                                              double start_inclination_rad);

}  // namespace stochnav::survey_error
