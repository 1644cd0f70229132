#pragma once
// Fitting noise terms to a calibration record, axis by axis, through the Allan-variance engine:
// overlapping Allan deviation at octave taus (stats/deviation.hpp) with its EDF, then the Ceres
// fit of fit/fit_noise_terms.hpp with the given terms. For noise-model plugins' fitters.

#include <array>
#include <span>

#include "stochnav/fit/fit_noise_terms.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"

namespace stochnav::plugin {

/// The fit of each axis (x, y, z) of `record` (SI units; the results' models are in natural SI
/// units, unit rad/s or m/s^2). Throws InputError naming record.source when an axis is too
/// short (fewer than 2 octave taus) or axes differ in length, and ConfigError for bad options.
/// options.controls steer the fit (starting values, fixed parameters, bounds of options.terms;
/// natural SI units, fit/parameter_control.hpp), e.g. a Gauss-Markov correlation time held:
///   options.terms = {kAngleRandomWalk, kGaussMarkov, kGaussMarkov};
///   options.controls = {{.term = 2, .parameter = 1, .fixed = 300.0}};   // tau_c#2 = 300 s
/// A plugin reads them from its fit options with plugin/fit_steering.hpp.
std::array<FitResult, 3> fit_calibration_axes(const CalibrationRecord& record,
                                              const FitOptions& options);

/// The estimator a fitter fits the terms to (the plugins' fit option "method").
enum class CalibrationEstimator {
  kAllanVariance,  ///< "avar": the octave OADEV, robust log fit (fit/fit_noise_terms.hpp)
  kGmwm,           ///< "gmwm": the classical Haar wavelet variance by GMM (fit/gmwm_fit.hpp)
};

/// fit_calibration_axes with the estimator. With kGmwm, options.terms (not empty: the automatic
/// selection is the Allan fit's) are fitted by fit_gmwm to each axis's classical wavelet
/// variance, options.controls and options.drop_terms_at_bound kept; the results' diagnostics
/// say which method ran.
/// Throws ConfigError for kGmwm with no terms, InputError as fit_gmwm does.
std::array<FitResult, 3> fit_calibration_axes(const CalibrationRecord& record,
                                              const FitOptions& options,
                                              CalibrationEstimator estimator);

/// The octave OADEV points of one axis of `record` (what fit_calibration_axes fits). Throws as
/// fit_calibration_axes.
FitData calibration_axis_data(const CalibrationRecord& record, std::size_t axis);

/// Constant white noise N (and optionally a rate random walk K) per axis, natural units
/// (rad/sqrt(s), rad/s/sqrt(s); m/s/sqrt(s), m/s^2/sqrt(s)), for the white and davar plugins.
struct WhiteWalkFit {
  std::array<double, 3> n{};
  std::array<double, 3> k{};
  /// Per axis (fit_quality): calibration_fit_quality's fields plus "method": "fit" | "floor_matched"
  /// and, for floor_matched, "failed_fit" (FitDiagnostics::failure of the N + K fit), "tau_n_s",
  /// "tau_k_s", "floor_adev" and, when the controls changed a value, "steered".
  nlohmann::json quality;
};

/// Shortest Allan-variance EDF of a point still "reliable" for the floor rule below.
inline constexpr double kReliableEdf = 10.0;

/// Fits N (with_walk: N and K) to each axis's Allan variance (fit_calibration_axes). When the
/// N + K fit fails (FitDiagnostics::failed: a coefficient on its search bound, or a chi-square
/// with p < kFailedFitPValue — what a flicker floor, bias instability, does to a model that has
/// no term for it), that axis uses the FLOOR-MATCHED rule instead: each line of the model meets
/// the measured floor at one tau,
///   N = sigma(tau_n) sqrt(tau_n),        tau_n = the measured tau nearest 1 s,
///   K = sigma_floor sqrt(3 / tau_k),     tau_k = the longest tau whose EDF >= kReliableEdf,
/// sigma(tau) the measured Allan deviation, sigma_floor^2 the EDF-weighted mean Allan variance
/// of the points from tau_n to tau_k (AVAR of a rate random walk: K^2 tau / 3). Over a flat
/// floor sigma_f = 0.664 B this gives K = 0.664 B sqrt(3 / tau_k) (0.664 B sqrt(10800 / tau_k)
/// in deg/h/sqrt(h) for B in deg/h): the bias wander the floor implies over the longest interval
/// the record measures; the model stays at or below the floor in between. N only (no walk)
/// keeps the fit, its failure reported in quality.
/// `estimator` and `controls` (of the terms {angle_random_walk, rate_random_walk if with_walk})
/// steer the N (+ K) fit as in fit_calibration_axes; the floor rule reads the Allan variance and
/// keeps to them too: a fixed N or K keeps its value, a bound clamps the rule's value (quality
/// "steered" lists the parameters the controls changed).
WhiteWalkFit fit_white_walk(const CalibrationRecord& record, bool with_walk,
                            CalibrationEstimator estimator = CalibrationEstimator::kAllanVariance,
                            std::span<const ParameterControl> controls = {});

/// The fit quality of the three axes, for NoiseModelPlugin::set_fit_quality:
/// {"x"|"y"|"z": {"chi_square", "dof" (points - parameters), "chi_square_per_dof", "p_value"
/// (upper tail of chi2(dof); null without dof), "at_bound": ["term.param", ...], "estimator":
/// "avar" | "gmwm" (fit_method_name)}}.
nlohmann::json calibration_fit_quality(const std::array<FitResult, 3>& fits);

/// The first term of `type` in a fit result's model, or nullptr.
const NoiseTerm* find_term(const NoiseModel& model, TermType type);

}  // namespace stochnav::plugin
