#pragma once
// Fitting noise terms to a calibration record, axis by axis, through the Allan-variance engine:
// overlapping Allan deviation at octave taus (stats/deviation.hpp) with its EDF, then the Ceres
// fit of fit/fit_noise_terms.hpp with the given terms. For noise-model plugins' fitters.

#include <array>

#include "stochnav/fit/fit_noise_terms.hpp"
#include "stochnav/plugin/noise_model_plugin.hpp"

namespace stochnav::plugin {

/// The fit of each axis (x, y, z) of `record` (SI units; the results' models are in natural SI
/// units, unit rad/s or m/s^2). Throws InputError naming record.source when an axis is too
/// short (fewer than 2 octave taus) or axes differ in length, and ConfigError for bad options.
std::array<FitResult, 3> fit_calibration_axes(const CalibrationRecord& record,
                                              const FitOptions& options);

/// The fit quality of the three axes, for NoiseModelPlugin::set_fit_quality:
/// {"x"|"y"|"z": {"chi_square", "dof" (points - parameters), "chi_square_per_dof", "p_value"
/// (upper tail of chi2(dof); null without dof), "at_bound": ["term.param", ...]}}.
nlohmann::json calibration_fit_quality(const std::array<FitResult, 3>& fits);

/// The first term of `type` in a fit result's model, or nullptr.
const NoiseTerm* find_term(const NoiseModel& model, TermType type);

}  // namespace stochnav::plugin
