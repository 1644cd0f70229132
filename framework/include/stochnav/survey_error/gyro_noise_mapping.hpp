#pragma once
// The magnitudes of the continuous-gyro terms GXY-RN, GXY-GD and GXY-GRW
// (survey_error/continuous_gyro.hpp) from a fitted stochnav noise model of the tool's x-y gyros
// (model/noise_model.hpp, the JSON `stochnav fit` writes). With T the averaging time of one
// gyrocompass measurement and T_run the running time of the continuous survey (s):
//
//   GXY-GRW^2 = N^2                     the angle random walk: an integrating gyro's angle error
//                                       grows as N sqrt(t), which is GXY-GRW's definition
//   GXY-RN^2  = N^2 / T + 2 Q^2 / T^2   the 1-sigma rate error of a T-average of the rate: the
//                                       white rate noise and the angle quantization (white
//                                       angle noise of variance Q^2 at both ends)
//   GXY-GD^2  = (0.664 B)^2 + K^2 T_run / 3
//               + 2 sigma^2 tau_c^2 g(T_run / tau_c) / T_run^2      (each Gauss-Markov term)
//                                       the constant drift that gives, at the end of the run,
//                                       the azimuth variance of the bias's change since the
//                                       initialising gyrocompass: bias instability as its Allan
//                                       floor, a rate random walk started at 0 (its integral's
//                                       variance K^2 t^3 / 3), a Gauss-Markov bias started at 0
//                                       (closed_form::ou_integral_shape g); 0 for K and
//                                       Gauss-Markov when T_run = 0
//
// The terms are independent, so their variances add. A constant drift grows the azimuth
// variance as t^2; K and Gauss-Markov grow it as t^3 at first, so matched at T_run the drift
// overstates the earlier stations (conservative). The bias the gyro has at the initialising
// gyrocompass, and its errors there, belong to the gyro bias terms GXY-B1/B2 of the full OWSG
// tool model, which are not implemented. Rate ramp, sinusoid, nonstationary, bias step and
// auxiliary-sensitivity terms do not enter (deterministic, averaging out over T, or a time
// profile); they are named in MappedGyroTerms::ignored_terms.

#include <span>
#include <string>
#include <vector>

#include "stochnav/model/noise_model.hpp"
#include "stochnav/survey_error/continuous_gyro.hpp"
#include "stochnav/survey_error/error_propagation.hpp"

namespace stochnav::survey_error {

/// The default averaging time of one gyrocompass measurement (s).
inline constexpr double kDefaultGyrocompassTime_s = 60.0;

struct MappedGyroTerms {
  ContinuousGyroTerms terms;
  std::vector<std::string> ignored_terms;  ///< term type names that did not enter, in order
};

/// `tool` with noise_rad_s, drift_rad_s and random_walk_rad_per_sqrt_s replaced by the mapping
/// above (the noise reduction factor, running speed and start inclination stay the tool's).
/// `model` must describe an angular rate (a gyro unit; its terms are then in rad/s units).
/// Requires gyrocompass_time_s > 0 and continuous_run_time_s >= 0, both finite; throws
/// std::invalid_argument "survey_error::map_gyro_noise_model: reason" otherwise.
MappedGyroTerms map_gyro_noise_model(const NoiseModel& model, double gyrocompass_time_s,
                                     double continuous_run_time_s, const ContinuousGyroTerms& tool);

/// T_run of a listing (s): the MD from the station that initialises the continuous survey
/// (continuous_initialisation_station) to the last station over terms.running_speed_m_s; 0
/// when no station is continuous.
double continuous_run_time_s(std::span<const ListingStation> stations,
                             const ContinuousGyroTerms& terms);

}  // namespace stochnav::survey_error
