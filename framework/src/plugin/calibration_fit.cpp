#include "stochnav/plugin/calibration_fit.hpp"

#include <algorithm>
#include <cmath>

#include "stochnav/core/errors.hpp"
#include "stochnav/fit/fit_data.hpp"
#include "stochnav/fit/gmwm_data.hpp"
#include "stochnav/fit/gmwm_fit.hpp"
#include "stochnav/io/json_numbers.hpp"
#include "stochnav/stats/deviation.hpp"
#include "stochnav/stats/phase.hpp"

namespace stochnav::plugin {

FitData calibration_axis_data(const CalibrationRecord& record, std::size_t axis) {
  if (!(record.rate_hz > 0.0)) {
    throw InputError(record.source + ": calibration rate must be > 0 Hz; give the record's rate");
  }
  const Unit unit =
      record.group == SensorGroup::kGyro ? Unit::kRadPerSecond : Unit::kMeterPerSecondSquared;
  const double tau0 = 1.0 / record.rate_hz;
  const auto& values = record.axes[axis];
  if (values.size() != record.axes[0].size()) {
    throw InputError(record.source +
                     ": calibration axes differ in length; give three equal "
                     "columns");
  }
  const std::vector<double> phase = phase_from_rate(values, tau0);
  const auto m_values =
      averaging_factors(Deviation::kOadev, TauSpacing::kOctave, phase.size(), tau0);
  if (m_values.size() < 2) {
    throw InputError(record.source + ": calibration record too short for a fit (" +
                     std::to_string(values.size()) + " samples); use a longer static record");
  }
  const auto points = compute_deviation(Deviation::kOadev, phase, tau0, m_values);
  return fit_data_from_deviations(Deviation::kOadev, points, unit, record.rate_hz);
}

std::array<FitResult, 3> fit_calibration_axes(const CalibrationRecord& record,
                                              const FitOptions& options) {
  std::array<FitResult, 3> results;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    results[axis] = fit_noise_terms(calibration_axis_data(record, axis), options);
  }
  return results;
}

std::array<FitResult, 3> fit_calibration_axes(const CalibrationRecord& record,
                                              const FitOptions& options,
                                              CalibrationEstimator estimator) {
  if (estimator == CalibrationEstimator::kAllanVariance) {
    return fit_calibration_axes(record, options);
  }
  if (options.terms.empty()) {
    throw ConfigError(record.source + ": the gmwm method fits the terms it is given; name them "
                                      "(\"terms\") or use the method \"avar\"");
  }
  const Unit unit =
      record.group == SensorGroup::kGyro ? Unit::kRadPerSecond : Unit::kMeterPerSecondSquared;
  GmwmOptions gmwm;
  gmwm.terms = options.terms;
  gmwm.controls = options.controls;
  gmwm.drop_terms_at_bound = options.drop_terms_at_bound;
  std::array<FitResult, 3> results;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (record.axes[axis].size() != record.axes[0].size()) {
      throw InputError(record.source +
                       ": calibration axes differ in length; give three equal columns");
    }
    const GmwmData data = gmwm_data_from_rate(record.axes[axis], record.rate_hz, unit, false,
                                              record.source);
    results[axis] = fit_gmwm(data, gmwm);
  }
  return results;
}

namespace {

// `rule_value` of term `term` (its only parameter) as the user's controls allow: the fixed value
// when it is fixed, else clamped into the bounds given. A changed value appends the parameter's
// label to `steered`.
double steered_value(double rule_value, std::span<const TermType> terms,
                     std::span<const ParameterControl> controls, std::size_t term,
                     nlohmann::json& steered) {
  double value = rule_value;
  for (const ParameterControl& control : controls) {
    if (control.term != term || control.parameter != 0) continue;
    if (control.fixed) value = *control.fixed;
    if (control.lower) value = std::max(value, *control.lower);
    if (control.upper) value = std::min(value, *control.upper);
  }
  if (value != rule_value) steered.push_back(parameter_label(terms, term, 0));
  return value;
}

}  // namespace

WhiteWalkFit fit_white_walk(const CalibrationRecord& record, bool with_walk,
                            CalibrationEstimator estimator,
                            std::span<const ParameterControl> controls) {
  FitOptions options;
  options.terms = {TermType::kAngleRandomWalk};
  if (with_walk) options.terms.push_back(TermType::kRateRandomWalk);
  options.controls.assign(controls.begin(), controls.end());
  WhiteWalkFit out;
  std::array<FitData, 3> data;
  for (std::size_t axis = 0; axis < 3; ++axis) data[axis] = calibration_axis_data(record, axis);
  const std::array<FitResult, 3> fits = fit_calibration_axes(record, options, estimator);
  out.quality = calibration_fit_quality(fits);
  const char* names[] = {"x", "y", "z"};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    nlohmann::json& quality = out.quality[names[axis]];
    quality["method"] = "fit";
    const FitResult& fit = fits[axis];
    if (const auto* arw = find_term(fit.model, TermType::kAngleRandomWalk)) {
      out.n[axis] = std::get<AngleRandomWalkTerm>(*arw).n;
    }
    if (const auto* rrw = find_term(fit.model, TermType::kRateRandomWalk)) {
      out.k[axis] = std::get<RateRandomWalkTerm>(*rrw).k;
    }
    if (!with_walk || !fit.diagnostics.failed()) continue;
    // The floor-matched rule (header).
    const FitData& d = data[axis];
    std::size_t near_one = 0;
    std::size_t reliable = 0;
    for (std::size_t i = 0; i < d.tau_s.size(); ++i) {
      if (std::abs(std::log(d.tau_s[i])) < std::abs(std::log(d.tau_s[near_one]))) near_one = i;
      if (d.edf[i] >= kReliableEdf) reliable = i;
    }
    // The floor: the EDF-weighted mean Allan variance of the points from tau_n to tau_k (one
    // point's estimate alone scatters by tens of percent).
    double weighted = 0.0, weight = 0.0;
    for (std::size_t i = std::min(near_one, reliable); i <= reliable; ++i) {
      weighted += d.edf[i] * d.avar[i];
      weight += d.edf[i];
    }
    const double floor_avar = weighted / weight;
    // The user's steering still holds: a fixed value stays, a bound clamps the rule's value.
    nlohmann::json steered = nlohmann::json::array();
    out.n[axis] = steered_value(std::sqrt(d.avar[near_one] * d.tau_s[near_one]),
                                options.terms, controls, 0, steered);
    out.k[axis] =
        steered_value(std::sqrt(floor_avar * 3.0 / d.tau_s[reliable]), options.terms, controls, 1,
                      steered);
    quality["method"] = "floor_matched";
    if (!steered.empty()) quality["steered"] = steered;
    quality["failed_fit"] = fit.diagnostics.failure();
    quality["tau_n_s"] = d.tau_s[near_one];
    quality["tau_k_s"] = d.tau_s[reliable];
    quality["floor_adev"] = std::sqrt(floor_avar);  // natural units
  }
  return out;
}

nlohmann::json calibration_fit_quality(const std::array<FitResult, 3>& fits) {
  nlohmann::json quality = nlohmann::json::object();
  const char* names[] = {"x", "y", "z"};
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const FitDiagnostics& d = fits[axis].diagnostics;
    quality[names[axis]] = {
        {"chi_square", number_or_null(d.chi_square)},
        {"dof", d.points > d.parameters ? d.points - d.parameters : 0},
        {"chi_square_per_dof", number_or_null(d.reduced_chi_square())},
        {"p_value", number_or_null(d.chi_square_p_value())},
        {"at_bound", d.at_bound},
        {"estimator", fit_method_name(d.method)}};
  }
  return quality;
}

const NoiseTerm* find_term(const NoiseModel& model, TermType type) {
  for (const auto& term : model.terms) {
    if (term_type(term) == type) return &term;
  }
  return nullptr;
}

}  // namespace stochnav::plugin
